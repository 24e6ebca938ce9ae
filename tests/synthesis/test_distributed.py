"""The search and the batch on a local Dask cluster give what one process gives.

The reference of every check is the single-process run of the same seed: a cluster of two
worker processes must reproduce its trials, criteria and best design bit for bit, also when
a worker dies during the run, when the run stops early, and when Ctrl-C stops it. The default
path (no ``--scheduler``) must not import Dask at all, and ``--scheduler`` without Dask must
name the extra to install.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from collections.abc import Callable, Iterable, Iterator
from dataclasses import replace
from importlib.util import find_spec
from pathlib import Path

import numpy as np
import pytest

from synthesis import SearchResult, SearchSettings, load_problem
from synthesis.app.batch import run_batch
from synthesis.criteria import Criteria, merit
from synthesis.evaluate import Evaluator
from synthesis.problem import Problem
from synthesis.search import search

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml"
#: Designs per block: small blocks make many tasks from a small budget.
BLOCK = 64


def test_default_path_imports_no_dask(tmp_path):
    quick = tmp_path / "problem.yaml"  # the shipped problem without its refinement
    quick.write_text(PROBLEM.read_text(encoding="utf-8").replace("refine: true", "refine: false"),
                     encoding="utf-8")
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(f"""
        import sys
        from synthesis.cli import main
        code = main(["synthesize", {str(quick)!r}, "--budget", "6", "--quiet"])
        code += main(["batch", {str(tmp_path)!r}, "--jobs", "1", "--quiet"])
        print(code, sorted(m for m in sys.modules if m.split(".")[0] in ("dask", "distributed")))
        """)], cwd=ROOT, env=dict(os.environ, PYTHONPATH=str(ROOT)), capture_output=True,
        text=True, timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "0 []"


@pytest.mark.parametrize("command", ["synthesize", "batch"])
def test_scheduler_without_dask_names_the_extra(command, monkeypatch, capsys):
    from synthesis.cli import main

    monkeypatch.setitem(sys.modules, "distributed", None)  # as if Dask were not installed
    target = PROBLEM if command == "synthesize" else PROBLEM.parent
    assert main([command, str(target), "--scheduler", "local:2", "--quiet"]) == 2
    assert "pip install 'assur[distributed]'" in capsys.readouterr().err


@pytest.mark.parametrize("spec", ["local:0", "local:two", "http://host:1", "tcp://"])
def test_misnamed_scheduler_is_refused(spec, capsys):
    from synthesis.cli import main

    assert main(["synthesize", str(PROBLEM), "--scheduler", spec]) == 2
    assert f"found {spec!r}" in capsys.readouterr().err


# --------------------------------------------------------------------- on a cluster
_needs_dask = pytest.mark.skipif(find_spec("distributed") is None,
                                 reason="Dask is not installed (extra 'distributed')")


@pytest.fixture(scope="module")
def executor():
    from synthesis.distributed import connect

    with connect("local:2") as found:
        yield found


@pytest.fixture(scope="module")
def problem() -> Problem:
    return load_problem(PROBLEM)


def _settings(problem: Problem, stall: int | None = None) -> SearchSettings:
    """Passive search only (the refinement runs in this process anyway), no early stop
    unless by ``stall``."""
    return replace(problem.settings, budget_log2=10, batch=BLOCK, refine=False,
                   q_required=None, seed=5, stall=stall)


def _search(problem: Problem, settings: SearchSettings, evaluate: Callable[..., Criteria],
            executor: object = None) -> SearchResult:
    return search(evaluate, problem.lower, problem.upper, problem.initial, settings,
                  executor=executor)  # type: ignore[arg-type]


def _same(a: SearchResult, b: SearchResult) -> None:
    """Bit-for-bit the same run: trials, criteria, best design, history and stop."""
    assert a.stop == b.stop
    np.testing.assert_array_equal(a.trials, b.trials, strict=True)
    for mine, theirs in zip(a.trial_criteria.arrays(), b.trial_criteria.arrays()):
        np.testing.assert_array_equal(mine, theirs, strict=True)
    np.testing.assert_array_equal(a.x, b.x, strict=True)
    assert [(h.trial, h.q, h.stage) for h in a.history] == \
        [(h.trial, h.q, h.stage) for h in b.history]


def _tasks_left(executor) -> int:
    """Tasks of the runs the scheduler still holds."""
    client = executor.client
    # a barrier: the messages sent before this task's have reached the scheduler
    client.submit(int, 0, pure=False).result()

    def count(dask_scheduler) -> int:
        return sum(str(key).startswith("assur-") for key in dask_scheduler.tasks)

    return int(client.run_on_scheduler(count))


@pytest.fixture(scope="module")
def serial(problem):
    return _search(problem, _settings(problem), Evaluator(problem))


@pytest.mark.distributed
@_needs_dask
def test_synthesize_on_the_cluster_is_the_single_process_run(problem, executor):
    from synthesis import synthesize

    settings = replace(problem.settings, budget_log2=8, batch=BLOCK, seed=3, refine=False)
    here = synthesize(problem, settings)
    there = synthesize(problem, settings, scheduler=executor)
    _same(here.search, there.search)
    assert here.design == there.design


class _KillOnce:
    """The evaluator, except that the first worker to meet ``trigger`` dies at once."""

    def __init__(self, evaluate: Evaluator, trigger: np.ndarray, marker: Path) -> None:
        self.evaluate, self.trigger, self.marker = evaluate, trigger.tobytes(), str(marker)

    def __call__(self, x: np.ndarray) -> Criteria:
        if x.tobytes() == self.trigger:
            try:
                os.close(os.open(self.marker, os.O_CREAT | os.O_EXCL))
            except FileExistsError:
                pass
            else:
                os._exit(1)  # the worker process is lost with its task
        return self.evaluate(x)


@pytest.mark.distributed
@_needs_dask
def test_a_lost_worker_does_not_change_the_result(problem, serial, executor, tmp_path):
    settings = _settings(problem)
    third = serial.trials[1 + 2 * BLOCK:1 + 3 * BLOCK]  # trial 0 is the initial design
    marker = tmp_path / "killed"
    there = _search(problem, settings, _KillOnce(Evaluator(problem), third, marker), executor)
    assert marker.exists()  # a worker did die mid-run
    _same(serial, there)


@pytest.mark.distributed
@_needs_dask
def test_several_blocks_per_task_give_the_same_run(problem, serial, executor):
    from synthesis.distributed import DaskExecutor

    chunked = DaskExecutor(executor.client, chunk=3)  # 16 blocks: 5 tasks of 3 and one of 1
    _same(serial, _search(problem, _settings(problem), Evaluator(problem), chunked))


@pytest.mark.distributed
@_needs_dask
def test_a_stop_rule_cancels_the_pending_tasks(problem, serial, executor):
    stall = 3 * BLOCK
    settings = _settings(problem, stall=stall)
    here = _search(problem, settings, Evaluator(problem))
    there = _search(problem, settings, Evaluator(problem), executor)
    assert there.stop == "stall" and len(there.trials) < len(serial.trials)
    _same(here, there)
    assert _tasks_left(executor) == 0


class _CtrlCAfter:
    """An executor whose user presses Ctrl-C after ``blocks`` results have come back."""

    def __init__(self, inner, blocks: int) -> None:
        self.inner, self.blocks = inner, blocks

    def map(self, fn: Callable[..., Criteria], items: Iterable[np.ndarray]
            ) -> Iterator[Criteria]:
        for k, result in enumerate(self.inner.map(fn, items)):
            if k == self.blocks:
                raise KeyboardInterrupt
            yield result


@pytest.mark.distributed
@_needs_dask
def test_ctrl_c_keeps_the_best_so_far_and_cancels(problem, serial, executor):
    settings = _settings(problem)
    there = _search(problem, settings, Evaluator(problem), _CtrlCAfter(executor, 5))
    assert there.stop == "interrupted"
    done = 1 + 5 * BLOCK
    np.testing.assert_array_equal(there.trials, serial.trials[:done], strict=True)
    # the best of those trials, ranked independently of the search's bookkeeping
    ranks = merit(serial.trial_criteria.take(np.arange(done)))
    np.testing.assert_array_equal(there.x, serial.trials[int(np.argmin(ranks))], strict=True)
    assert _tasks_left(executor) == 0


@pytest.mark.distributed
@_needs_dask
def test_ctrl_c_while_drawing_cancels_the_tasks(executor):
    def blocks() -> Iterator[float]:
        yield from (1.0, -2.0, 3.0)
        raise KeyboardInterrupt  # pressed while the next block is drawn

    try:
        list(executor.map(abs, blocks()))
    except KeyboardInterrupt as pressed:
        # its traceback keeps the executor's frame, and so its futures, alive
        assert pressed.__traceback__ is not None and _tasks_left(executor) == 0
    else:
        pytest.fail("the interrupt was lost")


@pytest.mark.distributed
@_needs_dask
def test_batch_on_the_cluster_is_the_single_process_batch(executor, tmp_path):
    for path in [PROBLEM, ROOT / "input_tables" / "course_11_link_table.yaml"]:
        shutil.copy(path, tmp_path / path.name)
    (tmp_path / "broken.yaml").write_text("mechanism: [links, 0, 1\n", encoding="utf-8")
    here = run_batch(tmp_path, jobs=1)
    there = run_batch(tmp_path, executor=executor)
    assert [replace(r, seconds=0.0) for r in there] == [replace(r, seconds=0.0) for r in here]
    # the course table has no sketch: its assembly variants are not verified
    assert [r.verdict for r in there] == ["unreadable", "correct", "not verified"]
