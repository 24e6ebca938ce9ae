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

import math
import os
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from assur import AssurError, ExistenceReport, KinematicModel, TableError
from assur.kinematics.existence import reason_sentence
from assur.text import check_lang, render
from synthesis.app.assess import Assessment, assess

if TYPE_CHECKING:
    from synthesis.distributed import DaskExecutor

__all__ = ["TABLE_SUFFIXES", "BatchRow", "check_table", "find_tables", "run_batch"]

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
        raise AssurError(render("batch.not_a_folder", "en", folder=root))
    return sorted(p for p in root.rglob("*") if p.is_file() and p.suffix.lower()
                  in TABLE_SUFFIXES and not p.name.startswith("."))


def _row(name: str, found: Assessment, lang: str, seconds: float) -> BatchRow:
    """The row of a table that could be read."""
    analysis = found.analysis
    problems = [d.text(lang) for d in analysis.issues if d.severity == "error"]
    problems += found.failed_conditions(lang)
    problems += [text for _mismatch, text in found.mismatch_texts(lang)]
    problems += [v.message.text(lang) for v in found.variants]
    if found.existence is not None and found.model is not None:
        existence = "whole cycle" if found.existence.all_exist else "fails"
        problems += _failures(found.existence, found.model, lang)
    elif isinstance(found.why_no_model, AssurError):
        existence = "not checked"
        problems.append(found.why_no_model.text(lang).replace("\n", " "))
    else:
        existence = "no dimensions"
    return BatchRow(name, "problems" if problems else "ok", problems[0] if problems else "",
                    len(problems), analysis.formula, analysis.n, analysis.p5, analysis.W,
                    found.identification, existence, seconds)


def _failures(report: ExistenceReport, model: KinematicModel, lang: str) -> list[str]:
    """Every interval where a group does not assemble, as a sentence."""
    crank = model.drive == "crank"
    found = []
    for group in report.groups:
        for interval in group.intervals:
            where = (f"{math.degrees(interval.start):.1f}°…{math.degrees(interval.end):.1f}°"
                     if crank else f"{interval.start:.2f}…{interval.end:.2f} mm")
            found.append(render("batch.group_fails", lang, group=group.label, where=where,
                                reason=reason_sentence(interval.reason, lang)))
    return found


def check_table(path: str | os.PathLike[str], *, lang: str = "en",
                root: str | os.PathLike[str] | None = None) -> BatchRow:
    """Check one table; never raises for a problem of the table itself.

    Parameters
    ----------
    path : path-like
        The table file.
    lang : str
        A catalogue language, for the problem sentence.
    root : path-like, optional
        The folder the row's file name is relative to.

    Returns
    -------
    BatchRow

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> row = check_table(tables / "course_11_link_table.yaml")
    >>> row.verdict, row.W, row.identification, row.existence
    ('ok', 1, 'matches', 'whole cycle')
    """
    start = time.perf_counter()
    path = Path(path)
    name = str(path.relative_to(root)) if root is not None else str(path)
    try:
        found = assess(path, points=EXISTENCE_POINTS)
    except AssurError as exc:
        issues = exc.issues if isinstance(exc, TableError) else None
        first = issues[0].text(lang) if issues else exc.text(lang)
        return BatchRow(name, "error", first, len(issues) if issues else 1, "", None, None,
                        None, "not checked", "not checked", time.perf_counter() - start)
    return _row(name, found, lang, time.perf_counter() - start)


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
              reports: str | os.PathLike[str] | None = None,
              executor: DaskExecutor | None = None) -> list[BatchRow]:
    """Check every table in a folder, in parallel.

    Parameters
    ----------
    folder : path-like
    jobs : int, optional
        Worker processes; default all local cores. ``1`` checks in this process.
    lang : str
        A catalogue language.
    progress : callable, optional
        Called as ``progress(done, total)`` while the rows come in.
    reports : path-like, optional
        A folder for one coursework report (HTML) per readable table, named after it.
    executor : DaskExecutor, optional
        Check the files as tasks on a Dask cluster (:func:`synthesis.distributed.connect`)
        instead of local processes; ``jobs`` is then ignored.

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
    if executor is not None or jobs == 1 or len(work) <= 1:
        for k, row in enumerate(map(_check_one, work) if executor is None
                                else executor.map(_check_one, work), 1):
            rows.append(row)
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
