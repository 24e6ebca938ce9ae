"""The rows of a batch check as a terminal table or as CSV (``assur batch``).

The CSV is UTF-8 and starts, unless asked not to, with the byte-order mark, by which
spreadsheet programs (Excel on Windows in particular) recognise UTF-8 and show Cyrillic
names and the Greek letters of the formulas correctly; Python's ``csv`` module, LibreOffice
and pandas read it either way (``encoding="utf-8-sig"``).
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Sequence

from assur.text import render
from synthesis.app.batch import VERDICTS, BatchRow
from synthesis.app.check_report import verdict_words as verdict_words_of

__all__ = ["BOM", "csv_text", "rows_to_csv", "summary", "verdict_words"]

_COLUMNS = ("file", "verdict", "problem", "problems", "formula", "n", "p5", "W",
            "identification", "existence", "seconds", "report", "report_error")
#: The byte-order mark that tells a spreadsheet program the CSV is UTF-8.
BOM = "\ufeff"


def verdict_words(row: BatchRow, lang: str = "en") -> str:
    """The verdict as the terminal shows it, as ``assur check`` does: with its count of
    problems, unless the table is correct, unreadable or skipped.

    Examples
    --------
    >>> from synthesis.app.batch import BatchRow
    >>> row = BatchRow("a.yaml", "wrong", "W = 0", 3, "", 3, 4, 0, "", "", 0.0)
    >>> verdict_words(row), verdict_words(row, "ru")
    ('wrong (3)', 'неверно (3)')
    """
    if row.verdict in ("unreadable", "skipped"):
        return render("batch.verdict." + row.verdict, lang)
    return verdict_words_of(row.verdict, row.problems, lang)


def rows_to_csv(rows: Iterable[BatchRow]) -> str:
    """The rows as CSV text (a header line, then one line per file).

    Parameters
    ----------
    rows : iterable of BatchRow

    Returns
    -------
    str
        The columns of :class:`~synthesis.app.batch.BatchRow`; the seconds to 1 ms.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> from synthesis.app.batch import check_table
    >>> text = rows_to_csv([check_table(tables / "four_bar.yaml", root=tables)])
    >>> text.splitlines()[1].split(",")[:2]
    ['four_bar.yaml', 'correct']
    """
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(_COLUMNS)
    for row in rows:
        record = row.to_dict()
        record["seconds"] = f"{row.seconds:.3f}"
        writer.writerow(["" if record[c] is None else record[c] for c in _COLUMNS])
    return buffer.getvalue()


def summary(rows: Sequence[BatchRow], lang: str = "en") -> str:
    """A plain-text table of the rows for the terminal, with totals.

    Parameters
    ----------
    rows : sequence of BatchRow
    lang : str
        A catalogue language, for the verdicts.

    Returns
    -------
    str
        One line per file (name, verdict, first problem), a blank line and the totals.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> from synthesis.app.batch import check_table
    >>> print(summary([check_table(tables / "four_bar.yaml", root=tables)], "ru"))
    four_bar.yaml  верно
    <BLANKLINE>
    верно: 1, вне программы: 0, не проверено: 0, неверно: 0, не читается: 0, пропущено: 0; всего: 1
    """
    width = max((len(r.file) for r in rows), default=4)
    words = [verdict_words(row, lang) for row in rows]
    column = max((len(w) for w in words), default=0)
    lines = []
    for row, word in zip(rows, words):
        lines.append(f"{row.file:<{width}}  {word:<{column}}  {row.problem}".rstrip())
        if row.report_error:
            lines.append(f"{'':<{width}}  " + render("batch.report_not_written", lang,
                                                     reason=row.report_error))
    counts = {v: sum(r.verdict == v for r in rows) for v in VERDICTS}
    lines.append("")
    lines.append(render("batch.totals", lang, counts=", ".join(
        f"{render('batch.verdict.' + v.replace(' ', '_'), lang)}: {counts[v]}"
        for v in VERDICTS), total=len(rows)))
    return "\n".join(lines)


def csv_text(rows: Sequence[BatchRow], *, bom: bool = True) -> str:
    """The CSV file's text: :func:`rows_to_csv`, after the byte-order mark unless ``bom`` is
    False."""
    return (BOM if bom else "") + rows_to_csv(rows)
