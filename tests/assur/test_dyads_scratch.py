"""The RRR speed path keeps scratch arrays between calls: results must never share them.

A solution is checked against the closure of the dyad (|C − H_i| = l_i, |C − H_j| = l_j, the
link angles pointing from the hinges to C) and against the readable solver (a jet argument
takes it), after later calls of the same shape have run, and while other threads solve other
dyads of that shape at the same time; and two solutions of one shape share no memory.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from typing import cast

import numpy as np

from assur.kinematics.dyads import DyadSolution, solve_rrr
from assur.kinematics.jets import Jet

EPS = np.finfo(float).eps
L_I, L_J, H_J = 80.0, 90.0, 100.0 + 0.0j


def pins(seed: int, n: int) -> np.ndarray:
    """Crank pins of a four-bar (crank 30 mm at the origin) at ``n`` random angles."""
    angles = np.random.default_rng(seed).uniform(-np.pi, np.pi, n)
    return np.asarray(30.0 * np.exp(1j * angles))


def closure_error(h_i: np.ndarray, dyad: DyadSolution) -> float:
    """The largest miss of the dyad's closure and link angles, relative to its size."""
    c, angle_i, angle_j = (np.asarray(x) for x in (dyad.c, dyad.angle_i, dyad.angle_j))
    misses = [np.abs(np.abs(c - h_i) - L_I), np.abs(np.abs(c - H_J) - L_J),
              np.abs(h_i + L_I * np.exp(1j * angle_i) - c),
              np.abs(H_J + L_J * np.exp(1j * angle_j) - c)]
    return float(max(np.max(m) for m in misses)) / (L_I + L_J + abs(H_J))


def test_a_solution_is_unchanged_by_later_calls() -> None:
    first_pins, later_pins = pins(1, 360), pins(2, 360)
    first = solve_rrr(first_pins, H_J, L_I, L_J, 1.0)
    readable = solve_rrr(Jet(first_pins), H_J, L_I, L_J, 1.0)
    for sigma in (1.0, -1.0):  # same shape, other positions and the other branch
        solve_rrr(later_pins, H_J, L_I, L_J, sigma)
    assert first.exists.all()
    assert closure_error(first_pins, first) <= 8 * EPS
    size = L_I + L_J + abs(H_J)
    assert np.max(np.abs(np.asarray(first.c) - cast(Jet, readable.c).v)) <= 4 * EPS * size
    np.testing.assert_array_equal(first.margin, readable.margin)


def test_threads_solving_at_once_keep_their_own_results() -> None:
    n = 12_000  # one block of the kernel, long enough for the threads' calls to overlap

    def solve(seed: int) -> float:
        h_i = pins(seed, n)
        worst = 0.0
        for _ in range(40):
            worst = max(worst, closure_error(h_i, solve_rrr(h_i, H_J, L_I, L_J, 1.0)))
        return worst

    with ThreadPoolExecutor(max_workers=4) as pool:
        errors = list(pool.map(solve, range(4)))
    assert max(errors) <= 8 * EPS


def test_solutions_of_one_shape_share_no_memory() -> None:
    first_pins, later_pins = pins(3, 360), pins(4, 360)
    first = solve_rrr(first_pins, H_J, L_I, L_J, 1.0)
    later = solve_rrr(later_pins, H_J, L_I, L_J, -1.0)
    fields = ("c", "angle_i", "angle_j", "margin")
    for name in fields:
        for other in fields:
            assert not np.may_share_memory(getattr(first, name), getattr(later, other)), (
                name, other)
