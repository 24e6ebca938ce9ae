"""Triads without a bar (every leash R–P or P–R) on seeded random crank-driven designs.

Each check compares with a computation written here: the number of real modes by a dense
sweep of the base rotation θ (the base placed by two of its leashes, which are lines for a
fixed θ, and the sign changes of the third leash's offset counted, the method of false
positions), the closure of every leash over full cycles, and central differences of the
positions. ``ASSUR_HIGHER_FULL=1`` takes more designs.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from higher_checks import check_analogs_against_central_differences, random_base

from assur.kinematics import jets as J
from assur.kinematics.higher import Triad, TriadInputs, assembly_modes, follow_mode

TWO_PI = 2 * np.pi
FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
COUNTED, CYCLED, DIFFERENCED = (1000, 60, 12) if FULL else (100, 4, 4)
KINDS = ["RP-RP-RP", "PR-PR-PR", "RP-RP-PR", "RP-PR-PR"]


@dataclass
class Designs:
    """A triad whose first leash hangs on a crank (pivot at the origin), the others on the
    frame: per leash the drawn base point b_k, the external point a_k (the hinge A_k of a
    P–R leash, the guide point Q_k of an R–P leash) and the guide direction u_k."""

    kinds: tuple[str, str, str]
    base: tuple[np.ndarray, ...]
    external: tuple[np.ndarray, ...]
    guide: tuple[np.ndarray, ...]

    @property
    def group(self) -> Triad:
        return Triad(self.kinds, self.base, self.external, self.guide)  # type: ignore[arg-type]

    def known(self, phi: Any) -> tuple[list[Any], list[Any]]:
        """a_k(φ) and u_k(φ): the crank turns the first leash's point and guide."""
        turn = J.expi(phi)
        a = [self.external[0] * turn, self.external[1], self.external[2]]
        u = [self.guide[0] * turn, self.guide[1], self.guide[2]]
        return a, u

    def inputs(self, phi: Any) -> TriadInputs:
        a, u = self.known(phi)
        return TriadInputs((a[0], a[1], a[2]),
                           tuple(u[i] if kind == "RP" else None  # type: ignore[arg-type]
                                 for i, kind in enumerate(self.kinds)))


def random_designs(seed: int, d: int, kinds: str) -> Designs:
    """Drawn assembled: an R–P leash's guide passes through its base hinge, a P–R leash's
    hinge lies on the base's guide through its base point."""
    rng = np.random.default_rng(seed)
    _, base, guide = random_base(rng, d)
    external = tuple(b if kind == "RP" else b + rng.uniform(-30, 30, d) * u
                     for b, u, kind in zip(base, guide, kinds.split("-"), strict=True))
    return Designs(tuple(kinds.split("-")), base, external, guide)  # type: ignore[arg-type]


def _offsets(designs: Designs, p1: np.ndarray, e: np.ndarray, a: list[Any], u: list[Any]
             ) -> list[np.ndarray]:
    """The offset of each leash from its line: an R–P hinge from the known link's guide, a
    P–R hinge A_k from the base's guide, the base placed at P₁ and turned by e."""
    out = []
    for k, kind in enumerate(designs.kinds):
        point = p1 + (designs.base[k] - designs.base[0])[..., None] * e
        if kind == "RP":
            out.append(np.asarray(J.cross(u[k], point - a[k])))
        else:
            out.append(np.asarray(J.cross(designs.guide[k][..., None] * e, a[k] - point)))
    return out


