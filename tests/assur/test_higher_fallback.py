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
from higher_fallback import (
    Joint,
    Motion,
    PoseModes,
    PoseSystem,
    newton_modes,
    sweep_modes,
    sweep_plans,
)
from test_higher_properties import _polar, random_class_iv, random_triads
from test_higher_vectors import V1, V1_MODES, V2, V2_MODES, V3, V3_MODES

from assur.kinematics.higher import HigherGroup, Triad, TriadInputs, assembly_modes

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
    return np.asarray(~near & ~thin)


def _leashed(kinds: str, seed: int, d: int) -> tuple[Triad, TriadInputs, PoseSystem,
                                                 dict[str, Motion]]:
    """Random triads of the leash kinds ``kinds`` ("RR-RP-PR": internal pair first), drawn
    assembled, leash 1 on a crank turned by 37°, leashes 2, 3 on the frame: the triad, its
    inputs there, its pose system (an R–P leash slides on a guide of its known link, a P–R
    leash on a guide of the base through its hinge; the prismatic pair drawn at a point of
    its guide up to 30 from the hinge) and the known links."""
    rng = np.random.default_rng(seed)
    a1 = _polar(rng, d, 8, 15)
    p1 = a1 + _polar(rng, d, 40, 70)
    base = [p1, p1 + _polar(rng, d, 30, 60), p1 + _polar(rng, d, 30, 60)]
    outer = [a1, base[1] + _polar(rng, d, 40, 70), base[2] + _polar(rng, d, 40, 70)]
    guide: list[np.ndarray | None] = [None, None, None]
    joints = []
    for k, kind in enumerate(kinds.split("-")):
        u = np.exp(2j * np.pi * rng.uniform(size=d))
        slide = rng.uniform(-30, 30, d) * u
        if kind != "RR":
            guide[k] = u
        if kind == "PR":
            base[k] = outer[k]
            joints.append(Joint("P", k + 1, 0, outer[k] + slide, u))
        else:
            joints.append(Joint("R", 0, k + 1, base[k]))
        if kind == "RP":
            outer[k] = base[k]
            joints.append(Joint("P", k + 1, f"k{k + 1}", outer[k] + slide, u))
        else:
            joints.append(Joint("R", k + 1, f"k{k + 1}", outer[k]))
    leashes = tuple(kinds.split("-"))
    turn = np.exp(1j * np.radians(37.0))
    moved = [turn if k == 0 else 1.0 for k in range(3)]
    inputs = TriadInputs((turn * outer[0], outer[1], outer[2]),
                         tuple(None if u is None or kind != "RP" else u * m for u, kind, m
                               in zip(guide, leashes, moved, strict=True)))  # type: ignore[arg-type]
    known = {f"k{k + 1}": Motion(0.0, moved[k]) for k in range(3)}
    return (Triad(leashes, tuple(base), tuple(outer), tuple(guide)),  # type: ignore[arg-type]
            inputs, PoseSystem(tuple(joints)), known)


@pytest.mark.parametrize("kind", ["RR-RR-RR", "RR-RR-RP", "RR-RR-PR", "IV"])
def test_mode_counts_agree_with_the_closed_forms(kind: str) -> None:
    """The sweep's number of modes equals the eliminant's on random crank-driven designs at
    the sketch (the same designs as ``test_higher_properties``), or with a P–R third leash on
    the base's guide through its frame hinge, the crank turned by 37°."""
    group: HigherGroup
    known = _still()
    if kind == "IV":
        designs = random_class_iv(130, COUNTED)
        group = g = designs.group
        system, inputs = _class_iv(g.h_a, g.c, g.d, g.e, g.f, g.h_c), designs.inputs(np.zeros(
            COUNTED))
    elif kind == "RR-RR-PR":
        group, inputs, system, known = _leashed(kind, 125, COUNTED)
    else:
        designs = random_triads(120, COUNTED, kind[-2:])
        group = t = designs.group
        system = _triad(t.base, t.external, designs.fixed[2])
        inputs = designs.inputs(np.zeros(COUNTED))
    modes = assembly_modes(group, inputs)
    found = sweep_modes(system, known)
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


def _among(some: PoseModes, every: PoseModes, system: PoseSystem) -> bool:
    """Every mode of ``some`` is one of ``every``'s: its joints within 1e-7 L."""
    apart = np.abs(some.points[..., :, None, :] - every.points[..., None, :, :]).max(axis=-1)
    nearest = np.nan_to_num(apart, nan=np.inf).min(axis=-1)
    real = ~np.isnan(some.points[..., 0])
    size = np.broadcast_to(np.asarray(system.size)[..., None], real.shape)
    return bool((nearest[real] <= 1e-7 * size[real]).all())


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
        assert _among(started, swept, system)


