"""Candidate designs of a problem with a triad reach the triad's solver as one batch.

The evaluator of ``class2_six_bar_triad.yaml`` is given D candidate designs at once; every
solve of the triad group must see all D of them along one design axis (shape (D,)), never
one design at a time. The criteria of the batch must equal those of the designs evaluated
one by one (an evaluation written here as the loop the batch replaces).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from assur.kinematics.analysis import State
from synthesis import load_problem
from synthesis.evaluate import Evaluator

PROBLEM = Path(__file__).resolve().parents[2] / "input_tables" / "problems" \
    / "class2_six_bar_triad.yaml"


def test_the_triad_is_solved_once_per_batch_over_the_design_axis(
        monkeypatch: pytest.MonkeyPatch) -> None:
    problem = load_problem(PROBLEM)
    evaluator = Evaluator(problem, grid=12)
    rng = np.random.default_rng(26)
    designs = problem.lower + (problem.upper - problem.lower) * rng.uniform(0.3, 0.7, (6, 4))
    seen: list[tuple[int, ...]] = []
    solve = State.solve

    def recording(state: State, group: Any, q: Any) -> None:
        if group.layout is not None:
            seen.append(state.flat_shape)
        solve(state, group, q)

    monkeypatch.setattr(State, "solve", recording)
    batch = evaluator(designs)
    assert seen and all(shape == (len(designs),) for shape in seen)
    calls = len(seen)
    monkeypatch.setattr(State, "solve", solve)
    one_by_one = [evaluator(design[None, :]) for design in designs]
    for k, single in enumerate(one_by_one):
        np.testing.assert_allclose(batch.q[k], single.q[0], rtol=1e-9, atol=1e-12)
    assert calls <= 2  # one analysis of the batch (and at most one of its control points)
