"""Speed against accuracy of the synthesis loop, and the comparison with pylinkage.

Run::

    python benchmarks/bench_synthesis.py [--out benchmarks/bench_synthesis.png] [--quick]
                                         [--no-peer]

Three parts, printed as tables and drawn in one picture:

1. the true continuous deviation against the number of control points: a four-bar is
   synthesised for a rocker law it cannot reproduce exactly, ψ*(φ) = 20°·(1 − cos φ), with
   K control points; Q is measured at the control points, the true deviation on a 3600-point
   grid (the difference shows what the control points miss);
2. best Q against the LPτ budget 2^m and against wall time, with and without refinement
   (the class-3 shipped problem);
3. the peer: pylinkage 1.3 (``pip install pylinkage==1.3.0``; not a dependency of this
   program) fits a four-bar coupler point to 20 points taken at equal crank steps from the
   coupler curve of a known crank-rocker, with its seeded differential evolution; our loop
   solves the same task (class 3) with its stop rule [Q] = the peer's RMS error.  Both
   errors are measured the same way, independently of both programs: RMS over the targets
   of the distance to the nearest point of the traced curve (closed-form coupler curve,
   200 000 points, polygon projection).  Times are compared at RMS 2e-5 (the peer's time is
   that of the first generation of its run whose best design is within 2e-5) and at the
   peer's converged error.

``--polish SEEDS`` runs instead the synthesis benchmark suite (``docs/synthesis_suite.md``)
both ways in one run, with the default settings and with the minimax polish turned off
(``polish=False``: the least-squares refinement alone), SEEDS seeds per problem, and prints
the success rate, the mean number of trials and the time of each way.
"""

from __future__ import annotations

import argparse
import copy
import importlib.util
import math
import multiprocessing
import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synthesis import SearchSettings, load_problem, problem_from_dict
from synthesis.evaluate import Evaluator
from synthesis.search import search

# The runs below are one passive pass and the refinement (shrink_passes=0, restarts=0: the
# figures quoted in docs/synthesis.md); the defaults add shrinking passes and restarts
# (docs/synthesis_suite.md).

