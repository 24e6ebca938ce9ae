"""Synthesis of mechanisms driven by a cylinder or by two cranks, checked by hand.

The boom of ``input_tables/problems/class1_boom_cylinder.yaml`` is re-solved in closed form:
the triangle A–B–C (|AC| fixed on the boom, |BC| the cylinder's length) gives the boom's
angle, and the moment balance of the boom about A — the massless cylinder a two-force
member pushing along BC, the payload at its point — gives the driving force.  The five-bar's
targets come from a closed form of the two cranks and the RRR dyad.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from closed_form import dyad

import assur
from assur.forces.solver import kinetostatics
from assur.kinematics.analysis import analyse
from synthesis import SearchSettings, load_problem
from synthesis.cli import main
from synthesis.evaluate import Evaluator
from synthesis.search import search

ROOT = Path(__file__).resolve().parents[2]
BOOM = ROOT / "input_tables" / "problems" / "class1_boom_cylinder.yaml"
FIVE_BAR = ROOT / "input_tables" / "problems" / "class4_five_bar_two_cranks.yaml"
A, C0 = 0j, 150 + 40j          # the boom's pivot and the cylinder's hinge on it, as drawn
AC = abs(C0 - A)


def _boom(b: complex, s_min: float, s_max: float, t: np.ndarray, load: complex,
          at: float) -> tuple[np.ndarray, np.ndarray]:
    """Boom angle (of A → C, radians) and the cylinder's pushing force (N) at the cycle
    parameter t: |BC| = s_min + (s_max − s_min)(1 − cos t)/2, C to the left of A → B as
    drawn; the payload ``load`` (N) acts ``at`` mm from A along A → C."""
    q = s_min + (s_max - s_min) * (1 - np.cos(t)) / 2
    d = abs(b - A)
    angle_b = math.atan2(b.imag, b.real)
    cos_a = (AC ** 2 + d ** 2 - q ** 2) / (2 * AC * d)
    phi = angle_b + np.arccos(cos_a)          # left of A → B
    c = A + AC * np.exp(1j * phi)
    u = (c - b) / np.abs(c - b)
    p = A + at * np.exp(1j * phi)

    def cross(r: np.ndarray | complex, f: np.ndarray | complex) -> np.ndarray:
        return np.asarray((np.conj(r) * f).imag)

    force = -cross(p - A, load) / cross(c - A, u)
    return phi, force


def _found(problem: Any, x: np.ndarray) -> tuple[complex, float, float]:
    f = {name.rsplit(".", 1)[1]: v for name, v in problem.design(x).items()}
    return complex(f["x_Hj"], f["y_Hj"]), f["s_min"], f["s_max"]


def test_boom_cylinder_bounds_respect_the_driving_force_limit() -> None:
    spec = yaml.safe_load(BOOM.read_text(encoding="utf-8"))
    limit = spec["forces"]["limits"]["driving_force"]
    load = complex(*spec["forces"]["loads"][0]["force"])
    at = spec["forces"]["loads"][0]["point"][0]
    (row,) = spec["control_points"]
    problem = load_problem(BOOM)
    t = np.linspace(0, 2 * np.pi, 2001)
    # the drawn design: its cylinder pushes harder than the limit, and misses the lift
    phi, force = _boom(80 - 30j, 90.0, 130.0, t, load, at)
    assert np.max(np.abs(force)) > 1.4 * limit
    assert math.degrees(phi[1000] - phi[0]) < row["psi_lo"]
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial,
                    problem.settings)
    assert result.criteria.feasible[0] and result.criteria.q[0] == 0
    b, s_min, s_max = _found(problem, result.x)
    assert s_min < s_max
    phi, force = _boom(b, s_min, s_max, t, load, at)
    lift = math.degrees(phi[1000] - phi[0])                  # t = 180°: the full stroke
    assert row["psi_lo"] <= lift <= row["psi_hi"]
    grid = np.linspace(0, 2 * np.pi, problem.grid, endpoint=False)
    assert np.max(np.abs(_boom(b, s_min, s_max, grid, load, at)[1])) <= limit * (1 + 1e-9)
    assert np.max(np.abs(force)) <= limit * 1.001           # between the grid positions too
    # the result file's mechanism moves the cylinder over the found stroke
    table = problem.mechanism_table(result.x)
    assert assur.build_model(assur.analyse_structure(assur.chain_from_dict(
        table))).input_range == pytest.approx((s_min, s_max), rel=1e-11)
    # the program's driving force is the one of the hand calculation
    assert problem.forces is not None
    model = Evaluator(problem).model(result.x[None])
    motion = analyse(model, grid, analogs=True)
    forces = kinetostatics(motion, problem.forces.data_of(motion), problem.forces.omega)
    np.testing.assert_allclose(np.abs(np.ravel(forces.driving)),
                               np.abs(_boom(b, s_min, s_max, grid, load, at)[1]), rtol=1e-9)


def _pen(t: np.ndarray, l1: float, l4: float, li: float, lj: float, lp: float,
         beta: float) -> np.ndarray:
    """The pen P of the five-bar: crank 1 about (0, 0) at 90° + t, crank 4 about (60, 0)
    at 90° + (90° + 2t) (the law's phase and ratio added to the sketched angle), the rods
    meeting at C left of B → D, P at lp from B at beta from B → C."""
    b = l1 * np.exp(1j * (np.pi / 2 + t))
    d = 60 + l4 * np.exp(1j * (np.pi / 2 + np.pi / 2 + 2 * t))
    c = dyad(b, d, li, lj, 1)
    out: np.ndarray = b + lp * np.exp(1j * (np.angle(c - b) + beta))
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_five_bar_over_two_input_laws_is_recovered(seed: int) -> None:
    spec = yaml.safe_load(FIVE_BAR.read_text(encoding="utf-8"))
    t = np.radians([row["phi"] for row in spec["control_points"]])
    targets = np.array([row["x"] + 1j * row["y"] for row in spec["control_points"]])
    # the file's points are those of the design it names
    truth = _pen(t, 25.0, 25.0, 70.0, 70.0, 50.0, math.radians(20.0))
    assert np.max(np.abs(truth - targets)) < 1e-8
    problem = load_problem(FIVE_BAR)
    settings = SearchSettings(budget_log2=8, seed=seed, refine=True, q_required=1e-7)
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial,
                    settings)
    assert result.criteria.feasible[0] and result.criteria.q[0] < 1e-6
    f = problem.design(result.x)
    found = _pen(t, f["L0(1).l_1"], f["L0(4).l_1"], f["L1(2,3).l_i"], f["L1(2,3).l_j"],
                 f["L1(2,3).l_P"], math.radians(f["L1(2,3).beta_P"]))
    assert np.max(np.abs(found - targets)) < 1e-6


def test_an_effort_limit_needs_an_input_of_its_kind(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    spec = yaml.safe_load((ROOT / "input_tables" / "problems"
                           / "class1_fourbar_torque_limit.yaml").read_text(encoding="utf-8"))
    spec["forces"]["limits"] = {"driving_force": 100}
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(spec, allow_unicode=True), encoding="utf-8")
    assert main(["synthesize", str(bad)]) == 2
    err = capsys.readouterr().err
    assert ("forces.limits 'driving_force': the mechanism has no input whose effort is a "
            "'driving_force'; its inputs' efforts are driving_torque") in err
