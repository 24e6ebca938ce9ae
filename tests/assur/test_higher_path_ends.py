"""The path of the root where the mode ends, and where a link needs sub-steps.

``follow_mode(..., method="roots")`` takes a design from the path of its root also where
its mode ends (the change points located on the local discriminant of the merging pair)
and where a link between two columns fails the step test (walked by sub-steps). Both are
checked against the plain continuation written in ``test_higher_agreement.py`` (the same
positions to 1e-9 L, the same ends to 1e-6°), with the step-by-step follower forbidden, so
that every design comes from the path.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from test_higher_agreement import PHI, TWO_PI, _agree, _pass
from test_higher_overlap import _subset
from test_higher_properties import Designs, random_triads

from assur.kinematics.higher import HigherSolution, assembly_modes, continuation, follow_mode
from assur.kinematics.higher.groups import values
from assur.kinematics.higher.modes import select_mode
from assur.kinematics.reasons import Reason

#: Designs of ``random_triads(90, 400)`` whose drawn mode ends (forward and backward; for
#: the first the backward end comes before the forward one). Not 22, 24 and 30: their
#: sketched root is in no bracket, and the steps follow them (``_follow_tracked``).
ENDING = [0, 3, 4, 5, 13, 18, 19, 31, 37]
#: Designs of the same sample whose path goes round the turn but has a 5° link that fails
#: the step test between two roots of the path (a close approach of another root).
NEAR = [132, 276, 307, 386]


def _forbidden(*args: Any) -> None:
    raise AssertionError("a design was followed step by step")


def _check(designs: Designs, monkeypatch: pytest.MonkeyPatch) -> HigherSolution:
    """The roots' solution, with no design by steps, against the plain continuation."""
    group = designs.group
    d = len(designs.pin)
    k0 = values(designs.inputs(np.zeros(d)))
    x0, found = select_mode(group, k0, assembly_modes(group, k0))
    assert found.all()
    ahead = _pass(designs, x0, found, 1.0, np.append(PHI[1:], TWO_PI))
    ended = ~np.isnan(ahead[1])
    behind = _pass(designs, x0, found & ended, -1.0, np.append(np.sort(TWO_PI - PHI[1:]), TWO_PI))
    with monkeypatch.context() as patch:
        patch.setattr(continuation, "_step_follow", _forbidden)
        solution = follow_mode(group, designs.inputs, PHI, method="roots")
    _agree(solution, designs, x0, found, ahead, behind)
    return solution


def test_a_mode_that_ends_is_taken_from_the_path(monkeypatch: pytest.MonkeyPatch) -> None:
    designs = _subset(random_triads(90, 400), np.array(ENDING))  # type: ignore[arg-type]
    solution = _check(designs, monkeypatch)
    assert np.isfinite(solution.ends).all()
    assert (solution.end_reasons == Reason.MODE_ENDS).all()
    gone = ~solution.exists
    assert gone[1:].any(axis=1).all()
    assert (solution.reason[gone] == Reason.MODE_ENDS).all()
    assert (solution.margin[gone] < 0.0).all()  # no root of the pair on the circle
    assert solution.closed.all()
    assert solution.overlap[0]  # the backward end before the forward one: every angle
    assert solution.exists[0].all()  # assembles, the later ones turning backward


def test_a_link_closer_than_the_columns_is_walked(monkeypatch: pytest.MonkeyPatch) -> None:
    designs = _subset(random_triads(90, 400), np.array(NEAR))  # type: ignore[arg-type]
    solution = _check(designs, monkeypatch)
    assert solution.exists.all() and np.isnan(solution.ends).all()
    # without the sub-steps these designs are not certified by the path
    monkeypatch.setattr(continuation, "REFINE_TRIALS", 0)
    monkeypatch.setattr(continuation, "_step_follow", _forbidden)
    with pytest.raises(AssertionError, match="step by step"):
        follow_mode(designs.group, designs.inputs, PHI, method="roots")


def test_the_extremum_between_a_merging_pair_is_where_the_slope_vanishes() -> None:
    """``_extremum`` from a start 0.1 rad away lands on the zero of Φ′ found by bisection on
    a sign change of Φ′ written out here (Φ(θ) = Σ φ_n e^{inθ}), to 1e-12 rad, and its local
    discriminant −Φ·sign Φ″ there is the one computed from that zero."""
    rng = np.random.default_rng(5)
    m = 3
    n = np.arange(-m, m + 1)
    half = rng.normal(size=(40, m)) + 1j * rng.normal(size=(40, m))
    coef = np.concatenate([np.conj(half[:, ::-1]), rng.normal(size=(40, 1)), half], axis=1)
    coef[:, m + 1] += 4.0  # a dominant first harmonic: one maximum and one minimum
    coef[:, m - 1] += 4.0

    def derivative(k: int, theta: np.ndarray) -> np.ndarray:
        return np.real(((1j * n) ** k * coef * np.exp(1j * n * theta[:, None])).sum(axis=-1))

    grid = np.linspace(0.0, TWO_PI, 4001)
    slopes = np.stack([derivative(1, np.full(40, t)) for t in grid], axis=1)
    first = np.argmax(np.sign(slopes[:, :-1]) != np.sign(slopes[:, 1:]), axis=1)
    low, high = grid[first], grid[first + 1]
    for _ in range(60):  # bisection on the sign of Φ′
        mid = 0.5 * (low + high)
        same = np.sign(derivative(1, mid)) == np.sign(derivative(1, low))
        low, high = np.where(same, mid, low), np.where(same, high, mid)
    zero = 0.5 * (low + high)
    theta, local = continuation._extremum(coef, zero + rng.choice([-0.1, 0.1], 40))
    assert np.abs(np.angle(np.exp(1j * (theta - zero)))).max() <= 1e-12
    expected = -derivative(0, zero) * np.sign(derivative(2, zero))
    np.testing.assert_allclose(local, expected, rtol=1e-12, atol=1e-12)
