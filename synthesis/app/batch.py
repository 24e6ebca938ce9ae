"""Batch checks for a teacher: every table of a folder, one row per file.

Each table (one per student) is checked the way the course checks a coursework:

1. the structure (counts, W, decomposition into Assur groups, the course's applicability
   conditions);
2. the structure-identification table given in the file, against the chain;
3. the existence of every group over the whole cycle, when the table gives dimensions.

A synthesis problem is checked as its mechanism at the problem's initial design.

A row holds the verdict and the first problem in plain words. A broken file is a row with
its error, never a stop. The files are checked in parallel on all local cores
(:class:`concurrent.futures.ProcessPoolExecutor`).
"""

from __future__ import annotations

import csv
import io
import math
import os
import time
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from assur import (
    AssurError,
    Chain,
    analyse_structure,
    check_identification,
    atomic_write_text,
    chain_from_dict,
    load_chain,
)
from synthesis.i18n import check_lang, term

__all__ = [
    "TABLE_SUFFIXES",
    "BatchRow",
    "check_table",
    "find_tables",
    "rows_to_csv",
    "run_batch",
    "summary",
    "write_csv",
]

#: File name endings of the tables a batch takes.
TABLE_SUFFIXES = (".yaml", ".yml")

#: Crank positions of the existence check (every 2°); the interval ends are refined anyway.
EXISTENCE_POINTS = 180

VERDICTS = ("ok", "problems", "error")


