"""Impact case: command line, input table, report and picture."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from synthesis.cases.impact.data import PAPER
from synthesis.cases.impact.plot import plot_case
from synthesis.cases.impact.study import run_study
from synthesis.cases.impact.table import read_impact_table
from synthesis.cli import main


def test_shipped_table_is_the_papers_data(tables_dir: Path) -> None:
    data = read_impact_table(tables_dir / "case_impact.yaml")
    assert data.same_as(PAPER)
    # values typed from the paper's section 3, in its units
    assert (data.r1, data.r2, data.r3, data.r4) == pytest.approx((0.1, 0.05, 0.08, 0.08))
    assert (data.m2, data.m3, data.m4) == pytest.approx((0.012, 0.018, 0.018))
    assert data.inertia_o2 == pytest.approx(10e-6) and data.inertia4 == pytest.approx(10e-6)
    assert data.clearance == pytest.approx(0.5e-3)
    assert data.omega2 == pytest.approx(1800 * 2 * math.pi / 60, rel=1e-3)
    assert math.degrees(data.theta2) == pytest.approx(150.0)


def test_default_run_prints_table_1_and_worst_errors(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["case", "impact"]) == 0
    out = capsys.readouterr().out
    assert "Worst relative error per column" in out
    worst = re.findall(r"^  (θ[23]'\+|F|r_A|r_O2) (\[2\]|P)\s+([0-9.]+) %$", out, re.MULTILINE)
    assert len(worst) == 10
    assert all(float(value) < 0.1 for *_, value in worst)
    assert "1e-4 N·s" in out and "r_2θ" in out and "I_O4" in out and "3 equations" in out


def test_json_lists_every_entry_within_0_1_percent(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["case", "impact", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert len(report["table_1"]) == 10
    for entry in report["table_1"].values():
        paper, computed = np.array(entry["paper"]), np.array(entry["computed"])
        assert np.all(np.abs(computed / paper - 1) < 1e-3)
    assert max(report["worst_relative_error"].values()) < 1e-3


def test_russian_report(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["case", "impact", "--lang", "ru"]) == 0
    out = capsys.readouterr().out
    assert "Наибольшая относительная погрешность" in out and "Неточности статьи" in out


def test_overrides_leave_the_table_comparison_out(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["case", "impact", "--theta2", "60", "--omega4", "-100", "100", "--k", "0.5",
            "--mu", "0.2", "--clearance", "0.2", "--json"]
    assert main(args) == 0
    report = json.loads(capsys.readouterr().out)
    assert "table_1" not in report
    assert report["data"]["theta2_deg"] == pytest.approx(60.0)
    assert report["data"]["clearance"] == pytest.approx(0.2e-3)
    # the pin is a clearance away from the bearing centre, on the other side when the rocker leads
    psi, theta4 = (np.radians(report["position"][key]) for key in ("psi_deg", "theta4_deg"))
    assert np.allclose(np.sin(psi - theta4), [1.0, -1.0], atol=1e-2)


def test_bad_input_reports_every_problem(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    table = tmp_path / "bad.yaml"
    table.write_text("lengths_mm: {r1: 100, r2: -50, r3: 80, r4: 80}\n"
                     "masses_kg: {m2: 0.012, m3: 0.018, m44: 0.018}\n"
                     "inertias_kg_mm2: {I_O2: 10, I3: 10, I4: 10}\n"
                     "clearance_mm: 0.5\ncrank: {theta2_deg: 150, omega2_rad_s: 188.5}\n"
                     "omega4_rad_s: [0, fast]\nk: 1.5\nmu: 0\nsigma: 1\n", encoding="utf-8")
    assert main(["case", "impact", "--table", str(table)]) == 2
    err = capsys.readouterr().err
    assert "bad.yaml" in err
    for text in ("'r2': must be positive", "unknown key 'm44'; did you mean 'm4'?",
                 "'omega4_rad_s'[1]: expected a number", "'k': must lie between 0"):
        assert text in err, text
    assert "'m4': this field is missing" not in err  # the misspelt m44 is reported once


def test_command_line_values_are_checked(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["case", "impact", "--mu", "-0.1", "--clearance", "500"]) == 2
    err = capsys.readouterr().err
    assert "'mu': must be zero or positive" in err and "'clearance_mm': must be smaller" in err


def test_plot_is_written(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "impact.png"
    assert main(["case", "impact", "--plot", str(target)]) == 0
    capsys.readouterr()
    assert target.read_bytes().startswith(b"\x89PNG")


def test_plot_has_the_mechanism_and_both_models() -> None:
    figure = plot_case(run_study())
    mechanism, jumps, impulses = figure.axes[:3]
    assert len(jumps.patches) == 2 * 3 * 3 and len(impulses.patches) == 2 * 3 * 3
    labels = [text.get_text() for text in mechanism.texts]
    assert {"F", "r_A", "r_O2"} <= set(labels)


def test_a_rocker_moving_with_the_pin_is_reported_not_solved(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cases.impact.position import impact_position

    rigid = float(impact_position(PAPER, omega4=0.0).omega4_rigid)
    target = tmp_path / "none.png"
    assert main(["case", "impact", "--omega4", repr(rigid), "--plot", str(target)]) == 0
    out = capsys.readouterr().out
    assert "no impact" in out and "nan" not in out
    assert target.exists()
