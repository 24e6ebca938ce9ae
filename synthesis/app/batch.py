"""Batch checks for a teacher: every entry of a folder, one row each.

Each table (one per student) is checked the way the course checks a coursework:

1. the structure (counts, W, decomposition into Assur groups, the course's applicability
   conditions);
2. the structure-identification table given in the file, against the chain;
3. the existence of every group over the whole cycle, when the table gives dimensions.

A synthesis problem is checked as its mechanism at the problem's initial design.

The verdict, the count and the first problem are the :class:`~assur.assessment.Assessment`'s
(the same as ``assur check`` and ``assur report`` show); the verdicts
(:data:`~assur.assessment.VERDICTS`), the same words in the terminal table, the CSV and the
JSON:

* ``correct`` — nothing to correct;
* ``outside program`` — a correct mechanism that the DGTU course does not cover (its only
  findings are the method's applicability conditions: two inputs, an actuator input, …);
* ``not verified`` — nothing found wrong, but something the table does not let the program
  check (an assembly variant of a table without a sketch); the row states it;
* ``wrong`` — something to correct; the row counts the problems and states the first;
* ``unreadable`` — the file cannot be read as a table (the row says why);
* ``skipped`` — not a table: another file, a folder, a hidden file, a link that leads
  nowhere or round in a loop, a FIFO or another special file (the row says which; none of
  them is opened).

A broken file is a row, never a stop. The tables are checked in parallel on all local cores
(:class:`concurrent.futures.ProcessPoolExecutor`).
"""

from __future__ import annotations

import errno
import os
import signal
import stat
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from assur import AssurError, TableError
from assur.assessment import POINTS, VERDICTS, Assessment
from assur.text import Message, check_lang, render
from synthesis.app.assess import assess
from synthesis.distributed import usable_cores

if TYPE_CHECKING:
    from synthesis.distributed import DaskExecutor

__all__ = ["TABLE_SUFFIXES", "VERDICTS", "BatchRow", "Entry", "check_table", "folder_entries",
           "run_batch"]

#: File name endings of the tables a batch takes.
TABLE_SUFFIXES = (".yaml", ".yml")

#: The longest first problem a row shows; the full list is in ``assur check --json`` and in
#: the table's report.
PROBLEM_WIDTH = 160


@dataclass(frozen=True)
class BatchRow:
    """The result of one table.

    Attributes
    ----------
    file : str
        The file name, relative to the checked folder.
    verdict : str
        One of :data:`VERDICTS` (see the module's description).
    problem : str
        The first problem in plain words, or why the entry was skipped (empty when the
        verdict is ``correct``).
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
    report : str
        With ``--reports``: the report written for the table (empty without).
    report_error : str
        Why the report could not be written (the verdict stays the verdict of the table).
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
    report: str = ""
    report_error: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready record."""
        return asdict(self)


@dataclass(frozen=True)
class Entry:
    """One entry of the checked folder: a table to check, or why it is skipped.

    Attributes
    ----------
    path : Path
    skip : Message or None
        None for a table; else the reason (``batch.skip.*``).
    """

    path: Path
    skip: Message | None = None


_FOLDER_LIKE_TABLE = Message("batch.skip.folder_like_table")


def _special(mode: int) -> str:
    """The kind of a special file, as the catalogue names it."""
    for test, kind in ((stat.S_ISFIFO, "fifo"), (stat.S_ISSOCK, "socket"),
                       (stat.S_ISCHR, "device"), (stat.S_ISBLK, "device")):
        if test(mode):
            return kind
    return "other"


def _classify(path: Path, entry: os.DirEntry[str]) -> Entry | None:
    """The entry of one name in a folder; None for a folder to descend into."""
    table = path.suffix.lower() in TABLE_SUFFIXES
    if entry.name.startswith("."):
        return Entry(path, Message("batch.skip.hidden"))
    link = entry.is_symlink()
    try:
        mode = os.stat(path).st_mode  # follows a link; never opens the file
    except OSError as exc:
        code = "batch.skip.link_loop" if exc.errno == errno.ELOOP else (
            "batch.skip.broken_link" if link else "batch.skip.unlistable")
        return Entry(path, Message(code, {"reason": exc.strerror or str(exc)}))
    if stat.S_ISDIR(mode):
        if link:
            return Entry(path, Message("batch.skip.link_to_folder"))
        return Entry(path, _FOLDER_LIKE_TABLE) if table else None
    if not stat.S_ISREG(mode):
        return Entry(path, Message("batch.skip.special", {"kind": _special(mode)}))
    if not table:
        return Entry(path, Message("batch.skip.not_table", {"suffixes": ", ".join(TABLE_SUFFIXES)}))
    return Entry(path)


