"""The class IV group with prismatic internal pairs: mode counts on many designs, and speed.

Counts: for each form with a prismatic internal pair, D random designs (the generator of
``tests/assur/test_higher_coupled.py``) at a crank angle of 37°; the modes of
:class:`ClassIVCoupled` against the fallback's (the sweep of the full pose system, or Newton's
search from random starts where no sweep plan exists). Designs with a root of p just off the
unit circle or a mode of thin margin are set aside (near a change point).

Speed: on the forms the tests' oracle :class:`ClassIV` also solves (hinged couplers), all modes of D designs at
one position (designs per second), and one design followed over 360 crank angles (positions
per second), both solvers in the same run; each variant runs once untimed, then R timed
rounds (median and best).

Run: ``python benchmarks/bench_coupled.py [--designs D] [--rounds R] [--forms F ... | all]
[--no-speed]``.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from functools import partial
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core: no threaded BLAS anywhere

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "assur"))

from bench_higher import rate
from class_iv_hinged import ClassIV  # type: ignore[import-not-found]
from test_higher_coupled import (  # type: ignore[import-not-found]
    COUPLED,
    SHARED,
    clear,
    fallback_modes,
    random_designs,
)

from assur.kinematics.higher import ClassIVInputs, HigherGroup, assembly_modes, follow_mode

#: Every form with a prismatic internal pair: couplers b, d (internal pairs C–D, F–E), then
#: the external pairs of a and c ("PR RR/RP": C prismatic, c slides on its known link).
EVERY = [f"{b} {d}/{e}" for b in ("RR", "PR", "RP", "PP") for d in ("RR", "PR", "RP", "PP")
         for e in ("RR", "RP", "PR", "PP") if "P" in b + d]


def counts(form: str, d: int) -> tuple[int, int, int] | None:
    """Designs agreeing, set aside, disagreeing; None for a form that is not kinematically
    determinate (two couplers sliding on both their links, or no elimination)."""
    try:
        designs = random_designs(form, 1000 + EVERY.index(form), d)
    except ValueError:
        return None
    if not designs.group.determinate:
        return None
    phi = np.radians(37.0)
    modes = assembly_modes(designs.group, designs.inputs(np.full(d, phi)))
    found = fallback_modes(designs, phi)
    keep = clear(modes)
    same = modes.count == found.count
    return int((keep & same).sum()), int((~keep).sum()), int((keep & ~same).sum())


def speed(form: str, d: int, rounds: int) -> None:
    """Designs/s of all modes and positions/s of one design's cycle, both solvers."""
    designs = random_designs(form, 2000 + SHARED.index(form), d)
    g = designs.group
    plain = ClassIV(g.h_a, g.c, g.f, g.h_c, g.d, g.e, g.u_a, g.u_c)
    k = designs.inputs(np.full(d, np.radians(37.0)))
    one = random_designs(form, 3000 + SHARED.index(form), 1)
    phi = np.radians(np.arange(360.0))
    single = one.group
    single_plain = ClassIV(single.h_a, single.c, single.f, single.h_c, single.d, single.e,
                           single.u_a, single.u_c)
    solvers: tuple[tuple[str, HigherGroup[ClassIVInputs], HigherGroup[ClassIVInputs]], ...] = (
        ("coupled", g, single), ("ClassIV", plain, single_plain))
    for name, group, alone in solvers:
        modes = rate(partial(assembly_modes, group, k), d, rounds)
        cycle = rate(partial(follow_mode, alone, one.inputs, phi), 360, rounds)
        print(f"{form:9s} {name:8s} modes {modes[0]:10.0f} {modes[1]:10.0f} designs/s   "
              f"cycle {cycle[0]:9.0f} {cycle[1]:9.0f} positions/s")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--forms", nargs="*", default=COUPLED,
                        help="forms to count ('all': every form with a prismatic internal pair)")
    parser.add_argument("--no-speed", action="store_true")
    args = parser.parse_args(argv)
    print(f"mode counts at 37°, {args.designs} designs per form: agree / set aside / differ")
    total = np.zeros(3, dtype=int)
    for form in EVERY if args.forms == ["all"] else args.forms:
        start = time.perf_counter()
        found = counts(form, args.designs)
        if found is None:
            print(f"{form:9s} not determinate: refused", flush=True)
            continue
        total += found
        print(f"{form:9s} {found[0]:6d} {found[1]:6d} {found[2]:6d}   "
              f"({time.perf_counter() - start:.1f} s)", flush=True)
    print(f"{'total':9s} {total[0]:6d} {total[1]:6d} {total[2]:6d}")
    if args.no_speed:
        return
    print("speed: median and best of the rounds")
    for form in SHARED:
        speed(form, args.designs, args.rounds)


if __name__ == "__main__":
    main()
