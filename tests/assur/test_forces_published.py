"""A published worked example of a slider-crank's dynamic force analysis, reproduced.

Source: Dan B. Marghitu, *Mechanisms and Robots Analysis with MATLAB*, Springer, London,
2009, Chapter 4 "Dynamic Force Analysis", the R-RRT mechanism (slider-crank) solved by the
contour method, p. 144, Eqs. (4.51)–(4.52); the page is readable at
https://studmed.ru/view/dan-b-marghitu-mechanisms-and-robots-analysis-with-matlab_8be015c74f0.html?page=15
and the data of the example (the same mechanism in the author's course notes "Dynamic Force
Analysis: R-RRT mechanism", §1.1) at https://www.scribd.com/doc/193600397/Dynamic-Force-Analysis.

Data as printed: crank AB = 1 m and rod BC = 1 m, the slider's path through A; the crank at
φ = π/4 from the horizontal axis, turning at the constant n = 30/π rpm (ω = 1 rad/s,
counter-clockwise: "ω1 = 1 k rad/s"); each moving link of mass 1 kg, centres of mass at the
middle of AB, the middle of BC and at C; the links' moments of inertia are printed
(I_C1 = I_C2 = 0.0833417 kg·m²) but both angular accelerations are 0 at this position;
g = 10 m/s² downwards; an external force of 100 N on the slider opposed to its velocity
(v_C = −√2 m/s, so F_ext = +100 ı N).

Printed result (the joint force of link 1 on link 2 at B, N, exact):

    F12x = −(400 + 7√2)/4 = −102.474 873 734 …
    F12y = (5/4)(84 + √2) =  106.767 766 953 …

and the two equations it comes from, the rod's moments about C (4.51) and the forces of rod
and slider along the slide (4.52): F12x + 100 + √2 + 3√2/4 = 0 (Fin3x = √2, Fin2x = 3√2/4,
F_ext = 100). The book's notation F_ij is the force of link i on link j, as the program's
reaction of a pair listed [i, j]; units and axes are the same (m → mm in the table).

Only this one crank position is printed in the source with numbers; the three-angle
checks of the method are the hand calculation in ``test_forces_textbook.py`` and the three
printed engine examples (45°, 60°, 125°) of Khurmi and Gupta in ``test_forces_khurmi.py``.
"""

from __future__ import annotations

import math

import numpy as np

import assur
from assur.forces import ForceData, Load, Mass, kinetostatics
from assur.kinematics.analysis import analyse
from assur.kinematics.jets import Jet
from assur.model import LinkId

ROOT2 = math.sqrt(2.0)
#: The printed results, N.
F12X = -(400.0 + 7.0 * ROOT2) / 4.0
F12Y = 5.0 / 4.0 * (84.0 + ROOT2)


def _example() -> tuple[assur.KinematicModel, ForceData]:
    half = 1000.0 * ROOT2 / 2          # mm: B = (√2/2, √2/2) m, C = (√2, 0) m
    b, c = complex(half, half), complex(2 * half, 0.0)
    pairs = [{"id": "A", "type": "R", "links": [0, 1]},
             {"id": "B", "type": "R", "links": [1, 2]},
             {"id": "C", "type": "R", "links": [2, 3]},
             {"id": "C_T", "type": "P", "links": [3, 0], "guide": 0}]
    geometry = {"A": {"point": [0, 0]}, "B": {"point": [b.real, b.imag]},
                "C": {"point": [c.real, c.imag]},
                "C_T": {"point": [c.real, c.imag], "direction": 0},
                "input": {"rotation": "ccw"}}
    chain = assur.chain_from_dict({"mechanism": {"pairs": pairs, "inputs": [1]},
                                   "geometry": geometry})
    model = assur.build_model(assur.analyse_structure(chain))
    masses: dict[LinkId, Mass] = {1: Mass(1.0, b / 2, 0.0833417),
                                  2: Mass(1.0, (b + c) / 2, 0.0833417), 3: Mass(1.0, c)}
    return model, ForceData(masses, (Load(3, force=100.0 + 0j, point=c),), -10j)


def test_the_printed_joint_force_at_b_is_reproduced() -> None:
    model, data = _example()
    motion = analyse(model, np.array([0.0]), analogs=True)   # the sketch: φ = π/4
    # the example's kinematics as printed: v_C = −√2 m/s (opposed by F_ext), ε2 = 0
    slider, rod = motion.joints["C"], motion.frames[2][1]
    assert isinstance(slider, Jet) and isinstance(rod, Jet)
    assert abs(slider.d1[0] * 1e-3 + ROOT2) < 1e-12 and abs(rod.d2[0]) < 1e-12
    result = kinetostatics(motion, data, omega=1.0)
    reaction = result.reactions["B"]
    assert reaction.links == (1, 2)
    assert abs(reaction.x[0] - F12X) < 1e-9 * abs(F12X)
    assert abs(reaction.y[0] - F12Y) < 1e-9 * abs(F12Y)
    # Eq. (4.52): the force of link 1 on 2 balances F_ext and the inertia forces along x
    assert abs(reaction.x[0] + 100.0 + ROOT2 + 3.0 * ROOT2 / 4.0) < 1e-9 * 100
