"""The general fallback against the closed forms: agreement of the mode counts and speed.

For each class IV form with revolute internal pairs (revolute; c sliding on a frame guide; a
sliding on a guide of the crank; both sliding) and each triad whose leashes slide on the base
(P–R, P–R, P–R; R–P, P–R, P–R) random crank-driven designs drawn assembled are solved at a
crank angle of 37° by the closed form (``assembly_modes``) and by the fallback's sweep of the
full pose system (``sweep_modes``, 1,440 samples, two sweeps joined), in the same run. The
class IV groups with a prismatic internal pair in both couplers (a–b and c–d, or a–b and
d–a) have their sweep compared with multi-start Newton (300 starts) on the first
``--newton`` designs (their closed form, ``ClassIVCoupled``, is counted against the sweep
by ``bench_coupled.py``). Printed per form: designs, how many lie within 1e-3 of a
birth or merge of modes (set aside), how many of the others disagree, and the designs per
second of each method; against Newton, on how many designs it finds more modes than the
sweep (a mode the sweep missed) and fewer (a mode Newton missed).

    python benchmarks/bench_fallback.py --designs 1000
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "assur"))

from higher_fallback import (
    Joint,
    Motion,
    PoseSystem,
    newton_modes,
    sweep_modes,
)

from assur.kinematics.higher import (
    AssemblyModes,
    ClassIVCoupled,
    ClassIVInputs,
    HigherGroup,
    Triad,
    TriadInputs,
    assembly_modes,
)

FORMS = ("RR", "RP", "PR", "PP")
TRIADS = ("PR-PR-PR", "RP-PR-PR")
COUPLERS = ("PRPR", "PRRP")
Case = tuple[HigherGroup, ClassIVInputs | TriadInputs, PoseSystem, dict[str, Motion]]


def _polar(rng: np.random.Generator, d: int, low: float, high: float) -> np.ndarray:
    return np.asarray(rng.uniform(low, high, d) * np.exp(2j * np.pi * rng.uniform(size=d)))


def _case(form: str, d: int, seed: int) -> Case:
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
    group = ClassIVCoupled(h_a, c, f, h_c, dd, e, u_a, u_c)
    inputs = ClassIVInputs(shift + turn * h_a, h_c, None if u_a is None else u_a * turn, u_c)
    ends = [Joint("P", link, body, h, u) if u is not None else Joint("R", link, body, h)
            for link, body, h, u in ((0, "k", h_a, u_a), (2, "frame", h_c, u_c))]
    system = PoseSystem((ends[0], Joint("R", 0, 1, c), Joint("R", 1, 2, dd),
                         Joint("R", 2, 3, e), Joint("R", 3, 0, f), ends[1]))
    return group, inputs, system, {"k": Motion(shift, turn), "frame": Motion(0.0, 1.0)}


def _triad(kinds: str, d: int, seed: int) -> Case:
    """A triad of the leash kinds (internal pair first), leash 1 on a crank at 37°, leashes
    2, 3 on the frame; a P–R leash slides on a guide of the base through its hinge, an R–P
    one on a guide of its known link through the base's hinge."""
    rng = np.random.default_rng(seed)
    a1 = _polar(rng, d, 8, 15)
    p1 = a1 + _polar(rng, d, 40, 70)
    base = [p1, p1 + _polar(rng, d, 30, 60), p1 + _polar(rng, d, 30, 60)]
    outer = [a1, base[1] + _polar(rng, d, 40, 70), base[2] + _polar(rng, d, 40, 70)]
    leashes = tuple(kinds.split("-"))
    guide = [np.exp(2j * np.pi * rng.uniform(size=d)) for _ in leashes]
    turn = np.exp(1j * np.radians(37.0))
    moved = (turn, 1.0 + 0j, 1.0 + 0j)
    joints = []
    for k, kind in enumerate(leashes):
        if kind == "PR":
            base[k] = outer[k]
            joints += [Joint("P", k + 1, 0, outer[k], guide[k]),
                       Joint("R", k + 1, f"k{k + 1}", outer[k])]
        else:
            outer[k] = base[k]
            joints += [Joint("R", 0, k + 1, base[k]),
                       Joint("P", k + 1, f"k{k + 1}", base[k], guide[k])]
    inputs = TriadInputs((turn * outer[0], outer[1], outer[2]),
                         tuple(u * m if kind == "RP" else None  # type: ignore[arg-type]
                               for u, m, kind in zip(guide, moved, leashes, strict=True)))
    group = Triad(leashes, tuple(base), tuple(outer), tuple(guide))  # type: ignore[arg-type]
    return group, inputs, PoseSystem(tuple(joints)), {f"k{k + 1}": Motion(0.0, moved[k])
                                                      for k in range(3)}


