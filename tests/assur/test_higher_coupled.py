"""The class IV group with prismatic internal pairs (:class:`ClassIVCoupled`) on random designs.

A form is named ``"b d/ac"``: the kinds of the couplers b (pairs C, D) and d (F, E), then the
external pairs of a and c (R a hinge, P a prismatic pair). a's external pair is on a crank
turning about the origin (a hinge at its pin, or a guide it carries), c's on the frame. Each
check compares with a computation made another way: the forms with hinged couplers with
:class:`ClassIV` (another elimination), the mode counts with the fallback's sweep of the full
pose system (or its Newton search where no sweep plan exists), rigidity and the guides with
distances and cross products of the joints, the analogs with central differences, the
followed mode and its interval with a walk through all modes on a fine grid.

``ASSUR_HIGHER_FULL=1`` runs the full profile.
"""

from __future__ import annotations

import os
import pickle
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from class_iv_hinged import ClassIV
from higher_checks import check_analogs_against_central_differences, check_class_iv_rigid
from higher_fallback import (
    Joint,
    Motion,
    PoseModes,
    PoseSystem,
    newton_modes,
    sweep_modes,
)
from test_higher_properties import walk_through

from assur.kinematics import jets as J
from assur.kinematics.higher import ClassIVInputs, assembly_modes, follow_mode
from assur.kinematics.higher.coupled import ClassIVCoupled
from assur.kinematics.higher.groups import expand, plain
from assur.kinematics.higher.modes import AssemblyModes

FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
COUNTED, RIGID, WALKED = (400, 40, 12) if FULL else (40, 6, 3)
SHARED = ["RR RR/RR", "RR RR/RP", "RR RR/PR", "RR RR/PP"]
COUPLED = ["PR RR/RR", "RP RR/RR", "PP RR/RR", "PR RP/RR", "PR RR/RP",
           "PR PR/PP", "RP PR/PR", "PR RP/RP"]
#: Forms with no sweep plan: the fallback is Newton's search from random starts (slower).
SEARCHED = ["PR RP/RR"]
TWO_PI = 2 * np.pi


def _polar(rng: np.random.Generator, d: int, low: float, high: float) -> np.ndarray:
    return np.asarray(rng.uniform(low, high, d) * np.exp(2j * np.pi * rng.uniform(size=d)))


def _col(v: Any) -> np.ndarray:
    return np.asarray(v)[:, None]


@dataclass
class Designs:
    """Random drawn groups of one form and how their known links move."""

    form: str
    group: ClassIVCoupled

    def inputs(self, phi: Any) -> ClassIVInputs:
        """H_a on the crank (pivot at the origin), H_c on the frame."""
        g, turn = self.group, J.expi(phi)
        return ClassIVInputs(turn * g.h_a, g.h_c, None if g.u_a is None else g.u_a * turn,
                             g.u_c)

    def grid(self, phi: np.ndarray) -> ClassIVInputs:
        """The inputs on the (design, angle) grid."""
        return Designs(self.form, expand(self.group)).inputs(np.asarray(phi)[None, :])

    def pose_system(self) -> PoseSystem:
        """a = 0, b = 1, c = 2, d = 3; a prismatic internal pair's guide on a or on c."""
        g = self.group

        def joint(moving: int | str, carrier: int | str, point: Any, guide: Any) -> Joint:
            if guide is None:
                return Joint("R", moving, carrier, point)
            return Joint("P", moving, carrier, point, guide)

        return PoseSystem((joint(0, "k", g.h_a, g.u_a), joint(1, 0, g.c, g.w_c),
                           joint(1, 2, g.d, g.w_d), joint(3, 2, g.e, g.w_e),
                           joint(3, 0, g.f, g.w_f), joint(2, "frame", g.h_c, g.u_c)))

    def known(self, phi: float) -> dict[str, Motion]:
        return {"k": Motion(np.asarray(0.0), np.asarray(np.exp(1j * phi))),
                "frame": Motion(0.0, 1.0)}


