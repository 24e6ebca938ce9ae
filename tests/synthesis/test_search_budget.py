"""The budget bounds the whole search, refinement included (issue 30, item 6).

The evaluator counts the designs it is given itself, independently of the search's record, so
the bound is checked against what was really evaluated.
"""

from __future__ import annotations

import numpy as np

from synthesis import SearchSettings
from synthesis.criteria import Criteria
from synthesis.search import search
from synthesis.search_result import SearchResult

#: Six varied parameters; the target of the residuals lies outside the box, so no design
#: reaches it and the refinement has every reason to go on.
Q = 6


class Rosenbrock:
    """Residuals of a chained Rosenbrock valley shifted outside the unit box: a slow,
    curved descent that least squares follows with many small steps."""

    def __init__(self) -> None:
        self.evaluated = 0

    def __call__(self, x: np.ndarray) -> Criteria:
        self.evaluated += len(x)
        y = 3.0 * x - 2.5                               # valley floor at y = 1 ↔ x = 7/6 > 1
        dev = np.concatenate([10.0 * (y[:, 1:] - y[:, :-1] ** 2), 1.0 - y], axis=1)
        zero = np.zeros(len(x))
        return Criteria(zero, zero, np.max(np.abs(dev), axis=1), dev, dev)


def _run(**fields: object) -> tuple[Rosenbrock, SearchSettings, SearchResult]:
    base: dict[str, object] = {"budget_log2": 3, "batch": 8, "shrink_passes": 0,
                               "restarts": 0, "refine_starts": 3, "refine_evaluations": 20}
    settings = SearchSettings(**{**base, **fields})  # type: ignore[arg-type]
    evaluate = Rosenbrock()
    result = search(evaluate, np.zeros(Q), np.ones(Q), np.full(Q, 0.1), settings)
    return evaluate, settings, result


def test_the_refinement_stops_at_the_budget_and_names_its_stage() -> None:
    evaluate, settings, result = _run()
    # the passive pass plans 1 + 2^3 trials; the refinement's share is 3 × 20 (each of its
    # starts could evaluate 20 residuals and 20 Jacobians of 6 designs, and the polish more)
    assert settings.planned == 9 and settings.evaluations == 9 + 60
    # a Jacobian batch (Q designs) may end past the budget, never more
    assert settings.evaluations <= evaluate.evaluated <= settings.evaluations + Q
    assert result.trials.shape[0] == evaluate.evaluated
    assert result.stop == "budget" and result.stopped_in == "refine"


def test_a_larger_budget_lets_the_same_refinement_run_further() -> None:
    small, _, _ = _run()
    large, settings, r_large = _run(budget_log2=7)   # 129 planned: E = 258
    assert large.evaluated > small.evaluated
    assert settings.evaluations <= large.evaluated <= settings.evaluations + Q
    assert r_large.stop == "budget" and r_large.stopped_in == "refine"


def test_the_time_limit_still_holds_in_the_refinement() -> None:
    evaluate, settings, result = _run(time_limit=1e-9)
    assert result.stop == "time"
    assert evaluate.evaluated < settings.evaluations
