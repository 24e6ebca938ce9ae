"""The ``params:`` of an identification row (tables 2.1–2.6) → a typed :class:`GroupParams`.

A row's ``params:`` lists the parameter columns of its group's kind (:mod:`assur.kinds`): a
number, ``'A'`` for a coordinate supplied by an earlier group, or ``[initial, lower, upper]``
(a range for synthesis; the model takes the initial value). Extra keys: ``delta`` (the
margin δ), ``s`` (on L0: +1 counter-clockwise, −1 clockwise), ``l_<name>``/``beta_<name>``
columns of tracing points and ``tracing: [{name: Ж, link: L}, ...]``.

The section is read once, with its row, and every rule that the row itself decides is
checked here: the columns of the kind, the numbers, the ranges, ``'A'`` only where a point
lies on a moving link (the row names the link each hinge and guide is on), the tracing
points.

Examples
--------
>>> from assur.io.reader import TableReader
>>> reader = TableReader.from_data({}, "rows.yaml")
>>> params = read_params(reader, "L0(1)", {"x_O1": 0, "y_O1": 0, "l_1": [40, 30, 50],
...                                       "phi_1_0": 90, "s": -1}, kind=0, links=(1, None),
...                      ends=(0, None), frame=0)
>>> params.values["l_1"], params.bounds, params.direction
(40.0, {'l_1': (30.0, 50.0)}, -1)
"""

from __future__ import annotations

import difflib
import math
from typing import Any

from assur.io.reader import MISSING, Node, TableReader, describe, normalise_id
from assur.kinds import kind_of
from assur.model import GroupParams, LinkId
from assur.text import Message

__all__ = ["SUPPLIED", "read_params"]

#: The symbol of a value supplied by an earlier group (``method.md`` §4.3).
SUPPLIED = "A"


def read_params(reader: TableReader, label: str, data: Any, *, kind: int,
                links: tuple[LinkId, LinkId | None], ends: tuple[LinkId, LinkId | None],
                frame: Any) -> GroupParams | None:
    """Read the ``params:`` of one identification row, recording every problem.

    Parameters
    ----------
    reader : TableReader
        Collects the problems.
    label : str
        The group's label (``"L1(2,3)"``), used in the problems' locations.
    data : mapping
        The ``params:`` as parsed from YAML.
    kind : int
        The row's L.
    links, ends : tuple
        The row's (i, j) and (i−1, j−1).
    frame : link id
        The frame (a point on it is given by its coordinates, not ``'A'``).

    Returns
    -------
    GroupParams or None
        None when a problem was recorded.
    """
    where = f"structure_identification ({label}) 'params'"
    count = len(reader.issues)
    node = Node(reader, where, dict(data), None)
    group_kind = kind_of(kind)
    columns = group_kind.columns
    allowed = set(columns) | {"delta", "tracing"} | ({"s"} if group_kind.is_input else set())
    extra = set()
    for key in node.mapping:
        if key in allowed:
            continue
        if isinstance(key, str) and key.startswith(("l_", "beta_")):
            extra.add(key)
            continue
        hint = difflib.get_close_matches(str(key), sorted(allowed), n=1, cutoff=0.6)
        if hint:
            reader.problem(where, "model.unknown_column_hint", column=repr(key), hint=hint[0])
        else:
            reader.problem(where, "model.unknown_column", column=repr(key), kind=group_kind.code,
                           columns=", ".join(columns))
    supplied = _supplied_columns(group_kind.code, dict(zip("ij", ends, strict=True)), frame)
    values: dict[str, float] = {}
    bounds: dict[str, tuple[float, float]] = {}
    for column in (*columns, "delta", *sorted(extra)):
        raw = node.mapping.get(column, MISSING)
        at = f"{where} {column!r}"
        if raw is MISSING:
            if column != "delta":
                reader.problem(at, "model.missing_column")
            continue
        rule = supplied.get(column)
        if rule is not None:
            _check_supplied(reader, at, raw, rule)
            if raw == SUPPLIED:
                continue
        elif raw == SUPPLIED:
            reader.problem(at, "model.supplied_here")
            continue
        if isinstance(raw, list) and len(raw) == 3 and all(_is_number(v) for v in raw):
            value, lo, hi = (float(v) for v in raw)
            if not lo <= value <= hi:
                reader.problem(at, "model.range", found=str(raw))
                continue
            bounds[column] = (lo, hi)
        elif _is_number(raw):
            value = float(raw)
        else:
            reader.problem(at, "model.value", found=describe(raw))
            continue
        values[column] = value
    direction = 1
    if group_kind.is_input:
        s = node.get("s", kind="int", required=False, default=1,
                     check=lambda v: None if v in (1, -1) else
                     Message("rule.plus_minus_one", {"name": "s"}))
        direction = s if s in (1, -1) else 1
    tracing = _tracing(reader, where, node.mapping.get("tracing"), links, values)
    if len(reader.issues) > count:
        return None
    return GroupParams(values, bounds, direction, tracing)


def _supplied_columns(code: str, ends: dict[str, LinkId | None], frame: Any
                      ) -> dict[str, tuple[str, LinkId | None]]:
    """Coordinate column → (rule, link): ``"frame_hinge"``/``"frame_guide"`` (a number is
    needed), ``"moving_hinge"`` (``'A'`` is needed), ``"moving_guide"`` (either)."""
    kind = kind_of(int(code[1:]))
    out: dict[str, tuple[str, LinkId | None]] = {}
    for side, (x, y) in kind.hinges.items():
        rule = "frame_hinge" if ends[side] == frame else "moving_hinge"
        out.update({x: (rule, ends[side]), y: (rule, ends[side])})
    for side, (x, y, _, _) in kind.guides.items():
        rule = "frame_guide" if ends[side] == frame else "moving_guide"
        out.update({x: (rule, ends[side]), y: (rule, ends[side])})
    return out


def _check_supplied(reader: TableReader, at: str, raw: Any,
                    rule: tuple[str, LinkId | None]) -> None:
    name, link = rule
    if raw == SUPPLIED and name in ("frame_hinge", "frame_guide"):
        reader.problem(at, f"model.{name}_needs_number")
    elif raw != SUPPLIED and name == "moving_hinge":
        reader.problem(at, "model.moving_hinge_supplied", link=repr(link), found=describe(raw))


def _tracing(reader: TableReader, where: str, names: Any, links: tuple[LinkId, LinkId | None],
             values: dict[str, float]) -> tuple[tuple[str, LinkId], ...]:
    out = []
    for entry in names if isinstance(names, list) else []:
        if not isinstance(entry, dict) or set(entry) - {"name", "link"}:
            reader.problem(f"{where} 'tracing'", "model.tracing_row", found=describe(entry))
            continue
        name, link = str(entry.get("name")), normalise_id(entry.get("link"))
        cols = (f"l_{name}", f"beta_{name}")
        if link not in links or link is None or any(c not in values for c in cols):
            reader.problem(f"{where} 'tracing'", "model.tracing_point", name=repr(name),
                           i=links[0], j=links[1], l=cols[0], beta=cols[1])
            continue
        out.append((name, link))
    return tuple(out)


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
