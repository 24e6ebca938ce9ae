"""The command line's one error boundary: every ending is a message and an exit code.

0 finished, 1 no feasible design, 2 bad input or an output not written where asked, 3 an
internal error (one line asking for a report), 130 interrupted, 141 a closed pipe.  Output
paths are refused before a run starts; a result that cannot be written at the end is saved
elsewhere, never lost.
"""

from __future__ import annotations

import csv
import errno
import importlib.abc
import os
import signal
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest
import yaml

import synthesis.search
from assur.io import files
from synthesis import SearchSettings, SettingError
from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = str(ROOT / "input_tables" / "four_bar.yaml")
PROBLEM = str(ROOT / "input_tables" / "problems" / "class3_fourbar_path.yaml")


def test_version_is_the_installed_package_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"assur {version('assur')}"


def test_every_bad_search_option_at_once_by_the_rule_of_the_table(capsys, monkeypatch):
    monkeypatch.setattr("synthesis.problem_table.load_problem", _must_not_run)
    code = main(["synthesize", PROBLEM, "--seed", "-5", "--budget", "99", "--time-limit", "-1",
                 "--shrink", "-3"])
    assert code == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert [line.split(":")[0] for line in lines] == ["--budget", "--seed", "--shrink",
                                                        "--time-limit"]
    for line, (field, value) in zip(lines, [("budget_log2", 99), ("seed", -5),
                                            ("shrink_passes", -3), ("time_limit", -1.0)]):
        with pytest.raises(SettingError) as table_rule:  # what a problem table would be told
            SearchSettings(**{field: value})
        assert line.endswith(table_rule.value.text("en")), line
    assert "from 0 to 24" in lines[0]  # the limit is stated


def _must_not_run(*_args, **_kwargs):
    raise AssertionError("the run started although an output path was refused")


def _read_only_folder(tmp_path: Path) -> Path:
    """A folder no file can be created in (chmod for a user; /sys for root, who ignores it)."""
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        (folder / "probe").touch()
    except OSError:
        return folder
    (folder / "probe").unlink()
    if not os.access("/sys", os.F_OK):
        pytest.skip("no folder here refuses a file")
    return Path("/sys")


