"""The general fallback against the closed forms: agreement of the mode counts and speed.

For each class IV form (revolute; c sliding on a frame guide; a sliding on a guide of the
crank; both sliding) random crank-driven designs drawn assembled are solved at a crank angle
of 37° by the closed form (``assembly_modes``) and by the fallback's sweep of the full pose
system (``sweep_modes``, 1,440 samples, two sweeps joined), in the same run. Printed per
form: designs, how many lie within 1e-3 of a birth or merge of modes (set aside), how many
of the others disagree, and the designs per second of each method.

    python benchmarks/bench_fallback.py --designs 1000
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from assur.kinematics.higher import ClassIV, ClassIVInputs, assembly_modes
from assur.kinematics.higher.fallback import Joint, Motion, PoseSystem, sweep_modes

FORMS = ("RR", "RP", "PR", "PP")


def _polar(rng: np.random.Generator, d: int, low: float, high: float) -> np.ndarray:
    return rng.uniform(low, high, d) * np.exp(2j * np.pi * rng.uniform(size=d))


def _case(form: str, d: int, seed: int) -> tuple[ClassIV, ClassIVInputs, PoseSystem,
                                                 dict[str, Motion]]:
    """The group, its inputs at 37°, its pose system and the known links there. H_a is on a
    crank (a guide of the crank when a slides; when both slide, a guide of a link in circular
    translation), H_c on the frame."""
    rng = np.random.default_rng(seed)
    h_a = _polar(rng, d, 8, 15)
    c, f = h_a + _polar(rng, d, 40, 70), h_a + _polar(rng, d, 40, 70)
    h_c = _polar(rng, d, 90, 110)
    dd, e = h_c + _polar(rng, d, 30, 60), h_c + _polar(rng, d, 30, 60)
    u_a = np.exp(2j * np.pi * rng.uniform(size=d)) if form[0] == "P" else None
    u_c = np.exp(2j * np.pi * rng.uniform(size=d)) if form[1] == "P" else None
    phi = np.radians(37.0)
    if form == "PP":
        shift, turn = rng.uniform(8, 15, d) * (np.exp(1j * phi) - 1.0), np.ones(d) + 0j
    else:
        shift, turn = np.zeros(d) + 0j, np.full(d, np.exp(1j * phi))
    group = ClassIV(h_a, c, f, h_c, dd, e, u_a, u_c)
    inputs = ClassIVInputs(shift + turn * h_a, h_c, None if u_a is None else u_a * turn, u_c)
    ends = [Joint("P", link, body, h, u) if u is not None else Joint("R", link, body, h)
            for link, body, h, u in ((0, "k", h_a, u_a), (2, "frame", h_c, u_c))]
    system = PoseSystem((ends[0], Joint("R", 0, 1, c), Joint("R", 1, 2, dd),
                         Joint("R", 2, 3, e), Joint("R", 3, 0, f), ends[1]))
    return group, inputs, system, {"k": Motion(shift, turn), "frame": Motion(0.0, 1.0)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    args = parser.parse_args()
    print(f"{'form':>5} {'designs':>8} {'set aside':>10} {'disagree':>9} "
          f"{'closed form /s':>15} {'fallback /s':>12}")
    for k, form in enumerate(FORMS):
        group, inputs, system, known = _case(form, args.designs, 200 + k)
        start = time.perf_counter()
        modes = assembly_modes(group, inputs)
        closed = time.perf_counter() - start
        start = time.perf_counter()
        found = sweep_modes(system, known)
        swept = time.perf_counter() - start
        size = np.abs(np.log(np.abs(modes.roots)))
        near = ((size > 1e-6) & (size < 1e-3)).any(axis=1)
        thin = (np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=1)
        keep = ~near & ~thin
        wrong = int((keep & (modes.count != found.count)).sum())
        print(f"{form:>5} {args.designs:>8} {int((~keep).sum()):>10} {wrong:>9} "
              f"{args.designs / closed:>15,.0f} {args.designs / swept:>12,.0f}")


if __name__ == "__main__":
    main()
