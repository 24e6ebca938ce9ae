"""The refinement holds the desirable conditions as constraints and slides along their limit."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from synthesis import SearchSettings, problem_from_dict
from synthesis.criteria import Criteria
from synthesis.evaluate import Evaluator
from synthesis.search import search
from tests.synthesis.test_evaluate import DATA, XHJ, _cosine

TARGET = np.array([0.9, 0.6])


def limited(x: np.ndarray) -> Criteria:
    """Q = max |x − (0.9, 0.6)| under the desirable condition x₀ + x₁ ≤ 1 (margin x₀ + x₁ − 1).

    By hand: min t with x₀ ≥ 0.9 − t, x₁ ≥ 0.6 − t, x₀ + x₁ ≤ 1 gives 1.5 − 2t ≤ 1, so
    t = 0.25 at the single point x = (0.65, 0.35), on the limit of the condition.
    """
    dev = x - TARGET
    margins = (x[:, 0] + x[:, 1] - 1.0)[:, None]
    zero = np.zeros(len(x))
    return Criteria(zero, np.maximum(margins[:, 0], 0.0), np.max(np.abs(dev), axis=1), dev,
                    dev, margins)


def test_the_refinement_reaches_the_optimum_on_the_limit_of_a_desirable_condition() -> None:
    for seed in range(3):
        r = search(limited, [0.0, 0.0], [1.0, 1.0], [0.2, 0.2],
                   SearchSettings(budget_log2=5, seed=seed, shrink_passes=0, restarts=0))
        assert r.criteria.p2[0] == 0.0
        assert r.criteria.q[0] == pytest.approx(0.25, abs=1e-6)
        np.testing.assert_allclose(r.x, [0.65, 0.35], atol=1e-5)


def test_a_refined_design_that_breaks_a_condition_is_never_the_result() -> None:
    r = search(limited, [0.0, 0.0], [1.0, 1.0], [0.2, 0.2],
               SearchSettings(budget_log2=5, seed=1, shrink_passes=0, restarts=0))
    refined = np.array(r.stage) == "refine"
    c = r.trial_criteria
    # the polish steps outside the allowed region on its way, but only a design that keeps
    # every condition can be the result, and the result is the best of those
    assert np.any(c.margins[refined, 0] > 0)
    held = c.p2 == 0
    assert r.criteria.q[0] == np.min(c.q[held])


def test_margins_of_a_four_bar_against_the_closed_form() -> None:
    """The margins are (α_max − [α])/[α], (Δθ − [Δθ])/[Δθ] and the signed box clearance, and
    their positive parts add up to P2 (test_evaluate.py finds α_max and Δθ by hand)."""
    data = copy.deepcopy(DATA)
    data["allowable"] = [{"links": [2, 3], "pressure_angle": 60, "rotations": {"H_j": 20},
                          "workspace": {"x": [-200, 200], "y": [-50, 300]}}]
    problem = problem_from_dict(data, "fourbar.yaml")
    l1, lj = 30.0, 70.0
    analysis = Evaluator(problem).analyse(np.array([[l1, lj]]))
    phi = 2 * np.pi * np.arange(72) / 72
    a = l1 * np.exp(1j * phi)
    d = np.abs(XHJ - a)
    alpha = np.max(np.abs(np.pi / 2 - np.arccos((90.0 ** 2 + lj ** 2 - d ** 2) / (180.0 * lj))))
    c = a + 90.0 * np.exp(1j * (np.angle(XHJ - a) + np.arccos(_cosine(phi, l1, 90.0, lj))))
    swing = np.ptp(np.unwrap(np.angle(c - XHJ)))
    # every joint stays inside the box; the nearest side is y = −50, reached by the crank
    # pin (y = −30, clearance 20), by C (its lowest y) or by the pivots (y = 0, clearance 50)
    clearance = [np.min(a.imag) + 50.0, np.min(c.imag) + 50.0, 50.0]
    scale = math.hypot(400.0, 350.0)
    margins = analysis.criteria.margins[0]
    assert margins.shape == (5,)
    assert margins[0] == pytest.approx(alpha / math.radians(60) - 1.0, abs=1e-12)
    assert margins[1] == pytest.approx(swing / math.radians(20) - 1.0, abs=1e-12)
    assert sorted(margins[2:]) == pytest.approx(sorted(-np.array(clearance) / scale), abs=1e-12)
    assert margins[0] < 0 < margins[1] and np.all(margins[2:] < 0)
    assert analysis.criteria.p2[0] == pytest.approx(np.sum(np.maximum(margins, 0)), rel=1e-12)