@pytest.mark.parametrize("case", ["folder", "under_file", "read_only", "plot_is_file"])
def test_output_paths_refused_before_the_search(case, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("synthesis.outcome.synthesize", _must_not_run)
    (tmp_path / "a_file.txt").write_text("x")
    option, path, words = {
        "folder": ("--out", tmp_path, "this is a folder"),
        "under_file": ("--out", tmp_path / "a_file.txt" / "result.yaml", "is a file"),
        "read_only": ("--out", _read_only_folder(tmp_path) / "result.yaml", "cannot write"),
        "plot_is_file": ("--plot", tmp_path / "a_file.txt", "this is a file"),
    }[case]
    assert main(["synthesize", PROBLEM, "--quiet", option, str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{option} {path}" in err and words in err and "Traceback" not in err


def test_missing_folders_of_an_output_are_made(tmp_path, capsys):
    target = tmp_path / "new" / "deeper" / "motion.csv"
    assert main(["analyze", FOUR_BAR, "--points", "12", "--csv", str(target)]) == 0
    assert len(target.read_text(encoding="utf-8").splitlines()) == 1 + 12
    assert capsys.readouterr().err.splitlines() == [f"written: {target}"]


def _full_disk(monkeypatch, folder: Path) -> None:
    """Every write into ``folder`` fails as on a full disk; other folders still work."""
    original = files.atomic_write_bytes

    def write(path, data):
        if Path(path).parent == folder:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        original(path, data)

    monkeypatch.setattr(files, "atomic_write_bytes", write)


def test_a_result_not_written_at_the_end_is_saved_elsewhere(tmp_path, capsys, monkeypatch):
    full, here = tmp_path / "full", tmp_path / "here"
    full.mkdir()
    here.mkdir()
    run = ["synthesize", PROBLEM, "--budget", "5", "--quiet", "--out"]
    assert main([*run, str(tmp_path / "reference.yaml")]) in (0, 1)
    capsys.readouterr()
    monkeypatch.chdir(here)
    _full_disk(monkeypatch, full)
    assert main([*run, str(full / "result.yaml")]) == 2  # never 1: that means "no design"
    err = capsys.readouterr().err
    spare = here / "result.saved.yaml"
    assert f"saved as {spare}" in err and "No space left on device" in err
    assert f"written: {spare}" in err
    assert spare.read_text("utf-8") == (tmp_path / "reference.yaml").read_text("utf-8")


def test_a_text_that_no_folder_takes_is_printed(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(files, "atomic_write_bytes", _no_space)
    assert main(["analyze", FOUR_BAR, "--points", "6", "--csv", str(tmp_path / "m.csv")]) == 2
    captured = capsys.readouterr()
    assert "printed above" in captured.err
    lines = captured.out.splitlines()
    rows = list(csv.reader(lines[next(k for k, x in enumerate(lines) if x.startswith("phi")):]))
    assert len(rows) == 1 + 6 and len({len(row) for row in rows}) == 1
    assert [float(row[0]) for row in rows[1:]] == pytest.approx([0, 60, 120, 180, 240, 300])


def _no_space(path, data):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def test_an_internal_error_is_one_line_naming_the_file(capsys, monkeypatch):
    def broken(*_args, **_kwargs):
        return 1 / 0

    monkeypatch.setattr("synthesis.app.assess.assess", broken)
    assert main(["check", FOUR_BAR]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and FOUR_BAR in err and "ZeroDivisionError" in err
    assert "report" in err and "Traceback" not in err
    assert main(["check", FOUR_BAR, "--debug"]) == 3
    assert "Traceback" in capsys.readouterr().err


def test_interrupted_command_exits_130(capsys, monkeypatch):
    def interrupted(*_args, **_kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr("synthesis.app.assess.assess", interrupted)
    assert main(["check", FOUR_BAR]) == 130
    assert capsys.readouterr().err.strip() == "interrupted"


class _InterruptImport(importlib.abc.MetaPathFinder):
    """Ctrl-C pressed while the program's modules are still loading."""

    def find_spec(self, name, path=None, target=None):
        if name == "synthesis.cli.boundary":
            raise KeyboardInterrupt


def test_interrupted_while_loading_exits_130(capsys, monkeypatch):
    monkeypatch.delitem(sys.modules, "synthesis.cli.boundary")
    monkeypatch.setattr(sys, "meta_path", [_InterruptImport(), *sys.meta_path])
    assert main(["check", FOUR_BAR]) == 130
    assert capsys.readouterr().err.strip() == "interrupted"


def _ctrl_c_after(monkeypatch, trials: int) -> None:
    """Press Ctrl-C (a real SIGINT) once the search has made ``trials`` trials."""
    report = synthesis.search._Search.report

    def pressing(self, final=False):
        report(self, final)
        if self.count >= trials and not final:
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(synthesis.search._Search, "report", pressing)


def test_ctrl_c_in_a_search_writes_the_best_design_and_exits_130(tmp_path, capsys,
                                                                  monkeypatch):
    _ctrl_c_after(monkeypatch, 256)
    out = tmp_path / "best.yaml"
    assert main(["synthesize", PROBLEM, "--budget", "14", "--quiet", "--out", str(out)]) == 130
    assert "interrupted" in capsys.readouterr().err
    head = out.read_text("utf-8")
    assert yaml.safe_load(head)  # the best design so far, as a table


def test_ctrl_c_in_the_search_of_a_report_exits_130(tmp_path, capsys, monkeypatch):
    _ctrl_c_after(monkeypatch, 64)
    out = tmp_path / "report.html"
    assert main(["report", PROBLEM, "--budget", "12", "--points", "12", "--out",
                 str(out), "--quiet"]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == "interrupted"


def test_a_closed_pipe_ends_quietly():
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    shell = (f"{sys.executable} -m synthesis analyze {FOUR_BAR} --json --points 20000 "
             f"| head -c 10 > /dev/null; echo $PIPESTATUS")
    done = subprocess.run(["bash", "-c", shell], env=env, capture_output=True, text=True,
                          check=False, timeout=300)
    assert done.stderr == ""  # no BrokenPipeError, no "Exception ignored"
    assert done.stdout.split()[0] == "141"


def test_check_loads_only_what_it_needs():
    code = (f"import sys; from synthesis.cli import main; main(['check', {FOUR_BAR!r}]); "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('scipy', 'matplotlib', 'tqdm') or m.startswith('synthesis.cli.commands.')))")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                          text=True, check=True, timeout=300)
    assert done.stdout.strip().splitlines()[-1] == "['synthesis.cli.commands.check']"
