"""Kinematic analysis of a mechanism over the input cycle, groups solved in layering order.

:func:`analyse` solves every group of a :class:`~assur.kinematics.model.KinematicModel` at all input
positions at once (crank angles φ, or actuator lengths) and returns a :class:`Motion`: every
link's pose, every revolute joint, every slider pair (point, slider coordinate, guide line),
every tracing point, and each group's existence margin. With ``analogs=True`` the input
coordinate is fed as a :class:`~assur.kinematics.jets.Jet`, so every quantity also carries its exact
first and second derivatives with respect to the input coordinate (velocity and
acceleration analogs); :func:`velocity` and :func:`acceleration` turn them into time
derivatives for a given crank speed.

Parameters shaped ``(D, 1)`` (D candidate designs) and positions shaped ``(N,)`` give
results shaped ``(D, N)``; nothing loops over positions or designs in Python.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.dyads import DyadSolution
from assur.kinematics.jets import Jet
from assur.kinematics.laws import STROKE, InputLaw, stroke_margin
from assur.kinematics.model import Anchor, GroupModel, Guide, KinematicModel
from assur.kinematics.reasons import Reason
from assur.kinematics.rules import given, rules_of
from assur.model import LinkId, PairId
from assur.typing import Value

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.higher.kind import HigherGroupSolution

#: What the analysis keeps of a group: a dyad's closed-form solution, or the followed mode
#: of a triad or class IV group.
GroupSolution: TypeAlias = "DyadSolution | HigherGroupSolution"

__all__ = [
    "GroupSolution",
    "Motion",
    "SliderState",
    "State",
    "acceleration",
    "analyse",
    "cycle_model",
    "held",
    "input_analogs",
    "input_grid",
    "sketch_input",
    "unwrap",
    "values",
    "velocity",
]


@dataclass(frozen=True)
class SliderState:
    """A prismatic pair over the cycle.

    The slider's reference point runs along ``base + offset·n(angle) + s·u(angle)``;
    ``base`` is fixed on the guide carrier, ``angle`` turns with it.
    """

    pair: PairId
    carrier: LinkId
    slider: LinkId
    point: Value
    s: Value
    base: Value
    angle: Value
    offset: Value


@dataclass(frozen=True)
class Motion:
    """The mechanism over the analysed positions.

    Attributes
    ----------
    model : KinematicModel
    q : ndarray
        Input coordinate: crank rotation φ from the reference position (radians) or actuator
        length (mm).
    solutions : dict
        Group label → :class:`~assur.kinematics.dyads.DyadSolution`, or
        :class:`~assur.kinematics.higher.kind.HigherGroupSolution` for a triad or class IV
        group (layering order).
    frames : dict
        Link → (origin, angle) of its local frame.
    joints : dict
        Revolute pair → its point.
    sliders : dict
        Prismatic pair → :class:`SliderState`.
    tracing : dict
        Tracing point name → its point.
    analogs : bool
        Whether values are jets (with derivatives w.r.t. q).

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=8)
    >>> motion.q.shape, sorted(motion.joints)
    ((8,), ['A', 'B', 'C', 'D'])
    """

    model: KinematicModel
    q: np.ndarray
    solutions: dict[str, GroupSolution]
    frames: dict[LinkId, tuple[Value, Value]]
    joints: dict[PairId, Value]
    sliders: dict[PairId, SliderState]
    tracing: dict[str, Value]
    analogs: bool

    def __repr__(self) -> str:
        def names(items: Iterable[object]) -> str:
            return ", ".join(map(str, items)) or "none"

        exists = np.asarray(self.exists)
        return (f"Motion({self.model.name!r}: {self.q.shape[-1]} positions, "
                f"analogs={self.analogs}, every group assembles at {int(exists.sum())} of "
                f"{exists.size}\n  groups: {names(self.solutions)}\n"
                f"  joints: {names(self.joints)}; sliders: {names(self.sliders)}; "
                f"tracing: {names(self.tracing)})")

    @property
    def exists(self) -> np.ndarray:
        """True where every group assembles."""
        out = None
        for solution in self.solutions.values():
            out = solution.exists if out is None else out & solution.exists
        return np.asarray(out)

    def link_angle(self, link: LinkId) -> Value:
        """Angle of a link's local frame (radians, in (−π, π]; unwrap with :func:`unwrap`)."""
        return self.frames[link][1]