def folder_entries(folder: str | os.PathLike[str]) -> list[Entry]:
    """Every entry under ``folder`` (into its sub-folders), in sorted order.

    A sub-folder is entered and its entries listed; a folder named like a table is listed
    as skipped and entered as well; links to folders are not followed (no loops).

    Raises
    ------
    AssurError
        If ``folder`` is not a folder.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> root = pathlib.Path(tempfile.mkdtemp())
    >>> (root / "a.yaml").write_text("mechanism: {}")
    13
    >>> (root / "x.yaml").mkdir()
    >>> [(e.path.name, e.skip and e.skip.code) for e in folder_entries(root)]
    [('a.yaml', None), ('x.yaml', 'batch.skip.folder_like_table')]
    """
    root = Path(folder)
    if not root.is_dir():
        raise AssurError(render("batch.not_a_folder", "en", folder=root))
    found: list[Entry] = []
    pending = [root]
    while pending:
        current = pending.pop()
        try:
            with os.scandir(current) as listing:
                items = list(listing)
        except OSError as exc:
            found.append(Entry(current, Message("batch.skip.unlistable",
                                                {"reason": exc.strerror or str(exc)})))
            continue
        for item in items:
            path = Path(item.path)
            entry = _classify(path, item)
            if entry is not None:
                found.append(entry)
            if entry is None or entry.skip == _FOLDER_LIKE_TABLE:
                pending.append(path)
    return sorted(found, key=lambda e: e.path.parts)


def _row(name: str, path: Path, found: Assessment, lang: str, seconds: float) -> BatchRow:
    """The row of a table that could be read: the assessment's verdict, count and first
    finding (with the table's path shown relative to the checked folder)."""
    analysis = found.analysis
    if found.existence is not None and found.model is not None:
        existence = "whole cycle" if found.existence.all_exist else "fails"
    elif isinstance(found.why_no_model, AssurError):
        existence = "not checked"
    else:
        existence = "no dimensions"
    first = "" if found.first is None else _short(found.first.text(lang), path, name)
    return BatchRow(name, found.verdict, first, found.problems, analysis.formula, analysis.n,
                    analysis.p5, analysis.W, found.identification, existence, seconds)


def _short(text: str, path: Path, name: str) -> str:
    """One line of at most :data:`PROBLEM_WIDTH` characters, the table named as in the row."""
    line = " ".join(text.replace(str(path), name).split())
    return line if len(line) <= PROBLEM_WIDTH else line[:PROBLEM_WIDTH - 1].rstrip() + "…"


