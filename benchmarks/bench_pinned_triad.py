"""Positions per second of a triad with a P–P leash and no bar, beside a followed triad and
the RRR dyad in the same run.

The triad of ``input_tables/six_bar_triad_pp_sliders.yaml``: a crank carries the slot of the
block hinged to the base at C and the guide of the P–P leash; the third leash is hinged to the
frame at E and slides on the base. It has one mode at every position, solved in closed form
(``place``: every angle at once, the analogs by implicit differentiation when asked) for one
design and for 1,000 designs (base points jittered by up to 1 mm). Beside it, the RRR triad
of ``bench_higher.py`` followed by continuation (``follow_mode``) and the crank + RRR dyad,
over the same angles and designs.

Run: ``python benchmarks/bench_pinned_triad.py [--points N] [--designs D] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import os
from functools import partial

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: no threaded BLAS anywhere

import numpy as np
from bench_higher import dyad, inputs, rate, triad

from assur.kinematics import jets as J
from assur.kinematics.higher import Triad, TriadInputs, follow_mode
from assur.kinematics.higher.pinned import place
from assur.kinematics.jets import Jet
from assur.typing import Value

BASE = (42 + 30j, 70 - 10j, 20 + 60j)
EXTERNAL = (42 + 30j, 70 - 10j, 30 + 70j)
GUIDE = tuple(np.exp(1j * np.radians(a)) for a in (35.5376778, 90.0, 120.0))


def pinned(designs: int, rng: np.random.Generator) -> Triad:
    """The benchmark triad; ``designs`` > 1 jitters the base points (shape (D,))."""
    base: tuple[Value, ...] = BASE
    if designs > 1:
        jitter = rng.uniform(-0.5, 0.5, (3, designs)) + 1j * rng.uniform(-0.5, 0.5, (3, designs))
        base = tuple(b + j for b, j in zip(BASE, jitter, strict=True))
    return Triad(("RP", "PR", "PP"), base, EXTERNAL, GUIDE)  # type: ignore[arg-type]


def known(phi: Value) -> TriadInputs:
    """The crank's slot and guide turned by φ; the hinge E on the frame."""
    turn = J.expi(phi)
    return TriadInputs((EXTERNAL[0] * turn, EXTERNAL[1], EXTERNAL[2] * turn),
                       (GUIDE[0] * turn, None, GUIDE[2] * turn))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    for option, default in (("--points", 360), ("--designs", 1000), ("--rounds", 3)):
        parser.add_argument(option, type=int, default=default)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(0)
    phi = np.linspace(0, 2 * np.pi, args.points, endpoint=False)
    k0 = known(0.0)
    rows = []
    for designs in (1, args.designs):
        group = pinned(designs, rng)
        exists = place(group, k0, known(phi)).exists
        print(f"{designs} design(s): assembles at {100 * np.mean(exists):.1f} % of the positions")
        positions = designs * args.points
        closed = rate(partial(place, group, k0, known(phi)), positions, args.rounds)
        jets = rate(partial(place, group, k0, known(Jet(phi, 1.0, 0.0))), positions, args.rounds)
        followed = rate(partial(follow_mode, triad(designs, rng), inputs, phi), positions,
                        args.rounds)
        cranks = 17.0 if designs == 1 else np.full((designs, 1), 17.0)
        pair = rate(partial(dyad, phi, cranks), positions, args.rounds)
        rows.append((designs, closed, jets, followed, pair))
    print(f"\n{'designs':>8} {'P–P triad':>12} {'with analogs':>13} {'RRR triad':>11} "
          f"{'RRR dyad':>12} {'dyad / P–P':>11}   (positions/s, medians)")
    for designs, closed, jets, followed, pair in rows:
        print(f"{designs:>8} {closed[0]:>12,.0f} {jets[0]:>13,.0f} {followed[0]:>11,.0f} "
              f"{pair[0]:>12,.0f} {pair[0] / closed[0]:>11,.1f}")


if __name__ == "__main__":
    main()
