"""Speed of the mechanism analysis on the course's 11-link example (one core).

Prints crank positions per second for

* positions only, one design, a long grid of crank angles;
* positions with velocity and acceleration analogs (second-order jets);
* a batch of 1,000 designs × 360 angles in one call (four parameters varied per design),
  per analysed position, next to the single-design rate;
* the existence check with interval refinement (one design, 360 angles).

Run: ``python benchmarks/bench_mechanism.py [--repeat 5] [--wall]``. Numpy's elementwise
operations run on one thread, so the figures are for one core.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

import assur
from assur.kinematics.analysis import analyse

TABLE = Path(__file__).resolve().parent.parent / "input_tables" / "course_11_link.yaml"


def best_time(call, repeat: int) -> float:
    """The fastest of ``repeat`` runs (CPU seconds of this process), after a warm-up run.

    CPU time (``time.process_time``) is what one core spends, so the figure holds on a
    machine busy with other work; ``--wall`` measures elapsed time instead.
    """
    call()
    best = float("inf")
    for _ in range(repeat):
        start = CLOCK()
        call()
        best = min(best, CLOCK() - start)
    return best


CLOCK = time.process_time


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--positions", type=int, default=360_000,
                        help="crank angles of the single-design runs")
    parser.add_argument("--wall", action="store_true",
                        help="measure elapsed time (time.perf_counter) instead of CPU time")
    args = parser.parse_args()
    global CLOCK
    if args.wall:
        CLOCK = time.perf_counter
    model = assur.load_model(TABLE)
    phi = np.linspace(0.0, 2 * np.pi, args.positions, endpoint=False)

    t_pos = best_time(lambda: analyse(model, phi), args.repeat)
    t_jet = best_time(lambda: analyse(model, phi, analogs=True), args.repeat)

    rng = np.random.default_rng(1)
    designs = 1000
    varied = {"L1(2,3).l_i": rng.uniform(136, 144, (designs, 1)),
              "L3(6,7).d": rng.uniform(0, 20, (designs, 1)),
              "L2(9,8).l_j": rng.uniform(120, 140, (designs, 1)),
              "L5(11,10).gamma": rng.uniform(45, 75, (designs, 1))}
    batch = model.with_params(varied)
    grid = assur.input_grid(model, 360)
    t_batch = best_time(lambda: analyse(batch, grid), args.repeat)
    t_batch_jet = best_time(lambda: analyse(batch, grid, analogs=True), args.repeat)
    motion = analyse(batch, grid)
    feasible = int(motion.exists.all(axis=1).sum())
    t_exist = best_time(lambda: assur.check_existence(model, points=360), args.repeat)

    rate = args.positions / t_pos
    rows = [
        ("11-link, positions only", args.positions, t_pos, rate),
        ("11-link, positions + analogs", args.positions, t_jet, args.positions / t_jet),
        ("1,000 designs x 360, positions", designs * 360, t_batch, designs * 360 / t_batch),
        ("1,000 designs x 360, + analogs", designs * 360, t_batch_jet,
         designs * 360 / t_batch_jet),
    ]
    print(f"mechanism: {model.name} ({len(model.groups)} groups), numpy {np.__version__}, "
          f"best of {args.repeat}, {'elapsed' if args.wall else 'CPU'} time")
    print(f"{'run':<34} {'positions':>10} {'time, s':>9} {'positions/s':>13} {'vs single':>9}")
    for name, count, seconds, per_second in rows:
        print(f"{name:<34} {count:>10,} {seconds:>9.4f} {per_second:>13,.0f} "
              f"{per_second / rate:>8.2f}x")
    print(f"feasible designs in the batch: {feasible} of {designs}")
    print(f"existence check with interval refinement, 360 angles: {t_exist * 1e3:.1f} ms")
    print(f"target >= 1,000,000 positions/s (positions only): "
          f"{'met' if rate >= 1e6 else 'NOT met'}; batch per position at least as fast: "
          f"{'met' if rows[2][3] >= rate else 'NOT met'}")


if __name__ == "__main__":
    main()