def random_designs(form: str, seed: int, d: int) -> Designs:
    """Drawn assembled: C, F 40–70 from H_a (8–15 from the crank pivot); D, E 30–60 from H_c
    (90–110 from the pivot); every guide direction uniform."""
    rng = np.random.default_rng(seed)
    h_a = _polar(rng, d, 8, 15)
    c, f = h_a + _polar(rng, d, 40, 70), h_a + _polar(rng, d, 40, 70)
    h_c = _polar(rng, d, 90, 110)
    dd, e = h_c + _polar(rng, d, 30, 60), h_c + _polar(rng, d, 30, 60)
    couplers, external = form.split("/")
    b, dk = couplers.split()
    kinds = {"u_a": external[0], "u_c": external[1], "w_c": b[0], "w_d": b[1], "w_f": dk[0],
             "w_e": dk[1]}
    guides = {name: np.exp(2j * np.pi * rng.uniform(size=d)) if kind == "P" else None
              for name, kind in kinds.items()}
    return Designs(form, ClassIVCoupled(h_a, c, f, h_c, dd, e, **guides))


def clear(modes: AssemblyModes) -> np.ndarray:
    """Designs away from a birth or merge of modes: no root of p just off the unit circle, no
    mode with a thin margin."""
    size = np.abs(np.log(np.abs(modes.roots)))
    near = ((size > 1e-6) & (size < 1e-3)).any(axis=-1)
    thin = (np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=-1)
    return np.asarray(~near & ~thin)


