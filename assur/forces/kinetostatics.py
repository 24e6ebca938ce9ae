"""Kinetostatics by Assur groups: joint reactions and the driving torque over the cycle.

:func:`kinetostatics` takes a :class:`~assur.kinematics.analysis.Motion` computed with
analogs, the masses and loads (:class:`~assur.forces.model.ForceData`) and the input speed ω,
and solves the groups from the last attached back to the input link (``docs/forces.md``):
d'Alembert inertia forces and torques from the exact second analogs, the closed form of each
dyad kind (:data:`~assur.forces.groups.EQUATIONS`), then the driving torque on the crank.
Beside it, the driving torque from the power balance (Zhukovsky's lever) and the
Newton–Euler residual of every link computed from the reported reactions.

Work is in SI: positions and analogs in m, forces in N, moments in N·m. Arrays are shaped
like the kinematics, ``(N,)`` positions or ``(D, N)`` designs × positions; a position where a
group does not assemble or a reaction is indeterminate is NaN with a reason, never an error.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from assur.forces.checks import LinkResidual, Power, lever_torque, link_residuals
from assur.forces.groups import EQUATIONS, ForceReason, Transfer, cross
from assur.forces.model import ForceData, Tabulated
from assur.kinematics import jets as J
from assur.kinematics.analysis import Motion, analyse, values
from assur.kinematics.jets import Jet
from assur.model import LinkId, PairId
from assur.text import Message

__all__ = ["ForceAnalysis", "Reaction", "kinetostatics"]

#: Millimetres to metres.
MM = 1e-3

#: A normalised determinant at or below this is the singular position itself (null).
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
        ``'driving_torque'`` (N·m on the crank, counter-clockwise positive).
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
    known, origins, input_link
        What the residuals are computed from: every moving link's known loads (resultant
        force, N, and moment about its origin, N·m), its origin (m), and the driven link.
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
    input_link: LinkId = field(repr=False)

    @cached_property
    def residuals(self) -> dict[LinkId, LinkResidual]:
        """Moving link → its Newton–Euler residual (:class:`~assur.forces.checks.LinkResidual`)
        from the reported reactions and driving torque (computed when first asked for).

        Examples
        --------
        >>> import numpy as np, assur
        >>> from assur.forces import ForceData, Load
        >>> model = assur.load_model("input_tables/four_bar.yaml")
        >>> motion = assur.analyse(model, np.radians([0.0, 90.0]), analogs=True)
        >>> result = kinetostatics(motion, ForceData(loads=(Load(3, torque=-15.0),)))
        >>> bool(max(r.moment.max() for r in result.residuals.values()) < 1e-12)
        True
        """
        with np.errstate(all="ignore"):
            return link_residuals(
                self.known, self.origins,
                {pid: (r.links, r.x + 1j * r.y, r.point, r.moment)
                 for pid, r in self.reactions.items()},
                {self.input_link: self.driving})

    def message(self, index: Any) -> Message | None:
        """Why the forces at one position are not given (None where they are).

        Examples
        --------
        >>> import numpy as np, assur
        >>> from assur.forces import ForceData, Load
        >>> model = assur.load_model("input_tables/four_bar.yaml")
        >>> motion = assur.analyse(model, np.array([0.0]), analogs=True)
        >>> result = kinetostatics(motion, ForceData(loads=(Load(3, torque=-15.0),)), 10.0)
        >>> result.message(0) is None
        True
        """
        reason = ForceReason(int(self.reason[index]))
        if reason == ForceReason.SOLVED:
            return None
        return Message(REASON_CODES[reason], {"group": self.singular[index] or ""})


def kinetostatics(motion: Motion, data: ForceData, omega: float = 0.0) -> ForceAnalysis:
    """Joint reactions and the driving torque at every analysed position.

    Parameters
    ----------
    motion : Motion
        From :func:`~assur.kinematics.analysis.analyse` with ``analogs=True``.
    data : ForceData
        Masses, loads and gravity (table units: sketch points in mm).
    omega : float
        Constant input speed (rad/s); 0 gives the static analysis.

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
    driving torque ``M_d = −M_1(O_1)`` and the frame's reaction at O_1.

    Examples
    --------
    The four-bar of ``docs/forces.md`` §8.2 with only the torque on the rocker, statically:

    >>> import numpy as np, assur
    >>> from assur.forces import ForceData, Load
    >>> model = assur.load_model("input_tables/four_bar.yaml")
    >>> motion = assur.analyse(model, np.radians([0.0, 90.0]), analogs=True)
    >>> result = kinetostatics(motion, ForceData(loads=(Load(3, torque=-15.0),)))
    >>> bool(np.all(np.abs(result.power_balance) < 1e-12))
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
        bodies = _Bodies(motion, shape)
        power = _known_loads(bodies, motion, data, omega)
        known = {link: (bodies.forces[link], bodies.moments[link]) for link in bodies.forces}
        reactions, reason, singular, ill = _groups(bodies, motion)
        crank = model.groups[0]
        pivot = bodies.joint(crank.pairs["H_i"])
        driving = -bodies.moment(crank.i, pivot)
        reactions[crank.pairs["H_i"]] = _oriented(
            motion, Transfer(crank.pairs["H_i"], model.frame, crank.i,
                             -bodies.force(crank.i), pivot))
        driving = np.where(reason > ForceReason.NOT_ASSEMBLED, np.nan, driving)
        lever, scale = lever_torque(power, float(model.direction))
    reason = np.where(~np.asarray(motion.exists) & (reason == 0), ForceReason.NOT_ASSEMBLED,
                      reason).astype(np.int8)
    return ForceAnalysis(omega=float(omega), gravity=complex(data.gravity),
                         drive="driving_torque", driving=driving, driving_lever=lever,
                         power_balance=driving - lever, power_scale=scale,
                         reactions=reactions, reason=reason, singular=singular,
                         ill_conditioned=ill, known=known, origins=bodies.origins,
                         input_link=crank.i)


