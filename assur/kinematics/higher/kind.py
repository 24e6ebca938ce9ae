"""The kinematics of the triad and the class IV group, the higher kinds of :mod:`assur.kinds`.

A sketched triad or class IV group enters the kinematic model like a dyad: its sketch rule
(:func:`sketch_triad`, :func:`sketch_class_iv`) records the drawn points of its internal
joints as parameters, the anchors of its external hinges and the guides of its blocks on the
known links, and the frames of its four links at the reference position. Its solver
(:func:`solve_triad`, :func:`solve_class_iv`) follows the drawn assembly mode over the
positions (:func:`~assur.kinematics.higher.continuation.follow_mode`), the external hinges
and guides coming from the earlier groups evaluated at any crank angle, and writes the
joints, sliders and link frames into the analysis state. :func:`assur.kinematics.rules.rules_of`
gives these functions as the rules of the kinds ``III`` and ``IV``.

Parameters of a group labelled ``III(4,5,6,7)``: ``x_<pair>``, ``y_<pair>`` — the drawn
point of each internal pair (mm, at the reference position; for a block sliding on the
base, the point of the base's guide line, drawn at the leash's external hinge);
``beta_<pair>`` — the drawn direction of a guide (degrees: of the base's guide, absolute;
of a known link's guide, in that link's frame) with ``x_<pair>``, ``y_<pair>`` its base point;
the external hinges are attachment points of the known links, as for a dyad. Every length of
the group follows from these drawn points, so a changed design picks its mode at the
sketch as ``docs/higher_groups.md`` §2 describes.
"""

from __future__ import annotations

import cmath
import math
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.higher.continuation import HigherSolution, Stroke, follow_mode
from assur.kinematics.higher.coupled import ClassIVCoupled
from assur.kinematics.higher.groups import (
    AnyGroup,
    ClassIVInputs,
    Leash,
    Triad,
    TriadInputs,
    plain,
    values,
)
from assur.kinematics.higher.pinned import place
from assur.kinematics.jets import Jet
from assur.kinematics.model import Sketched

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.analysis import State
    from assur.kinematics.build import Builder
    from assur.kinematics.model import Anchor, GroupModel, Guide
    from assur.kinematics.rules import ShortfallAt
    from assur.model import LinkId, PairId
    from assur.structure.classification import AssurGroup

__all__ = ["HigherGroupSolution", "Layout", "SketchMode", "actuator_ends", "shortfall_higher",
           "sketch_class_iv", "sketch_triad", "solve_class_iv", "solve_triad"]

#: Link names of a triad (base, leashes in solving order) and of a class IV group.
TRIAD_LINKS = ("base", "leash1", "leash2", "leash3")
CLASS_IV_LINKS = ("a", "b", "c", "d")
#: Internal joints of a class IV group, in the order of :attr:`Layout.internal`.
CLASS_IV_JOINTS = ("C", "D", "E", "F")


@dataclass(frozen=True, slots=True)
class Layout:
    """Which link and pair plays which part in a triad or a class IV group.

    Attributes
    ----------
    links : tuple of link ids
        Triad: the base, then the leashes in solving order (a bar first); class IV: a, b, c, d.
    names : tuple of str
        The names of those links (:data:`TRIAD_LINKS`, :data:`CLASS_IV_LINKS`), the keys of
        :attr:`HigherSolution.rotations`.
    internal : tuple of pair ids
        Triad: the internal pair of each leash; class IV: the pairs C (a–b), D (b–c), E (c–d),
        F (d–a).
    external : tuple of pair ids
        Triad: the external pair of each leash; class IV: H_a, H_c.
    leashes : tuple of Leash
        Triad: the form of each leash (internal pair first); empty for IV.
    anchors : tuple
        Per external pair: the :class:`Anchor` of its hinge on the known link, or None.
    guides : tuple
        Per external pair: the :class:`Guide` of a block's guide on the known link, or None.
    """

    links: tuple[LinkId, ...]
    names: tuple[str, ...]
    internal: tuple[PairId, ...]
    external: tuple[PairId, ...]
    leashes: tuple[Leash, ...] = ()
    anchors: tuple[Anchor | None, ...] = ()
    guides: tuple[Guide | None, ...] = ()


class _Leg(NamedTuple):
    """One leash of a triad as the sketch rule finds it: its form, its link, its internal
    and external pairs and the known link of the external pair."""

    kind: Leash
    leash: LinkId
    inner: PairId
    external: PairId
    known: LinkId


class _DrawnPP(NamedTuple):
    """A P–P leash at the sketch: X⁰, its point drawn at the internal pair; Y⁰, at the
    external pair (the known link's guide point); u_K⁰, the known link's guide."""

    inner: Any
    outer: Any
    guide: Any


