"""The structural check of a table as text or as a JSON record (``assur check``)."""

from __future__ import annotations

from typing import Any

from assur.structure.identification import Mismatch
from assur.structure.report import structure_report
from synthesis.app.assess import TABLE, Assessment

__all__ = ["check_record", "check_text"]


def check_text(assessment: Assessment, lang: str = "en") -> str:
    """The text report: counts, groups, formula, class, findings, the identification table
    and the verdict on the table given in the file.

    Parameters
    ----------
    assessment : Assessment
        From :func:`synthesis.app.assess.assess`.
    lang : str
        A catalogue language.

    Returns
    -------
    str

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> from synthesis.app.assess import assess
    >>> text = check_text(assess(tables / "course_11_link.yaml", points=None))
    >>> "I(0,1) → II₁(2,3)" in text
    True
    """
    return structure_report(assessment.analysis, lang=lang, table=assessment.table,
                            mismatches=_findings(assessment),
                            checked_rows=assessment.rows_given)


def check_record(assessment: Assessment) -> dict[str, Any]:
    """The structural analysis, the identification table and the check of the student's
    table as one JSON-ready mapping.

    Parameters
    ----------
    assessment : Assessment
        From :func:`synthesis.app.assess.assess`.

    Returns
    -------
    dict
        The analysis (:meth:`StructuralAnalysis.to_dict`) with ``identification_table``
        (None when the chain is not made of DGTU groups) and ``identification_check`` (the
        mismatches of the student's table, then its rows whose assembly variant the
        dimensions contradict, ``field`` ``"variant"``; None when the file gives none).

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> from synthesis.app.assess import assess
    >>> record = check_record(assess(tables / "course_11_link_table.yaml", points=None))
    >>> record["W"], record["identification_check"]
    (1, [])
    """
    mismatches = _findings(assessment)
    payload = assessment.analysis.to_dict()
    payload["identification_table"] = (None if assessment.table is None
                                       else [row.to_dict() for row in assessment.table])
    payload["identification_check"] = (None if mismatches is None
                                       else [m.to_dict() for m in mismatches])
    return payload


def _findings(assessment: Assessment) -> tuple[Mismatch, ...] | None:
    """The mismatches of the student's table, then its rows whose assembly variant the
    dimensions contradict (as mismatches of the field ``variant``); None without a table."""
    if assessment.mismatches is None:
        return None
    return (*assessment.mismatches, *(
        Mismatch(v.row, f"{TABLE}[{v.row}] (L{v.kind}, i = {v.group.i}, j = {v.group.j})",
                 "variant", v.group.sigma, v.given, v.message) for v in assessment.variants))
