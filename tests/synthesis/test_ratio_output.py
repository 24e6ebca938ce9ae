"""Class 1 with the velocity ratio n = dψ/dφ as the controlled output (``output: ratio``).

The ratio of the loop (exact first analogs) is compared with a central difference of the
positions of the public analysis; a ratio law drawn from a random crank-rocker is recovered
and the design re-analysed by the hand-written closed form of ``closed_form.py``; bad
``output`` values are reported by file and field.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from closed_form import fourbar

import assur
import assur.kinematics.analysis
from assur import TableError
from assur.kinematics.analysis import analyse
from synthesis import SearchSettings, load_problem, problem_from_dict
from synthesis.cli import main
from synthesis.evaluate import Evaluator
from synthesis.search import search

FOURBAR_ROWS = [
    {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
    {"L": 1, "i": 2, "j": 3, "i_minus_1": 1, "j_minus_1": 0, "variant": 1},
]


def _problem(truth: dict[str, float], rows: list[dict[str, Any]], *, spread: float = 0.0,
             rng: np.random.Generator | None = None) -> dict[str, Any]:
    """A class-1 ratio problem of a four-bar; with ``spread`` > 0 the coupler, the rocker and
    the start angle are varied in boxes of that relative half-width around ``truth``."""
    def cell(value: float, width: float) -> float | list[float]:
        if not spread:
            return value
        assert rng is not None
        lo, hi = value - width, value + width
        return [float(rng.uniform(lo, hi)), lo, hi]

    return {
        "general": {"control_points": len(rows), "groups": 2, "task_class": 1,
                    "output": "ratio", "grid": 120, "accuracy": 1e-10},
        "structure_identification": copy.deepcopy(FOURBAR_ROWS),
        "output": {"link": 3},
        "parameters": [
            {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": truth["l1"],
             "phi_1_0": cell(truth["phi0"], 30 * spread)},
            {"links": [2, 3], "x_Hi": "A", "y_Hi": "A", "x_Hj": truth["xhj"], "y_Hj": 0,
             "l_i": cell(truth["li"], truth["li"] * spread),
             "l_j": cell(truth["lj"], truth["lj"] * spread),
             "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0}],
        "control_points": rows,
    }


def _crank_rocker(rng: np.random.Generator) -> dict[str, float]:
    """A random Grashof crank-rocker (crank shortest, 10 mm clear of the Grashof limit)."""
    while True:
        l1 = rng.uniform(15, 40)
        xhj, li, lj = rng.uniform(70, 130, size=3)
        longest = max(xhj, li, lj)
        if l1 + longest <= xhj + li + lj - longest - 10:
            return {"l1": l1, "xhj": xhj, "li": li, "lj": lj, "phi0": rng.uniform(0, 360)}


def _closed_form_ratio(d: dict[str, float], phi: np.ndarray, h: float = 1e-3) -> np.ndarray:
    """n = dψ/dφ by a fourth-order central difference of the closed-form rocker angle."""
    stencil = np.asarray(phi)[:, None] + h * np.array([-2.0, -1.0, 1.0, 2.0])
    _, _, _, psi = fourbar(stencil, d["l1"], d["li"], d["lj"], d["xhj"],
                           phi0=math.radians(d["phi0"]))
    psi = np.unwrap(psi, axis=1)
    n: np.ndarray = (psi[:, 0] - 8 * psi[:, 1] + 8 * psi[:, 2] - psi[:, 3]) / (12 * h)
    return n


def test_ratio_against_central_difference_of_the_public_analysis() -> None:
    rng = np.random.default_rng(5)
    base = _crank_rocker(rng)          # 10 mm clear of the Grashof limit: ±2 mm keep it
    designs = [dict(base, li=base["li"] + rng.uniform(-2, 2), lj=base["lj"] + rng.uniform(-2, 2),
                    phi0=rng.uniform(0, 360)) for _ in range(6)]
    phi_deg = np.sort(rng.uniform(-180, 360, size=9))
    rows = [{"K": k, "phi": float(p), "n": 0.0} for k, p in enumerate(phi_deg)]
    problem = problem_from_dict(_problem(base, rows, spread=0.5, rng=rng))
    evaluator = Evaluator(problem)
    x = np.array([[d["phi0"], d["li"], d["lj"]] for d in designs])
    analysis = evaluator.analyse(x)
    assert np.all(analysis.criteria.p1 == 0)
    # positions only (no analogs), a fourth-order central difference in φ
    h = 1e-3
    phi = np.radians(phi_deg)
    stencil = (phi[:, None] + h * np.array([-2.0, -1.0, 1.0, 2.0])).ravel()
    motion = analyse(evaluator.model(x), stencil)
    psi = assur.kinematics.analysis.unwrap(assur.kinematics.analysis.values(motion.link_angle(3)).reshape(len(x), phi.size, 4))
    central = (psi[..., 0] - 8 * psi[..., 1] + 8 * psi[..., 2] - psi[..., 3]) / (12 * h)
    assert np.max(np.abs(central)) > 0.1            # the ratios are not trivially small
    assert analysis.output_control == pytest.approx(central, abs=1e-9)
    # the curve over the grid (reports) is the same ratio, at the grid angles
    grid = evaluator.grid[::10]
    stencil = (grid[:, None] + h * np.array([-2.0, -1.0, 1.0, 2.0])).ravel()
    psi = assur.kinematics.analysis.unwrap(assur.kinematics.analysis.values(analyse(evaluator.model(x), stencil).link_angle(3))
                       .reshape(len(x), grid.size, 4))
    central = (psi[..., 0] - 8 * psi[..., 1] + 8 * psi[..., 2] - psi[..., 3]) / (12 * h)
    assert analysis.output_grid[:, ::10] == pytest.approx(central, abs=1e-9)
    # the criteria path leaves the curve out but gives the same deviations
    assert evaluator(x).deviations == pytest.approx(analysis.criteria.deviations, abs=1e-15)


@pytest.mark.parametrize("zone", [False, True], ids=["values", "zone"])
def test_ratio_law_of_a_random_crank_rocker_is_recovered(zone: bool) -> None:
    rng = np.random.default_rng(2026)
    truth = _crank_rocker(rng)
    phi_deg = np.arange(0.0, 360.0, 45.0)
    n = _closed_form_ratio(truth, np.radians(phi_deg))
    if zone:   # a band of ±0.002 around the law, with its ends as equalities
        rows = [{"K": k, "phi": float(p), "n_lo": float(v - 0.002), "n_hi": float(v + 0.002)}
                for k, (p, v) in enumerate(zip(phi_deg, n))]
        for row in (rows[0], rows[-1]):
            row["n_lo"] = row["n_hi"] = row["n_lo"] + 0.002
    else:
        rows = [{"K": k, "phi": float(p), "n": float(v)}
                for k, (p, v) in enumerate(zip(phi_deg, n))]
    problem = problem_from_dict(_problem(truth, rows, spread=0.2, rng=rng))
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial,
                    SearchSettings(budget_log2=8, seed=1, refine=True, q_required=1e-10,
                                   refine_evaluations=400))
    assert result.criteria.p1[0] == 0 and result.criteria.p2[0] == 0
    assert result.criteria.q[0] <= 1e-9
    # independent re-analysis of the design found: closed form, central difference
    found = {**truth, "phi0": result.x[0], "li": result.x[1], "lj": result.x[2]}
    again = _closed_form_ratio(found, np.radians(phi_deg))
    if zone:
        lo = np.array([r["n_lo"] for r in rows])
        hi = np.array([r["n_hi"] for r in rows])
        miss = np.maximum(0.0, np.maximum(lo - again, again - hi))
    else:
        miss = np.abs(again - n)
    assert float(np.max(miss)) <= 1e-8                # difference error ~1e-11 plus Q


def _write(tmp_path: Path, data: dict[str, Any]) -> Path:
    path = tmp_path / "ratio.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    return path


def test_bad_output_values_are_reported_by_file_and_field(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    truth = {"l1": 30.0, "xhj": 100.0, "li": 90.0, "lj": 70.0, "phi0": 0.0}
    good = _problem(truth, [{"K": 0, "phi": 10.0, "n": 0.3}], spread=0.1,
                    rng=np.random.default_rng(0))
    assert load_problem(_write(tmp_path, good)).output.ratio

    data = copy.deepcopy(good)
    data["general"]["output"] = "speed"
    path = _write(tmp_path, data)
    with pytest.raises(TableError) as caught:
        load_problem(path)
    text = str(caught.value)
    assert str(path) in text
    assert "general 'output': expected one of 'angle', 'ratio'; found 'speed'" in text
    assert "unknown key" not in text                  # the n column is not reported as well
    assert main(["synthesize", str(path)]) == 2
    assert "general 'output'" in capsys.readouterr().err

    data = copy.deepcopy(good)
    data["control_points"] = [{"K": 0, "phi": 10.0, "psi": 5.0}]
    with pytest.raises(TableError) as caught:
        load_problem(_write(tmp_path, data))
    assert "control_points[0]: unknown key 'psi'" in str(caught.value)

    data = copy.deepcopy(good)
    data["general"]["task_class"] = 2
    data["control_points"] = [{"K": 0, "phi": 10.0, "S": 5.0}]
    with pytest.raises(TableError) as caught:
        load_problem(_write(tmp_path, data))
    assert "general 'output': only task class 1 chooses its output" in str(caught.value)