def input_grid(model: KinematicModel, points: int) -> np.ndarray:
    """Evenly spaced input positions over the model's interval.

    A full-turn crank gets ``points`` angles over [0, 2π) (the end equals the start); an
    actuator gets ``points`` lengths over its closed stroke.

    Parameters
    ----------
    model : KinematicModel
        The mechanism (its input is a crank or an actuator).
    points : int
        Number of positions.

    Returns
    -------
    numpy.ndarray
        Crank rotations φ in radians from the reference position, or actuator lengths in mm.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> print(assur.input_grid(model, 4).round(4))
    [0.     1.5708 3.1416 4.7124]
    """
    lo, hi = model.input_range
    if model.periodic:
        return lo + (hi - lo) * np.arange(points) / points
    return np.linspace(lo, hi, points)


def analyse(model: KinematicModel, q: np.ndarray | None = None, *, points: int = 360,
            analogs: bool = False) -> Motion:
    """Solve the mechanism at every input position, groups in layering order.

    Parameters
    ----------
    model : KinematicModel
    q : array_like, optional
        Input positions (crank rotation φ in radians from the reference position, any number
        of turns; or actuator lengths in mm). Default: :func:`input_grid` with ``points``.
    points : int
        Grid size when ``q`` is not given.
    analogs : bool
        Carry first and second derivatives w.r.t. q (velocity and acceleration analogs).

    Returns
    -------
    Motion
        NaN where a group (or an earlier one) does not assemble; see ``solutions[...]
        .exists``, ``.margin`` and ``.reason``, and :mod:`assur.kinematics.existence`.

    Examples
    --------
    At φ = 0 the mechanism is in its sketched position, so joint C is where the sketch puts it:

    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=4)
    >>> c = motion.joints["C"][0]
    >>> print(f"{c.real:.3f} {c.imag:.3f}")
    110.000 80.000
    """
    q = input_grid(model, points) if q is None else np.asarray(q, dtype=float)
    coordinate: Value = Jet(q, 1.0, 0.0) if analogs else q
    state = State(model)
    with np.errstate(all="ignore"):
        for group in model.groups:
            state.solve(group, coordinate)
        tracing = state.trace()
    shape = np.broadcast_shapes(model.design_shape, q.shape)
    frames = {link: (full(o, shape, analogs), full(a, shape, analogs))
              for link, (o, a) in state.frames.items()}
    joints = {pid: full(z, shape, analogs) for pid, z in state.joints.items()}
    sliders = {pid: SliderState(st.pair, st.carrier, st.slider, full(st.point, shape, analogs),
                                full(st.s, shape, analogs), full(st.base, shape, analogs),
                                full(st.angle, shape, analogs), st.offset)
               for pid, st in state.sliders.items()}
    tracing = {name: full(z, shape, analogs) for name, z in tracing.items()}
    return Motion(model, q, state.solutions, frames, joints, sliders, tracing, analogs)


def sketch_input(model: KinematicModel) -> Any:
    """The input coordinate of the sketched position: φ = 0 for a crank; for an actuator its
    drawn length (mm; shape () or of the designs), the distance of the two hinges of the bar
    it is (:func:`~assur.kinematics.higher.kind.actuator_ends`) as drawn."""
    group = next((g for g in model.groups if g.driven is not None), None)
    if group is None:
        return 0.0
    if group.layout is None:
        return model.params[group.column("l_j" if group.driven == "j" else "l_i")]
    state = State(model)
    for earlier in model.groups[:model.groups.index(group)]:
        state.solve(earlier, 0.0)
    anchors = dict(zip(group.layout.external, group.layout.anchors, strict=True))

    def drawn(pair: PairId) -> Any:
        anchor = anchors.get(pair)
        if anchor is not None:
            return state.point(anchor)
        return model.params[group.column(f"x_{pair}")] \
            + 1j * model.params[group.column(f"y_{pair}")]

    from assur.kinematics.higher.kind import actuator_ends  # only for an actuator

    point, origin = actuator_ends(group)
    return np.abs(drawn(point) - drawn(origin))


