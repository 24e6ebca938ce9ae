"""The speed paths of :mod:`assur.kinematics._fast` against the readable solvers.

Hypothesis draws RRR inputs of every layout the fast kernel meets (positions of one design,
designs × positions, calls large enough to be cut into blocks) and mixes in the positions
where the two paths must settle something: exact and near toggles (stretched and folded, in
and just outside the tolerance band), coincident hinges, links of zero or negative length,
non-assembling positions and NaN inputs. The fast kernel must give what the readable path
gives: the same margins, hinge distances, existence and reasons, and the same joint and link
angles. The crank's fast path must give the readable ``l·u(φ) + O``.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from assur.kinematics import _fast
from assur.kinematics.dyads import _rrr_limits, _rrr_readable, solve_input, solve_rrr
from assur.kinematics.jets import Jet

EPS = np.finfo(float).eps


def hinge_distances(rng: np.random.Generator, l_i: np.ndarray, l_j: np.ndarray,
                    shape: tuple[int, ...], undefined: bool) -> np.ndarray:
    """Hinge distances over ``shape``: generic, near or at both toggles; if ``undefined``,
    also zero and NaN (margin NaN)."""
    stretched = np.broadcast_to(l_i + l_j, shape)
    folded = np.broadcast_to(np.abs(l_i - l_j), shape)
    generic = rng.uniform(0.0, 1.5, shape) * stretched
    nudge = rng.choice([-1.0, 1.0], shape) * 10.0 ** rng.uniform(-17.0, -9.0, shape)
    weights = np.array([1.0, 1.0, 1.0, 1.0, undefined, undefined, 1.0])
    choice = rng.choice(7, shape, p=weights / weights.sum())
    return np.select(
        [choice == 0, choice == 1, choice == 2, choice == 3, choice == 4, choice == 5],
        [stretched * (1.0 + nudge), folded * (1.0 + nudge), stretched, folded,
         np.zeros(shape), np.full(shape, np.nan)],
        generic)


@st.composite
def rrr_arguments(draw: st.DrawFn) -> tuple:
    """(h_i, h_j, l_i, l_j, s, shape) of a plain-array RRR call."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    layout = draw(st.sampled_from(["positions", "designs", "blocks"]))
    n = int(rng.integers(1, 64))
    designs = {"positions": 0, "designs": int(rng.integers(1, 8)),
               "blocks": 2 * _fast.BLOCK // 300 + int(rng.integers(1, 20))}[layout]
    if layout == "blocks":
        n = 300
    scale = 10.0 ** draw(st.floats(-3.0, 6.0))
    ratio = 10.0 ** draw(st.floats(-9.0, 9.0))
    lengths = (designs, 1) if designs else ()
    l_i = scale * rng.uniform(0.5, 2.0, lengths)
    l_j = ratio * scale * rng.uniform(0.5, 2.0, lengths)
    undefined = draw(st.booleans())
    odd = draw(st.sampled_from(["none", "zero_i", "zero_j", "negative"]))
    if odd != "none" and designs and undefined:
        target = {"zero_i": l_i, "zero_j": l_j, "negative": l_j}[odd]
        target[0, 0] = -target[0, 0] if odd == "negative" else 0.0
    shape = (designs, n) if designs else (n,)
    h_i = scale * (rng.standard_normal(n) + 1j * rng.standard_normal(n))  # shape (n,)
    d = hinge_distances(rng, l_i, l_j, shape, undefined)
    h_j = h_i + d * np.exp(1j * rng.uniform(-np.pi, np.pi, shape))
    s = draw(st.sampled_from([1.0, -1.0, "array"]))
    if s == "array":
        s = rng.choice([-1.0, 1.0], lengths or (1,))
    if l_i.ndim == 0:
        l_i, l_j = float(l_i), float(l_j)
    return h_i, h_j, l_i, l_j, s, shape


@given(arguments=rrr_arguments())
def test_fast_rrr_equals_the_readable_path(arguments: tuple) -> None:
    h_i, h_j, l_i, l_j, s, shape = arguments
    fast = _fast.rrr(h_i, h_j, l_i, l_j, s, shape, _rrr_limits)
    readable = _rrr_readable(h_i, h_j, l_i, l_j, s)
    c, angle_i, angle_j, margin, d = (np.broadcast_to(x, shape) for x in readable[:5])
    np.testing.assert_array_equal(fast[3], margin)  # NaN where NaN
    np.testing.assert_array_equal(fast[4], d)
    np.testing.assert_array_equal(fast[5], readable[5])  # the smallest margin
    size = np.abs(h_j - h_i) + np.abs(l_i) + np.abs(l_j)  # the perimeter of the triangle
    np.testing.assert_array_equal(np.isnan(fast[0]), np.isnan(c))
    ok = np.isfinite(c)
    assert np.all(np.abs(fast[0] - c)[ok] <= 4 * EPS * size[ok])
    for fast_angle, angle, hinge in ((fast[1], angle_i, h_i), (fast[2], angle_j, h_j)):
        turn = np.angle(np.exp(1j * (fast_angle - angle)))  # moves C by turn·|C − hinge|
        assert np.all((np.abs(turn) * np.abs(c - hinge))[ok] <= 4 * EPS * size[ok])


@given(arguments=rrr_arguments(), delta=st.sampled_from([0.0, 1e-3]))
def test_fast_and_readable_solutions_agree(arguments: tuple, delta: float) -> None:
    h_i, h_j, l_i, l_j, s, _shape = arguments
    fast = solve_rrr(h_i, h_j, l_i, l_j, s, delta)
    readable = solve_rrr(Jet(h_i), h_j, l_i, l_j, s, delta)  # a jet takes the readable path
    np.testing.assert_array_equal(fast.exists, readable.exists)
    np.testing.assert_array_equal(fast.reason, readable.reason)
    np.testing.assert_array_equal(fast.margin, readable.margin)
    size = np.abs(h_j - h_i) + np.abs(l_i) + np.abs(l_j)
    ok = fast.exists
    assert np.all(np.isnan(fast.c[~ok])) and np.all(np.isnan(readable.c.v[~ok]))
    assert np.all(np.abs(fast.c - readable.c.v)[ok] <= 4 * EPS * size[ok])


@given(seed=st.integers(0, 2**32 - 1), designs=st.sampled_from([0, 3]),
       pivot=st.sampled_from([0j, 1.5 - 2.0j]))
def test_fast_crank_equals_the_readable_path(seed: int, designs: int, pivot: complex) -> None:
    rng = np.random.default_rng(seed)
    count = int(rng.choice([rng.integers(1, 50), rng.integers(1024, 1500)]))  # both unit forms
    angles = rng.uniform(-10.0, 10.0, count)
    length = rng.uniform(0.1, 50.0, (designs, 1)) if designs else float(rng.uniform(0.1, 50))
    assert _fast.crank_pin(pivot, length, angles) is not None  # the fast path serves this
    pin = solve_input(pivot, length, angles)
    readable = solve_input(pivot, length, Jet(angles))  # a jet takes the readable path
    np.testing.assert_array_equal(pin.c, readable.c.v)
    assert pin.exists.all() and (pin.margin == 1.0).all()
    exact = pivot + length * np.exp(1j * angles)  # numpy's complex exponential
    assert np.all(np.abs(pin.c - exact) <= 4 * EPS * (np.abs(length) + abs(pivot)))
