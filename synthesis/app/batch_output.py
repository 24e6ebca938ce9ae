"""The rows of a batch check as a terminal table or as CSV (``assur batch``)."""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Iterable, Sequence

from assur.io.files import atomic_write_text
from assur.text import render
from synthesis.app.batch import VERDICTS, BatchRow

__all__ = ["rows_to_csv", "summary", "write_csv"]

_COLUMNS = ("file", "verdict", "problem", "problems", "formula", "n", "p5", "W",
            "identification", "existence", "seconds")


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
    >>> text = rows_to_csv([check_table(tables / "course_11_link_table.yaml", root=tables)])
    >>> text.splitlines()[1].split(",")[:2]
    ['course_11_link_table.yaml', 'ok']
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
    >>> print(summary([check_table(tables / "course_11_link_table.yaml", root=tables)], "ru"))
    course_11_link_table.yaml  верно
    <BLANKLINE>
    верно: 1, есть ошибки: 0, файл не читается: 0; файлов: 1
    """
    width = max((len(r.file) for r in rows), default=4)
    words = {"ok": render("term.ok", lang), "problems": render("term.problems", lang),
             "error": render("term.error", lang)}
    column = max(len(w) for w in words.values())
    lines = [f"{row.file:<{width}}  {words[row.verdict]:<{column}}  {row.problem}".rstrip()
             for row in rows]
    counts = {v: sum(r.verdict == v for r in rows) for v in VERDICTS}
    lines.append("")
    lines.append(", ".join(f"{words[v]}: {counts[v]}" for v in VERDICTS)
                 + f"; {render('term.files', lang)}: {len(rows)}")
    return "\n".join(lines)


def write_csv(rows: Sequence[BatchRow], path: str | os.PathLike[str]) -> None:
    """Write the rows as CSV, atomically."""
    atomic_write_text(path, rows_to_csv(rows))
