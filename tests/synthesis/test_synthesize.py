"""``synthesize``: B2–B5 composed once; the report's RMS is the weighted one of the criteria."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from synthesis import SearchSettings, problem_from_dict, synthesize
from synthesis.criteria import criterion_rms
from synthesis.evaluate import Evaluator
from synthesis.search import search
from tests.synthesis.test_problem import GOOD


def _slider_crank_stroke(l1: float, l2: float, e: float, phi: np.ndarray) -> np.ndarray:
    """S(φ) − S(0) of a slider-crank with the guide along x at offset e (closed form)."""
    def x(angle: np.ndarray) -> np.ndarray:
        out: np.ndarray = l1 * np.cos(angle) + np.sqrt(l2 ** 2 - (l1 * np.sin(angle) - e) ** 2)
        return out
    stroke: np.ndarray = x(phi) - x(np.zeros(1))
    return stroke


def test_outcome_of_a_problem() -> None:
    problem = problem_from_dict(copy.deepcopy(GOOD), "good.yaml")
    outcome = synthesize(problem, SearchSettings(budget_log2=5, seed=2), progress=False)
    again = search(Evaluator(problem), problem.lower, problem.upper, problem.initial,
                   SearchSettings(budget_log2=5, seed=2))
    np.testing.assert_array_equal(outcome.search.x, again.x)
    data = outcome.to_dict()
    assert outcome.feasible == data["feasible"] == outcome.search.feasible
    assert outcome.design == data["design"] == problem.design(outcome.search.x)
    with pytest.raises(AttributeError):
        outcome.search = again  # type: ignore[misc]  # frozen


def test_report_rms_is_the_weighted_rms_of_the_criteria() -> None:
    data = copy.deepcopy(GOOD)
    data["control_points"] = [{"K": 0, "phi": 0, "S": 0, "E": 1},
                              {"K": 1, "phi": 90, "S": -30.0, "E": 3},
                              {"K": 2, "phi": 180, "S": -62.0, "E": 0.5}]
    problem = problem_from_dict(data, "weights.yaml")
    outcome = synthesize(problem, SearchSettings(budget_log2=3, seed=0), progress=False)
    l1, l2 = outcome.search.x
    # the slider of L2(3,2) moves along the frame guide through (0, 0) at angle 0 with the
    # offset e = 5 of its rod hinge; the crank is hinged at the origin
    stroke = _slider_crank_stroke(l1, l2, 5.0, np.radians([0.0, 90.0, 180.0]))
    delta = stroke - np.array([0.0, -30.0, -62.0])
    weights = np.array([1.0, 3.0, 0.5])
    weighted = math.sqrt(np.sum(weights * delta ** 2) / np.sum(weights))
    plain = math.sqrt(np.mean(delta ** 2))
    assert outcome.to_dict()["Q_rms"] == pytest.approx(weighted, rel=1e-9)
    assert abs(weighted - plain) > 1e-3 * weighted  # the two definitions differ here
    assert outcome.to_dict()["Q_rms"] == pytest.approx(
        float(criterion_rms(outcome.analysis.criteria.deviations, weights)[0]), rel=1e-12)
