"""Four-bar for a prescribed velocity ratio: speed against accuracy of the two solvers, their
behaviour at the extremes, and the same task given to the general synthesis search (B3–B4).

Correct digits are measured against a reference solve: every root of the modern solver
polished by Newton's method in extended precision (``np.longdouble``, the conditions
evaluated in that precision, the step solved from a central-difference Jacobian); a
reference is used only when its residual is below 1e-16.  In the extremes table the zone ψ′
of each request is placed inside the range the grid scan reports as attainable
(:func:`attainable_zone`), at 30 % of it, so that the rows probe the solvers rather than
the existence of a design; for δ → 0 the zone of the example (20° at δ = 0.05) is scaled by
√(δ/0.05), the width of a smooth peak at depth δ.

The last table runs the shipped problem table
``input_tables/problems/class1_fourbar_velocity_ratio.yaml`` (task class 1 with the velocity
ratio as the output) through the public loop — :func:`synthesis.problem.load_problem`,
:class:`~synthesis.evaluate.Evaluator`, :func:`synthesis.search.search` with the table's own
search settings and several seeds — beside the modern solver.

Run ``python benchmarks/bench_fourbar_velocity_ratio.py`` (``--quick`` for a shorter run).
The tables are quoted in ``docs/case_fourbar_velocity_ratio.md``.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from synthesis import SearchSettings, load_problem
from synthesis.cases.fourbar_velocity_ratio.check import check_design
from synthesis.cases.fourbar_velocity_ratio.conditions import (
    NoSolution,
    Request,
    condition_residuals,
    design_defect,
    design_from_unknowns,
    form_residuals,
)
from synthesis.cases.fourbar_velocity_ratio.kinematics import coupler_bounds, grashof_margin
from synthesis.cases.fourbar_velocity_ratio.modern_solver import attainable_zone, solve_modern
from synthesis.cases.fourbar_velocity_ratio.paper_solver import solve_paper
from synthesis.cases.fourbar_velocity_ratio.study import paper_check_tolerance
from synthesis.criteria import Criteria
from synthesis.evaluate import Evaluator
from synthesis.search import search
from synthesis.search_settings import settings_for

DEG = math.pi / 180.0
EXAMPLE = Request(n_star=0.5, psi1=20 * DEG, e=0.3, delta=0.05)
PROBLEM = (Path(__file__).resolve().parents[1] / "input_tables" / "problems"
           / "class1_fourbar_velocity_ratio.yaml")
FRAME_MM = 100.0   # the problem table's frame S


def extended_root(request: Request, x: np.ndarray) -> np.ndarray | None:
    """Newton polish of a root in extended precision; None if the residual stays > 1e-17."""
    x = np.asarray(x, dtype=np.longdouble)
    for _ in range(8):
        f = form_residuals(request, x)
        jacobian = np.empty((len(x), len(x)))
        for k in range(len(x)):
            h = np.longdouble(1e-7) * max(np.longdouble(1), abs(x[k]))
            step = np.zeros(len(x), dtype=np.longdouble)
            step[k] = h
            jacobian[:, k] = ((form_residuals(request, x + step) - form_residuals(request, x - step))
                              / (2 * h)).astype(float)
        dx = np.linalg.solve(jacobian, f.astype(float))
        x = x - dx.astype(np.longdouble)
        if np.max(np.abs(form_residuals(request, x))) < 1e-18:
            break
    return x if np.max(np.abs(form_residuals(request, x))) < 1e-16 else None


def unknowns(design) -> np.ndarray:
    return np.array([design.c, design.r, design.theta2 % (2 * math.pi)])


def digits(x: np.ndarray, references: list[np.ndarray]) -> tuple[float, int]:
    """Correct significant digits of x against the nearest reference, and its index."""
    errors = [float(np.max(np.abs(np.asarray(x, dtype=np.longdouble) - ref)
                           / np.maximum(1, np.abs(ref)))) for ref in references]
    k = int(np.argmin(errors))
    return min(18.0, -math.log10(max(errors[k], 1e-18))), k


def references(request: Request) -> list[np.ndarray]:
    result = solve_modern(request)
    return [ref for ref in (extended_root(request, unknowns(d)) for d in result.designs)
            if ref is not None]


def timed(function, *args, repeat: int = 1, **kwargs):
    best, out = math.inf, None
    for _ in range(repeat):
        start = time.perf_counter()
        out = function(*args, **kwargs)
        best = min(best, time.perf_counter() - start)
    return out, best


def table_accuracy(repeat: int) -> None:
    refs = references(EXAMPLE)
    print(f"\n### Speed against accuracy: e = 0.3, n* = 0.5, δ = 0.05, ψ′ = 20° "
          f"({len(refs)} reference roots)\n")
    print("| solver | tolerance | time, s | evaluations | designs | correct digits (worst) |")
    print("|---|---|---|---|---|---|")
    for xtol in (1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13):
        result, seconds = timed(solve_modern, EXAMPLE, xtol=xtol, repeat=repeat)
        worst = min((digits(unknowns(d), refs)[0] for d in result.designs), default=math.nan)
        print(f"| modern | xtol {xtol:.0e} | {seconds:.3f} | {result.evaluations} | "
              f"{len(result.designs)} | {worst:.1f} |")
    for tol in (1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
        result, seconds = timed(solve_paper, EXAMPLE, tol=tol, repeat=repeat)
        if result.design is None:
            print(f"| paper | tol {tol:.0e} | {seconds:.3f} | {result.evaluations} | 0 | "
                  f"stopped: {result.reason} |")
            continue
        got, which = digits(unknowns(result.design), refs)
        note = f" (wrong root: {result.defect})" if result.defect else ""
        print(f"| paper | tol {tol:.0e} | {seconds:.3f} | {result.evaluations} | 1 (root "
              f"r = {float(refs[which][1]):.4f}) | {got:.1f}{note} |")


def _inside(e: float, n_star: float, delta: float) -> Request:
    """A paper-form request with ψ′ at 30 % of the attainable range (20° if none)."""
    probe = Request(n_star=n_star, psi1=20 * DEG, e=e, delta=delta)
    try:
        zone = attainable_zone(probe)
    except NoSolution:
        return probe
    psi = 20 * DEG if zone is None else zone[0] + 0.3 * (zone[1] - zone[0])
    return Request(n_star=n_star, psi1=psi, e=e, delta=delta)


def extremes() -> list[tuple[str, Request]]:
    rows = [(f"Grashof limit: e = {e}", _inside(e, 0.8, 0.05)) for e in (0.6, 0.8, 0.9, 0.95)]
    rows.append(("Grashof limit: root at margin 5e-4",
                 Request(n_star=0.55, psi1=14 * DEG, e=0.4, delta=0.03)))
    rows += [(f"n* → 1: n* = {n}", _inside(0.3, n, 0.05)) for n in (0.7, 0.9, 0.97, 0.99)]
    rows += [(f"δ → 0: δ = {delta:g}, ψ′ = 20°·√(δ/0.05)",
              Request(n_star=0.5, psi1=20 * DEG * math.sqrt(delta / 0.05), e=0.3, delta=delta))
             for delta in (1e-2, 1e-3, 1e-4, 1e-6)]
    rows += [(f"small e: e = {e}", _inside(e, 0.5, 0.05)) for e in (0.1, 0.03, 0.01, 0.001)]
    rows.append(("return stroke: n* = −1.2", _inside(0.3, -1.2, 0.05)))
    return rows


def table_extremes() -> None:
    print("\n### Extremes (paper's form; tolerance: modern xtol 1e-13, paper tol 1e-6)\n")
    print("| request | ψ′ | modern: designs, worst digits, check, s | least Grashof margin | "
          "paper: outcome | paper digits | paper s | paper, θ2 started 10° from the peak |")
    print("|---|---|---|---|---|---|---|---|")
    for label, request in extremes():
        try:
            modern, m_seconds = timed(solve_modern, request)
        except NoSolution as exc:
            print(f"| {label} | refused: {exc} | | | | | | |")
            continue
        refs = [ref for ref in (extended_root(request, unknowns(d)) for d in modern.designs)
                if ref is not None]
        if modern.designs:
            worst = (f"{min(digits(unknowns(d), refs)[0] for d in modern.designs):.1f}" if refs
                     else "no reference")
            checks = all(check_design(d).passed for d in modern.designs)
            margin = min(float(grashof_margin(d.e, d.c, d.r)) for d in modern.designs)
            m_text = (f"{len(modern.designs)}, {worst}, "
                      f"{'passed' if checks else 'FAILED'}, {m_seconds:.2f}")
            m_margin = f"{margin:.1e}"
        else:
            m_text, m_margin = f"none ({modern.reason}), {m_seconds:.2f}", ""
        paper, p_seconds = timed(solve_paper, request)
        outcome, p_digits = _paper_outcome(paper, refs)
        if modern.designs:
            start = modern.designs[0].theta2 - 10 * DEG
            near, _ = _paper_outcome(solve_paper(request, theta_start=start), refs)
        else:
            near = ""
        print(f"| {label} | {math.degrees(request.psi1):.3g}° | {m_text} | {m_margin} | {outcome} | "
              f"{p_digits} | {p_seconds:.2f} | {near} |")


def _paper_outcome(paper, refs: list[np.ndarray]) -> tuple[str, str]:
    """How a run of the paper's scheme ended, and its correct digits."""
    if paper.design is None:
        return f"fails: {paper.reason}", ""
    if paper.defect:
        return f"WRONG ROOT: {paper.defect}", ""
    tolerance = paper_check_tolerance(1e-6, paper.design.delta)
    check = check_design(paper.design, value_tol=tolerance, angle_tol=tolerance)
    outcome = "root, check " + ("passed" if check.passed else "FAILED")
    return outcome, (f"{digits(unknowns(paper.design), refs)[0]:.1f}" if refs
                     else "no reference")


