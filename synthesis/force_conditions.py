"""Force limits as desirable conditions of the synthesis (block B2 → P2, ``docs/forces.md`` §9).

A problem table may hold a ``forces:`` table: the masses and loads of the links, the input
speed, and limits on the largest driving torque (of every crank), on the largest driving
force (of every linear input: a cylinder, a slider driven along its guide), on the largest
reaction in named pairs and on the largest couple in named prismatic pairs::

    forces:
      omega: 10                      # rad/s of the crank
      gravity: [0, -9.81]            # m/s², optional
      masses:
        2: {per_mm: 0.005, centre: middle, inertia: rod}          # follows the design
        3: {mass: 0.5, centre: {l: 60, beta: 0}, inertia: 6.0e-4} # fixed
      loads: [{link: 3, torque: -15}]
      limits: {driving_torque: 12, reactions: {"2-3": 400}, couples: {"6-7": 5}}  # N·m, N, N·m

The points of a design being synthesised are not sketch points: a centre of mass or the point
of a force is given in the link's own frame, as polar ``{l: mm, beta: degrees}`` (or as
``[x, y]`` mm in that frame), like the attachment points N and M of the identification
table. A mass may follow the design (:class:`MassRule`): ``per_mm`` (kg per mm of the
distance between the link's two hinges), ``centre: middle`` (the midpoint of the two hinges),
``inertia: rod`` (m·l²/12 about the centre); a link with one hinge (a slider, a block) has its
mass at that hinge unless a centre is given. The hinges of a link are its revolute pairs; a
link with more than two names the two meant with ``between: [A, B]``.

The penalty of a design (the designs of a batch at once, over the analysis grid)::

    P2_F = Σ_cranks max(0, max_φ |M_d| − [M_d]) / [M_d]
           + Σ_linear inputs max(0, max_φ |F_d| − [F_d]) / [F_d]
           + Σ_pairs max(0, max_φ |R| − [R]) / [R]
           + Σ_prismatic pairs max(0, max_φ |M| − [M]) / [M]

with |R| = √(x² + y²) for a revolute pair and |normal| for a prismatic one, and M the couple
of a prismatic pair (its ``moment`` about the slider point); a position where the forces are
not solved counts 1 for each limit. P2_F is 0 iff every limit holds at every grid position;
it joins P2 (``criteria.desirable_penalty``) for the designs with P1 = 0 only.

Examples
--------
>>> import numpy as np
>>> excess(np.array([[3.0, -5.0], [1.0, np.nan]]), 4.0).tolist()
[0.25, 1.0]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from assur.forces.solver import MM, kinetostatics
from assur.forces.table import (
    REACH,
    Reach,
    inertia_problem,
    link_key_problem,
    mass_problem,
    read_sections,
)
from assur.io.reader import MISSING, Node, describe, is_number, normalise_id, positive
from assur.kinematics.analysis import Motion, analyse, values
from assur.kinematics.model import KinematicModel
from assur.model import ForceData, LinkId, Mass, PairId
from assur.typing import BoolArray, ComplexArray, FloatArray

__all__ = ["LINEAR_DRIVES", "ForceConditions", "MassRule", "excess", "force_penalties",
           "read_force_conditions"]


_KEYS = ("omega", "gravity", "masses", "loads", "limits")
_LIMITS = ("driving_torque", "driving_force", "reactions", "couples")
#: Drives whose one input is linear (mm): an actuator between two links, a slider on a frame
#: guide.  A problem puts such a mechanism on the cycle of its input's harmonic law
#: (:func:`assur.cycle_model`), its stroke limits ``s_min``, ``s_max`` then parameters.
LINEAR_DRIVES = ("actuator", "slider")
#: The limit of ``limits:`` that bounds each kind of driving effort of the force analysis.
_EFFORT_LIMITS = {"driving_torque": "driving_torque", "driving_force": "driving_force"}
_MASS = ("mass", "per_mm", "centre", "inertia", "between")

#: ``centre:`` and ``inertia:`` words that make a mass follow the design.
MIDDLE, ROD = "middle", "rod"


@dataclass(frozen=True)
class MassRule:
    """One row of a problem's ``masses:`` table: the inertia data of a link for every design.

    Attributes
    ----------
    link : link id
    mass : float
        kg, or kg per mm of the hinge distance when ``per_mm``.
    per_mm : bool
        The mass is ``mass`` × the distance between the two ``hinges``.
    centre : complex or None
        Centre of mass in the link's frame, mm; None: the middle of the ``hinges`` (of one
        hinge: the hinge itself), or no centre when the mass is 0 and there are no hinges.
    inertia : float or None
        kg·m² about the centre; None: a slender rod, m·l²/12 with l the hinge distance.
    hinges : tuple of pair ids
        The revolute pairs the rule measures (none for a fixed mass, one for the mass at a
        slider's or block's hinge, two for a length).

    Examples
    --------
    >>> MassRule(9, 0.5, False, 1 + 2j, 0.0, ()).follows
    False
    """

    link: LinkId
    mass: float
    per_mm: bool
    centre: complex | None
    inertia: float | None
    hinges: tuple[PairId, ...]

    @property
    def fixed(self) -> Mass:
        """The mass of a rule that does not follow the design."""
        return Mass(self.mass, self.centre, 0.0 if self.inertia is None else self.inertia)

    @property
    def follows(self) -> bool:
        """Whether the mass data depend on the design (through the hinges)."""
        return bool(self.hinges)

    def of(self, motion: Motion) -> Mass:
        """The link's :class:`~assur.model.Mass` for the designs of a motion.

        Parameters
        ----------
        motion : Motion
            A batch of designs (a crank input); the hinges are measured in the link's frame
            (``Motion.frames``) at each design's first assembled position (a rigid link
            keeps them there).

        Returns
        -------
        Mass
            Arrays shaped ``(D, 1)`` (or ``(1,)`` for one design) when the rule follows the
            design, else numbers.
        """
        if not self.follows:
            return self.fixed
        points = [_in_frame(motion, self.link, pair) for pair in self.hinges]
        length = np.abs(points[-1] - points[0])
        mass = self.mass * length if self.per_mm else np.full(length.shape, self.mass)
        centre = np.asarray(sum(points) / len(points) if self.centre is None
                            else np.full(length.shape, self.centre))
        inertia = (mass * (length * MM) ** 2 / 12.0 if self.inertia is None
                   else np.full(length.shape, self.inertia))
        return Mass(mass, centre, inertia)


@dataclass(frozen=True)
class ForceConditions:
    """The ``forces:`` table of a problem.

    Attributes
    ----------
    data : ForceData
        Loads, gravity and the fixed masses, points in the links' own frames (``local``).
    omega : float
        Crank speed, rad/s (0: static).
    driving_torque : float or None
        [M_d], N·m, of every crank.
    reactions : mapping
        Pair id → [R], N.
    couples : mapping
        Prismatic pair id → [M], N·m: a limit on the couple of the pair.
    follow : tuple of MassRule
        The masses that follow the design.
    driving_force : float or None
        [F_d], N, of every linear input (a cylinder, a slider driven along its guide).
    """

    data: ForceData
    omega: float
    driving_torque: float | None
    reactions: Mapping[PairId, float]
    couples: Mapping[PairId, float] = field(default_factory=dict)
    follow: tuple[MassRule, ...] = ()
    driving_force: float | None = None

    def effort_limit(self, kind: str) -> float | None:
        """The limit of a driving effort of the kind the force analysis names it
        (``'driving_torque'``, N·m, or ``'driving_force'``, N), None when not limited."""
        limit: float | None = getattr(self, _EFFORT_LIMITS[kind])
        return limit

    def data_of(self, motion: Motion) -> ForceData:
        """The masses and loads of the designs of a motion (the rules resolved).

        Examples
        --------
        >>> from synthesis import load_problem
        >>> problem = load_problem("input_tables/problems/class1_fourbar_inertia_limit.yaml")
        >>> model = problem.model
        >>> motion = analyse(model, np.zeros(1), analogs=True)
        >>> data = problem.forces.data_of(motion)
        >>> round(float(data.masses[2].mass[0]), 9)     # 0.02 kg/mm × l_i = 110 mm
        2.2
        """
        if not self.follow:
            return self.data
        masses = {**self.data.masses, **{rule.link: rule.of(motion) for rule in self.follow}}
        return replace(self.data, masses=masses)


def read_force_conditions(top: Node, model: KinematicModel | None) -> ForceConditions | None:
    """The ``forces:`` table of a problem file, or None when there is none.

    Parameters
    ----------
    top : Node
        The top of the problem table; problems are recorded with its reader.
    model : KinematicModel or None
        The initial design (its moving links and pairs); None when the mechanism could not
        be built (then the table is not read: the mechanism's problems come first).

    Returns
    -------
    ForceConditions or None
        None also when a problem was recorded.

    Examples
    --------
    >>> from synthesis import load_problem
    >>> problem = load_problem("input_tables/problems/class1_fourbar_torque_limit.yaml")
    >>> problem.forces.driving_torque, problem.forces.omega
    (8.0, 10.0)
    """
    node = top.child("forces", allowed=_KEYS, required=False)
    if node is None or model is None:
        return None
    reader = node.reader
    before = len(reader.issues)
    omega = node.get("omega", kind="number", check=positive)
    reach = _reach(model)
    rules = _mass_rules(node, model, reach)
    local = Node(reader, node.location, _localised(node.mapping), None)
    data = read_sections(local, tuple(model.links), model.drive in LINEAR_DRIVES, reach)
    if not (node.given("masses") or node.given("loads")):
        reader.problem(node.location, "force.condition.no_loads")
    limits = node.child("limits", allowed=_LIMITS)
    torque, force, reactions, couples = (_limits(limits, model) if limits is not None
                                         else (None, None, {}, {}))
    if limits is not None and not any(limits.has(key) for key in _LIMITS):
        reader.problem(limits.location, "force.condition.no_limits")
    if len(reader.issues) > before or data is None or omega is MISSING:
        return None
    fixed = {rule.link: rule.fixed for rule in rules if not rule.follows}
    return ForceConditions(replace(data, masses=fixed, local=True), float(omega), torque,
                           reactions, couples, tuple(rule for rule in rules if rule.follows),
                           force)


def _reach(model: KinematicModel) -> Reach | None:
    """Where a point in a link's frame may lie: :data:`~assur.forces.table.REACH` times the
    longest link length of the initial design around the link's origin."""
    lengths = [abs(value) for name, value in model.params.items()
               if name.rpartition(".")[2].startswith("l_")]
    size = max(lengths, default=0.0)
    return Reach.around((0j, complex(size, size))) if size > 0 else None


def _localised(mapping: Mapping[str, Any]) -> dict[str, Any]:
    """The table with every ``{l, beta}`` point of a load written as [x, y] in the link's
    frame, and the masses (read by :func:`_mass_rules`) left out."""
    out = dict(mapping)
    if "masses" in out:
        out["masses"] = {}
    loads = out.get("loads")
    if isinstance(loads, list):
        out["loads"] = [_with_point(row) for row in loads]
    return out


def _with_point(row: Any) -> Any:
    if not isinstance(row, dict):
        return row
    z = _polar(row.get("point"))
    return row if z is None else {**row, "point": [z.real, z.imag]}


def _polar(value: Any) -> complex | None:
    """A point ``{l: mm, beta: degrees}`` as x + i·y, or None when it is not one."""
    if (isinstance(value, dict) and set(value) == {"l", "beta"}
            and all(is_number(v) for v in value.values())):
        return complex(value["l"] * complex(math.cos(math.radians(value["beta"])),
                                            math.sin(math.radians(value["beta"]))))
    return None


def _point(value: Any) -> complex | None:
    """``{l, beta}`` or ``[x, y]`` in the link's frame, mm; None when it is neither."""
    if isinstance(value, list) and len(value) == 2 and all(is_number(v) for v in value):
        return complex(value[0], value[1])
    return _polar(value)


def _hinges(model: KinematicModel, link: LinkId) -> list[PairId]:
    """The revolute pairs of a link, in table order."""
    return [pair for pair, (kind, links, _) in model.pair_links.items()
            if kind == "R" and link in links]


def _mass_rules(node: Node, model: KinematicModel, reach: Reach | None) -> list[MassRule]:
    """Every row of ``masses:``, each problem recorded."""
    section = node.child("masses", required=False)
    if section is None:
        return []
    rules = []
    for raw, row in section.mapping.items():
        where = f"{section.location}.{raw}"
        link = normalise_id(raw)
        if link_key_problem(section, where, raw):
            continue
        if link not in model.links:
            section.reader.problem(where, "force.link.not_moving", found=describe(raw),
                                   known=", ".join(map(str, model.links)))
        if not isinstance(row, dict):
            section.reader.problem(where, "force.mass.expected", found=describe(row))
            continue
        rule = _mass_rule(Node(section.reader, where, row, _MASS), link,
                          _hinges(model, link) if link in model.links else None, reach)
        if rule is not None:
            rules.append(rule)
    return rules


def _mass_rule(node: Node, link: LinkId, hinges: list[PairId] | None,
               reach: Reach | None) -> MassRule | None:
    """One row of ``masses:``; None when it has a problem (recorded) or the link is wrong."""
    reader = node.reader
    before = len(reader.issues)
    if node.given("mass") == node.given("per_mm"):
        reader.problem(node.location, "force.condition.mass_or_per_mm")
    per_mm = node.given("per_mm")
    mass = node.get("per_mm" if per_mm else "mass", kind="number", required=False,
                    default=0.0, check=mass_problem)
    centre, inertia = _centre(node, reach), _inertia(node)
    words = [word for word, used in (("per_mm", per_mm), (MIDDLE, centre == MIDDLE),
                                     (ROD, inertia == ROD)) if used]
    named = _between(node, link, hinges) if node.has("between") else None
    if hinges is None or mass is MISSING or len(reader.issues) > before:
        return None
    at_hinge = centre is None and len(hinges) == 1    # a slider or a block
    if named is None and words:
        named = _two_hinges(node, link, hinges, words[0])
    elif named is None and at_hinge:
        named = tuple(hinges)
    if centre is None and not at_hinge and (per_mm or mass > 0) and not node.given("centre"):
        reader.problem(node.location, "force.condition.centre_missing", link=str(link),
                       known=", ".join(map(str, hinges)) or "—")
    if len(reader.issues) > before:
        return None
    return MassRule(link, float(mass), per_mm,
                    centre if isinstance(centre, complex) else None,
                    None if inertia == ROD else float(inertia), named or ())


def _centre(node: Node, reach: Reach | None) -> complex | str | None:
    """``centre:``: a point in the link's frame within ``reach``, ``middle``, or None when
    absent."""
    if not node.has("centre"):
        return None
    value = node.mapping["centre"]
    point = _point(value)
    if point is not None and reach is not None and not reach.holds(point):
        node.reader.problem(f"{node.location} 'centre'", "force.point.outside",
                            found=f"[{point.real:g}, {point.imag:g}]", reach=REACH,
                            size=reach.size, box=reach.box())
        return None
    if point is not None or value == MIDDLE:
        return point if point is not None else MIDDLE
    node.reader.problem(f"{node.location} 'centre'", "force.condition.centre",
                        found=describe(value))
    return None


def _inertia(node: Node) -> float | str:
    """``inertia:``: kg·m² (≥ 0, default 0) or ``rod``."""
    value = node.mapping.get("inertia", 0.0)
    if value == ROD or (is_number(value) and inertia_problem(value) is None):
        return value if value == ROD else float(value)
    node.reader.problem(f"{node.location} 'inertia'", "force.condition.inertia",
                        found=describe(value))
    return 0.0


def _between(node: Node, link: LinkId, hinges: list[PairId] | None
             ) -> tuple[PairId, ...] | None:
    """``between: [A, B]``: two different hinges of the link."""
    value = node.mapping["between"]
    named = ([normalise_id(v) for v in value] if isinstance(value, list) else [])
    if hinges is not None and not (len(named) == 2 and named[0] != named[1]
                                   and all(pair in hinges for pair in named)):
        node.reader.problem(f"{node.location} 'between'", "force.condition.between",
                            link=str(link), known=", ".join(map(str, hinges)) or "—",
                            found=(f"[{', '.join(map(str, value))}]"
                                   if isinstance(value, list) else describe(value)))
        return None
    return tuple(named)


def _two_hinges(node: Node, link: LinkId, hinges: list[PairId], word: str
                ) -> tuple[PairId, ...] | None:
    """The two hinges a length needs; a problem when the link has not exactly two."""
    if len(hinges) == 2:
        return tuple(hinges)
    code = ("force.condition.hinges_ambiguous" if len(hinges) > 2
            else "force.condition.no_length")
    node.reader.problem(node.location, code, link=str(link), word=word,
                        known=", ".join(map(str, hinges)) or "—")
    return None


def _in_frame(motion: Motion, link: LinkId, pair: PairId) -> ComplexArray:
    """A hinge of a link in the link's frame (mm), per design: at each design's first
    assembled position, shape ``(D, 1)`` (``(1,)`` for one design)."""
    origin, angle = motion.frames[link]
    exists, joint, origin_v, angle_v = np.broadcast_arrays(
        np.asarray(motion.exists), values(motion.joints[pair]), values(origin), values(angle))
    first = np.argmax(exists, axis=-1)[..., None]

    def at(x: np.ndarray) -> np.ndarray:
        return np.take_along_axis(x, first, axis=-1)

    return np.asarray((at(joint) - at(origin_v)) * np.exp(-1j * at(angle_v)))


def _limits(node: Node, model: KinematicModel
            ) -> tuple[float | None, float | None, dict[PairId, float], dict[PairId, float]]:
    torque = node.get("driving_torque", kind="number", required=False, default=None,
                      check=positive)
    force = node.get("driving_force", kind="number", required=False, default=None,
                     check=positive)
    kinds = _effort_kinds(model)
    for key, value in (("driving_torque", torque), ("driving_force", force)):
        if value not in (None, MISSING) and key not in kinds:
            node.reader.problem(f"{node.location} {key!r}", "force.condition.no_such_input",
                                limit=key, inputs=", ".join(sorted(kinds)))
    reactions = _pair_limits(node, "reactions", tuple(model.pair_links),
                             "force.condition.unknown_pair", "force.condition.limit")
    prismatic = tuple(pair for pair, (kind, _, _) in model.pair_links.items() if kind == "P")
    couples = _pair_limits(node, "couples", prismatic, "force.condition.not_prismatic",
                           "force.condition.couple_limit")
    return (None if torque in (MISSING, None) else float(torque),
            None if force in (MISSING, None) else float(force), reactions, couples)


def _effort_kinds(model: KinematicModel) -> set[str]:
    """The kinds of the driving efforts of a model's inputs: ``driving_torque`` for a
    crank, ``driving_force`` for a linear input (an actuator, a slider on its guide)."""
    if model.drive in LINEAR_DRIVES:
        return {"driving_force"}
    if model.drive == "crank":
        return {"driving_torque"}
    return {"driving_force" if law.linear else "driving_torque" for law in model.laws.values()}


def _pair_limits(node: Node, key: str, pairs: tuple[PairId, ...], unknown: str,
                 wrong: str) -> dict[PairId, float]:
    """A table ``{pair: limit}`` of ``limits:`` whose pairs must be among ``pairs``."""
    out: dict[PairId, float] = {}
    table = node.child(key, required=False)
    if table is None:
        return out
    for raw, value in table.mapping.items():
        pair = normalise_id(raw)
        where = f"{table.location} {raw!r}"
        if pair not in pairs:
            node.reader.problem(where, unknown, found=describe(raw),
                                known=", ".join(map(str, pairs)) or "—")
        elif not is_number(value) or not value > 0:
            node.reader.problem(where, wrong, found=describe(value))
        else:
            out[pair] = float(value)
    return out


def force_penalties(conditions: ForceConditions | None,
                    model_of: Callable[[FloatArray], KinematicModel], x: FloatArray,
                    feasible: BoolArray, grid: FloatArray) -> FloatArray:
    """P2_F of a batch of designs, shape (D,); 0 for the designs with P1 > 0.

    Parameters
    ----------
    conditions : ForceConditions or None
        The problem's force limits (None: no penalty).
    model_of : callable
        Designs (D', q) → their kinematic model (``Evaluator.model``).
    x : ndarray, shape (D, q)
        The designs.
    feasible : ndarray of bool, shape (D,)
        P1 = 0: only these are analysed.
    grid : ndarray, shape (N,)
        Crank rotations of the analysis grid, radians.

    Returns
    -------
    ndarray, shape (D,)
    """
    out = np.zeros(np.shape(x)[0])
    if conditions is None or not feasible.any():
        return out
    motion = analyse(model_of(x[feasible]), grid, analogs=True)
    forces = kinetostatics(motion, conditions.data_of(motion), conditions.omega)
    shape = (int(feasible.sum()), grid.size)
    total = np.zeros(shape[0])
    for label, effort in forces.drivings.items():
        limit = conditions.effort_limit(forces.drive_kinds[label])
        if limit is not None:
            total += excess(np.broadcast_to(effort, shape), limit)
    for pair, limit in conditions.reactions.items():
        r = forces.reactions[pair]
        size = np.abs(r.normal) if r.normal is not None else np.hypot(r.x, r.y)
        total += excess(np.broadcast_to(size, shape), limit)
    for pair, limit in conditions.couples.items():
        couple = forces.reactions[pair].moment
        assert couple is not None, "a prismatic pair"
        total += excess(np.broadcast_to(couple, shape), limit)
    out[feasible] = total
    return out


def excess(values: FloatArray, limit: float) -> FloatArray:
    """``max(0, max_φ |v| − limit) / limit`` per design (rows), plus 1 where a position
    is not solved (NaN).

    Parameters
    ----------
    values : ndarray, shape (D, N)
    limit : float
        > 0.

    Returns
    -------
    ndarray, shape (D,)
    """
    values = np.asarray(values, dtype=float)
    solved = np.isfinite(values)
    peak = np.max(np.where(solved, np.abs(values), 0.0), axis=-1)
    penalty: FloatArray = np.maximum(0.0, peak - limit) / limit + (~solved.all(axis=-1))
    return penalty
