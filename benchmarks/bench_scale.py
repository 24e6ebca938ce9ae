"""Scale study of the Dask backend: speed-up here, and a cost model for many workers.

Run::

    python benchmarks/bench_scale.py [--budget 14] [--rounds 3] [--problem PROBLEM.yaml]

Needs the extra ``distributed``. Everything is measured side by side in one run and
repeated (``--rounds``), because the machine may be shared; the tables give the median and
the range over the rounds.

1. Speed-up: the passive LPτ search of the problem (the course's 11-link mechanism by
   default) with 2^budget designs, in this process, on a ``LocalCluster`` of 1 and of 2
   worker processes (started before the timing; their start is timed apart). Each cluster
   run is checked to give the single-process trials and best design bit for bit.
2. The terms of the cost model (``docs/scale.md``), per LPτ block of ``batch`` designs, in
   CPU time (``getrusage``: on a shared machine the wall time measures the queue for the
   cores as much as the work):

   * ``t_block``: evaluation of one block (the task's work), in this process and inside a
     worker of the 1-worker cluster (one BLAS thread there, as Dask sets it);
   * ``t_driver``: what the driver does per block whatever the cluster: draw the Sobol'
     points, record the block (rank, best, stop rules), concatenate at the end; measured by
     a search whose evaluator returns a block's criteria computed beforehand;
   * ``t_sched``: the client's and the scheduler's CPU per task (they share this process
     in a ``LocalCluster``), and ``t_wtask``: the workers' CPU per task, measured on the
     2-worker cluster by tasks that carry a real block in and a real block's criteria out
     but compute nothing, all submitted at once; the CPU the idle cluster spends in the same
     wall time (heartbeats, Dask's sampling profiler), measured over 2 s, is taken off;
   * ``t_round``: the wall-time round trip of one such task alone (latency; hidden by the
     window of tasks submitted ahead);
   * bytes in and out per block (pickled block, pickled criteria) and of the evaluator,
     sent once per worker.
3. The prediction of the model for 2^24 designs at 1 to 1024 workers.
"""

from __future__ import annotations

import argparse
import os
import pickle
import resource
import statistics
import sys
import time
from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import replace
from functools import partial
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synthesis import SearchResult, SearchSettings, load_problem
from synthesis.criteria import Criteria
from synthesis.distributed import DaskExecutor, connect
from synthesis.evaluate import Evaluator
from synthesis.problem import Problem
from synthesis.search import Executor, search

PROBLEM = ROOT / "input_tables" / "problems" / "class2_course_11_link.yaml"
#: Workers of the model's predictions, and the budget (log2) it predicts for.
PREDICT_WORKERS = (1, 2, 16, 64, 256, 1024)
PREDICT_BUDGET = 24
#: The driver's network link assumed by the model: 1 Gbit/s, in bytes per second.
LINK = 1e9 / 8


class _Canned:
    """An evaluator that returns one block's criteria computed beforehand (no work)."""

    def __init__(self, criteria: Criteria) -> None:
        self.criteria = criteria

    def __call__(self, x: np.ndarray) -> Criteria:
        whole = len(x) == len(self.criteria.q)
        return self.criteria if whole else self.criteria.take(np.arange(len(x)))


def _timed(run: Callable[[], SearchResult]) -> tuple[float, SearchResult]:
    start = time.perf_counter()
    result = run()
    return time.perf_counter() - start, result


def _search(problem: Problem, settings: SearchSettings, evaluate: Callable[..., Criteria],
            executor: Executor | None = None) -> SearchResult:
    return search(evaluate, problem.lower, problem.upper, problem.initial, settings,
                  executor=executor)


def _same(a: SearchResult, b: SearchResult) -> bool:
    return (np.array_equal(a.trials, b.trials) and np.array_equal(a.x, b.x)
            and all(np.array_equal(u, v, equal_nan=True)
                    for u, v in zip(a.trial_criteria.arrays(), b.trial_criteria.arrays())))


