"""The passive search: reproducibility, stop rules, interruption, refinement."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from synthesis import SearchSettings
from synthesis.criteria import Criteria
from synthesis.search import search

OPTIMUM = np.array([0.31, 0.77, 0.12])


def quadratic(x: np.ndarray) -> Criteria:
    """Q = max |x − x*|; designs with x_0 > 0.9 do not exist (P1 = x_0 − 0.9)."""
    dev = x - OPTIMUM
    p1 = np.maximum(x[:, 0] - 0.9, 0.0)
    zero = np.zeros(len(x))
    feasible = p1 == 0
    q = np.where(feasible, np.max(np.abs(dev), axis=1), np.nan)
    return Criteria(p1, np.where(feasible, zero, np.nan), q, dev, dev)


LOWER, UPPER, START = np.zeros(3), np.ones(3), np.array([0.95, 0.5, 0.5])
#: The passive pass alone (the defaults add shrinking passes, restarts and refinement).
PASSIVE: dict[str, Any] = {"refine": False, "shrink_passes": 0, "restarts": 0}


def test_same_seed_same_result_and_other_seed_other_trials() -> None:
    a = search(quadratic, LOWER, UPPER, START, SearchSettings(budget_log2=7, seed=5, **PASSIVE))
    b = search(quadratic, LOWER, UPPER, START, SearchSettings(budget_log2=7, seed=5, **PASSIVE))
    c = search(quadratic, LOWER, UPPER, START, SearchSettings(budget_log2=7, seed=6, **PASSIVE))
    np.testing.assert_array_equal(a.trials, b.trials)
    np.testing.assert_array_equal(a.x, b.x)
    assert not np.array_equal(a.trials[1:], c.trials[1:])


def test_trial_zero_is_the_initial_design_and_the_budget_is_2_to_m() -> None:
    r = search(quadratic, LOWER, UPPER, START, SearchSettings(budget_log2=6, batch=16, **PASSIVE))
    np.testing.assert_array_equal(r.trials[0], START)
    assert r.trials.shape[0] == 1 + 2 ** 6
    assert r.stop == "budget"
    assert np.all((r.trials[1:] >= LOWER) & (r.trials[1:] <= UPPER))
    # the infeasible initial design (P1 > 0) never wins against a feasible one
    assert r.criteria.p1[0] == 0


def test_best_is_the_best_trial_by_the_ranking() -> None:
    r = search(quadratic, LOWER, UPPER, START, SearchSettings(budget_log2=8, **PASSIVE))
    c = r.trial_criteria
    feasible = c.p1 == 0
    assert r.criteria.q[0] == np.min(c.q[feasible])


def test_favourable_design_stops_the_search() -> None:
    r = search(quadratic, LOWER, UPPER, START,
               SearchSettings(budget_log2=12, batch=32, q_required=0.2))
    assert r.stop == "favourable"
    assert r.criteria.q[0] <= 0.2
    assert r.trials.shape[0] < 2 ** 12


def test_no_progress_stops_the_search() -> None:
    def flat(x: np.ndarray) -> Criteria:
        zero = np.zeros(len(x))
        return Criteria(zero, zero, zero + 1.0, zero[:, None], zero[:, None])

    r = search(flat, LOWER, UPPER, START, SearchSettings(budget_log2=12, batch=16, stall=64, **PASSIVE))
    assert r.stop == "stall"
    assert r.trials.shape[0] <= 64 + 2 * 16 + 1


def test_time_limit_stops_the_search() -> None:
    r = search(quadratic, LOWER, UPPER, START,
               SearchSettings(budget_log2=20, batch=64, time_limit=0.2))
    assert r.stop == "time"
    assert r.trials.shape[0] < 2 ** 20


@pytest.mark.parametrize("limit", [5.0, 6.0])
def test_the_time_limit_holds_in_the_refinement(limit: float,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    # a clock that advances one second per evaluation: the limit falls inside the least
    # squares of the first refinement start (initial 1 s, LPτ 2 s, its start 3 s, then the
    # residuals 4 s, the Jacobian 5 s, a step 6 s)
    now = [0.0]

    def slow(x: np.ndarray) -> Criteria:
        now[0] += 1.0
        return quadratic(x)

    monkeypatch.setattr("synthesis.search.time.perf_counter", lambda: now[0])
    r = search(slow, LOWER, UPPER, START, SearchSettings(
        budget_log2=4, batch=16, time_limit=limit, shrink_passes=0, restarts=0))
    assert r.stop == "time" and r.stopped_in == "refine"
    assert now[0] == limit   # not one design evaluated after the limit was reached
    assert r.trials.shape[0] == 1 + 16 + int(np.sum(np.array(r.stage) == "refine"))


def test_ctrl_c_keeps_the_best_so_far() -> None:
    calls = []

    def interrupted(x: np.ndarray) -> Criteria:
        calls.append(len(x))
        if len(calls) == 4:
            raise KeyboardInterrupt
        return quadratic(x)

    r = search(interrupted, LOWER, UPPER, START, SearchSettings(budget_log2=10, batch=32, **PASSIVE))
    assert r.stop == "interrupted"
    assert r.trials.shape[0] == sum(calls[:3])
    assert r.criteria.q[0] == np.nanmin(r.trial_criteria.q)


def test_refinement_and_shrinking_improve_on_the_passive_best() -> None:
    plain = search(quadratic, LOWER, UPPER, START, SearchSettings(budget_log2=7, seed=2, **PASSIVE))
    shrunk = search(quadratic, LOWER, UPPER, START,
                    SearchSettings(budget_log2=7, seed=2, shrink_passes=2, refine=False, restarts=0))
    refined = search(quadratic, LOWER, UPPER, START,
                     SearchSettings(budget_log2=7, seed=2, refine=True, shrink_passes=0, restarts=0))
    assert shrunk.criteria.q[0] < plain.criteria.q[0]
    assert refined.criteria.q[0] < 1e-8
    np.testing.assert_allclose(refined.x, OPTIMUM, atol=1e-8)
    assert set(refined.stage) == {"initial", "lptau", "refine"}


def test_weighted_objective_can_accept_a_desirable_violation() -> None:
    def trade(x: np.ndarray) -> Criteria:
        # P2 = 0 only for x_0 < 0.5, but Q is smallest near x_0 = 0.8
        q = np.abs(x[:, 0] - 0.8)
        p2 = np.maximum(x[:, 0] - 0.5, 0.0) * 0.01
        zero = np.zeros(len(x))
        return Criteria(zero, p2, q, q[:, None], q[:, None])

    lex = search(trade, LOWER, UPPER, START, SearchSettings(budget_log2=8, **PASSIVE))
    soft = search(trade, LOWER, UPPER, START,
                  SearchSettings(budget_log2=8, objective="weighted", p2_weight=1.0, **PASSIVE))
    assert lex.x[0] <= 0.5
    assert soft.x[0] == pytest.approx(0.8, abs=0.02)


def test_refinement_reaches_the_minimax_not_the_least_squares_design() -> None:
    """Δ = (x − 0, x − 0, x − 3): least squares gives x = 1 (Q = 2), minimax x = 1.5 (Q = 1.5)."""
    targets = np.array([0.0, 0.0, 3.0])

    def residual(x: np.ndarray) -> Criteria:
        dev = x[:, :1] - targets[None, :]
        zero = np.zeros(len(x))
        return Criteria(zero, zero, np.max(np.abs(dev), axis=1), dev, dev)

    r = search(residual, [-5.0], [5.0], [4.0], SearchSettings(budget_log2=4, refine=True))
    assert r.criteria.q[0] == pytest.approx(1.5, abs=1e-6)
    assert r.x[0] == pytest.approx(1.5, abs=1e-6)


def two_wells(x: np.ndarray) -> Criteria:
    """Q = min(2·|x − 0.1|, |x − 0.8| + 0.05) in one dimension: a local optimum Q = 0.05
    at x = 0.8 with the wider basin, the global one Q = 0 at x = 0.1."""
    q = np.minimum(2 * np.abs(x[:, 0] - 0.1), np.abs(x[:, 0] - 0.8) + 0.05)
    zero = np.zeros(len(x))
    return Criteria(zero, zero, q, q[:, None], q[:, None])


def test_restarts_are_fresh_rounds_after_the_first() -> None:
    one = search(two_wells, [0.0], [1.0], [0.5], SearchSettings(budget_log2=5, seed=3, **PASSIVE))
    three = search(two_wells, [0.0], [1.0], [0.5],
                   SearchSettings(budget_log2=5, seed=3, refine=False, shrink_passes=0, restarts=2))
    # the first round is the run without restarts, trial for trial
    np.testing.assert_array_equal(three.trials[:one.trials.shape[0]], one.trials)
    assert three.trials.shape[0] == 1 + 3 * 2 ** 5
    rounds = [o for o in three.optima if o.stage == "round"]
    assert [o.round for o in rounds] == [0, 1, 2]
    # each round's best is the best of its own trials, and the result the best of all
    for r, o in enumerate(rounds):
        part = slice(1 + r * 2 ** 5, 1 + (r + 1) * 2 ** 5)
        q = three.trial_criteria.q[part]
        assert o.q == (min(np.min(q), three.trial_criteria.q[0]) if r == 0 else np.min(q))
        assert not np.array_equal(three.trials[part], three.trials[1:1 + 2 ** 5]) or r == 0
    assert three.criteria.q[0] == min(o.q for o in rounds)


def test_refinement_after_the_first_round_and_after_the_restarts() -> None:
    # seed 3: round 0 has the best LPτ trial of all rounds, so the last refinement must
    # skip it (already refined) and start from the best restart round's design
    r = search(two_wells, [0.0], [1.0], [0.5],
               SearchSettings(budget_log2=2, seed=3, refine=True, refine_starts=1,
                              restarts=6, batch=4, shrink_passes=0))
    stage = np.array(r.stage)
    lptau = np.flatnonzero(stage == "lptau")
    assert lptau.size == 7 * 4
    # round 0, its refinement, the six restarts, the last refinement
    assert stage[5] == "refine" and np.all(stage[lptau[4]:lptau[-1] + 1] == "lptau")
    assert np.all(stage[lptau[-1] + 1:] == "refine")
    rows = lptau.reshape(7, 4)
    bests = [r.trials[k[np.argmin(r.trial_criteria.q[k])], 0] for k in rows]
    # the first refinement starts at round 0's best (the initial design is worse)
    assert r.trials[5, 0] == bests[0]
    # the last one at the best restart round's design not already refined
    later = sorted((x for x in bests if abs(x - bests[0]) > 1e-3),
                   key=lambda x: two_wells(np.array([[x]])).q[0])
    assert r.trials[lptau[-1] + 1, 0] == later[0]
    assert len([o for o in r.optima if o.stage == "refine"]) == 2
    assert r.criteria.q[0] == min(o.q for o in r.optima)


def test_a_favourable_design_ends_the_restarts() -> None:
    r = search(quadratic, LOWER, UPPER, START,
               SearchSettings(budget_log2=8, batch=16, q_required=0.2, restarts=5))
    assert r.stop == "favourable"
    assert {o.round for o in r.optima} == {0}
    assert r.trials.shape[0] <= 1 + 2 ** 8