def _swept(designs: Designs, samples: int = 8192) -> np.ndarray:
    """The real modes at the sketch by sign changes of one leash's offset along θ.

    For each θ two leashes are lines in P₁ (Re(n̄·P₁) = c) and P₁ is their crossing; the
    offset of the third leash from its line changes sign at a mode. Of the three choices of
    the last leash, the one whose two lines stay least parallel over θ is taken. A sign
    change across a pole (the two lines parallel) has large values on both sides, a root
    small ones: a change counts where both values lie under the median size.
    """
    theta = (np.arange(samples) + 0.5) * TWO_PI / samples  # the drawn θ = 0 between samples
    e = np.exp(1j * theta)[None, :]
    a, u = designs.known(0.0)
    normals, rhs = [], []
    for k in range(3):
        s = (designs.base[k] - designs.base[0])[:, None] * e
        normal = np.broadcast_to(1j * u[k][:, None] if designs.kinds[k] == "RP"
                                 else 1j * designs.guide[k][:, None] * e, s.shape)
        normals.append(normal)
        rhs.append((np.conj(normal) * (a[k][:, None] - s)).real)
    counts, widest = [], []
    for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        det = (np.conj(normals[i]) * normals[j]).imag
        # P₁ on both lines Re(n̄·(P₁ + s)) = Re(n̄·a): Re(n̄₁P₁) = c₁, Re(n̄₂P₁) = c₂
        p1 = -1j * (rhs[i] * normals[j] - rhs[j] * normals[i]) / det
        offsets = _offsets(designs, p1, e, [v[:, None] for v in a], [v[:, None] for v in u])
        last = offsets[k]
        after = np.roll(last, -1, axis=1)
        typical = np.median(np.abs(last), axis=1, keepdims=True)
        change = (np.sign(last) != np.sign(after)) & (np.abs(last) + np.abs(after) < typical)
        counts.append(change.sum(axis=1))
        widest.append(np.abs(det).min(axis=1))
    choice = np.argmax(widest, axis=0)
    return np.asarray(np.take_along_axis(np.stack(counts), choice[None, :], axis=0)[0])


@pytest.mark.parametrize("kinds", KINDS)
def test_mode_count_agrees_with_a_sweep_of_the_base_rotation(kinds: str) -> None:
    designs = random_designs(60 + KINDS.index(kinds), COUNTED, kinds)
    modes = assembly_modes(designs.group, designs.inputs(np.zeros(COUNTED)))
    size = np.abs(np.log(np.abs(modes.roots)))
    robust = ~((size > 1e-6) & (size < 1e-3)).any(axis=1) \
        & ~(np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=1)
    assert robust.mean() >= 0.95
    swept = _swept(designs)
    assert (swept[robust] == modes.count[robust]).all()
    degree = designs.group.degree
    assert degree == (1 if len(set(designs.kinds)) == 1 else 2)
    assert set(modes.count.tolist()) <= set(range(0, 2 * degree + 1, 2))
    assert modes.count.max() == 2 * degree


@pytest.mark.parametrize("kinds", KINDS)
def test_every_leash_stays_closed_over_the_cycle(kinds: str) -> None:
    """Over the cycle every leash stays on its line (to 1e-9 L) wherever the mode exists."""
    designs = random_designs(70 + KINDS.index(kinds), CYCLED, kinds)
    phi = np.radians(np.arange(0.0, 360.0, 10.0))
    solution = follow_mode(designs.group, designs.inputs, phi)
    ok = solution.exists
    assert ok.any(axis=1).all()
    turn = np.exp(1j * phi)
    a = [np.broadcast_to(v[:, None] * t, ok.shape)
         for v, t in zip(designs.external, (turn, 1.0, 1.0), strict=True)]
    u = [np.broadcast_to(v[:, None] * t, ok.shape)
         for v, t in zip(designs.guide, (turn, 1.0, 1.0), strict=True)]
    x = solution.x
    p1 = a[0] + x[..., 0] + 1j * x[..., 1]
    e = np.exp(1j * x[..., 2])
    size = np.broadcast_to(np.asarray(designs.group.size)[:, None], ok.shape)
    for offset in _offsets(designs, p1, e, a, u):
        assert (np.abs(offset[ok]) <= 1e-9 * size[ok]).all()
    assert np.allclose(solution.rotations["base"][ok], x[..., 2][ok])


