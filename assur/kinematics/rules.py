"""The kinematics of each kind of group: its solver, sketch rule, shortfall, pressure angle.

The registry of kinds (:mod:`assur.kinds`) says what a kind is; this module says what the
kinematics does with it. :func:`rules_of` gives a kind's :class:`KindRules`:

- ``solve`` — solve the group over the positions, writing its joints, sliders and link
  frames into the analysis state (:class:`~assur.kinematics.analysis.State`);
- ``sketch`` — derive the group's parameters from the joints of a sketch
  (:class:`~assur.kinematics.build.Builder`), returning what the builder needs
  (:class:`~assur.kinematics.model.Sketched`); None for the input group, which the builder
  sketches itself;
- ``shortfall`` — the violated existence condition at the worst position of a failure
  interval, in mm or degrees (:class:`ShortfallAt`); None for the input group, which always
  assembles;
- ``pressure`` — the pressure angle at the internal hinge C, for the kinds that have one.

The closed forms of L0 and the dyads L1–L5 are here; the triad and the class IV group follow
their drawn assembly mode (:mod:`assur.kinematics.higher.kind`), a module loaded only when a
mechanism has such a group. The analysis, the builder, the existence check and the
transmission look a kind's rules up here; none of them tests ``kind == …``.

Examples
--------
>>> from assur.kinds import kind_of
>>> rules_of(kind_of(1)).pressure is not None, rules_of(kind_of(3)).pressure is None
(True, True)
>>> rules_of(kind_of(0)).sketch is None  # the builder sketches the crank itself
True
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.kinds import KINDS, GroupKind, KindCode
from assur.kinematics import dyads
from assur.kinematics import jets as J
from assur.kinematics.dyads import DyadSolution
from assur.kinematics.model import Sketched
from assur.model import joint_key
from assur.typing import Value

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.analysis import GroupSolution, State
    from assur.kinematics.build import Builder
    from assur.kinematics.model import Anchor, GroupModel
    from assur.model import LinkId, Pair
    from assur.structure.classification import AssurGroup

__all__ = [
    "GroupSolver",
    "KindRules",
    "PressureRule",
    "ShortfallAt",
    "ShortfallRule",
    "SketchRule",
    "given",
    "rules_of",
]

#: Solve a group at the positions q (crank angles or actuator lengths, plain or jets),
#: writing its joints, sliders and link frames into the analysis state.
GroupSolver = Callable[["State", "GroupModel", Value], "GroupSolution"]
#: Derive a group's parameters from a sketch (its label is the prefix of their names); None
#: after recording a problem in the builder.
SketchRule = Callable[["Builder", "AssurGroup", str], "Sketched | None"]
#: The violated condition at the worst position of a failure interval and its unit
#: (``"mm"`` or ``"deg"``).
ShortfallRule = Callable[["GroupModel", "ShortfallAt"], tuple[float, str]]
#: The rods among the group's binary links and the pressure angle at C over the positions,
#: from the angles of links i and j.
PressureRule = Callable[["GroupModel", "set[LinkId]", np.ndarray, np.ndarray],
                        tuple["tuple[LinkId, ...]", np.ndarray]]


@dataclass(frozen=True, slots=True)
class KindRules:
    """What the kinematics does with a group of one kind.

    Attributes
    ----------
    solve : GroupSolver
        Solve the group over the positions.
    sketch : SketchRule or None
        Derive its parameters from a sketch; None for the input group (the builder sketches
        the crank itself).
    shortfall : ShortfallRule or None
        The violated existence condition; None for the input group (it always assembles).
    pressure : PressureRule or None
        The pressure angle at C, for the dyads with a rod hinged there (L1, L2).
    """

    solve: GroupSolver
    sketch: SketchRule | None = None
    shortfall: ShortfallRule | None = None
    pressure: PressureRule | None = None


@dataclass(frozen=True, slots=True)
class ShortfallAt:
    """What a shortfall rule reads at the worst position of a failure interval: the input
    coordinate, the margin there and the group's δ, the model's parameter values (program
    units) and the point of a role's joint (``"H_i"``, ``"H_j"``)."""

    q: float
    margin: float
    delta: float
    value: Callable[[str], Any]
    hinge: Callable[[str], complex]


#: The columns of the external hinges H_i and H_j (the same in every dyad kind that has them).
_HI, _HJ = KINDS[1].hinges["i"], KINDS[1].hinges["j"]


# ------------------------------------------------------------------------------ solvers


