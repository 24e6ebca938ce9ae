"""Reason codes at constructed failing positions, and the solvers at numerical extremes.

Expected values come from hand calculation: the method.md §2.9 vectors rescaled, exact toggle
geometries, and closed forms for nearly parallel guides.
"""

from __future__ import annotations

import numpy as np
import pytest

from assur.kinematics.dyads import (
    REASONS,
    Reason,
    solve_input,
    solve_prp,
    solve_rpp,
    solve_rpr,
    solve_rrp,
    solve_rrr,
)

DEG = np.pi / 180.0


# --- reason codes -----------------------------------------------------------------------------

@pytest.mark.parametrize(("solution", "code"), [
    (lambda: solve_rrr(0j, 150 + 0j, 80.0, 60.0, 1), Reason.STRETCHED),  # 150 > 80 + 60
    (lambda: solve_rrr(0j, 15 + 0j, 80.0, 60.0, 1), Reason.FOLDED),  # 15 < 80 - 60
    (lambda: solve_rrr(0j, 10j, 30.0, 60.0, -1), Reason.FOLDED),  # 10 < 60 - 30
    (lambda: solve_rrr(5 + 5j, 5 + 5j, 80.0, 60.0, 1), Reason.COINCIDENT_HINGES),
    (lambda: solve_rrp(120j, 0j, 0.0, 0.0, 100.0, 1), Reason.ROD_TOO_SHORT),  # |h| = 120
    (lambda: solve_rrp(50j, 0j, 0.0, -60.0, 100.0, 1), Reason.ROD_TOO_SHORT),  # h = 50 + 60
    (lambda: solve_rpr(0j, 10 + 0j, 20.0, 1), Reason.OFFSET_TOO_LARGE),  # 20 > ρ = 10
    (lambda: solve_rpr(3j, 3j, 1.0, 1), Reason.COINCIDENT_HINGES),
    (lambda: solve_prp(0j, 0.3, 0.0, 10 + 0j, 0.3, 2.0), Reason.GUIDES_PARALLEL),
    (lambda: solve_prp(0j, 0.3, 0.0, 10 + 0j, 0.3 + np.pi, 2.0), Reason.GUIDES_PARALLEL),
    (lambda: solve_rpp(5j, 0.0, 0j, 0.2, 1.0), Reason.GUIDES_PARALLEL),
    (lambda: solve_rrr(np.nan + 0j, 100 + 0j, 80.0, 60.0, 1), Reason.UNDEFINED_INPUT),
    (lambda: solve_prp(0j, np.nan, 0.0, 10 + 0j, 0.3, 2.0), Reason.UNDEFINED_INPUT),
    (lambda: solve_input(0j, 10.0, np.nan), Reason.UNDEFINED_INPUT),
])
def test_reason_at_a_failing_position(solution: object, code: Reason) -> None:
    sol = solution()
    assert not sol.exists
    assert sol.reason == code
    assert np.isnan(sol.c)
    assert code in REASONS


def test_reasons_are_distinct_and_bilingual() -> None:
    assert set(REASONS) == {int(r) for r in Reason}
    english = [en for en, _ in REASONS.values()]
    russian = [ru for _, ru in REASONS.values()]
    assert len(set(english)) == len(english) and len(set(russian)) == len(russian)
    assert all(any("а" <= ch <= "я" for ch in ru) for ru in russian)  # Cyrillic text


def test_tolerance_band_reports_the_nearer_limit() -> None:
    # 3-4-5 triangle stretched almost straight: d = 139.9, l_i + l_j = 140
    sol = solve_rrr(0j, 139.9 + 0j, 80.0, 60.0, 1, delta=0.01)
    assert 0.0 < sol.margin < 0.01 and not sol.exists
    assert sol.reason == Reason.STRETCHED and np.isnan(sol.c)
    plain = solve_rrr(0j, 139.9 + 0j, 80.0, 60.0, 1)  # δ = 0: the same position assembles
    assert plain.exists and plain.margin == pytest.approx(sol.margin, rel=1e-12)
    near_fold = solve_rrr(0j, 20.1 + 0j, 80.0, 60.0, 1, delta=0.01)
    assert near_fold.reason == Reason.FOLDED


