"""A file of any table the course checks, assessed: ``assur check``, ``assur report`` and
``assur batch`` read a file here and render :func:`assur.check`'s one
:class:`~assur.assessment.Assessment`.

A chain table or an identification table is read as a chain; a synthesis problem is checked
at its initial design (its mechanism table at the initial values).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from assur.api import check
from assur.assessment import Assessment
from assur.errors import Issue, TableError
from assur.io.chain_table import chain_from_dict
from assur.io.reader import TableReader
from assur.io.sketch import higher_pair_problem
from assur.model import Chain

if TYPE_CHECKING:  # pragma: no cover
    from synthesis.problem import Problem

__all__ = ["assess", "load_table_chain", "read_table"]

#: Tables that only a synthesis problem has.
_SYNTHESIS_KEYS = ("parameters", "control_points", "allowable")


def read_table(path: str | os.PathLike[str]) -> Chain | Problem:
    """The table of a file, read and parsed once: a synthesis problem (it has the problem's
    own tables) or a chain (a chain table or an identification table).

    Raises
    ------
    AssurError
        When the file cannot be read as a table (every problem listed).
    """
    reader = TableReader.from_path(path)
    data = reader.data
    if isinstance(data, dict) and any(key in data for key in _SYNTHESIS_KEYS):
        from synthesis.problem_table import problem_from_dict

        reader.expect("problem")
        return problem_from_dict(data, reader.source, Path(path).parent)
    reader.expect("chain")
    return chain_from_dict(data, source=reader.source)


def load_table_chain(path: str | os.PathLike[str]) -> Chain:
    """The chain of a table file; for a synthesis problem, its mechanism at the initial design.

    Raises
    ------
    AssurError
        When the file cannot be read as a table (every problem listed).
    """
    table = read_table(path)
    return table if isinstance(table, Chain) else _design(table, path)


def _design(problem: Problem, path: str | os.PathLike[str]) -> Chain:
    """The mechanism of a synthesis problem at its initial design."""
    return chain_from_dict(problem.mechanism_table(problem.initial), source=str(path))


def assess(table: str | os.PathLike[str] | Chain, *, points: int | None = 360) -> Assessment:
    """Assess a table file (or a chain already read) with :func:`assur.check`.

    Parameters
    ----------
    table : path-like or Chain
        A chain table, an identification table or a synthesis problem (checked at its
        initial design), or a chain already read.
    points : int or None
        Crank positions of the existence check; None leaves the existence out.

    Returns
    -------
    Assessment
        When only the table's sketch is inconsistent, the assessment of its structure, read
        without the sketch, with the sketch's problems as its first findings.

    Raises
    ------
    AssurError
        When the file cannot be read as a table (every problem listed).

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> found = assess(tables / "problems" / "class1_fourbar_rocker.yaml", points=None)
    >>> found.analysis.W, found.identification
    (1, 'matches')
    """
    if isinstance(table, Chain):
        return check(table, points=points)
    try:
        read = read_table(table)
    except TableError as exc:
        if not exc.issues or not all(_in_sketch(issue) for issue in exc.issues):
            raise
        sketch_problems = exc.issues
    else:
        if isinstance(read, Chain):
            return check(read, points=points)
        # a synthesis problem's assembly variants are its givens: nothing to verify
        return check(_design(read, table), points=points).with_variants_given()
    # only the sketch is inconsistent: the structure does not need it
    found = check(_chain_without_sketch(table), points=points)
    return found.with_problems(sketch_problems)


def _in_sketch(issue: Issue) -> bool:
    """Whether a problem of a table is one of its sketch (the ``geometry:`` section) that the
    structure does without (not a higher pair's profiles)."""
    return issue.location.startswith(("geometry", "mechanism 'geometry'")) and \
        not higher_pair_problem(issue)


def _chain_without_sketch(path: str | os.PathLike[str]) -> Chain:
    """The chain of a chain table read without its sketch."""
    reader = TableReader.from_path(path)
    data = reader.data
    if isinstance(data, dict):
        data = {key: value for key, value in data.items() if key != "geometry"}
        if isinstance(data.get("mechanism"), dict):
            data["mechanism"] = {key: value for key, value in data["mechanism"].items()
                                 if key != "geometry"}
    return chain_from_dict(data, source=reader.source)