def cycle_model(model: KinematicModel) -> KinematicModel:
    """The model with its input a law of one cycle parameter t, whatever drives it.

    A crank turns once per cycle; a slider on a frame guide or an actuator runs its stroke
    and back harmonically, ``s_min + (s_max − s_min)·(1 − cos t)/2``, with ``s_min``,
    ``s_max`` (mm) new parameters of the group holding it. Every design of a batch then
    shares the positions t while its stroke limits may differ (``with_params`` with arrays
    shaped ``(D, 1)``); a model whose inputs already follow laws is returned as it is.

    Parameters
    ----------
    model : KinematicModel
        Driven by a crank, a slider, an actuator, or by laws (several inputs).

    Returns
    -------
    KinematicModel
        ``drive == 'laws'``, positions t ∈ [0, 2π) (:func:`input_grid`); the force
        analysis then takes ω as the rate of t (rad/s).

    Raises
    ------
    ValueError
        For an actuator inside a triad or a class IV group, which is followed along its
        length only.

    Examples
    --------
    Two boom designs whose cylinders end their strokes at 120 and 135 mm, at four positions:

    >>> import pathlib, assur
    >>> tables = pathlib.Path(assur.__file__).parents[1] / "input_tables"
    >>> cycle = cycle_model(assur.load_model(tables / "hydraulic_boom_forces.yaml"))
    >>> cycle.drive, cycle.params["L1(1,2).s_min"], cycle.params["L1(1,2).s_max"]
    ('laws', 95.0, 135.0)
    >>> designs = cycle.with_params({"L1(1,2).s_max": np.array([[120.0], [135.0]])})
    >>> motion = analyse(designs, input_grid(designs, 4))
    >>> values(motion.sliders["Pd"].s).round(3).tolist()
    [[95.0, 107.5, 120.0, 107.5], [95.0, 115.0, 135.0, 115.0]]
    """
    if model.drive == "laws":
        return model
    params = dict(model.params)
    if model.drive == "crank":
        group = next(g for g in model.groups if g.group_kind.is_input)
        law = InputLaw(group.label, False, ratio=model.direction)
    else:
        group = next(g for g in model.groups if g.driven is not None
                     or g.group_kind.is_input)
        if group.layout is not None:
            raise ValueError(f"the actuator of {group.label} is followed along its length "
                             "only; a triad or class IV group takes no law of a cycle")
        law = InputLaw(group.label, True, limited=True)
        params.update({group.column(c): v for c, v in zip(STROKE, model.input_range,
                                                           strict=True)})
    return replace(model, params=params, drive="laws", direction=1,
                   input_range=(0.0, 2 * math.pi), laws={group.label: law})


def input_analogs(model: KinematicModel, label: str, q: np.ndarray | None = None, *,
                  points: int = 360) -> Motion:
    """The motion of a mechanism with several inputs, its analogs taken with respect to one
    input's coordinate, the others held (partial derivatives ∂x/∂q_k, ∂²x/∂q_k²).

    Parameters
    ----------
    model : KinematicModel
        Whose inputs follow laws (``drive == 'laws'``, :func:`cycle_model`).
    label : str
        The group holding the input (a key of ``model.laws``: ``"L0(4)"``).
    q : array_like, optional
        Positions t (radians); default :func:`input_grid` with ``points``.
    points : int
        Grid size when ``q`` is not given.

    Returns
    -------
    Motion
        Values as :func:`analyse` gives them; the jets' ``d1``, ``d2`` are per radian of a
        crank's rotation, or per mm of a slider's or an actuator's coordinate.

    Raises
    ------
    KeyError
        When no input's law is held by ``label``.

    Examples
    --------
    By the chain rule the analogs with respect to t are Σ_k ∂x/∂q_k · q_k′(t):

    >>> import pathlib, assur
    >>> tables = pathlib.Path(assur.__file__).parents[1] / "input_tables"
    >>> model = assur.load_model(tables / "five_bar_two_cranks.yaml")   # φ1 = t, φ4 = 90° + 2t
    >>> t = input_grid(model, 8)
    >>> d1 = input_analogs(model, "L0(1)", t).joints["C"].d1
    >>> d4 = input_analogs(model, "L0(4)", t).joints["C"].d1
    >>> bool(np.allclose(analyse(model, t, analogs=True).joints["C"].d1, d1 + 2 * d4))
    True
    """
    if label not in model.laws:
        raise KeyError(f"no input is held by {label!r}; inputs: {', '.join(model.laws)}")
    laws = {name: replace(law, moving=name == label) for name, law in model.laws.items()}
    return analyse(replace(model, laws=laws), q, points=points, analogs=True)


