"""A mode whose forward and backward ends overlap: every angle has a position, no full turn.

Followed forward from the sketch, the drawn mode of some triads ends at φ_f; followed
backward, it ends at φ_b < φ_f. Every crank angle then has a position of the drawn mode's
circuit, but the angles between φ_b and φ_f have two (one reached each way), the crank cannot
make a full turn, and the positions shown over the cycle jump at φ_f. That must be said, not
shown as a smooth full turn: the solution flags it (``overlap``) and its notes name both ends.
The reference is the fine-step continuation of ``test_higher_speed`` run forward and backward
on a 1° grid: the overlap is there when the forward pass ends and both passes reach a common
angle.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from test_higher_properties import Designs, random_triads
from test_higher_speed import TWO_PI, _fine

from assur.kinematics.higher import assembly_modes, follow_mode
from assur.kinematics.higher.groups import values
from assur.kinematics.higher.modes import select_mode


def _subset(designs: Designs, rows: slice) -> Designs:
    """The designs ``rows`` of a seeded sample."""
    def cut(v: object) -> object:
        if isinstance(v, tuple):
            return tuple(cut(item) for item in v)
        return v[rows] if isinstance(v, np.ndarray) and v.ndim else v

    group = designs.group
    fields = {f.name: cut(getattr(group, f.name)) for f in dataclasses.fields(group)}
    return Designs(type(group)(**fields), designs.pin[rows], cut(designs.fixed))


def test_overlapping_ends_are_flagged_and_named() -> None:
    designs = _subset(random_triads(7, 600), slice(246, 262))  # design 253 of the sample: 7
    d = len(designs.pin)
    phi = np.radians(np.arange(1.0, 360.0, 1.0))
    k0 = values(designs.inputs(np.zeros(d)))
    x0, _ = select_mode(designs.group, k0, assembly_modes(designs.group, k0))
    ahead = np.isfinite(_fine(designs, x0, phi, 1.0)[..., 0])
    behind = np.isfinite(_fine(designs, x0, np.sort(TWO_PI - phi), -1.0)[..., 0])[:, ::-1]
    both = (ahead & behind).any(axis=1) & ~ahead.all(axis=1)  # a pass that ends, and overlaps
    assert both[7] and not both.all()
    solution = follow_mode(designs.group, designs.inputs, phi)
    assert (solution.overlap == both).all()
    assert solution.exists[7].all()  # every angle has a position …
    step = np.abs(np.diff(solution.joints["P1"][7]))
    assert step.max() > 10 * np.median(step)  # … and the motion jumps at φ_f
    forward, backward = np.degrees(solution.ends[7])
    assert backward < forward
    jump = float(np.degrees(phi[int(np.argmax(step))]))
    assert jump <= forward <= jump + 1.0
    notes = [note.code for note in solution.notes(7)]
    assert "higher.overlap" in notes
    assert all("higher.overlap" not in [n.code for n in solution.notes(i)]
               for i in np.flatnonzero(~both))
