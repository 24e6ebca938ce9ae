"""Run the synthesis benchmark suite: success rate and time per budget and setting.

::

    python benchmarks/synthesis_suite/run.py --profile quick          # a few problems, 3 seeds
    python benchmarks/synthesis_suite/run.py --profile full --jobs 2  # every problem, 10 seeds
    python benchmarks/synthesis_suite/run.py --report                 # table and plot only

Every run (setting, problem, seed) is appended as one JSON line to
``results/<setting>.jsonl`` as soon as it ends, so an interrupted run resumes where it
stopped.  ``--report`` reads every results file and ``optima.yaml`` (the known optima, see
``establish.py``) and writes ``docs/synthesis_suite.md`` (the table) and
``docs/img/synthesis_suite.png`` (success rate against time).

A run succeeds when its design is feasible (P1 = P2 = 0) and Q ≤ Q* + tol, with tol the
problem's [Q] when Q* = 0 and 0.5 % of Q* otherwise.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import sys
import time
from collections import Counter, defaultdict
from dataclasses import replace
from pathlib import Path
from typing import Any

import yaml

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT))

from synthesis import SearchSettings, load_problem
from synthesis.evaluate import Evaluator
from synthesis.problem import Problem
from synthesis.search import search

#: Relative tolerance on Q* > 0 within which a run counts as reaching the optimum.
RELATIVE = 5e-3

#: The settings compared: name → fields of SearchSettings (seed and [Q] come per run).
SETTINGS: dict[str, dict[str, Any]] = {
    # before: what a student met — the shipped problems' search table, and the program's
    # defaults when a problem has none
    "before-shipped": {"budget_log2": 10, "refine": True, "shrink_passes": 0, "restarts": 0},
    "before-program": {"budget_log2": 12, "refine": False, "shrink_passes": 0, "restarts": 0},
    # candidates: rounds of LPτ and shrinking passes (cheap), the refinement after them
    "b10-s3-r3": {"budget_log2": 10, "refine": True, "shrink_passes": 3, "restarts": 3},
    "b8-s3-r3": {"budget_log2": 8, "refine": True, "shrink_passes": 3, "restarts": 3},
    "b10-s3-r7": {"budget_log2": 10, "refine": True, "shrink_passes": 3, "restarts": 7},
    # the stop-on-stall rule: a round ends after 512 trials without improving its best
    "b10-s3-r3-stall512": {"budget_log2": 10, "refine": True, "shrink_passes": 3,
                           "restarts": 3, "stall": 512},
}
#: Settings measured on the search before the refinement held the desirable conditions as
#: constraints (docs/synthesis_suite.md, "before"): name → (success %, mean s per run).
#: Their results files are not kept; the plot shows them beside the runs of this tree.
BEFORE: dict[str, tuple[float, float]] = {
    "before-shipped": (88.5, 4.20), "before-program": (6.9, 2.75),
    "b10-s3-r3 (before)": (92.3, 8.82)}
PROFILES: dict[str, dict[str, Any]] = {
    "quick": {"problems": ["e01_fourbar_angle", "e08_slider_crank", "c01_rocker_pressure_45",
                           "i01_rocker_law"], "seeds": 3},
    "full": {"problems": None, "seeds": 10},
}

_CACHE: dict[str, Problem] = {}


def problems(names: list[str] | None) -> list[str]:
    listed = yaml.safe_load((HERE / "suite.yaml").read_text(encoding="utf-8"))["problems"]
    stems = [Path(item["problem"]).stem for item in listed]
    return stems if names is None else [s for s in stems if s in names]


def one_run(task: tuple[str, str, int]) -> dict[str, Any]:
    """Search one problem with one setting and seed; the outcome as plain data."""
    setting, stem, seed = task
    if stem not in _CACHE:
        _CACHE[stem] = load_problem(HERE / "problems" / f"{stem}.yaml")
    problem = _CACHE[stem]
    settings: SearchSettings = replace(problem.settings, seed=seed, **SETTINGS[setting])
    start = time.perf_counter()
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial, settings)
    seconds = time.perf_counter() - start
    c = result.criteria
    return {"setting": setting, "problem": stem, "seed": seed,
            "Q": float(c.q[0]) * problem.output_scale, "P1": float(c.p1[0]),
            "P2": float(c.p2[0]), "stop": result.stop, "trials": int(result.trials.shape[0]),
            "seconds": seconds}


def done(path: Path) -> set[tuple[str, str, int]]:
    if not path.exists():
        return set()
    rows = [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines() if line]
    return {(r["setting"], r["problem"], r["seed"]) for r in rows}


def run(settings: list[str], stems: list[str], seeds: int, jobs: int) -> None:
    folder = HERE / "results"
    folder.mkdir(exist_ok=True)
    tasks = [(s, p, seed) for s in settings for p in stems for seed in range(seeds)
             if (s, p, seed) not in done(folder / f"{s}.jsonl")]
    print(f"{len(tasks)} runs to do", flush=True)
    with multiprocessing.Pool(jobs) as pool:
        for k, row in enumerate(pool.imap_unordered(one_run, tasks), 1):
            with (folder / f"{row['setting']}.jsonl").open("a", encoding="utf-8") as f:
                f.write(json.dumps(row) + "\n")
            print(f"[{k}/{len(tasks)}] {row['setting']} {row['problem']} seed {row['seed']}: "
                  f"Q={row['Q']:.6g} {row['stop']} {row['seconds']:.2f} s", flush=True)


def success(row: dict[str, Any], optimum: dict[str, Any]) -> bool:
    """Whether a run reached the known optimum (see the module docstring)."""
    q_star = optimum["q_star"]
    tol = optimum["accuracy"] if q_star == 0 else RELATIVE * q_star
    return row["P1"] == 0 and row["P2"] == 0 and row["Q"] <= q_star + tol


def report() -> None:
    """Write docs/synthesis_suite.md's table and docs/img/synthesis_suite.png."""
    optima = yaml.safe_load((HERE / "optima.yaml").read_text(encoding="utf-8"))["optima"]
    rows: dict[str, list[dict[str, Any]]] = defaultdict(list)
    seen = set()
    for path in sorted((HERE / "results").glob("*.jsonl")):
        for line in path.read_text(encoding="utf-8").splitlines():
            row = json.loads(line) if line else None
            key = row and (row["setting"], row["problem"], row["seed"])
            if row and row["problem"] in optima and key not in seen:
                seen.add(key)
                rows[row["setting"]].append(row)
    lines = [("| setting | runs | success | failed (problem: runs) | median s | mean s | max s "
              "| mean trials |"), "|---|---|---|---|---|---|---|---|"]
    points = []
    for name in SETTINGS:
        runs = rows.get(name)
        if not runs:
            continue
        ok = [success(r, optima[r["problem"]]) for r in runs]
        failed: dict[str, list[int]] = defaultdict(list)
        seeds = Counter(r["problem"] for r in runs)
        for r, good in zip(runs, ok):
            if not good:
                failed[r["problem"]].append(r["seed"])
        secs = sorted(r["seconds"] for r in runs)
        rate = 100.0 * sum(ok) / len(ok)
        text = ("; ".join(f"{p} ({len(s)}/{seeds[p]})" for p, s in sorted(failed.items()))
                if len(failed) <= 6 else f"{len(failed)} problems") or "—"
        lines.append(f"| {name} | {len(runs)} | {rate:.1f} % | {text} | "
                     f"{secs[len(secs) // 2]:.2f} | {sum(secs) / len(secs):.2f} | "
                     f"{secs[-1]:.2f} | {sum(r['trials'] for r in runs) / len(runs):.0f} |")
        points.append((name, rate, sum(secs) / len(secs)))
    table = "\n".join(lines) + "\n"
    (HERE / "results" / "table.md").write_text(table, encoding="utf-8")
    print(table)
    _plot(points)