def given(x: Value | None) -> Value:
    """A solver output that the group's kind always has (a dyad's link j, its slider)."""
    assert x is not None
    return x


def _solve_input(state: State, group: GroupModel, q: Value) -> DyadSolution:
    if group.guide_i is not None:
        return _solve_slide(state, group, q)
    p, col = state.p, group.column
    angle = p(col("phi_1_0")) + state.model.direction * q
    pivot = p(col("x_O1")) + 1j * p(col("y_O1"))
    sol = dyads.solve_input(pivot, p(col("l_1")), angle)
    state.joints[group.pairs["H_i"]] = sol.origin_i
    state.rotors[group.i] = (sol.c - sol.origin_i) / p(col("l_1"))
    return sol


def _solve_slide(state: State, group: GroupModel, q: Value) -> DyadSolution:
    """A slider driven along a frame guide: q its displacement from the sketched point."""
    assert group.guide_i is not None
    base, theta, _ = state.guide(group.guide_i)
    sol = dyads.solve_slide(base, theta, q)
    state.rotors[group.i] = J.expi(theta)
    state.slider(group.pairs["P_i"], group.guide_i.carrier, group.i, sol.c, q, base, theta, 0.0)
    return sol


def _solve_rrr(state: State, group: GroupModel, q: Value) -> DyadSolution:
    p, col, roles = state.p, group.column, group.pairs
    assert group.hinge_i is not None and group.hinge_j is not None and group.j is not None
    h_i, h_j = state.point(group.hinge_i), state.point(group.hinge_j)
    l_i = q if group.driven == "i" else p(col("l_i"))
    l_j = q if group.driven == "j" else p(col("l_j"))
    sol = dyads.solve_rrr(h_i, h_j, l_i, l_j, group.sigma, state.delta(group))
    state.joints.update({roles["H_i"]: h_i, roles["H_j"]: h_j, roles["C"]: sol.c})
    if group.driven is not None:
        frame = (sol.origin_i, sol.angle_i) if group.driven == "i" else \
            (given(sol.origin_j), given(sol.angle_j))
        state.actuator(group, frame, sol.c, q)
    else:
        state.rotors[group.i] = (sol.c - sol.origin_i) / p(col("l_i"))
        state.rotors[group.j] = (sol.c - given(sol.origin_j)) / p(col("l_j"))
    return sol


def _solve_rrp(state: State, group: GroupModel, q: Value) -> DyadSolution:
    p, col, roles = state.p, group.column, group.pairs
    assert group.hinge_j is not None and group.guide_i is not None and group.j is not None
    h_j = state.point(group.hinge_j)
    base, theta, e = state.guide(group.guide_i)
    sol = dyads.solve_rrp(h_j, base, theta, e, p(col("l_j")), group.sigma, state.delta(group))
    state.joints.update({roles["C"]: sol.c, roles["H_j"]: h_j})
    state.slider(roles["P_i"], group.guide_i.carrier, group.i, sol.c, given(sol.s_i), base,
                 sol.angle_i, e)
    state.rotors[group.j] = (sol.c - given(sol.origin_j)) / p(col("l_j"))
    return sol


def _solve_rpr(state: State, group: GroupModel, q: Value) -> DyadSolution:
    p, col, roles = state.p, group.column, group.pairs
    assert group.hinge_i is not None and group.hinge_j is not None and group.j is not None
    h_i, h_j = state.point(group.hinge_i), state.point(group.hinge_j)
    h = p(col("d"))
    sol = dyads.solve_rpr(h_i, h_j, h, group.sigma, state.delta(group))
    state.joints.update({roles["H_i"]: h_i, roles["H_j"]: h_j})
    state.slider(roles["P_c"], group.i, group.j, h_j, given(sol.s_i), sol.origin_i, sol.angle_i, h)
    r = given(sol.origin_j) - sol.origin_i
    axis = r * (sol.s_i - 1j * p(col("d"))) / J.dot(r, r)
    state.rotors[group.i] = state.rotors[group.j] = axis
    return sol


def _solve_prp(state: State, group: GroupModel, q: Value) -> DyadSolution:
    roles = group.pairs
    assert group.guide_i is not None and group.guide_j is not None and group.j is not None
    a, theta_i, e_i = state.guide(group.guide_i)
    b, theta_j, e_j = state.guide(group.guide_j)
    sol = dyads.solve_prp(a, theta_i, e_i, b, theta_j, e_j, state.delta(group))
    state.joints[roles["C"]] = sol.c
    state.slider(roles["P_i"], group.guide_i.carrier, group.i, sol.c, given(sol.s_i), a,
                 sol.angle_i, e_i)
    state.slider(roles["P_j"], group.guide_j.carrier, group.j, sol.c, given(sol.s_j), b,
                 given(sol.angle_j), e_j)
    return sol


