"""The mechanism picture: hinges where the analysis puts them, broken positions marked."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.patches import Circle

import assur
import assur.plot.mechanism
from assur.kinematics.analysis import analyse

ROOT = Path(__file__).resolve().parents[2]


def test_hinges_are_drawn_at_the_joints_of_the_position() -> None:
    model = assur.load_model(ROOT / "input_tables" / "course_11_link.yaml")
    motion = analyse(model, np.radians(np.arange(0, 360, 30.0)))
    index = 4
    _, ax = assur.plot.mechanism.figure_for(motion)
    assur.draw_mechanism(motion, index, ax)
    centres = sorted((round(p.center[0], 9), round(p.center[1], 9))
                     for p in ax.patches if isinstance(p, Circle))
    revolute = [pid for pid, (kind, _, _) in model.pair_links.items() if kind == "R"]
    expected = sorted((round(float(motion.joints[pid][index].real), 9),
                       round(float(motion.joints[pid][index].imag), 9)) for pid in revolute)
    assert centres == expected
    assert "120.0°" in ax.get_title()


def test_a_broken_position_is_marked_in_the_title() -> None:
    model = assur.load_model(ROOT / "input_tables" / "course_11_link_fails.yaml")
    motion = analyse(model, np.radians([0.0, 45.0]))
    _, ax = assur.plot.mechanism.figure_for(motion)
    assur.draw_mechanism(motion, 1, ax, lang="ru")
    assert "не собирается" in ax.get_title()
    # the groups after the broken kulisa group are not drawn: fewer hinges than joints
    drawn = sum(isinstance(p, Circle) for p in ax.patches)
    assert drawn == sum(bool(np.isfinite(z[1])) for z in motion.joints.values())
    assert drawn < len(motion.joints)
    assert math.isnan(motion.joints["8-9"][1].real)