@dataclass(frozen=True, eq=False)
class HigherGroupSolution:
    """A triad or class IV group over the positions, as the analysis keeps a group's result.

    ``exists``, ``margin`` and ``reason`` are those of :attr:`follow` (with the reasons 8 and 9
    of :class:`~assur.kinematics.reasons.Reason`);
    ``origin_i``, ``angle_i`` the frame of the group's first link (triad base, class IV a).
    """

    follow: HigherSolution
    group: AnyGroup
    joints: dict[str, PairId]
    origin_i: Any
    angle_i: Any
    origin_j: None = None
    angle_j: None = None

    @property
    def followed(self) -> bool:
        """The positions come from a continuation from the sketch; False for a group solved
        in closed form at every position (a triad with a P–P leash and no bar), whose
        existence may be re-solved at any single position."""
        return not (isinstance(self.group, Triad) and self.group.unique)

    def modes(self, design: int = 0) -> list[SketchMode]:
        """Every real assembly mode at the sketch of one design, the drawn one marked.

        Parameters
        ----------
        design : int
            Which design (0 for a single one).

        Returns
        -------
        list of SketchMode
            Sorted by the angle of the eliminated link; the drawn mode is the one nearest the
            drawn joints (its angle is 0 in a table's own design).
        """
        modes = self.follow.modes
        index = (design,) if np.ndim(modes.count) else ()
        count = int(modes.count[index])
        sketch = {name: complex(np.reshape(plain(z), -1)[design if np.ndim(plain(z)) else 0])
                  for name, z in self.group.sketch.items()}
        rows = []
        for k in range(count):
            points = {pid: complex(modes.joints[name][index + (k,)])
                      for name, pid in self.joints.items()}
            apart = max(abs(complex(modes.joints[name][index + (k,)]) - z)
                        for name, z in sketch.items())
            angle = float(modes.x[index + (k, self.group.eliminated)])
            rows.append(SketchMode(angle if abs(angle) > 1e-12 else 0.0, points,
                                   float(modes.margin[index + (k,)]),
                                   int(modes.det_sign[index + (k,)]), apart))
        nearest = min(range(count), key=lambda k: rows[k].apart, default=None)
        return [replace(row, drawn=k == nearest) for k, row in enumerate(rows)]

    @property
    def exists(self) -> np.ndarray:
        """True where the drawn mode assembles (margin ≥ δ)."""
        return self.follow.exists

    @property
    def margin(self) -> np.ndarray:
        """The Hadamard margin of the constraint lines (negative in a gap)."""
        return self.follow.margin

    @property
    def reason(self) -> np.ndarray:
        """0, 7, 8 or 9 at each position."""
        return self.follow.reason


@dataclass(frozen=True, slots=True)
class SketchMode:
    """One real assembly mode at the sketch: the angle θ of the eliminated link from the
    drawing (rad), the internal joints by pair id, the margin, the sign of det J, the
    largest distance of a joint from its drawn point, and whether it is the drawn mode."""

    angle: float
    joints: dict[PairId, complex]
    margin: float
    det_sign: int
    apart: float
    drawn: bool = False


# ------------------------------------------------------------------------- sketch rules


def _problem(build: Builder, label: str, code: str, **data: str) -> None:
    build.problem(f"geometry ({label})", f"higher.sketch.{code}", group=label, **data)


def _column(label: str, name: str) -> str:
    return f"{label}.{name}"


def _sketched(layout: Layout, frames: dict[LinkId, tuple[complex, float]],
              driven: str | None = None) -> Sketched:
    first = layout.links[0]
    return Sketched(1, frames[first], frames[first], layout=layout, frames=frames,
                    driven=driven)


def _bodies(group: AssurGroup) -> Callable[[LinkId], LinkId]:
    """Each link of the group as a body: an actuator's members (cylinder, rod, welded by the
    frozen driven pair) as its first member."""
    members = tuple(group.composite or ())
    return lambda link: members[0] if link in members else link


def _actuator_refused(build: Builder, group: AssurGroup, label: str, code: str,
                      **data: str) -> None:
    members = ", ".join(map(str, group.composite or ()))
    _problem(build, label, code, members=members, **data)


