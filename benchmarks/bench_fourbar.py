"""Four-bar positions per second: the group solvers against other ways of computing them.

One crank-rocker four-bar (O₁ = 0, O₂ = 100 mm, crank 30, coupler 80, rocker 90) is solved over
N crank angles of one turn, on one core, by

(a) ``solve_input`` + ``solve_rrr`` on plain arrays (crank pin, joint C, both link angles, the
    existence margin, mask and reason codes);
(b) a hand-written minimal numpy closed form computing the same joints and link angles (no
    margin, mask or reasons): the practical limit of numpy on this machine;
(c) pylinkage 1.3 (if installed): ``Linkage.step_fast`` (numba) and the plain ``step``;
(d) 1,000 designs × 360 angles in one call of (a), parameters shaped (D, 1).

Every variant is timed in turn within each round, so that all of them see the same machine
load; the table gives the median rate over the rounds and the ratios to (b) and to
pylinkage's numba path. The script also checks that the variants agree on the coupler joint.

Run: ``python benchmarks/bench_fourbar.py [--points N] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: no threaded BLAS anywhere

import numpy as np  # noqa: E402

from assur import solve_input, solve_rrr  # noqa: E402

O1, O2 = 0.0 + 0.0j, 100.0 + 0.0j
CRANK, COUPLER, ROCKER = 30.0, 80.0, 90.0
SIGMA = 1.0


def ours(phi: np.ndarray, crank: float | np.ndarray = CRANK) -> np.ndarray:
    """Crank pin and RRR dyad through the group solvers; returns the coupler joint C."""
    pin = solve_input(O1, crank, phi)
    return solve_rrr(pin.c, O2, COUPLER, ROCKER, SIGMA).c


def handwritten(phi: np.ndarray) -> np.ndarray:
    """Minimal closed-form four-bar in real arithmetic: joints A, C and angles φ₂, φ₃."""
    ax = CRANK * np.cos(phi)
    ay = CRANK * np.sin(phi)
    rx = O2.real - ax
    ry = O2.imag - ay
    d2 = rx * rx + ry * ry
    x = (d2 + COUPLER * COUPLER - ROCKER * ROCKER) / (2.0 * d2)
    y = SIGMA * np.sqrt(COUPLER * COUPLER / d2 - x * x)
    wx = rx * x - ry * y
    wy = rx * y + ry * x
    cx = ax + wx
    cy = ay + wy
    np.arctan2(wy, wx)  # coupler angle φ₂
    np.arctan2(wy - ry, wx - rx)  # rocker angle φ₃
    return cx + 1j * cy


def pylinkage_linkage(n: int) -> object | None:
    """The same four-bar as a pylinkage ``Linkage`` advancing 2π/n per step, or None."""
    try:
        from pylinkage.actuators import Crank
        from pylinkage.components import Ground
        from pylinkage.dyads import RRRDyad
        from pylinkage.simulation import Linkage
    except ImportError:
        return None
    o1 = Ground(O1.real, O1.imag, name="O1")
    o2 = Ground(O2.real, O2.imag, name="O2")
    crank = Crank(anchor=o1, radius=CRANK, angular_velocity=2.0 * np.pi / n)
    dyad = RRRDyad(anchor1=crank.output, anchor2=o2, distance1=COUPLER, distance2=ROCKER)
    return Linkage([o1, o2, crank, dyad], name="four-bar")


def numba_available() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def median_rate(times: list[float], positions: int) -> float:
    return positions / float(np.median(times))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=3600, help="crank angles per call")
    parser.add_argument("--rounds", type=int, default=15, help="timing rounds (median taken)")
    parser.add_argument("--designs", type=int, default=1000, help="designs in variant (d)")
    args = parser.parse_args(argv)
    n = args.points
    phi = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    phi_d = np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False)
    cranks = np.linspace(0.9, 1.1, args.designs)[:, None] * CRANK

    variants: dict[str, tuple[Callable[[], object], int]] = {
        "(a) assur solvers, plain arrays": (lambda: ours(phi), n),
        "(b) hand-written numpy closed form": (lambda: handwritten(phi), n),
        f"(d) assur solvers, {args.designs} designs x 360": (
            lambda: ours(phi_d, cranks), args.designs * 360),
    }
    linkage = pylinkage_linkage(n)
    if linkage is None:
        print("pylinkage is not installed; to include it: pip install pylinkage==1.3.0")
    else:
        if numba_available():
            linkage.step_fast(iterations=n)  # compile once, outside the timing
            variants["(c) pylinkage 1.3 step_fast (numba)"] = (
                lambda: linkage.step_fast(iterations=n), n)
        else:
            print("numba is not installed, so pylinkage's step_fast would run uncompiled;"
                  " to include it: pip install numba")
        steps = max(n // 10, 36)
        variants["(c) pylinkage 1.3 step (plain)"] = (
            lambda: list(linkage.step(iterations=steps)), steps)

    # agreement on the coupler joint before timing anything
    c_ours, c_hand = ours(phi), handwritten(phi)
    print(f"max |C_assur - C_hand| = {np.max(np.abs(c_ours - c_hand)):.3e} mm")
    if linkage is not None:
        linkage.step_fast(iterations=1)  # back to a known start is not needed: compare a turn
        traj = linkage.step_fast(iterations=n)
        c_pl = traj[:, 3, 0] + 1j * traj[:, 3, 1]
        pins = traj[:, 2, 0] + 1j * traj[:, 2, 1]
        c_ref = solve_rrr(pins, O2, COUPLER, ROCKER, SIGMA).c
        c_alt = solve_rrr(pins, O2, COUPLER, ROCKER, -SIGMA).c
        dev = min(np.nanmax(np.abs(c_pl - c_ref)), np.nanmax(np.abs(c_pl - c_alt)))
        print(f"max |C_assur - C_pylinkage| on pylinkage's crank pins = {dev:.3e} mm")

    for run, _ in variants.values():  # warm caches and allocators
        run()
    times: dict[str, list[float]] = {name: [] for name in variants}
    for _ in range(args.rounds):
        for name, (run, _) in variants.items():
            start = time.perf_counter()
            run()
            times[name].append(time.perf_counter() - start)

    rates = {name: median_rate(times[name], count) for name, (_, count) in variants.items()}
    hand = rates["(b) hand-written numpy closed form"]
    fast = rates.get("(c) pylinkage 1.3 step_fast (numba)")
    print(f"\nfour-bar positions per second, N = {n} crank angles per call, "
          f"median of {args.rounds} rounds, one process")
    header = f"{'variant':46s} {'positions/s':>13s} {'vs (b)':>8s}"
    header += f" {'vs numba':>9s}" if fast else ""
    print(header)
    for name in sorted(rates):
        line = f"{name:46s} {rates[name]:13,.0f} {rates[name] / hand:8.2f}"
        line += f" {rates[name] / fast:9.2f}" if fast else ""
        print(line)
    print("\ntargets: (a)/(b) >= 0.8, (a)/numba >= 1.5, (d) per position >= (a)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