SLIDING = 1000 if FULL else 200


def _matched(found: PoseModes, expected: np.ndarray, links: list[int], size: np.ndarray
             ) -> np.ndarray:
    """Per design: every expected mode (rotations e^{iθ} of ``links``, NaN-padded) is within
    1e-7 of one of the found modes' rotations of those links, counted as distances L·|Δe^{iθ}|."""
    turns = np.exp(1j * found.x[..., [3 * k + 2 for k in links]])
    apart = np.abs(expected[..., :, None, :] - turns[..., None, :, :]).max(axis=-1)
    nearest = np.nan_to_num(apart, nan=np.inf).min(axis=-1)
    missing = ~np.isnan(expected[..., 0]) & (nearest > 1e-7)
    return np.asarray(~missing.any(axis=-1) & np.isfinite(size))


def _satisfied(system: PoseSystem, known: dict[str, Motion], found: PoseModes) -> bool:
    """Every mode found satisfies the full pose system to 1e-9 L."""
    wide = PoseSystem(tuple(Joint(j.kind, j.first, j.second, np.asarray(j.point)[..., None],
                                  None if j.direction is None
                                  else np.asarray(j.direction)[..., None])
                            for j in system.joints))
    grown = {n: Motion(np.asarray(m.shift)[..., None], np.asarray(m.turn)[..., None])
             for n, m in known.items()}
    error = np.abs(wide.residual(found.x, grown)).max(axis=-1) / wide.size
    return bool((error[~np.isnan(found.x[..., 0])] <= 1e-9).all())


@pytest.mark.parametrize("kinds", ["PR-PR-PR", "RP-PR-PR"])
def test_triads_with_sliding_internal_pairs_against_the_closed_form(kinds: str) -> None:
    """Triads whose three leashes (P–R) or two of them slide on the base, which have no sweep
    beside two internal hinges: the sweep's modes (dyads closed with prismatic pairs) equal
    the barless triad's closed form in number and base rotation (1e-7), and satisfy the full
    pose system, on 200 random designs (1,000 in the full profile)."""
    group, inputs, system, known = _leashed(kinds, 170, SLIDING)
    assert all(plan.kinds[:2] != "RR" for plan in sweep_plans(system))
    modes = assembly_modes(group, inputs)
    found = sweep_modes(system, known)
    keep = _robust(modes)
    assert keep.mean() >= 0.95
    assert modes.count.max() >= 2
    assert (modes.count[keep] == found.count[keep]).all()
    expected = np.exp(1j * modes.x[..., 2:3])
    assert _matched(found, expected, [0], group.size)[keep].all()
    assert _satisfied(system, known, found)


def _sliding_couplers(internal: str, seed: int, d: int, external: str = "RR"
                      ) -> tuple[PoseSystem, dict[str, Motion]]:
    """Random class IV groups a = 0, b = 1, c = 2, d = 3, H_a on a crank turned by 37°, H_c on
    the frame, the internal pairs a–b, b–c, c–d, d–a of the kinds ``internal``, the external
    pairs of a, c of the kinds ``external`` (a prismatic pair on a guide of random direction
    carried by its second link)."""
    rng = np.random.default_rng(seed)
    h_a = _polar(rng, d, 8, 15)
    c, f = h_a + _polar(rng, d, 40, 70), h_a + _polar(rng, d, 40, 70)
    h_c = _polar(rng, d, 90, 110)
    dd, e = h_c + _polar(rng, d, 30, 60), h_c + _polar(rng, d, 30, 60)
    joints = []
    pairs: tuple[tuple[int, int | str, np.ndarray], ...] = ((0, "crank", h_a), (2, "frame", h_c), (0, 1, c), (1, 2, dd), (2, 3, e), (3, 0, f))
    for (one, two, point), kind in zip(pairs, external + internal, strict=True):
        joints.append(Joint("P", one, two, point, np.exp(2j * np.pi * rng.uniform(size=d)))
                      if kind == "P" else Joint("R", one, two, point))
    known = {"crank": Motion(0.0, np.exp(1j * np.radians(37.0))), "frame": STILL}
    return PoseSystem(tuple(joints)), known


