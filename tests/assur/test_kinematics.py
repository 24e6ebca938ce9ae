"""Mechanism kinematics: closure, invariances, branches, analogs, batches and the extremes."""

from __future__ import annotations

import cmath
import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

import assur
import assur.kinematics.analysis
from assur.kinematics.analysis import analyse

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "input_tables" / "course_11_link.yaml"
DATA = yaml.safe_load(EXAMPLE.read_text())
PHI = np.linspace(0.0, 2 * np.pi, 90, endpoint=False)


def _model(data: dict) -> assur.KinematicModel:
    return assur.build_model(assur.analyse_structure(assur.chain_from_dict(data)))


def _mapped(point_map, angle_shift: float = 0.0, flip: bool = False,
            rotation: str | None = None) -> dict:
    """The example with its sketch moved point by point (directions turned accordingly)."""
    data = copy.deepcopy(DATA)
    geometry = data["geometry"]
    for key, entry in geometry.items():
        if key in ("input", "tracing"):
            continue
        z = point_map(complex(*entry["point"]))
        entry["point"] = [z.real, z.imag]
        if "direction" in entry:
            d = -entry["direction"] if flip else entry["direction"]
            entry["direction"] = d + angle_shift
    for entry in geometry["tracing"].values():
        z = point_map(complex(*entry["point"]))
        entry["point"] = [z.real, z.imag]
    if rotation:
        geometry["input"] = {"rotation": rotation}
    return data


BASE = _model(DATA)
BASE_MOTION = analyse(BASE, PHI)


def _scale(motion: assur.Motion) -> float:
    return max(float(np.nanmax(np.abs(z))) for z in motion.joints.values())


def _check_closure(motion: assur.Motion, rel: float = 1e-9) -> None:
    """Distances between joints of one link are constant; sliders stay on their guides."""
    model = motion.model
    scale = _scale(motion)
    on_link: dict = {}
    for pid, (kind, links, _) in model.pair_links.items():
        if kind == "R":
            for link in links:
                on_link.setdefault(link, []).append(np.asarray(assur.kinematics.analysis.values(motion.joints[pid])))
    for link, points in on_link.items():
        for a in range(len(points)):
            for b in range(a + 1, len(points)):
                d = np.abs(points[a] - points[b])
                spread = np.nanmax(d, axis=-1) - np.nanmin(d, axis=-1)
                assert np.nanmax(spread) <= rel * scale, link
    for pid, slider in motion.sliders.items():
        u = np.exp(1j * np.asarray(assur.kinematics.analysis.values(slider.angle)))
        rel_pos = np.conj(u) * (np.asarray(assur.kinematics.analysis.values(slider.point))
                                - np.asarray(assur.kinematics.analysis.values(slider.base)))
        assert np.nanmax(np.abs(rel_pos.real - assur.kinematics.analysis.values(slider.s))) <= rel * scale, pid
        assert np.nanmax(np.abs(rel_pos.imag - np.asarray(slider.offset))) <= rel * scale, pid


def test_course_example_closes_at_every_position() -> None:
    assert BASE_MOTION.exists.all()
    _check_closure(BASE_MOTION)


@given(l_i=st.floats(120, 160), l_j=st.floats(80, 120), d=st.floats(-60, 60),
       rod=st.floats(30, 200), gamma=st.floats(10, 170), beta_j=st.floats(-80, 80),
       e_j=st.floats(-30, 30), beta_n=st.floats(-180, 180))
def test_constraints_hold_at_every_assembled_position_of_random_designs(
        l_i: float, l_j: float, d: float, rod: float, gamma: float, beta_j: float,
        e_j: float, beta_n: float) -> None:
    model = BASE.with_params({"L1(2,3).l_i": l_i, "L1(2,3).l_j": l_j, "L3(6,7).d": d,
                              "L2(9,8).l_j": rod, "L5(11,10).gamma": gamma,
                              "L4(4,5).beta_j": beta_j, "L4(4,5).e_j": e_j,
                              "L1(2,3).beta_N": beta_n})
    motion = analyse(model, PHI)
    if motion.exists.any():
        _check_closure(motion)
    # the last group's output is NaN exactly where some group does not assemble
    assert (np.isnan(motion.sliders["11-0"].s) == ~motion.exists).all()


