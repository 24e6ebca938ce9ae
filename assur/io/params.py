"""The ``params:`` of an identification row (tables 2.1–2.6) → a typed :class:`GroupParams`,
and the one reading of a cell of tables 2.1–2.6 (:func:`read_cell`).

A row's ``params:`` lists the parameter columns of its group's kind (:mod:`assur.kinds`): a
number, or ``'A'`` for a coordinate supplied by an earlier group (the ranges
``[initial, lower, upper]`` of a synthesis live in the problem table, read by
:mod:`synthesis`). The course's own forms of a value that does not vary are read as well
(``docs/tables.md`` §6): ``[v, v, 0]`` a fixed value v, ``[0, A, 0]`` a value supplied by an
earlier group, ``[0, 0, 0]`` an absent parameter; the course's Cyrillic «А» is read as
``'A'``, with a warning. Extra keys: ``delta`` (the
margin δ), ``s`` (on L0: +1 counter-clockwise, −1 clockwise), ``l_<name>``/``beta_<name>``
columns of tracing points and ``tracing: [{name: Ж, link: L}, ...]``.

The section is read once, with its row, and every value is checked here.

Examples
--------
>>> params = read_params("rows.yaml", "L0(1)", {"x_O1": 0, "y_O1": 0, "l_1": 40,
...                                       "phi_1_0": 90, "s": -1})
>>> params.values["l_1"], params.direction
(40.0, -1)
>>> read_params("rows.yaml", "L0(1)", {"l_1": "long"}).problems[0].text()
"structure_identification (L0(1)) 'params' 'l_1': expected a number or 'A' (supplied by an \
earlier group); found 'long' (a text)"
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from assur.errors import Issue
from assur.io.reader import (
    Node,
    TableReader,
    describe,
    is_number,
    latin_form,
    lookalike_letters,
    normalise_id,
    radian_look,
    with_commas,
)
from assur.model import GroupParams
from assur.text import Message

__all__ = ["SUPPLIED", "Cell", "read_cell", "read_params"]

#: The symbol of a value supplied by an earlier group (``method.md`` §4.3).
SUPPLIED = "A"
#: The columns that hold angles, in degrees (``phi_1_0``, ``beta_S``, ``gamma``, …).
_ANGLE = re.compile(r"(phi|beta|gamma|alpha|theta|psi)(_|$)")


@dataclass(frozen=True)
class Cell:
    """One cell of tables 2.1–2.6 as read by :func:`read_cell`.

    Attributes
    ----------
    value : object
        What the cell stands for: a number (a fixed value, or the initial value of a varied
        one), :data:`SUPPLIED`, or the value as written when it is neither a range nor one
        of the course's forms (the kinematic model judges it).
    bounds : tuple of float or None
        ``(initial, lower, upper)`` of a range with lower < upper (a varied parameter);
        None otherwise.
    problem : Message or None
        Why the cell is refused (a list that is neither a range nor one of the course's
        forms).
    warning : Message or None
        The Cyrillic «А» read as ``'A'``.
    both_forms : bool
        Whether the cell is ``[v, v, 0]`` with v < 0, which the program's encoding would
        read as a range (v to 0, from v): it is read as the course's fixed value v.
    ranged : bool
        Whether the cell is written as a range of the program's, right or wrong (three
        numbers, lower < upper or out of order, none of the course's forms).
    """

    value: Any
    bounds: tuple[float, float, float] | None = None
    problem: Message | None = None
    warning: Message | None = None
    both_forms: bool = False
    ranged: bool = False


def read_cell(raw: Any) -> Cell:
    """Read one parameter cell in the program's encoding or in the course's.

    The program's: a number (fixed), ``'A'`` (supplied by an earlier group),
    ``[initial, lower, upper]`` with lower ≤ initial ≤ upper (varied when lower < upper).
    The course's (table rows "initial value, left bound, right bound"): ``[v, v, 0]`` — "the
    left bound … equal to the number of the value" — a fixed value v; ``[0, A, 0]`` — "the
    symbol «А» in place of the left bound and … zero for the right" — supplied (the initial
    value may also be written ``A``); ``[0, 0, 0]``, an absent parameter, is the fixed value
    0 in either encoding.  ``[v, v, 0]`` with v < 0 would also be a range of the program's
    (v to 0 from v): it is read as the course's fixed value v, marked
    :attr:`Cell.both_forms` (a problem table warns of it).

    Parameters
    ----------
    raw : object
        The cell as parsed from YAML.

    Returns
    -------
    Cell

    Examples
    --------
    >>> read_cell([110, 110, 0]).value, read_cell([0, "A", 0]).value, read_cell(0).value
    (110, 'A', 0)
    >>> read_cell([36, 30, 50]).bounds, read_cell([-15, -15, 0]).value
    ((36.0, 30.0, 50.0), -15)
    >>> read_cell("А").value, read_cell("А").warning.code
    ('A', 'params.supplied_lookalike')
    >>> print(read_cell([0, "B", 0]).problem.text("en"))  # doctest: +NORMALIZE_WHITESPACE
    expected a number, 'A', [initial, lower, upper], or the course's [v, v, 0] (fixed) or
    [0, A, 0] (supplied by an earlier group); found [0, 'B', 0]
    >>> print(read_cell([5, 3, 0]).problem.text("en"))  # doctest: +NORMALIZE_WHITESPACE
    the course writes a fixed value v as [v, v, 0] (the initial value equal to the left
    bound); found [5, 3, 0]
    """
    if isinstance(raw, str):
        return _supplied(raw) or Cell(raw)
    if not isinstance(raw, list):
        return Cell(raw)
    found = with_commas(raw)
    symbol = _supplied(raw[1]) if len(raw) == 3 and isinstance(raw[1], str) else None
    if symbol is not None:
        first = _supplied(raw[0]) if isinstance(raw[0], str) else None
        if (first is not None or (is_number(raw[0]) and raw[0] == 0)) \
                and is_number(raw[2]) and raw[2] == 0:
            return Cell(SUPPLIED, warning=symbol.warning if first is None or symbol.warning
                        else first.warning)
        return Cell(raw, problem=Message("params.supplied_form", {"found": found}))
    if len(raw) != 3 or not all(map(is_number, raw)):
        return Cell(raw, problem=Message("params.cell", {"found": found}))
    initial, lower, upper = (float(v) for v in raw)
    if upper == 0 and initial == lower != 0:
        return Cell(raw[0], both_forms=lower < 0)
    if lower > upper and upper == 0:
        return Cell(raw, problem=Message("params.fixed_form", {"found": found}))
    if lower > upper:
        return Cell(raw, problem=Message("problem.bounds_order", {"found": found}), ranged=True)
    if not lower <= initial <= upper:
        return Cell(raw, problem=Message("problem.initial_outside", {"found": found}),
                    ranged=True)
    if lower == upper:
        return Cell(raw[0])
    return Cell(raw[0], (initial, lower, upper), ranged=True)


def _supplied(text: str) -> Cell | None:
    """``'A'``, or the course's «А» typed in Cyrillic (with a warning); None for other text."""
    if text == SUPPLIED:
        return Cell(SUPPLIED)
    if latin_form(text) == SUPPLIED and lookalike_letters(text):
        return Cell(SUPPLIED, warning=Message("params.supplied_lookalike", {"value": text}))
    return None