def _solve_rpp(state: State, group: GroupModel, q: Value) -> DyadSolution:
    roles = group.pairs
    assert group.hinge_j is not None and group.guide_i is not None and group.j is not None
    h_j = state.point(group.hinge_j)
    a, theta_s, e = state.guide(group.guide_i)
    sol = dyads.solve_rpp(h_j, state.p(group.column("gamma")), a, theta_s, e,
                          state.delta(group))
    state.joints[roles["H_j"]] = h_j
    state.slider(roles["P_i"], group.guide_i.carrier, group.i, sol.c, given(sol.s_i), a,
                 sol.angle_i, e)
    state.slider(roles["P_c"], group.j, group.i, sol.c, given(sol.s_j), given(sol.origin_j),
                 given(sol.angle_j), 0.0)
    return sol


# ------------------------------------------------------------------------ sketch builders


def _ends(group: AssurGroup) -> tuple[LinkId, LinkId]:
    """The known links i−1 and j−1 that a dyad attaches to."""
    assert group.i_minus_1 is not None and group.j_minus_1 is not None
    return group.i_minus_1, group.j_minus_1


def _hinges(build: Builder, group: AssurGroup, pairs: tuple[Pair, Pair, Pair],
            label: str) -> tuple[complex, complex, Anchor, Anchor]:
    """The sketched external hinges H_i, H_j of a dyad and their anchors."""
    prev_i, prev_j = _ends(group)
    hi, hj = build.point(pairs[0]), build.point(pairs[1])
    return (hi, hj, build.attachment(prev_i, hi, label, _HI),
            build.attachment(prev_j, hj, label, _HJ))


