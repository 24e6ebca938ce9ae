"""Kinetostatics by Assur groups: joint reactions and the driving torque over the cycle.

:func:`kinetostatics` takes a :class:`~assur.kinematics.analysis.Motion` computed with
analogs, the masses and loads (:class:`~assur.model.ForceData`) and the input speed ω,
and solves the groups from the last attached back to the input link (``docs/forces.md``):
d'Alembert inertia forces and torques from the exact second analogs, the equilibrium of each
group's kind (:data:`EQUILIBRIA`), then the driving torque on the crank.
Beside it, the driving torque from the power balance (Zhukovsky's lever) and the
Newton–Euler residual of every link computed from the reported reactions.

Work is in SI: positions and analogs in m, forces in N, moments in N·m. Arrays are shaped
like the kinematics, ``(N,)`` positions or ``(D, N)`` designs × positions; a position where a
group does not assemble or a reaction is indeterminate is NaN with a reason, never an error.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, TypeVar

import numpy as np

from assur.forces.checks import LinkResidual, Power, lever_torque, link_residuals
from assur.forces.groups import (
    ForceReason,
    Loads,
    Solved,
    Transfer,
    cross,
    dot,
    equilibrium_prp,
    equilibrium_rpp,
    equilibrium_rpr,
    equilibrium_rrp,
    equilibrium_rrr,
)
from assur.forces.linear import equilibrium_linear
from assur.kinds import KindCode
from assur.kinematics import jets as J
from assur.kinematics.analysis import Motion, analyse, held, sketch_input, values
from assur.kinematics.jets import Jet
from assur.kinematics.model import GroupModel, KinematicModel
from assur.model import ForceData, LinkId, PairId, Tabulated
from assur.text import Message
from assur.typing import Value

__all__ = ["EQUILIBRIA", "Equilibrium", "ForceAnalysis", "Reaction", "kinetostatics"]

#: A load's constant value: a force (complex, N) or a torque (float, N·m).
_Number = TypeVar("_Number", complex, float)

#: The kinetostatics of a group: the reactions in its pairs from the known loads of its links.
Equilibrium = Callable[[GroupModel, Loads], Solved]

#: The equilibrium of each kind of group, by kind code: the closed form of each dyad kind
#: (:mod:`assur.forces.groups`), one linear solve per position for the triad and the class IV
#: group (:mod:`assur.forces.linear`). The input group has none: the drive balances it last.
EQUILIBRIA: Mapping[KindCode, Equilibrium] = {
    "L1": equilibrium_rrr,
    "L2": equilibrium_rrp,
    "L3": equilibrium_rpr,
    "L4": equilibrium_prp,
    "L5": equilibrium_rpp,
    "III": equilibrium_linear,
    "IV": equilibrium_linear,
}

#: Millimetres to metres.
MM = 1e-3

#: A normalised determinant, or a group's existence margin, at or below this is the singular
#: position itself (null): the margin of a toggle is the square of its determinant, and the
#: kinematics holds it only to round-off.
SINGULAR = 1e-12

#: Below this the reactions are flagged as ill-conditioned (they grow like 1/determinant).
NEAR = 1e-6

#: Catalogue code of each reason.
REASON_CODES = {
    ForceReason.NOT_ASSEMBLED: "force.reason.not_assembled",
    ForceReason.TOGGLE: "force.reason.toggle",
    ForceReason.PARALLEL_GUIDES: "force.reason.parallel_guides",
    ForceReason.INDETERMINATE: "force.reason.indeterminate",
}


@dataclass(frozen=True, slots=True)
class Reaction:
    """The reaction in one kinematic pair over the positions.

    Attributes
    ----------
    pair : pair id
    links : (a, b)
        The pair's links as listed; the reaction is the force of a on b.
    x, y : ndarray
        Its components in global axes, N.
    normal : ndarray or None
        Prismatic pairs: its component along n = i·u (u the current guide direction), N.
    moment : ndarray or None
        Prismatic pairs: the moment about the slider point K of everything a exerts on b, N·m.
    point : ndarray
        The pair's point, m (complex): the hinge, or K.
    """

    pair: PairId
    links: tuple[LinkId, LinkId]
    x: np.ndarray
    y: np.ndarray
    normal: np.ndarray | None
    moment: np.ndarray | None
    point: np.ndarray

    @property
    def acting_point(self) -> np.ndarray | None:
        """Prismatic pairs: where the normal force acts on the guide line, K + (M/N)·u (m);
        NaN where N is 0. None for a revolute pair.

        Examples
        --------
        >>> r = Reaction("P", (0, 1), np.array([0.0]), np.array([2.0]), np.array([2.0]),
        ...              np.array([0.5]), np.array([0j]))
        >>> r.acting_point.tolist()
        [(0.25+0j)]
        """
        if self.normal is None or self.moment is None:
            return None
        with np.errstate(all="ignore"):
            along = -1j * (self.x + 1j * self.y) / self.normal
            return np.asarray(self.point + self.moment / self.normal * along)


@dataclass(frozen=True)
class ForceAnalysis:
    """The result of :func:`kinetostatics`, aligned with the kinematics' positions.

    Attributes
    ----------
    omega : float
        Input speed (rad/s, or mm/s for an actuator).
    gravity : complex
        m/s².
    drive : str
        ``'driving_torque'`` (N·m on the crank, counter-clockwise positive), or
        ``'driving_force'`` (N, a slider along its drawn guide direction, an actuator along
        its length) — of the first input.
    driving : ndarray
        The driving torque from the group-by-group solution.
    driving_lever : ndarray
        The same from the power balance.
    power_balance : ndarray
        ``driving − driving_lever``.
    power_scale : ndarray
        Σ |power terms| / |θ_in′|: the power balance is round-off when small beside it.
    reactions : dict
        Pair → :class:`Reaction`.
    reason : ndarray, int8
        :class:`~assur.forces.groups.ForceReason` per position (0 where solved).
    singular : ndarray, object
        The label of the singular group, None elsewhere.
    ill_conditioned : ndarray, bool
        A group's normalised determinant is below 1e-6 (reactions grow like its inverse).
    known, origins, drive_loads
        What the residuals are computed from: every moving link's known loads (resultant
        force, N, and moment about its origin, N·m), its origin (m), and each drive as a
        load (the driving torque on a crank, a slider's driving force along its guide, or an
        actuator's force on its two members).
    drivings : dict
        Label of the group holding each input → its driving effort (N·m on a crank, N on a
        slider or an actuator), in the order of the inputs; ``driving`` is the first. With
        several inputs ``driving_lever`` is the first input's effort from the power balance
        of every load and the other inputs' efforts.
    drive_kinds : dict
        The same labels → ``'driving_torque'`` or ``'driving_force'``.
    """

    omega: float
    gravity: complex
    drive: str
    driving: np.ndarray
    driving_lever: np.ndarray
    power_balance: np.ndarray
    power_scale: np.ndarray
    reactions: dict[PairId, Reaction]
    reason: np.ndarray
    singular: np.ndarray
    ill_conditioned: np.ndarray
    known: dict[LinkId, tuple[np.ndarray, np.ndarray]] = field(repr=False)
    origins: dict[LinkId, np.ndarray] = field(repr=False)
    drive_loads: tuple[DriveLoad, ...] = field(repr=False)
    drivings: dict[str, np.ndarray] = field(default_factory=dict)
    drive_kinds: dict[str, str] = field(default_factory=dict)

    def __repr__(self) -> str:
        solved = int(np.count_nonzero(self.reason == 0))
        return (f"ForceAnalysis({self.drive} at {self.reason.size} positions, "
                f"solved at {solved}, omega={self.omega:g}, "
                f"gravity=({self.gravity.real:g}, {self.gravity.imag:g})\n"
                f"  reactions in pairs: {', '.join(map(str, self.reactions))})")

    def to_dict(self) -> dict[str, Any]:
        """The ``forces`` object of ``assur analyze --json``.

        Returns
        -------
        dict
            ``omega``, ``gravity`` ([gx, gy] m/s²), the drive (``driving_torque`` N·m, or
            ``driving_force`` N for an actuator) and the same from the lever
            (``driving_torque_lever``), ``power_balance`` (their difference), ``reactions``
            (pair → ``links``, ``x``, ``y``; prismatic pairs also ``normal`` and ``moment``),
            ``residual`` (the largest relative Newton–Euler residual of the links per
            position: ``force``, ``moment``), ``reason`` (null where solved, else
            ``not_assembled``, ``toggle``, ``parallel_guides`` or ``indeterminate``) and
            ``singular`` (the group).

        Examples
        --------
        >>> from pathlib import Path
        >>> import assur
        >>> table = Path(assur.__file__).parents[1] / "input_tables" / "slider_crank_press.yaml"
        >>> record = assur.analyse(table, points=36, forces=True, omega=10.0).forces.to_dict()
        >>> sorted(record["reactions"]["3-0"]), record["reactions"]["3-0"]["links"]
        (['links', 'moment', 'normal', 'x', 'y'], [3, 0])
        """
        from assur.records import floats

        forces = self
        drive = forces.drive
        reactions: dict[str, Any] = {}
        for pair, reaction in forces.reactions.items():
            entry: dict[str, Any] = {"links": list(reaction.links), "x": floats(reaction.x),
                                     "y": floats(reaction.y)}
            if reaction.normal is not None and reaction.moment is not None:
                entry["normal"] = floats(reaction.normal)
                entry["moment"] = floats(reaction.moment)
            reactions[str(pair)] = entry
        with np.errstate(all="ignore"):
            residuals = list(forces.residuals.values())
            worst_force = np.max([r.force for r in residuals], axis=0)
            worst_moment = np.max([r.moment for r in residuals], axis=0)
        inputs = {label: {"kind": self.drive_kinds[label], "values": floats(values)}
                  for label, values in self.drivings.items()}
        return {
            "inputs": inputs,
            "omega": forces.omega,
            "gravity": [forces.gravity.real, forces.gravity.imag],
            drive: floats(forces.driving),
            f"{drive}_lever": floats(forces.driving_lever),
            "power_balance": floats(forces.power_balance),
            "reactions": reactions,
            "residual": {"force": floats(worst_force), "moment": floats(worst_moment)},
            "reason": [None if r == 0 else ForceReason(int(r)).name.lower()
                       for r in forces.reason.ravel()],
            "singular": list(forces.singular.ravel()),
        }

    @cached_property
    def residuals(self) -> dict[LinkId, LinkResidual]:
        """Moving link → its Newton–Euler residual (:class:`~assur.forces.checks.LinkResidual`)
        from the reported reactions and driving torque (computed when first asked for; see
        the example of :func:`kinetostatics`).
        """
        with np.errstate(all="ignore"):
            return link_residuals(
                self.known, self.origins,
                [*((r.links, r.x + 1j * r.y, r.point, r.moment)
                   for r in self.reactions.values()), *self.drive_loads])

    def message(self, index: int | tuple[int, ...]) -> Message | None:
        """Why the forces at one position are not given (None where they are).

        Examples
        --------
        >>> from pathlib import Path
        >>> from assur.kinematics.build import load_with_forces
        >>> from assur.kinematics.analysis import analyse
        >>> table = Path(__file__).parents[2] / "input_tables" / "four_bar_gravity.yaml"
        >>> model, data = load_with_forces(table)
        >>> result = kinetostatics(analyse(model, points=4, analogs=True), data, 10.0)
        >>> result.message(0) is None
        True
        """
        reason = ForceReason(int(self.reason[index]))
        if reason == ForceReason.SOLVED:
            return None
        return Message(REASON_CODES[reason], {"group": self.singular[index] or ""})


def kinetostatics(motion: Motion, data: ForceData, omega: float = 0.0) -> ForceAnalysis:
    """Joint reactions and the driving torque (or force) at every analysed position.

    Parameters
    ----------
    motion : Motion
        From :func:`~assur.kinematics.analysis.analyse` with ``analogs=True``.
    data : ForceData
        Masses, loads and gravity (table units: sketch points in mm).
    omega : float
        Constant input speed (rad/s; mm/s for an actuator); 0 gives the static analysis.

    Returns
    -------
    ForceAnalysis

    Raises
    ------
    ValueError
        If the motion carries no analogs, or a load names a link the model does not have.

    Notes
    -----
    Groups are solved in reverse layering order; each solved group's reactions on links of
    earlier groups join those links' known loads. The crank's equilibrium then gives the
    driving torque ``M_d = −M_1(O_1)`` and the frame's reaction at O_1; an actuator's force
    comes from the equilibrium of the member hinged at its group's internal joint.

    Examples
    --------
    A four-bar with only a torque on the rocker, statically:

    >>> from pathlib import Path
    >>> import numpy as np, assur
    >>> from assur.forces import ForceData, Load
    >>> TABLES = Path(assur.__file__).parents[1] / "input_tables"
    >>> model = assur.load_model(TABLES / "four_bar.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, np.radians([0.0, 90.0]), analogs=True)
    >>> result = kinetostatics(motion, ForceData(loads=(Load(3, torque=-15.0),)))
    >>> bool(np.all(np.abs(result.power_balance) < 1e-12))
    True
    >>> bool(max(r.moment.max() for r in result.residuals.values()) < 1e-12)
    True
    """
    if not motion.analogs:
        raise ValueError("the force analysis needs the motion with analogs: "
                         "analyse(model, q, analogs=True)")
    unknown = [link for link in data.links if link not in motion.frames]
    if unknown:
        raise ValueError(f"links {unknown} carry masses or loads but are not moving links of "
                         f"the model ({', '.join(map(str, motion.frames))})")
    model = motion.model
    shape = np.shape(motion.exists)
    with np.errstate(all="ignore"):
        frames = _frames(motion)
        bodies = _Bodies(motion, frames, shape)
        power = _known_loads(bodies, motion, frames, data, omega)
        known = {link: (bodies.forces[link], bodies.moments[link]) for link in bodies.forces}
        solved, reason, singular, ill, actuator = _groups(bodies, motion)
        efforts = _efforts(bodies, motion, solved, actuator)
        blank = reason > ForceReason.NOT_ASSEMBLED
        drivings = {label: np.where(blank, np.nan, effort.driving)
                    for label, effort in efforts.items()}
        first, *others = efforts
        rate = efforts[first].rate
        others_power = sum((drivings[label] * efforts[label].rate for label in others),
                           np.zeros(shape))
        lever, scale = lever_torque(Power(power.total + others_power, power.scale), rate)
    driving = drivings[first]
    reactions = {pair: solved[pair] for pair in model.pair_links if pair in solved}
    reason = np.where(~np.asarray(motion.exists) & (reason == 0), ForceReason.NOT_ASSEMBLED,
                      reason).astype(np.int8)
    return ForceAnalysis(omega=float(omega), gravity=complex(data.gravity),
                         drive=efforts[first].kind, driving=driving, driving_lever=lever,
                         power_balance=driving - lever, power_scale=scale, reactions=reactions,
                         reason=reason, singular=singular, ill_conditioned=ill, known=known,
                         origins=bodies.origins,
                         drive_loads=tuple(effort.load for effort in efforts.values()),
                         drivings=drivings,
                         drive_kinds={label: e.kind for label, e in efforts.items()})


@dataclass(frozen=True)
class _Effort:
    """One input's driving effort: its kind (``'driving_torque'``, N·m, or
    ``'driving_force'``, N), its values, its load for the residuals, and the rate of its
    coordinate per unit input speed (rad or m per unit of the input coordinate)."""

    kind: str
    driving: np.ndarray
    load: DriveLoad
    rate: float | np.ndarray


def _efforts(bodies: _Bodies, motion: Motion, reactions: dict[PairId, Reaction],
             actuator: tuple[np.ndarray, DriveLoad] | None) -> dict[str, _Effort]:
    """The driving effort of every input, in the order of the mechanism's inputs: the
    torque on a crank, the force on a slider along its frame guide, an actuator's force."""
    model = motion.model
    out: dict[str, _Effort] = {}
    for group in model.groups:
        law = model.laws.get(group.label)
        rate: float | np.ndarray = float(model.direction) if law is None else \
            np.broadcast_to(np.asarray(_jet(law.coordinate(Jet(motion.q, 1.0, 0.0),
                                                           model.value)).d1), bodies.shape)
        if group.group_kind.is_input and group.guide_i is not None:
            driving, load = _slide(bodies, motion, group, reactions)
            out[group.label] = _Effort("driving_force", driving, load, MM * rate)
        elif group.group_kind.is_input:
            driving, load = _crank(bodies, motion, group, reactions)
            out[group.label] = _Effort("driving_torque", driving, load, rate)
        elif group.driven is not None and actuator is not None:
            out[group.label] = _Effort("driving_force", *actuator,
                                       MM * (1.0 if law is None else rate))
    return out


def _slide(bodies: _Bodies, motion: Motion, group: GroupModel,
           reactions: dict[PairId, Reaction]) -> tuple[np.ndarray, DriveLoad]:
    """An input slider on a frame guide: the driving force along the guide (N, positive
    along the drawn direction) and the guide's reaction (normal force and couple)."""
    model = motion.model
    pair = group.pairs["P_i"]
    point = bodies.joint(pair)
    n = bodies.normal(pair)
    u = -1j * n
    force = bodies.force(group.i)
    driving = np.asarray(-dot(force, u))
    normal = np.asarray(-dot(force, n))
    couple = -bodies.moment(group.i, point)
    reactions[pair] = _oriented(motion, Transfer(pair, model.frame, group.i, normal * n, point,
                                                 normal, couple))
    return driving, ((model.frame, group.i), driving * u, point, None)


#: A load given with the reactions to the residual check: the two links (the load acts on
#: the second, its opposite on the first), force (N), point (m), couple (N·m) or None.
DriveLoad = tuple[tuple[LinkId, LinkId], np.ndarray, np.ndarray, "np.ndarray | None"]


def _crank(bodies: _Bodies, motion: Motion, crank: GroupModel,
           reactions: dict[PairId, Reaction]) -> tuple[np.ndarray, DriveLoad]:
    """An input crank L0: the frame's reaction at O_1 and the driving torque."""
    model = motion.model
    pivot = bodies.joint(crank.pairs["H_i"])
    driving = -bodies.moment(crank.i, pivot)
    reactions[crank.pairs["H_i"]] = _oriented(
        motion, Transfer(crank.pairs["H_i"], model.frame, crank.i, -bodies.force(crank.i),
                         pivot))
    return driving, ((model.frame, crank.i), np.zeros(bodies.shape, complex), pivot, driving)


def _frames(motion: Motion) -> dict[LinkId, tuple[Jet, Jet]]:
    """The frame (origin, angle) of every moving link; an actuator's member hinged at the
    composite's internal joint C slides along the other member, so its origin is C."""
    model = motion.model
    frames = {link: (_jet(origin), _jet(angle)) for link, (origin, angle) in motion.frames.items()
              if link != model.frame}
    group = _driven(model)
    if group is not None:
        from assur.kinematics.higher.kind import actuator_ends  # only for an actuator

        point = actuator_ends(group)[0]
        member = _member(model, group, point)
        frames[member] = (_jet(motion.joints[point]), frames[member][1])
    return frames


def _driven(model: KinematicModel) -> GroupModel | None:
    """The group holding a linear actuator (an RRR dyad, a triad, a class IV group), if the
    input is one."""
    return next((group for group in model.groups if group.driven is not None), None)


def _bar(group: GroupModel) -> LinkId:
    """The link of an actuator's group that stands for its composite (the bar it is)."""
    if group.layout is not None:
        return group.layout.links[group.layout.names.index(str(group.driven))]
    side = group.j if group.driven == "j" else group.i
    assert side is not None
    return side


class _Welded:
    """The loads of a higher group whose actuator's members count as its one bar link: the
    pairs on either member are seen on that link (:class:`~assur.forces.groups.Loads`)."""

    def __init__(self, bodies: _Bodies, group: GroupModel) -> None:
        self.bodies = bodies
        self.members = set(group.composite)
        self.bar = _bar(group)
        self.joint, self.normal = bodies.joint, bodies.normal
        self.force, self.moment = bodies.force, bodies.moment

    def pair(self, pair: PairId) -> tuple[str, tuple[LinkId, LinkId]]:
        kind, (first, second) = self.bodies.pair(pair)
        return kind, (self.bar if first in self.members else first,
                      self.bar if second in self.members else second)


def _member(model: KinematicModel, group: GroupModel, pair: PairId) -> LinkId:
    """The member of an actuator's composite link that a pair touches."""
    return next(link for link in model.pair_links[pair][1] if link in group.composite)


class _Bodies:
    """The known loads of every moving link, accumulated over the positions.

    Implements :class:`~assur.forces.groups.Loads` for the group equations.
    """

    def __init__(self, motion: Motion, frames: dict[LinkId, tuple[Jet, Jet]],
                 shape: tuple[int, ...]) -> None:
        self.motion = motion
        self.shape = shape
        moving = list(frames)
        self.origins = {link: np.broadcast_to(frames[link][0].v * MM, shape) for link in moving}
        self.forces: dict[LinkId, np.ndarray] = {link: np.zeros(shape, complex)
                                                 for link in moving}
        self.moments: dict[LinkId, np.ndarray] = {link: np.zeros(shape) for link in moving}
        self._points: dict[PairId, np.ndarray] = {}
        self._normals: dict[PairId, np.ndarray] = {}

    def joint(self, pair: PairId) -> np.ndarray:
        if pair not in self._points:
            slider = self.motion.sliders.get(pair)
            point = self.motion.joints[pair] if slider is None else slider.point
            self._points[pair] = values(point) * MM
        return self._points[pair]

    def normal(self, pair: PairId) -> np.ndarray:
        if pair not in self._normals:
            self._normals[pair] = 1j * _expi(values(self.motion.sliders[pair].angle))
        return self._normals[pair]

    def pair(self, pair: PairId) -> tuple[str, tuple[LinkId, LinkId]]:
        kind, links, _ = self.motion.model.pair_links[pair]
        return kind, links

    def force(self, link: LinkId) -> np.ndarray:
        return self.forces[link]

    def moment(self, link: LinkId, point: np.ndarray) -> np.ndarray:
        moment: np.ndarray = self.moments[link] - cross(point - self.origins[link],
                                                        self.forces[link])
        return moment

    def add(self, link: LinkId, force: np.ndarray, point: np.ndarray,
            couple: np.ndarray | None = None) -> None:
        """A force at a point of the link, and a couple."""
        self.load(link, force, point - self.origins[link], couple)

    def load(self, link: LinkId, force: np.ndarray, arm: np.ndarray,
             couple: np.ndarray | None = None) -> np.ndarray:
        """A force at the point ``origin + arm`` of the link, and a couple; returns the
        force's moment about the origin."""
        moment = cross(arm, force)
        self.forces[link] = self.forces[link] + force
        self.moments[link] = self.moments[link] + (moment if couple is None else
                                                   moment + couple)
        return moment

    def turn(self, link: LinkId, couple: float | np.ndarray) -> None:
        """A couple on the link."""
        self.moments[link] = self.moments[link] + couple


def _known_loads(bodies: _Bodies, motion: Motion, frames: dict[LinkId, tuple[Jet, Jet]],
                 data: ForceData, omega: float) -> Power:
    """Weights, inertia forces and torques, and the external loads of every link; their power
    per unit input speed (the power balance)."""
    model = motion.model
    sketch = None if data.local else _sketch_frames(motion, frames)
    rotors: dict[LinkId, np.ndarray] = {}
    w2 = omega * omega

    def carried(link: LinkId, x: complex | np.ndarray) -> np.ndarray:
        """A point fixed on the link, sketched at x (or at x in the link's frame; an array
        per design), mm: its arm from the link's origin, m."""
        if link not in rotors:
            rotors[link] = _expi(frames[link][1].v)
        local: complex | np.ndarray = x * MM
        if sketch is not None:
            origin0, angle0 = sketch[link]
            local = (x - origin0) * np.exp(-1j * angle0) * MM
        return np.asarray(local * rotors[link])

    def power(link: LinkId, force: np.ndarray, moment: np.ndarray) -> np.ndarray:
        """The power of a force per unit input speed, f·P′ with P′ = O′ + i·θ′·arm:
        f·O′ + θ′·(its moment about the origin)."""
        origin, angle = frames[link]
        return np.asarray(dot(force, origin.d1 * MM) + angle.d1 * moment)

    periodic = model.periodic
    terms: list[np.ndarray] = []
    for link, mass in data.masses.items():
        origin, angle = frames[link]
        spin = -mass.inertia * w2 * angle.d2
        if mass.centre is not None and np.any(np.asarray(mass.mass) > 0):
            arm = carried(link, mass.centre)
            acceleration = origin.d2 * MM + arm * (1j * angle.d2 - angle.d1 * angle.d1)
            force = data.weight(link) - mass.mass * w2 * acceleration
            terms.append(power(link, force, bodies.load(link, force, arm, spin)))
        else:
            bodies.turn(link, spin)
        terms.append(spin * angle.d1)
    for load in data.loads:
        if load.force is not None and load.point is not None:
            force = np.asarray(_value(load.force, motion.q, periodic))
            moment = bodies.load(load.link, force, carried(load.link, load.point))
            terms.append(power(load.link, force, moment))
        if load.torque is not None:
            torque = _value(load.torque, motion.q, periodic)
            bodies.turn(load.link, torque)
            terms.append(torque * frames[load.link][1].d1)
    zero = np.zeros(bodies.shape)
    return Power(sum(terms, zero), sum((np.abs(t) for t in terms), zero))


def _sketch_frames(motion: Motion, frames: dict[LinkId, tuple[Jet, Jet]]
                   ) -> dict[LinkId, tuple[np.ndarray, np.ndarray]]:
    """The frame (origin, mm; angle, rad) of every moving link at the sketched position: from
    the motion where it analyses that position (the crank grids start there), else from an
    analysis of that one position."""
    model = motion.model
    sketched = _sketched(model)
    q = np.asarray(motion.q)
    hit = np.flatnonzero(q == sketched[0]) if q.ndim == 1 else np.zeros(0, int)
    if hit.size == 0 or not np.all(np.take(np.asarray(motion.exists), hit[:1], axis=-1)):
        frames = _frames(analyse(held(model), np.zeros(1), analogs=True)
                         if model.drive == "laws" else analyse(model, sketched, analogs=True))
        return {link: (origin.v, angle.v) for link, (origin, angle) in frames.items()}
    shape = np.shape(motion.exists)

    def at(x: np.ndarray) -> np.ndarray:
        return np.broadcast_to(x, shape)[..., hit[0]:hit[0] + 1]

    return {link: (at(origin.v), at(angle.v)) for link, (origin, angle) in frames.items()}


def _expi(angle: np.ndarray) -> np.ndarray:
    """exp(i·angle), computed once when the angle is one value broadcast over the positions
    (a guide on the frame).

    Examples
    --------
    >>> _expi(np.broadcast_to(np.pi / 2, (3,))).round(12).tolist()
    [1j, 1j, 1j]
    """
    if angle.ndim and not any(angle.strides):
        return np.broadcast_to(np.asarray(J.expi(angle.flat[0])), angle.shape)
    return np.asarray(J.expi(angle))


def _sketched(model: KinematicModel) -> np.ndarray:
    """The input coordinate of the sketched position: φ = 0, or the actuator's length."""
    if model.drive == "laws":
        return np.full(1, np.nan)  # the laws need not pass through the sketch
    group = _driven(model)
    if group is None:
        return np.zeros(1)
    return np.atleast_1d(np.asarray(sketch_input(model), dtype=float))


def _jet(x: Value) -> Jet:
    assert isinstance(x, Jet), "a motion with analogs"
    return x


def _value(value: _Number | Tabulated, q: np.ndarray, periodic: bool) -> _Number | np.ndarray:
    return value.at(q, periodic=periodic) if isinstance(value, Tabulated) else value


def _groups(bodies: _Bodies, motion: Motion
            ) -> tuple[dict[PairId, Reaction], np.ndarray, np.ndarray, np.ndarray,
                       tuple[np.ndarray, DriveLoad] | None]:
    """Solve the dyads from the last attached back; their reactions on earlier links join
    those links' loads. Returns the reactions, reasons, singular groups, ill-conditioned
    positions and, for an actuator input, its driving force and its load on the members."""
    model = motion.model
    shape = bodies.shape
    reactions: dict[PairId, Reaction] = {}
    reason = np.zeros(shape, np.int8)
    singular = np.full(shape, None, dtype=object)
    ill = np.zeros(shape, bool)
    blocked = np.zeros(shape, bool)
    actuator = None
    for group in reversed(model.groups):
        equilibrium = EQUILIBRIA.get(group.group_kind.code)
        if equilibrium is None:      # the input group: solved last, by the drive
            continue
        members = _merge(bodies, group) if group.driven is not None else None
        welded = members is not None and group.layout is not None
        solved = equilibrium(group, _Welded(bodies, group) if welded else bodies)
        solution = motion.solutions[group.label]
        apart = ~np.broadcast_to(np.asarray(solution.exists, dtype=bool), shape)
        here = ~apart & ((solved.determinant <= SINGULAR) | (solution.margin <= SINGULAR))
        reason[apart & ~blocked] = ForceReason.NOT_ASSEMBLED
        new = here & ~blocked
        if new.any():
            reason[new] = solved.singular
            singular[new] = group.label
        blocked |= here | apart
        ill |= solved.determinant < NEAR
        own = (group.i, group.j, *group.composite)
        for transfer in solved.transfers:
            if blocked.any():
                transfer = _blanked(transfer, blocked)
            if members is not None:
                transfer = _to_member(model, group, transfer)
            reactions[transfer.pair] = _oriented(motion, transfer)
            if transfer.source not in own and transfer.source != model.frame:
                bodies.add(transfer.source, -transfer.force, transfer.point,
                           None if transfer.couple is None else -transfer.couple)
        if members is not None:
            actuator = _split(bodies, motion, group, members, reactions)
    return reactions, reason, singular, ill, actuator


def _merge(bodies: _Bodies, group: GroupModel) -> dict[LinkId, tuple[np.ndarray, np.ndarray]]:
    """Make an actuator's composite one body for its group: the loads of its members
    summed on the member that stands for it. Returns the members' own loads."""
    side = _bar(group)
    own = {link: (bodies.forces[link], bodies.moments[link]) for link in group.composite}
    origin = bodies.origins[side]
    bodies.forces[side] = sum((f for f, _ in own.values()), np.zeros(bodies.shape, complex))
    bodies.moments[side] = sum((m - cross(origin - bodies.origins[link], f)
                                for link, (f, m) in own.items()), np.zeros(bodies.shape))
    return own


def _to_member(model: KinematicModel, group: GroupModel, transfer: Transfer) -> Transfer:
    """A transfer of an actuator's group with the composite replaced by the member that the
    pair actually touches."""
    source, target = transfer.source, transfer.target
    if source in group.composite:
        source = _member(model, group, transfer.pair)
    if target in group.composite:
        target = _member(model, group, transfer.pair)
    return Transfer(transfer.pair, source, target, transfer.force, transfer.point,
                    transfer.normal, transfer.couple)


def _split(bodies: _Bodies, motion: Motion, group: GroupModel,
           members: dict[LinkId, tuple[np.ndarray, np.ndarray]],
           reactions: dict[PairId, Reaction]) -> tuple[np.ndarray, DriveLoad]:
    """The actuator's force and the reaction in its driven pair from the equilibrium of the
    member hinged at the bar's far end (the dyad's C)."""
    from assur.kinematics.higher.kind import actuator_ends  # only for an actuator

    model = motion.model
    pair_c, hinge = actuator_ends(group)
    member = _member(model, group, pair_c)
    c = bodies.joint(pair_c)
    on_member = reactions[pair_c]
    sign = 1.0 if on_member.links[1] == member else -1.0
    from_partner = sign * (on_member.x + 1j * on_member.y)   # force of the partner on m_C
    force, moment = members[member]
    moment_c = moment - cross(c - bodies.origins[member], force)
    pair = next(pid for pid, (kind, links, _) in model.pair_links.items()
                if kind == "P" and set(links) <= set(group.composite))
    slider = motion.sliders[pair]
    ends = {member: c, next(m for m in group.composite if m != member): bodies.joint(hinge)}
    axis = ends[slider.slider] - ends[slider.carrier]
    axis = axis / np.abs(axis)
    flip = 1.0 if member == slider.slider else -1.0
    push = -flip * (force + from_partner)                   # force of the carrier on the slider
    couple = -flip * moment_c
    driving = np.asarray(dot(push, axis))
    n = bodies.normal(pair)
    normal = np.asarray(dot(push, n))
    reactions[pair] = _oriented(motion, Transfer(pair, slider.carrier, slider.slider,
                                                 normal * n, c, normal, couple))
    return driving, ((slider.carrier, slider.slider), driving * axis, c, None)


def _blanked(transfer: Transfer, blocked: np.ndarray) -> Transfer:
    """The transfer with NaN where a group is singular."""

    def blank(x: np.ndarray | None) -> np.ndarray | None:
        return None if x is None else np.where(blocked, np.nan, x)

    force = blank(transfer.force)
    assert force is not None
    return Transfer(transfer.pair, transfer.source, transfer.target, force, transfer.point,
                    blank(transfer.normal), blank(transfer.couple))


def _oriented(motion: Motion, transfer: Transfer) -> Reaction:
    """The reaction as the force of the pair's first listed link on its second."""
    links = motion.model.pair_links[transfer.pair][1]
    if links == (transfer.source, transfer.target):
        return Reaction(transfer.pair, links, transfer.force.real, transfer.force.imag,
                        transfer.normal, transfer.couple, transfer.point)
    force = -transfer.force
    return Reaction(transfer.pair, links, force.real, force.imag,
                    None if transfer.normal is None else -transfer.normal,
                    None if transfer.couple is None else -transfer.couple, transfer.point)