def test_delta_may_vary_per_design() -> None:
    deltas = np.array([[0.0], [0.1]])  # two designs
    sol = solve_rrr(0j, np.array([100.0, 139.0]) + 0j, 80.0, 60.0, 1, delta=deltas)
    # margins 1 - |c|: c = (80² + 100² - 60²)/(2·80·100) = 0.8 gives 0.2; at d = 139, 0.0171
    np.testing.assert_array_equal(sol.exists, [[True, True], [True, False]])


# --- scales -----------------------------------------------------------------------------------

@pytest.mark.parametrize("scale", [1e-3, 1e6])
def test_test_vectors_hold_at_every_scale(scale: float) -> None:
    k = scale
    rrr = solve_rrr(0j, 100 * k + 0j, 80 * k, 60 * k, 1)
    assert rrr.c == pytest.approx((64 + 48j) * k, rel=1e-14)
    assert rrr.angle_j == pytest.approx(126.86989764584402 * DEG, rel=1e-14)
    rrp = solve_rrp(50j * k, 0j, 0.0, 0.0, 100 * k, -1)
    assert rrp.s_i == pytest.approx(-np.sqrt(7500) * k, rel=1e-14)
    rpr = solve_rpr(0j, 100 * k + 0j, 20 * k, 1)
    assert rpr.s_i == pytest.approx(np.sqrt(9600) * k, rel=1e-14)
    assert rpr.angle_i == pytest.approx(-np.arctan2(20, np.sqrt(9600)), rel=1e-14)
    prp = solve_prp(0j, 30 * DEG, 0.0, 100 * k + 0j, 90 * DEG, 0.0)
    assert prp.c == pytest.approx((100 + 100j / np.sqrt(3)) * k, rel=1e-14)
    rpp = solve_rpp((20 + 50j) * k, 90 * DEG, 0j, 0.0, 0.0)
    assert (rpp.s_i, rpp.s_j) == (pytest.approx(20 * k, rel=1e-14), pytest.approx(-50 * k))


def test_far_from_the_origin() -> None:
    # a millimetre-sized dyad placed a kilometre (1e6 mm) away from the frame origin
    base = 1e6 + 1e6j
    sol = solve_rrr(base, base + 0.1, 0.08, 0.06, 1)
    assert sol.c - base == pytest.approx(0.064 + 0.048j, abs=1e-9)


# --- near toggle ------------------------------------------------------------------------------

@pytest.mark.parametrize("hinges", [0j, np.zeros(3, complex)], ids=["scalar", "array"])
def test_exact_toggle_assembles_with_zero_margin(hinges: complex | np.ndarray) -> None:
    sol = solve_rrr(hinges, hinges + 100, 60.0, 40.0, 1)  # stretched: 60 + 40 = 100
    assert np.all(sol.exists) and np.all(sol.margin == 0.0) and np.all(sol.reason == 0)
    np.testing.assert_allclose(sol.c, 60.0, atol=1e-12)
    folded = solve_rrr(hinges, hinges + 20, 60.0, 40.0, -1)  # folded: 60 - 40 = 20
    assert np.all(folded.exists) and np.all(folded.margin == 0.0)
    np.testing.assert_allclose(folded.c, 60.0, atol=1e-12)
    # 3-4-5 triangle scaled by 0.1 and rotated: the rounded coordinates give margin ~1e-16
    turn = np.exp(0.3j)
    tilted = solve_rrr(hinges, hinges + 14 * turn, 8.0, 6.0, 1)
    assert np.all(tilted.exists) and np.all(np.abs(tilted.margin) <= 1e-14)
    np.testing.assert_allclose(tilted.c, 8 * turn, atol=1e-6)


def test_exact_tangency_of_rod_and_path() -> None:
    rrp = solve_rrp(100j, 0j, 0.0, 0.0, 100.0, 1)  # rod exactly reaches the guide
    assert rrp.exists and rrp.s_i == 0.0 and rrp.c == 0j


