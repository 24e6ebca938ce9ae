"""Triad positions per second over a crank cycle, beside the RRR dyad's rate in the same run.

A crank (O = 0, pin B drawn at (−17, −0.5)) drives an RRR triad: base C–D–F, leashes B–C, E–D
(E on the frame) and G–F (G on the frame). ``follow_mode`` follows its sketched mode over N
crank angles (continuation: analog predictor, Newton corrector, step control, neighbour test),
for one design and for 1,000 designs at once (base hinges jittered by up to 1 mm). Beside it,
``solve_input`` + ``solve_rrr`` (crank + RRR dyad, the four-bar of ``bench_fourbar.py``) over
the same angles and designs.

Each variant runs once untimed, then R timed rounds; the table gives the median and the best
rate (positions per second) and the ratios dyad / triad of both.

Run: ``python benchmarks/bench_higher.py [--points N] [--designs D] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from functools import partial

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: no threaded BLAS anywhere

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.dyads import solve_input, solve_rrr
from assur.kinematics.higher import Triad, TriadInputs, follow_mode
from assur.typing import Value

PIN = -17 - 0.5j
BASE = (77.5 + 30.5j, 112 + 7.5j, 114 + 52j)
FRAME = (81 + 31j, 150 + 80j)


def triad(designs: int, rng: np.random.Generator) -> Triad:
    """The benchmark triad; ``designs`` > 1 jitters the base hinges (shape (D,))."""
    if designs == 1:
        return Triad(("RR", "RR", "RR"), BASE, (PIN, *FRAME))
    jitter = rng.uniform(-0.5, 0.5, (3, designs)) + 1j * rng.uniform(-0.5, 0.5, (3, designs))
    return Triad(("RR", "RR", "RR"), tuple(b + j for b, j in zip(BASE, jitter, strict=True)),
                 (PIN, *FRAME))


def inputs(phi: Value) -> TriadInputs:
    """The crank pin and the two frame hinges at the crank angles ``phi``."""
    return TriadInputs((PIN * J.expi(phi), *FRAME))


def dyad(phi: np.ndarray, crank: float | np.ndarray) -> np.ndarray:
    """Crank + RRR dyad (O₁ = 0, O₂ = 100, coupler 80, rocker 90)."""
    return np.asarray(solve_rrr(solve_input(0j, crank, phi).c, 100 + 0j, 80.0, 90.0, 1.0).c)


def rate(run: Callable[[], object], positions: int, rounds: int, batch: float = 0.2
         ) -> tuple[float, float]:
    """Median and best positions per second over ``rounds`` timings of at least ``batch`` s."""
    run()
    rates = []
    for _ in range(rounds):
        calls, start = 0, time.perf_counter()
        while True:
            run()
            calls += 1
            elapsed = time.perf_counter() - start
            if elapsed >= batch:
                break
        rates.append(calls * positions / elapsed)
    return float(np.median(rates)), float(np.max(rates))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=360)
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(0)
    phi = np.linspace(0, 2 * np.pi, args.points, endpoint=False)
    rows = []
    for designs in (1, args.designs):
        group = triad(designs, rng)
        solution = follow_mode(group, inputs, phi)
        print(f"{designs} design(s): the sketched mode assembles at "
              f"{100 * solution.exists.mean():.1f} % of the positions")
        cranks = 17.0 if designs == 1 else np.full((designs, 1), 17.0)
        positions = designs * args.points
        higher = rate(partial(follow_mode, group, inputs, phi), positions, args.rounds)
        pair = rate(partial(dyad, phi, cranks), positions, args.rounds)
        rows.append((designs, higher, pair))
    print(f"\n{'designs':>8} {'triad pos/s (median, best)':>30} {'RRR dyad pos/s':>26} "
          f"{'dyad / triad':>16}")
    for designs, (t_med, t_best), (d_med, d_best) in rows:
        print(f"{designs:>8} {t_med:>15,.0f} {t_best:>14,.0f} {d_med:>13,.0f} {d_best:>12,.0f} "
              f"{d_med / t_med:>8,.0f} {d_best / t_best:>7,.0f}")


if __name__ == "__main__":
    main()