def _sketch_rrr(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    c = build.point(pairs[2])
    hi, hj, anchor_i, anchor_j = _hinges(build, group, pairs, label)
    build.put(label, "l_i", abs(c - hi))
    build.put(label, "l_j", abs(c - hj))
    sigma = _sign(_cross(hj - hi, c - hi))
    return Sketched(sigma, (hi, cmath.phase(c - hi)), (hj, cmath.phase(c - hj)),
                    hinge_i=anchor_i, hinge_j=anchor_j,
                    driven=build.driven_side(group) if group.composite else None)


def _sketch_rrp(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    pi, pj, pc = pairs
    prev_i, prev_j = _ends(group)
    c, hj, base, theta = build.point(pc), build.point(pj), build.point(pi), build.direction(pi)
    anchor_j = build.attachment(prev_j, hj, label, _HJ)
    build.put(label, "l_j", abs(c - hj))
    guide = build.guide(pi, prev_i, base, theta, label, KINDS[2].guides["i"], c)
    sigma = _sign(_dot(c - hj, cmath.exp(1j * theta)))
    return Sketched(sigma, (c, theta), (hj, cmath.phase(c - hj)), hinge_j=anchor_j,
                    guide_i=guide)


def _sketch_rpr(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    theta = build.direction(pairs[2])
    hi, hj, anchor_i, anchor_j = _hinges(build, group, pairs, label)
    axis = cmath.exp(1j * theta)
    build.put(label, "d", _cross(axis, hj - hi))
    sigma = _sign(_dot(axis, hj - hi))
    return Sketched(sigma, (hi, theta), (hj, theta), hinge_i=anchor_i, hinge_j=anchor_j)


def _sketch_prp(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    pi, pj, pc = pairs
    prev_i, prev_j = _ends(group)
    c = build.point(pc)
    a, ti, b, tj = build.point(pi), build.direction(pi), build.point(pj), build.direction(pj)
    gi = build.guide(pi, prev_i, a, ti, label, KINDS[4].guides["i"], c)
    gj = build.guide(pj, prev_j, b, tj, label, KINDS[4].guides["j"], c)
    return Sketched(1, (c, ti), (c, tj), guide_i=gi, guide_j=gj)


def _sketch_rpp(build: Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    pi, pj, pc = pairs
    prev_i, prev_j = _ends(group)
    hj, a, ts, tt = build.point(pj), build.point(pi), build.direction(pi), build.direction(pc)
    us, ut = cmath.exp(1j * ts), cmath.exp(1j * tt)
    denominator = _cross(ut, us)
    if abs(denominator) < 1e-12:
        build.problem(f"geometry {joint_key(pc)!r} 'direction'", "sketch.parallel_guides",
                      group=label)
        return None
    c = hj + _cross(a - hj, us) / denominator * ut
    anchor_j = build.attachment(prev_j, hj, label, _HJ)
    build.put(label, "gamma", math.degrees(_wrap(tt - ts)))
    gi = build.guide(pi, prev_i, a, ts, label, KINDS[5].guides["i"], c)
    return Sketched(1, (c, ts), (hj, tt), hinge_j=anchor_j, guide_i=gi)


# ------------------------------------------------------------------------- shortfalls


def _shortfall_rrr(group: GroupModel, at: ShortfallAt) -> tuple[float, str]:
    d = abs(at.hinge("H_j") - at.hinge("H_i"))
    l_i = at.q if group.driven == "i" else float(at.value(group.column("l_i")))
    l_j = at.q if group.driven == "j" else float(at.value(group.column("l_j")))
    return float(max(d - (l_i + l_j), abs(l_i - l_j) - d)), "mm"


def _shortfall_rrp(group: GroupModel, at: ShortfallAt) -> tuple[float, str]:
    return float(-at.margin * float(at.value(group.column("l_j")))), "mm"


def _shortfall_rpr(group: GroupModel, at: ShortfallAt) -> tuple[float, str]:
    return float(-at.margin * abs(at.hinge("H_j") - at.hinge("H_i"))), "mm"


def _shortfall_guides(group: GroupModel, at: ShortfallAt) -> tuple[float, str]:
    angle = math.degrees(math.asin(min(max(at.margin, 0.0), 1.0)))
    return float(math.degrees(math.asin(min(at.delta, 1.0))) - angle), "deg"


# ---------------------------------------------------------------------- pressure angles


def _pressure_rrr(group: GroupModel, binary: set[LinkId], phi_i: np.ndarray,
                  phi_j: np.ndarray) -> tuple[tuple[LinkId, ...], np.ndarray]:
    rods = tuple(link for link in (group.i, group.j) if link in binary)
    return rods, np.arccos(np.minimum(np.abs(np.sin(phi_i - phi_j)), 1.0))


def _pressure_rrp(group: GroupModel, binary: set[LinkId], phi_i: np.ndarray,
                  phi_j: np.ndarray) -> tuple[tuple[LinkId, ...], np.ndarray]:
    rods = (group.j,) if group.j in binary else ()
    return rods, np.arccos(np.minimum(np.abs(np.cos(phi_j - phi_i)), 1.0))


# ------------------------------------------------------------------------------ helpers


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _cross(a: complex, b: complex) -> float:
    return (a.conjugate() * b).imag


def _dot(a: complex, b: complex) -> float:
    return (a.conjugate() * b).real


def _sign(value: float) -> int:
    return -1 if value < 0 else 1


# ----------------------------------------------------------------------------- registry

#: The rules of the input group and the dyads, by kind code.
_DYADS: Mapping[KindCode, KindRules] = {
    "L0": KindRules(_solve_input),
    "L1": KindRules(_solve_rrr, _sketch_rrr, _shortfall_rrr, _pressure_rrr),
    "L2": KindRules(_solve_rrp, _sketch_rrp, _shortfall_rrp, _pressure_rrp),
    "L3": KindRules(_solve_rpr, _sketch_rpr, _shortfall_rpr),
    "L4": KindRules(_solve_prp, _sketch_prp, _shortfall_guides),
    "L5": KindRules(_solve_rpp, _sketch_rpp, _shortfall_guides),
}


@cache
def _higher() -> Mapping[KindCode, KindRules]:
    """The rules of the triad and the class IV group (their module loaded on first use)."""
    from assur.kinematics.higher import kind as higher

    return {"III": KindRules(higher.solve_triad, higher.sketch_triad, higher.shortfall_higher),
            "IV": KindRules(higher.solve_class_iv, higher.sketch_class_iv,
                            higher.shortfall_higher)}


def rules_of(kind: GroupKind) -> KindRules:
    """The kinematics of a kind of group.

    Parameters
    ----------
    kind : GroupKind
        An entry of :data:`assur.kinds.KINDS` or :data:`assur.kinds.HIGHER`.

    Returns
    -------
    KindRules
        Its solver, sketch rule, shortfall and pressure angle (None where the kind has none).
    """
    rules = _DYADS.get(kind.code)
    return rules if rules is not None else _higher()[kind.code]
