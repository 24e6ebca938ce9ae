"""A slider-crank engine's force analysis by hand at three crank angles.

The method is the kinetostatics of Assur groups as taught in the course's textbook,
I. I. Artobolevsky, *Теория механизмов и машин* (4th ed., Moscow: Nauka, 1988), the chapters
on the force analysis of mechanisms: d'Alembert's inertia forces, then the groups from the
last one back to the crank. The printed examples are checked elsewhere: one engine at a
single angle in ``test_forces_published.py`` and three engines of one textbook at 45°, 60° and
125° in ``test_forces_khurmi.py``. Here one engine is worked through three angles by hand, in
``_hand`` below with scalar components only and sharing nothing with the program but the
data: the closed-form kinematics of the offset slider-crank differentiated by hand (rod angle β from
l·sin β = e − r·sin φ), then the slider's x-equation, the rod's moments about the crank pin,
the slider's y-equation, the rod's force polygon and the crank's moments.

Its results (ω = 150 rad/s, gas force −2000 N, N and N·m; "x–y" the force of the first link
of the pair on the second):

| φ | M_d | 0-1 x | 0-1 y | 1-2 x | 1-2 y | 2-3 x | 2-3 y | 3-0 y |
|---|---|---|---|---|---|---|---|---|
| 45° | −9.0214 | −1032.87 | −1241.58 | −651.03 | −867.59 | 802.52 | 72.29 | 60.52 |
| 150° | −98.5949 | 5285.44 | −1150.17 | 4817.79 | −888.01 | 3163.76 | −227.73 | −239.50 |
| 260° | 172.8671 | 3386.40 | 2617.45 | 3292.63 | 2077.81 | 2746.97 | 733.60 | 721.83 |
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import assur
from assur.forces import ForceData, Load, Mass, kinetostatics
from assur.kinematics.analysis import analyse

# Offset slider-crank (m, kg, N): crank r, rod l, offset e of the slide line y = e.
R, L, E = 0.060, 0.240, 0.010
M1, C1 = 0.8, 0.030            # crank: mass, centre at distance C1 from O along OA
M2, A2, I2 = 1.5, 0.080, 0.012  # rod: mass, centre at A2 from A along AB, inertia
M3 = 1.2                        # slider, centre at B
P = -2000.0                     # gas force on the slider along x, N
G = -9.81                       # gravity along y
OMEGA = 150.0                   # rad/s, counter-clockwise, constant


def _hand(phi: float) -> dict[str, float]:
    """Every reaction and the driving torque at crank angle φ (radians from the x-axis)."""
    s, c = math.sin(phi), math.cos(phi)
    sin_b = (E - R * s) / L                     # rod angle β: l sin β = e − r sin φ
    cos_b = math.sqrt(1 - sin_b**2)
    b1 = -R * c / (L * cos_b)                   # dβ/dφ
    b2 = (R * s + L * sin_b * b1**2) / (L * cos_b)  # d²β/dφ²
    ax, ay = R * c, R * s                       # crank pin A
    bx, by = ax + L * cos_b, E                  # wrist pin B
    x2 = -R * c - L * cos_b * b1**2 - L * sin_b * b2  # d²x_B/dφ²
    g2x = -R * c + A2 * (-cos_b * b1**2 - sin_b * b2)  # rod centre, d²/dφ²
    g2y = -R * s + A2 * (-sin_b * b1**2 + cos_b * b2)
    gx, gy = ax + A2 * cos_b, ay + A2 * sin_b
    w2 = OMEGA**2
    # slider 3: F23 (rod on slider) + P − M3·a_B = 0 along x
    f23x = M3 * w2 * x2 - P
    # rod 2 about A: B−A × F32 + (G2−A) × (weight + inertia) − I2·ε2 = 0, F32 = −F23
    fx, fy = -M2 * w2 * g2x, M2 * G - M2 * w2 * g2y
    moment = (gx - ax) * fy - (gy - ay) * fx - I2 * w2 * b2
    f32x = -f23x
    f32y = ((by - ay) * f32x - moment) / (bx - ax)
    f23y = -f32y
    # slider 3 along y: F23y + N + M3·g = 0 (slider's y-acceleration is 0)
    normal = -f23y - M3 * G
    # rod's force polygon: F12 + F32 + weight + inertia = 0
    f12x, f12y = -f32x - fx, -f32y - fy
    # crank 1 about O: M_d + A × F21 + (C1 on OA) × M1·g = 0 (its inertia force is radial)
    f21x, f21y = -f12x, -f12y
    m_d = -(ax * f21y - ay * f21x) - C1 * c * M1 * G
    # crank's force polygon: F01 + F21 + M1·g − M1·a_S1 = 0, a_S1 = −ω²·C1·(cos φ, sin φ)
    f01x = -f21x - M1 * w2 * C1 * c
    f01y = -f21y - M1 * G - M1 * w2 * C1 * s
    return {"driving": m_d, "0-1 x": f01x, "0-1 y": f01y, "1-2 x": f12x, "1-2 y": f12y,
            "2-3 x": f23x, "2-3 y": f23y, "3-0 y": -normal}


def _program(angles: np.ndarray) -> dict[str, np.ndarray]:
    a0 = complex(R, 0) * 1e3
    b0 = complex(R + math.sqrt(L**2 - E**2), E) * 1e3
    pairs = [{"id": "0-1", "type": "R", "links": [0, 1]},
             {"id": "1-2", "type": "R", "links": [1, 2]},
             {"id": "2-3", "type": "R", "links": [2, 3]},
             {"id": "3-0", "type": "P", "links": [3, 0], "guide": 0}]
    geometry = {"0-1": {"point": [0, 0]}, "1-2": {"point": [a0.real, a0.imag]},
                "2-3": {"point": [b0.real, b0.imag]},
                "3-0": {"point": [0, E * 1e3], "direction": 0}, "input": {"rotation": "ccw"}}
    chain = assur.chain_from_dict({"mechanism": {"pairs": pairs, "inputs": [1]},
                                   "geometry": geometry})
    model = assur.build_model(assur.analyse_structure(chain))
    centre2 = a0 + A2 * 1e3 * (b0 - a0) / abs(b0 - a0)
    data = ForceData({1: Mass(M1, complex(C1 * 1e3, 0)), 2: Mass(M2, centre2, I2),
                      3: Mass(M3, b0)}, (Load(3, force=complex(P, 0), point=b0),), complex(0, G))
    result = kinetostatics(analyse(model, angles, analogs=True), data, OMEGA)
    out = {"driving": result.driving}
    for pid, reaction in result.reactions.items():
        out[f"{pid} x"], out[f"{pid} y"] = reaction.x, reaction.y
    return out


@pytest.mark.parametrize("degrees", [45.0, 150.0, 260.0])
def test_hand_calculation_is_reproduced(degrees: float) -> None:
    hand = _hand(math.radians(degrees))
    program = _program(np.radians([degrees]))
    forces = max(abs(v) for k, v in hand.items() if k != "driving")
    for key, value in hand.items():
        scale = abs(hand["driving"]) if key == "driving" else forces
        assert program[key][0] == pytest.approx(value, abs=1e-9 * scale), key
    assert program["3-0 x"][0] == pytest.approx(0.0, abs=1e-12 * forces)
