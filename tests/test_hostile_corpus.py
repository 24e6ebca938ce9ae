"""A corpus of hostile inputs to the newer features (issue 30), each ending as the README
promises: exit 0, 1 or 2 (never 3), the file and the field named in both languages, no
traceback, and no output file left behind by a refusal.

The expectations come from the stated ranges (``docs/forces.md`` §1.1, the options' ranges
in ``synthesis/cli/options.py``), computed here, not from the program's answers.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import yaml

from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
TABLES = ROOT / "input_tables"
GRAVITY = TABLES / "four_bar_gravity.yaml"
TORQUE_PROBLEM = TABLES / "problems" / "class1_fourbar_torque_limit.yaml"
CYRILLIC = re.compile("[а-яА-Я]")


def _run(capsys: pytest.CaptureFixture[str], *argv: object) -> tuple[int, str, str]:
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:  # the argument parser's own refusal
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    assert "Traceback" not in err and "internal error" not in err, err
    assert code != 3, err
    return code, out, err


def _table(tmp_path: Path, edit: Any, source: Path = GRAVITY, name: str = "t.yaml") -> Path:
    data = yaml.safe_load(source.read_text(encoding="utf-8"))
    edit(data)
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    return path


def _refused(capsys: pytest.CaptureFixture[str], tmp_path: Path, table: Path,
             field: str, *options: object) -> None:
    """Exit 2 naming the file and ``field`` in English and in Russian, the CSV not written."""
    csv = tmp_path / "out.csv"
    for lang in ("en", "ru"):
        code, _, err = _run(capsys, "analyze", table, "--forces", "--omega", 10,
                            "--points", 36, "--csv", csv, "--lang", lang, *options)
        assert code == 2, err
        assert str(table) in err and field in err, err
        assert (CYRILLIC.search(err) is not None) == (lang == "ru"), err
        assert not csv.exists()


# ------------------------------------------------------------- item 4: the force sections

#: The sketch of four_bar_gravity.yaml spans x 0…110, y 0…80 mm: its diagonal, and the reach
#: 100 diagonals beyond the box on every side (docs/forces.md §1.1).
DIAGONAL = math.hypot(110.0, 80.0)
REACH_X = (-100.0 * DIAGONAL, 110.0 + 100.0 * DIAGONAL)


def _set_mass(field: str, value: Any) -> Any:
    return lambda d: d["masses"][2].__setitem__(field, value)


ABSURD: dict[str, tuple[Callable[[dict[Any, Any]], Any], str]] = {
    "mass 1e300": (_set_mass("mass", 1e300), "masses.2 'mass'"),
    "mass above 1e6 kg": (_set_mass("mass", 2e6), "masses.2 'mass'"),
    "mass zero": (_set_mass("mass", 0), "masses.2 'mass'"),
    "inertia 1e300": (_set_mass("inertia", 1e300), "masses.2 'inertia'"),
    "inertia above 1e6": (_set_mass("inertia", 2e6), "masses.2 'inertia'"),
    "centre 1e300": (_set_mass("centre", [1e300, 0]), "masses.2 'centre'[0]"),
    "centre beyond the reach": (_set_mass("centre", [REACH_X[1] + 1.0, 40]),
                                "masses.2 'centre'"),
    "centre nan": (_set_mass("centre", [70, float("nan")]), "masses.2 'centre'[1]"),
    "torque 1e300": (lambda d: d["loads"][0].__setitem__("torque", 1e300),
                     "loads[0] 'torque'"),
    "torque inf": (lambda d: d["loads"][0].__setitem__("torque", float("inf")),
                   "loads[0] 'torque'"),
    "tabulated torque 1e300": (lambda d: d["loads"][0].__setitem__(
        "torque", {"phi": [0, 180, 360], "value": [1, 1e300, 1]}),
        "loads[0] 'torque' 'value'[1]"),
    "force 1e300": (lambda d: d["loads"].append(
        {"link": 2, "force": [0, -1e300], "point": [70, 65]}), "loads[1] 'force'[1]"),
    "load point beyond the reach": (lambda d: d["loads"].append(
        {"link": 2, "force": [0, -10], "point": [REACH_X[0] - 1.0, 0]}), "loads[1] 'point'"),
    "gravity 1e300": (lambda d: d.__setitem__("gravity", [0, -1e300]), "'gravity'[1]"),
    "gravity above 1000": (lambda d: d.__setitem__("gravity", [0, -1500]), "'gravity'"),
    "a fraction as link key": (lambda d: d["masses"].__setitem__(2.0, d["masses"].pop(2)),
                               "masses.2.0"),
    "a boolean as link key": (lambda d: d["masses"].__setitem__(True, d["masses"].pop(1)),
                              "masses.True"),
}


@pytest.mark.parametrize("case", sorted(ABSURD))
def test_an_absurd_force_value_is_refused_naming_its_field(
        capsys: pytest.CaptureFixture[str], tmp_path: Path, case: str) -> None:
    edit, field = ABSURD[case]
    _refused(capsys, tmp_path, _table(tmp_path, edit), field)


def test_the_bounds_themselves_are_accepted(capsys: pytest.CaptureFixture[str],
                                            tmp_path: Path) -> None:
    def edit(d: dict[str, Any]) -> None:
        d["masses"][2].update(mass=1e6, inertia=1e6, centre=[REACH_X[0] + 1.0, 40])
        d["gravity"] = [0, -1000]
    code, _, err = _run(capsys, "analyze", _table(tmp_path, edit), "--forces", "--omega", 10,
                        "--points", 36)
    assert code == 0, err


def test_a_key_written_twice_is_refused(capsys: pytest.CaptureFixture[str],
                                        tmp_path: Path) -> None:
    path = tmp_path / "twice.yaml"
    path.write_text(GRAVITY.read_text(encoding="utf-8") + "masses:\n  2: {mass: 1, centre: [0, 0]}\n",
                    encoding="utf-8")
    code, _, err = _run(capsys, "analyze", path, "--forces", "--omega", 10)
    assert code == 2 and str(path) in err and "masses" in err


# ------------------------------------------------------ item 4: a problem's force conditions

PROBLEM_CASES: dict[str, tuple[Callable[[dict[str, Any]], None], str]] = {
    "omega nan": (lambda f: f.__setitem__("omega", float("nan")), "forces 'omega'"),
    "omega 1e300": (lambda f: f.__setitem__("omega", 1e300), "forces 'omega'"),
    "omega zero": (lambda f: f.__setitem__("omega", 0), "forces 'omega'"),
    "mass 1e300": (lambda f: f.__setitem__("masses", {2: {"mass": 1e300, "centre": "middle"}}),
                   "forces.masses.2 'mass'"),
    "a boolean as link key": (lambda f: f.__setitem__(
        "masses", {True: {"mass": 1, "centre": "middle"}}), "forces.masses.True"),
    "torque 1e300": (lambda f: f["loads"][0].__setitem__("torque", 1e300),
                     "forces.loads[0] 'torque'"),
    # the longest link of the initial design is l_i = 110 mm: a point in a link's frame may
    # lie within x, y = −100·110√2 … 110 + 100·110√2 ≈ −15556 … 15666 mm
    "centre beyond the reach": (lambda f: f.__setitem__(
        "masses", {2: {"mass": 1, "centre": {"l": 16000, "beta": 0}}}), "forces.masses.2 'centre'"),
}


@pytest.mark.parametrize("case", sorted(PROBLEM_CASES))
def test_an_absurd_force_condition_is_refused_naming_the_problem_file(
        capsys: pytest.CaptureFixture[str], tmp_path: Path, case: str) -> None:
    edit, field = PROBLEM_CASES[case]
    path = _table(tmp_path, lambda d: edit(d["forces"]), TORQUE_PROBLEM, "p.yaml")
    out = tmp_path / "result.yaml"
    for lang in ("en", "ru"):
        code, _, err = _run(capsys, "synthesize", path, "--budget", 2, "--out", out,
                            "--lang", lang)
        assert code == 2 and str(path) in err and field in err, err
        assert not out.exists()


# ----------------------------------------------------------- items 4 and 5: the options

@pytest.mark.parametrize("options, named", [
    (("--forces", "--omega", "nan"), "--omega"),
    (("--forces", "--omega", "inf"), "--omega"),
    (("--forces", "--omega", "1e300"), "--omega"),
    (("--forces", "--omega", "0"), "--omega"),
    (("--forces", "--omega", "-10"), "--omega"),
    (("--forces", "--omega", "ten"), "--omega"),
    (("--points", "100000000000"), "--points"),
    (("--points", "100001"), "--points"),
    (("--animate", "{out}.gif", "--frames", "0"), "--frames"),
    (("--plot", "{out}.png", "--at", "inf"), "--at"),
    (("--plot", "{out}.png", "--at", "nan"), "--at"),
    (("--json", "--forces", "--omega", "nan"), "--omega"),
])
def test_an_option_out_of_its_range_is_refused_naming_it(
        capsys: pytest.CaptureFixture[str], tmp_path: Path, options: tuple[str, ...],
        named: str) -> None:
    out = tmp_path / "out"
    argv = [o.format(out=out) for o in options]
    for lang in ("en", "ru"):
        code, stdout, err = _run(capsys, "analyze", GRAVITY, *argv, "--lang", lang)
        assert code == 2 and named in err and stdout == "", err
        assert not list(tmp_path.iterdir())


def test_the_largest_point_count_and_one_frame_are_accepted(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    gif = tmp_path / "a.gif"
    code, _, err = _run(capsys, "analyze", GRAVITY, "--points", 36, "--animate", gif,
                        "--frames", 1)
    assert code == 0 and gif.exists(), err


@pytest.mark.parametrize("omega", [".nan", ".inf", "ten", "1.0e+300", "0"])
def test_report_refuses_general_omega_out_of_range(
        capsys: pytest.CaptureFixture[str], tmp_path: Path, omega: str) -> None:
    path = tmp_path / "r.yaml"
    path.write_text(GRAVITY.read_text(encoding="utf-8").replace(
        "omega: 10 ", f"omega: {omega} "), encoding="utf-8")
    out = tmp_path / "r.html"
    code, _, err = _run(capsys, "report", path, "--out", out, "--points", 36)
    assert code == 2 and "general 'omega'" in err and str(path) in err, err
    assert not out.exists()


def _strict(text: str) -> Any:
    def refuse(name: str) -> None:
        raise AssertionError(f"bare {name} in the JSON output")
    return json.loads(text, parse_constant=refuse)


def test_json_is_strict_where_positions_fail(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = _run(capsys, "analyze", TABLES / "course_11_link_fails.yaml", "--json",
                          "--points", 36)
    assert code == 0, err
    data = _strict(out)
    assert data["all_exist"] is False
    # a failed position is null, not NaN
    assert any(None in joint["x"] for joint in data["joints"].values())


# -------------------------------------------------------------- item 5: problem tables

def test_a_bad_fixed_value_in_parameters_is_told_at_the_problem_row(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    source = TABLES / "problems" / "class2_course_11_link.yaml"
    text = source.read_text(encoding="utf-8").replace("y_Hj: 160", "y_Hj: lots").replace(
        "mechanism: ../", f"mechanism: {TABLES}/")
    path = tmp_path / "p.yaml"
    path.write_text(text, encoding="utf-8")
    for lang in ("en", "ru"):
        code, _, err = _run(capsys, "synthesize", path, "--budget", 2, "--lang", lang)
        assert code == 2, err
        assert str(path) in err and "parameters[2] 'y_Hj'" in err, err
        assert "course_11_link_table.yaml" not in err, err


def test_a_reversed_stroke_is_refused_naming_its_values(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = _table(tmp_path, lambda d: d["geometry"]["input"].__setitem__("stroke", [115, 85]),
                  TABLES / "actuator_triad.yaml")
    code, _, err = _run(capsys, "analyze", path)
    assert code == 2 and "'stroke'" in err and "[115, 85]" in err, err


def test_the_tracker_refuses_an_absurd_ratio_naming_the_field(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "tracker.yaml"
    path.write_text(re.sub(r"k5: \[2\.0\]", "k5: [2.0e+6]",
                           (TABLES / "case_tracker.yaml").read_text(encoding="utf-8")),
                    encoding="utf-8")
    code, _, err = _run(capsys, "case", "tracker", "--table", path, "--budget", 4)
    assert code == 2 and "'k5'" in err and "2e+06" in err and str(path) in err, err
    code, _, err = _run(capsys, "case", "tracker", "--k5", "2e6", "--budget", 4)
    assert code == 2 and "--k5" in err, err


def test_a_crank_slot_drawn_through_the_pivot_is_the_same_mechanism(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    """The slot of crank 1 (60° from the x-axis, through its pivot A) drawn by a point at A
    and by a point 20 mm along it: one line, one mechanism, the same motion."""
    table = {
        "mechanism": {"pairs": [
            {"id": "A", "type": "R", "links": [0, 1]},
            {"id": "B", "type": "P", "links": [1, 2], "guide": 1},
            {"id": "C", "type": "R", "links": [2, 3]},
            {"id": "D", "type": "R", "links": [3, 0]}], "inputs": [1]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": [0, 0], "direction": 60},
                     "C": {"point": [20, 34.641016]}, "D": {"point": [60, -10]}}}
    along = json.loads(json.dumps(table))
    along["geometry"]["B"]["point"] = [10.0, 17.320508]
    runs = []
    for name, data in (("at_pivot.yaml", table), ("along.yaml", along)):
        path = tmp_path / name
        path.write_text(yaml.safe_dump(data), encoding="utf-8")
        code, out, err = _run(capsys, "analyze", path, "--json", "--points", 36)
        assert code == 0, err
        runs.append(_strict(out)["joints"]["C"])
    for axis in ("x", "y"):
        for a, b in zip(runs[0][axis], runs[1][axis]):
            assert (a is None) == (b is None)
            if a is not None:
                assert a == pytest.approx(b, abs=1e-6)
    # the slider C stays on the slot line through A at 60° + the crank's turn
    assert runs[0]["x"][0] == pytest.approx(20.0, abs=1e-5)
