"""Pressure angles and joint rotations against hand formulas (law of cosines, arcsin)."""

from __future__ import annotations

import cmath
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import assur
import assur.kinematics.transmission
from assur.kinematics.analysis import analyse
from assur.kinematics.jets import value

ROOT = Path(__file__).resolve().parents[2]
PHI = np.linspace(0.0, 2 * np.pi, 720, endpoint=False)


def _build(pairs: list[dict[str, Any]], geometry: dict[str, Any]) -> assur.KinematicModel:
    chain = assur.chain_from_dict({"mechanism": {"pairs": pairs, "inputs": [1]},
                                   "geometry": geometry})
    return assur.build_model(assur.analyse_structure(chain))


R = [{"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
     {"id": "C", "type": "R", "links": [2, 3]}]


def test_four_bar_pressure_angle_is_the_transmission_angle_defect() -> None:
    """Crank 20, coupler 70, rocker 60, frame 80: cos μ = (l2² + l3² − d²)/(2 l2 l3)."""
    crank, li, lj, frame = 20.0, 70.0, 60.0, 80.0
    a0 = complex(crank, 0)
    dist = frame - crank
    cos_a = (li * li + dist * dist - lj * lj) / (2 * li * dist)
    c0 = a0 + li * cmath.exp(1j * math.acos(cos_a))
    model = _build(R + [{"id": "D", "type": "R", "links": [3, 0]}],
                   {"A": {"point": [0, 0]}, "B": {"point": [crank, 0]},
                    "C": {"point": [c0.real, c0.imag]}, "D": {"point": [frame, 0]}})
    motion = analyse(model, PHI)
    (item,) = assur.pressure_angles(motion)
    assert set(item.binary) == {2, 3}
    d = np.abs(frame - crank * np.exp(1j * PHI))
    mu = np.arccos((li * li + lj * lj - d * d) / (2 * li * lj))
    np.testing.assert_allclose(item.alpha, np.abs(np.pi / 2 - mu), atol=1e-9)
    # rocker swing between the two dead centres (crank and coupler collinear)
    ext = math.acos((frame ** 2 + lj ** 2 - (li + crank) ** 2) / (2 * frame * lj))
    fold = math.acos((frame ** 2 + lj ** 2 - (li - crank) ** 2) / (2 * frame * lj))
    rotations = {r.pair: r for r in assur.joint_rotations(motion)}
    fine = analyse(model, np.linspace(0, 2 * np.pi, 20001))
    fine_rot = {r.pair: r for r in assur.joint_rotations(fine)}
    assert fine_rot["D"].swing == pytest.approx(ext - fold, abs=1e-6)
    assert rotations["A"].full_turn and rotations["A"].swing == pytest.approx(2 * np.pi)
    assert rotations["D"].group == "L1(2,3)"


def test_slider_crank_pressure_angle_is_arcsin_of_the_offset() -> None:
    r, rod, e = 25.0, 90.0, 10.0
    model = _build(R[:2] + [{"id": "C", "type": "R", "links": [2, 3]},
                            {"id": "G", "type": "P", "links": [3, 0], "guide": 0}],
                   {"A": {"point": [0, 0]}, "B": {"point": [r, 0]},
                    "C": {"point": [r + math.sqrt(rod * rod - e * e), e]},
                    "G": {"point": [0, e], "direction": 0}})
    motion = analyse(model, PHI)
    (item,) = assur.pressure_angles(motion)
    assert item.binary == (2,)
    expected = np.arcsin(np.abs(r * np.sin(PHI) - e) / rod)
    np.testing.assert_allclose(item.alpha, expected, atol=1e-9)
    assert item.maximum == pytest.approx(math.asin((r + e) / rod), abs=1e-5)


def test_course_example_l1_pressure_angle_by_hand() -> None:
    """The course's reading (method.md §2.7): a two-hinge link is counted by its hinges, as
    table 1.6 counts them.  Rocker 3 has two (2-3, 3-0) and carries the guide of slider 4;
    coupler 2 has the hinge 2-6 of link 6, rod 8 the hinge 8-10.  So L1(2,3) has a pressure
    angle and L2(9,8) none.  By hand, from the table's dimensions: crank pin
    B = 40·e^{i(30° + φ)}, hinge distance d = |H_j − B| with H_j = (150, 0), and with l_i = 140,
    l_j = 100 the angle at C is cos μ = (l_i² + l_j² − d²)/(2 l_i l_j); α = |90° − μ|."""
    model = assur.load_model(ROOT / "input_tables" / "course_11_link_table.yaml")
    binary = assur.kinematics.transmission.binary_links(model)
    assert 3 in binary and not {2, 8} & binary
    (item,) = assur.pressure_angles(analyse(model, PHI))
    assert (item.label, item.pair, item.binary, item.guides) == ("L1(2,3)", "2-3", (3,), (3,))
    b = 40.0 * np.exp(1j * (np.radians(30.0) + PHI))
    d = np.abs(150.0 - b)
    mu = np.arccos((140.0 ** 2 + 100.0 ** 2 - d * d) / (2 * 140.0 * 100.0))
    np.testing.assert_allclose(item.alpha, np.abs(np.pi / 2 - mu), atol=1e-9)


def test_joint_rotations_of_the_course_example_from_positions() -> None:
    """θ_ab from the directions of joints on each link, unwrapped by hand."""
    model = assur.load_model(ROOT / "input_tables" / "course_11_link.yaml")
    motion = analyse(model, PHI)
    rot = {r.pair: r for r in assur.joint_rotations(motion)}
    assert len(rot) == 10  # 1 + 3 + 1 + 2 + 2 + 1 revolute joints (method.md §2.8)
    j = {pair: np.asarray(value(point), dtype=complex) for pair, point in motion.joints.items()}
    coupler = np.angle(j["2-3"] - j["1-2"])
    rocker = np.angle(j["2-3"] - j["3-0"])
    theta = np.unwrap(coupler - rocker)
    assert rot["2-3"].swing == pytest.approx(np.ptp(theta), abs=1e-9)
    assert rot["3-0"].swing == pytest.approx(np.ptp(np.unwrap(rocker)), abs=1e-9)
