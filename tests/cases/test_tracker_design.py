"""Tracker case: the design procedure Etapa I–VI, checked by plain simulation."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from synthesis.cases.tracker.design import (
    PATENT_TASK,
    DesignTask,
    choose,
    design_at,
    design_table,
    refine,
)
from synthesis.cases.tracker.study import run_study, verify


def _confirmed(task: DesignTask, design) -> None:
    """A plain simulation of the returned dimensions meets every requirement of the task."""
    check = verify(design, positions=361)
    assert check.assembles
    assert check.stroke == pytest.approx(task.stroke, abs=1e-9)
    assert check.b_min >= task.min_transmission - 1e-9
    assert check.min_clearance >= task.min_clearance - 1e-6
    assert check.motion.s[-1] - check.motion.s[0] <= task.actuator_stroke + 1e-9


def test_patent_example_picks_k2_2_2_as_the_patent_does():
    table = design_table(PATENT_TASK)
    assert table.k2_min == 1.6                        # Etapa I: k2 = 1.4 gives 22.8° < 25°
    chosen = choose(table)
    assert (chosen.k2, chosen.k5) == (2.2, 2.0)        # Etapa VI of the patent
    assert chosen.l2 == pytest.approx(660.0) and chosen.l5 == pytest.approx(600.0)
    assert chosen.l_d == pytest.approx(1215.0, abs=0.04 * 300)   # Tabel 1, bold column
    _confirmed(PATENT_TASK, chosen)


def _simulated_admissible(task: DesignTask, design) -> bool:
    check = verify(design, positions=181)
    return (check.assembles and check.b_min >= task.min_transmission - 1e-9
            and check.clearance >= task.min_clearance - 1e-9
            and check.motion.s[-1] - check.motion.s[0] <= task.actuator_stroke + 1e-9)


@pytest.mark.parametrize("changes", [
    {"stroke": math.radians(180.0)},
    {"stroke": math.radians(240.0), "min_transmission": math.radians(20.0),
     "min_clearance": 40.0},
    {"k5": (1.8, 2.5), "min_clearance": 70.0},
    {"min_transmission": math.radians(30.0), "min_clearance": 60.0, "l1": 250.0,
     "actuator_stroke": 760.0, "k2": (1.5, 1.9, 2.3, 2.7)},
], ids=["a180", "a240-b20", "k5-1.8-2.5", "b30-l1-250"])
def test_other_tasks_give_designs_a_simulation_confirms(changes):
    task = replace(PATENT_TASK, **changes)
    table = design_table(task)
    chosen = choose(table)
    assert chosen is not None
    _confirmed(task, chosen)
    # the choice is the shortest l_d among the rows a simulation finds admissible
    rows = [table.design(i, j) for i in range(len(task.k2)) for j in range(len(task.k5))]
    admissible = [d for d in rows if _simulated_admissible(task, d)]
    assert min(d.l_d for d in admissible) == pytest.approx(chosen.l_d)
    refined = refine(task, chosen.k5)
    _confirmed(task, refined)
    assert refined.l_d <= chosen.l_d + 1e-9


def test_refined_design_sits_on_the_border_of_the_clearance():
    refined = refine(PATENT_TASK, 2.0)
    assert refined.l_g == pytest.approx(85.0, abs=1e-6)
    assert 2.0 < refined.k2 < 2.2
    slightly_smaller = design_at(PATENT_TASK, refined.k2 - 1e-4, 2.0)
    assert [v.requirement for v in slightly_smaller.violations] == ["clearance"]


def test_continuous_k2_finds_the_window_between_the_table_rows():
    # b_min ≥ 30° needs k2 above ~1.93, l_s ≤ 700 mm needs k2 below ~2.0: no row fits
    task = replace(PATENT_TASK, min_transmission=math.radians(30.0), min_clearance=60.0,
                   l1=250.0, actuator_stroke=700.0, k2=(1.5, 1.9, 2.3, 2.7))
    assert choose(design_table(task)) is None
    refined = refine(task, 2.0)
    _confirmed(task, refined)
    assert math.degrees(refined.b_min) == pytest.approx(30.0, abs=1e-6)


def test_impossible_requirements_give_no_design_and_say_why():
    task = replace(PATENT_TASK, min_clearance=500.0)
    assert choose(design_table(task)) is None
    assert refine(task, 2.0) is None
    study = run_study(task)
    assert study.chosen is None and study.refined is None
    violation = design_at(task, 2.2, 2.0).violations[0]
    assert violation.requirement == "clearance" and violation.limit == 500.0


def test_design_table_broadcasts_over_k2_and_k5():
    task = replace(PATENT_TASK, k5=(1.8, 2.0, 2.2))
    table = design_table(task)
    assert table.values.k_s.shape == (5, 3)
    assert np.array_equal(table.values.b_min[:, 0], table.values.b_min[:, 2])


@pytest.mark.parametrize("changes, message", [
    ({"stroke": 0.0}, "strictly between 0° and 360°"),
    ({"min_transmission": math.radians(95.0)}, r"\[0°, 90°\)"),
    ({"l1": -1.0}, "l1 must be positive"),
    ({"min_clearance": -1.0}, "must not be negative"),
    ({"k5": (0.5,)}, "k5 needs at least one value, each greater than 1"),
])
def test_task_rejects_bad_values(changes, message):
    with pytest.raises(ValueError, match=message):
        replace(PATENT_TASK, **changes)
