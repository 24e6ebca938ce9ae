"""The kinds of groups: everything a kind means, declared once.

A :class:`GroupKind` holds what the program knows of one kind of group: its names in every
language (catalogue codes), the pair pattern that classification recognises, the roles of
its pairs, the parameter columns of ``method.md`` §4.3, the assembly variants and output code
of the identification table, the pairs rebuilt from an identification row, the existence
condition, and the per-kind computations of the kinematics (solver call, sketch builder,
shortfall, pressure angle). Structure, identification, kinematics, existence, transmission,
schemes and reports look a kind up here; none of them tests ``kind == …``.

The registry :data:`KINDS` maps the DGTU number L (0 for the input group, 1–5 for the dyads)
to its record; :data:`HIGHER` adds, by code, the class III triad and the class IV group of
order 2 (their rules live in :mod:`assur.kinematics.higher.kind`).

Adding a kind is one :class:`GroupKind` entry. Adding a per-kind computation is one field of
:class:`GroupKind` and one function per kind, named ``_<computation>_<kind>`` below, given to
that kind's entry (kinds that lack it get None, and the caller skips them).

Examples
--------
>>> kind = KINDS[2]
>>> kind.code, kind.pairs, kind.columns[:3]
('L2', 'RRP', ('x_Hj', 'y_Hj', 'l_j'))
>>> kind.title("ru")
'двухповодковая группа 2-го вида (ВВП)'
>>> kind_of_pattern("R", ("P", "R")).number
2
"""

from __future__ import annotations

import cmath
import importlib
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.kinematics import dyads
from assur.kinematics import jets as J
from assur.kinematics.dyads import Value
from assur.model import joint_key
from assur.text import render

if TYPE_CHECKING:  # pragma: no cover
    from assur.forces.groups import Loads, Solved
    from assur.kinematics.analysis import _State
    from assur.kinematics.build import _Builder
    from assur.kinematics.dyads import DyadSolution
    from assur.kinematics.higher.kind import HigherGroupSolution, Layout
    from assur.kinematics.model import Anchor, GroupModel, Guide
    from assur.model import LinkId, Pair
    from assur.structure.classification import AssurGroup

__all__ = [
    "HIGHER",
    "KINDS",
    "GroupKind",
    "Sketched",
    "kind_of",
    "kind_of_class",
    "kind_of_pattern",
]

#: Columns (x, y) of an external hinge H_i / H_j.
HingeColumns = tuple[str, str]
#: Columns (base x, base y, direction β, offset e or None) of an external guide.
GuideColumns = tuple[str, str, str, "str | None"]
#: The type of a pair (``"R"``/``"P"``) and its guide carrier in an identification row:
#: ``"prev"`` the known link i−1 / j−1, ``"i"``/``"j"`` the group's own link, None for R.
RowPair = tuple[str, "str | None"]


