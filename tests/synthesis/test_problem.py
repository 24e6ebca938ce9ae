"""Reading problem tables: valid input, and bad input reported all at once by location."""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from assur import TableError
from synthesis import load_problem, problem_from_dict

GOOD: dict[str, Any] = {
    "general": {"control_points": 3, "direction": 1, "groups": 2, "task_class": 2,
                "grid": 90},
    "structure_identification": [
        {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
        {"L": 2, "i": 3, "j": 2, "i_minus_1": 0, "j_minus_1": 1, "variant": 1}],
    "output": {"link": 3},
    "parameters": [
        {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": [30, 20, 40], "phi_1_0": 0},
        {"links": [3, 2], "x_Hj": "A", "y_Hj": "A", "l_j": [150, 120, 180], "x_Ak": 0,
         "y_Ak": 0, "beta_g": 0, "e": 5, "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0}],
    "control_points": [{"K": 0, "phi": 0, "S": 0}, {"K": 1, "phi": 90, "S": -33.0},
                       {"K": 2, "phi": 180, "S": -60.0, "E": 2}],
}


def _messages(data: dict[str, Any]) -> list[str]:
    with pytest.raises(TableError) as caught:
        problem_from_dict(data, "bad.yaml")
    assert str(caught.value).startswith(f"{len(caught.value.issues)} problem")
    return [str(issue) for issue in caught.value.issues]


def test_good_problem_reads_the_design_vector() -> None:
    problem = problem_from_dict(copy.deepcopy(GOOD), "good.yaml")
    assert problem.names == ("L0(1).l_1", "L2(3,2).l_j")
    np.testing.assert_array_equal(problem.lower, [20, 120])
    np.testing.assert_array_equal(problem.upper, [40, 180])
    np.testing.assert_array_equal(problem.initial, [30, 150])
    np.testing.assert_allclose(problem.control.phi, [0, math.pi / 2, math.pi])
    np.testing.assert_array_equal(problem.control.weight, [1, 1, 2])
    table = problem.mechanism_table([25.5, 140.0])
    rows = table["structure_identification"]
    assert rows[0]["params"]["l_1"] == 25.5 and rows[1]["params"]["l_j"] == 140
    assert rows[1]["params"]["e"] == 5 and rows[1]["params"]["x_Hj"] == "A"


def test_every_problem_is_reported_at_once() -> None:
    bad = copy.deepcopy(GOOD)
    bad["general"]["task_class"] = 7
    bad["general"]["groups"] = 1  # (3 would be read with [4, 5] below as a row left out)
    bad["general"]["gird"] = 90
    bad["control_points"][1]["K"] = 5
    bad["parameters"][1]["l_j"] = [150, 180, 120]
    bad["parameters"].append({"links": [4, 5], "l_i": 3})
    messages = _messages(bad)
    text = "\n".join(messages)
    assert "general: unknown key 'gird'; did you mean 'grid'?" in text
    assert "general 'task_class': expected one of 1, 2, 3, 4, 5; found 7" in text
    assert "general 'groups': the structure identification has 2 groups" in text
    assert "control_points[1] 'K': control points must be numbered 0, 1, 2" in text
    assert "parameters[1] 'l_j': the lower bound must not exceed the upper bound" in text
    assert "parameters[2] 'links': no group of the mechanism has links [4, 5]" \
        in text
    assert len(messages) >= 6


def test_class_specific_columns_are_checked() -> None:
    bad = copy.deepcopy(GOOD)
    bad["general"]["task_class"] = 3
    bad["control_points"] = [{"K": 0, "x": 1.0}, {"K": 1, "x": 1, "y": "north"},
                             {"K": 2, "x": 0, "y": 0, "E": -1}]
    text = "\n".join(_messages(bad))
    assert "control_points[0] 'y': this field is missing; expected a number" in text
    assert "control_points[1] 'y': expected a number; found 'north' (a text)" in text
    assert "control_points[2] 'E': must be positive; found -1" in text
    assert "output 'point': a path task (class 3 or 4) needs the tracing point" in text


def test_zone_limits_and_mixed_zone_rows() -> None:
    bad = copy.deepcopy(GOOD)
    bad["general"]["task_class"] = 1
    bad["control_points"] = [{"K": 0, "phi": 0, "psi_lo": 1, "psi_hi": 0},
                             {"K": 1, "phi": 90, "psi": 3}, {"K": 2, "phi": 180, "psi": 4}]
    text = "\n".join(_messages(bad))
    assert "control_points[0] 'psi_hi': the upper limit must not be below the lower one" in text
    assert "either every row is a zone (psi_lo, psi_hi) or none is; 1 of 3 rows are" in text


def test_columns_are_checked_by_the_kinematic_model() -> None:
    bad = copy.deepcopy(GOOD)
    del bad["parameters"][1]["e"]
    bad["parameters"][1]["ee"] = 3
    text = "\n".join(_messages(bad))
    assert "unknown column 'ee'; did you mean 'e'?" in text
    assert "'e': this column is missing" not in text  # the misspelt 'ee' is reported once


def test_nothing_varied_and_missing_mechanism() -> None:
    bad = copy.deepcopy(GOOD)
    bad["parameters"][0]["l_1"] = 30
    bad["parameters"][1]["l_j"] = [150, 150, 150]
    assert any("no parameter is varied" in m for m in _messages(bad))
    bad = copy.deepcopy(GOOD)
    del bad["structure_identification"]
    assert any("mechanism: this field is missing" in m for m in _messages(bad))


def _with_mechanism_file(tmp_path: Path, name: str) -> Path:
    """A copy of GOOD in tmp_path whose identification table is the file ``name``."""
    data = copy.deepcopy(GOOD)
    del data["structure_identification"]
    data["mechanism"] = name
    path = tmp_path / "problem.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


def test_missing_mechanism_file_names_the_file(tmp_path: Path) -> None:
    path = _with_mechanism_file(tmp_path, "nowhere.yaml")
    with pytest.raises(TableError) as caught:
        load_problem(path)
    assert "nowhere.yaml: the file does not exist" in str(caught.value)
    assert str(path) in str(caught.value)


def test_allowable_rows_are_checked() -> None:
    bad = copy.deepcopy(GOOD)
    bad["allowable"] = [{"links": [3, 2], "pressure_angle": 120, "rotations": {"Q": 10},
                         "workspace": {"x": [5, 1], "y": [0, 1]}}]
    text = "\n".join(_messages(bad))
    assert "allowable[0] 'pressure_angle': must lie in (0, 90] degrees" in text
    assert "allowable[0].workspace 'x': expected [min, max] with min < max (mm); found [5, 1]" \
        in text
    assert "unknown revolute joint 'Q'" in text


def test_reading_leaves_the_data_alone_and_hands_assur_plain_numbers(
        monkeypatch: pytest.MonkeyPatch) -> None:
    import assur

    def no_analysis(*args: object, **kwargs: object) -> None:
        raise AssertionError("a table was analysed while it was read")

    monkeypatch.setattr(assur, "analyse", no_analysis)
    data = copy.deepcopy(GOOD)
    data["allowable"] = [{"links": [3, 2], "pressure_angle": 50}]
    problem = problem_from_dict(data, "good.yaml")
    assert data == {**GOOD, "allowable": [{"links": [3, 2], "pressure_angle": 50}]}
    rows = problem.mechanism["structure_identification"]
    cells = [v for row in rows for k, v in row["params"].items() if k != "tracing"]
    assert not any(isinstance(v, list) for v in cells)
    # the initial values, as the table wrote them, and the input direction s of 'general'
    assert rows[0]["params"] == {"x_O1": 0, "y_O1": 0, "l_1": 30, "phi_1_0": 0, "s": 1}
    assert rows[1]["params"]["l_j"] == 150
    assert problem.pressure_angles == {"L2(3,2)": math.radians(50)}


def test_a_pressure_angle_where_none_exists_is_reported_when_evaluated() -> None:
    from synthesis.evaluate import Evaluator

    data = copy.deepcopy(GOOD)
    data["allowable"] = [{"links": [1], "pressure_angle": 30}]
    problem = problem_from_dict(data, "bad.yaml")
    with pytest.raises(TableError) as caught:
        Evaluator(problem)
    assert caught.value.source == "bad.yaml"
    assert [str(i) for i in caught.value.issues] == [
        ("allowable (L0(1)) 'pressure_angle': the pressure angle is computed only for L1 and L2 "
         "groups with a two-hinge rod; L0(1) has none")]


def test_bounds_are_checked_where_they_are_written() -> None:
    bad = copy.deepcopy(GOOD)
    bad["parameters"][0]["l_1"] = [10, 20, 40]
    bad["parameters"][1]["l_j"] = [150, 120]
    bad["structure_identification"][1]["params"] = {"e": [5, 6, 4]}
    text = "\n".join(_messages(bad))
    assert ("parameters[0] 'l_1': expected [initial, lower, upper] with lower ≤ initial ≤ "
            "upper; found [10, 20, 40]") in text
    assert ("parameters[1] 'l_j': expected a number, 'A', [initial, lower, upper], or the "
            "course's [v, v, 0] (fixed) or [0, A, 0] (supplied by an earlier group); found "
            "[150, 120]") in text
    # a parameters row replaces the column of the identification row: 'e' comes from it
    assert "'e'" not in text


def test_bounds_in_the_identification_rows_are_varied_too() -> None:
    data = copy.deepcopy(GOOD)
    del data["parameters"][1]["e"]
    data["structure_identification"][1]["params"] = {"e": [5, 0, 10]}
    problem = problem_from_dict(data, "good.yaml")
    # columns in the order of table 2.3 (x_Hj, y_Hj, l_j, x_Ak, y_Ak, beta_g, e, …)
    assert problem.names == ("L0(1).l_1", "L2(3,2).l_j", "L2(3,2).e")
    np.testing.assert_array_equal(problem.lower, [20, 120, 0])


def test_a_mechanism_file_reports_its_own_problems(tmp_path: Path) -> None:
    rows = copy.deepcopy(GOOD["structure_identification"])
    rows[1]["i_minus_one"] = 0
    (tmp_path / "chain.yaml").write_text(yaml.safe_dump({"structure_identification": rows}),
                                         encoding="utf-8")
    with pytest.raises(TableError) as caught:
        load_problem(_with_mechanism_file(tmp_path, "chain.yaml"))
    assert caught.value.source == str(tmp_path / "chain.yaml")
    assert any(issue.location.startswith("structure_identification[1]")
               and "i_minus_one" in str(issue) for issue in caught.value.issues)


def test_a_stroke_task_needs_a_sliding_output_link() -> None:
    bad = copy.deepcopy(GOOD)
    bad["output"] = {"link": 2}  # the rod of the RRP group: two revolute pairs, no slider
    assert _messages(bad) == [
        ("output 'link': link 2 has no prismatic pair to slide in; task class 2 controls the "
         "displacement S of a slider")]


def test_accuracy_is_read_in_the_unit_of_the_output() -> None:
    """[Q] of a class-1 angle task is in degrees (as ψ), of the others in mm; the search
    gets radians for ψ."""
    folder = Path(__file__).resolve().parents[2] / "input_tables" / "problems"
    rocker = load_problem(folder / "class1_fourbar_rocker.yaml")
    assert rocker.accuracy == 1e-4 and rocker.output_unit == "deg"
    assert rocker.settings.q_required == pytest.approx(1e-4 * math.pi / 180, rel=1e-15)
    path = load_problem(folder / "class3_fourbar_path.yaml")
    assert path.output_unit == "mm" and path.settings.q_required == path.accuracy == 1e-4


@pytest.mark.parametrize("lang, words", [
    ("en", "expected [initial, lower, upper] with lower ≤ initial ≤ upper; found [50, 20, 40]"),
    ("ru", ("ожидалось [начальное, нижняя, верхняя] с нижняя ≤ начальное ≤ верхняя; "
           "найдено: [50, 20, 40]"))])
def test_an_initial_value_above_its_upper_bound_is_refused(
        lang: str, words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cli import main

    data = copy.deepcopy(GOOD)
    data["parameters"][0]["l_1"] = [50, 20, 40]   # initial 50 > upper 40
    path = tmp_path / "above.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    assert main(["synthesize", str(path), "--quiet", "--lang", lang]) == 2
    captured = capsys.readouterr()
    assert str(path) in captured.err and "Traceback" not in captured.err
    assert f"parameters[0] 'l_1': {words}" in captured.err
    assert captured.out == ""