FOURBAR_ROWS = [
    {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
    {"L": 1, "i": 2, "j": 3, "i_minus_1": 1, "j_minus_1": 0, "variant": 1},
]

# the peer task: ground pivots (0, 0), (3, 0); crank 1, coupler 3, rocker 2.5; coupler point
# 1.5 from the crank-coupler joint at 0.6 rad from the coupler line
PEER_TRUE = (1.0, 3.0, 2.5, 1.5, 0.6)
PEER_LOWER = (0.5, 2.0, 2.0, 0.5, 0.0)
PEER_UPPER = (1.5, 4.0, 3.5, 2.5, 1.2)
PEER_POINTS = 20
PEER_LEVEL = 2e-5        # the RMS error the comparison is made at


# ------------------------------------------------------------------ independent closed form

def coupler_curve(phi: np.ndarray, l1: float, li: float, lj: float, ln: float, beta: float,
                  xhj: float = 3.0) -> np.ndarray:
    """Coupler point of the four-bar with pivots (0, 0), (xhj, 0); C left of A → H_j."""
    a = l1 * np.exp(1j * phi)
    w = xhj - a
    d = np.abs(w)
    phi_i = np.angle(w) + np.arccos((li ** 2 + d ** 2 - lj ** 2) / (2 * li * d))
    point: np.ndarray = a + ln * np.exp(1j * (phi_i + beta))
    return point


def rms_to_curve(targets: np.ndarray, design: tuple[float, ...]) -> float:
    """RMS over the targets of the distance to the traced curve (no timing)."""
    curve = coupler_curve(np.linspace(0, 2 * np.pi, 200_000, endpoint=False), *design)
    seg = np.roll(curve, -1) - curve
    out = []
    for p in targets:
        rel = p - curve
        t = np.clip((np.conj(seg) * rel).real / np.abs(seg) ** 2, 0, 1)
        out.append(np.min(np.abs(rel - t * seg)))
    return float(np.sqrt(np.mean(np.square(out))))


# ------------------------------------------------------------------------------- part 1

def rocker_problem(k: int) -> dict[str, Any]:
    phi = np.arange(k) * 360.0 / k
    psi = 20.0 * (1 - np.cos(np.radians(phi)))
    return {
        "general": {"control_points": k, "groups": 2, "task_class": 1, "grid": 360},
        "structure_identification": copy.deepcopy(FOURBAR_ROWS),
        "output": {"link": 3},
        "parameters": [
            {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": [30, 15, 50], "phi_1_0": [0, -180, 180]},
            {"links": [2, 3], "x_Hi": "A", "y_Hi": "A", "x_Hj": 100, "y_Hj": [0, -60, 60],
             "l_i": [110, 60, 160], "l_j": [90, 40, 120], "l_N": 0, "beta_N": 0, "l_M": 0,
             "beta_M": 0}],
        "control_points": [{"K": n, "phi": float(phi[n]), "psi": float(psi[n])}
                           for n in range(k)],
    }


def part_control_points(budget: int) -> list[dict[str, float]]:
    rows = []
    dense = 3600
    for k in (4, 6, 8, 12, 18, 24, 36):
        problem = problem_from_dict(rocker_problem(k), f"rocker_{k}.yaml")
        evaluator = Evaluator(problem)
        result = search(evaluator, problem.lower, problem.upper, problem.initial,
                        SearchSettings(budget_log2=budget, seed=0, refine=True, shrink_passes=0, restarts=0))
        check = problem_from_dict(rocker_problem(dense), "dense.yaml")
        true = Evaluator(check, grid=dense)(result.x[None, :])
        rows.append({"K": k, "Q_deg": math.degrees(result.criteria.q[0]),
                     "true_deg": math.degrees(true.q[0]), "seconds": result.elapsed})
    return rows


# ------------------------------------------------------------------------------- part 2

def part_budget(budgets: list[int]) -> list[dict[str, float]]:
    problem = load_problem(ROOT / "input_tables" / "problems" / "class3_fourbar_path.yaml")
    evaluator = Evaluator(problem)
    rows = []
    for m in budgets:
        for refine in (False, True):
            r = search(evaluator, problem.lower, problem.upper, problem.initial,
                       SearchSettings(budget_log2=m, seed=0, refine=refine, shrink_passes=0, restarts=0))
            rows.append({"m": m, "refine": refine, "Q": float(r.criteria.q[0]),
                         "seconds": r.elapsed, "trials": int(r.trials.shape[0])})
    return rows


# ------------------------------------------------------------------------------- part 3

def peer_targets() -> np.ndarray:
    return coupler_curve(2 * np.pi * np.arange(PEER_POINTS) / PEER_POINTS, *PEER_TRUE)


def run_pylinkage(targets: np.ndarray, seed: int) -> dict[str, Any] | None:
    """pylinkage 1.3: its four-bar with a fixed coupler point, its differential evolution."""
    try:
        # (an optional peer, not a dependency: no type information)
        import pylinkage as pl  # type: ignore[import-not-found, unused-ignore]
        from pylinkage.optimization import (  # type: ignore[import-not-found, unused-ignore]
            differential_evolution_optimization,
        )
        from pylinkage.optimization.utils import (  # type: ignore[import-not-found, unused-ignore]
            kinematic_minimization,
        )
    except ImportError:
        return None

    o1 = pl.Ground(0.0, 0.0, name="O1")
    o2 = pl.Ground(3.0, 0.0, name="O2")
    crank = pl.Crank(anchor=o1, radius=1.0)          # 360 steps per turn (its default)
    joint = pl.RRRDyad(crank.output, o2, distance1=3.0, distance2=2.5, name="B")
    point = pl.FixedDyad(crank.output, joint, distance=1.5, angle=0.6, name="P")
    linkage = pl.Linkage([o1, o2, crank, joint, point], name="four-bar")

    def polygon_rms(path: np.ndarray) -> float:
        seg = np.roll(path, -1) - path
        rel = targets[:, None] - path[None, :]
        t = np.clip((np.conj(seg)[None, :] * rel).real / np.abs(seg)[None, :] ** 2, 0, 1)
        return float(np.sqrt(np.mean(np.min(np.abs(rel - t * seg[None, :]), axis=1) ** 2)))

    @kinematic_minimization  # type: ignore[untyped-decorator, unused-ignore]
    def fitness(loci: Any, **_: Any) -> float:
        return polygon_rms(np.array([complex(*frame[-1]) for frame in loci]))

    log: list[tuple[float, float, np.ndarray]] = []

    def progress(intermediate_result: Any) -> None:
        log.append((time.perf_counter() - start, float(intermediate_result.fun),
                    np.array(intermediate_result.x)))

    start = time.perf_counter()
    ensemble = differential_evolution_optimization(
        fitness, linkage, bounds=(list(PEER_LOWER), list(PEER_UPPER)), order_relation=min,
        seed=seed, verbose=False, callback=progress)
    seconds = time.perf_counter() - start
    design = tuple(float(v) for v in ensemble[0].dimensions)
    # the first generation whose best design is within PEER_LEVEL (independent measure)
    level_time, level_rms = math.nan, math.nan
    for elapsed, score, x in log:
        if score <= 2 * PEER_LEVEL:
            rms = rms_to_curve(targets, tuple(x))
            if rms <= PEER_LEVEL:
                level_time, level_rms = elapsed, rms
                break
    return {"seconds": seconds, "design": design, "rms": rms_to_curve(targets, design),
            "generations": len(log), "level_seconds": level_time, "level_rms": level_rms,
            "trace": [(elapsed, score) for elapsed, score, _ in log]}


def peer_problem(targets: np.ndarray, accuracy: float) -> dict[str, Any]:
    lo, hi = PEER_LOWER, PEER_UPPER
    mid = [(a + b) / 2 for a, b in zip(lo, hi)]
    return {
        "general": {"control_points": PEER_POINTS, "groups": 2, "task_class": 3, "grid": 360,
                    "accuracy": accuracy},
        "structure_identification": copy.deepcopy(FOURBAR_ROWS),
        "output": {"link": 2, "point": "N"},
        "parameters": [
            {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": [mid[0], lo[0], hi[0]], "phi_1_0": 0},
            {"links": [2, 3], "x_Hi": "A", "y_Hi": "A", "x_Hj": 3, "y_Hj": 0,
             "l_i": [mid[1], lo[1], hi[1]], "l_j": [mid[2], lo[2], hi[2]],
             "l_N": [mid[3], lo[3], hi[3]],
             "beta_N": [math.degrees(mid[4]), math.degrees(lo[4]), math.degrees(hi[4])],
             "l_M": 0, "beta_M": 0}],
        "control_points": [{"K": k, "x": float(p.real), "y": float(p.imag)}
                           for k, p in enumerate(targets)],
    }


def run_ours(targets: np.ndarray, accuracy: float, seed: int) -> dict[str, Any]:
    start = time.perf_counter()
    problem = problem_from_dict(peer_problem(targets, accuracy), "peer.yaml")
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial,
                    SearchSettings(budget_log2=8, seed=seed, refine=True,
                                   q_required=accuracy, shrink_passes=0, restarts=0))
    seconds = time.perf_counter() - start
    x = result.x
    design = (x[0], x[1], x[2], x[3], math.radians(x[4]))
    return {"seconds": seconds, "design": tuple(float(v) for v in design),
            "rms": rms_to_curve(targets, design), "trials": int(result.trials.shape[0])}


# ------------------------------------------------------------ the second local optimiser

def _suite_runner() -> Any:
    """``benchmarks/synthesis_suite/run.py`` as a module (its problems and success rule)."""
    spec = importlib.util.spec_from_file_location(
        "synthesis_suite_run", ROOT / "benchmarks" / "synthesis_suite" / "run.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _suite_run(task: tuple[str, int, bool]) -> dict[str, Any]:
    """One problem of the suite, one seed, the default settings with or without the polish."""
    stem, seed, polish = task
    problem = load_problem(ROOT / "benchmarks" / "synthesis_suite" / "problems" / f"{stem}.yaml")
    settings = replace(problem.settings, seed=seed, polish=polish)
    start = time.perf_counter()
    result = search(Evaluator(problem), problem.lower, problem.upper, problem.initial, settings)
    c = result.criteria
    return {"problem": stem, "seed": seed, "polish": polish,
            "Q": float(c.q[0]) * problem.output_scale, "P1": float(c.p1[0]),
            "P2": float(c.p2[0]), "trials": int(result.trials.shape[0]),
            "seconds": time.perf_counter() - start}


def part_polish(seeds: int, jobs: int) -> list[dict[str, Any]]:
    """The suite with and without the minimax polish, interleaved (same load on both)."""
    suite = _suite_runner()
    optima = suite.yaml.safe_load((ROOT / "benchmarks" / "synthesis_suite" / "optima.yaml")
                                  .read_text(encoding="utf-8"))["optima"]
    tasks = [(stem, seed, polish) for stem in suite.problems(None) for seed in range(seeds)
             for polish in (True, False)]
    with multiprocessing.Pool(jobs) as pool:
        rows = pool.map(_suite_run, tasks)
    for row in rows:
        row["success"] = bool(suite.success(row, optima[row["problem"]]))
    print(f"{'polish':>7} {'runs':>5} {'success':>8} {'mean trials':>12} {'mean s':>8} "
          f"{'median s':>9}  failed (problem: seeds)")
    for polish in (True, False):
        runs = [r for r in rows if r["polish"] == polish]
        secs = sorted(r["seconds"] for r in runs)
        failed: dict[str, list[int]] = {}
        for r in runs:
            if not r["success"]:
                failed.setdefault(r["problem"], []).append(r["seed"])
        print(f"{('yes' if polish else 'no'):>7} {len(runs):>5} "
              f"{100.0 * sum(r['success'] for r in runs) / len(runs):>7.1f}% "
              f"{sum(r['trials'] for r in runs) / len(runs):>12.0f} "
              f"{sum(secs) / len(secs):>8.2f} {secs[len(secs) // 2]:>9.2f}  "
              + ("; ".join(f"{p}: {s}" for p, s in failed.items()) or "—"))
    return rows


# ----------------------------------------------------------------------------- report

def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "bench_synthesis.png"))
    parser.add_argument("--quick", action="store_true", help="smaller budgets")
    parser.add_argument("--no-peer", action="store_true", help="skip the pylinkage run")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--polish", type=int, metavar="SEEDS", default=None,
                        help="the suite with and without the minimax polish, SEEDS seeds")
    parser.add_argument("--jobs", type=int, default=1, help="processes for --polish")
    args = parser.parse_args(argv)
    if args.polish is not None:
        part_polish(args.polish, args.jobs)
        return 0

    budget = 8 if args.quick else 10
    print(f"1. Control points against the true continuous deviation "
          f"(rocker law 20°·(1 − cos φ), four-bar, 2^{budget} LPτ + refinement)")
    part1 = part_control_points(budget)
    print(f"{'K':>4} {'Q at the points, deg':>22} {'true deviation, deg':>21} {'s':>7}")
    for r in part1:
        print(f"{r['K']:>4} {r['Q_deg']:>22.5f} {r['true_deg']:>21.5f} {r['seconds']:>7.2f}")

    print("\n2. Best Q against the LPτ budget (class-3 shipped problem)")
    budgets = [6, 8, 10] if args.quick else [6, 8, 10, 12, 14]
    part2 = part_budget(budgets)
    print(f"{'2^m':>6} {'refine':>7} {'best Q, mm':>14} {'trials':>8} {'s':>8}")
    for r in part2:
        print(f"{2 ** r['m']:>6} {('yes' if r['refine'] else 'no'):>7} {r['Q']:>14.4e} "
              f"{r['trials']:>8} {r['seconds']:>8.3f}")

    part3 = None
    if not args.no_peer:
        print("\n3. Against pylinkage 1.3 (four-bar coupler point, 20 points, path without "
              "timing)")
        targets = peer_targets()
        peer = run_pylinkage(targets, args.seed)
        if peer is None:
            print("   pylinkage is not installed: pip install pylinkage==1.3.0")
        else:
            ours = run_ours(targets, PEER_LEVEL, args.seed)
            floor = max(peer["rms"], 1e-13)       # below ~1e-13 rounding decides, not design
            final = run_ours(targets, floor, args.seed)
            part3 = (peer, ours, final)
            print(f"{'program':<40} {'RMS error':>12} {'seconds':>10}")
            print(f"{'pylinkage 1.3 DE, first within 2e-5':<40} {peer['level_rms']:>12.3e} "
                  f"{peer['level_seconds']:>10.2f}")
            print(f"{'assur synthesize, [Q] = 2e-5':<40} {ours['rms']:>12.3e} "
                  f"{ours['seconds']:>10.2f}")
            print(f"{'pylinkage 1.3 DE, converged':<40} {peer['rms']:>12.3e} "
                  f"{peer['seconds']:>10.2f}   ({peer['generations']} generations)")
            print(f"{f'assur synthesize, [Q] = {floor:.0e}':<40} {final['rms']:>12.3e} "
                  f"{final['seconds']:>10.2f}")
            print(f"speed ratio at RMS 2e-5: {peer['level_seconds'] / ours['seconds']:.0f}x; "
                  f"to convergence: {peer['seconds'] / final['seconds']:.0f}x")

    _plot(args.out, part1, part2, part3)
    print(f"\npicture: {args.out}")
    return 0