@dataclass(frozen=True, slots=True)
class Sketched:
    """What a kind's sketch builder derives from the joints of a sketch.

    ``frame_i``/``frame_j`` are the link frames (origin, angle) at the reference position.
    A triad or class IV group gives its :class:`~assur.kinematics.higher.kind.Layout` and the
    frames of all its links in ``frames``.
    """

    sigma: int
    frame_i: tuple[complex, float]
    frame_j: tuple[complex, float]
    hinge_i: Anchor | None = None
    hinge_j: Anchor | None = None
    guide_i: Guide | None = None
    guide_j: Guide | None = None
    driven: str | None = None
    layout: Layout | None = None
    frames: Mapping[LinkId, tuple[complex, float]] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class GroupKind:
    """One kind of group.

    Parameters
    ----------
    number : int or None
        The DGTU number L (0 input group, 1–5 dyads); None for kinds outside the DGTU table.
    code : str
        ``"L0"`` … ``"L5"``, ``"III"``, ``"IV"``.
    pairs : str
        The pair string in English (``"RRR"``); empty where the kind has none.
    group_class : int
        Artobolevsky's class (1 for the input group).
    pattern : tuple or None
        Classification key of a dyad: (internal pair type, sorted external pair types).
    roles : tuple of (role, side)
        Role of each pair (``"H_i"``, ``"C"``, ``"P_i"`` …) and the side it comes from:
        ``"i"``/``"j"`` the external pair of link i/j, ``"c"`` the internal pair.
    columns : tuple of str
        The parameter columns, in the order of tables 2.1–2.6.
    hinges, guides : mapping
        Side → columns of its external hinge, or of its external guide.
    variants : tuple
        Allowed values of the identification table's ``variant``; ``default_variant`` is
        printed when the dimensions are not known.
    out_code : str
        The output-parameter code of table 1.6.
    condition : str
        The existence inequality, as printed in reports.
    row_pairs : tuple of three RowPair, or None
        External pair of i, internal pair, external pair of j of a group rebuilt from an
        identification row.
    j_rule : str
        How classification picks link j: ``"frame_last"``/``"frame_first"`` (the link on
        the frame, else the later/earlier link), ``"revolute"`` (the link whose external
        pair is revolute), ``"not_carrier"`` (the link that does not carry the internal
        guide).
    solve, sketch, shortfall, pressure, equilibrium : callable or None
        The per-kind computations: solve the group over the positions (``_solve_*``),
        derive its parameters from a sketch (``_sketch_*``), the violated condition in mm or
        degrees (``_shortfall_*``), the pressure angle at C (``_pressure_*``), the
        kinetostatics of a dyad: its reactions from the known loads of its links
        (``assur.forces.groups.equilibrium_*``, ``docs/forces.md``).

    Examples
    --------
    >>> from assur import KINDS
    >>> KINDS[3].pairs, KINDS[3].group_class
    ('RPR', 2)
    """

    number: int | None
    code: str
    pairs: str
    group_class: int
    pattern: tuple[str, str] | None = None
    roles: tuple[tuple[str, str], ...] = ()
    columns: tuple[str, ...] = ()
    hinges: Mapping[str, HingeColumns] = field(default_factory=dict)
    guides: Mapping[str, GuideColumns] = field(default_factory=dict)
    variants: tuple[int | None, ...] = (None,)
    default_variant: int | None = None
    out_code: str = ""
    condition: str = "—"
    row_pairs: tuple[RowPair, RowPair, RowPair] | None = None
    j_rule: str = ""
    solve: Callable[[_State, GroupModel, Value], DyadSolution | HigherGroupSolution] | None = None
    sketch: Callable[[_Builder, AssurGroup, str], Sketched | None] | None = None
    shortfall: Callable[[GroupModel, _Shortfall], tuple[float, str]] | None = None
    pressure: Callable[[GroupModel, set[LinkId], np.ndarray, np.ndarray],
                       tuple[tuple[LinkId, ...], np.ndarray]] | None = None
    equilibrium: Callable[[GroupModel, Loads], Solved] | None = None

    @property
    def key(self) -> str:
        """The stem of this kind's catalogue codes (``"kind.l1"``)."""
        return f"kind.{self.code.lower()}"

    def title(self, lang: str = "en") -> str:
        """The course's name of the kind, e.g. ``'dyad of kind 1 (RRR)'``."""
        return render(f"{self.key}.name", lang)

    def pair_text(self, lang: str = "en") -> str:
        """The pair string in the language (``'RRR'``, ``'ВВВ'``); empty for none."""
        return render(f"{self.key}.pairs", lang) if self.pairs else ""

    def role_rule(self, lang: str = "en") -> str:
        """How the course names the links i and j of this kind."""
        return render(f"{self.key}.roles", lang)

    @property
    def is_input(self) -> bool:
        """Whether this is the input group (class I): it always assembles."""
        return self.group_class == 1

    @property
    def sided(self) -> bool:
        """Whether the kind has two assembly variants σ = ±1."""
        return self.default_variant is not None


@dataclass(frozen=True, slots=True)
class _Shortfall:
    """What a shortfall rule reads at the worst position of a failure interval."""

    q: float
    margin: float
    delta: float
    value: Callable[[str], Any]
    hinge: Callable[[str], complex]


# ------------------------------------------------------------------------------ solvers


def given(x: Value | None) -> Value:
    """A solver output that the group's kind always has (a dyad's link j, its slider)."""
    assert x is not None
    return x