@pytest.mark.parametrize("excess", [1e-13, 1e-10])
def test_just_beyond_toggle_fails(excess: float) -> None:
    sol = solve_rrr(0j, 100 * (1 + excess) + 0j, 60.0, 40.0, 1)
    assert not sol.exists and sol.reason == Reason.STRETCHED
    # dc/dd = (d - l_i)/(l_i·d) at the toggle, so 1 - c ≈ -(40/6000)·(100·excess)
    assert sol.margin == pytest.approx(-excess * 40 / 60, rel=1e-2)


def test_sweep_through_near_toggle_keeps_the_branch() -> None:
    # the hinge distance approaches l_i + l_j = 140 from below to within 1e-14 relative
    gap = np.geomspace(1e-1, 1e-14, 200)
    for sigma in (1.0, -1.0):
        sol = solve_rrr(0j, 140 * (1 - gap) + 0j, 80.0, 60.0, sigma)
        assert sol.exists.all()
        assert np.all(np.diff(sol.margin) < 0)  # monotone: no roundoff noise at the end
        side = sigma * sol.c.imag  # C left (σ = +1) or right (σ = −1) of H_i -> H_j
        assert np.all(side >= 0.0)
        assert np.all(np.diff(side) <= 0.0)  # C approaches the line without crossing it
        # height of C over the line, by Heron's formula in factored form: h = 2·Area / d
        d = 140 * (1 - gap)
        area16 = (80 + 60 + d) * (80 + 60 - d) * (d + 80 - 60) * (d - 80 + 60)
        height = np.sqrt(area16) / (2 * d)
        np.testing.assert_allclose(side, height, rtol=1e-6, atol=1e-9)


# --- nearly parallel guides ---------------------------------------------------------------------

@pytest.mark.parametrize("t", [1e-3, 1e-6, 1e-9])
def test_prp_nearly_parallel_guides(t: float) -> None:
    # guide i: x-axis through 0; guide j: through B = (100, 5) at angle t.
    # Hand calculation: S_i = 100 - 5·cot t, S_j = -5 / sin t
    sol = solve_prp(0j, 0.0, 0.0, 100 + 5j, t, 0.0)
    assert sol.exists and sol.margin == pytest.approx(np.sin(t), rel=1e-15)
    assert sol.s_i == pytest.approx(100 - 5 / np.tan(t), rel=1e-12)
    assert sol.s_j == pytest.approx(-5 / np.sin(t), rel=1e-12)
    assert sol.c == pytest.approx(100 - 5 / np.tan(t), rel=1e-12)
    assert solve_prp(0j, 0.0, 0.0, 100 + 5j, t, 0.0, delta=2 * t).reason == Reason.GUIDES_PARALLEL


@pytest.mark.parametrize("gamma", [1e-4, 1e-8])
def test_rpp_nearly_parallel_guides(gamma: float) -> None:
    # slider i on the x-axis; guide of j through H_j = (0, 2) at angle γ.
    # C = (2·cot(−γ)... ) by hand: T = -2 / sin γ, S = -2·cot γ
    sol = solve_rpp(2j, gamma, 0j, 0.0, 0.0)
    assert sol.exists and sol.margin == pytest.approx(np.sin(gamma), rel=1e-15)
    assert sol.s_j == pytest.approx(-2 / np.sin(gamma), rel=1e-12)
    assert sol.s_i == pytest.approx(-2 / np.tan(gamma), rel=1e-12)


# --- many turns ---------------------------------------------------------------------------------

def test_crank_over_many_turns() -> None:
    phi = np.linspace(0.0, 2 * np.pi, 37)
    turns = 10_000 * 2 * np.pi
    one = solve_rrr(solve_input(0j, 30.0, phi).c, 100 + 0j, 80.0, 90.0, 1)
    many = solve_rrr(solve_input(0j, 30.0, phi + turns).c, 100 + 0j, 80.0, 90.0, 1)
    # the crank angle itself carries roundoff ~ turns·eps ≈ 1e-11 rad
    np.testing.assert_allclose(many.c, one.c, atol=1e-8)
    np.testing.assert_allclose(np.angle(np.exp(1j * (many.angle_j - one.angle_j))), 0, atol=1e-9)
