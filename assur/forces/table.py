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
["masses.2 'mass': must be positive and at most 1e+06; found -1",
 "loads[0] 'link': expected a moving link (1, 2, 3); found 0"]

Every value has a physical range (``docs/forces.md`` §1.1): a mass in (0, :data:`MAX_MASS`],
an inertia in [0, :data:`MAX_INERTIA`], gravity at most :data:`MAX_GRAVITY`, every force,
torque and tabulated value finite and at most ``LARGEST`` in size, and a centre or a load
point within :data:`REACH` times the size of the mechanism around its sketch.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from assur.io.reader import MISSING, Node, describe, normalise_id, number_problem
from assur.model import Chain, ForceData, LinkId, Load, Mass, PairType, Tabulated
from assur.text import Message

__all__ = ["MAX_GRAVITY", "MAX_INERTIA", "MAX_MASS", "REACH", "SECTIONS", "Reach",
           "inertia_problem", "link_key_problem", "mass_problem", "read_forces",
           "read_sections"]

#: The top-level keys this reader owns.
SECTIONS = ("masses", "loads", "gravity")

_MASS = ("mass", "centre", "inertia")
_LOAD = ("link", "force", "point", "torque")

#: The largest mass of one link, kg.
MAX_MASS = 1e6
#: The largest moment of inertia of one link about its centre of mass, kg·m².
MAX_INERTIA = 1e6
#: The largest gravity, m/s² (a hundred times the Earth's).
MAX_GRAVITY = 1e3
#: How far a centre of mass or the point of a force may lie from the mechanism: this many
#: times its size (the diagonal of the box around its sketch) beyond that box.
REACH = 100.0


@dataclass(frozen=True, slots=True)
class Reach:
    """Where a centre of mass or the point of a force may lie: the box around the
    mechanism's sketch grown by :data:`REACH` times its diagonal on every side.

    Examples
    --------
    >>> box = Reach.around([0j, 100 + 0j, 100 + 80j])
    >>> box.holds(50 + 40j), box.holds(20000 + 0j)
    (True, False)
    """

    low: complex
    high: complex
    size: float

    @classmethod
    def around(cls, points: Iterable[complex]) -> Reach | None:
        """The reach around ``points`` (None when there are fewer than two distinct ones)."""
        xs = [z.real for z in points]
        ys = [z.imag for z in points]
        if not xs:
            return None
        low, high = complex(min(xs), min(ys)), complex(max(xs), max(ys))
        size = abs(high - low)
        if size == 0:
            return None
        grow = REACH * size * (1 + 1j)
        return cls(low - grow, high + grow, size)

    def box(self) -> str:
        """The reach as text: ``x low…high, y low…high`` (mm)."""
        return (f"x {self.low.real:g}…{self.high.real:g}, "
                f"y {self.low.imag:g}…{self.high.imag:g}")

    def holds(self, z: complex) -> bool:
        """Whether ``z`` lies inside the reach."""
        return (self.low.real <= z.real <= self.high.real
                and self.low.imag <= z.imag <= self.high.imag)


def mass_problem(value: float) -> Message | None:
    """The rule of a mass (kg): positive and at most :data:`MAX_MASS`.

    >>> mass_problem(0.5) is None, mass_problem(0).text("en")
    (True, 'must be positive and at most 1e+06')
    """
    return None if 0 < value <= MAX_MASS else Message("rule.positive_at_most",
                                                      {"high": MAX_MASS})


def inertia_problem(value: float) -> Message | None:
    """The rule of a moment of inertia (kg·m²): zero (a point mass) to :data:`MAX_INERTIA`.

    >>> inertia_problem(0) is None, inertia_problem(1e7).text("en")
    (True, 'must be zero or positive and at most 1e+06')
    """
    return None if 0 <= value <= MAX_INERTIA else Message("rule.non_negative_at_most",
                                                          {"high": MAX_INERTIA})


def link_key_problem(node: Node, where: str, raw: Any) -> bool:
    """Record a key of a table over links that is not a link id (a boolean, a fraction:
    ``{2.0: …}`` or ``{true: …}`` would silently name link 2 or 1); True when recorded."""
    if isinstance(raw, int | str) and not isinstance(raw, bool):
        return False
    node.reader.problem(where, "table.wrong_kind", expected=Message("value.kind.id"),
                        found=describe(raw))
    return True


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
    sketch = chain.geometry.points.values() if chain.geometry is not None else ()
    return read_sections(root, chain.moving_links, _actuated(chain), Reach.around(sketch))


