"""The ``masses:``, ``loads:`` and ``gravity:`` sections of a chain table (``docs/forces.md`` §1).

:func:`read_forces` reads them from the root of a parsed table through the table reader, so
that every problem is recorded with its table, row and field, all at once, beside the
problems of the other sections.

Examples
--------
>>> from assur import chain_from_dict
>>> from assur.io.reader import TableReader
>>> chain = chain_from_dict({"mechanism": {"pairs": [
...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
...     {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
...     "inputs": [1]}})
>>> reader = TableReader.from_data({"masses": {2: {"mass": -1, "centre": [1, 2]}},
...                                 "loads": [{"link": 0, "torque": 5}]}, "t.yaml")
>>> read_forces(reader.root(), chain) is None
True
>>> [issue.text() for issue in reader.issues]  # doctest: +NORMALIZE_WHITESPACE
["masses.2 'mass': must be zero or positive; found -1",
 "loads[0] 'link': expected a moving link (1, 2, 3); found 0"]
"""

from __future__ import annotations

import itertools
import math
from typing import Any

from assur.io.reader import MISSING, Node, describe, normalise_id
from assur.model import Chain, ForceData, LinkId, Load, Mass, PairType, Tabulated

__all__ = ["SECTIONS", "read_forces", "read_sections"]

#: The top-level keys this reader owns.
SECTIONS = ("masses", "loads", "gravity")

_MASS = ("mass", "centre", "inertia")
_LOAD = ("link", "force", "point", "torque")


def read_forces(root: Node, chain: Chain) -> ForceData | None:
    """The force-analysis sections of a table, or None when it has neither masses nor loads.

    Parameters
    ----------
    root : Node
        The top of the table (``TableReader.root``); problems go to its reader.
    chain : Chain
        The mechanism, for its moving links and its input (a crank's tables are over the
        angle ``phi`` in degrees, an actuator's over its ``length`` in mm).

    Returns
    -------
    ForceData or None
        None also when a problem was recorded (see ``root.reader.issues``).

    Examples
    --------
    >>> from assur import load_chain
    >>> from assur.io.reader import TableReader
    >>> from pathlib import Path; import assur
    >>> TABLES = Path(assur.__file__).parents[1] / "input_tables"
    >>> chain = load_chain(TABLES / "four_bar.yaml")
    >>> reader = TableReader.from_data({"loads": [{"link": 3, "torque": -15}],
    ...                                 "gravity": [0, -9.81]})
    >>> read_forces(reader.root(), chain).gravity
    -9.81j
    """
    return read_sections(root, chain.moving_links, _actuated(chain))


def read_sections(root: Node, moving: tuple[LinkId, ...], actuated: bool
                  ) -> ForceData | None:
    """The force-analysis sections given the moving links and the kind of input.

    The chain reader calls this while it reads the rest of the table, so that the problems
    of these sections are listed with those of the others.

    Parameters
    ----------
    root : Node
        The top of the table.
    moving : tuple of link ids
        The links that may carry masses and loads.
    actuated : bool
        Whether the input is a linear actuator (tables over ``length``, else ``phi``).

    Returns
    -------
    ForceData or None
        None when the table has neither ``masses:`` nor ``loads:``, or a problem was
        recorded.
    """
    reader = root.reader
    before = len(reader.issues)
    key = "length" if actuated else "phi"
    masses = _masses(root, moving)
    loads = _loads(root, moving, key)
    gravity = _gravity(root)
    if len(reader.issues) > before or not (root.has("masses") or root.has("loads")):
        return None
    return ForceData(masses, loads, gravity)


def _actuated(chain: Chain) -> bool:
    """Whether the input is a driven prismatic pair (an actuator)."""
    for drive in chain.inputs:
        if drive.link is None and drive.pair is not None:
            return chain.pair(drive.pair).type == PairType.P
    return False


def _link(node: Node, moving: tuple[LinkId, ...], where: str, value: Any) -> LinkId | None:
    """The moving link ``value`` names; none is judged when no moving link is known (the
    chain could not be read, which is reported)."""
    link: LinkId = normalise_id(value)
    if moving and link not in moving:
        node.reader.problem(where, "force.link.not_moving", found=describe(value),
                            known=", ".join(map(str, moving)))
        return None
    return link


def _nonnegative(node: Node, key: str, default: Any) -> Any:
    value = node.get(key, kind="number", required=default is MISSING, default=default)
    if value is not MISSING and value < 0:
        node.reader.problem(f"{node.location} {key!r}", "force.negative", found=describe(value))
        return MISSING
    return value


def _point(node: Node, key: str) -> complex | None:
    """An optional [x, y] pair of numbers (None when absent or wrong, the latter recorded)."""
    if not node.has(key):
        return None
    value = node.mapping[key]
    if (isinstance(value, list) and len(value) == 2
            and all(_number(v) for v in value)):
        return complex(value[0], value[1])
    node.reader.problem(f"{node.location} {key!r}".strip(), "force.vector.expected",
                        found=describe(value))
    return None


