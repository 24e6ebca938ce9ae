"""Triads with a P–P leash and no bar on seeded random crank-driven designs.

The P–P leash slides on a guide of the base and on a guide of the crank, so the base turns
with the crank; the other two leashes (R–P or P–R) hang on the crank and on the frame. Each
check compares with a computation written here: the full pose system of the four links (12
unknowns, two equations per pair) solved by Newton's method from many random starts for the
number of modes and the pose, the same pose equations evaluated at the solved positions over
full cycles, central differences of the positions, and the margin of the constraint lines
computed here on a dense grid for the existence. ``ASSUR_HIGHER_FULL=1`` takes more designs.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from higher_checks import random_base

from assur.kinematics import jets as J
from assur.kinematics.higher import Triad, TriadInputs, assembly_modes
from assur.kinematics.higher.groups import expand
from assur.kinematics.higher.pinned import place
from assur.kinematics.jets import Jet

TWO_PI = 2 * np.pi
FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
COUNTED, STARTS, CYCLED, DIFFERENCED = (1000, 16, 60, 12) if FULL else (40, 8, 8, 4)
#: Leash 1 hangs on the crank, leash 2 on the frame, the P–P leash on the crank.
KINDS = ["RP-RP-PP", "RP-PR-PP", "PR-RP-PP", "PR-PR-PP"]


@dataclass
class Designs:
    """Per leash the drawn base point b_k (an R–P hinge, a point of the base's guide of a
    P–R leash drawn at its hinge, the P–P leash's point on the base's guide), the external
    point e_k (the P–R hinge; a point of the known link's guide of R–P and P–P leashes) and
    the guide directions: g_k of the known link's guide (R–P, P–P) or of the base's (P–R),
    h of the P–P leash's guide on the base."""

    kinds: tuple[str, str, str]
    base: tuple[np.ndarray, ...]
    external: tuple[np.ndarray, ...]
    guide: tuple[np.ndarray, ...]
    own: np.ndarray

    @property
    def group(self) -> Triad:
        return Triad(self.kinds, self.base, self.external, self.guide)  # type: ignore[arg-type]

    def inputs(self, phi: Any) -> TriadInputs:
        """The known data at φ of shape (D, N) (or a jet of it): leash 1 and the P–P leash
        on the crank, leash 2 on the frame."""
        turn = J.expi(phi)
        col = [(v[:, None] * t) for v, t in zip(self.external, (turn, 1.0, turn), strict=True)]
        u = [(v[:, None] * t) for v, t in zip(self.guide, (turn, 1.0, turn), strict=True)]
        return TriadInputs((col[0], col[1], col[2]),
                           tuple(u[i] if kind != "PR" else None  # type: ignore[arg-type]
                                 for i, kind in enumerate(self.kinds)))

    def sketch(self) -> TriadInputs:
        return TriadInputs(self.external, tuple(  # type: ignore[arg-type]
            g if kind != "PR" else None for g, kind in zip(self.guide, self.kinds, strict=True)))


def random_designs(seed: int, d: int, kinds: str) -> Designs:
    """Drawn assembled: an R–P guide through its hinge, a P–R hinge on the base's guide, the
    guides of leashes 1 and 2 and the P–P leash's two guides at 20°…160° to each other."""
    rng = np.random.default_rng(seed)
    polar, base, guide = random_base(rng, d)
    guide = (guide[0], guide[0] * np.exp(1j * np.radians(rng.uniform(20, 160, d))), guide[2])
    split = tuple(kinds.split("-"))
    external = tuple(b if kind == "RP" else b + rng.uniform(-30, 30, d) * u
                     for b, u, kind in zip(base[:2], guide[:2], split[:2], strict=True))
    external += (base[2] + polar(10, 30),)
    own = guide[2] * np.exp(1j * np.radians(rng.uniform(30, 150, d)))
    return Designs(split, base, external, guide, own)  # type: ignore[arg-type]


# ----------------------------------------------------------------- the full pose system


def _pairs(designs: Designs) -> list[tuple[str, int, int, np.ndarray, np.ndarray | None]]:
    """Every pair: (type, link X, link Y, drawn point, drawn guide direction on X). Links:
    0 base, 1–3 leashes, -1 the frame, -2 the crank."""
    known = (-2, -1, -2)
    out: list[tuple[str, int, int, np.ndarray, np.ndarray | None]] = []
    for k, kind in enumerate(designs.kinds):
        b, e, g = designs.base[k], designs.external[k], designs.guide[k]
        if kind == "RP":
            out += [("R", 0, k + 1, b, None), ("P", known[k], k + 1, b, g)]
        elif kind == "PR":
            out += [("P", 0, k + 1, b, g), ("R", k + 1, known[k], e, None)]
        else:
            out += [("P", 0, k + 1, b, designs.own), ("P", known[k], k + 1, e, g)]
    return out


def _pose_residual(designs: Designs, poses: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """The 12 pose equations of the group; ``poses`` (..., 4, 3) = (t_x, t_y, θ) of the base
    and the leashes (a point drawn at z is at t + z·e^{iθ}), φ of shape (...)."""
    def pose(link: int) -> tuple[Any, Any]:
        if link == -1:
            return 0.0, 0.0 * phi
        if link == -2:
            return 0.0, phi
        return poses[..., link, 0] + 1j * poses[..., link, 1], poses[..., link, 2]

    out = []
    for kind, x, y, z, u in _pairs(designs):
        (tx, ax), (ty, ay) = pose(x), pose(y)
        zz = z.reshape(z.shape + (1,) * (np.ndim(phi) - 1))
        gap = ty + zz * np.exp(1j * ay) - (tx + zz * np.exp(1j * ax))
        if kind == "R":
            out += [gap.real, gap.imag]
        else:
            assert u is not None
            uu = u.reshape(zz.shape) * np.exp(1j * ax)
            out += [np.broadcast_to(np.angle(np.exp(1j * (ax - ay))), gap.shape),
                    (np.conj(uu) * gap).imag]
    return np.stack(out, axis=-1)


def _brute_force(designs: Designs, phi: np.ndarray, starts: int, seed: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """All poses by Levenberg–Marquardt from ``starts`` random starts per design: the number
    of distinct solutions (the base's pose, angles mod 2π) and the base pose (P₁, θ) of one."""
    rng = np.random.default_rng(seed)
    d = len(phi)
    x = np.concatenate([rng.uniform(-150, 150, (d, starts, 4, 2)),
                        rng.uniform(-np.pi, np.pi, (d, starts, 4, 1))], axis=-1).reshape(d, starts, 12)
    at = np.broadcast_to(phi[:, None], (d, starts))
    h = 1e-6
    for _ in range(25):
        f = _pose_residual(designs, x.reshape(d, starts, 4, 3), at)
        jac = np.stack([(_pose_residual(designs, (x + h * np.eye(12)[i]).reshape(d, starts, 4, 3), at)
                         - f) / h for i in range(12)], axis=-1)
        normal = np.swapaxes(jac, -1, -2) @ jac + 1e-12 * np.eye(12)
        x = x - np.linalg.solve(normal, (np.swapaxes(jac, -1, -2) @ f[..., None]))[..., 0]
    f = _pose_residual(designs, x.reshape(d, starts, 4, 3), at)
    size = np.asarray(designs.group.size)[:, None]
    good = np.abs(f).max(axis=-1) <= 1e-9 * size
    pose = x.reshape(d, starts, 4, 3)[..., 0, :]
    p1 = pose[..., 0] + 1j * pose[..., 1] + designs.base[0][:, None] * np.exp(1j * pose[..., 2])
    key = np.stack([p1, size * np.exp(1j * pose[..., 2])], axis=-1)
    apart = np.abs(key[:, :, None, :] - key[:, None, :, :]).max(axis=-1)
    same = (apart <= 1e-6 * size[..., None]) & good[:, :, None] & good[:, None, :]
    first = good & ~(same & np.tril(np.ones((starts, starts), dtype=bool), -1)).any(axis=2)
    pick = np.argmax(good, axis=1)
    return first.sum(axis=1), np.stack([p1[np.arange(d), pick], pose[np.arange(d), pick, 2]], -1)


@pytest.mark.parametrize("kinds", KINDS)
def test_one_mode_agrees_with_newton_on_the_full_pose_system(kinds: str) -> None:
    """At a random crank angle: the number of distinct poses Newton's method finds from
    random starts is the solver's count (1), and the pose is the solver's mode."""
    designs = random_designs(200 + KINDS.index(kinds), COUNTED, kinds)
    phi = np.random.default_rng(3).uniform(0, TWO_PI, COUNTED)
    k = designs.inputs(phi[:, None])
    k = TriadInputs(tuple(v[:, 0] for v in k.a),  # type: ignore[arg-type]
                    tuple(None if v is None else v[:, 0] for v in k.u))  # type: ignore[arg-type]
    modes = assembly_modes(designs.group, k)
    count, pose = _brute_force(designs, phi, STARTS, 5)
    robust = np.nan_to_num(modes.margin[:, 0], nan=0.0) > 1e-3
    assert robust.mean() >= 0.95
    assert (modes.count[robust] == 1).all() and (count[robust] == 1).all()
    size = np.asarray(designs.group.size)
    p1 = modes.joints["O"][:, 0]
    assert (np.abs(p1 - pose[:, 0])[robust] <= 1e-8 * size[robust]).all()
    turn = np.angle(np.exp(1j * (modes.x[:, 0, 2] - pose[:, 1].real)))
    assert (np.abs(turn[robust]) <= 1e-9).all()
    assert designs.group.degree == 1


def _poses(designs: Designs, solution: Any, phi: np.ndarray) -> np.ndarray:
    """The poses of the four links from the solved joints and rotations (the P–P leash's
    translation from its two guides)."""
    rot = solution.rotations
    theta = rot["base"]
    base = solution.joints["O"] - designs.base[0][:, None] * np.exp(1j * theta)
    k = designs.inputs(phi)
    out = [np.stack([base.real, base.imag, theta], axis=-1)]
    for i, kind in enumerate(designs.kinds):
        angle = rot[f"leash{i + 1}"]
        e = np.exp(1j * angle)
        if kind == "RP":
            t = solution.joints[f"P{i + 1}"] - designs.base[i][:, None] * e
        elif kind == "PR":
            t = k.a[i] - designs.external[i][:, None] * e
        else:
            # the leash's points drawn at b and e on the base's and the crank's guide lines
            b, ext = designs.base[i][:, None], designs.external[i][:, None]
            n1 = 1j * designs.own[:, None] * np.exp(1j * theta)
            n2 = 1j * designs.guide[i][:, None] * np.exp(1j * phi)
            c1 = (np.conj(n1) * (base + b * np.exp(1j * theta) - b * e)).real
            c2 = (np.conj(n2) * (ext * np.exp(1j * phi) - ext * e)).real
            det = (np.conj(n1) * n2).imag
            t = -1j * (c1 * n2 - c2 * n1) / det
        out.append(np.stack([t.real, t.imag, angle], axis=-1))
    return np.stack(out, axis=-2)


@pytest.mark.parametrize("kinds", KINDS)
def test_every_pair_holds_over_the_cycle_and_the_mode_is_the_only_one(kinds: str) -> None:
    """Over the cycle the pose equations of all six pairs hold (to 1e-9 L) wherever the mode
    exists; at a sample of positions the set of all modes has one member, the solved one."""
    designs = random_designs(210 + KINDS.index(kinds), CYCLED, kinds)
    phi = np.broadcast_to(np.radians(np.arange(0.0, 360.0, 5.0)), (CYCLED, 72))
    solution = place(designs.group, designs.sketch(), designs.inputs(phi))
    ok = solution.exists
    assert ok.mean() > 0.9 and ok[:, 0].all()
    size = np.broadcast_to(np.asarray(designs.group.size)[:, None], ok.shape)
    residual = _pose_residual(designs, _poses(designs, solution, phi), phi)
    assert (np.abs(residual[ok]).max(axis=-1) <= 1e-9 * size[ok]).all()
    sample = np.s_[:, ::9]
    modes = assembly_modes(expand(designs.group), designs.inputs(phi[sample]))
    assert (modes.count[ok[sample]] == 1).all()
    apart = np.abs(modes.joints["O"][..., 0] - solution.joints["O"][sample])
    assert (apart[ok[sample]] <= 1e-9 * size[sample][ok[sample]]).all()


@pytest.mark.parametrize("kinds", KINDS)
def test_analogs_against_central_differences(kinds: str) -> None:
    designs = random_designs(220 + KINDS.index(kinds), DIFFERENCED, kinds)
    centre = np.broadcast_to(np.radians([17.0, 95.0, 200.0, 290.0]), (DIFFERENCED, 4))
    h = 1e-5
    k0 = designs.sketch()
    exact = place(designs.group, k0, designs.inputs(Jet(centre, 1.0, 0.0)))
    ahead = place(designs.group, k0, designs.inputs(Jet(centre + h, 1.0, 0.0)))
    behind = place(designs.group, k0, designs.inputs(Jet(centre - h, 1.0, 0.0)))
    ok = exact.exists & ahead.exists & behind.exists & (exact.margin > 0.05)
    assert ok.any()
    size = np.broadcast_to(np.asarray(designs.group.size)[:, None], ok.shape)
    for part in ("joints", "rotations"):
        for name, jet in getattr(exact, part).items():
            plus, minus = getattr(ahead, part)[name], getattr(behind, part)[name]
            unit = size if part == "joints" else 1.0
            for fd, analog in (((plus.v - minus.v) / (2 * h), jet.d1),
                               ((plus.d1 - minus.d1) / (2 * h), jet.d2)):
                error = np.abs(fd - analog) / (np.abs(analog) + unit)
                assert (error[ok] <= 1e-5).all(), (name, error[ok].max())


def _margin(designs: Designs, phi: np.ndarray) -> np.ndarray:
    """The Hadamard ratio of the constraint lines (§1.7) written out: leash 1's and leash 2's
    lines (normal, point) and the P–P leash's line at infinity [0, 0, 1], moments about the
    base's centroid divided by the RMS radius of its points, with the base at θ = φ placed
    by two lines."""
    turn = np.exp(1j * phi)
    known = (turn, np.ones_like(turn), turn)
    normals, points, rhs = [], [], []
    for i, kind in enumerate(designs.kinds[:2]):
        # the hinge on the known link's line (R–P), or the base's line through the hinge
        # (P–R): Re(n̄·P₁) = Re(n̄·(a_k − (b_k − b_1)·e^{iθ}))
        normal = 1j * designs.guide[i][:, None] * (known[i] if kind == "RP" else turn)
        on = designs.external[i][:, None] * known[i] \
            - (designs.base[i] - designs.base[0])[:, None] * turn
        normals.append(normal)
        rhs.append((np.conj(normal) * on).real)
        points.append(kind)
    det = (np.conj(normals[0]) * normals[1]).imag
    p1 = -1j * (rhs[0] * normals[1] - rhs[1] * normals[0]) / det
    corners = [p1 + (b - designs.base[0])[:, None] * turn for b in designs.base]
    centre = sum(corners) / 3
    spread = np.sqrt(sum(np.abs(c - centre) ** 2 for c in corners) / 3)
    rows = []
    for i, kind in enumerate(points):
        at = corners[i] if kind == "RP" else designs.external[i][:, None] * known[i]
        unit = normals[i] / np.abs(normals[i])
        moment = (np.conj(at - centre) * unit).imag / spread
        rows.append(np.stack([unit.real, unit.imag, moment], axis=-1))
    rows.append(np.broadcast_to([0.0, 0.0, 1.0], rows[0].shape))
    matrix = np.stack(rows, axis=-2)
    return np.abs(np.linalg.det(matrix)) / np.prod(np.linalg.norm(matrix, axis=-1), axis=-1)


@pytest.mark.parametrize("kinds", ["RP-RP-PP", "PR-RP-PP"])
def test_existence_agrees_with_a_dense_scan_of_the_lines(kinds: str) -> None:
    """Leash 1's line turns with the crank and leash 2's stays put: twice a turn they are
    parallel and the base runs off. With δ = 0.05, the group exists exactly where the margin
    computed here on a 0.05° grid is ≥ δ; elsewhere the reason is 5 (guides parallel)."""
    designs = random_designs(230 + KINDS.index(kinds), CYCLED, kinds)
    phi = np.broadcast_to(np.radians(np.arange(0.0, 360.0, 0.05)), (CYCLED, 7200))
    delta = 0.05
    solution = place(designs.group, designs.sketch(), designs.inputs(phi), delta=delta)
    scan = _margin(designs, phi)
    clear = np.abs(scan - delta) > 1e-9
    assert (solution.exists == (scan >= delta))[clear].all()
    assert (~solution.exists).any(axis=1).mean() > 0.5
    assert (solution.reason[~solution.exists] == 5).all()
    assert (solution.reason[solution.exists] == 0).all()
    assert np.allclose(solution.margin, scan, atol=1e-9)


TABLE = Path(__file__).parents[2] / "input_tables" / "six_bar_triad_pp_sliders.yaml"
LABEL = "III(2,3,4,5)"


def _example() -> Designs:
    """The triad of ``six_bar_triad_pp_sliders.yaml`` as one design of this file: leash 1 the
    block 2 hinged at C in the crank's slot, leash 2 the leash 3 hinged to the frame at E on
    the base's vertical guide, the P–P leash 5 (base's guide through G4, crank's through G1)."""
    def one(z: complex) -> np.ndarray:
        return np.array([z])

    def unit(degrees: float) -> np.ndarray:
        return np.exp(1j * np.radians(np.array([degrees])))

    return Designs(("RP", "PR", "PP"), (one(42 + 30j), one(70 - 10j), one(20 + 60j)),
                   (one(42 + 30j), one(70 - 10j), one(30 + 70j)),
                   (unit(35.5376778), unit(90.0), unit(120.0)), unit(0.0))


def test_the_example_table_through_the_analysis() -> None:
    """``six_bar_triad_pp_sliders.yaml`` through ``analyse``: one mode at the sketch, every
    pair's pose equation, the joints' analogs against central differences of the analysis,
    the margin against the one written here."""
    from assur.kinematics.analysis import analyse, values
    from assur.kinematics.build import load_model
    from assur.kinematics.higher.kind import HigherGroupSolution

    model = load_model(TABLE)
    centre = np.radians([10.0, 100.0, 190.0, 280.0])
    h = 1e-5
    motion = analyse(model, np.concatenate([centre, centre - h, centre + h]), analogs=True)
    assert np.asarray(motion.exists).all()
    solution = motion.solutions[LABEL]
    assert isinstance(solution, HigherGroupSolution) and len(solution.modes()) == 1
    for pid in ("C", "G4", "G1", "D"):
        jet = J.as_jet(motion.joints[pid] if pid in motion.joints else motion.sliders[pid].point)
        v, d1, d2 = (np.asarray(part).reshape(3, 4) for part in (jet.v, jet.d1, jet.d2))
        assert np.abs((v[2] - v[1]) / (2 * h) - d1[0]).max() <= 1e-6 * 100, pid
        assert np.abs((d1[2] - d1[1]) / (2 * h) - d2[0]).max() <= 1e-6 * 100, pid
    designs = _example()
    phi = np.radians(np.arange(0.0, 360.0, 1.0))
    plain = analyse(model, phi)
    scan = _margin(designs, phi[None, :])[0]
    assert np.abs(np.asarray(values(plain.solutions[LABEL].margin)) - scan).max() <= 1e-9


def test_existence_intervals_of_the_example_against_a_dense_scan() -> None:
    """With δ = 0.4 the example fails where its lines' margin, written here, is below δ: the
    intervals of ``check_existence`` (reason 5, ends bisected) against the crossings of
    δ on a 0.001° grid."""
    from assur.kinematics.build import load_model
    from assur.kinematics.existence import check_existence

    delta = 0.4
    model = load_model(TABLE).with_params({f"{LABEL}.delta": delta})
    report = check_existence(model, points=360)
    (group,) = [g for g in report.groups if g.label == LABEL]
    phi = np.radians(np.arange(0.0, 360.0, 0.001))
    below = _margin(_example(), phi[None, :])[0] < delta
    starts = phi[np.flatnonzero(below & ~np.roll(below, 1))]
    ends = phi[np.flatnonzero(below & ~np.roll(below, -1))]
    assert len(group.intervals) == len(starts) >= 1
    step = np.radians(0.002)
    for interval in group.intervals:
        assert interval.reason == 5
        assert np.abs(np.angle(np.exp(1j * (starts - interval.start)))).min() <= step
        assert np.abs(np.angle(np.exp(1j * (ends - interval.end)))).min() <= step
        assert interval.worst_margin < delta


def test_designs_in_one_call_equal_each_design_alone() -> None:
    """The example with its group's drawn points moved at random (up to 2 mm), three designs
    in one analysis (as the synthesis evaluates them) and each alone."""
    from assur.kinematics.analysis import analyse, values
    from assur.kinematics.build import load_model

    model = load_model(TABLE)
    rng = np.random.default_rng(11)
    varied = {name: value + rng.uniform(-2, 2, (3, 1)) for name, value in model.params.items()
              if name.startswith(LABEL) and (".x_" in name or ".y_" in name)}
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    batch = analyse(model.with_params(varied), phi)
    assert np.asarray(batch.exists).all()
    for i in range(3):
        alone = analyse(model.with_params({n: float(v[i, 0]) for n, v in varied.items()}), phi)
        for pid in ("C", "G4", "G1"):
            apart = np.asarray(values(batch.joints[pid]))[i] - np.asarray(values(alone.joints[pid]))
            assert np.abs(apart).max() <= 1e-9 * 100