def read_sections(root: Node, moving: tuple[LinkId, ...], actuated: bool,
                  reach: Reach | None = None) -> ForceData | None:
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
    reach : Reach, optional
        Where centres and load points may lie (unbounded but for ``LARGEST`` when None).

    Returns
    -------
    ForceData or None
        None when the table has neither ``masses:`` nor ``loads:``, or a problem was
        recorded.
    """
    reader = root.reader
    before = len(reader.issues)
    key = "length" if actuated else "phi"
    masses = _masses(root, moving, reach)
    loads = _loads(root, moving, key, reach)
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


def _numeric(value: Any) -> Any:
    """A number written as text (``1e300``, which YAML reads as text) as the number."""
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return value
    return value


def _bad_number(node: Node, where: str, value: Any) -> bool:
    """Record ``value`` when it is not a finite number of at most ``LARGEST`` in size."""
    rule = number_problem(_numeric(value))
    if rule is None:
        return False
    if rule.code == "value.kind.number":
        node.reader.problem(where, "table.wrong_kind", expected=rule, found=describe(value))
    else:
        node.reader.problem(where, "table.rule_broken", rule=rule, found=describe(value))
    return True


def _point(node: Node, key: str, reach: Reach | None = None) -> complex | None:
    """An optional [x, y] pair of numbers, inside ``reach`` when given (None when absent or
    wrong, the latter recorded)."""
    if not node.has(key):
        return None
    value = node.mapping[key]
    where = f"{node.location} {key!r}".strip()
    if not (isinstance(value, list) and len(value) == 2):
        node.reader.problem(where, "force.vector.expected", found=describe(value))
        return None
    bad = [_bad_number(node, f"{where}[{i}]", v) for i, v in enumerate(value)]
    if any(bad):
        return None
    z = complex(_numeric(value[0]), _numeric(value[1]))
    if reach is not None and not reach.holds(z):
        node.reader.problem(where, "force.point.outside", found=f"[{z.real:g}, {z.imag:g}]",
                            reach=REACH, size=reach.size, box=reach.box())
        return None
    return z


def _masses(root: Node, moving: tuple[LinkId, ...], reach: Reach | None
            ) -> dict[LinkId, Mass]:
    section = root.child("masses", required=False)
    out: dict[LinkId, Mass] = {}
    if section is None:
        return out
    for raw, row in section.mapping.items():
        where = f"{section.location}.{raw}"
        link = None if link_key_problem(section, where, raw) else \
            _link(section, moving, where, raw)
        if not isinstance(row, dict):
            section.reader.problem(where, "force.mass.expected", found=describe(row))
            continue
        node = Node(section.reader, where, row, _MASS)
        mass = node.get("mass", kind="number", check=mass_problem)
        inertia = node.get("inertia", kind="number", required=False, default=0.0,
                           check=inertia_problem)
        centre = _point(node, "centre", reach)
        if mass is not MISSING and not node.given("centre"):
            section.reader.problem(where, "force.mass.centre_missing", link=str(raw))
        if link is not None and MISSING not in (mass, inertia):
            out[link] = Mass(float(mass), centre, float(inertia))
    return out


def _loads(root: Node, moving: tuple[LinkId, ...], key: str, reach: Reach | None
           ) -> tuple[Load, ...]:
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
        point = _point(node, "point", reach)
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
        if parts == ("value",) and isinstance(_numeric(value), int | float) \
                and not isinstance(value, bool):
            return None if _bad_number(node, where, value) else complex(_numeric(value))
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
        bad = [_bad_number(node, f"{where} {name!r}[{i}]", v) for i, v in enumerate(column)]
        if any(bad):  # (every bad value listed)
            continue
        columns[name] = [float(_numeric(v)) for v in column]
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
    gravity = _point(root, "gravity") or 0j
    if abs(gravity) > MAX_GRAVITY:
        root.reader.problem("'gravity'", "table.rule_broken",
                            rule=Message("rule.number_size", {"high": MAX_GRAVITY}),
                            found=f"|g| = {abs(gravity):g}")
        return 0j
    return gravity
