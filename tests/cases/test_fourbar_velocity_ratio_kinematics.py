"""Kinematics of the velocity-ratio four-bar: formulas (5), (7), (8) and (18)–(20) against a
plain circle-intersection construction, finite differences and hand-derived facts."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import brentq

from synthesis.cases.fourbar_velocity_ratio.check import grashof_type, ratio_by_construction
from synthesis.cases.fourbar_velocity_ratio.conditions import ratio_function, stationarity_function
from synthesis.cases.fourbar_velocity_ratio.kinematics import (
    coupler_bounds,
    grashof_margin,
    ratio_and_derivative,
    rocker_angle,
    velocity_ratio,
)

THETA = np.linspace(0.0, 2.0 * np.pi, 97)


def crank_rockers(count: int, seed: int = 7) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Random Grashof crank-rockers (e, c, r) as columns of shape (count, 1)."""
    rng = np.random.default_rng(seed)
    e = rng.uniform(0.05, 0.7, count)
    r = e + rng.uniform(0.05, 1.5, count)
    lo, hi = coupler_bounds(e, r)
    c = lo + rng.uniform(0.05, 0.95, count) * (hi - lo)
    return e[:, None], c[:, None], r[:, None]


def test_paper_branch_closes_the_loop_and_lies_left_of_crank_pin_to_rocker_pivot():
    e, c, r = crank_rockers(40)
    phi, exists = rocker_angle(e, c, r, THETA)
    assert exists.all()
    crank_pin = e * np.exp(1j * THETA)
    rocker_end = 1.0 + r * 1j * np.exp(1j * phi)
    np.testing.assert_allclose(np.abs(rocker_end - crank_pin), np.broadcast_to(c, phi.shape),
                               rtol=1e-12)
    side = (np.conj(1.0 - crank_pin) * (rocker_end - crank_pin)).imag
    assert np.all(side > 0)


def test_velocity_ratio_7_matches_the_construction():
    e, c, r = crank_rockers(30)
    n, _, _, _ = ratio_and_derivative(e, c, r, THETA)
    by_construction = np.stack([ratio_by_construction(float(a), float(b), float(d), THETA)
                                for a, b, d in zip(e[:, 0], c[:, 0], r[:, 0])])
    np.testing.assert_allclose(n, by_construction, rtol=1e-8, atol=1e-9)


def test_analytic_derivative_of_n_matches_a_finite_difference():
    e, c, r = crank_rockers(30, seed=11)
    h = 1e-5
    _, dn, _, _ = ratio_and_derivative(e, c, r, THETA)
    plus, _, _, _ = ratio_and_derivative(e, c, r, THETA + h)
    minus, _, _, _ = ratio_and_derivative(e, c, r, THETA - h)
    np.testing.assert_allclose(dn, (plus - minus) / (2 * h), rtol=1e-6, atol=1e-7)


def test_ratio_is_plus_or_minus_e_over_r_where_crank_and_rocker_are_parallel():
    e, c, r = 0.3, 1.0, 0.5

    def parallel(theta: float) -> float:
        phi, _ = rocker_angle(e, c, r, theta)
        return float(np.cos(theta - phi))

    values = [parallel(t) for t in THETA]
    roots = [brentq(parallel, THETA[k], THETA[k + 1]) for k in range(len(THETA) - 1)
             if np.sign(values[k]) != np.sign(values[k + 1])]
    assert len(roots) == 2
    found = sorted(float(ratio_by_construction(e, c, r, t)) for t in roots)
    np.testing.assert_allclose(found, [-e / r, e / r], rtol=1e-9)


@given(st.floats(0.05, 0.9), st.floats(0.02, 2.0), st.floats(0.02, 0.98))
def test_forward_stroke_ratio_stays_below_one(e: float, extra: float, t: float):
    r = e + extra
    lo, hi = coupler_bounds(e, r)
    c = float(lo + t * (hi - lo))
    n = ratio_by_construction(e, c, r, np.linspace(0.0, 2 * np.pi, 721))
    assert np.nanmax(n) < 1.0


def test_paper_functions_are_7_and_9_cleared_of_fractions():
    e, c, r = crank_rockers(20, seed=3)
    phi, _ = rocker_angle(e, c, r, THETA)
    n, dn, _, _ = ratio_and_derivative(e, c, r, THETA)
    level = 0.37
    denominator = e * np.cos(THETA - phi) - np.cos(phi)
    np.testing.assert_allclose(ratio_function(e, r, level, THETA, phi),
                               r * denominator * (n - level), rtol=1e-10, atol=1e-13)
    # with n = n(θ), F1 of (18) is −r·D·dn/dθ (hand derivation from (7) and (8))
    np.testing.assert_allclose(stationarity_function(e, r, n, THETA, phi),
                               -r * denominator * dn, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("lengths, kind", [
    ((0.3, 1.0, 0.5), "crank-rocker"),
    ((1.5, 0.4, 1.2), "double-rocker"),
    ((0.3, 0.4, 0.5), "non-Grashof"),
    ((0.3, 1.2, 0.5), "change-point"),
])
def test_grashof_type_by_hand(lengths, kind):
    e, c, r = lengths
    assert grashof_type(e, c, r)[0] == kind
    assert (grashof_margin(e, c, r) > 0) == (kind == "crank-rocker")


def test_velocity_ratio_keeps_extended_precision():
    theta = np.longdouble(1.0)
    phi, _ = rocker_angle(np.longdouble(0.3), np.longdouble(1.0), np.longdouble(0.5), theta)
    assert velocity_ratio(np.longdouble(0.3), np.longdouble(0.5), theta, phi).dtype == np.longdouble
