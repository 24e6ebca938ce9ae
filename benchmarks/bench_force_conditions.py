"""Speed of the force penalty P2_F of the synthesis next to the kinematics with analogs.

On the course's 11-link problem (``class2_course_11_link.yaml``) with a ``forces:`` table
(masses on every link, a resistance on slider 11, a driving-torque limit, a reaction limit
and two couple limits), for a batch of designs × the problem's grid of 360 crank angles:
the kinematics with analogs alone, then the whole P2_F (kinematics, kinetostatics and the
limits, ``force_penalties``) with the masses fixed, and with the masses following the design
(``per_mm``, ``centre: middle``, ``inertia: rod``; the sliders' masses at their hinges).
Prints designs × positions per second and the cost of the force pass over the kinematics.

Run: ``python benchmarks/bench_force_conditions.py [--designs 200] [--repeat 5] [--wall]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import bench_mechanism
import numpy as np
import yaml
from bench_mechanism import best_time

from assur.kinematics.analysis import analyse
from synthesis import problem_from_dict
from synthesis.evaluate import Evaluator
from synthesis.force_conditions import force_penalties

PROBLEM = (Path(__file__).resolve().parent.parent / "input_tables" / "problems"
           / "class2_course_11_link.yaml")
BARS = {1: ("0-1", "1-2"), 2: ("1-2", "2-6"), 3: ("2-3", "3-0"), 6: ("2-6", "6-8"),
        8: ("6-8", "8-10")}
BLOCKS = {4: 0.3, 5: 0.3, 7: 0.4, 9: 0.5, 10: 0.6}


def _forces(follow: bool) -> dict[str, Any]:
    bars = {link: ({"per_mm": 0.005, "centre": "middle", "inertia": "rod",
                    "between": list(pair)} if follow else
                   {"mass": 0.5, "centre": [20, 0], "inertia": 1e-3})
            for link, pair in BARS.items()}
    blocks = {link: {"mass": mass} if follow else {"mass": mass, "centre": [0, 0]}
              for link, mass in BLOCKS.items()}
    return {"omega": 10, "gravity": [0, -9.81],
            "masses": {**bars, **blocks, 11: {"mass": 0.5, "centre": [0, 0]}},
            "loads": [{"link": 11, "force": [0, -500], "point": [0, 0]}],
            "limits": {"driving_torque": 20, "reactions": {"2-6": 600},
                       "couples": {"10-11": 80, "6-7": 0.05}}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--designs", type=int, default=200)
    parser.add_argument("--wall", action="store_true",
                        help="measure elapsed time (time.perf_counter) instead of CPU time")
    args = parser.parse_args()
    if args.wall:
        bench_mechanism.CLOCK = time.perf_counter
    table = yaml.safe_load(PROBLEM.read_text(encoding="utf-8"))
    table["mechanism"] = str(PROBLEM.parent / table["mechanism"])
    problems = {kind: problem_from_dict({**table, "forces": _forces(kind == "following")},
                                        str(PROBLEM)) for kind in ("fixed", "following")}
    problem = problems["fixed"]
    evaluator = Evaluator(problem)
    rng = np.random.default_rng(2)
    x = problem.lower + rng.random((4 * args.designs, problem.lower.size)) * (
        problem.upper - problem.lower)
    x = x[evaluator(x).p1 == 0][:args.designs]
    grid = evaluator.grid
    count = len(x) * grid.size
    every = np.ones(len(x), bool)
    t_kin = best_time(lambda: analyse(evaluator.model(x), grid, analogs=True),
                      args.repeat)
    print(f"{PROBLEM.name}, {len(x)} designs x {grid.size} angles, "
          f"{'wall' if args.wall else 'CPU'} time, best of {args.repeat}")
    print(f"{'pass':<34}{'positions/s':>13}{'over kinematics':>17}")
    print(f"{'kinematics with analogs':<34}{count / t_kin:>13,.0f}{1.0:>17.2f}")
    for kind, case in problems.items():
        conditions = case.forces
        t = best_time(lambda c=conditions: force_penalties(c, evaluator.model, x, every, grid),
                      args.repeat)
        print(f"{'P2_F, masses ' + kind:<34}{count / t:>13,.0f}{t / t_kin:>17.2f}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