def ratio_evaluator(request: Request):
    """B2 for the search: the ratio conditions of the paper's form as deviations Δ_K.

    Designs are rows (t, r, θ2) with c = c_lo + t·(c_hi − c_lo), so that the box of the
    search is the crank-rocker domain; P1 is the distance outside it.
    """
    def evaluate(x: np.ndarray) -> Criteria:
        t, r, theta2 = x[:, 0], x[:, 1], x[:, 2]
        lo, hi = coupler_bounds(request.e, r)
        c = lo + t * (hi - lo)
        outside = np.maximum(0.0, lo - hi) + np.maximum(0.0, -grashof_margin(request.e, c, r))
        with np.errstate(invalid="ignore"):
            residual = form_residuals(request, np.stack([c, r, theta2])).T
        p1 = np.where(np.all(np.isfinite(residual), axis=1), outside, 1.0 + outside)
        dev = np.where(p1[:, None] > 0, np.nan, np.abs(residual))
        q = np.where(p1 > 0, np.nan, np.max(np.abs(residual), axis=1))
        return Criteria(p1, np.where(p1 > 0, np.nan, 0.0), q, dev,
                        np.where(p1[:, None] > 0, np.nan, residual))
    return evaluate


def table_search() -> None:
    refs = references(EXAMPLE)
    print("\n### The same task for the general search (LPτ + least-squares refinement)\n")
    print("| method | trials (designs evaluated) | time, s | max condition residual | "
          "correct digits | nearest root r | check |")
    print("|---|---|---|---|---|---|---|")
    r_min = EXAMPLE.e / EXAMPLE.n_star
    lower, upper = [0.0, r_min, 0.0], [1.0, 6 * r_min, 2 * math.pi]
    for budget in (10, 14):
        settings = SearchSettings(budget_log2=budget, seed=0, refine=True, refine_starts=3,
                                  refine_evaluations=400)
        result, seconds = timed(search, ratio_evaluator(EXAMPLE), lower, upper,
                                [0.5, 2 * r_min, math.pi / 2], settings)
        t, r, theta2 = result.x
        lo, hi = coupler_bounds(EXAMPLE.e, r)
        x = np.array([lo + t * (hi - lo), r, theta2 % (2 * math.pi)])
        got, which = digits(x, refs)
        design = design_from_unknowns(EXAMPLE, x)
        ok = design_defect(design, accuracy=1e-6) is None and check_design(
            design, value_tol=1e-6, angle_tol=1e-6).passed
        print(f"| search 2^{budget} + refine | {len(result.trials)} | {seconds:.2f} | "
              f"{float(result.criteria.q[0]):.1e} | {got:.1f} | {float(refs[which][1]):.4f} | "
              f"{'passed' if ok else 'failed'} |")
    modern, seconds = timed(solve_modern, EXAMPLE)
    print(f"| modern solver (all roots) | {modern.evaluations} | {seconds:.2f} | "
          f"{max(float(np.max(np.abs(form_residuals(EXAMPLE, unknowns(d))))) for d in modern.designs):.1e}"
          f" | {min(digits(unknowns(d), refs)[0] for d in modern.designs):.1f} | all "
          f"{len(modern.designs)} | passed |")
    paper, seconds = timed(solve_paper, EXAMPLE)
    print(f"| paper's scheme (tol 1e-6) | {paper.evaluations} | {seconds:.2f} | "
          f"{float(np.max(np.abs(form_residuals(EXAMPLE, unknowns(paper.design))))):.1e} | "
          f"{digits(unknowns(paper.design), refs)[0]:.1f} | {paper.design.r:.4f} | "
          f"{'passed' if paper.ok else 'failed'} |")