def _number(value: Any) -> bool:
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value))


def _masses(root: Node, moving: tuple[LinkId, ...]) -> dict[LinkId, Mass]:
    section = root.child("masses", required=False)
    out: dict[LinkId, Mass] = {}
    if section is None:
        return out
    for raw, row in section.mapping.items():
        where = f"{section.location}.{raw}"
        link = _link(section, moving, where, raw)
        if not isinstance(row, dict):
            section.reader.problem(where, "force.mass.expected", found=describe(row))
            continue
        node = Node(section.reader, where, row, _MASS)
        mass = _nonnegative(node, "mass", MISSING)
        inertia = _nonnegative(node, "inertia", 0.0)
        centre = _point(node, "centre")
        if mass is not MISSING and mass > 0 and not node.given("centre"):
            section.reader.problem(where, "force.mass.centre_missing", link=str(raw))
        if link is not None and MISSING not in (mass, inertia):
            out[link] = Mass(float(mass), centre, float(inertia))
    return out


def _loads(root: Node, moving: tuple[LinkId, ...], key: str) -> tuple[Load, ...]:
    out = []
    for node in root.rows("loads", _LOAD, required=False):
        node.swapped({"link": lambda v: isinstance(v, (int, str)) and not isinstance(v, bool),
                      "force": lambda v: isinstance(v, (list, dict))})
        raw = node.get("link", kind="id")
        link = None if raw is MISSING else _link(node, moving, f"{node.location} 'link'", raw)
        if node.misspelt.keys() & {"force", "torque"}:
            continue  # written misspelt or swapped with the link: reported as such
        has_force, has_torque = node.has("force"), node.has("torque")
        if has_force == has_torque:
            node.reader.problem(node.location, "force.load.force_or_torque")
            continue
        point = _point(node, "point")
        if has_force:
            force = _tabulated(node, "force", key, ("x", "y"))
            if not node.given("point"):
                node.reader.problem(node.location, "force.load.point_missing",
                                    link=str(raw))
            if link is not None and force is not None and point is not None:
                out.append(Load(link, force=force, point=point))
        else:
            if node.has("point"):
                node.reader.problem(f"{node.location} 'point'", "force.load.point_with_torque")
            torque = _tabulated(node, "torque", key, ("value",))
            if link is not None and torque is not None:
                out.append(Load(link, torque=torque.real if isinstance(torque, complex)
                                else torque))
    return tuple(out)


def _tabulated(node: Node, field: str, key: str, parts: tuple[str, ...]
               ) -> complex | Tabulated | None:
    """A constant ([Fx, Fy] or a number) or a table over the input coordinate."""
    value = node.mapping[field]
    where = f"{node.location} {field!r}"
    if not isinstance(value, dict):
        if parts == ("value",) and _number(value):
            return complex(value)
        if parts == ("x", "y"):
            return _point(node, field)
        node.reader.problem(where, "force.table.expected", found=describe(value),
                            keys=", ".join((key, *parts)))
        return None
    table = Node(node.reader, where, value, (key, *parts))
    columns = {}
    for name in (key, *parts):
        column = table.get(name, kind="list")
        if column is MISSING:
            continue
        if not all(_number(v) for v in column):
            node.reader.problem(f"{where} {name!r}", "force.table.numbers",
                                found=describe(column))
            continue
        columns[name] = [float(v) for v in column]
    if len(columns) < 1 + len(parts):
        return None
    lengths = {len(c) for c in columns.values()}
    if len(lengths) > 1:
        node.reader.problem(where, "force.table.lengths",
                            found=", ".join(f"{k}: {len(c)}" for k, c in columns.items()))
        return None
    nodes = columns[key]
    values = ([complex(x, y) for x, y in zip(columns["x"], columns["y"])]
              if parts == ("x", "y") else columns["value"])
    if not _nodes_ok(node, f"{where} {key!r}", key, nodes, values):
        return None
    return Tabulated(tuple(nodes), tuple(values))


def _nodes_ok(node: Node, where: str, key: str, nodes: list[float],
              values: list[Any]) -> bool:
    reader = node.reader
    if len(nodes) < 2:
        reader.problem(where, "force.table.too_short", n=len(nodes))
        return False
    if any(b <= a for a, b in itertools.pairwise(nodes)):
        reader.problem(where, "force.table.not_increasing", found=_list(nodes))
        return False
    if key != "phi":
        return True
    if nodes[0] < 0 or nodes[-1] > 360:
        reader.problem(where, "force.table.outside", found=_list(nodes))
        return False
    if nodes[-1] == 360 and (nodes[0] != 0 or values[0] != values[-1]):
        reader.problem(where, "force.table.ends")
        return False
    return True


def _list(numbers: list[float]) -> str:
    return ", ".join(f"{v:g}" for v in numbers)


def _gravity(root: Node) -> complex:
    if not root.has("gravity"):
        return 0j
    return _point(root, "gravity") or 0j