def held(model: KinematicModel) -> KinematicModel:
    """The model of a cycle of laws with every input held at its sketched position (a crank
    at rotation 0, a slider at displacement 0, an actuator at its drawn length), whatever
    the cycle parameter: the sketched pose, which the laws need not pass through."""
    laws = {}
    for label, law in model.laws.items():
        drawn = 0.0
        group = model.group(label)
        if group.driven is not None:
            drawn = float(np.max(sketch_input(replace(model, laws={}))))
        laws[label] = replace(law, phase=drawn if law.linear else 0.0, ratio=0, table=(),
                              limited=False, held=True)
    return replace(model, laws=laws)


def full(x: Any, shape: tuple[int, ...], jet: bool = False) -> Any:
    """``x`` broadcast to ``shape`` (read-only views); a jet when ``jet`` (zero derivatives
    for a constant)."""
    if jet and not isinstance(x, Jet):
        x = Jet(x, 0.0, 0.0)
    if isinstance(x, Jet):
        return Jet(np.broadcast_to(x.v, shape), np.broadcast_to(x.d1, shape),
                   np.broadcast_to(x.d2, shape))
    return np.broadcast_to(x, shape)


class State:
    """Poses known so far while the groups are solved one after another.

    Each group's solver (:attr:`assur.kinematics.rules.KindRules.solve`) reads the poses of
    the earlier groups here and writes its own: joints, sliders, link frames.
    """

    def __init__(self, model: KinematicModel) -> None:
        self.model = model
        self.p = model.value
        self.solutions: dict[str, GroupSolution] = {}
        self.frames: dict[LinkId, tuple[Value, Value]] = {}
        self.rotors: dict[LinkId, Value] = {}
        self.joints: dict[PairId, Value] = {}
        self.sliders: dict[PairId, SliderState] = {}

    def rotor(self, link: LinkId) -> Value:
        if link not in self.rotors:
            self.rotors[link] = J.expi(self.frames[link][1])
        return self.rotors[link]

    def point(self, anchor: Anchor) -> Value:
        """Position of a point fixed on a link."""
        p = self.p
        if anchor.link == self.model.frame:
            fixed: Value = p(f"{anchor.owner}.{anchor.first}") \
                + 1j * p(f"{anchor.owner}.{anchor.second}")
            return fixed
        first = p(f"{anchor.owner}.{anchor.first}")
        if anchor.second is None:
            local = first
        elif anchor.polar:
            local = first * np.exp(1j * p(f"{anchor.owner}.{anchor.second}"))
        else:
            local = first + 1j * p(f"{anchor.owner}.{anchor.second}")
        origin = self.frames[anchor.link][0]
        if np.ndim(local) == 0 and local == 0:
            return origin
        moved: Value = origin + local * self.rotor(anchor.link)
        return moved

    def guide(self, guide: Guide) -> tuple[Value, Value, Value]:
        """Base point, absolute direction and offset of a guide."""
        beta = self.p(f"{guide.base.owner}.{guide.beta}")
        angle = beta if guide.carrier == self.model.frame else self.frames[guide.carrier][1] + beta
        offset = 0.0 if guide.offset is None else self.p(f"{guide.base.owner}.{guide.offset}")
        return self.point(guide.base), angle, offset

    def delta(self, group: GroupModel) -> Any:
        return self.model.params.get(group.column("delta"), 0.0)

    @cached_property
    def _flat(self) -> KinematicModel:
        """The model with design parameters of shape (D, 1) laid flat to (D,)."""
        return replace(self.model, params={name: np.reshape(v, -1) if np.ndim(v) else v
                                           for name, v in self.model.params.items()})

    def flat_value(self, name: str) -> Any:
        """A parameter in program units with the designs along one axis (shape () or (D,))."""
        return self._flat.value(name)

    @property
    def flat_shape(self) -> tuple[int, ...]:
        """() for one design, (D,) for D designs."""
        return self._flat.design_shape

    def earlier(self, group: GroupModel) -> Callable[[Value], State]:
        """The groups before ``group`` solved at any input positions, one per design
        (shape (D,) or a jet of it): how a triad or class IV group reads its known links."""
        flat = replace(self._flat, groups=self.model.groups[:self.model.groups.index(group)])

        def at(q: Value) -> State:
            state = State(flat)
            for earlier in flat.groups:
                state.solve(earlier, q)
            return state

        return at

    def slider(self, pair: PairId, carrier: LinkId, slider: LinkId, point: Value, s: Value,
               base: Value, angle: Value, offset: Value) -> None:
        self.sliders[pair] = SliderState(pair, carrier, slider, point, s, base, angle, offset)

    def solve(self, group: GroupModel, q: Value) -> None:
        """Solve one group (its kind's solver) and record its links' frames; a group that
        holds an input with a law gets that input's coordinate at the cycle parameter q, and
        does not assemble where a linear input is beyond its stroke."""
        law = self.model.laws.get(group.label)
        margin = None
        if law is not None:
            q = law.coordinate(q, self.p)
            if law.limited:
                lo, hi = (self.p(group.column(column)) for column in STROKE)
                margin = stroke_margin(q, lo, hi)
                q = J.where(margin >= -STROKE_TOLERANCE, q, np.nan)
        sol = rules_of(group.group_kind).solve(self, group, q)
        if margin is not None and isinstance(sol, DyadSolution):
            sol = _stroke_limited(sol, margin, group.group_kind.is_input)
        self.solutions[group.label] = sol
        self.frames[group.i] = (sol.origin_i, sol.angle_i)
        if group.j is not None:
            self.frames[group.j] = (given(sol.origin_j), given(sol.angle_j))

    def actuator(self, group: GroupModel, frame: tuple[Value, Value], point: Value,
                 q: Value) -> None:
        """Frames of the actuator's members and its driven pair (s = actuator length).

        ``frame`` is the frame of the bar the actuator is (origin at one hinge, axis towards
        the other), ``point`` its other hinge, where the slider's point is taken.
        """
        origin, angle = frame
        for member in group.composite:
            self.frames[member] = (origin, angle)
        pairs = self.model.pair_links
        driven = [pid for pid, (ptype, links, _) in pairs.items()
                  if ptype == "P" and set(links) <= set(group.composite)]
        for pid in driven:
            carrier = pairs[pid][2] or group.composite[0]
            slider = next(link for link in pairs[pid][1] if link != carrier)
            self.slider(pid, carrier, slider, point, q + np.zeros(np.shape(J.value(point))),
                        origin, angle, 0.0)

    def trace(self) -> dict[str, Value]:
        return {point.name: self.point(point.anchor) for point in self.model.tracing}


