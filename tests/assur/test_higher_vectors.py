"""Test vectors V1–V3 of ``higher_groups.md`` §6: every mode at the sketch, the drawn mode over
the cycle.

The known hinges come from the program's crank and RRR dyad solvers; the expected numbers are
the document's, printed to 10 significant digits, so agreement is asserted to 1e-9 of the
group's size (half a unit in the last printed digit is below 3e-10 of it).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from assur.kinematics import jets as J
from assur.kinematics.dyads import solve_rrr
from assur.kinematics.higher import (
    ClassIVCoupled,
    ClassIVInputs,
    Triad,
    TriadInputs,
    assembly_modes,
    follow_mode,
)

DEG = np.pi / 180.0


def _z(*pairs: tuple[float, float]) -> np.ndarray:
    return np.array([complex(x, y) for x, y in pairs])


def fourbar(o, a, b, c):
    """The crank O–A and the dyad A–B–C over the crank angle: A, B and the rotations of
    the coupler (A, B) and the rocker (B, C) from the sketch."""
    sigma = np.sign(J.cross(c - a, b - a))

    def at(phi):
        pin = o + (a - o) * J.expi(phi)
        joint = solve_rrr(pin, c, abs(b - a), abs(b - c), sigma).c
        return pin, J.arg((joint - pin) / (b - a)), J.arg((joint - c) / (b - c))

    return at


# --- V1: eight-bar, four-bar driving an RRR triad ---------------------------------------------

V1 = {"O": 0j, "A": -23 + 9.5j, "B": 87 + 97.5j, "C": 101.5 - 6.5j, "D": 112.8 + 67.2j,
      "E": 169.5 + 57j, "F": 174 + 92.5j, "G": 189.5 + 151j, "H": 127.5 + 52j,
      "I": -4.9 + 124.9j}
V1_TRIAD = Triad(("RR", "RR", "RR"), (V1["E"], V1["F"], V1["H"]), (V1["D"], V1["G"], V1["I"]))


def v1_inputs(phi):
    a, coupler, rocker = fourbar(V1["O"], V1["A"], V1["B"], V1["C"])(phi)
    d = V1["C"] + (V1["D"] - V1["C"]) * J.expi(rocker)
    i = a + (V1["I"] - V1["A"]) * J.expi(coupler)
    return TriadInputs((d, V1["G"] + 0 * J.value(phi), i))


V1_MODES = [  # θ (deg), E, F, H
    (-119.4740140, (125.1819896, 123.4638102), (153.8734126, 102.0791837),
     (141.4943032, 162.4882695)),
    (-64.0371994, (168.8646676, 80.45454829), (202.7519971, 91.95015179),
     (145.9821998, 116.0269065)),
    (0.0, (169.5, 57), (174, 92.5), (127.5, 52)),
    (50.7681248, (157.6674657, 103.3364154), (133.0154944, 129.2744245),
     (134.9770957, 67.64121816)),
]
V1_MARGINS = [0.6936, 0.4456, 0.5351, 0.6330]
V1_CYCLE = {
    60: [(157.8087862, 64.6816584), (156.2529449, 100.4318942), (117.255092, 52.66509119)],
    150: [(173.9692409, 61.57560651), (164.2312394, 96.00918498), (137.2673804, 40.55244229)],
    240: [(203.7469948, 56.39736894), (193.211313, 90.59531346), (167.5436725, 34.52685323)],
    330: [(179.7304882, 55.19420578), (183.4088914, 90.7887187), (137.8572535, 49.22493292)],
}

# --- V2: crank driving a class IV group -------------------------------------------------------

V2 = {"O": 0j, "B": -12.5 - 20j, "C": 57 + 66j, "D": 115 + 67j, "E": 87 + 118j, "F": 25.5 + 98.5j,
      "G": 140.5 + 22j}
V2_GROUP = ClassIVCoupled(V2["B"], V2["C"], V2["F"], V2["G"], V2["D"], V2["E"])


def v2_inputs(phi):
    return ClassIVInputs(V2["B"] * J.expi(phi), V2["G"] + 0 * J.value(phi))


V2_MODES = [  # θ_a (deg), C, D, E, F
    (-74.5734039, (88.88884579, -64.11974557), (97.50688836, -6.754866576),
     (48.71487079, -38.44617487), (111.838823, -25.10950917)),
    (-74.5638170, (88.89622658, -64.10278036), (135.4350658, -29.47423085),
     (128.9590007, -87.29343684), (111.8396762, -25.08870446)),
    (-42.9661853, (96.97177587, -4.437857218), (99.48803256, 53.51616294),
     (53.8367456, 89.58498603), (96.07237445, 40.8135635)),
    (-28.1331108, (89.33974508, 23.06873949), (122.6639987, 70.55025293),
     (103.3378638, 125.427393), (76.88577882, 66.58194121)),
    (0.0, (57, 66), (115, 67), (87, 118), (25.5, 98.5)),
    (4.9348117, (49.34446359, 71.65976393), (89.34593013, 29.64925721),
     (31.9259502, 39.02720499), (15.16550369, 101.329592)),
]
V2_MARGINS = [0.9986, 0.8045, 0.2529, 0.3654, 0.3288, 0.7084]
V2_CYCLE = {
    60: [(56.06870114, 80.17672511), (112.1220578, 65.24283059), (80.85847743, 114.3100145),
         (17.25915267, 103.4644675)],
    150: [(77.60907023, 105.9486164), (123.8972328, 70.98569302), (105.9647756, 126.3339268),
          (41.87170479, 133.7216376)],
    240: [(72.7131221, 92.98176781), (126.7391906, 71.85870158), (112.016455, 128.1458321),
          (47.54569368, 130.59959)],
    330: [(61.68517916, 62.5383768), (119.311891, 69.18383238), (96.19477124, 122.5748314),
          (35.86452242, 99.7108624)],
}

# --- V3: crank driving a triad with one slider ------------------------------------------------

V3 = {"O": 0j, "B": -17 - 0.5j, "C": 77.5 + 30.5j, "D": 112 + 7.5j, "E": 81 + 31j, "F": 114 + 52j}
V3_TRIAD = Triad(("RR", "RR", "RP"), (V3["C"], V3["D"], V3["F"]), (V3["B"], V3["E"], V3["F"]),
                 (None, None, 1 + 0j))


def v3_inputs(phi):
    fixed = 0 * J.value(phi)
    return TriadInputs((V3["B"] * J.expi(phi), V3["E"] + fixed, V3["F"] + fixed),
                       (None, None, 1 + fixed))


V3_MODES = [  # θ (deg), C, D, F
    (-63.6696117, (47.53102859, 75.17692085), (42.21960627, 34.05467878), (82.98988278, 52)),
    (0.0, (77.5, 30.5), (112, 7.5), (114, 52)),
    (58.1576759, (81.9354623, 9.650088686), (119.6756654, 26.82352951), (82.92793985, 52)),
    (116.1540522, (78.06728533, 28.71405928), (83.50524201, 69.81975995), (42.67992933, 52)),
]
V3_MARGINS = [0.9035, 0.8588, 0.6081, 0.6352]
V3_CYCLE = {
    60: [(79.15614348, 32.81224619), (112.1585314, 7.710604955), (116.9229292, 52)],
    150: [(95.81860022, 49.856644), (115.7370593, 13.49038233), (138.1258812, 52)],
    240: [(99.81658739, 53.35551254), (116.6658453, 15.46946618), (142.1564337, 52)],
    330: [(80.79934052, 34.8814911), (112.3968107, 8.032843476), (119.5479747, 52)],
}

CASES: dict[str, tuple[Any, ...]] = {
    "V1": (V1_TRIAD, v1_inputs, ["P1", "P2", "P3"], V1_MODES, V1_MARGINS, V1_CYCLE),
    "V2": (V2_GROUP, v2_inputs, ["C", "D", "E", "F"], V2_MODES, V2_MARGINS, V2_CYCLE),
    "V3": (V3_TRIAD, v3_inputs, ["P1", "P2", "P3"], V3_MODES, V3_MARGINS, V3_CYCLE),
}


def test_v1_known_hinges_at_60_degrees() -> None:
    k = v1_inputs(np.array([60 * DEG]))
    assert abs(k.a[0][0] - (100.2972757 + 68.05154897j)) < 1e-7
    assert abs(k.a[2][0] - (-25.78611165 + 101.4850058j)) < 1e-7


@pytest.mark.parametrize("case", CASES)
def test_every_mode_at_the_sketch(case: str) -> None:
    group, inputs, names, expected, margins, _ = CASES[case]
    modes = assembly_modes(group, inputs(np.zeros(1)))
    size = float(group.size)
    assert modes.count.tolist() == [len(expected)]
    theta = modes.x[0, :, group.eliminated]
    for i, (angle, *points) in enumerate(expected):
        assert abs(theta[i] - angle * DEG) <= 1e-9
        for name, point in zip(names, points, strict=True):
            assert abs(modes.joints[name][0, i] - complex(*point)) <= 1e-9 * size
        assert modes.margin[0, i] == pytest.approx(margins[i], abs=5e-5)


@pytest.mark.parametrize("case", ["V1", "V3"])
def test_the_roots_off_the_circle(case: str) -> None:
    group, inputs, *_ = CASES[case]
    radii = {"V1": (0.314819, 3.176427), "V3": (0.212165, 4.713302)}[case]
    found = np.abs(assembly_modes(group, inputs(np.zeros(1))).roots[0])
    off = np.sort(found[np.abs(np.log(found)) > 1e-3])
    assert off == pytest.approx(radii, abs=1e-6)


@pytest.mark.parametrize("case", CASES)
def test_the_drawn_mode_over_the_cycle(case: str) -> None:
    group, inputs, names, _, _, cycle = CASES[case]
    angles = np.array(sorted(cycle), dtype=float)
    solution = follow_mode(group, inputs, angles * DEG)
    size = float(group.size)
    assert solution.exists.all()
    assert solution.closed and np.isnan(solution.ends).all()
    for column, angle in enumerate(angles):
        for name, point in zip(names, cycle[int(angle)], strict=True):
            assert abs(solution.joints[name][column] - complex(*point)) <= 1e-9 * size