@pytest.mark.parametrize("kinds", KINDS)
def test_analogs_against_central_differences(kinds: str) -> None:
    designs = random_designs(80 + KINDS.index(kinds), DIFFERENCED, kinds)
    check_analogs_against_central_differences(designs.group, designs.inputs, DIFFERENCED)


def test_the_example_table_keeps_its_blocks_on_their_guides() -> None:
    """``six_bar_triad_sliders.yaml``: 2 modes at the sketch; over the turn C stays on the
    crank's slot, D on y = −10, F on x = 5 and the base's distances constant."""
    from assur.kinematics.analysis import analyse, values
    from assur.kinematics.build import load_model
    from assur.kinematics.higher.kind import HigherGroupSolution

    table = Path(__file__).parents[2] / "input_tables" / "six_bar_triad_sliders.yaml"
    model = load_model(table)
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    motion = analyse(model, phi)
    assert motion.exists.all()
    c, d, f = (np.asarray(values(motion.joints[p])) for p in "CDF")
    slot = np.exp(1j * (np.radians(35.5376778) + phi))
    offset = (np.conj(slot) * (c - (42 + 30j) * np.exp(1j * phi))).imag
    assert np.abs(offset).max() < 1e-9
    assert np.abs(d.imag + 10).max() < 1e-9 and np.abs(f.real - 5).max() < 1e-9
    for p, q, p0, q0 in ((c, d, 42 + 30j, 55 - 10j), (c, f, 42 + 30j, 5 + 45j),
                         (d, f, 55 - 10j, 5 + 45j)):
        assert np.abs(np.abs(p - q) - abs(p0 - q0)).max() < 1e-9
    solution = motion.solutions["III(2,3,4,5)"]
    assert isinstance(solution, HigherGroupSolution) and len(solution.modes()) == 2


MIXES = [f"{a}-{b}-{c}" for a in ("RP", "PR") for b in ("RP", "PR") for c in ("RP", "PR")]
#: The same check with a bar first (the base's frame is then on the bar's hinge).
BARRED = ["RR-RR-RR", "RR-RP-PR", "RR-PR-RP", "RR-RR-PP", "RR-PR-PP"]
#: And without a bar beside a P–P leash (the base's frame on its first leash's point).
PINNED = ["RP-PR-PP", "PR-RP-PP"]


def _table(mix: str, rng: np.random.Generator) -> dict[str, Any]:
    """A crank 1 (O–A) driving a triad: base 5 with the internal pairs B, C, D (listed in
    that order, so the first leash in pair order is ``mix[:2]``); leash 2 hangs on the crank
    (A), leashes 3 and 4 on the frame (E, F). RR: two hinges; RP: a block hinged to the base
    sliding on the known link; PR: a leash hinged to the known link sliding on a guide of the
    base; PP: both."""
    a = 12.0 * np.exp(1j * rng.uniform(0, TWO_PI))
    inner = [complex(*rng.uniform(60, 120, 2)) + 40 * np.exp(1j * t)
             for t in rng.uniform(0, TWO_PI) + np.array([0.0, 2.1, 4.2])]
    pairs: list[dict[str, Any]] = [{"id": "O", "type": "R", "links": [0, 1]}]
    geometry: dict[str, Any] = {"O": {"point": [0, 0]}, "input": {"rotation": "ccw"}}
    for k, (pin, pout, known) in enumerate((("B", "A", 1), ("C", "E", 0), ("D", "F", 0))):
        leash, drawn = k + 2, inner[k]
        outer = a if k == 0 else drawn + complex(*rng.uniform(-40, 40, 2))
        into: dict[str, Any] = {"id": pin, "type": "R", "links": [leash, 5]}
        out: dict[str, Any] = {"id": pout, "type": "R", "links": [leash, known]}
        direction = float(rng.uniform(-180, 180))
        if mix[3 * k + 1] == "P":
            out.update(type="P", guide=known)
        if mix[3 * k] == "P":
            into.update(type="P", guide=5)
        own = direction + float(rng.uniform(30, 150)) * (mix[3 * k:3 * k + 2] == "PP")
        geometry[pin] = {"point": [drawn.real, drawn.imag], "direction": own}
        geometry[pout] = {"point": [outer.real, outer.imag], "direction": direction}
        pairs += [into, out]
    return {"mechanism": {"pairs": pairs, "inputs": [1]}, "geometry": geometry}