def sketch_triad(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    """The sketch rule of a triad: drawn internal points, external anchors, block guides.

    Parameters
    ----------
    build : Builder
        The model being built from the sketch (parameters, frames, problems).
    group : AssurGroup
        The triad as structure found it (a bar, if any, is solved first).
    label : str
        Its label, the prefix of its parameters (``"III(4,5,6,7)"``).

    Returns
    -------
    Sketched or None
        Its :class:`Layout` and the frames of its links; None after recording a problem (two
        or three leashes with two sliders, which fix the base's rotation more than once and
        its position not at all; a P–P leash on parallel guides; an actuator that is the
        base, or a leash other than a bar).

    Notes
    -----
    A prismatic pair makes its two links turn together and slide along the guide's
    direction, whichever of them carries the guide: a block's guide on the leash (a slotted
    leash on a block or pin of the known link or of the base) gives the same equations as
    on the other link, and is taken as drawn on the other link here; the slider is written
    with the table's carrier (:func:`solve_triad`).

    A linear actuator (cylinder and rod, their driven prismatic pair frozen) may be a bar
    leash, hinged at both ends: its length is the input, and both members get the leash's
    frame (its ``driven`` name, ``leash1``…).
    """
    pairs = build.topo.pairs
    body = _bodies(group)
    count = Counter(body(link) for pid in group.internal for link in pairs[pid].links)
    base = next(link for link, n in count.items() if n == 3)
    if group.composite and base == body(group.composite[0]):
        _actuator_refused(build, group, label, "actuator")
        return None
    rows = []
    for ext, leash, known in group.external:
        inner = next(p for p in group.internal
                     if body(leash) in {body(link) for link in pairs[p].links})
        kind = Leash.of(pairs[inner].type.value == "P", pairs[ext].type.value == "P")
        if leash in (group.composite or ()) and not kind.bar:
            _actuator_refused(build, group, label, "actuator_slider", kind=kind.text)
            return None
        rows.append(_Leg(kind, leash, inner, ext, known))
    rows.sort(key=lambda row: (not row.kind.bar, row.kind is Leash.PP))
    kinds = [row.kind for row in rows]
    if kinds.count(Leash.PP) > 1:
        _problem(build, label, "leashes", found=", ".join(k.text for k in kinds))
        return None
    frames: dict[LinkId, tuple[complex, float]] = {}
    anchors: list[Anchor | None] = []
    guides: list[Guide | None] = []
    drawn: list[complex] = []
    for kind, leash, inner, ext, known in rows:
        if kind.slides[1]:  # on a guide of the known link
            point, theta = build.point(pairs[inner]), build.direction(pairs[ext])
            line = build.point(pairs[ext]) if kind is Leash.PP else point
            if kind is Leash.PP:
                own = build.direction(pairs[inner])
                if abs(math.sin(own - theta)) < 1e-6:
                    _problem(build, label, "pp_parallel", pair=str(ext))
                    return None
                build.put(label, f"beta_{inner}", math.degrees(own))
            guides.append(build.guide(pairs[ext], known, line, theta, label,
                                      (f"x_{ext}", f"y_{ext}", f"beta_{ext}", None), None))
            anchors.append(None)
            frames[leash] = (point, theta)
        else:
            hinge = build.point(pairs[ext])
            anchors.append(build.attachment(known, hinge, label, (f"x_{ext}", f"y_{ext}")))
            guides.append(None)
            if kind is Leash.RR:
                point = build.point(pairs[inner])
                frames[leash] = (hinge, cmath.phase(point - hinge))
            else:
                point, theta = hinge, build.direction(pairs[inner])
                build.put(label, f"beta_{inner}", math.degrees(theta))
                frames[leash] = (hinge, theta)
        build.put(label, f"x_{inner}", point.real)
        build.put(label, f"y_{inner}", point.imag)
        drawn.append(point)
    frames[base] = (drawn[0], cmath.phase(drawn[1] - drawn[0]))
    layout = Layout((base, *(row.leash for row in rows)), TRIAD_LINKS,
                    tuple(row.inner for row in rows), tuple(row.external for row in rows),
                    tuple(kinds), tuple(anchors), tuple(guides))
    driven = next((k for k, row in enumerate(rows) if row.leash in (group.composite or ())),
                  None)
    if driven is not None:
        frames.update({member: frames[rows[driven].leash] for member in group.composite or ()})
    return _sketched(layout, frames, None if driven is None else TRIAD_LINKS[driven + 1])


def sketch_class_iv(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    """The sketch rule of the class IV group: drawn C, D, E, F, the guides of its prismatic
    internal pairs, the anchors of hinged external pairs and the guides of prismatic ones.

    Parameters
    ----------
    build : Builder
        The model being built from the sketch.
    group : AssurGroup
        The group as structure found it.
    label : str
        Its label (``"IV(2,3,4,5)"``).

    Returns
    -------
    Sketched or None
        Its :class:`Layout` and link frames; None after recording a problem (a form that is
        not kinematically determinate although 3n − 2p = 0, :func:`_class_iv_refusals`; an
        actuator that is a or c, or a coupler with a prismatic pair at an end). An actuator
        that is the coupler b or d (hinged at both ends) gives its members the coupler's frame
        (its ``driven`` name).

    Notes
    -----
    A prismatic internal pair records ``beta_<pair>``, the absolute direction of its guide at
    the reference position (degrees), beside its drawn point. A prismatic pair gives the same
    equation whichever of its links carries the guide, so the guide of an external prismatic
    pair is built on the known link even where the table puts it on the group's link; the
    slider is written with the table's carrier (:func:`solve_class_iv`).
    """
    pairs = build.topo.pairs
    body = _bodies(group)
    (h_a, a, known_a), (h_c, c, known_c) = group.external
    if group.composite and body(group.composite[0]) in (body(a), body(c)):
        _actuator_refused(build, group, label, "actuator")
        return None

    def between(x: LinkId, y: LinkId | None = None) -> list[PairId]:
        return [p for p in group.internal if body(x) in (ends := {body(n) for n in pairs[p].links})
                and (y is None or body(y) in ends)]

    p_c, p_f = between(a)
    b = next(link for link in pairs[p_c].links if link != a)
    p_d = between(b, c)[0]
    p_e = next(p for p in between(c) if p != p_d)
    d = next(link for link in pairs[p_e].links if link != c)
    internal = dict(zip(CLASS_IV_JOINTS, (p_c, p_d, p_e, p_f), strict=True))
    driven = next((name for name, link in (("b", b), ("d", d))
                   if link in (group.composite or ())), None)
    ends = {"b": ("C", "D"), "d": ("F", "E")}.get(str(driven), ())
    sliding = [str(internal[n]) for n in ends if pairs[internal[n]].type.value != "R"]
    if sliding:
        _actuator_refused(build, group, label, "actuator_coupled", pairs=", ".join(sliding))
        return None
    refusals = _class_iv_refusals(build, internal, (h_a, h_c), (a, b, c, d))
    for code, data in refusals:
        _problem(build, label, code, **data)
    if refusals:
        return None
    pts = {name: build.point(pairs[pid]) for name, pid in internal.items()}
    ha, hc = build.point(pairs[h_a]), build.point(pairs[h_c])
    anchors: list[Anchor | None] = []
    guides: list[Guide | None] = []
    for ext, known, hinge in ((h_a, known_a, ha), (h_c, known_c, hc)):
        if pairs[ext].type.value == "P":
            guides.append(build.guide(pairs[ext], known, hinge, build.direction(pairs[ext]),
                                      label, (f"x_{ext}", f"y_{ext}", f"beta_{ext}", None),
                                      None))
            anchors.append(None)
        else:
            anchors.append(build.attachment(known, hinge, label, (f"x_{ext}", f"y_{ext}")))
            guides.append(None)
    for name, pid in internal.items():
        build.put(label, f"x_{pid}", pts[name].real)
        build.put(label, f"y_{pid}", pts[name].imag)
        if pairs[pid].type.value == "P":
            build.put(label, f"beta_{pid}", math.degrees(build.direction(pairs[pid])))
    frames = {a: (ha, cmath.phase(pts["C"] - ha)), b: (pts["C"], cmath.phase(pts["D"] - pts["C"])),
              c: (hc, cmath.phase(pts["D"] - hc)), d: (pts["F"], cmath.phase(pts["E"] - pts["F"]))}
    layout = Layout((a, b, c, d), CLASS_IV_LINKS, (p_c, p_d, p_e, p_f), (h_a, h_c),
                    anchors=tuple(anchors), guides=tuple(guides))
    if driven is not None:
        frames.update({member: frames[b if driven == "b" else d]
                       for member in group.composite or ()})
    return _sketched(layout, frames, driven)


def actuator_ends(group: GroupModel) -> tuple[PairId, PairId]:
    """The two hinges of the bar that a linear actuator is (its length is the input): the
    hinge where its slider's point is taken (the RRR dyad's C, a triad leash's internal pair,
    D of the class IV coupler b, E of d), then the origin of the bar's frame (the dyad's or
    the leash's external hinge, C of b, F of d).

    Parameters
    ----------
    group : GroupModel
        A group whose ``driven`` is set.

    Returns
    -------
    tuple of two pair ids
    """
    layout = group.layout
    if layout is None:
        return group.pairs["C"], group.pairs["H_j" if group.driven == "j" else "H_i"]
    if not layout.leashes:  # a class IV coupler: b from C to D, d from F to E
        c, d, e, f = layout.internal
        return (d, c) if group.driven == "b" else (e, f)
    k = TRIAD_LINKS.index(str(group.driven)) - 1
    return layout.internal[k], layout.external[k]


def _class_iv_refusals(build: Builder, internal: dict[str, PairId],
                       external: tuple[PairId, PairId], links: tuple[LinkId, ...]
                       ) -> list[tuple[str, dict[str, str]]]:
    """The reasons a class IV group with prismatic pairs is not kinematically determinate.

    A coupler (b between C and D, d between F and E) whose two pairs both slide turns with a
    and with c: it only makes a and c turn together, one condition on their rotations, and
    fixes nothing of their relative position. Two such couplers give that condition twice
    and leave c a free translation against a; one such coupler beside two sliding external
    pairs (the rotations of a and c both fixed by the known links) puts its condition on the
    known links only and leaves the two slides one equation; and a coupler whose two guides
    are parallel as drawn keeps a free slide along them. Any other form that
    :attr:`ClassIVCoupled.determinate` rejects (a slide parallel to the guides of the
    couplers' prismatic pairs, which then enters neither equation) is named by its sliding
    pairs.

    Returns
    -------
    list of (code, data)
        Catalogue codes under ``higher.sketch.`` with their data; empty for a determinate form.
    """
    pairs = build.topo.pairs
    a, b, c, d = (str(link) for link in links)
    both = [(coupler, (internal[one], internal[two])) for coupler, one, two in
            ((b, "C", "D"), (d, "F", "E"))
            if all(pairs[internal[n]].type.value == "P" for n in (one, two))]
    refusals: list[tuple[str, dict[str, str]]] = []
    if len(both) == 2:
        refusals.append(("class_iv_couplers", {
            "pairs": ", ".join(str(p) for _, ps in both for p in ps), "a": a, "c": c}))
    elif both and all(pairs[p].type.value == "P" for p in external):
        coupler, ps = both[0]
        refusals.append(("class_iv_turns", {"link": coupler, "a": a, "c": c,
                                            "pairs": ", ".join(map(str, ps))}))
    for coupler, (one, two) in both:
        if abs(math.sin(build.direction(pairs[one]) - build.direction(pairs[two]))) < 1e-6:
            refusals.append(("class_iv_parallel", {"link": coupler,
                                                   "pairs": f"{one}, {two}"}))
    sliding = [pid for pid in (*internal.values(), *external) if pairs[pid].type.value == "P"]
    if refusals or all(pairs[pid].type.value == "R" for pid in internal.values()):
        return refusals

    def guide(pid: PairId) -> complex | None:
        return cmath.exp(1j * build.direction(pairs[pid])) if pid in sliding else None

    drawn = ClassIVCoupled(*(build.point(pairs[pid]) for pid in
                             (external[0], internal["C"], internal["F"], external[1],
                              internal["D"], internal["E"])),
                           *(guide(pid) for pid in (*external, *internal.values())))
    if not drawn.determinate:
        refusals.append(("class_iv_unfixed", {"pairs": ", ".join(map(str, sliding))}))
    return refusals


# ------------------------------------------------------------------------------ solvers

#: The known links evaluated at any crank angle: the analysis state of the earlier groups.
Known = Callable[[Any], "State"]


def _drawn(state: State, group: GroupModel, pid: PairId) -> Any:
    p = state.flat_value
    return p(_column(group.label, f"x_{pid}")) + 1j * p(_column(group.label, f"y_{pid}"))


@dataclass(frozen=True)
class _Actuator:
    """How a linear actuator that is a bar of the group enters its inputs: its drawn length
    (from the inputs at the sketch, the stroke's start q₀) and the inputs with the length q."""

    drawn: Callable[[Any], Any]
    put: Callable[[Any, Any], Any]


def _follow(state: State, group: GroupModel, q: Any, make: Callable[[Any], AnyGroup],
            inputs: Callable[[State], Any], actuator: _Actuator | None = None
            ) -> tuple[HigherSolution, Any, AnyGroup]:
    """Follow the group's drawn mode over q; also its inputs at the reference position and
    the group as solved. A triad with a P–P leash and no bar has one mode, placed at every
    position in closed form from the inputs at q (:func:`~assur.kinematics.higher.pinned.place`).
    With an ``actuator`` q is its length and the mode is followed along the model's stroke."""
    known = state.earlier(group)
    k0 = values(inputs(known(np.zeros(state.flat_shape))))
    phi = np.asarray(J.value(q), dtype=float)
    delta = np.reshape(state.delta(group), -1) if np.ndim(state.delta(group)) \
        else state.delta(group)
    solved = make(k0)
    if isinstance(solved, Triad) and solved.unique:
        return place(solved, k0, inputs(state), delta=delta), k0, solved
    if actuator is None:
        follow = follow_mode(solved, lambda angle: inputs(known(angle)), phi,
                             analogs=isinstance(q, Jet), delta=delta)
        return follow, k0, solved
    low, high = state.model.input_range
    follow = follow_mode(solved, lambda length: actuator.put(inputs(known(length)), length), phi,
                         analogs=isinstance(q, Jet), delta=delta,
                         stroke=Stroke(low, high, actuator.drawn(k0)))
    return follow, k0, solved


def _record(state: State, group: GroupModel, follow: HigherSolution, solved: AnyGroup,
            joints: dict[str, PairId], frames: dict[str, tuple[Any, float]]
            ) -> HigherGroupSolution:
    """Write the link frames into the state (origin, angle at the sketch + rotation)."""
    layout = group.layout
    assert layout is not None
    for link, name in zip(layout.links, layout.names, strict=True):
        origin, angle0 = frames[name]
        state.frames[link] = (origin, follow.rotations[name] + angle0)
    first = state.frames[layout.links[0]]
    return HigherGroupSolution(follow, solved, joints, first[0], first[1])


def _triad_inputs(group: GroupModel) -> Callable[[State], TriadInputs]:
    layout = group.layout
    assert layout is not None

    def inputs(known: State) -> TriadInputs:
        a: list[Any] = []
        u: list[Any] = []
        for anchor, guide in zip(layout.anchors, layout.guides, strict=True):
            if guide is not None:
                base, angle, _ = known.guide(guide)
                a.append(base)
                u.append(J.expi(angle))
            else:
                assert anchor is not None
                a.append(known.point(anchor))
                u.append(None)
        return TriadInputs((a[0], a[1], a[2]), (u[0], u[1], u[2]))

    return inputs


def solve_triad(state: State, group: GroupModel, q: Any) -> HigherGroupSolution:
    """Follow a triad's drawn mode over the positions q (its kind's solver).

    Parameters
    ----------
    state : State
        The analysis so far: the earlier groups solved at q; the triad's joints, sliders and
        link frames are written into it.
    group : GroupModel
        The triad's model (its :class:`Layout`).
    q : ndarray or Jet
        Crank rotations from the sketch (radians), or the lengths of an actuator that is a
        bar of the group (mm, over the model's stroke); a jet for the analogs.

    Returns
    -------
    HigherGroupSolution
        ``exists``, ``margin``, ``reason`` over q, the followed mode and the modes at the sketch.
    """
    layout = group.layout
    assert layout is not None
    base = [_drawn(state, group, pid) for pid in layout.internal]
    p = state.flat_value

    def guide(k0: TriadInputs, i: int, kind: Leash) -> Any:
        if kind.slides[1]:
            return k0.u[i]
        if kind is Leash.PR:
            return J.expi(p(_column(group.label, f"beta_{layout.internal[i]}")))
        return None

    def make(k0: TriadInputs) -> Triad:
        return Triad((layout.leashes[0], layout.leashes[1], layout.leashes[2]),
                     (base[0], base[1], base[2]), k0.a,
                     (guide(k0, 0, layout.leashes[0]), guide(k0, 1, layout.leashes[1]),
                      guide(k0, 2, layout.leashes[2])))

    driven = None if group.driven is None else TRIAD_LINKS.index(group.driven) - 1
    actuator = None if driven is None else _Actuator(
        lambda k0: np.abs(base[driven] - k0.a[driven]),
        lambda k, length: replace(k, lengths=tuple(length if i == driven else None
                                                   for i in range(3))))
    follow, k0, solved = _follow(state, group, q, make, _triad_inputs(group), actuator)
    theta = follow.rotations["base"]
    frames: dict[str, tuple[Any, float]] = {
        "base": (follow.joints["O"], _phase(base[1] - base[0]))}
    for i, (kind, inner, ext) in enumerate(zip(layout.leashes, layout.internal, layout.external,
                                               strict=True)):
        name = TRIAD_LINKS[i + 1]
        anchor, guide_k = layout.anchors[i], layout.guides[i]
        if kind is Leash.PP:
            assert guide_k is not None
            frames[name] = _pp_sliders(state, group, i, follow,
                                       _DrawnPP(base[i], k0.a[i], k0.u[i]),
                                       guide_k)
            continue
        if guide_k is not None:  # R–P: a block hinged to the base on a known link's guide
            point = follow.joints[f"P{i + 1}"]
            line, angle, offset = state.guide(guide_k)
            state.joints[inner] = point
            _slide(state, ext, (layout.links[i + 1], point), (guide_k.carrier, line), angle,
                   offset)
            frames[name] = (point, _phase(k0.u[i]))
            continue
        assert anchor is not None
        hinge = state.point(anchor)
        state.joints[ext] = hinge
        if kind is Leash.RR:
            state.joints[inner] = follow.joints[f"P{i + 1}"]
            frames[name] = (hinge, _phase(base[i] - k0.a[i]))
        else:  # P–R: a leash hinged to a known link, sliding along the base's guide
            angle0 = p(_column(group.label, f"beta_{inner}"))
            line = follow.joints["O"] + _col(base[i] - base[0]) * J.expi(theta)
            _slide(state, inner, (layout.links[i + 1], hinge), (layout.links[0], line),
                   theta + angle0, 0.0)
            frames[name] = (hinge, angle0)
    joints = {f"P{i + 1}": (ext if kind is Leash.PR else inner) for i, (kind, inner, ext) in
              enumerate(zip(layout.leashes, layout.internal, layout.external, strict=True))}
    solution = _record(state, group, follow, solved, joints, frames)
    _drive(state, group, q)
    return solution


def _pp_sliders(state: State, group: GroupModel, i: int, follow: HigherSolution,
                drawn: _DrawnPP, guide_k: Guide) -> tuple[Any, float]:
    """Write the two sliders of a P–P leash; its frame (origin, drawn angle).

    The leash turns with the base (θ); its point drawn at the internal pair, X⁰, runs on the
    base's guide, X = P_k + t·u_bE, and its point drawn at the external pair, Y⁰ (the known
    link's guide point at the reference position), on the known link's guide (Q, u_K):
    cross(u_K, X + (Y⁰ − X⁰)E − Q) = 0 gives t.
    """
    layout = group.layout
    assert layout is not None
    inner, ext = layout.internal[i], layout.external[i]
    leash = layout.links[i + 1]
    theta = follow.rotations["base"]
    turn = J.expi(theta)
    own = state.flat_value(_column(group.label, f"beta_{inner}"))
    along = J.expi(theta + own)
    line, angle, offset = state.guide(guide_k)
    known = J.expi(angle)
    arm = _col(drawn.outer - drawn.inner) * turn
    start = follow.joints[f"P{i + 1}"]
    t = -J.cross(known, start + arm - line) / J.cross(known, along)
    point = start + t * along
    outer = point + arm
    state.joints[inner], state.joints[ext] = point, outer
    _slide(state, inner, (leash, point), (layout.links[0], start), theta + own, 0.0)
    _slide(state, ext, (leash, outer), (guide_k.carrier, line), angle, offset)
    return point, _phase(drawn.guide)


def _slide(state: State, pair: PairId, pin: tuple[LinkId, Any], slot: tuple[LinkId, Any],
           angle: Any, offset: Any) -> Any:
    """Write the slider of a prismatic pair from its two links and their coincident points;
    return the slider's point (on the link that does not carry the guide).

    ``slot`` is the link taken as the guide's carrier in the equations with the guide's
    point on it, ``pin`` the other link with its point on the guide line. A prismatic pair
    makes both links turn together and slide along the guide, whichever carries it; where
    the table puts the guide on the ``pin`` link (a slotted leash), the two swap, so that
    the slider's base point is fixed on its carrier and s = (point − base)·u(angle).
    """
    if state.model.pair_links[pair][2] == pin[0]:
        pin, slot = slot, pin
    (slider, point), (carrier, base) = pin, slot
    state.slider(pair, carrier, slider, point, J.dot(point - base, J.expi(angle)), base, angle,
                 offset)
    return point


def solve_class_iv(state: State, group: GroupModel, q: Any) -> HigherGroupSolution:
    """Follow a class IV group's drawn mode over the positions q (its kind's solver).

    Parameters
    ----------
    state : State
        The analysis so far; the group's joints, the sliders of its prismatic pairs and its
        link frames are written into it.
    group : GroupModel
        The group's model (its :class:`Layout`).
    q : ndarray or Jet
        Crank rotations from the sketch (radians), or the lengths of an actuator that is a
        bar of the group (mm, over the model's stroke); a jet for the analogs.

    Returns
    -------
    HigherGroupSolution
        As :func:`solve_triad`.

    Notes
    -----
    Every form is a :class:`ClassIVCoupled`, whose joints give the point of each link drawn at a
    sliding pair. A prismatic pair's joint is its point on the link that does not carry the
    guide in the table, and its slider has the table's carrier (:func:`_slide`).
    """
    layout = group.layout
    assert layout is not None
    p = state.flat_value
    pts = dict(zip(CLASS_IV_JOINTS, (_drawn(state, group, pid) for pid in layout.internal),
                   strict=True))
    betas = {name: p(_column(group.label, f"beta_{pid}"))
             for name, pid in zip(CLASS_IV_JOINTS, layout.internal, strict=True)
             if state.model.pair_links[pid][0] == "P"}

    def external(known: State, side: int) -> tuple[Any, Any]:
        """The hinge, or the guide's point and direction, of one external pair."""
        anchor, guide = layout.anchors[side], layout.guides[side]
        if guide is not None:
            base, angle, _ = known.guide(guide)
            return base, J.expi(angle)
        assert anchor is not None
        return known.point(anchor), None

    def inputs(known: State) -> ClassIVInputs:
        (h_a, u_a), (h_c, u_c) = external(known, 0), external(known, 1)
        return ClassIVInputs(h_a, h_c, u_a, u_c)

    def make(k0: ClassIVInputs) -> AnyGroup:
        drawn = (k0.h_a, pts["C"], pts["F"], k0.h_c, pts["D"], pts["E"], k0.u_a, k0.u_c)
        w = {name: J.expi(beta) for name, beta in betas.items()}
        return ClassIVCoupled(*drawn, w_c=w.get("C"), w_d=w.get("D"), w_e=w.get("E"),
                              w_f=w.get("F"))

    actuator = None if group.driven is None else _Actuator(
        lambda k0: np.abs(pts["C"] - pts["D"]) if group.driven == "b" else
        np.abs(pts["F"] - pts["E"]),
        lambda k, length: replace(k, **{f"l_{group.driven}": length}))
    follow, k0, solved = _follow(state, group, q, make, inputs, actuator)
    j = follow.joints
    origins = []
    for side, name in enumerate(("Ha", "Hc")):
        anchor, guide = layout.anchors[side], layout.guides[side]
        ext, link = layout.external[side], layout.links[2 * side]
        if guide is None:
            assert anchor is not None
            origins.append(state.point(anchor))
            state.joints[ext] = origins[-1]
        else:  # the link slides on the known link's guide, its point drawn there on the line
            line, angle, offset = state.guide(guide)
            origins.append(j[name])
            state.joints[ext] = _slide(state, ext, (link, j[name]), (guide.carrier, line),
                                       angle, offset)
    a, b, c, d = layout.links
    sides = {"C": (a, b, "Ca"), "D": (c, b, "Dc"), "E": (c, d, "Ec"), "F": (a, d, "Fa")}
    for name, pid in zip(CLASS_IV_JOINTS, layout.internal, strict=True):
        if name not in betas:
            state.joints[pid] = j[name]
            continue
        link, coupler, own = sides[name]  # the guide turns with the coupler and with link
        angle = _col(betas[name]) + follow.rotations["b" if coupler == b else "d"]
        state.joints[pid] = _slide(state, pid, (coupler, j[name]), (link, j[own]), angle, 0.0)
    frames: dict[str, tuple[Any, float]] = {
        "a": (origins[0], _phase(pts["C"] - k0.h_a)), "b": (j["C"], _phase(pts["D"] - pts["C"])),
        "c": (origins[1], _phase(pts["D"] - k0.h_c)), "d": (j["F"], _phase(pts["E"] - pts["F"]))}
    joints = dict(zip(CLASS_IV_JOINTS, layout.internal, strict=True))
    joints.update({name: ext for name, ext, guide in zip(("Ha", "Hc"), layout.external,
                                                          layout.guides, strict=True)
                   if guide is not None})  # a sliding point moves from mode to mode
    solution = _record(state, group, follow, solved, joints, frames)
    _drive(state, group, q)
    return solution


def _drive(state: State, group: GroupModel, q: Any) -> None:
    """The frames of an actuator's members and its driven pair, once the group's own frames
    are written (nothing for a group without an actuator)."""
    if group.driven is None:
        return
    layout = group.layout
    assert layout is not None
    point = actuator_ends(group)[0]
    bar = layout.links[layout.names.index(group.driven)]
    state.actuator(group, state.frames[bar], state.joints[point], q)


def _col(z: Any) -> Any:
    """A drawn value (shape () or (D,)) as a column against the positions."""
    return np.asarray(z)[..., None] if np.ndim(z) else z


def _phase(z: Any) -> Any:
    """The angle of a drawn vector, as a column against the positions."""
    return _col(np.angle(np.asarray(z)))


# ---------------------------------------------------------------------------- shortfall


def shortfall_higher(group: GroupModel, at: ShortfallAt) -> tuple[float, str]:
    """How far the group is from assembling at the worst position of a failure interval.

    In a gap (margin < 0) the margin is −|Im θ| of the nearest complex root: that angle in
    degrees; inside the tolerance band (0 ≤ margin < δ) the shortfall is 0.

    Parameters
    ----------
    group : GroupModel
        The group (unused: the rule is the same for both kinds).
    at : ShortfallAt
        What the existence check reads at the worst position.

    Returns
    -------
    shortfall : float
        Degrees.
    unit : str
        ``"deg"``.
    """
    return float(math.degrees(max(-at.margin, 0.0))), "deg"
