"""Tracker case: the command, its input table, reports and pictures."""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import pytest

from assur import TableError
from synthesis.cases.tracker import cli
from synthesis.cases.tracker.design import PATENT_TASK
from synthesis.cases.tracker.plot import save_plots
from synthesis.cases.tracker.study import run_study
from synthesis.cases.tracker.task import load_task, task_from_data


def _run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser()
    cli.add_args(parser)
    return cli.run(parser.parse_args(argv))


def test_shipped_table_is_the_patents_example(tables_dir):
    assert load_task(tables_dir / "case_tracker.yaml") == PATENT_TASK


def test_report_shows_tabel_1_with_differences_and_the_inconsistencies(capsys):
    assert _run([]) == 0
    out = capsys.readouterr().out
    assert "31.8 / 31.74 (-0.06)" in out                     # b_min for k2 = 2.2, Tabel 1
    assert "1215 / 1212.1" in out                            # l_d in mm
    assert "not derivable" in out
    for fact in ("4.4° in Tabel 1", "31.5° in Etapa VI", "l_s = 1000 mm", "k_s = k_d·k_i"):
        assert fact in out
    assert "The patent chose k2 = 2.2, k5 = 2: the same design" in out


def test_russian_report(capsys):
    assert _run(["--lang", "ru"]) == 0
    out = capsys.readouterr().out
    assert "Несоответствия в патенте" in out and "не выводится" in out


def test_json_output_with_overrides(capsys):
    assert _run(["--json", "--stroke", "180", "--k5", "1.8", "2.2", "--min-clearance",
                 "60"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["task"]["stroke_deg"] == pytest.approx(180.0)
    assert data["task"]["k5"] == [1.8, 2.2]
    chosen = data["chosen"]
    assert chosen["simulation"]["stroke_deg"] == pytest.approx(180.0, abs=1e-7)
    assert chosen["lengths_mm"]["l_g"] >= 60.0
    assert {row["status"] for row in data["reproduction"]} == {"match", "differs",
                                                              "not derivable"}


def test_plots_are_written(tmp_path):
    paths = save_plots(run_study(PATENT_TASK), tmp_path, "ru", dpi=40)
    assert paths[0].name == "tracker_charts.png"
    names = sorted(p.name for p in Path(tmp_path).iterdir())
    assert names == ["tracker_charts.png", "tracker_chosen.png", "tracker_refined.png",
                     "tracker_synthesis.png"]
    assert all((tmp_path / n).read_bytes()[:4] == b"\x89PNG" for n in names)


def test_bad_table_lists_every_problem_by_file_and_field(tmp_path):
    path = tmp_path / "task.yaml"
    path.write_text("design_task:\n  stroke_deg: 400\n  k2: [0.5, 2]\n  l1mm: 300\n",
                    encoding="utf-8")
    with pytest.raises(TableError) as err:
        _run(["--table", str(path), "--l1", "-5"])
    text = str(err.value)
    assert text.startswith(f"4 problems in {path}")
    assert "design_task 'stroke_deg': must lie strictly between 1 and 360; found 400" in text
    assert "design_task 'k2': every value must be greater than 1" in text
    assert "unknown key 'l1mm'; did you mean 'l1_mm'?" in text
    assert "option '--l1': must be positive; found -5.0" in text


def test_table_values_and_option_overrides_combine():
    task = task_from_data({"design_task": {"stroke_deg": 200, "k5": [2.5]}}, "t.yaml",
                          {"l1_mm": 250.0})
    assert math.degrees(task.stroke) == pytest.approx(200.0)
    assert task.k5 == (2.5,) and task.l1 == 250.0 and task.k2 == PATENT_TASK.k2


def test_command_line_exits_2_on_bad_input_without_traceback(tmp_path, capsys):
    from synthesis.cli import main

    path = tmp_path / "task.yaml"
    path.write_text("design_task:\n  k5: [0.5]\n", encoding="utf-8")
    assert main(["case", "tracker", "--table", str(path), "--budget", "0"]) == 2
    err = capsys.readouterr().err
    assert "design_task 'k5': every value must be greater than 1" in err
    assert "Traceback" not in err


@pytest.mark.parametrize("stroke", ["2.1e-298", "0.5"])
def test_a_stroke_too_small_to_build_is_the_users_error(tmp_path, capsys, stroke):
    # a stroke of 2.1e-298° once reached the program's own mechanism table, whose error named
    # synthesis/cases/tracker/mechanism.yaml instead of the user's file
    from synthesis.cli import main

    path = tmp_path / "task.yaml"
    path.write_text(f"design_task:\n  stroke_deg: {stroke}\n", encoding="utf-8")
    assert main(["case", "tracker", "--table", str(path), "--budget", "0"]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and "stroke_deg" in err and "mechanism.yaml" not in err
