"""``assur check``: the course example, reports, wrong and broken tables."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
COURSE = ROOT / "input_tables" / "course_11_link.yaml"
COURSE_TABLE = ROOT / "input_tables" / "course_11_link_table.yaml"
BROKEN = sorted((ROOT / "tests" / "assur" / "broken").glob("*.yaml"))
FORMULA = "I(0,1) → II₁(2,3) → II₄(4,5) → II₃(6,7) → II₂(8,9) → II₅(10,11)"


@pytest.mark.parametrize("path", [COURSE, COURSE_TABLE], ids=["chain", "table"])
def test_course_example_json(path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert (data["W"], data["n"], data["p5"], data["p4"]) == (1, 11, 16, 0)
    assert [g["kind"] for g in data["groups"]] == [1, 4, 3, 2, 5]
    assert [g["links"] for g in data["groups"]] == [[2, 3], [4, 5], [6, 7], [8, 9], [10, 11]]
    assert [g["level"] for g in data["groups"]] == [1, 2, 2, 3, 4]
    assert data["formula"] == FORMULA
    assert data["mechanism_class"] == 2 and data["applicable"] is True
    assert data["issues"] == []


def test_table_file_is_checked_against_its_own_analysis(capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    assert main(["check", str(COURSE_TABLE), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["identification_check"] == []


def test_russian_report(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(COURSE), "--lang", "ru"]) == 0
    out = capsys.readouterr().out
    assert f"Формула строения: {FORMULA}" in out
    assert "группа Ассура 2 класса 2 порядка 1 вида (ВВВ)" in out
    assert "Класс механизма: II" in out


def test_wrong_identification_table_is_reported_field_by_field(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data = yaml.safe_load(COURSE.read_text(encoding="utf-8"))
    table = yaml.safe_load(COURSE_TABLE.read_text(encoding="utf-8"))
    rows = table["structure_identification"]
    rows[3]["i_minus_1"] = 3          # L3 row: the kulisa 6 hangs on link 2, not 3
    rows[4]["L"] = 3                  # L4 row written as an L3 group
    data["structure_identification"] = rows
    path = tmp_path / "student.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "differs from the analysis (2 mismatches)" in out
    assert "structure_identification[3] (L3, i = 6, j = 7) 'i_minus_1': expected 2, found 3" in out
    assert "structure_identification[4] (L3, i = 4, j = 5) 'L': expected 4, found 3" in out


@pytest.mark.parametrize("path", BROKEN, ids=[p.stem for p in BROKEN])
def test_broken_tables_exit_2_without_traceback(path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and "Traceback" not in err


def test_missing_file_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(tmp_path / "nothing.yaml")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_console_entry_point() -> None:
    result = subprocess.run([sys.executable, "-m", "synthesis", "check", str(COURSE), "--json"],
                            capture_output=True, text=True, encoding="utf-8", check=False)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["formula"] == FORMULA


@pytest.mark.parametrize("table", ["four_bar.yaml", "course_11_link.yaml"])
def test_a_sketch_typo_is_refused_by_analyze_and_reported_beside_the_structure_by_check(
        table: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A misspelt key of one joint of the sketch: ``analyze`` needs the sketch and exits 2;
    ``check`` does not need it for the structure: it prints the structure and reports the
    sketch's problem beside it, in its verdict."""
    path = tmp_path / table
    text = (ROOT / "input_tables" / table).read_text(encoding="utf-8")
    head, _, sketch = text.partition("geometry:")
    path.write_text(head + "geometry:" + sketch.replace("point:", "pont:", 1), encoding="utf-8")
    joint = yaml.safe_load(path.read_text(encoding="utf-8"))["geometry"]
    typo = next(key for key, row in joint.items() if isinstance(row, dict) and "pont" in row)
    assert main(["analyze", str(path)]) == 2
    lines = capsys.readouterr().err.splitlines()
    problem = f"  - geometry {typo!r}: unknown key 'pont'; did you mean 'point'?"
    assert lines == [f"1 problem in {path}:", problem]  # the misspelt point is not also missing
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "Structure formula: I(0,1) → II₁(2,3)" in out and problem in out.splitlines()
    assert main(["check", str(path), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found["verdict"] == "wrong" and found["findings"][0]["where"] == f"geometry {typo!r}"
