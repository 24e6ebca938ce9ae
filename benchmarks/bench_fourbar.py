"""Four-bar positions per second: the group solvers against other ways of computing them.

One crank-rocker four-bar (O₁ = 0, O₂ = 100 mm, crank 30, coupler 80, rocker 90) is solved over
N crank angles of one turn, on one core, by

(a) ``solve_input`` + ``solve_rrr`` on plain arrays: crank pin, joint C, both link angles, the
    existence margin, mask and reason codes, all computed in the call;
(b) a hand-written minimal numpy closed form computing the same joints and link angles (no
    margin, mask or reasons): the practical limit of numpy on this machine;
(c) pylinkage 1.3, if installed: ``Linkage.step_fast`` (numba) and the plain ``step``;
(d) 1,000 designs × 360 angles in one call (crank length varied, shape (1000, 1)), by (a)
    and by (b).

(a) and (b) hand back the same three arrays, read from their results: the coupler joint C, the
coupler angle φ₂ and the rocker angle φ₃ (for (a), the solution's ``c``, ``angle_i`` and
``angle_j``; its margin, mask and reasons are computed in the same call, not when first read).

Timing: in each round the variants run in a shuffled order; each one is called once untimed
and then timed over a batch of calls, so that every figure is a steady-state rate, not the
cost of the first call after another variant's memory traffic. The table gives the median
and the best rate over the rounds, and the ratios of both measured in the same run (on a
shared machine other processes only ever slow a variant down, so the best rate is the closer
estimate of its own cost; the median shows the spread). The script first checks that the
variants agree on the coupler joint and both link angles.

Run: ``python benchmarks/bench_fourbar.py [--points N ...] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from typing import cast

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: no threaded BLAS anywhere

import numpy as np

from assur import solve_input, solve_rrr

O1, O2 = 0.0 + 0.0j, 100.0 + 0.0j
CRANK, COUPLER, ROCKER = 30.0, 80.0, 90.0
SIGMA = 1.0
BATCH_SECONDS = 0.1


Joint = tuple[np.ndarray, np.ndarray, np.ndarray]


def ours(phi: np.ndarray, crank: float | np.ndarray = CRANK) -> Joint:
    """Crank pin and RRR dyad through the group solvers: C, φ₂ and φ₃ read from the solution."""
    pin = solve_input(O1, crank, phi)
    dyad = solve_rrr(pin.c, O2, COUPLER, ROCKER, SIGMA)
    return cast(Joint, (dyad.c, dyad.angle_i, dyad.angle_j))


def handwritten(phi: np.ndarray, crank: float | np.ndarray = CRANK) -> Joint:
    """Minimal closed-form four-bar in real arithmetic: joints A, C and angles φ₂, φ₃."""
    ax = crank * np.cos(phi)
    ay = crank * np.sin(phi)
    rx = O2.real - ax
    ry = O2.imag - ay
    d2 = rx * rx + ry * ry
    x = (d2 + COUPLER * COUPLER - ROCKER * ROCKER) / (2.0 * d2)
    y = SIGMA * np.sqrt(COUPLER * COUPLER / d2 - x * x)
    wx = rx * x - ry * y
    wy = rx * y + ry * x
    cx = ax + wx
    cy = ay + wy
    coupler = np.arctan2(wy, wx)  # φ₂
    rocker = np.arctan2(wy - ry, wx - rx)  # φ₃
    return cx + 1j * cy, coupler, rocker


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


def check_agreement(phi: np.ndarray, linkage: object | None) -> None:
    """Print how far the variants are from each other on the coupler joint C and the angles."""
    (c, coupler, rocker), (c_hand, coupler_hand, rocker_hand) = ours(phi), handwritten(phi)
    turn = np.angle(np.exp(1j * np.concatenate([coupler - coupler_hand, rocker - rocker_hand])))
    print(f"max |C_assur - C_hand| = {np.max(np.abs(c - c_hand)):.3e} mm,"
          f" max |phi_assur - phi_hand| = {np.max(np.abs(turn)):.3e} rad")
    if linkage is not None:
        traj = linkage.step_fast(iterations=phi.size)
        pins = traj[:, 2, 0] + 1j * traj[:, 2, 1]
        c_pl = traj[:, 3, 0] + 1j * traj[:, 3, 1]
        dev = min(np.nanmax(np.abs(c_pl - solve_rrr(pins, O2, COUPLER, ROCKER, b).c))
                  for b in (SIGMA, -SIGMA))  # whichever branch pylinkage settled on
        print(f"max |C_assur - C_pylinkage| on pylinkage's crank pins = {dev:.3e} mm")


def steady_rate(run: Callable[[], object], positions: int) -> float:
    """Positions per second of ``run`` over a batch of calls after one untimed call."""
    run()
    calls, elapsed = 0, 0.0
    start = time.perf_counter()
    while elapsed < BATCH_SECONDS:
        run()
        calls += 1
        elapsed = time.perf_counter() - start
    return positions * calls / elapsed


def variants_for(n: int, designs: int) -> dict[str, tuple[Callable[[], object], int]]:
    phi = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    variants: dict[str, tuple[Callable[[], object], int]] = {
        f"(a) assur solvers, N = {n}": (lambda: ours(phi), n),
        f"(b) hand-written numpy, N = {n}": (lambda: handwritten(phi), n),
    }
    linkage = pylinkage_linkage(n)
    if linkage is not None and numba_available():
        linkage.step_fast(iterations=n)  # compile once, outside the timing
        variants[f"(c) pylinkage step_fast (numba), N = {n}"] = (
            lambda: linkage.step_fast(iterations=n), n)
    if linkage is not None:
        steps = max(n // 10, 36)
        variants[f"(c) pylinkage step (plain), N = {n}"] = (
            lambda: list(linkage.step(iterations=steps)), steps)
    return variants


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, nargs="+", default=[360, 3600],
                        help="crank angles per call (one table block each)")
    parser.add_argument("--rounds", type=int, default=7, help="timing rounds (median taken)")
    parser.add_argument("--designs", type=int, default=1000, help="designs in variant (d)")
    args = parser.parse_args(argv)

    linkage = pylinkage_linkage(360)
    if linkage is None:
        print("pylinkage is not installed; to include it: pip install pylinkage==1.3.0")
    elif not numba_available():
        print("numba is not installed, so pylinkage's step_fast would run uncompiled;"
              " to include it: pip install numba")
    check_agreement(np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False),
                    linkage if numba_available() else None)

    variants: dict[str, tuple[Callable[[], object], int]] = {}
    for n in args.points:
        variants.update(variants_for(n, args.designs))
    phi_d = np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False)
    cranks = np.linspace(0.9, 1.1, args.designs)[:, None] * CRANK
    np.testing.assert_allclose(ours(phi_d, cranks)[0], handwritten(phi_d, cranks)[0], atol=1e-9)
    variants[f"(d) assur solvers, {args.designs} x 360"] = (
        lambda: ours(phi_d, cranks), args.designs * 360)
    variants[f"(d) hand-written numpy, {args.designs} x 360"] = (
        lambda: handwritten(phi_d, cranks), args.designs * 360)

    rng = np.random.default_rng(7)
    names = list(variants)
    rates: dict[str, list[float]] = {name: [] for name in names}
    for _ in range(args.rounds):
        for name in rng.permutation(names):
            run, count = variants[name]
            rates[name].append(steady_rate(run, count))
    median = {name: float(np.median(values)) for name, values in rates.items()}
    best = {name: max(values) for name, values in rates.items()}

    print(f"\nfour-bar positions per second, one process, {args.rounds} rounds")
    print(f"{'variant':44s} {'median':>13s} {'best':>13s}")
    for name in names:
        print(f"{name:44s} {median[name]:13,.0f} {best[name]:13,.0f}")
    for label, rate in (("median", median), ("best", best)):
        print(f"\nratios measured side by side ({label} rates):")
        print_ratios(rate, args.points, args.designs)
    print("targets: (a)/(b) >= 1.0 (issue 26), (a)/numba >= 1.5, (d) per position >= (a)")
    return 0


def print_ratios(rate: dict[str, float], points: list[int], designs: int) -> None:
    """Print the ratios of the variants' rates ``rate`` (positions/s by variant name)."""
    for n in points:
        a, b = rate[f"(a) assur solvers, N = {n}"], rate[f"(b) hand-written numpy, N = {n}"]
        line = f"  N = {n:6d}: (a)/(b) = {a / b:5.2f}"
        fast = rate.get(f"(c) pylinkage step_fast (numba), N = {n}")
        if fast:
            line += f"   (a)/numba = {a / fast:5.2f}"
        plain = rate.get(f"(c) pylinkage step (plain), N = {n}")
        if plain:
            line += f"   (a)/plain step = {a / plain:6.1f}"
        print(line)
    d_ours = rate[f"(d) assur solvers, {designs} x 360"]
    d_hand = rate[f"(d) hand-written numpy, {designs} x 360"]
    print(f"  {designs} x 360 in one call: (d) assur/(d) hand = {d_ours / d_hand:5.2f};"
          f" per position vs (a) at N = {points[-1]}:"
          f" {d_ours / rate[f'(a) assur solvers, N = {points[-1]}']:5.2f}")


if __name__ == "__main__":
    raise SystemExit(main())