#: A linear input within this (normalised) distance beyond its stroke end is at the end.
STROKE_TOLERANCE = 1e-12


def _stroke_limited(sol: DyadSolution, margin: np.ndarray, is_input: bool) -> DyadSolution:
    """A group holding a linear input, failing where the input is beyond its stroke; an
    input group's margin is its margin to the stroke ends."""
    shape = np.broadcast_shapes(np.shape(sol.exists), np.shape(margin))
    inside = np.broadcast_to(margin >= -STROKE_TOLERANCE, shape)
    own = np.broadcast_to(margin if is_input else sol.margin, shape)
    return sol._replace(
        margin=np.where(inside, own, margin),
        exists=np.broadcast_to(sol.exists, shape) & inside,
        reason=np.where(inside, sol.reason, Reason.STROKE_END).astype(np.int8))


def velocity(x: Jet, omega: float | np.ndarray) -> np.ndarray:
    """Time derivative of a quantity for an input speed ω = dq/dt (rad/s or mm/s)."""
    return x.d1 * omega


def acceleration(x: Jet, omega: float | np.ndarray, epsilon: float | np.ndarray = 0.0
                 ) -> np.ndarray:
    """Second time derivative for input speed ω and input acceleration ε = d²q/dt²."""
    return x.d2 * omega * omega + x.d1 * epsilon


def unwrap(angle: np.ndarray, axis: int = -1) -> np.ndarray:
    """Continuous angles along the positions; NaN gaps (no assembly) are bridged.

    Unlike :func:`numpy.unwrap`, a NaN does not spoil the angles after it: the jump
    correction across a gap compares the last angle before it with the first after it.
    """
    angle = np.asarray(angle, dtype=float)
    moved = np.moveaxis(angle, axis, -1)
    filled = moved.copy()
    valid = np.isfinite(filled)
    # carry the last valid value forward so that differences across a gap are meaningful
    index = np.where(valid, np.arange(filled.shape[-1]), 0)
    np.maximum.accumulate(index, axis=-1, out=index)
    carried = np.take_along_axis(filled, index, axis=-1)
    step = np.diff(carried, axis=-1)
    step = np.where(np.isfinite(step), step, 0.0)
    correction = -2 * np.pi * np.round(step / (2 * np.pi))
    out = moved.copy()
    out[..., 1:] += np.cumsum(correction, axis=-1)
    return np.moveaxis(out, -1, axis)


def values(x: Value) -> np.ndarray:
    """The plain values of a quantity (jets or arrays)."""
    return np.asarray(J.value(x))