def test_slider_crank_matches_its_closed_form() -> None:
    """Offset slider-crank: x_C = r cos φ + sqrt(l² − (r sin φ − e)²) (hand formula)."""
    r, rod, e = 25.0, 90.0, 10.0
    x0 = r + math.sqrt(rod * rod - e * e)
    chain = assur.chain_from_dict({"mechanism": {"pairs": [
        {"id": "O", "type": "R", "links": [0, 1]}, {"id": "A", "type": "R", "links": [1, 2]},
        {"id": "B", "type": "R", "links": [2, 3]},
        {"id": "G", "type": "P", "links": [3, 0], "guide": 0}], "inputs": [1]},
        "geometry": {"O": {"point": [0, 0]}, "A": {"point": [r, 0]},
                     "B": {"point": [x0, e]}, "G": {"point": [0, e], "direction": 0}}})
    model = assur.build_model(assur.analyse_structure(chain))
    motion = analyse(model, PHI, analogs=True)
    x = r * np.cos(PHI) + np.sqrt(rod * rod - (r * np.sin(PHI) - e) ** 2)
    v = -r * np.sin(PHI) - (r * np.sin(PHI) - e) * r * np.cos(PHI) / np.sqrt(
        rod * rod - (r * np.sin(PHI) - e) ** 2)
    slider = motion.sliders["G"]
    np.testing.assert_allclose(slider.s.v, x, rtol=1e-12)
    np.testing.assert_allclose(slider.s.d1, v, rtol=1e-9, atol=1e-12)
    assert motion.joints["B"].v.imag == pytest.approx(np.full(PHI.shape, e))


@given(alpha=st.floats(-math.pi, math.pi), tx=st.floats(-2000, 2000),
       ty=st.floats(-2000, 2000))
def test_rigid_motion_of_the_sketch_moves_every_joint(alpha: float, tx: float,
                                                      ty: float) -> None:
    turn, shift = cmath.exp(1j * alpha), complex(tx, ty)
    moved = _model(_mapped(lambda z: turn * z + shift, angle_shift=math.degrees(alpha)))
    motion = analyse(moved, PHI)
    scale = _scale(BASE_MOTION) + abs(shift)
    for pid, z in BASE_MOTION.joints.items():
        assert np.abs(motion.joints[pid] - (turn * z + shift)).max() <= 1e-9 * scale, pid
    for pid, s in BASE_MOTION.sliders.items():
        assert np.abs(motion.sliders[pid].s - s.s).max() <= 1e-9 * scale, pid


@pytest.mark.parametrize("factor", [2e-5, 1e-2, 1e3, 2e3])
def test_dimensions_from_micrometres_to_kilometres(factor: float) -> None:
    """Scaled sketches (about 1e-3 mm … 1e6 mm) give scaled positions and equal angles."""
    motion = analyse(_model(_mapped(lambda z: factor * z)), PHI, analogs=True)
    assert motion.exists.all()
    for pid, z in BASE_MOTION.joints.items():
        scale = factor * _scale(BASE_MOTION)
        assert np.abs(motion.joints[pid].v - factor * z).max() <= 1e-11 * scale, pid
    for link, (_, angle) in BASE_MOTION.frames.items():
        diff = np.angle(np.exp(1j * (motion.frames[link][1].v - angle)))
        assert np.abs(diff).max() <= 1e-10, link


def test_mirrored_sketch_takes_the_mirrored_branch() -> None:
    """The mirror image, driven the other way, is the mirror image at every position. The
    L1 variant (C left or right of H_i→H_j) flips; the L2 and L3 variants (ahead or behind
    along the guide) do not, since a reflection keeps dot products."""
    mirrored = _model(_mapped(np.conj, flip=True, rotation="cw"))
    signs = {g.label: g.sigma for g in BASE.groups}
    for group in mirrored.groups:
        if group.kind == 1:
            assert group.sigma == -signs[group.label]
        else:
            assert group.sigma == signs[group.label]
    motion = analyse(mirrored, PHI)
    scale = _scale(BASE_MOTION)
    for pid, z in BASE_MOTION.joints.items():
        assert np.abs(motion.joints[pid] - np.conj(z)).max() <= 1e-9 * scale, pid


def test_batch_of_designs_equals_a_loop_over_designs() -> None:
    changes = {"L1(2,3).l_i": [138.0, 140.0, 143.0], "L3(6,7).d": [5.0, 10.0, -8.0],
               "L2(9,8).l_j": [120.0, 130.0, 150.0], "L5(11,10).gamma": [45.0, 60.0, 75.0]}
    batch = BASE.with_params({k: np.array(v)[:, None] for k, v in changes.items()})
    assert batch.design_shape == (3, 1)
    motion = analyse(batch, PHI, analogs=True)
    for d in range(3):
        single = analyse(BASE.with_params({k: v[d] for k, v in changes.items()}), PHI,
                               analogs=True)
        for pid, z in single.joints.items():
            np.testing.assert_allclose(motion.joints[pid].v[d], z.v, rtol=1e-13, atol=1e-11)
            np.testing.assert_allclose(motion.joints[pid].d2[d], z.d2, rtol=1e-12, atol=1e-9)


