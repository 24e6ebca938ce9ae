"""Higher groups at the speed of dyads: the figures of the README's benchmark table, in one run.

Figures (one core; positions per second unless marked):

* the whole analysis of ``input_tables/four_bar.yaml`` (``analyse``: every joint, link frame
  and tracing point with the groups' existence) at N = 360 and 3,600;
* four-bar, crank + RRR dyad through ``solve_input`` + ``solve_rrr`` (existence margin, mask
  and reasons included), beside the minimal hand-written numpy closed form of
  ``bench_fourbar.py``, at N = 360 and N = 3,600, both handing back C and both link angles
  (their ratio measured in the same process, the variants interleaved);
* RRR triad (``input_tables/eight_bar_triad.yaml``, the whole mechanism) analysed over 360
  crank angles for one design and for D designs at once (the triad's hinges jittered by up
  to ±0.5 mm, shape (D, 1));
* class IV group (``input_tables/class_iv_group.yaml``), the same;
* the force analysis of the six-bar with a triad (``six_bar_triad_forces.yaml``) over
  N = 360 and 3,600 positions against its kinematics with analogs (time ratio);
* the synthesis of ``input_tables/problems/class2_six_bar_triad.yaml`` at its default budget
  and seed (seconds of the first ``synthesize`` call in the process, after its import, and
  of a second call; its Q and design are printed beside), and at the budget 2¹⁰ in a
  process of its own (first call and second: a search that large loads the compiled
  corrector before its first batch, and the first call pays for the loading).

``--before TREE`` runs the same measurements with the program of another checkout (e.g. the
main branch) in a separate process, alternating with this checkout's, and prints both columns
and the speed-up after/before of every figure; the script itself is the same in both runs.

Run: ``python benchmarks/bench_speed_table.py [--designs D] [--rounds R] [--before OTHER_CHECKOUT]``;
``--json`` prints the figures of this checkout as one JSON object.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

from bench_higher import rate

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: no threaded BLAS anywhere

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
TABLES = ROOT / "input_tables"

#: Figure name → (label in the table, unit, whether a larger value is better).
FIGURES: dict[str, tuple[str, str, bool]] = {
    "fourbar_360": ("four-bar (solvers), N = 360", "pos/s", True),
    "hand_360": ("hand-written numpy four-bar, N = 360", "pos/s", True),
    "fourbar_ratio_360": ("  four-bar / hand-written, N = 360", "ratio", True),
    "fourbar_3600": ("four-bar (solvers), N = 3,600", "pos/s", True),
    "hand_3600": ("hand-written numpy four-bar, N = 3,600", "pos/s", True),
    "fourbar_ratio_3600": ("  four-bar / hand-written, N = 3,600", "ratio", True),
    "analysis_360": ("analyse(four_bar.yaml), N = 360", "pos/s", True),
    "analysis_3600": ("analyse(four_bar.yaml), N = 3,600", "pos/s", True),
    "triad_1": ("RRR triad, 1 x 360", "pos/s", True),
    "triad_many": ("RRR triad, D x 360", "pos/s", True),
    "class_iv_1": ("class IV group, 1 x 360", "pos/s", True),
    "class_iv_many": ("class IV group, D x 360", "pos/s", True),
    "forces_360": ("triad forces (six_bar_triad_forces.yaml), N = 360", "ms", False),
    "forces_3600": ("triad forces, N = 3,600", "ms", False),
    "forces_ratio_360": ("triad forces / kinematics with analogs, N = 360", "ratio", False),
    "forces_ratio_3600": ("triad forces / kinematics with analogs, N = 3,600", "ratio", False),
    "synthesis": ("synthesis of class2_six_bar_triad", "s", False),
    "synthesis_again": ("  the same, called again in the process", "s", False),
    "synthesis_large": ("synthesis of class2_six_bar_triad, budget 2^10", "s", False),
    "synthesis_large_again": ("  the same, called again in the process", "s", False),
}

#: The budget (log2 of the trials of a round) of the larger synthesis.
LARGE_BUDGET = 10


def best_rate(run: Callable[[], object], positions: int, seconds: float, rounds: int) -> float:
    """The best positions per second of ``run`` over ``rounds`` batches of at least
    ``seconds`` each, after one untimed call (:func:`bench_higher.rate`)."""
    return rate(run, positions, rounds, seconds)[1]


def fourbar(rounds: int) -> dict[str, float]:
    """The four-bar through the solvers and by hand, interleaved, at N = 360 and 3,600."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_fourbar import handwritten, ours

    out: dict[str, float] = {}
    for n in (360, 3600):
        phi = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
        ours_best, hand_best = 0.0, 0.0
        for _ in range(8 * rounds):  # short batches, interleaved: both see the same load
            ours_best = max(ours_best, best_rate(partial(ours, phi), n, 0.05, 1))
            hand_best = max(hand_best, best_rate(partial(handwritten, phi), n, 0.05, 1))
        out[f"fourbar_{n}"], out[f"hand_{n}"] = ours_best, hand_best
        out[f"fourbar_ratio_{n}"] = ours_best / hand_best
    return out