def _plot(path: str, part1: list[dict[str, float]], part2: list[dict[str, float]],
          part3: tuple[dict[str, Any], ...] | None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 4, figsize=(20, 4.5))
    ax = axes[0]
    ax.plot([r["K"] for r in part1], [r["Q_deg"] for r in part1], "o-", label="Q at the points")
    ax.plot([r["K"] for r in part1], [r["true_deg"] for r in part1], "s-",
            label="true deviation")
    ax.set_xlabel("control points K")
    ax.set_ylabel("deviation, deg")
    ax.set_title("control points (class 1)")
    ax.legend()
    for refine, style in ((False, "o-"), (True, "s-")):
        rows = [r for r in part2 if r["refine"] == refine]
        label = "with refinement" if refine else "LPτ only"
        axes[1].loglog([2 ** r["m"] for r in rows], [max(r["Q"], 1e-12) for r in rows], style,
                       label=label)
        axes[2].loglog([r["seconds"] for r in rows], [max(r["Q"], 1e-12) for r in rows], style,
                       label=label)
    axes[1].set_xlabel("LPτ budget 2^m")
    axes[2].set_xlabel("wall time, s")
    for ax in axes[1:3]:
        ax.set_ylabel("best Q, mm")
        ax.set_title("class-3 shipped problem")
        ax.legend()
    ax = axes[3]
    if part3 is not None:
        peer, ours, final = part3
        trace = np.array(peer["trace"])
        ax.loglog(trace[:, 0], np.maximum(trace[:, 1], 1e-17), "k-",
                  label="pylinkage 1.3 DE (best per generation)")
        ax.loglog([ours["seconds"], final["seconds"]], [ours["rms"], final["rms"]], "r*",
                  markersize=12, label="assur synthesize")
        ax.axhline(PEER_LEVEL, color="grey", linestyle=":")
        ax.legend()
    ax.set_xlabel("wall time, s")
    ax.set_ylabel("RMS distance to the path")
    ax.set_title("peer task: four-bar coupler point, 20 points")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