def _quadratic_rows(u: np.ndarray, known: np.ndarray, near: np.ndarray, far: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The condition Im(conj(u·X)·(R + X·W − Y·V)) = 0 (a point of X's link on the guide of
    direction u·X through a point of Y's link), multiplied by 2i·X·Y, as
    a(X)·Y² + b(X)·Y + c(X) = 0; a, b, c as polynomial coefficients in X (lowest first,
    three each, padded). ``known`` = R, ``near`` = W, ``far`` = V."""
    big_a, big_b = np.conj(u) * known, -np.conj(u) * far
    c = (np.conj(u) * near).imag
    zero = np.zeros_like(big_a)
    return (np.stack([big_b, zero, zero], axis=-1),
            np.stack([big_a, 2j * c, -np.conj(big_a)], axis=-1),
            np.stack([zero, zero, -np.conj(big_b)], axis=-1))


def _coupler_modes(system: PoseSystem, known: dict[str, Motion]) -> tuple[np.ndarray,
                                                                        np.ndarray]:
    """The modes of the class IV group with a–b and c–d prismatic (b turning with a, d with
    c), written independently: with X = e^{iθ_a}, Y = e^{iθ_c} the two guide conditions are
    quadratics in Y; the resultant in X (degree ≤ 8), its roots on the unit circle and Y as
    the common root. Returns (e^{iθ_a}, e^{iθ_c}) per mode (NaN-padded, (D, 8, 2)) and the
    designs with a root within 1e-3 of the unit circle, off it (set aside)."""
    j = {(jt.first, jt.second): jt for jt in system.joints}
    h_a, h_c = j[(0, "crank")].point, j[(2, "frame")].point
    at_a, at_c = np.asarray(known["crank"].turn) * h_a, h_c + 0j * h_a
    ab, cd = j[(0, 1)], j[(2, 3)]
    d_pt, f_pt = np.asarray(j[(1, 2)].point), np.asarray(j[(3, 0)].point)
    # a–b: a's point C on b's guide, b = c's point D shifted: R = H_a − H_c, X = θ_a.
    first = _quadratic_rows(np.asarray(ab.direction), at_a - at_c, d_pt - h_a, d_pt - h_c)
    # c–d: c's point E on d's guide, d = a's point F shifted: R = H_c − H_a, X = θ_c.
    second = _quadratic_rows(np.asarray(cd.direction), at_c - at_a, f_pt - h_c, f_pt - h_a)
    out = np.full(np.shape(at_a) + (8, 2), np.nan + 0j)
    doubt = np.zeros(np.shape(at_a), dtype=bool)
    mul = np.polynomial.polynomial.polymul
    for n in range(np.shape(at_a)[0]):
        a1, b1, c1 = (row[n] for row in first)  # in Y = θ_c, coefficients in X = θ_a
        # the second condition has X = θ_c, Y = θ_a: regroup it as a quadratic in θ_c
        a2x, b2x, c2x = (row[n] for row in second)
        a2 = np.array([c2x[2], b2x[2], a2x[2]])  # θ_c² terms, by powers of θ_a
        b2 = np.array([c2x[1], b2x[1], a2x[1]])
        c2 = np.array([c2x[0], b2x[0], a2x[0]])
        ac = np.polynomial.polynomial.polysub(mul(a1, c2), mul(a2, c1))
        ab_ = np.polynomial.polynomial.polysub(mul(a1, b2), mul(a2, b1))
        bc = np.polynomial.polynomial.polysub(mul(b1, c2), mul(b2, c1))
        res = np.polynomial.polynomial.polysub(mul(ac, ac), mul(ab_, bc))
        roots = np.polynomial.polynomial.polyroots(np.trim_zeros(res, "b"))
        with np.errstate(all="ignore"):  # X = 0 is a root of the multiplied equations
            gamma = -np.polynomial.polynomial.polyval(roots, ac) \
                / np.polynomial.polynomial.polyval(roots, ab_)
            off = np.nan_to_num(np.maximum(np.abs(np.log(np.abs(roots))),
                                           np.abs(np.log(np.abs(gamma)))), nan=np.inf)
        real = off < 1e-6
        doubt[n] = ((off >= 1e-6) & (off < 1e-3)).any()
        out[n, : real.sum()] = np.stack([roots[real], gamma[real]], axis=-1)
    return out, doubt


def test_class_iv_with_both_couplers_sliding_against_a_resultant() -> None:
    """The class IV group with a–b and c–d prismatic has no sweep beside two internal hinges:
    the sweep's modes (dyads closed with prismatic pairs) equal, in number and the rotations
    of a and c (1e-7), the roots of a resultant written here, and satisfy the full pose
    system, on 200 random designs (1,000 in the full profile)."""
    system, known = _sliding_couplers("PRPR", 180, SLIDING)
    assert all(plan.kinds[:2] != "RR" for plan in sweep_plans(system))
    expected, doubt = _coupler_modes(system, known)
    found = sweep_modes(system, known)
    keep = ~doubt
    count = (~np.isnan(expected[..., 0])).sum(axis=-1)
    assert keep.mean() >= 0.95
    assert count.max() >= 4
    assert (count[keep] == found.count[keep]).all()
    assert _matched(found, expected, [0, 2], system.size)[keep].all()
    assert _satisfied(system, known, found)


@pytest.mark.parametrize("kind", ["RR-RR-PR", "RP-RP-PR", "PPRR/RR", "RPRR/RP"])
def test_plans_with_prismatic_pairs_give_the_modes_of_the_hinged_plans(kind: str) -> None:
    """On groups that have sweeps beside two internal hinges and sweeps through a prismatic
    internal pair (triads with a P–R leash; class IV groups, internal pairs a–b, b–c, c–d,
    d–a / external pairs of a, c), each of the latter alone finds the modes of two of the
    former joined: the same number and the same joints (1e-7 L) on random designs. Between
    them the groups have every kind of dyad with a prismatic internal pair."""
    if "/" in kind:
        system, known = _sliding_couplers(kind[:4], 190, COUNTED, kind[5:])
    else:
        _, _, system, known = _leashed(kind, 195, COUNTED)
    plans = sweep_plans(system)
    hinged = [plan for plan in plans if plan.kinds[:2] == "RR"]
    sliding = [plan for plan in plans if plan.kinds[:2] != "RR"]
    assert len(hinged) >= 2 and sliding and plans[:len(hinged)] == hinged
    old = sweep_modes(system, known, plans=hinged[:2])
    assert old.count.max() >= 2
    for plan in sliding:
        new = sweep_modes(system, known, plans=[plan])
        assert (old.count == new.count).all(), plan.kinds
        assert _among(old, new, system), plan.kinds


def test_the_groups_compared_have_every_kind_of_dyad() -> None:
    """The groups of the comparison above between them close every dyad kind but P, P, P."""
    systems = [_leashed(kind, 1, 1)[2] for kind in ("RR-RR-PR", "RP-RP-PR")]
    systems += [_sliding_couplers(kind[:4], 1, 1, kind[5:])[0] for kind in ("PPRR/RR",
                                                                             "RPRR/RP")]
    kinds = {plan.kinds for system in systems for plan in sweep_plans(system)}
    assert kinds == {"RRR", "RRP", "RPR", "PRR", "PRP", "RPP", "PPR"}


@pytest.mark.parametrize("internal", ["PRPR", "PRRP"])
def test_newton_finds_only_modes_of_the_sweep_through_sliding_couplers(internal: str) -> None:
    """Multi-start Newton (200 starts) on class IV groups with a prismatic pair on each
    coupler finds no mode the sweep misses, and most of the sweep's (6 designs)."""
    system, known = _sliding_couplers(internal, 200, 6)
    swept, started = sweep_modes(system, known), newton_modes(system, known, starts=200)
    assert started.count.sum() >= 0.9 * swept.count.sum()
    assert _among(started, swept, system)


def test_a_group_of_sliders_only_has_no_sweep() -> None:
    """A class IV group whose every pair is prismatic has no dyad to close: the sweep says
    so (naming the pairs) instead of returning no modes."""
    system, known = _sliding_couplers("PPPP", 210, 1)
    sliders = PoseSystem(tuple(Joint("P", j.first, j.second, j.point, 1j) if j.kind == "R"
                               else j for j in system.joints))
    assert sweep_plans(sliders) == []
    with pytest.raises(ValueError, match="0–crank P"):
        sweep_modes(sliders, known)


def test_a_coarse_sweep_finds_the_roots_beside_a_pole_of_the_slides() -> None:
    """A P, R, P dyad's guides turn parallel twice a turn and its slides pass through
    infinity: with 180 samples roots lie between a sample and the pole on some of 200 designs,
    and the sweep through that dyad alone still finds every mode of the closed form."""
    group, inputs, system, known = _leashed("RP-RP-PR", 196, 200)
    modes = assembly_modes(group, inputs)
    keep = _robust(modes)
    plans = [plan for plan in sweep_plans(system) if plan.kinds == "PRP"]
    found = sweep_modes(system, known, samples=180, plans=plans)
    assert (modes.count[keep] == found.count[keep]).all()