def analysis(rounds: int) -> dict[str, float]:
    """The whole analysis of the four-bar table (every joint, frame and tracing point)."""
    import assur
    from assur.kinematics.analysis import analyse

    model = assur.load_model(TABLES / "four_bar.yaml")
    return {f"analysis_{n}": best_rate(partial(analyse, model, assur.input_grid(model, n)), n,
                                       0.1, 4 * rounds) for n in (360, 3600)}


def higher(table: str, key: str, designs: int, rounds: int) -> dict[str, float]:
    """One design and ``designs`` designs of a mechanism with a higher group over 360 angles."""
    import assur
    from assur.kinematics.analysis import analyse

    model = assur.load_model(TABLES / table)
    label = next(group.label for group in model.groups if group.layout is not None)
    rng = np.random.default_rng(26)
    batch = model.with_params({
        name: value + rng.uniform(-0.5, 0.5, (designs, 1))
        for name, value in model.params.items()
        if name.startswith(f"{label}.") and name.split(".")[-1][:2] in ("x_", "y_")})
    q = assur.input_grid(model, 360)
    return {f"{key}_1": best_rate(lambda: analyse(model, q), 360, 0.5, rounds),
            f"{key}_many": best_rate(lambda: analyse(batch, q), 360 * designs, 0.0, 1)}


def forces(rounds: int) -> dict[str, float]:
    """Time of the force analysis (ms) and over that of the kinematics with analogs, of the
    six-bar with a triad."""
    from assur.forces import kinetostatics
    from assur.kinematics.analysis import analyse
    from assur.kinematics.build import load_with_forces

    model, data = load_with_forces(TABLES / "six_bar_triad_forces.yaml")
    assert data is not None
    out = {}
    for n in (360, 3600):
        q = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
        motion = analyse(model, q, analogs=True)
        kinematics = 1.0 / best_rate(partial(analyse, model, q, analogs=True), 1, 0.2, rounds)
        force = 1.0 / best_rate(partial(kinetostatics, motion, data, 10.0), 1, 0.2, rounds)
        out[f"forces_{n}"] = 1e3 * force
        out[f"forces_ratio_{n}"] = force / kinematics
    return out


def synthesis_large() -> dict[str, float]:
    """Seconds of the synthesis of the triad problem at the budget ``LARGE_BUDGET``, the
    first call and the next, in a new process (nothing loaded by the other figures)."""
    code = ("import json, sys, time\n"
            "import synthesis as syn\n"
            "problem = syn.load_problem(sys.argv[1])\n"
            "synthesize = syn.synthesize\n"
            "seconds = []\n"
            "for _ in range(2):\n"
            "    start = time.perf_counter()\n"
            "    synthesize(problem, budget=int(sys.argv[2]))\n"
            "    seconds.append(time.perf_counter() - start)\n"
            "print(json.dumps(seconds))\n")
    proc = subprocess.run([sys.executable, "-c", code,
                           str(TABLES / "problems" / "class2_six_bar_triad.yaml"),
                           str(LARGE_BUDGET)], capture_output=True, text=True, check=True)
    first, again = json.loads(proc.stdout.strip().splitlines()[-1])
    return {"synthesis_large": first, "synthesis_large_again": again}


