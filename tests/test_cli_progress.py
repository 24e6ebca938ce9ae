"""Progress bars: the total, the best so far and the time left on a terminal; nothing in a
pipe, a log or with ``--quiet``."""

from __future__ import annotations

import io
from pathlib import Path

from synthesis import load_problem, synthesize
from synthesis.app import progress
from synthesis.app.batch import run_batch
from synthesis.cli import main
from synthesis.search_settings import settings_for

ROOT = Path(__file__).resolve().parent.parent
PROBLEM = ROOT / "input_tables" / "problems" / "class3_fourbar_path.yaml"


class Terminal(io.StringIO):
    """A text stream that says it is a terminal."""

    def isatty(self) -> bool:
        return True


def test_bars_only_on_a_terminal_and_never_with_quiet():
    assert progress.shown(False, Terminal())
    assert not progress.shown(True, Terminal())
    assert not progress.shown(False, io.StringIO())


def test_search_bar_shows_total_best_and_time_left(monkeypatch):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "REDRAW", 0.0)
    totals = []
    move_to = progress.Bar.move_to

    def recording(self, done, total=None, note=None):
        totals.append(total)
        move_to(self, done, total, note)

    monkeypatch.setattr(progress.Bar, "move_to", recording)
    problem = load_problem(PROBLEM)
    screen = Terminal()
    with progress.following_search(quiet=False, stream=screen) as bar:
        outcome = synthesize(problem, settings_for(problem, budget_log2=6, refine=False,
                                                   shrink_passes=0, restarts=0))
    drawn = screen.getvalue()
    assert bar.done == outcome.search.trials.shape[0] == 1 + 2 ** 6
    assert set(totals) == {1 + 2 ** 6}  # from the start: trial 0 and the 2**6 LPτ trials
    assert f"/{1 + 2 ** 6} [" in drawn
    assert "best P1=" in drawn and "<" in drawn  # the best so far; elapsed<left


def test_the_total_counts_every_round(monkeypatch):
    # two rounds of 2**4 LPτ trials and 2 shrinking passes of 2**4 each (the passes draw at
    # least 16), counted by hand from the settings
    totals = []
    monkeypatch.setattr(progress.Bar, "move_to",
                        lambda self, done, total=None, note=None: totals.append(total))
    problem = load_problem(PROBLEM)
    with progress.following_search(quiet=True, stream=Terminal()):
        synthesize(problem, settings_for(problem, budget_log2=4, refine=False, shrink_passes=2,
                                         restarts=1))
    assert set(totals) == {1 + 2 * (2 ** 4 + 2 * 16)}


def test_quiet_terminal_and_pipe_get_no_progress(monkeypatch, capsys):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "REDRAW", 0.0)
    screen = Terminal()
    with progress.following_search(quiet=True, stream=screen) as bar:
        problem = load_problem(PROBLEM)
        synthesize(problem, settings_for(problem, budget_log2=4, refine=False,
                                              shrink_passes=0, restarts=0))
    assert screen.getvalue() == "" and bar.done == 1 + 2 ** 4  # counted, not drawn
    assert main(["synthesize", str(PROBLEM), "--budget", "4"]) in (0, 1)
    err = capsys.readouterr().err  # standard error is not a terminal here
    assert "trials" not in err and "\r" not in err


def test_batch_bar_counts_every_table(monkeypatch, tmp_path):
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "REDRAW", 0.0)
    for name in ("four_bar.yaml", "slider_crank.yaml", "stephenson.yaml"):
        (tmp_path / name).write_bytes((ROOT / "input_tables" / name).read_bytes())
    (tmp_path / "notes.txt").write_text("not a table")
    screen = Terminal()
    with progress.counting(0, "progress.batch", quiet=False, stream=screen) as bar:
        rows = run_batch(tmp_path, jobs=1, progress=lambda done, total: bar.move_to(done, total))
    assert len(rows) == 4 and bar.done == bar.total == 3  # the tables, not the text file
    assert "/3 [" in screen.getvalue()  # the total, with the time left after it