def _base_turns_rigidly(mix: str, seed: int) -> int:
    """Check one random design of the leash mix; the number of positions checked where the
    base has moved."""
    from assur.io.chain_table import chain_from_dict
    from assur.kinematics.analysis import analyse, values
    from assur.kinematics.build import build_model
    from assur.structure.analysis import analyse_structure

    rng = np.random.default_rng(1000 * (MIXES + BARRED + PINNED).index(mix) + seed)
    table = _table(mix, rng)
    geometry = table["geometry"]
    model = build_model(analyse_structure(chain_from_dict(table)))
    layout = model.groups[-1].layout
    assert layout is not None and layout.leashes == tuple(mix.split("-"))
    motion = analyse(model, np.radians(np.arange(0.0, 360.0, 10.0)))
    ok = np.asarray(motion.exists)
    assert ok[0]
    origin, angle = (np.asarray(values(v)) for v in motion.frames[5])

    def drawn(pid: str) -> complex:
        return complex(*geometry[pid]["point"])

    def carried(z: complex) -> np.ndarray:
        return np.asarray(origin + (z - origin[0]) * np.exp(1j * (angle - angle[0])))

    scale = max(abs(drawn(p) - drawn(q)) for p in "ABCDEF" for q in "ABCDEF")
    extra = drawn("B") + complex(*rng.uniform(-50, 50, 2))
    for k, (pin, pout) in enumerate((("B", "A"), ("C", "E"), ("D", "F"))):
        kind = mix[3 * k:3 * k + 2]
        if kind[0] == "R":
            hinge = np.asarray(values(motion.joints[pin]))
            assert np.abs(carried(drawn(pin)) - hinge)[ok].max() <= 1e-9 * scale
            far = np.abs(np.abs(carried(extra) - hinge) - abs(extra - drawn(pin)))
            assert far[ok].max() <= 1e-9 * scale
        else:  # the slider on the base's guide through the base point drawn at P_k⁰
            start = pin if kind == "PP" else pout
            hinge = np.asarray(values(motion.joints[start]))
            along = np.exp(1j * (np.radians(geometry[pin]["direction"]) + angle - angle[0]))
            on = carried(drawn(start))
            off = np.imag(np.conj(along) * (hinge - on))
            assert np.abs(off)[ok].max() <= 1e-9 * scale
            line = np.asarray(values(motion.sliders[pin].base))
            assert np.abs(line - on)[ok].max() <= 1e-9 * scale
    return int((ok & (np.abs(carried(extra) - extra) > 0.01 * scale)).sum())


@pytest.mark.parametrize("mix", MIXES + BARRED + PINNED)
def test_the_base_frame_carries_the_base_rigidly(mix: str) -> None:
    """Points carried by the base's frame, z(φ) = O(φ) + (z⁰ − O(0))·e^{i(θ(φ) − θ(0))}, stay
    on the base over the cycle (to 1e-9 L): the base's hinges (R–P leashes) land on the
    solved hinges (R–R, R–P leashes), an arbitrary carried point keeps its drawn distances to them, and the hinge
    of a P–R leash (the inner slider of a P–P leash) stays on the base's guide carried the same way, whose point drawn at the
    hinge is the slider's guide point (fixed on the base)."""
    assert sum(_base_turns_rigidly(mix, seed) for seed in range(2)) >= 4
