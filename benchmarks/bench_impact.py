"""Impacts per second: the batched impulse systems of the impact case against a loop.

The source's four-bar is placed at N crank angles × 3 rocker speeds (``impact_position``) and
both impact models are solved (a) in one batched call each (``solve_paper``,
``solve_townsend_mansour``: stacked 9×9 and 4×4 systems, one ``numpy.linalg.solve``) and
(b) one impact at a time in a Python loop over the same functions with scalar inputs. The
script first checks that (a) and (b) agree, then prints the median time of R rounds.

Run: ``python benchmarks/bench_impact.py [--points N] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np

from synthesis.cases.impact.data import PAPER
from synthesis.cases.impact.models import solve_paper, solve_townsend_mansour
from synthesis.cases.impact.position import impact_position

OMEGA4 = np.array([0.0, -30.0, -60.0])


def _batched(theta2: np.ndarray) -> np.ndarray:
    position = impact_position(PAPER, theta2[:, None], OMEGA4)
    return np.stack([solve_paper(PAPER, position).normal,
                     solve_townsend_mansour(PAPER, position).normal])


def _looped(theta2: np.ndarray) -> np.ndarray:
    out = np.empty((2, theta2.size, OMEGA4.size))
    for i, angle in enumerate(theta2):
        for j, omega4 in enumerate(OMEGA4):
            position = impact_position(PAPER, angle, omega4)
            out[0, i, j] = solve_paper(PAPER, position).normal
            out[1, i, j] = solve_townsend_mansour(PAPER, position).normal
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=360)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    theta2 = np.radians(np.linspace(0.0, 360.0, args.points, endpoint=False))
    assert np.allclose(_batched(theta2), _looped(theta2), rtol=1e-12)
    times = {}
    for name, func in (("batched", _batched), ("loop", _looped)):
        rounds = []
        for _ in range(args.rounds):
            start = time.perf_counter()
            func(theta2)
            rounds.append(time.perf_counter() - start)
        times[name] = float(np.median(rounds))
    impacts = 2 * theta2.size * OMEGA4.size
    for name, seconds in times.items():
        print(f"{name:>8}: {seconds * 1e3:9.2f} ms for {impacts} impacts "
              f"({impacts / seconds:,.0f} impacts/s)")
    print(f"ratio loop/batched: {times['loop'] / times['batched']:.1f}")


if __name__ == "__main__":
    main()