def _couplers(internal: str, d: int, seed: int) -> tuple[PoseSystem, dict[str, Motion]]:
    """A class IV group (H_a on a crank at 37°, H_c on the frame) with the internal pairs
    a–b, b–c, c–d, d–a of the kinds ``internal``, a prismatic one on a guide of random
    direction carried by its second link."""
    _, _, system, known = _case("RR", d, seed)
    rng = np.random.default_rng(seed + 1)
    joints = list(system.joints)
    for k, kind in enumerate(internal, start=1):
        if kind == "P":
            j = joints[k]
            joints[k] = Joint("P", j.first, j.second, j.point,
                              np.exp(2j * np.pi * rng.uniform(size=d)))
    return PoseSystem(tuple(joints)), known


def _aside(modes: AssemblyModes) -> np.ndarray:
    """Designs within 1e-3 of a birth or merge of modes."""
    size = np.abs(np.log(np.abs(modes.roots)))
    near = ((size > 1e-6) & (size < 1e-3)).any(axis=1)
    thin = (np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=1)
    return np.asarray(near | thin)


def _row(form: str, designs: int, aside: int, wrong: int, other: float, swept: float) -> None:
    print(f"{form:>9} {designs:>8} {aside:>10} {wrong:>9} {other:>15,.1f} {swept:>12,.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--newton", type=int, default=100)
    args = parser.parse_args()
    print(f"{'form':>9} {'designs':>8} {'set aside':>10} {'disagree':>9} "
          f"{'closed form /s':>15} {'fallback /s':>12}")
    cases = [(form, _case(form, args.designs, 200 + k)) for k, form in enumerate(FORMS)]
    cases += [(kinds, _triad(kinds, args.designs, 220 + k)) for k, kinds in enumerate(TRIADS)]
    for form, (group, inputs, system, known) in cases:
        start = time.perf_counter()
        modes = assembly_modes(group, inputs)
        closed = time.perf_counter() - start
        start = time.perf_counter()
        found = sweep_modes(system, known)
        swept = time.perf_counter() - start
        aside = _aside(modes)
        wrong = int((~aside & (modes.count != found.count)).sum())
        _row(form, args.designs, int(aside.sum()), wrong, args.designs / closed,
             args.designs / swept)
    print(f"{'form':>9} {'designs':>8} {'Newton +':>10} {'Newton -':>9} "
          f"{'Newton /s':>15} {'fallback /s':>12}")
    for k, internal in enumerate(COUPLERS):
        system, known = _couplers(internal, args.designs, 240 + k)
        start = time.perf_counter()
        found = sweep_modes(system, known)
        swept = time.perf_counter() - start
        few = args.newton
        start = time.perf_counter()
        started = newton_modes(*_first(system, known, few), starts=300)
        newton = time.perf_counter() - start
        more = int((started.count > found.count[:few]).sum())
        fewer = int((started.count < found.count[:few]).sum())
        _row(internal, few, more, fewer, few / newton, args.designs / swept)


def _first(system: PoseSystem, known: dict[str, Motion], n: int
           ) -> tuple[PoseSystem, dict[str, Motion]]:
    """The first n designs."""
    def cut(v: complex | np.ndarray | None) -> complex | np.ndarray | None:
        return v if v is None or np.ndim(v) == 0 else np.asarray(v)[:n]

    joints = tuple(Joint(j.kind, j.first, j.second, np.asarray(cut(j.point)), cut(j.direction))
                   for j in system.joints)
    return PoseSystem(joints), {name: Motion(np.asarray(cut(m.shift)), np.asarray(cut(m.turn)))
                                for name, m in known.items()}

if __name__ == "__main__":
    main()