def _match(mine: np.ndarray, theirs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each of my modes (D, M, 4) the largest joint gap to the nearest of theirs (D, N, 4)
    and that one's index."""
    apart = np.nan_to_num(np.abs(mine[:, :, None, :] - theirs[:, None, :, :]).max(axis=-1),
                          nan=np.inf)
    return apart.min(axis=-1), apart.argmin(axis=-1)


def _nearest(mine: np.ndarray, theirs: np.ndarray) -> np.ndarray:
    return _match(mine, theirs)[0]


COUPLER_JOINTS = ("C", "D", "E", "F")


# --- the shared forms against ClassIV ---------------------------------------------------------


@pytest.mark.parametrize("form", SHARED)
def test_hinged_couplers_give_the_modes_of_class_iv(form: str) -> None:
    """With hinged couplers both solvers find the same modes: count, joints to 1e-9 L, and
    the margin (physical columns: the same number whatever the unknowns)."""
    designs = random_designs(form, 10 + SHARED.index(form), COUNTED)
    g = designs.group
    plain = ClassIV(g.h_a, g.c, g.f, g.h_c, g.d, g.e, g.u_a, g.u_c)
    k = designs.inputs(np.full(COUNTED, np.radians(37.0)))
    mine, theirs = assembly_modes(g, k), assembly_modes(plain, k)
    keep = clear(mine) & clear(theirs)
    assert keep.mean() >= 0.9
    assert (mine.count[keep] == theirs.count[keep]).all()
    assert mine.count.max() >= 2
    stack = [np.stack([m.joints[n] for n in COUPLER_JOINTS], axis=-1) for m in (mine, theirs)]
    gap, which = _match(*stack)
    real = ~np.isnan(stack[0][..., 0]) & keep[:, None]
    assert (gap[real] <= 1e-9 * np.broadcast_to(_col(g.size), gap.shape)[real]).all()
    margin = np.take_along_axis(theirs.margin, which, axis=-1)
    assert (np.abs(mine.margin - margin)[real] <= 1e-9).all()


# --- the prismatic internal pairs against the fallback ----------------------------------------


def fallback_modes(designs: Designs, phi: float) -> PoseModes:
    """The sweep of the full pose system, or Newton's search where no sweep plan exists."""
    try:
        return sweep_modes(designs.pose_system(), designs.known(phi), samples=1440)
    except ValueError:
        return newton_modes(designs.pose_system(), designs.known(phi), starts=300)


@pytest.mark.parametrize("form", COUPLED)
def test_mode_count_agrees_with_the_fallback(form: str) -> None:
    """At 37°, the real modes agree in number and in their joints with the fallback's."""
    d = COUNTED // 4 if form in SEARCHED else COUNTED
    designs = random_designs(form, 20 + COUPLED.index(form), d)
    g = designs.group
    assert g.determinate
    phi = np.radians(37.0)
    modes = assembly_modes(g, designs.inputs(np.full(d, phi)))
    found = fallback_modes(designs, phi)
    keep = clear(modes)
    assert keep.mean() >= 0.9
    assert (modes.count[keep] == found.count[keep]).all()
    assert modes.count.max() >= (1 if form == "PR PR/PP" else 2)  # PR PR/PP: two lines
    mine = np.stack([modes.joints[n] for n in COUPLER_JOINTS], axis=-1)
    # the fallback's joint points are on their first bodies: b at C, D; d at E, F
    gap = _nearest(mine, found.points[..., [1, 2, 3, 4]])
    real = ~np.isnan(mine[..., 0]) & keep[:, None]
    assert (gap[real] <= 1e-7 * np.broadcast_to(_col(g.size), gap.shape)[real]).all()


# --- rigidity and the guides over full cycles -------------------------------------------------


def _on_guide(turn: np.ndarray, guide: Any, moving: np.ndarray, fixed: np.ndarray) -> np.ndarray:
    """|cross(E·w, moving − fixed)|: the distance of ``moving`` from the turned guide line."""
    return np.asarray(np.abs((np.conj(turn * _col(guide)) * (moving - fixed)).imag))


@pytest.mark.parametrize("form", COUPLED + ["PR RR/PR"])
def test_links_stay_rigid_and_on_their_guides_over_the_cycle(form: str) -> None:
    designs = random_designs(form, 30 + len(form) + COUPLED.count(form), RIGID)
    g = designs.group
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    solution = follow_mode(g, designs.inputs, phi)
    ok = check_class_iv_rigid(solution, g, own="ac")
    j, rot = solution.joints, solution.rotations
    size = np.broadcast_to(_col(g.size), ok.shape)[ok]
    turns = {name: np.exp(1j * rot[name]) for name in "abcd"}
    # internal pairs: a hinge joins equal points; a prismatic pair keeps the coupler turned
    # with the guide's link and its point on the guide line through the link's point
    for coupler, point, own, link, guide in (("b", "C", "Ca", "a", g.w_c),
                                             ("b", "D", "Dc", "c", g.w_d),
                                             ("d", "F", "Fa", "a", g.w_f),
                                             ("d", "E", "Ec", "c", g.w_e)):
        if guide is None:
            assert (np.abs(j[point] - j[own])[ok] <= 1e-9 * size).all(), point
            continue
        assert (np.abs(turns[coupler] - turns[link])[ok] <= 1e-9).all(), point
        assert (_on_guide(turns[link], guide, j[point], j[own])[ok] <= 1e-9 * size).all(), point
    k = designs.grid(phi)
    for here, known, guide in ((j["Ha"], k.h_a, k.u_a), (j["Hc"], k.h_c, k.u_c)):
        if guide is None:
            assert (np.abs(here - known)[ok] <= 1e-9 * size).all()
        else:
            assert (np.abs((np.conj(guide) * (here - known)).imag)[ok] <= 1e-9 * size).all()


# --- analogs against central differences ------------------------------------------------------


@pytest.mark.parametrize("form", COUPLED)
def test_analogs_against_central_differences(form: str) -> None:
    designs = random_designs(form, 50 + COUPLED.index(form), 6)
    check_analogs_against_central_differences(designs.group, designs.inputs, 6)


@pytest.mark.parametrize("form", SHARED + COUPLED)
def test_residual_and_jacobian_off_the_solutions_against_central_differences(form: str) -> None:
    """At arbitrary unknowns (no pose), the Jacobian that Newton takes with the residual equals
    central differences of the residual, the derivative of the lifting factor included."""
    d = 12
    designs = random_designs(form, 70 + (SHARED + COUPLED).index(form), d)
    g = designs.group
    k = designs.inputs(np.full(d, 0.4))
    x = np.random.default_rng(7).uniform(-2.5, 2.5, (d, 2))
    f, jac = g.equations(x, k)
    residual = np.stack(np.broadcast_arrays(*map(plain, g.residual(x, k))), axis=-1)
    assert np.allclose(f, residual, rtol=1e-12, atol=1e-12 * _col(g.size))
    h = 1e-6
    for i in range(2):
        step = np.zeros(2)
        step[i] = h
        ahead, behind = (np.stack(np.broadcast_arrays(*map(plain, g.residual(x + sign * step, k))),
                                  axis=-1)
                         for sign in (1.0, -1.0))
        slope = (ahead - behind) / (2.0 * h)
        scale = np.abs(slope).max(axis=-1, keepdims=True) + _col(g.size) * 1e-3
        assert (np.abs(jac[..., i] - slope) <= 1e-6 * scale).all(), i


def test_a_used_group_pickles_and_solves_the_same() -> None:
    """A group that has fitted its matrices travels to another process (pickle) and gives the
    same residual there."""
    designs = random_designs("PR RR/RP", 90, 4)
    k = designs.inputs(np.full(4, 0.3))
    x = np.zeros((4, 2))
    before = np.stack(np.broadcast_arrays(*map(plain, designs.group.residual(x, k))), axis=-1)
    copy = pickle.loads(pickle.dumps(designs.group))
    after = np.stack(np.broadcast_arrays(*map(plain, copy.residual(x, k))), axis=-1)
    assert np.array_equal(before, after)


# --- the followed mode and its interval against a walk through all modes ----------------------


@pytest.mark.parametrize("form", ["PR RR/RR", "PP RR/RR", "PR RR/RP", "RP PR/PR"])
def test_no_mode_switch_and_the_interval_against_a_walk_through_all_modes(form: str) -> None:
    """On a 0.2° grid, every mode at every angle; the walk from the drawn pose steps to the
    nearest mode and ends where none is within 0.1. The continuation's positions (2° apart)
    equal the walk's, and its ends lie within one walk step of the walk's. (A 0.1° grid for
    RP PR/PR, whose lifted slide moves by up to 0.07 rad in 0.2° away from any end.)"""
    designs = random_designs(form, 60 + COUPLED.index(form), WALKED)
    g = designs.group
    fine = 3600 if form == "RP PR/PR" else 1800
    grid = np.linspace(0, TWO_PI, fine, endpoint=False)
    walk, forward, backward = walk_through(g, assembly_modes(expand(g), designs.grid(grid)).x)
    coarse = np.arange(0, fine, 10)
    phi = grid[coarse]
    solution = follow_mode(g, designs.inputs, phi)
    tolerance = 2 * TWO_PI / fine
    ahead = np.where(np.isnan(solution.ends[:, 0]), TWO_PI, solution.ends[:, 0])
    assert (np.abs(ahead - forward) <= tolerance).all()
    back = ~np.isnan(solution.ends[:, 1])
    assert (np.abs(solution.ends[back, 1] - backward[back]) <= tolerance).all()
    walked = walk[:, coarse]
    away = (np.abs(phi - forward[:, None]) > tolerance) \
        & (np.abs(phi - backward[:, None]) > tolerance)
    assert (solution.exists == ~np.isnan(walked[..., 0]))[away].all()
    both = solution.exists & ~np.isnan(walked[..., 0])
    gap = np.abs(np.angle(np.exp(1j * (solution.x - walked))))
    assert both.any() and np.nanmax(np.where(both[..., None], gap, np.nan)) <= 1e-7


# --- what is refused ----------------------------------------------------------------------------


def test_indeterminate_forms_are_flagged() -> None:
    """Two PP couplers are refused; a PP coupler with both links sliding, or with parallel
    guides, and a coupler guide parallel to the only slide it could fix are not determinate."""
    pts = (-12.5 - 20j, 57 + 66j, 25.5 + 98.5j, 140.5 + 22j, 115 + 67j, 87 + 118j)
    with pytest.raises(ValueError):
        ClassIVCoupled(*pts, w_c=1, w_d=1j, w_e=1, w_f=1j)
    assert not ClassIVCoupled(*pts, u_a=1, u_c=1j, w_c=1, w_d=1j).determinate
    assert not ClassIVCoupled(*pts, w_c=1, w_d=-1).determinate
    assert ClassIVCoupled(*pts, w_c=1, w_d=1j).determinate
    assert ClassIVCoupled(*pts, u_a=1j, w_c=1, w_d=1j).determinate
    assert ClassIVCoupled(*pts, u_a=1, w_c=1, w_f=1).determinate is False
    assert ClassIVCoupled(*pts, u_a=1, w_c=1).determinate