def _verdict(design) -> str:
    check = check_design(design)
    if check.passed:
        return "passed"
    return "failed: " + ", ".join(code for code, _ in check.failures)


def _residuals(design) -> str:
    """The three conditions of the paper's form, as table cells."""
    values = condition_residuals(design)
    return " | ".join(f"{values[key]:.1e}" for key in ("n(θ2) − n*", "dn/dθ(θ2)",
                                                        "n(θ1) − n_end"))


def table_problem(seeds: range) -> None:
    """The shipped problem table (class 1, output: ratio) through B1–B4, beside the modern
    solver: design, residuals of the paper's conditions, the check, time and designs."""
    refs = references(EXAMPLE)
    print("\n### The same task as a class-1 problem table "
          "(`input_tables/problems/class1_fourbar_velocity_ratio.yaml`)\n")
    print("| method | c | r | θ2, ° | ψ″, ° | Q | n(θ2) − n* | dn/dθ(θ2) | n(θ1) − n_end | "
          "correct digits | check | time, s | designs evaluated |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    problem = load_problem(PROBLEM)
    for seed in seeds:
        evaluator = Evaluator(problem)
        result, seconds = timed(search, evaluator, problem.lower, problem.upper,
                                problem.initial, settings_for(problem, seed=seed))
        theta2, c, r = result.x
        x = np.array([c / FRAME_MM, r / FRAME_MM, math.radians(theta2) % (2 * math.pi)])
        design = design_from_unknowns(EXAMPLE, x)
        got, _ = digits(x, refs)
        crit = result.criteria
        state = "" if crit.p1[0] == 0 and crit.p2[0] == 0 else f" (P1 = {crit.p1[0]:.3g}, " \
                                                              f"P2 = {crit.p2[0]:.3g})"
        print(f"| problem table, seed {seed}{state} | {x[0]:.9f} | {x[1]:.9f} | "
              f"{theta2 % 360:.6f} | {math.degrees(design.psi2):.4f} | {crit.q[0]:.1e} | "
              f"{_residuals(design)} | {got:.1f} | {_verdict(design)} | {seconds:.2f} | "
              f"{len(result.trials)} |")
    modern, seconds = timed(solve_modern, EXAMPLE)
    for k, d in enumerate(modern.designs):
        x = unknowns(d)
        cost = f"{seconds:.2f} | {modern.evaluations}" if k == 0 else "(same run) | "
        print(f"| modern solver, design {k + 1} | {d.c:.9f} | {d.r:.9f} | "
              f"{math.degrees(d.theta2) % 360:.6f} | {math.degrees(d.psi2):.4f} | | "
              f"{_residuals(d)} | {digits(x, refs)[0]:.1f} | {_verdict(d)} | {cost} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the extremes table")
    args = parser.parse_args()
    table_accuracy(repeat=1 if args.quick else 3)
    if not args.quick:
        table_extremes()
    table_search()
    table_problem(range(2) if args.quick else range(6))


if __name__ == "__main__":
    main()