def _solve_input(state: _State, group: GroupModel, q: Value) -> DyadSolution:
    p, col = state.p, group.column
    angle = p(col("phi_1_0")) + state.model.direction * q
    pivot = p(col("x_O1")) + 1j * p(col("y_O1"))
    sol = dyads.solve_input(pivot, p(col("l_1")), angle)
    state.joints[group.pairs["H_i"]] = sol.origin_i
    state.rotors[group.i] = (sol.c - sol.origin_i) / p(col("l_1"))
    return sol


def _solve_rrr(state: _State, group: GroupModel, q: Value) -> DyadSolution:
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


def _solve_rrp(state: _State, group: GroupModel, q: Value) -> DyadSolution:
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


def _solve_rpr(state: _State, group: GroupModel, q: Value) -> DyadSolution:
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


def _solve_prp(state: _State, group: GroupModel, q: Value) -> DyadSolution:
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


def _solve_rpp(state: _State, group: GroupModel, q: Value) -> DyadSolution:
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


def _hinges(build: _Builder, group: AssurGroup, pairs: tuple[Pair, Pair, Pair],
            label: str) -> tuple[complex, complex, Anchor, Anchor]:
    """The sketched external hinges H_i, H_j of a dyad and their anchors."""
    prev_i, prev_j = _ends(group)
    hi, hj = build.point(pairs[0]), build.point(pairs[1])
    return (hi, hj, build.attachment(prev_i, hi, label, _HI),
            build.attachment(prev_j, hj, label, _HJ))