def test_analogs_match_central_differences() -> None:
    h1, h2 = 1e-5, 1e-3
    jet = analyse(BASE, PHI, analogs=True)
    plus, minus = analyse(BASE, PHI + h1), analyse(BASE, PHI - h1)
    plus2, minus2 = analyse(BASE, PHI + h2), analyse(BASE, PHI - h2)

    def check(name, j, p, m, p2, m2, z) -> None:
        d1 = (p - m) / (2 * h1)
        d2 = (p2 - 2 * z + m2) / (h2 * h2)
        assert np.abs(j.d1 - d1).max() <= 1e-6 * max(np.abs(j.d1).max(), 1.0), name
        assert np.abs(j.d2 - d2).max() <= 1e-5 * max(np.abs(j.d2).max(), 1.0), name

    for pid in jet.joints:
        check(pid, jet.joints[pid], plus.joints[pid], minus.joints[pid], plus2.joints[pid],
              minus2.joints[pid], BASE_MOTION.joints[pid])
    for pid in jet.sliders:
        check(pid, jet.sliders[pid].s, plus.sliders[pid].s, minus.sliders[pid].s,
              plus2.sliders[pid].s, minus2.sliders[pid].s, BASE_MOTION.sliders[pid].s)
    for link in jet.frames:
        angle = [np.unwrap(m.frames[link][1]) for m in (plus, minus, plus2, minus2, BASE_MOTION)]
        check(link, jet.frames[link][1], *angle)


def test_velocity_and_acceleration_for_a_crank_speed() -> None:
    """x(t) = x(φ(t)) with φ = ω t + ε t²/2: time differences against the analog formulas."""
    omega, epsilon, dt = 12.5, 30.0, 1e-4
    jet = analyse(BASE, PHI, analogs=True)

    def at(t: float) -> assur.Motion:
        return analyse(BASE, PHI + omega * t + 0.5 * epsilon * t * t)

    later, now, earlier = at(dt), at(0.0), at(-dt)
    for pid in ("2-3", "4-5", "8-9"):
        v = assur.kinematics.analysis.velocity(jet.joints[pid], omega)
        numeric_v = (later.joints[pid] - earlier.joints[pid]) / (2 * dt)
        assert np.abs(v - numeric_v).max() <= 1e-5 * np.abs(v).max(), pid
        a = assur.kinematics.analysis.acceleration(jet.joints[pid], omega, epsilon)
        numeric_a = (later.joints[pid] - 2 * now.joints[pid] + earlier.joints[pid]) / dt ** 2
        assert np.abs(a - numeric_a).max() <= 1e-4 * np.abs(a).max(), pid


def test_crank_angles_over_many_turns_keep_the_branch() -> None:
    far = analyse(BASE, PHI + 2 * np.pi * 1000)
    scale = _scale(BASE_MOTION)
    for pid, z in BASE_MOTION.joints.items():
        assert np.abs(far.joints[pid] - z).max() <= 1e-9 * scale, pid
    turns = np.linspace(0, 2 * np.pi * 30, 30 * 720 + 1)
    jet = analyse(BASE, turns, analogs=True)
    step = turns[1] - turns[0]
    for pid, z in jet.joints.items():
        jumps = np.abs(np.diff(z.v))
        assert (jumps <= 1.05 * np.abs(z.d1).max() * step + 1e-12).all(), pid


