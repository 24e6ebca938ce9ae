"""The ``general:`` section of a mechanism table: read once, every key and value checked.

A misspelt key gets a did-you-mean, a value out of its range stops the command with exit 2
and a message naming the file, the row and the field, in English and in Russian; a valid
section changes what ``assur analyze`` judges (the allowable pressure angle written in the
table); and ``analyze --forces`` reads the file once.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
import yaml

import assur
from assur.io.general import read_general
from assur.io.reader import TableReader
from assur.kinematics.build import build_model
from assur.model import Allowable, General
from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = ROOT / "input_tables" / "four_bar.yaml"
GRAVITY = ROOT / "input_tables" / "four_bar_gravity.yaml"


def _with_general(tmp_path: Path, general: Any, source: Path = FOUR_BAR) -> Path:
    data = yaml.safe_load(source.read_text(encoding="utf-8"))
    data["general"] = general
    path = tmp_path / "table.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    return path


def _run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize("command", ["check", "analyze"])
def test_the_misspelt_key_and_the_angle_out_of_range_stop_the_command(
        command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _with_general(tmp_path, {"omgea": 10,
                                    "allowable": [{"links": [2, 3], "pressure_angle": 120}]})
    code, out, err = _run([command, str(path)], capsys)
    assert code == 2 and out == "" and "Traceback" not in err
    assert str(path) in err
    assert "general: unknown key 'omgea'; did you mean 'omega'?" in err
    assert ("general.allowable[0] 'pressure_angle': must lie in (0, 90] degrees, or be "
            "'default'; found 120") in err
    code, _, err = _run([command, str(path), "--lang", "ru"], capsys)
    assert code == 2 and str(path) in err
    assert "general: неизвестный ключ 'omgea'; возможно, имелось в виду 'omega'?" in err
    assert ("general.allowable[0] 'pressure_angle': значение должно лежать в (0, 90] "
            "градусов или быть 'default'; найдено: 120") in err


@pytest.mark.parametrize(("general", "where", "rule"), [
    ({"omega": 0}, "general 'omega'", "must be positive"),
    ({"omega": -3.5}, "general 'omega'", "must be positive"),
    ({"omega": float("inf")}, "general 'omega'", "a number"),
    ({"allowable": [{"links": [2, 3], "pressure_angle": 0}]},
     "general.allowable[0] 'pressure_angle'", "must lie in (0, 90]"),
    ({"allowable": [{"links": [2, 3], "pressure_angle": 90.5}]},
     "general.allowable[0] 'pressure_angle'", "must lie in (0, 90]"),
    ({"allowable": [{"links": [2, 3, 3], "pressure_angle": 60}]},
     "general.allowable[0] 'links'", "must list the links of one group, each once"),
    ({"allowable": [{"links": [], "pressure_angle": 60}]},
     "general.allowable[0] 'links'", "must list the links of one group"),
    ({"allowable": [{"links": [2, 3], "rotations": {"C": -10}}]},
     "general.allowable[0].rotations 'C'", "must be positive"),
    ({"allowable": [{"links": [2, 3], "workspace": {"x": [50, -50], "y": [0, 10]}}]},
     "general.allowable[0].workspace 'x'", "expected [min, max] with min < max"),
    ({"allowable": [{"links": [2, 3], "pressure_agnle": 60}]},
     "general.allowable[0]", "did you mean 'pressure_angle'?"),
    ([1, 2], "'general'", "expected a mapping"),
])
def test_every_value_is_checked_against_its_range(
        general: Any, where: str, rule: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _run(["analyze", str(_with_general(tmp_path, general))], capsys)
    assert code == 2 and "Traceback" not in err
    line = next((line for line in err.splitlines() if where in line), "")
    assert rule in line, err


def test_the_section_is_read_into_a_typed_object() -> None:
    reader = TableReader.from_data({"general": {"omega": 12, "allowable": [
        {"links": ["2", 3], "pressure_angle": 30, "rotations": {"B": 170}},
        {"links": [4, 5], "pressure_angle": "default",
         "workspace": {"x": [-1, 1], "y": [0, 2.5]}}]}}, "t.yaml")
    assert read_general(reader.root()) == General(12.0, (
        Allowable((2, 3), 30.0, {"B": 170.0}, None),
        Allowable((4, 5), None, {}, (-1.0, 1.0, 0.0, 2.5))))
    assert reader.issues == []
    assert read_general(TableReader.from_data({}, "t.yaml").root()) == General()


def test_the_allowable_angle_written_in_the_table_is_the_one_judged(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _with_general(tmp_path, {"allowable": [{"links": [2, 3], "pressure_angle": 30}]})
    code, out, _ = _run(["analyze", str(path), "--points", "12", "--json"], capsys)
    assert code == 0
    allowed = {p["group"]: p["allowed_deg"] for p in json.loads(out)["pressure_angles"]}
    assert allowed == {"L1(2,3)": 30.0}
    code, out, _ = _run(["analyze", str(FOUR_BAR), "--points", "12", "--json"], capsys)
    assert {p["allowed_deg"] for p in json.loads(out)["pressure_angles"]} == {45.0}


def test_analyze_with_forces_reads_the_file_once(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    reads: list[str] = []
    original = TableReader.from_path.__func__  # type: ignore[attr-defined]

    def counted(cls: type[TableReader], /, path: Any, **kwargs: Any) -> TableReader:
        reads.append(str(path))
        return original(cls, path, **kwargs)  # type: ignore[no-any-return]

    monkeypatch.setattr(TableReader, "from_path", classmethod(counted))
    code, out, _ = _run(["analyze", str(GRAVITY), "--points", "12", "--forces", "--omega",
                         "10", "--json"], capsys)
    assert code == 0 and "forces" in json.loads(out)
    assert reads == [str(GRAVITY)]


def test_a_limit_names_its_group_by_the_links_in_any_order(tmp_path: Path) -> None:
    """A dyad by [j, i], a triad by the four links of its label III(2,3,4,5)."""
    for source, links, label in ((FOUR_BAR, [3, 2], "L1(2,3)"),
                                 (ROOT / "input_tables" / "six_bar_triad.yaml", [5, 2, 3, 4],
                                  "III(2,3,4,5)")):
        path = _with_general(tmp_path, {"allowable": [{"links": links,
                                                        "pressure_angle": 30}]}, source)
        chain = assur.load(path)
        model = build_model(assur.analyse_structure(chain))
        assert chain.general.pressure_angles(model) == {"L0(1)": 45.0, label: 30.0}
