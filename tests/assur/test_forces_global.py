"""The group-by-group kinetostatics against one global Newton–Euler solve of all links at once.

For random designs of a mechanism with each dyad kind (input crank + one dyad of kind L1…L5)
with random masses, centres, moments of inertia, forces, torques and gravity, the test writes
the three equilibrium equations of every moving link (d'Alembert) in every pair's reaction
components and the driving torque, and solves that square system at every position with
``numpy.linalg.solve``. The centres' accelerations are built here from the joints and guide
directions of the motion (not from the link frames the library uses). The two solutions agree
to 1e-9 relative; the power balance and every link's residual hold at every assembled position.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import assur
from assur.forces import ForceData, Load, Mass, kinetostatics
from assur.kinematics import jets as J
from assur.kinematics.analysis import analyse
from assur.kinematics.jets import Jet

MM = 1e-3
OMEGA = 12.0
PHI = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
DESIGNS = 12

#: Crank + one dyad of each kind: pairs (id, type, links, guide).
CHAINS = {
    "L1": [("A", "R", [0, 1], None), ("B", "R", [1, 2], None), ("C", "R", [2, 3], None),
           ("D", "R", [3, 0], None)],
    "L2": [("A", "R", [0, 1], None), ("B", "R", [1, 2], None), ("C", "R", [2, 3], None),
           ("D", "P", [3, 0], 0)],
    "L3": [("A", "R", [0, 1], None), ("B", "R", [1, 2], None), ("C", "P", [2, 3], 3),
           ("D", "R", [3, 0], None)],
    "L4": [("A", "R", [0, 1], None), ("B", "P", [1, 2], 1), ("C", "R", [2, 3], None),
           ("D", "P", [0, 3], 0)],
    "L5": [("A", "R", [0, 1], None), ("B", "R", [1, 2], None), ("C", "P", [2, 3], 3),
           ("D", "P", [3, 0], 0)],
}


def _sketch(kind: str, rng: np.random.Generator) -> dict:
    """A random sketch of the chain of ``kind`` (mm, degrees)."""
    def point(lo: float, hi: float) -> list[float]:
        r, a = rng.uniform(lo, hi), rng.uniform(0, 2 * math.pi)
        return [r * math.cos(a), r * math.sin(a)]

    a = [0.0, 0.0]
    b = point(20, 45)
    c = [b[0] + rng.uniform(60, 120), b[1] + rng.uniform(-60, 60)]
    d = [c[0] + rng.uniform(-40, 40), c[1] + rng.uniform(-100, -40)]
    angle = float(rng.uniform(-180, 180))
    geometry: dict = {"A": {"point": a}, "B": {"point": b}, "C": {"point": c},
                      "D": {"point": d}, "input": {"rotation": str(rng.choice(["ccw", "cw"]))}}
    if kind == "L2":
        geometry["D"] = {"point": c, "direction": angle}
    elif kind == "L3":
        geometry["C"] = {"point": b, "direction": angle}
    elif kind == "L4":
        geometry["B"] = {"point": c, "direction": angle}
        geometry["D"] = {"point": c, "direction": angle + float(rng.uniform(30, 150))}
    elif kind == "L5":
        geometry["C"] = {"point": b, "direction": angle}
        geometry["D"] = {"point": d, "direction": angle + float(rng.uniform(30, 150))}
    return geometry


def _design(kind: str, seed: int) -> tuple[assur.KinematicModel, ForceData]:
    rng = np.random.default_rng(seed)
    pairs = [{"id": i, "type": t, "links": links, **({"guide": g} if g is not None else {})}
             for i, t, links, g in CHAINS[kind]]
    data = {"mechanism": {"pairs": pairs, "inputs": [{"link": 1}]},
            "geometry": _sketch(kind, rng)}
    model = assur.build_model(assur.analyse_structure(assur.chain_from_dict(data)))

    def near() -> complex:
        return complex(*rng.uniform(-80, 160, 2))

    masses = {link: Mass(float(rng.uniform(0.1, 2.0)), near(), float(rng.uniform(0, 5e-3)))
              for link in (1, 2, 3)}
    loads = (Load(3, force=complex(*rng.uniform(-500, 500, 2)), point=near()),
             Load(2, force=complex(*rng.uniform(-200, 200, 2)), point=near()),
             Load(2, torque=float(rng.uniform(-20, 20))),
             Load(3, torque=float(rng.uniform(-20, 20))))
    gravity = complex(*rng.uniform(-10, 10, 2))
    return model, ForceData(masses, loads, gravity)


def _frames(motion: assur.Motion) -> dict:
    """Per moving link: a point fixed on it and its angle (jets), from the joints and guides.

    A link's fixed points are its hinges and the slider point of every prismatic pair in
    which it is the slider; its angle is a guide direction of one of its prismatic pairs, or
    the direction between two of its hinges.
    """
    model = motion.model
    out = {}
    for link in motion.frames:
        if link == model.frame:
            continue
        points, angles = [], []
        for pid, (kind, links, _) in model.pair_links.items():
            if link not in links:
                continue
            if kind == "R":
                points.append(motion.joints[pid])
            else:
                slider = motion.sliders[pid]
                angles.append(slider.angle)
                if slider.slider == link:
                    points.append(slider.point)
        if angles:
            out[link] = (points[0], angles[0])
        else:
            out[link] = (points[0], J.arg(points[1] - points[0]))
    return out


def _fixed(frames: dict, frames0: dict, link, x: complex) -> Jet:
    """A point fixed on ``link`` sketched at ``x`` (mm), in m with its analogs."""
    p, theta = frames[link]
    p0, theta0 = frames0[link]
    w = (x - p0.v) * np.exp(-1j * theta0.v)
    return (p + w * J.expi(theta)) * MM


def _global(motion: assur.Motion, data: ForceData, omega: float, sketched: float = 0.0) -> dict:
    """Every pair's reaction and the drive from one linear system per position.

    The drive is a torque on the crank, or for an actuator (whose length at the sketch is
    ``sketched``) a force pushing its two hinges apart.
    """
    model = motion.model
    frames = _frames(motion)
    at = np.flatnonzero(np.asarray(motion.q) == sketched)[:1]
    if at.size:   # the sketched position is among the analysed ones
        frames0 = {link: tuple(Jet(j.v[at], j.d1[at], j.d2[at]) for j in pose)
                   for link, pose in frames.items()}
    else:
        frames0 = _frames(analyse(model, np.array([sketched]), analogs=True))
    links = sorted(frames)
    row = {link: 3 * k for k, link in enumerate(links)}
    pairs = list(model.pair_links)
    column = {pid: 2 * k for k, pid in enumerate(pairs)}
    size = 3 * len(links)
    assert 2 * len(pairs) + 1 == size
    n_pos = motion.q.size
    a = np.zeros((n_pos, size, size))
    rhs = np.zeros((n_pos, size))
    for pid, (kind, (first, second), _) in model.pair_links.items():
        c = column[pid]
        if kind == "R":
            point = motion.joints[pid].v * MM
        else:
            point = motion.sliders[pid].point.v * MM
            n = 1j * np.exp(1j * motion.sliders[pid].angle.v)
        for link, sign in ((second, 1.0), (first, -1.0)):
            if link not in row:
                continue
            r = row[link]
            if kind == "R":  # unknowns Rx, Ry at the hinge
                a[:, r, c] += sign
                a[:, r + 1, c + 1] += sign
                a[:, r + 2, c] += -sign * point.imag
                a[:, r + 2, c + 1] += sign * point.real
            else:  # unknowns N (along n) at K and the couple M
                a[:, r, c] += sign * n.real
                a[:, r + 1, c] += sign * n.imag
                a[:, r + 2, c] += sign * (point.real * n.imag - point.imag * n.real)
                a[:, r + 2, c + 1] += sign
    if model.drive == "crank":
        a[:, row[model.groups[0].i] + 2, size - 1] = 1.0
    else:
        pid = next(p for p, (kind, links, _) in model.pair_links.items()
                   if kind == "P" and model.links[links[0]] == model.links[links[1]])
        slider = motion.sliders[pid]
        hinges = {link: next(motion.joints[p].v for p, (kind, links, _) in
                             model.pair_links.items() if kind == "R" and link in links)
                  for link in (slider.carrier, slider.slider)}
        e = hinges[slider.slider] - hinges[slider.carrier]
        e = e / np.abs(e)
        k = slider.point.v * MM
        for link, sign in ((slider.slider, 1.0), (slider.carrier, -1.0)):
            r = row[link]
            a[:, r, size - 1] += sign * e.real
            a[:, r + 1, size - 1] += sign * e.imag
            a[:, r + 2, size - 1] += sign * (k.real * e.imag - k.imag * e.real)
    w2 = omega * omega

    def known(link, force, point, torque) -> None:
        r = row[link]
        rhs[:, r] -= force.real
        rhs[:, r + 1] -= force.imag
        rhs[:, r + 2] -= point.real * force.imag - point.imag * force.real + torque

    for link, mass in data.masses.items():
        centre = _fixed(frames, frames0, link, mass.centre)
        force = mass.mass * data.gravity - mass.mass * w2 * centre.d2
        known(link, force, centre.v, -mass.inertia * w2 * frames[link][1].d2)
    for load in data.loads:
        if load.torque is not None:
            known(load.link, np.zeros(n_pos, complex), np.zeros(n_pos, complex),
                  load.torque + np.zeros(n_pos))
        else:
            point = _fixed(frames, frames0, load.link, load.point)
            known(load.link, load.force + np.zeros(n_pos, complex), point.v, np.zeros(n_pos))
    ok = np.all(np.isfinite(a), axis=(1, 2)) & np.all(np.isfinite(rhs), axis=1)
    x = np.full((n_pos, size), np.nan)
    x[ok] = np.linalg.solve(a[ok], rhs[ok][..., None])[..., 0]
    return {"driving": x[:, -1], **{pid: (x[:, column[pid]], x[:, column[pid] + 1])
                                    for pid in pairs}}


def worst(motion: assur.Motion, result, expected: dict, solved: np.ndarray
          ) -> tuple[float, float, float]:
    """The largest differences from the global solve where solved, relative: of the forces
    (to the largest force), of the moments and the drive (to the largest moment plus the
    largest force times the mechanism's size), and the power balance (to its scale)."""
    forces, moments = [], [(result.driving, expected["driving"])]
    for pid, (kind, _, _) in motion.model.pair_links.items():
        reaction = result.reactions[pid]
        first, second = expected[pid]
        if kind == "R":
            forces += [(reaction.x, first), (reaction.y, second)]
        else:
            forces.append((reaction.normal, first))
            moments.append((reaction.moment, second))
    length = max(np.max(np.abs(motion.joints[p].v[solved])) for p in motion.joints) * MM
    force_scale = np.max([np.abs(want[solved]) for _, want in forces], axis=0)
    moment_scale = np.max([np.abs(want[solved]) for _, want in moments], axis=0)
    moment_scale = moment_scale + force_scale * length
    force = max(np.max(np.abs(got[solved] - want[solved]) / force_scale)
                for got, want in forces)
    moment = max(np.max(np.abs(got[solved] - want[solved]) / moment_scale)
                 for got, want in moments)
    balance = np.max(np.abs(result.power_balance[solved]) / result.power_scale[solved])
    return float(force), float(moment), float(balance)


def agrees(motion: assur.Motion, result, expected: dict, solved: np.ndarray,
           balance: float) -> None:
    """Reactions and drive equal to the global solve to 1e-9 relative, the power balance to
    ``balance`` relative (:func:`worst`)."""
    force, moment, power = worst(motion, result, expected, solved)
    assert force <= 1e-9 and moment <= 1e-9 and power <= balance, (force, moment, power)


@pytest.mark.parametrize("kind", list(CHAINS))
def test_group_solution_equals_the_global_solve(kind: str) -> None:
    compared = 0
    for seed in range(DESIGNS):
        model, data = _design(kind, seed)
        assert model.groups[1].kind == int(kind[1])
        motion = analyse(model, PHI, analogs=True)
        result = kinetostatics(motion, data, OMEGA)
        with np.errstate(invalid="ignore"):  # NaN where the design does not assemble
            expected = _global(motion, data, OMEGA)
        solved = result.reason == 0
        assert np.array_equal(solved, motion.exists), seed
        agrees(motion, result, expected, solved, 1e-10)
        for residual in result.residuals.values():
            assert np.max(residual.force[solved], initial=0) <= 1e-10
            assert np.max(residual.moment[solved], initial=0) <= 1e-10
        compared += int(solved.sum())
    assert compared > DESIGNS * PHI.size / 3


def test_a_batch_of_designs_equals_the_loop_over_them() -> None:
    model, data = _design("L1", 3)
    lengths = model.params["L1(2,3).l_i"] * np.linspace(0.97, 1.03, 5)
    batch = model.with_params({"L1(2,3).l_i": lengths[:, None]})
    together = kinetostatics(analyse(batch, PHI, analogs=True), data, OMEGA)
    for k, length in enumerate(lengths):
        single = model.with_params({"L1(2,3).l_i": length})
        alone = kinetostatics(analyse(single, PHI, analogs=True), data, OMEGA)
        np.testing.assert_allclose(together.driving[k], alone.driving, rtol=1e-12, atol=1e-12)
        for pid, reaction in alone.reactions.items():
            np.testing.assert_allclose(together.reactions[pid].x[k], reaction.x, rtol=1e-12,
                                       atol=1e-9)


def test_a_wrong_reaction_shows_in_the_residuals_of_its_two_links() -> None:
    model, data = _design("L2", 1)
    result = kinetostatics(analyse(model, PHI, analogs=True), data, OMEGA)
    solved = result.reason == 0
    wrong = dataclasses.replace(result.reactions["B"], x=result.reactions["B"].x * (1 + 1e-6))
    broken = dataclasses.replace(result, reactions={**result.reactions, "B": wrong})
    for link, residual in broken.residuals.items():
        worst = np.max(residual.force[solved])
        assert (worst > 1e-8) == (link in (1, 2)), link


def _boom(seed: int) -> tuple[assur.KinematicModel, ForceData, float]:
    """A random boom lifted by a hydraulic cylinder (2) with its rod (3): the input is the
    cylinder's own prismatic pair; returns the model, loads and the sketched length."""
    rng = np.random.default_rng(seed)
    b = complex(*rng.uniform(60, 140, 2)) * complex(1, -0.5)
    c = complex(rng.uniform(120, 200), rng.uniform(30, 90))
    length = abs(c - b)
    data = {"mechanism": {"pairs": [{"id": "A", "type": "R", "links": [0, 1]},
                                    {"id": "B", "type": "R", "links": [0, 2]},
                                    {"id": "Pd", "type": "P", "links": [2, 3], "guide": 2},
                                    {"id": "C", "type": "R", "links": [3, 1]}],
                          "inputs": [{"pair": "Pd"}]},
            "geometry": {"A": {"point": [0, 0]}, "B": {"point": [b.real, b.imag]},
                         "C": {"point": [c.real, c.imag]},
                         "input": {"stroke": [0.95 * length, 1.05 * length]}}}
    model = assur.build_model(assur.analyse_structure(assur.chain_from_dict(data)))

    def near() -> complex:
        return complex(*rng.uniform(-50, 250, 2))

    masses = {link: Mass(float(rng.uniform(0.5, 5.0)), near(), float(rng.uniform(0, 0.05)))
              for link in (1, 2, 3)}
    loads = (Load(1, force=complex(*rng.uniform(-900, 900, 2)), point=near()),
             Load(3, torque=float(rng.uniform(-20, 20))))
    return model, ForceData(masses, loads, complex(0, -9.81)), length


@pytest.mark.parametrize("seed", range(6))
def test_actuator_force_equals_the_global_solve(seed: int) -> None:
    model, data, length = _boom(seed)
    q = np.linspace(*model.input_range, 25)
    motion = analyse(model, q, analogs=True)
    speed = 40.0  # mm/s
    result = kinetostatics(motion, data, speed)
    with np.errstate(invalid="ignore"):  # NaN where the boom cannot be assembled
        expected = _global(motion, data, speed, length)
    assert result.drive == "driving_force"
    solved = result.reason == 0
    assert np.array_equal(solved, motion.exists) and solved.sum() >= 5
    scale = np.max([np.abs(expected[p][0][solved]) for p in ("A", "B", "C")], axis=0)
    pairs = {"A": ("x", "y"), "B": ("x", "y"), "C": ("x", "y"), "Pd": ("normal", "moment")}
    for pid, parts in pairs.items():
        for part, want in zip(parts, expected[pid]):
            got = getattr(result.reactions[pid], part)
            np.testing.assert_array_less(np.abs(got - want)[solved], 1e-9 * scale)
    np.testing.assert_array_less(np.abs(result.driving - expected["driving"])[solved],
                                 1e-9 * scale)
    assert np.all(np.abs(result.power_balance[solved]) <= 1e-10 * result.power_scale[solved])
    for residual in result.residuals.values():
        assert np.max(residual.force[solved]) <= 1e-10
        assert np.max(residual.moment[solved]) <= 1e-10


@pytest.mark.parametrize("kind", list(CHAINS))
def test_a_thousand_designs_in_one_call_keep_the_balances(kind: str) -> None:
    """Every dimension of the dyad varied by up to ±10 % over 1000 designs × 36 angles."""
    model, data = _design(kind, 5)
    rng = np.random.default_rng(7)
    varied = {name: value * rng.uniform(0.9, 1.1, (1000, 1)) + rng.uniform(-2, 2, (1000, 1))
              for name, value in model.params.items()
              if name.startswith(f"{kind}(") and not name.endswith(".delta")}
    batch = model.with_params(varied)
    result = kinetostatics(analyse(batch, PHI[::4], analogs=True), data, OMEGA)
    solved = result.reason == 0
    assert result.driving.shape == (1000, 12) and solved.sum() > 3000
    assert np.all(np.abs(result.power_balance[solved]) <= 1e-10 * result.power_scale[solved])
    for residual in result.residuals.values():
        assert np.max(residual.force[solved]) <= 1e-10
        assert np.max(residual.moment[solved]) <= 1e-10
    assert np.all(np.isnan(result.driving[~solved]))