def _four_bar(l_j: float) -> assur.KinematicModel:
    """Crank 30 from (0, 0), rocker pivot (100, 0), coupler 70, rocker l_j (sketch at φ = 0)."""
    a, d, li = 30 + 0j, 100 + 0j, 70.0
    dist = abs(d - a)
    cos_a = (li * li + dist * dist - l_j * l_j) / (2 * li * dist)
    c = a + li * cmath.exp(1j * math.acos(cos_a))
    chain = assur.chain_from_dict({
        "mechanism": {"pairs": [
            {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
            {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
            "inputs": [1]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": [a.real, a.imag]},
                     "C": {"point": [c.real, c.imag]}, "D": {"point": [d.real, d.imag]}}})
    return assur.build_model(assur.analyse_structure(chain))


def test_toggle_position_is_flagged_and_keeps_the_branch() -> None:
    """Coupler + rocker = 130 + 1e-9 = the largest hinge distance: stretched at φ = 180°."""
    model = _four_bar(60.0).with_params({"L1(2,3).l_j": 60.0 + 1e-9})
    phi = np.linspace(0, 2 * np.pi, 3601)
    motion = analyse(model, phi, analogs=True)
    sol = motion.solutions["L1(2,3)"]
    assert sol.exists.all()
    toggle = int(np.argmin(sol.margin))
    assert abs(phi[toggle] - np.pi) < 1e-9 and sol.margin[toggle] < 1e-10
    a, c, d = (motion.joints[k].v for k in ("B", "C", "D"))
    np.testing.assert_allclose(np.abs(c - a), 70.0, rtol=1e-9)
    np.testing.assert_allclose(np.abs(c - d), 60.0 + 1e-9, rtol=1e-9)
    side = ((np.conj(d - a) * (c - a)).imag) * model.group("L1(2,3)").sigma
    assert (side >= -1e-6).all()  # never on the other branch (0 only at the toggle itself)
    # away from the toggle the analogs are accurate; near it the margin says they are not
    h = 1e-6
    fine = sol.margin > 1e-3
    numeric = (analyse(model, phi + h).joints["C"] - analyse(model, phi - h)
               .joints["C"]) / (2 * h)
    err = np.abs(motion.joints["C"].d1 - numeric)[fine]
    assert err.max() <= 1e-6 * np.abs(motion.joints["C"].d1[fine]).max()


@pytest.mark.parametrize("gap_deg", [1e-2, 1e-5, 1e-7])
def test_nearly_parallel_guides_stay_on_both_guides(gap_deg: float) -> None:
    """The frame guide of slider 5 nearly parallel to rocker 3 at φ = 0."""
    rocker = float(np.degrees(BASE_MOTION.sliders["3-4"].angle[0]))  # guide of slider 4
    model = BASE.with_params({"L4(4,5).beta_j": rocker + gap_deg})
    motion = analyse(model, PHI)
    sol = motion.solutions["L4(4,5)"]
    assert sol.margin[0] == pytest.approx(math.sin(math.radians(gap_deg)), rel=1e-6)
    for pid in ("3-4", "5-0"):
        slider = motion.sliders[pid]
        u = np.exp(1j * slider.angle)
        rel = np.conj(u) * (slider.point - slider.base)
        reach = np.abs(slider.point - slider.base)
        assert (np.abs(rel.imag - slider.offset) <= 1e-9 * reach + 1e-9).all(), pid


def test_linear_actuator_drives_a_dyad_with_a_variable_length_link() -> None:
    """A kite four-bar (as in the solar tracker) driven by an actuator E–C."""
    b = 300 * cmath.exp(1j * math.radians(60))
    d = 300 + 0j
    mid, half = (b + d) / 2, abs(d - b) / 2
    c = mid + math.sqrt(540 ** 2 - half ** 2) * (d - b) / abs(d - b) * 1j
    e = -300 + 0j
    chain = assur.chain_from_dict({
        "mechanism": {"pairs": [
            {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
            {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]},
            {"id": "E", "type": "R", "links": [0, 4]}, {"id": "F", "type": "R", "links": [5, 3]},
            {"id": "S", "type": "P", "links": [4, 5], "guide": 4}],
            "inputs": [{"pair": "S"}]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": [b.real, b.imag]},
                     "C": {"point": [c.real, c.imag]}, "D": {"point": [300, 0]},
                     "E": {"point": [e.real, e.imag]}, "F": {"point": [c.real, c.imag]},
                     "S": {"point": [e.real, e.imag], "direction": [(c - e).real, (c - e).imag]},
                     "input": {"stroke": [950, 1100]}}})
    model = assur.build_model(assur.analyse_structure(chain))
    assert model.drive == "actuator" and model.input_range == (950.0, 1100.0)
    q = assur.input_grid(model, 31)
    motion = analyse(model, q, analogs=True)
    assert motion.exists.all()
    np.testing.assert_allclose(np.abs(motion.joints["F"].v - e), q, rtol=1e-12)
    np.testing.assert_allclose(motion.sliders["S"].s.v, q, rtol=1e-12)
    np.testing.assert_allclose(np.abs(motion.joints["C"].v - motion.joints["F"].v), 0,
                               atol=1e-9)
    np.testing.assert_allclose(np.abs(motion.joints["C"].v - 300), 540, rtol=1e-12)
    np.testing.assert_allclose(np.abs(motion.joints["B"].v), 300, rtol=1e-12)
    # d|EC|/dq = 1 along the actuator axis
    axis = (motion.joints["F"].v - e) / q
    np.testing.assert_allclose((np.conj(axis) * motion.joints["F"].d1).real, 1.0, rtol=1e-9)