class _Bodies:
    """The known loads of every moving link, accumulated over the positions (§3).

    Implements :class:`~assur.forces.groups.Loads` for the group equations.
    """

    def __init__(self, motion: Motion, shape: tuple[int, ...]) -> None:
        self.motion = motion
        self.shape = shape
        moving = [link for link in motion.frames if link != motion.model.frame]
        self.origins = {link: np.broadcast_to(values(motion.frames[link][0]) * MM, shape)
                        for link in moving}
        self.forces = {link: np.zeros(shape, complex) for link in moving}
        self.moments = {link: np.zeros(shape) for link in moving}
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
            self._normals[pair] = 1j * expi(values(self.motion.sliders[pair].angle))
        return self._normals[pair]

    def force(self, link: LinkId) -> np.ndarray:
        return self.forces[link]

    def moment(self, link: LinkId, point: np.ndarray) -> np.ndarray:
        return self.moments[link] - cross(point - self.origins[link], self.forces[link])

    def add(self, link: LinkId, force: np.ndarray, point: np.ndarray,
            couple: np.ndarray | None = None) -> None:
        """A force at a point of the link, and a couple."""
        self.load(link, force, point - self.origins[link], couple)

    def load(self, link: LinkId, force: np.ndarray, arm: np.ndarray,
             couple: np.ndarray | None = None) -> None:
        """A force at the point ``origin + arm`` of the link, and a couple."""
        moment = cross(arm, force)
        self.forces[link] = self.forces[link] + force
        self.moments[link] = self.moments[link] + (moment if couple is None else
                                                   moment + couple)

    def turn(self, link: LinkId, couple: np.ndarray) -> None:
        """A couple on the link."""
        self.moments[link] = self.moments[link] + couple


