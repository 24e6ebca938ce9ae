"""Force limits in the synthesis (``docs/forces.md`` §9): P2_F over batches of designs.

The problem ``class1_fourbar_torque_limit.yaml`` loads the rocker with a torque T only, so by
virtual work the driving torque is M_d = −T·dψ/dφ (counter-clockwise crank): the checks below
take dψ/dφ from central differences of the rocker angle, never from the force analysis.
"""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path

import numpy as np
import pytest
import yaml

import assur
from assur.forces import ForceData, Mass, kinetostatics
from assur.kinematics.analysis import analyse, values
from assur.kinematics.build import load_with_forces
from synthesis import load_problem, problem_from_dict, synthesize
from synthesis.evaluate import Evaluator
from synthesis.force_conditions import force_penalties

TABLES = Path(__file__).resolve().parents[2] / "input_tables"
PROBLEM = TABLES / "problems" / "class1_fourbar_torque_limit.yaml"
TORQUE, LIMIT, STEP = 15.0, 8.0, 1e-6


def _torque_by_virtual_work(evaluator: Evaluator, x: np.ndarray) -> np.ndarray:
    """max_φ |T·dψ/dφ| over the grid, per design (central differences of the rocker angle)."""
    model = evaluator.model(x)
    ahead = analyse(model, evaluator.grid + STEP).link_angle(3)
    behind = analyse(model, evaluator.grid - STEP).link_angle(3)
    rate = np.angle(np.exp(1j * (np.asarray(ahead) - np.asarray(behind)))) / (2 * STEP)
    peak: np.ndarray = np.max(np.abs(TORQUE * rate), axis=-1)
    return peak


def test_the_penalty_of_a_batch_is_the_excess_of_the_torque_by_virtual_work() -> None:
    problem = load_problem(PROBLEM)
    evaluator = Evaluator(problem)
    rng = np.random.default_rng(5)
    lower, upper = 0.6 * problem.lower, 1.4 * problem.upper   # some do not assemble
    x = lower + rng.random((24, 3)) * (upper - lower)
    criteria = evaluator(x)
    feasible = criteria.p1 == 0
    assert 4 < feasible.sum() < 24
    got = force_penalties(problem.forces, evaluator.model, x, feasible, evaluator.grid)
    torque = _torque_by_virtual_work(evaluator, x[feasible])
    np.testing.assert_allclose(got[feasible], np.maximum(0.0, torque - LIMIT) / LIMIT,
                               rtol=1e-6, atol=1e-9)
    assert np.all(got[~feasible] == 0)
    # the designs' P2 is the other desirable conditions' plus this penalty
    free = Evaluator(dataclasses.replace(problem, forces=None))(x)
    np.testing.assert_allclose(criteria.p2[feasible], free.p2[feasible] + got[feasible])


def test_a_torque_limit_moves_the_optimum_and_the_result_respects_it() -> None:
    problem = load_problem(PROBLEM)
    free = dataclasses.replace(problem, forces=None)
    # the LPτ trials only, and no early stop: both searches run to their best design
    settings = dataclasses.replace(problem.settings, refine=False, q_required=1e-4)
    limited = synthesize(problem, settings, progress=False)
    unlimited = synthesize(free, settings, progress=False)
    evaluator = Evaluator(problem)
    x_lim, x_free = np.atleast_2d(limited.search.x), np.atleast_2d(unlimited.search.x)
    # without the limit the best design needs more torque than allowed ...
    assert _torque_by_virtual_work(evaluator, x_free)[0] > LIMIT * 1.1
    # ... with it the search settles elsewhere, less accurate, and within the limit
    assert limited.feasible and limited.search.criteria.p2[0] == 0
    assert np.max(np.abs(x_lim - x_free)) > 5.0
    assert limited.q > 10 * unlimited.q
    assert _torque_by_virtual_work(evaluator, x_lim)[0] <= LIMIT * (1 + 1e-6)


def test_points_in_the_link_frames_give_what_sketch_points_give() -> None:
    model, data = load_with_forces(TABLES / "four_bar_gravity.yaml")
    assert data is not None
    frames = analyse(model, np.zeros(1), analogs=True).frames
    local = {}
    for link, mass in data.masses.items():
        origin, angle = (np.asarray(values(v)).item() for v in frames[link])
        local[link] = Mass(mass.mass, (mass.centre - origin) * np.exp(-1j * angle),
                           mass.inertia)
    motion = analyse(model, points=24, analogs=True)
    sketch = kinetostatics(motion, data, 10.0)
    framed = kinetostatics(motion, ForceData(local, data.loads, data.gravity, local=True),
                           10.0)
    np.testing.assert_allclose(framed.driving, sketch.driving, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(framed.reactions["C"].x, sketch.reactions["C"].x, atol=1e-10)


def test_every_problem_of_the_forces_table_is_reported_at_once() -> None:
    data = yaml.safe_load(PROBLEM.read_text())
    bad = copy.deepcopy(data)
    bad["forces"] = {"omega": -1, "masses": {9: {"mass": 1, "centre": {"l": 5, "beta": 0}}},
                     "loads": [{"link": 3, "torque": -15}],
                     "limits": {"driving_torque": 0, "reactions": {"X": 100, "2-3": -5}},
                     "torque": 1}
    with pytest.raises(assur.TableError) as caught:
        problem_from_dict(bad, "bad.yaml")
    text = caught.value.text("en")
    for part in ("unknown key 'torque'", "forces 'omega'", "forces.masses.9",
                 "forces.limits 'driving_torque'", "forces.limits.reactions 'X'",
                 "forces.limits.reactions '2-3'"):
        assert part in text, part


def test_a_reaction_limit_is_the_excess_of_the_two_force_coupler() -> None:
    # With only a torque T on the rocker, the coupler 2–3 carries a force along B–C alone,
    # |R| = |T| / (distance from the rocker pivot D to the line B–C), from the joints alone.
    problem = load_problem(PROBLEM)
    assert problem.forces is not None
    conditions = dataclasses.replace(problem.forces, driving_torque=None,
                                     reactions={"2-3": 150.0})
    evaluator = Evaluator(problem)
    x = np.array([[36.0, 110.0, 105.0], [44.0, 130.0, 90.0]])
    feasible = evaluator(x).p1 == 0
    assert feasible.all()
    got = force_penalties(conditions, evaluator.model, x, feasible, evaluator.grid)
    joints = analyse(evaluator.model(x), evaluator.grid).joints
    b, c, d = (np.asarray(values(joints[p])) for p in ("1-2", "2-3", "3-0"))
    along = (c - b) / np.abs(c - b)
    arm = np.abs((np.conj(along) * (d - c)).imag) * 1e-3        # m
    largest = np.max(TORQUE / arm, axis=-1)
    np.testing.assert_allclose(got, np.maximum(0.0, largest - 150.0) / 150.0, rtol=1e-9)
    assert (got > 0).any()
