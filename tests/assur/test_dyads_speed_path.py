"""The plain-array path of ``solve_input`` and ``solve_rrr`` against answers found another way.

The usual call (crank pins as an array; the other hinge, the lengths and the branch as
numbers) skips the general argument handling, keeps the link lengths' arrays with its scratch
and decides existence from one search for the smallest margin. Each check below computes
what that call must give in its own way: the law of cosines for the margin, the triangle
inequality for existence and reasons, the sign of a cross product for the branch, and
``numpy.min`` for the smallest element.
"""

from __future__ import annotations

import numpy as np
import pytest

from assur.kinematics import _fast
from assur.kinematics.dyads import Reason, solve_input, solve_rrr

H_J = 100.0 + 0.0j


def pins(n: int, radius: float = 30.0, seed: int = 3) -> np.ndarray:
    """Crank pins of a crank of ``radius`` at the origin, at ``n`` random angles."""
    return np.asarray(radius * np.exp(1j * np.random.default_rng(seed).uniform(-np.pi, np.pi, n)))


def cosine_margin(h_i: np.ndarray, l_i: float, l_j: float) -> np.ndarray:
    """``1 − |cos|`` of the angle at H_i by the law of cosines (NaN where it is undefined)."""
    d = np.abs(H_J - h_i)
    return 1.0 - np.abs((l_i * l_i + d * d - l_j * l_j) / (2.0 * l_i * d))


def closure_miss(h_i: np.ndarray, c: np.ndarray, l_i: float, l_j: float) -> float:
    """The largest miss of |C − H_i| = l_i and |C − H_j| = l_j, relative to the dyad's size."""
    misses = np.concatenate([np.abs(np.abs(c - h_i) - l_i), np.abs(np.abs(c - H_J) - l_j)])
    return float(np.max(misses)) / (l_i + l_j + abs(H_J))


def test_link_lengths_kept_with_the_scratch_are_those_of_the_call() -> None:
    h_i = pins(360)
    pairs = [(70.0 + 2.0 * k, 90.0 - k) for k in range(2 * _fast.KEPT_LENGTHS + 3)]
    for l_i, l_j in pairs + pairs[::-1] + pairs[:3]:  # kept, dropped and made again
        dyad = solve_rrr(h_i, H_J, l_i, l_j, 1.0)
        assert dyad.exists.all()
        assert closure_miss(h_i, np.asarray(dyad.c), l_i, l_j) <= 1e-14
        np.testing.assert_allclose(dyad.margin, cosine_margin(h_i, l_i, l_j), atol=1e-12)


@pytest.mark.parametrize("sigma", [1, -1, 0, 1.0, -1.0, 0.0, np.float64(-1.0), np.float64(2.0)])
def test_the_branch_of_a_number_sigma(sigma: float) -> None:
    h_i = pins(50)
    c = np.asarray(solve_rrr(h_i, H_J, 80.0, 90.0, sigma).c)
    left = np.imag(np.conj(H_J - h_i) * (c - h_i)) > 0.0  # C left of the line H_i → H_j
    assert left.all() if sigma >= 0 else not left.any()  # σ = 0 reads as +1 (table 1.6)


def test_existence_against_a_tolerance_between_the_margins() -> None:
    h_i = pins(400)
    margin = cosine_margin(h_i, 80.0, 90.0)
    delta = float(np.median(margin))
    dyad = solve_rrr(h_i, H_J, 80.0, 90.0, 1.0, delta)
    close = np.abs(margin - delta) <= 1e-12  # the test's margin may round the other way there
    np.testing.assert_array_equal(dyad.exists[~close], (margin >= delta)[~close])
    np.testing.assert_array_equal(dyad.reason[dyad.exists], Reason.ASSEMBLES)
    c = np.asarray(dyad.c)
    assert np.isnan(c[~dyad.exists]).all() and np.isfinite(c[dyad.exists]).all()


def test_reasons_from_the_triangle_inequality() -> None:
    l_i, l_j = 3.0, 0.5  # folded where d < 2.5, stretched where d > 3.5
    d = np.array([1.9, 2.4, 2.6, 3.0, 3.4, 3.6, 0.0, 5.0, 1.0])
    h_i = H_J - d * np.exp(0.7j)
    dyad = solve_rrr(h_i, H_J, l_i, l_j, -1.0)
    expected = np.select([d == 0.0, d > l_i + l_j, d < l_i - l_j],
                         [Reason.COINCIDENT_HINGES, Reason.STRETCHED, Reason.FOLDED],
                         Reason.ASSEMBLES)
    np.testing.assert_array_equal(dyad.reason, expected)
    np.testing.assert_array_equal(dyad.exists, expected == Reason.ASSEMBLES)
    assert closure_miss(h_i[dyad.exists], np.asarray(dyad.c)[dyad.exists], l_i, l_j) <= 1e-14


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_a_crank_angle_that_is_not_finite(bad: float) -> None:
    angle = np.linspace(0.0, 6.0, 7)
    angle[[2, 5]] = bad
    pin = solve_input(1.0 - 2.0j, 30.0, angle)
    finite = np.isfinite(angle)
    np.testing.assert_array_equal(pin.exists, finite)
    np.testing.assert_array_equal(pin.reason, np.where(finite, 0, Reason.UNDEFINED_INPUT))
    expected = 1.0 - 2.0j + 30.0 * (np.cos(angle[finite]) + 1j * np.sin(angle[finite]))
    np.testing.assert_allclose(np.asarray(pin.c)[finite], expected, rtol=0, atol=1e-13)


@pytest.mark.parametrize("shape", [(7,), (3, 5), (2, 3, 4)])
def test_smallest_element(shape: tuple[int, ...]) -> None:
    rng = np.random.default_rng(11)
    for _ in range(50):
        x = rng.uniform(-1.0, 1.0, shape)
        if rng.random() < 0.5:
            x.flat[rng.integers(x.size)] = np.nan
        for view in (x, x.T, x[..., ::2]):
            expected = np.min(view)  # NaN if any element is NaN
            np.testing.assert_array_equal(_fast.smallest(view), expected)
    assert _fast.smallest(np.empty((0, 3))) == np.inf