def _plot(points: list[tuple[str, float, float]]) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 4.5))
    ax = fig.add_subplot()
    for name, (rate, seconds) in BEFORE.items():
        ax.plot(seconds, rate, "o", color="grey")
        ax.annotate(name, (seconds, rate), textcoords="offset points", xytext=(5, -10),
                    fontsize=8, color="grey")
    for name, rate, seconds in points:
        ax.plot(seconds, rate, "o")
        ax.annotate(name, (seconds, rate), textcoords="offset points", xytext=(5, 3),
                    fontsize=8)
    ax.axhline(99.0, color="grey", linestyle=":")
    ax.set_xscale("log")
    ax.set_xlabel("mean time per run, s (2-core machine, shared)")
    ax.set_ylabel("runs reaching the known optimum, %")
    ax.set_title("Synthesis benchmark suite: success against time")
    fig.tight_layout()
    out = ROOT / "docs" / "img" / "synthesis_suite.png"
    fig.savefig(out, dpi=110)
    print(f"written: {out}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--profile", choices=sorted(PROFILES), default="quick")
    parser.add_argument("--settings", nargs="*", default=None, choices=sorted(SETTINGS))
    parser.add_argument("--seeds", type=int, default=None)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--problems", nargs="*", default=None, help="only these (file stems)")
    parser.add_argument("--report", action="store_true", help="only write the table and plot")
    args = parser.parse_args()
    if not args.report:
        profile = PROFILES[args.profile]
        run(args.settings or list(SETTINGS), problems(args.problems or profile["problems"]),
            args.seeds or profile["seeds"], args.jobs)
    report()


if __name__ == "__main__":
    main()
