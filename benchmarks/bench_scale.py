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
2. The terms of the cost model (``docs/scale.md``), per LPτ block of ``batch`` designs:

   * ``t_block``: evaluation of one block (the task's work), in this process and inside a
     worker of the 1-worker cluster (one BLAS thread there, as Dask sets it);
   * ``t_driver``: what the driver does per block whatever the cluster: draw the Sobol'
     points, record the block (rank, best, stop rules), concatenate at the end; measured by
     a search whose evaluator returns a block's criteria computed beforehand;
   * ``t_task``: Dask's cost per task (client, scheduler, worker, both transfers), measured
     on the 2-worker cluster by tasks that carry a real block in and a real block's criteria
     out but compute nothing, all submitted at once (their throughput; an upper bound here,
     where client, scheduler and workers share two cores);
   * ``t_round``: the round trip of one such task alone (latency; hidden by the window of
     tasks submitted ahead while 2·t_block > t_round);
   * bytes in and out per block (pickled block, pickled criteria) and of the evaluator,
     sent once per worker.
"""

from __future__ import annotations

import argparse
import pickle
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

from synthesis.criteria import Criteria
from synthesis.distributed import DaskExecutor, connect
from synthesis.evaluate import Evaluator
from synthesis.problem import Problem, load_problem
from synthesis.search import Executor, SearchResult, SearchSettings, search

PROBLEM = ROOT / "input_tables" / "problems" / "class2_course_11_link.yaml"
#: Workers of the model's predictions, and the budget (log2) it predicts for.
PREDICT_WORKERS = (1, 2, 16, 64, 256, 1024)
PREDICT_BUDGET = 24


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


def _evaluation_time(evaluate: Callable[..., Criteria], x: np.ndarray) -> float:
    """Seconds of one evaluation (a task, timed where it runs)."""
    start = time.perf_counter()
    evaluate(x)
    return time.perf_counter() - start


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
          f"2^{args.budget} designs = {blocks} blocks of {settings.batch}")

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
        rng = np.random.default_rng(0)
        x = problem.lower + rng.random((settings.batch, problem.lower.size)) * (
            problem.upper - problem.lower)
        criteria = evaluator(x)
        canned = _Canned(criteria)
        t_block: list[float] = []
        t_worker: list[float] = []
        t_driver: list[float] = []
        t_task: list[float] = []
        t_round: list[float] = []
        n_tasks = 256
        client = executors[2].client
        for _ in range(args.rounds):
            t_block.append(statistics.median(_evaluation_time(evaluator, x) for _k in range(8)))
            t_worker.append(statistics.median(executors[1].client.gather([
                executors[1].client.submit(_evaluation_time, evaluator, x, pure=False)
                for _k in range(8)])))
            seconds, _result = _timed(lambda: _search(problem, settings, canned))
            t_driver.append(seconds / blocks)
            for window, n, found in ((n_tasks, n_tasks, t_task), (1, 16, t_round)):
                start = time.perf_counter()
                for _criteria in DaskExecutor(client, ahead=window).map(canned,
                                                                       (x for _k in range(n))):
                    pass
                found.append((time.perf_counter() - start) / n)
        sizes = {"block in": len(pickle.dumps(x)), "criteria out": len(pickle.dumps(criteria)),
                 "evaluator (once per worker)": len(pickle.dumps(evaluator))}
        print(f"\n2. cost terms per block of {settings.batch} designs (median [min–max], ms)")
        for name, values in (("t_block (evaluation)", t_block),
                             ("t_block on a worker", t_worker),
                             ("t_driver (draw + record)", t_driver),
                             ("t_task (Dask, per task)", t_task),
                             ("t_round (one task alone)", t_round)):
            print(f"{name:28s} {_spread([1e3 * v for v in values])}")
        for name, size in sizes.items():
            print(f"{name:28s} {size / 1024:8.1f} KiB")

        # ---------------------------------------------------------------- 3. prediction
        tb, td, tt = (statistics.median(v) for v in (t_block, t_driver, t_task))
        n = 2 ** PREDICT_BUDGET // settings.batch
        print(f"\n3. predicted passive search of 2^{PREDICT_BUDGET} designs ({n} blocks): "
              "T(W) = N·max(t_block/W, t_driver, t_task/c) for c blocks per task")
        print(f"{'W':>6s} {'T (c = 1), s':>14s} {'T (c = 16), s':>14s} {'limit (c = 1)':>16s}")
        for workers in PREDICT_WORKERS:
            terms = {"workers": tb / workers, "driver": td, "scheduler": tt}
            chunked = max(tb / workers, td, tt / 16)
            print(f"{workers:6d} {n * max(terms.values()):14.0f} {n * chunked:14.0f} "
                  f"{max(terms, key=lambda k: terms[k]):>16s}")
        print(f"stops scaling at W ≈ t_block / max(t_driver, t_task) = {tb / max(td, tt):.0f} "
              f"(c = 1), t_block / max(t_driver, t_task/16) = {tb / max(td, tt / 16):.0f} (c = 16)")


if __name__ == "__main__":
    main()