def synthesis() -> tuple[dict[str, float], str]:
    """Seconds of the synthesis of the triad problem at its defaults, the first call in the
    process and the next; its Q and design. ``synthesize`` is looked up before the clock
    starts: the lookup imports the search and with it scipy's optimizers and quasi-random
    sequences (about 0.7 s, a cost of starting the program that ``bench_startup.py``
    measures), which an earlier version of this script counted in the figure."""
    import synthesis as syn

    problem = syn.load_problem(TABLES / "problems" / "class2_six_bar_triad.yaml")
    synthesize = syn.synthesize
    seconds = []
    for _ in range(2):
        start = time.perf_counter()
        result = synthesize(problem)
        seconds.append(time.perf_counter() - start)
    design = ", ".join(f"{name.split('.')[-1]} = {value:.12g}"
                       for name, value in result.design.items())
    return ({"synthesis": seconds[0], "synthesis_again": seconds[1]},
            f"Q = {result.q:.6g} mm; {design}")


def measure(designs: int, rounds: int) -> tuple[dict[str, float], str]:
    """Every figure of this checkout, and the synthesis result's note."""
    figures = fourbar(rounds) | analysis(rounds)
    figures |= higher("eight_bar_triad.yaml", "triad", designs, rounds)
    figures |= higher("class_iv_group.yaml", "class_iv", designs, rounds)
    figures |= forces(rounds)
    found, note = synthesis()
    return figures | found | synthesis_large(), note


def run_tree(tree: Path, designs: int, rounds: int) -> tuple[dict[str, float], str]:
    """The figures of the program of ``tree``, measured by this script in a new process."""
    env = dict(os.environ, PYTHONPATH=str(tree), MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, __file__, "--json", "--designs", str(designs),
                           "--rounds", str(rounds)], env=env, capture_output=True, text=True,
                          check=False, cwd=tree)
    if proc.returncode:
        raise SystemExit(f"the run with {tree} failed:\n{proc.stdout}\n{proc.stderr}")
    record = json.loads(proc.stdout.strip().splitlines()[-1])
    return record["figures"], record["note"]


def show(value: float, unit: str) -> str:
    return f"{value:,.0f}" if unit == "pos/s" else f"{value:.3g}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--before", type=Path, help="another checkout of the program to compare with")
    parser.add_argument("--json", action="store_true", help="this checkout's figures as JSON")
    args = parser.parse_args(argv)
    if args.json:
        figures, note = measure(args.designs, args.rounds)
        print(json.dumps({"figures": figures, "note": note}))
        return 0
    here = ROOT
    trees = {"after": here} if args.before is None else {"before": args.before, "after": here}
    runs: dict[str, list[dict[str, float]]] = {name: [] for name in trees}
    notes: dict[str, str] = {}
    for _ in range(1 if args.before is None else 2):  # before, after, before, after
        for name, tree in trees.items():
            figures, notes[name] = run_tree(tree.resolve(), args.designs, args.rounds)
            runs[name].append(figures)
    best = {name: {key: (max if FIGURES[key][2] else min)(r[key] for r in rows)
                   for key in FIGURES} for name, rows in runs.items()}
    print(f"one core; D = {args.designs} designs; best of the runs\n")
    header = f"{'figure':52s} {'unit':>6s}"
    header += "".join(f" {name:>13s}" for name in trees)
    if args.before is not None:
        header += f" {'after/before':>13s}"
    print(header)
    for key, (label, unit, larger) in FIGURES.items():
        line = f"{label.replace('D x', f'{args.designs} x'):52s} {unit:>6s}"
        line += "".join(f" {show(best[name][key], unit):>13s}" for name in trees)
        if args.before is not None:
            old, new = best["before"][key], best["after"][key]
            line += f" {(new / old if larger else old / new):12.2f}x"
        print(line)
    for name, note in notes.items():
        print(f"synthesis result ({name}): {note}")
    if args.before is not None:
        print("after/before: the speed-up, > 1 where the figure is better after")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
