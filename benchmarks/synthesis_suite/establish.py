"""Establish the optimum Q* of every suite problem and write ``optima.yaml``.

* ``exact`` problems: Q* = 0 by construction (targets from a known mechanism inside the
  bounds, ``generate.py``); nothing is searched.
* ``constrained`` and ``inexact`` problems: two independent methods on the same criteria
  (:class:`synthesis.evaluate.Evaluator`, lexicographic ranking P1, P2, Q):

  A. the program's search with far more effort than any setting of the suite: 2^12 LPτ
     trials per round, 4 shrinking passes, 7 restarts, refinement from 3 starts, seed 1000
     (the first problem, c01, was also run with 2^14 trials and seeds 1000 and 1001);
  B. :func:`scipy.optimize.differential_evolution` (population 20 per parameter, 200
     generations, seed 1000) on the scalar merit, followed by the program's refinement
     (least squares and the minimax polish, as a search with budget 0) from its result.

  Q* is the smaller of the two; both values are written so that their agreement can be read.
  A second run keeps the Q* of an earlier one when it finds nothing lower (``earlier``).

Run ``python benchmarks/synthesis_suite/establish.py [--jobs J]``; it takes minutes per
problem.
"""

from __future__ import annotations

import argparse
import multiprocessing
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from scipy import optimize

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT))

from synthesis import SearchSettings, load_problem
from synthesis.criteria import merit
from synthesis.evaluate import Evaluator
from synthesis.search import search

SEEDS = (1000,)


def _q(problem: Any, result: Any) -> float | None:
    c = result.criteria
    if c.p1[0] != 0 or c.p2[0] != 0:
        return None
    return float(c.q[0]) * problem.output_scale


def establish(stem: str) -> dict[str, Any]:
    """Q* of one problem by methods A and B (see the module docstring)."""
    problem = load_problem(HERE / "problems" / f"{stem}.yaml")
    evaluator = Evaluator(problem)
    lo, hi = problem.lower, problem.upper
    start = time.perf_counter()
    by_search = []
    for seed in SEEDS:
        settings = SearchSettings(budget_log2=12, seed=seed, shrink_passes=4, refine=True,
                                  restarts=7)
        by_search.append(_q(problem, search(evaluator, lo, hi, problem.initial, settings)))

    def scalar(x: np.ndarray) -> np.ndarray:
        return merit(evaluator(np.atleast_2d(x.T)), q_ref=1.0)

    found = optimize.differential_evolution(
        scalar, list(zip(lo, hi)), popsize=20, maxiter=200, tol=0.0, seed=SEEDS[0],
        polish=False, vectorized=True, updating="deferred")
    polished = search(evaluator, lo, hi, found.x,
                      SearchSettings(budget_log2=0, seed=SEEDS[0], refine=True))
    by_de = _q(problem, polished)
    values = [v for v in [*by_search, by_de] if v is not None]
    return {"problem": stem, "search": by_search, "differential_evolution": by_de,
            "q_star": min(values) if values else None,
            "seconds": round(time.perf_counter() - start, 1)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--only", nargs="*", default=None)
    args = parser.parse_args()
    listed = yaml.safe_load((HERE / "suite.yaml").read_text(encoding="utf-8"))["problems"]
    path = HERE / "optima.yaml"
    optima: dict[str, Any] = (yaml.safe_load(path.read_text(encoding="utf-8"))["optima"]
                              if path.exists() else {})
    todo = []
    for item in listed:
        stem = Path(item["problem"]).stem
        problem = load_problem(HERE / item["problem"])
        entry = {"kind": item["kind"], "accuracy": problem.accuracy,
                 "unit": problem.output_unit}
        if item["kind"] == "exact":
            optima[stem] = {**entry, "q_star": 0.0, "how": "targets from a known mechanism"}
        elif args.only is None or stem in args.only:
            optima[stem] = {**optima.get(stem, {}), **entry}
            todo.append(stem)
    with multiprocessing.Pool(args.jobs) as pool:
        for row in pool.imap_unordered(establish, todo):
            stem = row.pop("problem")
            # an optimum established before and not met again stays the optimum
            earlier = optima[stem].get("q_star")
            if earlier is not None and (row["q_star"] is None or earlier < row["q_star"]):
                row.update(q_star=earlier, earlier=earlier)
            optima[stem].update(row, how="min of search A and differential evolution B")
            print(stem, row, flush=True)
            path.write_text(yaml.safe_dump({"optima": optima}, sort_keys=False,
                                           allow_unicode=True), encoding="utf-8")
    path.write_text(yaml.safe_dump({"optima": optima}, sort_keys=False, allow_unicode=True),
                    encoding="utf-8")


if __name__ == "__main__":
    main()