def _sketch_rrr(build: _Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    c = build.point(pairs[2])
    hi, hj, anchor_i, anchor_j = _hinges(build, group, pairs, label)
    build.put(label, "l_i", abs(c - hi))
    build.put(label, "l_j", abs(c - hj))
    sigma = _sign(_cross(hj - hi, c - hi))
    return Sketched(sigma, (hi, cmath.phase(c - hi)), (hj, cmath.phase(c - hj)),
                    hinge_i=anchor_i, hinge_j=anchor_j,
                    driven=build.driven_side(group) if group.composite else None)


def _sketch_rrp(build: _Builder, group: AssurGroup, label: str) -> Sketched | None:
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


def _sketch_rpr(build: _Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    theta = build.direction(pairs[2])
    hi, hj, anchor_i, anchor_j = _hinges(build, group, pairs, label)
    axis = cmath.exp(1j * theta)
    build.put(label, "d", _cross(axis, hj - hi))
    sigma = _sign(_dot(axis, hj - hi))
    return Sketched(sigma, (hi, theta), (hj, theta), hinge_i=anchor_i, hinge_j=anchor_j)


def _sketch_prp(build: _Builder, group: AssurGroup, label: str) -> Sketched | None:
    pairs = build.topo.dyad_pairs(group)
    pi, pj, pc = pairs
    prev_i, prev_j = _ends(group)
    c = build.point(pc)
    a, ti, b, tj = build.point(pi), build.direction(pi), build.point(pj), build.direction(pj)
    gi = build.guide(pi, prev_i, a, ti, label, KINDS[4].guides["i"], c)
    gj = build.guide(pj, prev_j, b, tj, label, KINDS[4].guides["j"], c)
    return Sketched(1, (c, ti), (c, tj), guide_i=gi, guide_j=gj)


def _sketch_rpp(build: _Builder, group: AssurGroup, label: str) -> Sketched | None:
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


def _shortfall_rrr(group: GroupModel, at: _Shortfall) -> tuple[float, str]:
    d = abs(at.hinge("H_j") - at.hinge("H_i"))
    l_i = at.q if group.driven == "i" else float(at.value(group.column("l_i")))
    l_j = at.q if group.driven == "j" else float(at.value(group.column("l_j")))
    return float(max(d - (l_i + l_j), abs(l_i - l_j) - d)), "mm"


def _shortfall_rrp(group: GroupModel, at: _Shortfall) -> tuple[float, str]:
    return float(-at.margin * float(at.value(group.column("l_j")))), "mm"


def _shortfall_rpr(group: GroupModel, at: _Shortfall) -> tuple[float, str]:
    return float(-at.margin * abs(at.hinge("H_j") - at.hinge("H_i"))), "mm"


def _shortfall_guides(group: GroupModel, at: _Shortfall) -> tuple[float, str]:
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

_TAIL = ("l_N", "beta_N", "l_M", "beta_M")
_HI, _HJ = ("x_Hi", "y_Hi"), ("x_Hj", "y_Hj")
_R: RowPair = ("R", None)
_P_PREV: RowPair = ("P", "prev")

#: The modules of the per-kind computations that only some programs use, loaded on first call.
_FORCES = "assur.forces.groups"
_LINEAR = "assur.forces.linear"
_HIGHER = "assur.kinematics.higher.kind"


def _later(module: str, name: str) -> Callable[..., Any]:
    """The function ``name`` of ``module``, imported when first called.

    The registry names the kinetostatics and the rules of the higher groups without loading
    them, so a program that only reads tables and analyses dyads never imports them.
    """
    def call(*args: Any, **kwargs: Any) -> Any:
        return getattr(importlib.import_module(module), name)(*args, **kwargs)

    call.__name__ = call.__qualname__ = name
    return call


#: The kinds of the DGTU method: L0 (input group) and the dyads L1–L5.
KINDS: Mapping[int, GroupKind] = {
    0: GroupKind(0, "L0", "", 1, roles=(("H_i", "i"),),
                 columns=("x_O1", "y_O1", "l_1", "phi_1_0"), out_code="0",
                 solve=_solve_input),
    1: GroupKind(1, "L1", "RRR", 2, ("R", "RR"), (("H_i", "i"), ("H_j", "j"), ("C", "c")),
                 (*_HI, *_HJ, "l_i", "l_j", *_TAIL), {"i": _HI, "j": _HJ},
                 variants=(1, -1), default_variant=1, out_code="8;2",
                 condition="|l_i − l_j| ≤ |H_iH_j| ≤ l_i + l_j,  |cos ∠H_i| ≤ 1 − δ",
                 row_pairs=(_R, _R, _R), j_rule="frame_last", solve=_solve_rrr,
                 sketch=_sketch_rrr, shortfall=_shortfall_rrr, pressure=_pressure_rrr,
                 equilibrium=_later(_FORCES, "equilibrium_rrr")),
    2: GroupKind(2, "L2", "RRP", 2, ("R", "PR"), (("P_i", "i"), ("C", "c"), ("H_j", "j")),
                 (*_HJ, "l_j", "x_Ak", "y_Ak", "beta_g", "e", *_TAIL), {"j": _HJ},
                 {"i": ("x_Ak", "y_Ak", "beta_g", "e")}, variants=(1, -1), default_variant=1,
                 out_code="7;3", condition="|h| ≤ (1 − δ)·l_j",
                 row_pairs=(_P_PREV, _R, _R), j_rule="revolute", solve=_solve_rrp,
                 sketch=_sketch_rrp, shortfall=_shortfall_rrp, pressure=_pressure_rrp,
                 equilibrium=_later(_FORCES, "equilibrium_rrp")),
    3: GroupKind(3, "L3", "RPR", 2, ("P", "RR"), (("H_i", "i"), ("P_c", "c"), ("H_j", "j")),
                 (*_HI, *_HJ, "d", *_TAIL), {"i": _HI, "j": _HJ}, variants=(0, 1, -1),
                 default_variant=0, out_code="5", condition="|d| ≤ (1 − δ)·|H_iH_j|",
                 row_pairs=(_R, ("P", "i"), _R), j_rule="not_carrier", solve=_solve_rpr,
                 sketch=_sketch_rpr, shortfall=_shortfall_rpr,
                 equilibrium=_later(_FORCES, "equilibrium_rpr")),
    4: GroupKind(4, "L4", "PRP", 2, ("R", "PP"), (("P_i", "i"), ("C", "c"), ("P_j", "j")),
                 ("x_Ak", "y_Ak", "beta_i", "e_i", "x_Bk", "y_Bk", "beta_j", "e_j", *_TAIL),
                 guides={"i": ("x_Ak", "y_Ak", "beta_i", "e_i"),
                         "j": ("x_Bk", "y_Bk", "beta_j", "e_j")},
                 out_code="4", condition="|sin(θ_j − θ_i)| ≥ δ",
                 row_pairs=(_P_PREV, _R, _P_PREV), j_rule="frame_first", solve=_solve_prp,
                 sketch=_sketch_prp, shortfall=_shortfall_guides,
                 equilibrium=_later(_FORCES, "equilibrium_prp")),
    5: GroupKind(5, "L5", "RPP", 2, ("P", "PR"), (("P_i", "i"), ("P_c", "c"), ("H_j", "j")),
                 (*_HJ, "gamma", "x_Ak", "y_Ak", "beta_S", "e", *_TAIL), {"j": _HJ},
                 {"i": ("x_Ak", "y_Ak", "beta_S", "e")}, out_code="5",
                 condition="|sin γ| ≥ δ", row_pairs=(_P_PREV, ("P", "j"), _R),
                 j_rule="revolute", solve=_solve_rpp, sketch=_sketch_rpp,
                 shortfall=_shortfall_guides, equilibrium=_later(_FORCES, "equilibrium_rpp")),
}

#: The kinds outside the DGTU table, by code: the triad (class III, order 3, with bars,
#: blocks hinged to the base or leashes sliding on the base) and the class IV group of
#: order 2 (hinges or sliders), solved by continuation of the drawn assembly mode
#: (:mod:`assur.kinematics.higher`). No identification row names them (``docs/tables.md``).
HIGHER: Mapping[str, GroupKind] = {
    "III": GroupKind(None, "III", "", 3, condition="m = |det R| / Π‖R_k‖ ≥ δ",
                     solve=_later(_HIGHER, "solve_triad"), sketch=_later(_HIGHER, "sketch_triad"),
                     shortfall=_later(_HIGHER, "shortfall_higher"),
                     equilibrium=_later(_LINEAR, "equilibrium_linear")),
    "IV": GroupKind(None, "IV", "", 4, condition="m = |det R| / Π‖R_k‖ ≥ δ",
                    solve=_later(_HIGHER, "solve_class_iv"),
                    sketch=_later(_HIGHER, "sketch_class_iv"),
                    shortfall=_later(_HIGHER, "shortfall_higher"),
                    equilibrium=_later(_LINEAR, "equilibrium_linear")),
}
_BY_CLASS = {kind.group_class: kind for kind in HIGHER.values()}

_BY_PATTERN = {kind.pattern: kind for kind in KINDS.values() if kind.pattern is not None}


def kind_of(number: int | str) -> GroupKind:
    """The kind with DGTU number L (0–5), or the higher kind with code ``"III"``/``"IV"``.

    Parameters
    ----------
    number : int or str
        The DGTU number L of the kind (0 for the input group), or ``"III"``, ``"IV"``.

    Returns
    -------
    GroupKind
        Its registry entry.

    Raises
    ------
    KeyError
        For a number that is no kind.

    Examples
    --------
    >>> kind_of(4).pairs, kind_of("III").group_class
    ('PRP', 3)
    """
    try:
        return HIGHER[number] if isinstance(number, str) else KINDS[number]
    except KeyError:
        raise KeyError(f"no group kind {number!r}; the kinds are L0–L5, III, IV") from None


def kind_of_class(group_class: int) -> GroupKind | None:
    """The higher kind of a group of this class (3 triad, 4 class IV), None for others.

    Parameters
    ----------
    group_class : int
        Artobolevsky's class of the group.

    Returns
    -------
    GroupKind or None
        The registry entry of the triad or the class IV group.

    Examples
    --------
    >>> kind_of_class(4).code, kind_of_class(5)
    ('IV', None)
    """
    return _BY_CLASS.get(group_class)


def kind_of_pattern(internal: str, external: tuple[str, str]) -> GroupKind | None:
    """The dyad kind with this internal pair type and these external pair types, or None.

    >>> kind_of_pattern("P", ("R", "R")).code
    'L3'
    >>> kind_of_pattern("P", ("P", "P")) is None
    True
    """
    return _BY_PATTERN.get((internal, "".join(sorted(external))))
