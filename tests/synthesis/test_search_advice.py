"""A run short of [Q] says what to try, with the distinct optima its rounds ended at."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from synthesis import load_problem, synthesize
from synthesis.search_settings import settings_for

ROCKER = Path(__file__).resolve().parents[2] / "input_tables/problems/class1_fourbar_rocker.yaml"


def test_the_advice_counts_the_distinct_ends_of_the_rounds() -> None:
    problem = load_problem(ROCKER)
    budget, restarts = 4, 5
    outcome = synthesize(problem, settings_for(problem, budget_log2=budget, refine=False,
                                               shrink_passes=0, restarts=restarts, seed=2))
    result, advice = outcome.search, outcome.to_dict()["advice"]
    assert advice is not None and not outcome.favourable
    # the rounds' bests found again from the raw trials: trial 0 and round 0's 2^m trials,
    # then 2^m trials per restart
    c = result.trial_criteria
    ok = (c.p1 == 0) & (c.p2 == 0)
    span = problem.upper - problem.lower
    ends: list[tuple[float, np.ndarray]] = []
    for r in range(1 + restarts):
        part = np.arange(0 if r == 0 else 1 + r * 2 ** budget, 1 + (r + 1) * 2 ** budget)
        part = part[ok[part]]
        if part.size:
            k = part[np.argmin(c.q[part])]
            ends.append((float(c.q[k]), result.trials[k]))
    distinct: list[tuple[float, np.ndarray]] = []
    for q, x in sorted(ends, key=lambda e: e[0]):
        if all(np.max(np.abs(x - y) / span) > 1e-3 for _, y in distinct):
            distinct.append((q, x))
    scale = problem.output_scale
    assert len(distinct) > 1
    assert advice["optima"] == len(distinct) and advice["rounds"] == 1 + restarts
    assert advice["q_min"] == distinct[0][0] * scale == outcome.q
    assert advice["q_max"] == distinct[-1][0] * scale
    # several optima: more restarts, a larger budget, and the refinement that was off
    tries = {t["what"]: t.get("value") for t in advice["try"]}
    assert tries == {"budget": budget + 2, "refine": None, "restarts": 2 * restarts}
