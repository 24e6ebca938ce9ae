"""The structural check of a table as text (``assur check``), ending with the verdict that
``assur batch`` and ``assur report`` show too; its JSON record is
:meth:`assur.assessment.Assessment.to_dict`."""

from __future__ import annotations

from assur.assessment import Assessment
from assur.structure.report import structure_report
from assur.text import render

__all__ = ["check_text", "verdict_text", "verdict_words"]


def check_text(assessment: Assessment, lang: str = "en", order: str = "course") -> str:
    """The text report: counts, groups, formula, class, findings, the identification table
    and the verdict on the table given in the file.

    Parameters
    ----------
    assessment : Assessment
        From :func:`assur.check`.
    lang : str
        A catalogue language.
    order : {'course', 'layering'}
        The order of the rows of table 1.6: by kind, as the course prints it, or layering.

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
    text = structure_report(assessment.analysis, lang=lang, table=assessment.table,
                            mismatches=assessment.table_findings,
                            checked_rows=assessment.rows_given, models=assessment.group_models,
                            model_mismatches=assessment.model_mismatches,
                            checked_models=assessment.models_given, order=order)
    return f"{text}\n\n{verdict_text(assessment, lang)}"


def verdict_text(assessment: Assessment, lang: str = "en") -> str:
    """The verdict line (the words of ``assur batch``, with the count of findings unless the
    table is correct) and every finding behind it, the first first.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> from synthesis.app.assess import assess
    >>> print(verdict_text(assess(tables / "four_bar.yaml", points=36), "ru"))
    Итог: верно
    """
    lines = [render("check.verdict", lang,
                    verdict=verdict_words(assessment.verdict, assessment.problems, lang))]
    if assessment.findings:
        lines.append(render("check.findings", lang))
        lines += [f"  - {finding.text(lang)}" for finding in assessment.findings]
    return "\n".join(lines)


def verdict_words(verdict: str, problems: int, lang: str = "en") -> str:
    """A verdict in ``lang``, with its count of findings unless it is ``correct``.

    >>> verdict_words("wrong", 3), verdict_words("not verified", 2, "ru")
    ('wrong (3)', 'не проверено (2)')
    """
    words = render("batch.verdict." + verdict.replace(" ", "_"), lang)
    shown = verdict in ("wrong", "not verified", "outside program")
    return render("check.verdict_count", lang, verdict=words, n=problems) if shown else words

