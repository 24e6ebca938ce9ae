"""Speed of the force analysis on the course's 11-link example next to its kinematics (one core).

Prints positions per second for the kinematics with analogs (what the force analysis needs),
for the force analysis of that motion (masses on every link, the tabulated resistance on
slider 11, gravity), and for both together, for one design over a long grid of crank angles
and for a batch of designs × 360 angles (every length and frame hinge of the groups varied
by up to ±1 %); then the ratio force analysis / kinematics. ``--table`` takes another table
with force sections, e.g. the six-bar with a triad (one linear solve per position).

Run: ``python benchmarks/bench_forces.py [--repeat 5] [--positions 100000] [--wall]``;
``python benchmarks/bench_forces.py --table input_tables/six_bar_triad_forces.yaml
--positions 3600``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import bench_mechanism
import numpy as np
from bench_mechanism import best_time

import assur
from assur.forces import kinetostatics
from assur.kinematics.analysis import analyse
from assur.kinematics.build import load_with_forces

TABLE = Path(__file__).resolve().parent.parent / "input_tables" / "course_11_link_forces.yaml"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--positions", type=int, default=100_000)
    parser.add_argument("--designs", type=int, default=300)
    parser.add_argument("--table", type=Path, default=TABLE)
    parser.add_argument("--wall", action="store_true",
                        help="measure elapsed time (time.perf_counter) instead of CPU time")
    args = parser.parse_args()
    if args.wall:
        bench_mechanism.CLOCK = time.perf_counter
    model, data = load_with_forces(args.table)
    assert data is not None
    rows = []
    phi = np.linspace(0.0, 2 * np.pi, args.positions, endpoint=False)
    rng = np.random.default_rng(1)
    batch = model.with_params({
        name: value * rng.uniform(0.99, 1.01, (args.designs, 1))
        for name, value in model.params.items()
        if not name.startswith("L0(") and name.split(".")[-1][:2] in ("l_", "x_", "y_")})
    for label, design, q in (("one design", model, phi),
                             (f"{args.designs} designs x 360", batch,
                              assur.input_grid(model, 360))):
        count = int(np.prod(np.broadcast_shapes(design.design_shape, q.shape)))
        motion = analyse(design, q, analogs=True)
        t_kin = best_time(lambda d=design, x=q: analyse(d, x, analogs=True), args.repeat)
        t_force = best_time(lambda m=motion: kinetostatics(m, data, 10.0), args.repeat)
        rows.append((label, count, t_kin, t_force))
    print(f"{args.table.name}, {'wall' if args.wall else 'CPU'} time, best of {args.repeat}")
    print(f"{'run':<22}{'positions':>11}{'kinematics/s':>15}{'forces/s':>13}{'both/s':>12}"
          f"{'forces/kin':>12}")
    for label, count, t_kin, t_force in rows:
        print(f"{label:<22}{count:>11}{count / t_kin:>15,.0f}{count / t_force:>13,.0f}"
              f"{count / (t_kin + t_force):>12,.0f}{t_force / t_kin:>12.2f}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
