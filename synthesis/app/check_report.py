"""The structural check of a table as text (``assur check``); its JSON record is
:meth:`assur.assessment.Assessment.to_dict`."""

from __future__ import annotations

from assur.assessment import Assessment
from assur.structure.report import structure_report

__all__ = ["check_text"]


def check_text(assessment: Assessment, lang: str = "en") -> str:
    """The text report: counts, groups, formula, class, findings, the identification table
    and the verdict on the table given in the file.

    Parameters
    ----------
    assessment : Assessment
        From :func:`assur.check`.
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
                            mismatches=assessment.findings,
                            checked_rows=assessment.rows_given)

