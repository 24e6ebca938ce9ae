"""The ``params:`` of an identification row (tables 2.1–2.6) → a typed :class:`GroupParams`.

A row's ``params:`` lists the parameter columns of its group's kind (:mod:`assur.kinds`): a
number, or ``'A'`` for a coordinate supplied by an earlier group (the ranges
``[initial, lower, upper]`` of a synthesis live in the problem table, read by
:mod:`synthesis`). Extra keys: ``delta`` (the
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
from typing import Any

from assur.errors import Issue
from assur.io.reader import (
    Node,
    TableReader,
    describe,
    is_number,
    normalise_id,
    radian_look,
)
from assur.model import GroupParams
from assur.text import Message

__all__ = ["SUPPLIED", "read_params"]

#: The symbol of a value supplied by an earlier group (``method.md`` §4.3).
SUPPLIED = "A"
#: The columns that hold angles, in degrees (``phi_1_0``, ``beta_S``, ``gamma``, …).
_ANGLE = re.compile(r"(phi|beta|gamma|alpha|theta|psi)(_|$)")


def read_params(source: str, label: str, data: Any,
                warnings: list[Issue] | None = None) -> GroupParams:
    """Read the ``params:`` of one identification row.

    Every value is checked here (a number, ``'A'``, or a range with lower ≤ initial ≤
    upper; ``s`` ±1; tracing rows ``{name, link}``); the problems are kept in
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
        if raw == SUPPLIED:
            supplied.add(str(column))
        elif isinstance(raw, list) and len(raw) == 3 and all(is_number(v) for v in raw):
            reader.problem(at, "model.range_in_problem", found=str(raw))
        elif is_number(raw):
            values[str(column)] = float(raw)
            look = radian_look(raw) if _ANGLE.match(str(column)) else None
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

