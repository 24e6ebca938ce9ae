"""The general fallback (full pose system, one-parameter sweep, multi-start Newton).

Its modes are checked against numbers obtained elsewhere: the published modes of the test
vectors V1–V3 (``higher_groups.md`` §6) and, on seeded random designs, the closed forms'
modes (the RRR and RR-RR-RP triads and the revolute class IV group; the class IV forms with
sliders are compared in ``test_higher_class_iv_sliders.py``). ``ASSUR_HIGHER_FULL=1`` runs
1,000 designs per kind instead of 40.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest
from test_higher_properties import random_class_iv, random_triads
from test_higher_vectors import V1, V1_MODES, V2, V2_MODES, V3, V3_MODES

from assur.kinematics.higher import HigherGroup, Triad, TriadInputs, assembly_modes
from assur.kinematics.higher.fallback import (
    Joint,
    Motion,
    PoseModes,
    PoseSystem,
    newton_modes,
    sweep_modes,
)

FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
COUNTED = 1000 if FULL else 40
STILL = Motion(0.0, 1.0)


def _triad(base: tuple[Any, ...], outer: tuple[Any, ...], slider: Any = None) -> PoseSystem:
    """Base 0 with hinges to leashes 1–3; each leash hinged to its own known link k1–k3 (the
    third sliding on k3's guide of direction ``slider`` through ``outer[2]`` if given)."""
    joints = [Joint("R", 0, k + 1, base[k]) for k in range(3)]
    joints += [Joint("R", k + 1, f"k{k + 1}", outer[k]) for k in range(2)]
    joints.append(Joint("R", 3, "k3", outer[2]) if slider is None
                  else Joint("P", 3, "k3", outer[2], slider))
    return PoseSystem(tuple(joints))


def _class_iv(h_a: Any, c: Any, d: Any, e: Any, f: Any, h_c: Any) -> PoseSystem:
    """a = 0 (H_a on k1), b = 1, c = 2 (H_c on k2), d = 3."""
    return PoseSystem((Joint("R", 0, "k1", h_a), Joint("R", 0, 1, c), Joint("R", 1, 2, d),
                       Joint("R", 2, 3, e), Joint("R", 3, 0, f), Joint("R", 2, "k2", h_c)))


def _still() -> dict[str, Motion]:
    return {f"k{k}": STILL for k in (1, 2, 3)}


def _sorted_points(found: PoseModes, joints: list[int]) -> np.ndarray:
    """The modes' points of the listed joints, ordered by the first joint's x."""
    pts = found.points[: int(found.count)][:, joints]
    return pts[np.argsort(pts[:, 0].real)]


@pytest.mark.parametrize("vector", ["V1", "V2", "V3"])
def test_every_mode_of_the_test_vectors(vector: str) -> None:
    """All real modes at the sketch, to the printed 10 digits (1e-9 of the group's size)."""
    table: Sequence[tuple[Any, ...]]
    if vector == "V1":
        system = _triad((V1["E"], V1["F"], V1["H"]), (V1["D"], V1["G"], V1["I"]))
        table, joints = V1_MODES, [0, 1, 2]
    elif vector == "V2":
        system = _class_iv(V2["B"], V2["C"], V2["D"], V2["E"], V2["F"], V2["G"])
        table, joints = V2_MODES, [1, 2, 3, 4]
    else:
        system = _triad((V3["C"], V3["D"], V3["F"]), (V3["B"], V3["E"], 2 + 52j), 1 + 0j)
        table, joints = V3_MODES, [0, 1, 2]
    found = sweep_modes(system, _still())
    assert int(found.count) == len(table)
    expected = np.array([[complex(*p) for p in row[1:]] for row in table])
    expected = expected[np.argsort(expected[:, 0].real)]
    assert np.abs(_sorted_points(found, joints) - expected).max() <= 1e-9 * float(system.size)


def _robust(modes: Any) -> np.ndarray:
    """Designs away from a birth or merge of modes (no root of p within 1e-3 of the circle,
    off it; no mode with a margin under 1e-3)."""
    size = np.abs(np.log(np.abs(modes.roots)))
    near = ((size > 1e-6) & (size < 1e-3)).any(axis=1)
    thin = (np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=1)
    return ~near & ~thin


def _pr_leash(seed: int, d: int) -> tuple[Triad, TriadInputs, PoseSystem]:
    """Random triads whose third leash is hinged to the frame at A₃ and slides along a guide
    of the base through A₃ (P–R), drawn assembled: the triad, its inputs at the sketch and its
    pose system (leash 3 sliding on the base's guide, carried by the base)."""
    designs = random_triads(seed, d, "RR")
    g = designs.group
    a3 = designs.fixed[1]
    u3 = np.exp(2j * np.pi * np.random.default_rng(seed).uniform(size=d))
    triad = Triad(("RR", "RR", "PR"), (g.base[0], g.base[1], a3), g.external, (None, None, u3))
    joints = [Joint("R", 0, 1, g.base[0]), Joint("R", 0, 2, g.base[1]), Joint("P", 3, 0, a3, u3)]
    joints += [Joint("R", k + 1, f"k{k + 1}", g.external[k]) for k in range(3)]
    return triad, TriadInputs(g.external), PoseSystem(tuple(joints))


@pytest.mark.parametrize("kind", ["RR-RR-RR", "RR-RR-RP", "RR-RR-PR", "IV"])
def test_mode_counts_agree_with_the_closed_forms(kind: str) -> None:
    """The sweep's number of modes equals the eliminant's on random crank-driven designs at
    the sketch (the same designs as ``test_higher_properties``; a P–R third leash on the
    base's guide through its frame hinge)."""
    group: HigherGroup
    if kind == "IV":
        designs = random_class_iv(130, COUNTED)
        group = g = designs.group
        system, inputs = _class_iv(g.h_a, g.c, g.d, g.e, g.f, g.h_c), designs.inputs(np.zeros(
            COUNTED))
    elif kind == "RR-RR-PR":
        group, inputs, system = _pr_leash(125, COUNTED)
    else:
        designs = random_triads(120, COUNTED, kind[-2:])
        group = t = designs.group
        system = _triad(t.base, t.external, designs.fixed[2])
        inputs = designs.inputs(np.zeros(COUNTED))
    modes = assembly_modes(group, inputs)
    found = sweep_modes(system, _still())
    keep = _robust(modes)
    assert keep.mean() >= 0.97
    assert (modes.count[keep] == found.count[keep]).all()
    assert modes.count.max() >= 4


@pytest.mark.parametrize("kind", ["RR-RR-RR", "RR-RR-RP", "IV"])
def test_a_coarse_sweep_still_finds_every_mode(kind: str) -> None:
    """With 90 samples (4° apart; three sweeps joined) roots lie between samples in pairs and
    beside the dyads' limits on many designs; the brackets of pairs and of the joins must still
    find them all (200 designs of each kind against the closed forms)."""
    if kind == "IV":
        designs = random_class_iv(150, 200)
        g = designs.group
        system = _class_iv(g.h_a, g.c, g.d, g.e, g.f, g.h_c)
    else:
        designs = random_triads(160, 200, kind[-2:])
        g = designs.group
        system = _triad(g.base, g.external, designs.fixed[2])
    modes = assembly_modes(g, designs.inputs(np.zeros(200)))
    keep = _robust(modes)
    found = sweep_modes(system, _still(), samples=90, plans_used=3)
    assert (modes.count[keep] == found.count[keep]).all()


def test_newton_from_random_starts_finds_only_modes_of_the_sweep() -> None:
    """Multi-start Newton on the full pose system: every pose it accepts is one of the sweep's
    modes (it may miss some, it adds none), on the test vectors and 10 random class IV groups."""
    designs = random_class_iv(140, 6)
    g = designs.group
    slider = _class_iv(V2["B"], V2["C"], V2["D"], V2["E"], V2["F"], V2["G"]).joints[:5] + (
        Joint("P", 2, "k2", V2["G"], np.exp(1j * np.radians(150.0))),)
    systems = [_class_iv(V2["B"], V2["C"], V2["D"], V2["E"], V2["F"], V2["G"]),
               PoseSystem(slider), _class_iv(g.h_a, g.c, g.d, g.e, g.f, g.h_c)]
    for system in systems:
        known = _still()
        swept, started = sweep_modes(system, known), newton_modes(system, known, starts=120)
        assert started.count.sum() >= 0.5 * swept.count.sum()
        apart = np.abs(started.points[..., :, None, :] - swept.points[..., None, :, :])
        nearest = np.nan_to_num(apart.max(axis=-1), nan=np.inf).min(axis=-1)
        real = ~np.isnan(started.points[..., 0])
        size = np.broadcast_to(np.asarray(system.size)[..., None], real.shape)
        assert (nearest[real] <= 1e-7 * size[real]).all()
