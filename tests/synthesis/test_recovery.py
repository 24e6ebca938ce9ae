"""Recovery: targets generated from a randomly drawn mechanism are reproduced by the search.

For every task class a mechanism is drawn with a seeded generator (dimensions not chosen by
hand), its output is computed by the hand-written closed forms of ``closed_form.py``, the
problem is built with bounds drawn around the true values and a random initial design, and
the design the search returns is re-analysed with the closed forms (not with the program).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from closed_form import (
    coupler_point,
    crank_rocker,
    distance_to_curve,
    rocker_rotation,
    slider_crank,
)

from synthesis import SearchSettings, problem_from_dict
from synthesis.evaluate import Evaluator
from synthesis.search import search

TOL = 1e-6            # mm / rad; the search stops at [Q] = 1e-7 (favourable) or budget
FOURBAR_ROWS: list[dict[str, Any]] = [
    {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
    {"L": 1, "i": 2, "j": 3, "i_minus_1": 1, "j_minus_1": 0, "variant": 1},
]


def _box(rng: np.random.Generator, true: float, spread: float) -> list[float]:
    """[initial, lower, upper]: a box of width 2·spread·|true| placed at random around true."""
    width = 2 * spread * abs(true)
    lower = true - rng.uniform(0.2, 0.8) * width
    upper = lower + width
    return [float(rng.uniform(lower, upper)), float(lower), float(upper)]


def _fourbar_problem(rng: np.random.Generator, d: dict[str, float], task_class: int,
                     points: list[dict[str, Any]], point: bool) -> dict[str, Any]:
    return {
        "general": {"control_points": len(points), "direction": 1, "groups": 2,
                    "task_class": task_class, "grid": 180, "accuracy": 1e-7},
        "structure_identification": [dict(r) for r in FOURBAR_ROWS],
        "output": {"link": 2, "point": "N"} if point else {"link": 3},
        "parameters": [
            {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": _box(rng, d["l1"], 0.2), "phi_1_0": 0},
            {"links": [2, 3], "x_Hi": "A", "y_Hi": "A", "x_Hj": d["xhj"], "y_Hj": 0,
             "l_i": _box(rng, d["li"], 0.1), "l_j": _box(rng, d["lj"], 0.1),
             "l_N": _box(rng, d["ln"], 0.2) if point else 0,
             "beta_N": _box(rng, math.degrees(d["beta"]), 0.3) if point else 0,
             "l_M": 0, "beta_M": 0},
        ],
        "control_points": points,
    }


def _solve(data: dict[str, Any], budget: int = 9) -> tuple[Any, Any]:
    problem = problem_from_dict(data, "recovery.yaml")
    settings = SearchSettings(budget_log2=budget, seed=1, refine=True, refine_starts=4,
                              q_required=1e-7)
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial,
                    settings)
    return problem, result


def _design(problem: Any, x: np.ndarray) -> dict[str, float]:
    return {name.rsplit(".", 1)[1]: v for name, v in problem.design(x).items()}


@pytest.mark.parametrize("seed", [11, 12])
def test_class1_rocker_angle(seed: int) -> None:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    phi = np.radians(np.arange(12) * 30.0)
    psi = rocker_rotation(phi, d["l1"], d["li"], d["lj"], d["xhj"])
    points = [{"K": k, "phi": float(np.degrees(phi[k])), "psi": float(np.degrees(psi[k]))}
              for k in range(12)]
    problem, result = _solve(_fourbar_problem(rng, d, 1, points, point=False))
    assert result.criteria.p1[0] == 0 and result.criteria.p2[0] == 0
    found = _design(problem, result.x)
    again = rocker_rotation(phi, found["l_1"], found["l_i"], found["l_j"], d["xhj"])
    assert np.max(np.abs(again - psi)) < TOL
    assert result.criteria.q[0] == pytest.approx(np.max(np.abs(again - psi)), abs=1e-9)


@pytest.mark.parametrize("seed", [21, 22])
def test_class2_slider_stroke(seed: int) -> None:
    rng = np.random.default_rng(seed)
    a, rod, e = rng.uniform(20, 50), rng.uniform(120, 200), rng.uniform(-20, 20)
    phi = np.radians(np.arange(12) * 30.0)
    stroke = slider_crank(phi, a, rod, e)
    data = {
        "general": {"control_points": 12, "groups": 2, "task_class": 2, "grid": 180,
                    "accuracy": 1e-7},
        "structure_identification": [
            {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
            {"L": 2, "i": 3, "j": 2, "i_minus_1": 0, "j_minus_1": 1, "variant": 1}],
        "output": {"link": 3},
        "parameters": [
            {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": _box(rng, a, 0.2), "phi_1_0": 0},
            {"links": [3, 2], "x_Hj": "A", "y_Hj": "A", "l_j": _box(rng, rod, 0.2),
             "x_Ak": 0, "y_Ak": 0, "beta_g": 0, "e": [float(rng.uniform(-25, 25)), -25.0, 25.0],
             "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0}],
        "control_points": [{"K": k, "phi": float(np.degrees(phi[k])), "S": float(stroke[k]),
                            "E": 1.0 + k % 2} for k in range(12)],
    }
    problem, result = _solve(data)
    assert result.criteria.p1[0] == 0 and result.criteria.p2[0] == 0
    found = _design(problem, result.x)
    again = slider_crank(phi, found["l_1"], found["l_j"], found["e"])
    weights = 1.0 + np.arange(12) % 2
    assert np.max(weights * np.abs(again - stroke)) < TOL
    assert result.criteria.q[0] == pytest.approx(np.max(weights * np.abs(again - stroke)),
                                                 abs=1e-9)


@pytest.mark.parametrize("seed", [31, 32])
def test_class3_path_without_timing(seed: int) -> None:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    args = (d["l1"], d["li"], d["lj"], d["xhj"], d["ln"], d["beta"])
    targets = coupler_point(np.radians(np.arange(15) * 24.0), *args)
    points = [{"K": k, "x": float(p.real), "y": float(p.imag)} for k, p in enumerate(targets)]
    problem, result = _solve(_fourbar_problem(rng, d, 3, points, point=True))
    assert result.criteria.p1[0] == 0 and result.criteria.p2[0] == 0
    f = _design(problem, result.x)
    curve = coupler_point(np.linspace(0, 2 * np.pi, 40000, endpoint=False), f["l_1"],
                          f["l_i"], f["l_j"], d["xhj"], f["l_N"], math.radians(f["beta_N"]))
    assert np.max(distance_to_curve(curve, targets)) < 5 * TOL


@pytest.mark.parametrize("seed", [41, 42])
def test_class4_path_with_timing(seed: int) -> None:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    args = (d["l1"], d["li"], d["lj"], d["xhj"], d["ln"], d["beta"])
    phi = np.radians(np.arange(15) * 24.0)
    targets = coupler_point(phi, *args)
    points = [{"K": k, "phi": float(np.degrees(phi[k])), "x": float(p.real),
               "y": float(p.imag)} for k, p in enumerate(targets)]
    problem, result = _solve(_fourbar_problem(rng, d, 4, points, point=True))
    assert result.criteria.p1[0] == 0 and result.criteria.p2[0] == 0
    f = _design(problem, result.x)
    again = coupler_point(phi, f["l_1"], f["l_i"], f["l_j"], d["xhj"], f["l_N"],
                          math.radians(f["beta_N"]))
    assert np.max(np.abs(again - targets)) < TOL


def test_class1_zone_is_entered() -> None:
    """A zone of ±0.2° around a random rocker law: the search ends inside it (Q ≤ [Q])."""
    rng = np.random.default_rng(51)
    d = crank_rocker(rng)
    phi = np.radians(np.arange(12) * 30.0)
    psi = np.degrees(rocker_rotation(phi, d["l1"], d["li"], d["lj"], d["xhj"]))
    points = [{"K": k, "phi": float(np.degrees(phi[k])), "psi_lo": float(psi[k] - 0.2),
               "psi_hi": float(psi[k] + 0.2)} for k in range(12)]
    problem, result = _solve(_fourbar_problem(rng, d, 1, points, point=False))
    f = _design(problem, result.x)
    again = np.degrees(rocker_rotation(phi, f["l_1"], f["l_i"], f["l_j"], d["xhj"]))
    assert result.criteria.q[0] <= 1e-7
    assert np.all(np.abs(again - psi) <= 0.2 + math.degrees(1e-7))


def test_fourbar_closed_form_matches_the_model() -> None:
    """The closed form used above and the program agree on one design (guards the tests)."""
    rng = np.random.default_rng(61)
    d = crank_rocker(rng)
    phi = np.radians(np.arange(15) * 24.0)
    targets = coupler_point(phi, d["l1"], d["li"], d["lj"], d["xhj"], d["ln"], d["beta"])
    points = [{"K": k, "phi": float(np.degrees(phi[k])), "x": float(p.real),
               "y": float(p.imag)} for k, p in enumerate(targets)]
    problem = problem_from_dict(_fourbar_problem(rng, d, 4, points, point=True), "t.yaml")
    x = [d["l1"], d["li"], d["lj"], d["ln"], math.degrees(d["beta"])]
    criteria = Evaluator(problem)(np.array([x]))
    assert criteria.q[0] < 1e-9