@dataclass(frozen=True)
class BatchRow:
    """The result of one table.

    Attributes
    ----------
    file : str
        The file name, relative to the checked folder.
    verdict : {'ok', 'problems', 'error'}
        ``error``: the file cannot be read as a table; ``problems``: it was read and the
        check found something wrong; ``ok``: nothing to correct.
    problem : str
        The first problem in plain words (empty when the verdict is ``ok``).
    problems : int
        How many problems were found in all.
    formula : str
        The structure formula found by the program.
    n, p5, W : int or None
        The counts.
    identification : str
        ``matches``, ``differs``, ``not given`` or ``not checked``: the student's
        identification table against the chain.
    existence : str
        ``whole cycle``, ``fails``, ``no dimensions`` or ``not checked``.
    seconds : float
        Time spent on the file.
    """

    file: str
    verdict: str
    problem: str
    problems: int
    formula: str
    n: int | None
    p5: int | None
    W: int | None
    identification: str
    existence: str
    seconds: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready record."""
        return asdict(self)


def find_tables(folder: str | os.PathLike[str]) -> list[Path]:
    """Every table file under ``folder`` (recursively), in sorted order.

    Raises
    ------
    AssurError
        If ``folder`` is not a folder.
    """
    root = Path(folder)
    if not root.is_dir():
        raise AssurError(f"{root}: not a folder; expected the folder of the students' tables")
    return sorted(p for p in root.rglob("*") if p.is_file() and p.suffix.lower()
                  in TABLE_SUFFIXES and not p.name.startswith("."))


def _kinematic_checks(analysis: Any, lang: str) -> tuple[str, list[str], list[str]]:
    """The table's assembly variants against the dimensions, and the existence over the
    cycle: the existence status word, the variant problems and the existence problems."""
    from assur import REASONS, build_model, check_existence
    from synthesis.app.coursework.variants import variant_findings

    model = build_model(analysis)
    variants = [text for _row, text in variant_findings(
        model, analysis.chain.identification or (), lang)]
    found = []
    report = check_existence(model, points=EXISTENCE_POINTS)
    crank = model.drive == "crank"
    for group in report.groups:
        for interval in group.intervals:
            where = (f"{math.degrees(interval.start):.1f}°…{math.degrees(interval.end):.1f}°"
                     if crank else f"{interval.start:.2f}…{interval.end:.2f} mm")
            reason = REASONS[interval.reason][1 if lang == "ru" else 0]
            if lang == "ru":
                found.append(f"группа {group.label} не собирается при φ = {where}: {reason}")
            else:
                found.append(f"group {group.label} does not assemble for φ = {where}: {reason}")
    return ("whole cycle" if report.all_exist else "fails"), variants, found


def _load(path: Path) -> Chain:
    """The chain of a table; for a synthesis problem, its mechanism at the initial design."""
    from synthesis.app.coursework import is_problem

    if is_problem(path):
        from synthesis.problem import load_problem

        problem = load_problem(path)
        return chain_from_dict(problem.mechanism_table(problem.initial), source=str(path))
    return load_chain(path)


def check_table(path: str | os.PathLike[str], *, lang: str = "en",
                root: str | os.PathLike[str] | None = None) -> BatchRow:
    """Check one table; never raises for a problem of the table itself.

    Parameters
    ----------
    path : path-like
        The table file.
    lang : {"en", "ru"}
        Language of the problem sentence.
    root : path-like, optional
        The folder the row's file name is relative to.

    Returns
    -------
    BatchRow
    """
    start = time.perf_counter()
    path = Path(path)
    name = str(path.relative_to(root)) if root is not None else str(path)
    try:
        chain = _load(path)
    except AssurError as exc:
        issues = getattr(exc, "issues", None)
        first = str(issues[0]) if issues else str(exc)
        return BatchRow(name, "error", first, len(issues) if issues else 1, "", None, None,
                        None, "not checked", "not checked", time.perf_counter() - start)
    analysis = analyse_structure(chain)
    found = [d.text(lang) for d in analysis.issues if d.severity == "error"]
    applicability = analysis.applicability_ru if lang == "ru" else analysis.applicability
    found += list(applicability)
    identification = "not given"
    if chain.identification is not None:
        try:
            mismatches = check_identification(analysis, chain.identification)
        except AssurError as exc:
            identification = "not checked"
            found.append(str(exc))
        else:
            identification = "differs" if mismatches else "matches"
            found += [m.message_ru if lang == "ru" else m.message for m in mismatches]
    existence = "no dimensions"
    if analysis.decomposed and analysis.applicable and (chain.geometry or chain.group_params):
        try:
            existence, variants, failures = _kinematic_checks(analysis, lang)
            if variants:
                identification = "differs"
            found += variants + failures
        except AssurError as exc:
            existence = "not checked"
            found.append(str(exc).replace("\n", " "))
    return BatchRow(name, "problems" if found else "ok", found[0] if found else "", len(found),
                    analysis.formula, analysis.n, analysis.p5, analysis.W, identification,
                    existence, time.perf_counter() - start)


def _check_one(job: tuple[str, str, str, str | None]) -> BatchRow:
    """Worker: check one file (and write its report); any failure becomes an error row."""
    path, lang, root, reports = job
    name = str(Path(path).relative_to(root))
    try:
        row = check_table(path, lang=lang, root=root)
        if reports is not None and row.verdict != "error":
            from synthesis.app.coursework import write_report

            write_report(path, Path(reports) / Path(name).with_suffix(".html"), lang=lang)
        return row
    except Exception as exc:  # noqa: BLE001 - a row, never a stop: report any failure
        return BatchRow(name, "error", f"{type(exc).__name__}: {exc}", 1, "", None, None,
                        None, "not checked", "not checked", 0.0)


def run_batch(folder: str | os.PathLike[str], *, jobs: int | None = None, lang: str = "en",
              progress: Callable[[int, int], None] | None = None,
              reports: str | os.PathLike[str] | None = None) -> list[BatchRow]:
    """Check every table in a folder, in parallel.

    Parameters
    ----------
    folder : path-like
    jobs : int, optional
        Worker processes; default all local cores. ``1`` checks in this process.
    lang : {"en", "ru"}
    progress : callable, optional
        Called as ``progress(done, total)`` while the rows come in.
    reports : path-like, optional
        A folder for one coursework report (HTML) per readable table, named after it.

    Returns
    -------
    list of BatchRow
        One per table, in sorted file order.
    """
    check_lang(lang)
    paths = find_tables(folder)
    root = str(Path(folder))
    target = None if reports is None else str(reports)
    work = [(str(p), lang, root, target) for p in paths]
    jobs = jobs or os.cpu_count() or 1
    rows: list[BatchRow] = []
    if jobs == 1 or len(work) <= 1:
        for k, job in enumerate(work, 1):
            rows.append(_check_one(job))
            if progress:
                progress(k, len(work))
        return rows
    chunk = max(1, min(32, len(work) // (4 * jobs)))
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        for k, row in enumerate(pool.map(_check_one, work, chunksize=chunk), 1):
            rows.append(row)
            if progress and (k % 25 == 0 or k == len(work)):
                progress(k, len(work))
    return rows


_COLUMNS = ("file", "verdict", "problem", "problems", "formula", "n", "p5", "W",
            "identification", "existence", "seconds")


def rows_to_csv(rows: Iterable[BatchRow]) -> str:
    """The rows as CSV text (a header line, then one line per file)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(_COLUMNS)
    for row in rows:
        record = row.to_dict()
        record["seconds"] = f"{row.seconds:.3f}"
        writer.writerow(["" if record[c] is None else record[c] for c in _COLUMNS])
    return buffer.getvalue()


def summary(rows: Sequence[BatchRow], lang: str = "en") -> str:
    """A plain-text table of the rows for the terminal, with totals."""
    width = max((len(r.file) for r in rows), default=4)
    words = {v: term(v, lang) for v in VERDICTS}
    column = max(len(w) for w in words.values())
    lines = [f"{row.file:<{width}}  {words[row.verdict]:<{column}}  {row.problem}".rstrip()
             for row in rows]
    counts = {v: sum(r.verdict == v for r in rows) for v in VERDICTS}
    lines.append("")
    lines.append(", ".join(f"{words[v]}: {counts[v]}" for v in VERDICTS)
                 + f"; {term('files', lang)}: {len(rows)}")
    return "\n".join(lines)


def write_csv(rows: Sequence[BatchRow], path: str | os.PathLike[str]) -> None:
    """Write the rows as CSV, atomically."""
    atomic_write_text(path, rows_to_csv(rows))
