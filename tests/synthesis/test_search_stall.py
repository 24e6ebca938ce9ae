"""The stall rule ends a round whose best no longer improves, and only such a round."""

from __future__ import annotations

import numpy as np

from synthesis import SearchSettings
from synthesis.criteria import Criteria
from synthesis.search import search


def plateau(x: np.ndarray) -> Criteria:
    """Q = max(|x₀ − 0.5|, 0.01): the passive pass improves until it lands within 0.01 of
    0.5, then nothing it draws is better."""
    q = np.maximum(np.abs(x[:, 0] - 0.5), 0.01)
    zero = np.zeros(len(x))
    return Criteria(zero, zero, q, q[:, None], q[:, None])


def last_improvement(q: np.ndarray) -> int:
    """Index of the last trial that lowered the running minimum (counted here, not by the
    search)."""
    best, last = np.inf, 0
    for k, value in enumerate(q):
        if value < best:
            best, last = value, k
    return last


def test_a_round_that_no_longer_improves_ends_after_stall_trials() -> None:
    batch, stall = 8, 40
    settings = SearchSettings(budget_log2=10, batch=batch, stall=stall, shrink_passes=2,
                              refine=False, restarts=0)
    r = search(plateau, [0.0, 0.0], [1.0, 1.0], [0.9, 0.9], settings)
    assert r.stop == "stall"
    trials = r.trials.shape[0]
    assert trials < 2 ** 10
    last = last_improvement(r.trial_criteria.q)
    # the round ends at the end of the first block after which more than `stall` trials
    # have passed since the last improvement; the block before did not yet pass it
    assert trials - last > stall
    assert trials - batch - last <= stall


def test_without_a_stall_the_round_runs_its_budget() -> None:
    # the same run without the rule draws the whole budget: the stall ended it, not the budget
    r = search(plateau, [0.0, 0.0], [1.0, 1.0], [0.9, 0.9],
               SearchSettings(budget_log2=10, batch=8, shrink_passes=2, refine=False,
                              restarts=0))
    assert r.stop == "budget"
    assert r.trials.shape[0] == 1 + 2 ** 10 + 2 * 2 ** 8


def test_each_restart_is_a_round_of_its_own_under_the_stall_rule() -> None:
    batch, stall, restarts = 8, 40, 2
    r = search(plateau, [0.0, 0.0], [1.0, 1.0], [0.9, 0.9],
               SearchSettings(budget_log2=10, batch=batch, stall=stall, shrink_passes=0,
                              refine=False, restarts=restarts))
    assert r.stop == "stall"
    assert [o.round for o in r.optima] == list(range(1 + restarts))
    # replay the rule on the recorded Q: blocks of 8 trials (trial 0, the initial design,
    # opens round 0); a round's best starts afresh, and the round ends after the first block
    # that leaves more than `stall` trials since its last improvement
    q = r.trial_criteria.q
    start, ends = 0, []
    for _ in range(1 + restarts):
        end = start + 1 if start == 0 else start
        while True:
            end += batch
            if end - (start + last_improvement(q[start:end])) > stall:
                break
        ends.append(end)
        start = end
    assert ends[-1] == q.size
    # each round's best is the best of its own trials
    bounds = [0, *ends]
    for o, a, b in zip(r.optima, bounds, bounds[1:]):
        assert o.q == np.min(q[a:b])
