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
import signal
import socket
import subprocess
import sys
import textwrap
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from synthesis import SearchResult, SearchSettings, load_problem
from synthesis.app.batch import run_batch
from synthesis.criteria import Criteria, merit
from synthesis.distributed import DaskExecutor
from synthesis.evaluate import Evaluator
from synthesis.problem import Problem
from synthesis.search import search

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml"
#: Designs per block: small blocks make many tasks from a small budget.
BLOCK = 64


def test_default_path_imports_no_dask(tmp_path: Path) -> None:
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
def test_scheduler_without_dask_names_the_extra(command: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cli import main

    monkeypatch.setitem(sys.modules, "distributed", None)  # as if Dask were not installed
    target = PROBLEM if command == "synthesize" else PROBLEM.parent
    assert main([command, str(target), "--scheduler", "local:2", "--quiet"]) == 2
    assert "pip install 'assur[distributed]'" in capsys.readouterr().err


def _closed_port() -> int:
    """A port of this machine where nothing listens (bound, then released)."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


#: Bad ``--scheduler`` values and the part of each that the message must quote as found.
_MISNAMED = [("local:0", "'0'"), ("local:two", "'two'"), ("local:-1", "'-1'"),
             (f"local:{os.cpu_count() or 1}0", f"'{os.cpu_count() or 1}0'"),
             ("http://host:1", "'http://host:1'"), ("tcp://", "''"),
             ("tcp://127.0.0.1:abc", "'abc'"), ("tcp://:::", "'::'"), ("tcp://[::1]", "''"),
             ("tcp://127.0.0.1:0", "'0'"), ("tcp://127.0.0.1:65536", "'65536'"),
             ("tcp://[::1:8786", "'[::1:8786'"), ("tcp://999.1.1.1:8786", "'999.1.1.1'"),
             ("tcp://-host:8786", "'-host'"), ("tcp://host:8786/x", "'8786/x'")]


@pytest.mark.parametrize("command", ["synthesize", "batch"])
@pytest.mark.parametrize(("spec", "found"), _MISNAMED)
def test_misnamed_scheduler_is_refused_before_the_run(command: str, spec: str, found: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cli import main

    shutil.copy(PROBLEM, tmp_path / PROBLEM.name)
    target = tmp_path / PROBLEM.name if command == "synthesize" else tmp_path
    out = tmp_path / "out.yaml"
    extra = ["--out", str(out)] if command == "synthesize" else ["--csv", str(out)]
    assert main([command, str(target), "--scheduler", spec, *extra]) == 2
    printed = capsys.readouterr()
    assert printed.err.startswith(f"--scheduler {spec!r}") or \
        printed.err.startswith("--scheduler expects")
    assert f"found {found}" in printed.err and "Traceback" not in printed.err
    assert printed.out == "" and not out.exists()  # refused before anything ran


def test_the_local_maximum_is_the_cores(capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cli import main
    from synthesis.distributed import parse_scheduler

    cores = len(os.sched_getaffinity(0))
    assert parse_scheduler(f"local:{cores}") == cores
    assert main(["synthesize", str(PROBLEM), "--scheduler", f"local:{cores + 1}"]) == 2
    assert f"from 1 to {cores} " in capsys.readouterr().err


@pytest.mark.parametrize("lang", ["en", "ru"])
@pytest.mark.parametrize("command", ["synthesize", "batch"])
def test_an_unreachable_scheduler_is_refused(command: str, lang: str, capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cli import main
    from synthesis.distributed import CONNECT_SECONDS

    target = PROBLEM if command == "synthesize" else PROBLEM.parent
    spec = f"tcp://127.0.0.1:{_closed_port()}"
    start = time.monotonic()
    assert main([command, str(target), "--scheduler", spec, "--quiet", "--lang", lang]) == 2
    assert time.monotonic() - start < CONNECT_SECONDS + 30
    err = capsys.readouterr().err
    assert err.startswith(f"--scheduler {spec}" if lang == "en" else f"'--scheduler {spec}'")
    assert "Traceback" not in err


@pytest.mark.parametrize("command", ["synthesize", "batch"])
def test_tls_without_its_settings_is_refused(command: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis.cli import main

    for name in ("CA_FILE", "CLIENT__CERT"):  # the test's own environment must not give them
        monkeypatch.delenv(f"DASK_DISTRIBUTED__COMM__TLS__{name}", raising=False)
    target = PROBLEM if command == "synthesize" else PROBLEM.parent
    assert main([command, str(target), "--scheduler", "tls://127.0.0.1:1", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("--scheduler tls://127.0.0.1:1") and "ca-file" in err
    assert "Traceback" not in err


def test_jobs_above_the_cores_are_lowered_with_a_warning(tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    from synthesis.cli import main

    started: list[int] = []

    class Counting(ProcessPoolExecutor):
        def __init__(self, max_workers: int, **kwargs: Any) -> None:
            started.append(max_workers)
            super().__init__(max_workers=max_workers, **kwargs)

    monkeypatch.setattr("synthesis.app.batch.ProcessPoolExecutor", Counting)
    for name in ("a.yaml", "b.yaml", "c.yaml"):
        shutil.copy(ROOT / "input_tables" / "course_11_link_table.yaml", tmp_path / name)
    cores = len(os.sched_getaffinity(0))
    assert main(["batch", str(tmp_path), "--jobs", "100000", "--quiet", "--lang", "ru"]) == 0
    err = capsys.readouterr().err
    assert err.strip() == f"--jobs 100000: больше, чем ядер у этого компьютера ({cores}); " \
        f"используется {cores}"
    assert started == ([cores] if cores > 1 else [])


# --------------------------------------------------------------------- on a cluster
_needs_dask = pytest.mark.skipif(find_spec("distributed") is None,
                                 reason="Dask is not installed (extra 'distributed')")


@pytest.fixture(scope="module")
def executor() -> Iterator[DaskExecutor]:
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


def _search(problem: Problem, settings: SearchSettings, evaluate: Callable[..., Criteria], executor: object = None) -> SearchResult:
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


def _tasks_left(executor: DaskExecutor) -> int:
    """Tasks of the runs the scheduler still holds."""
    client = executor.client
    # a barrier: the messages sent before this task's have reached the scheduler
    client.submit(int, 0, pure=False).result()

    def count(dask_scheduler: Any) -> int:
        return sum(str(key).startswith("assur-") for key in dask_scheduler.tasks)

    return int(client.run_on_scheduler(count))


@pytest.fixture(scope="module")
def serial(problem: Problem) -> SearchResult:
    return _search(problem, _settings(problem), Evaluator(problem))


@pytest.mark.distributed
@_needs_dask
def test_synthesize_on_the_cluster_is_the_single_process_run(problem: Problem,
                                                             executor: DaskExecutor) -> None:
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
def test_a_lost_worker_does_not_change_the_result(problem: Problem, serial: SearchResult, executor: DaskExecutor, tmp_path: Path) -> None:
    settings = _settings(problem)
    third = serial.trials[1 + 2 * BLOCK:1 + 3 * BLOCK]  # trial 0 is the initial design
    marker = tmp_path / "killed"
    there = _search(problem, settings, _KillOnce(Evaluator(problem), third, marker), executor)
    assert marker.exists()  # a worker did die mid-run
    _same(serial, there)


@pytest.mark.distributed
@_needs_dask
def test_several_blocks_per_task_give_the_same_run(problem: Problem, serial: SearchResult, executor: DaskExecutor) -> None:
    from synthesis.distributed import DaskExecutor

    chunked = DaskExecutor(executor.client, chunk=3)  # 16 blocks: 5 tasks of 3 and one of 1
    _same(serial, _search(problem, _settings(problem), Evaluator(problem), chunked))


@pytest.mark.distributed
@_needs_dask
def test_a_stop_rule_cancels_the_pending_tasks(problem: Problem, serial: SearchResult, executor: DaskExecutor) -> None:
    stall = 3 * BLOCK
    settings = _settings(problem, stall=stall)
    here = _search(problem, settings, Evaluator(problem))
    there = _search(problem, settings, Evaluator(problem), executor)
    assert there.stop == "stall" and len(there.trials) < len(serial.trials)
    _same(here, there)
    assert _tasks_left(executor) == 0


class _CtrlCAfter:
    """An executor whose user presses Ctrl-C after ``blocks`` results have come back."""

    def __init__(self, inner: DaskExecutor, blocks: int) -> None:
        self.inner, self.blocks = inner, blocks

    def map(self, fn: Callable[..., Criteria], items: Iterable[np.ndarray]) -> Iterator[Criteria]:
        for k, result in enumerate(self.inner.map(fn, items)):
            if k == self.blocks:
                raise KeyboardInterrupt
            yield result


@pytest.mark.distributed
@_needs_dask
def test_ctrl_c_keeps_the_best_so_far_and_cancels(problem: Problem, serial: SearchResult, executor: DaskExecutor) -> None:
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
def test_ctrl_c_while_drawing_cancels_the_tasks(executor: DaskExecutor) -> None:
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
def test_batch_on_the_cluster_is_the_single_process_batch(executor: DaskExecutor, tmp_path: Path) -> None:
    for path in [PROBLEM, ROOT / "input_tables" / "course_11_link_table.yaml"]:
        shutil.copy(path, tmp_path / path.name)
    (tmp_path / "broken.yaml").write_text("mechanism: [links, 0, 1\n", encoding="utf-8")
    here = run_batch(tmp_path, jobs=1)
    there = run_batch(tmp_path, executor=executor)
    assert [replace(r, seconds=0.0) for r in there] == [replace(r, seconds=0.0) for r in here]
    # the course table has no sketch: its assembly variants are not verified
    assert [r.verdict for r in there] == ["unreadable", "correct", "not verified"]


@pytest.fixture
def lonely() -> Iterator[DaskExecutor]:
    """A cluster of one worker, of this test alone."""
    from synthesis.distributed import connect

    with connect("local:1") as found:
        yield found


@pytest.mark.distributed
@_needs_dask
def test_the_only_worker_lost_mid_run_changes_nothing(problem: Problem, serial: SearchResult, lonely: DaskExecutor, tmp_path: Path) -> None:
    # the one worker holds the function and dies; the restarted worker must get it back
    settings = _settings(problem)
    third = serial.trials[1 + 2 * BLOCK:1 + 3 * BLOCK]
    marker = tmp_path / "killed"
    there = _search(problem, settings, _KillOnce(Evaluator(problem), third, marker), lonely)
    assert marker.exists()
    _same(serial, there)


class _Witness:
    """The evaluator, leaving the id of the process of each evaluation in a folder."""

    def __init__(self, evaluate: Evaluator, folder: Path) -> None:
        self.evaluate, self.folder = evaluate, str(folder)

    def __call__(self, x: np.ndarray) -> Criteria:
        Path(self.folder, str(os.getpid())).touch()
        return self.evaluate(x)


class _JoinAfter:
    """An executor whose cluster gains a worker once ``blocks`` results have come back."""

    def __init__(self, inner: DaskExecutor, blocks: int) -> None:
        self.inner, self.blocks = inner, blocks
        self.joined: set[int] = set()

    def map(self, fn: Callable[..., Criteria], items: Iterable[np.ndarray]) -> Iterator[Criteria]:
        client = self.inner.client
        for k, result in enumerate(self.inner.map(fn, items)):
            if k == self.blocks and not self.joined:  # once, in the first stage
                before = set(client.run(os.getpid).values())
                assert client.cluster is not None  # the local cluster of the fixture
                client.cluster.scale(2)
                client.wait_for_workers(2, timeout=120)
                self.joined = set(client.run(os.getpid).values()) - before
            yield result


@pytest.mark.distributed
@_needs_dask
def test_a_worker_joining_late_takes_tasks_and_changes_nothing(problem: Problem, serial: SearchResult, lonely: DaskExecutor, tmp_path: Path) -> None:
    joining = _JoinAfter(lonely, 2)
    there = _search(problem, _settings(problem), _Witness(Evaluator(problem), tmp_path),
                    joining)
    _same(serial, there)
    assert len(joining.joined) == 1
    assert joining.joined <= {int(p.name) for p in tmp_path.iterdir()}  # it did evaluate


def _children(pid: int) -> list[int]:
    """The processes started by ``pid`` (none once it is gone)."""
    found: list[int] = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            found += map(int, (task / "children").read_text().split())
        except OSError:
            pass
    return found


def _cpu_seconds(pid: int) -> float:
    """User and system time of a process (0 once it is gone)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _interrupt_when_working(command: list[str]) -> tuple[subprocess.CompletedProcess[str],
                                                            list[int]]:
    """Run ``command`` in its own process group; press Ctrl-C (SIGINT to the whole group,
    as a terminal does) once a worker process has spent a second of CPU on the tasks."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.Popen([sys.executable, "-m", "synthesis", *command], cwd=ROOT, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           start_new_session=True)
    deadline = time.monotonic() + 240
    workers: list[int] = []
    while time.monotonic() < deadline and run.poll() is None:
        # the workers are forked from the fork server, a child of the command
        servers = [p for p in _children(run.pid) if b"forkserver" in _cmdline(p)]
        workers = [p for server in servers for p in _children(server)]
        if any(_cpu_seconds(p) > 1.0 for p in workers):
            break
        time.sleep(0.1)
    os.killpg(run.pid, signal.SIGINT)
    out, err = run.communicate(timeout=240)
    for _ in range(300):  # the workers close with their cluster, if not at once
        if not any(Path(f"/proc/{p}").exists() for p in workers):
            break
        time.sleep(0.1)
    return subprocess.CompletedProcess(run.args, run.returncode, out, err), workers


def _cmdline(pid: int) -> bytes:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return b""


@pytest.mark.distributed
@_needs_dask
def test_ctrl_c_of_synthesize_on_a_cluster_keeps_the_best_and_exits_130(tmp_path: Path) -> None:
    best = tmp_path / "best.yaml"
    done, workers = _interrupt_when_working(
        ["synthesize", str(PROBLEM), "--budget", "20", "--scheduler", "local:1", "--quiet",
         "--out", str(best)])
    assert done.returncode == 130, done.stderr
    assert "Traceback" not in done.stderr and done.stderr.splitlines()[-1] == "interrupted"
    assert workers and not any(Path(f"/proc/{p}").exists() for p in workers)
    design = yaml.safe_load(best.read_text(encoding="utf-8"))
    # the written design is the one of the report, as without a cluster
    assert "interrupted" in done.stdout and design


@pytest.mark.distributed
@_needs_dask
def test_ctrl_c_of_batch_on_a_cluster_exits_130(tmp_path: Path) -> None:
    table = ROOT / "input_tables" / "course_11_link_table.yaml"
    for k in range(400):
        shutil.copy(table, tmp_path / f"student{k:03}.yaml")
    report = tmp_path / "rows.csv"
    done, workers = _interrupt_when_working(
        ["batch", str(tmp_path), "--scheduler", "local:1", "--quiet", "--csv", str(report)])
    assert done.returncode == 130, done.stderr
    assert "Traceback" not in done.stderr and done.stderr.splitlines()[-1] == "interrupted"
    assert workers and not any(Path(f"/proc/{p}").exists() for p in workers)
    assert done.stdout == "" and not report.exists()  # no rows of a batch cut short
