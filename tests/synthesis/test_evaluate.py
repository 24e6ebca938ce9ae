"""Block B2 on a four-bar: P1, pressure angle and joint rotation against closed forms."""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np
import pytest

from synthesis import problem_from_dict
from synthesis.evaluate import Evaluator

XHJ = 100.0
DATA: dict[str, Any] = {
    "general": {"control_points": 2, "groups": 2, "task_class": 1, "grid": 72},
    "structure_identification": [
        {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
        {"L": 1, "i": 2, "j": 3, "i_minus_1": 1, "j_minus_1": 0, "variant": 1}],
    "output": {"link": 3},
    "parameters": [
        {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": [30, 10, 80], "phi_1_0": 0},
        {"links": [2, 3], "x_Hi": "A", "y_Hi": "A", "x_Hj": XHJ, "y_Hj": 0, "l_i": 90,
         "l_j": [70, 40, 120], "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0}],
    "allowable": [{"links": [2, 3], "pressure_angle": 30, "rotations": {"H_j": 20}}],
    "control_points": [{"K": 0, "phi": 0, "psi": 0}, {"K": 1, "phi": 180, "psi": 10}],
}


def _cosine(phi: np.ndarray, l1: float, li: float, lj: float) -> np.ndarray:
    """c of the RRR existence condition at H_i = crank pin (method.md §2.1)."""
    d = np.abs(XHJ - l1 * np.exp(1j * phi))
    return (li ** 2 + d ** 2 - lj ** 2) / (2 * li * d)


def test_p1_of_a_crank_too_long_to_turn() -> None:
    problem = problem_from_dict(copy.deepcopy(DATA), "fourbar.yaml")
    l1, lj = 75.0, 60.0
    criteria = Evaluator(problem)(np.array([[l1, lj]]))
    # grid positions and the two control angles (0 and 180°) are all checked
    phi = np.concatenate([2 * np.pi * np.arange(72) / 72, [0.0, np.pi]])
    v = np.abs(_cosine(phi, l1, 90.0, lj)) - 1.0
    # N_Q = 2 and the failing group is the 2nd: π = (2 − 2) + v/(1 + v) where v > 0
    expected = np.sum(np.where(v > 0, v / (1 + v), 0.0))
    assert expected > 0
    assert criteria.p1[0] == pytest.approx(expected, rel=1e-12)
    assert math.isnan(criteria.q[0]) and math.isnan(criteria.p2[0])


def test_pressure_angle_and_rocker_swing_penalties() -> None:
    problem = problem_from_dict(copy.deepcopy(DATA), "fourbar.yaml")
    l1, lj = 30.0, 70.0
    analysis = Evaluator(problem).analyse(np.array([[l1, lj]]))
    phi = 2 * np.pi * np.arange(72) / 72
    a = l1 * np.exp(1j * phi)
    d = np.abs(XHJ - a)
    # transmission angle μ at C from the law of cosines; α = |90° − μ|
    mu = np.arccos((90.0 ** 2 + lj ** 2 - d ** 2) / (2 * 90.0 * lj))
    alpha = np.max(np.abs(np.pi / 2 - mu))
    # rocker angle: C found by hand (left of A → H_j), angle of H_j → C
    w = XHJ - a
    phi_i = np.angle(w) + np.arccos(_cosine(phi, l1, 90.0, lj))
    rocker = np.unwrap(np.angle(a + 90.0 * np.exp(1j * phi_i) - XHJ))
    swing = np.ptp(rocker)
    assert analysis.pressure["L1(2,3)"][0, 0] == pytest.approx(alpha, abs=1e-12)
    assert analysis.rotations["L1(2,3)"][0, 0] == pytest.approx(swing, abs=1e-12)
    expected = (alpha - math.radians(30)) / math.radians(30) + \
        (swing - math.radians(20)) / math.radians(20)
    assert analysis.criteria.p2[0] == pytest.approx(expected, rel=1e-12)
    # ψ at 180° is the unwrapped rocker angle there, from its value at 0
    assert analysis.output_control[0, 1] == pytest.approx(rocker[36] - rocker[0], abs=1e-12)


def test_workspace_penalty_of_the_joints_of_a_group() -> None:
    data = copy.deepcopy(DATA)
    data["allowable"] = [{"links": [2, 3], "workspace": {"x": [-200, 200], "y": [-20, 300]}}]
    problem = problem_from_dict(data, "fourbar.yaml")
    l1, lj = 30.0, 70.0
    criteria = Evaluator(problem)(np.array([[l1, lj]]))
    phi = 2 * np.pi * np.arange(72) / 72
    a = l1 * np.exp(1j * phi)
    c = a + 90.0 * np.exp(1j * (np.angle(XHJ - a) + np.arccos(_cosine(phi, l1, 90.0, lj))))
    # the crank pin dips to y = −30 (10 mm below the box); C and the pivot stay inside
    excess = np.max(np.maximum(-20.0 - a.imag, 0)) + np.max(np.maximum(-20.0 - c.imag, 0))
    assert excess == pytest.approx(10.0, abs=1e-9)
    assert criteria.p2[0] == pytest.approx(excess / math.hypot(400.0, 320.0), rel=1e-12)