def _not_checked(name: str, verdict: str, problem: str, problems: int = 1,
                 seconds: float = 0.0) -> BatchRow:
    """The row of an entry whose structure was not analysed."""
    return BatchRow(name, verdict, problem, problems, "", None, None, None, "not checked",
                    "not checked", seconds)


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
    >>> row = check_table(tables / "four_bar.yaml")
    >>> row.verdict, row.W, row.identification, row.existence
    ('correct', 1, 'not given', 'whole cycle')
    >>> row = check_table(tables / "course_11_link_table.yaml")  # no sketch: variants unchecked
    >>> row.verdict, row.problems, row.identification, row.existence
    ('not verified', 2, 'matches', 'whole cycle')
    >>> check_table(tables / "hydraulic_boom.yaml").verdict
    'outside program'
    """
    start = time.perf_counter()
    path = Path(path)
    name = str(path.relative_to(root)) if root is not None else str(path)
    try:
        found = assess(path, points=POINTS)
    except AssurError as exc:
        issues = exc.issues if isinstance(exc, TableError) else None
        # the sentence; the lines under it (the spot in the file) are for the terminal
        first = (issues[0].text(lang) if issues else exc.text(lang)).splitlines()[0]
        return _not_checked(name, "unreadable", _short(first, path, name),
                            len(issues) if issues else 1, time.perf_counter() - start)
    return _row(name, path, found, lang, time.perf_counter() - start)


def _write_report(path: str, target: Path, lang: str) -> str:
    """Write the coursework report of one table; empty, or why it could not be written."""
    from assur.io.files import atomic_write_text
    from synthesis.app.coursework import build_report, render_html

    try:
        atomic_write_text(target, render_html(build_report(path, lang=lang)))
    except AssurError as exc:
        return exc.text(lang).replace("\n", " ")
    except Exception as exc:  # noqa: BLE001 - the row keeps its verdict whatever the pictures do
        return render("batch.report_failed", lang, error=type(exc).__name__,
                      detail=str(exc)[:200])
    return ""


def _check_one(job: tuple[str, str, str, str | None]) -> BatchRow:
    """Worker: check one file (and write its report); any failure becomes an unreadable row."""
    path, lang, root, reports = job
    name = str(Path(path).relative_to(root))
    try:
        row = check_table(path, lang=lang, root=root)
    except Exception as exc:  # noqa: BLE001 - a row, never a stop: report any failure
        return _not_checked(name, "unreadable", f"{type(exc).__name__}: {exc}")
    if reports is not None and row.verdict != "unreadable":
        target = Path(reports) / Path(name).with_suffix(".html")
        error = _write_report(path, target, lang)
        row = replace(row, report_error=error) if error else replace(row, report=str(target))
    return row


def _skipped(entry: Entry, root: Path, lang: str) -> BatchRow:
    assert entry.skip is not None
    return _not_checked(str(entry.path.relative_to(root)), "skipped", entry.skip.text(lang), 0)


def run_batch(folder: str | os.PathLike[str], *, jobs: int | None = None, lang: str = "en",
              progress: Callable[[int, int], None] | None = None,
              reports: str | os.PathLike[str] | None = None,
              executor: DaskExecutor | None = None) -> list[BatchRow]:
    """Check every table in a folder, in parallel; every other entry is a skipped row.

    Parameters
    ----------
    folder : path-like
    jobs : int, optional
        Worker processes; default, and at most, the cores of this machine
        (:func:`synthesis.distributed.usable_cores`). ``1`` checks in this process.
    lang : str
        A catalogue language.
    progress : callable, optional
        Called as ``progress(done, total)`` after every table checked.
    reports : path-like, optional
        A folder for one coursework report (HTML) per readable table, named after it.
    executor : DaskExecutor, optional
        Check the files as tasks on a Dask cluster (:func:`synthesis.distributed.connect`)
        instead of local processes; ``jobs`` is then ignored.

    Returns
    -------
    list of BatchRow
        One per entry (:func:`folder_entries`), in sorted file order.
    """
    check_lang(lang)
    root = Path(folder)
    entries = folder_entries(root)
    target = None if reports is None else str(reports)
    work = [(str(e.path), lang, str(root), target) for e in entries if e.skip is None]
    jobs = min(jobs or usable_cores(), usable_cores())  # more processes only share the cores
    checked: list[BatchRow] = []
    if executor is not None:
        checked = _collect(executor.map(_check_one, work), len(work), progress)
    elif jobs == 1 or len(work) <= 1:
        rows = map(_check_one, work)
        checked = _collect(rows, len(work), progress)
    else:
        chunk = max(1, min(8, len(work) // (4 * jobs)))
        with ProcessPoolExecutor(max_workers=jobs, initializer=_leave_ctrl_c_to_the_parent) as pool:
            checked = _collect(pool.map(_check_one, work, chunksize=chunk), len(work), progress)
    done = iter(checked)
    return [next(done) if e.skip is None else _skipped(e, root, lang) for e in entries]


def _leave_ctrl_c_to_the_parent() -> None:
    """Workers ignore Ctrl-C: the parent stops the batch and reports it, once."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _collect(rows: Iterable[BatchRow], total: int,
             progress: Callable[[int, int], None] | None) -> list[BatchRow]:
    found = []
    for row in rows:
        found.append(row)
        if progress:
            progress(len(found), total)
    return found
