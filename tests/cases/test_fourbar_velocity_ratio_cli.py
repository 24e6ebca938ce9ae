"""Command line of the velocity-ratio four-bar: input table, exit codes, languages, JSON, plot."""

from __future__ import annotations

import argparse
import json
import math

import pytest

from assur.errors import TableError
from synthesis.cases.fourbar_velocity_ratio import cli
from synthesis.cases.fourbar_velocity_ratio.conditions import Design, condition_residuals


def run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser()
    cli.add_args(parser)
    return cli.run(parser.parse_args(argv))


def test_shipped_table_runs_both_solvers_and_reports_json(tables_dir, capsys):
    table = tables_dir / "case_fourbar_velocity_ratio.yaml"
    assert run(["--table", str(table), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["passed"] and out["request"]["form"] == "paper"
    assert out["paper"]["matches_modern_design"] is not None
    for item in out["modern"]["designs"]:
        design = Design(e=item["e"], c=item["c"], r=item["r"],
                        theta2=math.radians(item["theta2_deg"]), n_star=item["n_star"],
                        delta=item["delta"], psi1=math.radians(item["psi1_deg"]),
                        psi2=math.radians(item["psi2_deg"]))
        assert max(abs(v) for v in condition_residuals(design).values()) < 1e-11
        assert item["check"]["passed"]


def test_russian_report_and_plot(tmp_path, capsys):
    picture = tmp_path / "ratio.png"
    code = run(["--e", "0.3", "--n-star", "0.5", "--psi1", "20", "--psi2", "22", "--lang", "ru",
                "--plot", str(picture)])
    text = capsys.readouterr().out
    assert code == 0
    assert "ПОДТВЕРЖДЕНО" in text and "ищутся c, r, θ2 и δ" in text
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_forward_stroke_ratio_of_one_or_more_is_answered_without_a_design(capsys):
    assert run(["--e", "0.3", "--n-star", "1.2", "--delta", "0.05", "--psi1", "20"]) == 1
    assert "forward stroke" in capsys.readouterr().out


def test_bad_table_lists_every_problem(tmp_path):
    table = tmp_path / "bad.yaml"
    table.write_text("fourbar_velocity_ratio:\n  e: abc\n  n_starr: 0.5\n  delta: 2\n"
                     "  psi1_deg: 20\n  method: fast\n", encoding="utf-8")
    with pytest.raises(TableError) as info:
        run(["--table", str(table)])
    text = str(info.value)
    assert str(table) in text
    for field in ("'e'", "did you mean 'n_star'", "'n_star'", "'delta'", "'method'"):
        assert field in text


@pytest.mark.parametrize("n_star", ["5e-324", "5e-301", "-2e-4", "1e5"])
def test_a_peak_ratio_out_of_scale_is_refused(tmp_path, n_star):
    # a ratio of 5e-324 once left the grid without a single finite peak (a traceback)
    table = tmp_path / "tiny.yaml"
    table.write_text(f"fourbar_velocity_ratio:\n  e: 0.3\n  n_star: {n_star}\n  delta: 0.05\n"
                     "  psi1_deg: 20\n", encoding="utf-8")
    with pytest.raises(TableError) as info:
        run(["--table", str(table)])
    assert "'n_star'" in str(info.value) and "|n*|" in str(info.value)


def test_over_determined_request_is_refused():
    with pytest.raises(TableError, match="over-determines"):
        run(["--e", "0.3", "--n-star", "0.5", "--delta", "0.05", "--psi1", "20", "--psi2", "20"])


def test_registered_as_a_built_in_case(capsys):
    from synthesis.cli import main

    assert main(["case", "fourbar-velocity-ratio", "--e", "0.3", "--n-star", "1.0",
                 "--delta", "0.05", "--psi1", "20"]) == 1
    assert "no such mechanism" in capsys.readouterr().out
    assert main(["case", "fourbar-velocity-ratio", "--e", "0.3", "--n-star", "0.5",
                 "--delta", "-1", "--psi1", "20"]) == 2
    assert "--delta:" in capsys.readouterr().err


def test_without_options_the_published_example_is_run(tables_dir, capsys):
    # the shipped table holds the published example; run without a table, the case must
    # request the same values and find the same designs
    assert run(["--json"]) == 0
    default = json.loads(capsys.readouterr().out)
    assert run(["--table", str(tables_dir / "case_fourbar_velocity_ratio.yaml"),
                "--method", "modern", "--json"]) == 0
    shipped = json.loads(capsys.readouterr().out)
    assert default["request"] == shipped["request"]
    assert default["modern"]["designs"] == shipped["modern"]["designs"]


@pytest.mark.parametrize(("argv", "flags"), [
    (["--n-star", "5000", "--delta", "2"], ["--n-star:", "--delta:"]),
    (["--e", "0.3", "--delta", "0.05", "--psi2", "20"], ["--e, --delta and --psi2"]),
])
def test_problems_of_typed_values_name_the_flags(argv, flags):
    with pytest.raises(TableError) as info:
        run(argv)
    text = str(info.value)
    assert all(flag in text for flag in flags)
    assert "n_star" not in text and "psi2_deg" not in text and "fourbar_velocity_ratio" not in text


def test_no_solution_answer_in_russian(capsys):
    assert run(["--e", "0.3", "--n-star", "1.2", "--delta", "0.05", "--psi1", "20",
                "--lang", "ru"]) == 1
    text = capsys.readouterr().out
    assert "такого механизма нет" in text and "обратном ходе" in text
    assert run(["--e", "0.3", "--n-star", "0.5", "--delta", "0.05", "--psi1", "35",
                "--lang", "ru"]) == 1
    assert "самый широкий" in capsys.readouterr().out