def read_params(source: str, label: str, data: Any,
                warnings: list[Issue] | None = None) -> GroupParams:
    """Read the ``params:`` of one identification row.

    Every value is checked here (a number, ``'A'``, or one of the course's forms of a value
    that does not vary, :func:`read_cell`; ``s`` ±1; tracing rows ``{name, link}``); the problems are kept in
    :attr:`GroupParams.problems`. Which columns a group needs, and where ``'A'`` may stand,
    depend on the group the structure analysis finds: the kinematic model checks them and
    reports them together with the problems of the values
    (:func:`assur.kinematics.build.model_from_params`), so that reading the structure of a
    table does not depend on its dimensions.

    Parameters
    ----------
    source : str
        The table's file.
    label : str
        The row's group label (``"L1(2,3)"``), used in the problems' locations.
    data : mapping
        The ``params:`` as parsed from YAML.
    warnings : list of Issue, optional
        Where an angle that looks written in radians (:func:`~assur.io.reader.radian_look`)
        is warned of.

    Returns
    -------
    GroupParams
    """
    reader = TableReader.from_data(data, source)
    where = f"structure_identification ({label}) 'params'"
    node = Node(reader, where, dict(data), None)
    values: dict[str, float] = {}
    supplied = set()
    for column, raw in node.mapping.items():
        if column in ("s", "tracing"):
            continue
        at = f"{where} {column!r}"
        cell = read_cell(raw)
        if cell.warning is not None and warnings is not None:
            warnings.append(Issue(at, cell.warning))
        if cell.ranged:
            reader.problem(at, "model.range_in_problem", found=str(raw))
        elif cell.problem is not None:
            reader.problem(at, cell.problem.code, **cell.problem.data)
        elif cell.value == SUPPLIED:
            supplied.add(str(column))
        elif is_number(cell.value):
            values[str(column)] = float(cell.value)
            look = radian_look(cell.value) if _ANGLE.match(str(column)) else None
            if look is not None and warnings is not None:
                warnings.append(Issue(at, look))
        else:
            reader.problem(at, "model.value", found=describe(raw))
    s = node.get("s", kind="int", required=False, default=1,
                 check=lambda v: None if v in (1, -1) else
                 Message("rule.plus_minus_one", {"name": "s"}))
    tracing = []
    names = node.mapping.get("tracing")
    for entry in names if isinstance(names, list) else []:
        if not isinstance(entry, dict) or set(entry) - {"name", "link"}:
            reader.problem(f"{where} 'tracing'", "model.tracing_row", found=describe(entry))
        else:
            tracing.append((str(entry.get("name")), normalise_id(entry.get("link"))))
    return GroupParams(values, frozenset(supplied), s if s in (1, -1) else 1,
                       tuple(tracing), tuple(map(str, node.mapping)), tuple(reader.issues))

