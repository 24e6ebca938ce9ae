"""The criteria and conditions added to the problem table: a class-2 tolerance zone,
``criterion: rms``, stroke ranges of prismatic pairs, laws as formulas of φ — each against a
hand calculation on an offset slider-crank (``closed_form.slider_crank``) — and their
validation (exit 2, the field named, expected and found)."""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from closed_form import slider_crank

from synthesis import problem_from_dict
from synthesis.cli import main
from synthesis.evaluate import Evaluator
from synthesis.expressions import LawError, parse_law

A, ROD = 30.0, 150.0        # crank and rod of the slider-crank, mm (no offset)
PHI = np.arange(12) * 30.0  # degrees
SLIDER: dict[str, Any] = {
    "general": {"control_points": 12, "groups": 2, "task_class": 2, "grid": 36},
    "structure_identification": [
        {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
        {"L": 2, "i": 3, "j": 2, "i_minus_1": 0, "j_minus_1": 1, "variant": 1}],
    "output": {"link": 3},
    "parameters": [
        {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": [A, 20.0, 40.0], "phi_1_0": 0},
        {"links": [3, 2], "x_Hj": "A", "y_Hj": "A", "l_j": ROD, "x_Ak": 0, "y_Ak": 0,
         "beta_g": 0, "e": 0, "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0}],
}
STROKE = slider_crank(np.radians(PHI), A, ROD, 0.0)   # S(φ) − S(0), by hand
WEIGHTS = 1.0 + np.arange(12) % 3


def _problem(**tables: Any) -> Any:
    data = copy.deepcopy(SLIDER)
    data.update(tables)
    return problem_from_dict(data, "fields.yaml")


def test_class2_tolerance_zone_deviations() -> None:
    """A band S* ± 1 mm around a shifted target: Δ_K = E_K·max(0, lo − S, S − hi)."""
    target = STROKE + np.linspace(-3.0, 3.0, 12)
    lo, hi = target - 1.0, target + 1.0
    rows = [{"K": k, "phi": float(PHI[k]), "S_lo": float(lo[k]), "S_hi": float(hi[k]),
             "E": float(WEIGHTS[k])} for k in range(12)]
    criteria = Evaluator(_problem(control_points=rows))(np.array([[A]]))
    hand = WEIGHTS * np.maximum(0.0, np.maximum(lo - STROKE, STROKE - hi))
    assert hand.max() > 1.0 and (hand == 0).sum() >= 2   # both inside and outside
    np.testing.assert_allclose(criteria.deviations[0], hand, atol=1e-9)
    assert criteria.q[0] == pytest.approx(hand.max(), abs=1e-9)


def test_rms_criterion() -> None:
    """Q = sqrt(Σ E_K·δ_K² / Σ E_K) with δ_K the unweighted deviation of S from S_K."""
    target = STROKE + np.sin(np.arange(12.0))
    rows = [{"K": k, "phi": float(PHI[k]), "S": float(target[k]), "E": float(WEIGHTS[k])}
            for k in range(12)]
    general = {**SLIDER["general"], "criterion": "rms"}
    criteria = Evaluator(_problem(control_points=rows, general=general))(np.array([[A]]))
    delta = STROKE - target
    hand = math.sqrt(np.sum(WEIGHTS * delta ** 2) / np.sum(WEIGHTS))
    assert criteria.q[0] == pytest.approx(hand, rel=1e-9)


def test_stroke_range_enters_p2() -> None:
    """s runs from ROD − A (φ = 180°) to ROD + A (φ = 0), both on the grid: a range whose
    upper end is 5 mm short gives P2 = 5/(s_max − s_min); a range 1 mm wider each side
    gives P2 = 0 and the margin −1/(s_max − s_min)."""
    rows = [{"K": k, "phi": float(PHI[k]), "S": float(STROKE[k])} for k in range(12)]
    short = (ROD - A - 3.0, ROD + A - 5.0)
    problem = _problem(control_points=rows,
                       allowable=[{"links": [3, 2], "strokes": {"P_i": list(short)}}])
    criteria = Evaluator(problem)(np.array([[A]]))
    assert criteria.p2[0] == pytest.approx(5.0 / (short[1] - short[0]), rel=1e-9)
    wide = (ROD - A - 1.0, ROD + A + 1.0)
    problem = _problem(control_points=rows,
                       allowable=[{"links": [3, 2], "strokes": {"P_i": list(wide)}}])
    criteria = Evaluator(problem)(np.array([[A]]))
    assert criteria.p2[0] == 0
    assert criteria.margins[0, -1] == pytest.approx(-1.0 / (wide[1] - wide[0]), rel=1e-9)


def test_class2_law_is_the_closed_form() -> None:
    """The law S(φ) written as the slider-crank's formula: the control values equal the
    closed form, and the mechanism it came from has Q = 0."""
    law = {"phi": [0, 330], "S": "30*cos(radians(phi)) + sqrt(150**2 - (30*sin(radians("
                                 "phi)))**2) - 180"}
    problem = _problem(law=law)
    np.testing.assert_allclose(problem.control.value, STROKE, atol=1e-12)
    np.testing.assert_allclose(np.degrees(problem.control.phi), PHI, atol=1e-12)
    assert Evaluator(problem)(np.array([[A]])).q[0] < 1e-9


def test_class4_law_gives_the_points() -> None:
    data = yaml.safe_load((Path(__file__).resolve().parents[2] / "input_tables" / "problems"
                           / "class4_fourbar_timed.yaml").read_text(encoding="utf-8"))
    del data["control_points"]
    data["general"]["control_points"] = 7
    data["law"] = {"phi": [0, 300], "x": "10 + 40*cos(radians(φ))",
                   "y": "60 + 25*sin(radians(phi)) - 2*phi/pi"}
    problem = problem_from_dict(data, "law.yaml", base="input_tables/problems")
    phi = np.linspace(0.0, 300.0, 7)
    hand = (10 + 40 * np.cos(np.radians(phi))
            + 1j * (60 + 25 * np.sin(np.radians(phi)) - 2 * phi / np.pi))
    np.testing.assert_allclose(problem.control.point, hand, atol=1e-12)
    np.testing.assert_allclose(problem.control.phi, np.radians(phi), atol=1e-15)


@pytest.mark.parametrize(("text", "reason"), [
    ("__import__('os').system('true')", "function"),
    ("phi.real", "node"),
    ("eval(phi)", "function"),
    ("(lambda: 1)()", "function"),
    ("x + phi", "name"),
    ("sin(phi, 2)", "function"),
    ("phi if 1 else 2", "node"),
    ("phi < 2", "node"),
    ("[phi][0]", "node"),
    ("'phi'", "node"),
    ("2 + 3", "no_angle"),
    ("phi +", "syntax"),
    ("phi // 2", "node"),
    ("1" * 400 + "+phi", "big_number"),
    ("phi" + "+phi" * 200, "too_long"),
])
def test_parser_refuses(text: str, reason: str) -> None:
    with pytest.raises(LawError) as info:
        parse_law(text)
    assert info.value.reason == reason


def test_parser_evaluates_like_numpy() -> None:
    phi = np.linspace(-170.0, 170.0, 9)
    law = parse_law("-abs(phi)**0.5 + exp(-phi/100) * log(2 + cos(radians(phi))) "
                    "+ tan(radians(phi)/4) - degrees(pi)/+3 + sqrt(2)")
    hand = (-np.abs(phi) ** 0.5 + np.exp(-phi / 100) * np.log(2 + np.cos(np.radians(phi)))
            + np.tan(np.radians(phi) / 4) - 180.0 / 3 + np.sqrt(2))
    np.testing.assert_allclose(law(phi), hand, rtol=1e-14)


def _exit_2(tmp_path: Path, data: dict[str, Any], capsys: pytest.CaptureFixture[str]) -> str:
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    assert main(["synthesize", str(path)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and str(path) in err
    return err


def test_bad_new_fields_exit_2_all_at_once(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    data = copy.deepcopy(SLIDER)
    data["general"]["criterion"] = "mean"
    data["law"] = {"phi": [0, 330], "S": "import os"}
    data["allowable"] = [{"links": [3, 2], "strokes": {"P_i": [180, 120], "C": [0, 1]}}]
    err = _exit_2(tmp_path, data, capsys)
    assert "general 'criterion': expected one of 'max', 'rms'; found 'mean'" in err
    assert ("law 'S': expected a formula of 'phi' (degrees) made of numbers, 'phi', 'pi', "
            "'+ - * / **', 'sin cos tan sqrt exp log abs radians degrees', e.g. "
            "'50 + 20*cos(radians(phi))'; found 'import os' (a text): not a formula") in err
    assert ("allowable[0] 'strokes' 'P_i': the lower end of the stroke must not exceed the "
            "upper one; expected s_min <= s_max, found [180, 120]") in err


def test_bad_stroke_pair_and_law_of_no_angle(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    data = copy.deepcopy(SLIDER)
    data["law"] = {"phi": [0, 330], "S": "2 * pi"}
    data["allowable"] = [{"links": [3, 2], "strokes": {"C": [0, 1]}}]
    err = _exit_2(tmp_path, data, capsys)
    assert "law 'S': " in err and "found '2 * pi' (a text): the formula does not depend on 'phi'" \
        in err
    assert ("allowable (L2(3,2)) 'strokes': unknown prismatic pair 'C'; the prismatic pairs "
            "of L2(3,2) are P_i") in err


def test_bad_guidance_fields_exit_2(tmp_path: Path,
                                    capsys: pytest.CaptureFixture[str]) -> None:
    path = (Path(__file__).resolve().parents[2] / "input_tables" / "problems"
            / "class5_fourbar_guidance.yaml")
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    data["control_points"] = data["control_points"][:1]
    data["general"]["control_points"] = 1
    data["output"]["length"] = -5
    data["output"]["angle"] = [10, 20, 0]
    err = _exit_2(tmp_path, data, capsys)
    assert ("control_points: a guidance task needs at least 2 control poses ('x', 'y', "
            "'theta'); found 1") in err
    assert "output 'length': " in err and "found -5" in err
    assert "output 'angle': the lower bound must not exceed the upper bound" in err
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    data["control_points"][0]["phi"] = 0
    err = _exit_2(tmp_path, data, capsys)
    assert ("control_points: either every pose gives its crank angle 'phi' (a timed task) or "
            "none does; 1 of 6 rows do") in err


def test_segment_fields_belong_to_class_5(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    data = copy.deepcopy(SLIDER)
    data["output"] = {"link": 3, "length": 50}
    data["control_points"] = [{"K": k, "phi": float(PHI[k]), "S": float(STROKE[k])}
                              for k in range(12)]
    err = _exit_2(tmp_path, data, capsys)
    assert ("output 'length': only task class 5 (rigid-body guidance) has a segment; remove "
            "'length' from this task of class 2") in err


def test_law_undefined_and_law_with_table_exit_2(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    data = copy.deepcopy(SLIDER)
    data["law"] = {"phi": [0, 330], "S": "sqrt(phi - 100)"}
    data["control_points"] = [{"K": 0, "phi": 0, "S": 0}]
    err = _exit_2(tmp_path, data, capsys)
    # φ_K = 0, 30, …, 330: the root is not real at 0, 30, 60 and 90
    assert ("law 'S': the formula has no finite value at 'phi' = 0 degrees (4 of the control "
            "angles)") in err
    assert ("law: give the required motion either as a law (formulas of 'phi') or as the "
            "control-point table, not both") in err