def _spread(values: list[float]) -> str:
    return f"{statistics.median(values):8.3f} [{min(values):.3f}–{max(values):.3f}]"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problem", default=str(PROBLEM))
    parser.add_argument("--budget", type=int, default=14, help="log2 of the designs")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()

    problem = load_problem(args.problem)
    settings = replace(problem.settings, budget_log2=args.budget, refine=False,
                       q_required=None, stall=None, shrink_passes=0, seed=1)
    evaluator = Evaluator(problem)
    blocks = 2 ** args.budget // settings.batch
    print(f"problem {Path(args.problem).name}: q = {problem.lower.size} varied parameters, "
          f"2^{args.budget} designs = {blocks} blocks of {settings.batch}; "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")

    with ExitStack() as stack:
        starts = {}
        executors = {}
        for workers in (1, 2):
            start = time.perf_counter()
            executors[workers] = stack.enter_context(connect(f"local:{workers}"))
            starts[workers] = time.perf_counter() - start
            # warm the workers: imports and the first evaluation
            _search(problem, replace(settings, budget_log2=10), evaluator, executors[workers])
        print("cluster start (s): " + ", ".join(f"local:{w} {t:.2f}" for w, t in starts.items()))

        # ---------------------------------------------------------------- 1. speed-up
        times: dict[str, list[float]] = {"single process": [], "local:1": [], "local:2": []}
        for _ in range(args.rounds):
            seconds, reference = _timed(lambda: _search(problem, settings, evaluator))
            times["single process"].append(seconds)
            for workers, executor in executors.items():
                seconds, result = _timed(partial(_search, problem, settings, evaluator, executor))
                assert _same(reference, result), "the cluster run differs from the single process"
                times[f"local:{workers}"].append(seconds)
        print(f"\n1. passive search, 2^{args.budget} designs, {args.rounds} rounds "
              "(median [min–max]); every cluster run identical to the single process")
        print(f"{'run':16s} {'seconds':>26s} {'speed-up':>9s}")
        for name, values in times.items():
            ratios = [s / v for s, v in zip(times["single process"], values)]
            print(f"{name:16s} {_spread(values):>26s} {statistics.median(ratios):9.2f}")

        # ---------------------------------------------------------------- 2. model terms
        _model(problem, settings, evaluator, executors, args.rounds)
        print(f"\nload average at the end: {os.getloadavg()[0]:.1f}")


def _cpu() -> float:
    """CPU seconds of this process, every thread (user + system)."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def _cpu_of_evaluations(evaluate: Callable[..., Criteria], x: np.ndarray, times: int) -> float:
    """CPU seconds of one evaluation, averaged over ``times`` (a task, measured where it runs)."""
    start = _cpu()
    for _k in range(times):
        evaluate(x)
    return (_cpu() - start) / times


def _workers_cpu(executor: DaskExecutor) -> float:
    return sum(executor.client.run(_cpu).values())


def _cpu_while(run: Callable[[], object], executor: DaskExecutor) -> tuple[float, float, float]:
    """Wall seconds of ``run()``, and the CPU seconds it took here and on the workers."""
    here, there, start = _cpu(), _workers_cpu(executor), time.perf_counter()
    run()
    return time.perf_counter() - start, _cpu() - here, _workers_cpu(executor) - there


def _drain(executor: DaskExecutor, fn: Callable[..., Criteria], x: np.ndarray, count: int,
           ahead: int) -> None:
    for _criteria in DaskExecutor(executor.client, ahead=ahead).map(
            fn, (x for _k in range(count))):
        pass


def _model(problem: Problem, settings: SearchSettings, evaluator: Evaluator,
           executors: dict[int, DaskExecutor], rounds: int) -> None:
    """Measure the terms of the cost model and predict the time of a 2^24-design run."""
    rng = np.random.default_rng(0)
    x = problem.lower + rng.random((settings.batch, problem.lower.size)) * (
        problem.upper - problem.lower)
    criteria = evaluator(x)
    canned = _Canned(criteria)
    blocks = 2 ** settings.budget_log2 // settings.batch
    terms: dict[str, list[float]] = {name: [] for name in (
        "t_block: evaluation, here", "t_block: evaluation, on a worker",
        "t_driver: draw + record", "t_sched: client + scheduler per task",
        "t_wtask: worker per task (no work)", "t_round: one task alone (wall)")}
    rows = list(terms.values())
    n_tasks = 256
    executor = executors[2]
    for _ in range(rounds):
        rows[0].append(_cpu_of_evaluations(evaluator, x, 8))
        rows[1].append(executors[1].client.submit(_cpu_of_evaluations, evaluator, x, 8,
                                                  pure=False).result())
        start = _cpu()
        _search(problem, settings, canned)
        rows[2].append((_cpu() - start) / blocks)
        # the cluster's CPU while idle (heartbeats, profiling) is taken off the tasks' CPU
        idle, idle_here, idle_there = _cpu_while(lambda: time.sleep(2.0), executor)
        wall, here, there = _cpu_while(
            lambda: _drain(executor, canned, x, n_tasks, n_tasks), executor)
        rows[3].append((here - idle_here / idle * wall) / n_tasks)
        rows[4].append((there - idle_there / idle * wall) / n_tasks)
        start = time.perf_counter()
        _drain(executor, canned, x, 16, 1)
        rows[5].append((time.perf_counter() - start) / 16)
    print(f"\n2. cost terms per block of {settings.batch} designs, CPU ms unless marked "
          "(median [min–max])")
    for name, values in terms.items():
        print(f"{name:38s} {_spread([1e3 * v for v in values])}")
    sizes = {"block in": len(pickle.dumps(x)), "criteria out": len(pickle.dumps(criteria)),
             "evaluator (once per worker)": len(pickle.dumps(evaluator))}
    for name, size in sizes.items():
        print(f"{name:38s} {size / 1024:8.1f} KiB")

    # ---------------------------------------------------------------- 3. prediction
    block, driver, sched, wtask = (statistics.median(v) for v in rows[1:5])
    wire = (sizes["block in"] + sizes["criteria out"]) / LINK
    n = 2 ** PREDICT_BUDGET // settings.batch
    print(f"\n3. predicted passive search of 2^{PREDICT_BUDGET} designs ({n} blocks of "
          f"{settings.batch}), each part on its own cores, c blocks per task:\n"
          "   T(W) = N·max((t_block + t_wtask)/W, t_driver, t_sched/c, bytes/link), "
          f"link {LINK / 2 ** 20:.0f} MiB/s")
    print(f"{'W':>6s} {'T (c = 1), s':>14s} {'limit':>10s} {'T (c = 16), s':>14s} {'limit':>10s}")
    for workers in PREDICT_WORKERS:
        line = f"{workers:6d}"
        for chunk in (1, 16):
            parts = {"workers": (block + wtask / chunk) / workers, "driver": driver,
                     "scheduler": sched / chunk, "network": wire}
            limit = max(parts, key=lambda k: parts[k])
            line += f" {n * parts[limit]:14.0f} {limit:>10s}"
        print(line)
    for chunk in (1, 16):
        serial = max(driver, sched / chunk, wire)
        print(f"c = {chunk:2d}: stops scaling at W ≈ (t_block + t_wtask/c) / max(t_driver, "
              f"t_sched/c, bytes/link) = {(block + wtask / chunk) / serial:.0f}")


if __name__ == "__main__":
    main()
