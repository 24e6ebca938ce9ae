"""``assur analyze TABLE --forces --omega W``: the JSON, CSV and text outputs and the refusals."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from force_tables import TABLES
from test_forces_vectors import VECTOR_A

from synthesis.cli.main import main

PRESS = str(TABLES / "slider_crank_press.yaml")
#: ``--points 12`` lists 0°, 30°, …: the positions of the test vectors 30°, 120°, 210°, 300°.
AT = [1, 4, 7, 10]


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(["analyze", *argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _vector(name: str) -> np.ndarray:
    return np.array(dict(VECTOR_A)[name])


def test_json_holds_the_test_vector_and_balances_the_slider(
        capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run([PRESS, "--forces", "--omega", "10", "--points", "12", "--json"], capsys)
    assert code == 0
    record = json.loads(out)
    forces = record["forces"]
    driving = np.array(forces["driving_torque"])[AT]
    np.testing.assert_allclose(driving, _vector("driving torque, N·m"), rtol=0, atol=1e-7)
    slide = forces["reactions"]["3-0"]
    assert slide["links"] == [3, 0]
    np.testing.assert_allclose(np.array(slide["normal"])[AT], _vector("3-0 normal, N"),
                               rtol=0, atol=1e-6)
    # The slider's equilibrium from the JSON alone (docs/forces.md §6.2): the rod's force on
    # it (pair 2-3 listed [2, 3]), the frame's force on it (−R of 3-0, listed [3, 0]), the
    # 600 N resistance, its weight and its inertia force −m·a (a of the hinge 2-3, mm/s²).
    rod = forces["reactions"]["2-3"]
    acc = record["joints"]["2-3"]["acceleration"]
    for axis, load in (("x", -600.0), ("y", -1.5 * 9.81)):
        total = (np.array(rod[axis]) - np.array(slide[axis]) + load
                 - 1.5 * np.array(acc[axis]) * 1e-3)
        assert np.max(np.abs(total)) < 1e-9 * 600
    assert max(abs(v) for v in forces["power_balance"]) < 1e-10 * 30
    assert forces["reason"] == [None] * 12


def test_csv_columns_follow_the_json(capsys: pytest.CaptureFixture[str], tmp_path) -> None:
    path = tmp_path / "press.csv"
    code, _, _ = _run([PRESS, "--forces", "--omega", "10", "--points", "12", "--csv",
                       str(path)], capsys)
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(path.read_text())))
    column = np.array([float(row["driving_torque"]) for row in rows])[AT]
    np.testing.assert_allclose(column, _vector("driving torque, N·m"), atol=1e-7)
    normal = np.array([float(row["R_3-0_normal"]) for row in rows])[AT]
    np.testing.assert_allclose(normal, _vector("3-0 normal, N"), atol=1e-6)


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_text_report_names_the_extremes_and_the_checks(
        lang: str, capsys: pytest.CaptureFixture[str], tmp_path) -> None:
    picture = tmp_path / "press.png"
    plot = ["--plot", str(picture)] if lang == "en" else []
    code, out, _ = _run([PRESS, "--forces", "--omega", "10", "--points", "72", "--lang", lang,
                         *plot], capsys)
    assert code == 0
    section = out[out.index("Силовой" if lang == "ru" else "Force analysis"):]
    # φ = 30° gives −30.306 N·m (test vector); the minimum over 72 positions is near it
    low = float(section.split("мин. " if lang == "ru" else "min ")[1].split(" ")[0])
    assert -31.5 < low <= -30.306
    assert ("рычагом Жуковского" if lang == "ru" else "Zhukovsky's lever") in section
    assert "3-0 [3, 0]" in section
    assert not plot or picture.read_bytes()[1:4] == b"PNG"


def test_forces_without_sections_or_speed_are_refused_with_both_reasons(
        capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = _run([str(TABLES / "four_bar.yaml"), "--forces"], capsys)
    assert code == 2
    assert "'masses:' or 'loads:'" in err and "--omega W" in err