def _known_loads(bodies: _Bodies, motion: Motion, data: ForceData, omega: float) -> Power:
    """Weights, inertia forces and torques, and the external loads of every link (§3); their
    power per unit input speed (§6.1)."""
    model = motion.model
    sketch = analyse(model, np.zeros(1)).frames
    rotors: dict[LinkId, np.ndarray] = {}
    w2 = omega * omega

    def carried(link: LinkId, x: complex) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """A point fixed on the link, sketched at x (mm): its arm from the link's origin, its
        velocity and acceleration analogs, in m."""
        origin, angle = _jet(motion.frames[link][0]), _angle(motion, link)
        origin0, angle0 = sketch[link]
        if link not in rotors:
            rotors[link] = expi(angle.v)
        local = (x - values(origin0)) * np.exp(-1j * values(angle0)) * MM
        arm = local * rotors[link]
        return (arm, origin.d1 * MM + arm * (1j * angle.d1),
                origin.d2 * MM + arm * (1j * angle.d2 - angle.d1 * angle.d1))

    periodic = model.drive == "crank"
    terms: list[Any] = []
    for link, mass in data.masses.items():
        angle = _angle(motion, link)
        spin = -mass.inertia * w2 * angle.d2
        if mass.mass > 0 and mass.centre is not None:
            arm, velocity, acceleration = carried(link, mass.centre)
            force = data.weight(link) - mass.mass * w2 * acceleration
            bodies.load(link, force, arm, spin)
            terms.append(J.dot(force, velocity))
        else:
            bodies.turn(link, spin)
        terms.append(spin * angle.d1)
    for load in data.loads:
        if load.force is not None and load.point is not None:
            arm, velocity, _ = carried(load.link, load.point)
            force = _value(load.force, motion.q, periodic) + np.zeros(bodies.shape)
            bodies.load(load.link, force, arm)
            terms.append(J.dot(force, velocity))
        if load.torque is not None:
            torque = _value(load.torque, motion.q, periodic) + np.zeros(bodies.shape)
            bodies.turn(load.link, torque)
            terms.append(torque * _angle(motion, load.link).d1)
    zero = np.zeros(bodies.shape)
    return Power(sum(terms, zero), sum((np.abs(t) for t in terms), zero))


def expi(angle: np.ndarray) -> np.ndarray:
    """exp(i·angle), computed once when the angle is one value broadcast over the positions
    (a guide on the frame).

    Examples
    --------
    >>> expi(np.broadcast_to(np.pi / 2, (3,))).round(12).tolist()
    [1j, 1j, 1j]
    """
    if angle.ndim and not any(angle.strides):
        return np.broadcast_to(np.asarray(J.expi(angle.flat[0])), angle.shape)
    return np.asarray(J.expi(angle))


def _angle(motion: Motion, link: LinkId) -> Jet:
    return _jet(motion.frames[link][1])


def _jet(x: Any) -> Jet:
    assert isinstance(x, Jet), "a motion with analogs"
    return x


def _value(value: complex | float | Tabulated, q: np.ndarray, periodic: bool) -> Any:
    return value.at(q, periodic=periodic) if isinstance(value, Tabulated) else value


def _groups(bodies: _Bodies, motion: Motion) -> tuple[dict[PairId, Reaction], np.ndarray,
                                                      np.ndarray, np.ndarray]:
    """Solve the dyads from the last attached back; their reactions on earlier links join
    those links' loads (§5)."""
    shape = bodies.shape
    reactions: dict[PairId, Reaction] = {}
    reason = np.zeros(shape, np.int8)
    singular = np.full(shape, None, dtype=object)
    ill = np.zeros(shape, bool)
    blocked = np.zeros(shape, bool)
    for group in reversed(motion.model.groups[1:]):
        solved = EQUATIONS[f"L{group.kind}"](group, bodies)
        here = solved.determinant <= SINGULAR
        new = here & ~blocked
        if new.any():
            reason[new] = solved.singular
            singular[new] = group.label
        blocked |= here
        ill |= solved.determinant < NEAR
        own = (group.i, group.j)
        for transfer in solved.transfers:
            if blocked.any():
                transfer = _blanked(transfer, blocked)
            reactions[transfer.pair] = _oriented(motion, transfer)
            if transfer.source not in own and transfer.source != motion.model.frame:
                bodies.add(transfer.source, -transfer.force, transfer.point,
                           None if transfer.couple is None else -transfer.couple)
    return reactions, reason, singular, ill


def _blanked(transfer: Transfer, blocked: np.ndarray) -> Transfer:
    """The transfer with NaN where a group is singular."""

    def blank(x: np.ndarray | None) -> np.ndarray | None:
        return None if x is None else np.where(blocked, np.nan, x)

    force = blank(transfer.force)
    assert force is not None
    return Transfer(transfer.pair, transfer.source, transfer.target, force, transfer.point,
                    blank(transfer.normal), blank(transfer.couple))


def _oriented(motion: Motion, transfer: Transfer) -> Reaction:
    """The reaction as the force of the pair's first listed link on its second (§5.5)."""
    links = motion.model.pair_links[transfer.pair][1]
    sign = 1.0 if links == (transfer.source, transfer.target) else -1.0
    force = sign * transfer.force
    return Reaction(transfer.pair, links, force.real, force.imag,
                    None if transfer.normal is None else sign * transfer.normal,
                    None if transfer.couple is None else sign * transfer.couple,
                    transfer.point)
