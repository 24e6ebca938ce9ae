"""Large plain-array calls of the crank and the RRR dyad against row-by-row calls.

Calls of many designs × many angles take the fast paths (one scaling pass for per-design crank
lengths; the RRR kernel in blocks of ``BLOCK`` positions). Each row must equal the small call
of that design alone, including where an input is undefined (NaN crank pins in some rows of
every block) and where the dyad does not assemble.
"""

from __future__ import annotations

import numpy as np
import pytest

from assur.kinematics._fast import BLOCK
from assur.kinematics.jets import TANGENT_FROM
from assur.kinematics.dyads import Reason, solve_input, solve_rrr

ANGLES = np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False)
CRANKS = np.linspace(15.0, 45.0, 60)[:, None]  # 60 designs: 21,600 positions, several blocks


@pytest.mark.parametrize("count", [ANGLES.size, 4 * TANGENT_FROM // 3])  # both unit forms
def test_crank_for_many_designs_equals_one_design_at_a_time(count: int) -> None:
    angles = np.linspace(0.0, 2.0 * np.pi, count, endpoint=False)
    starts = angles + np.linspace(0.0, 1.0, CRANKS.shape[0])[:, None]  # a start per design
    for phi in (angles, starts):
        pins = solve_input(1.0 - 2.0j, CRANKS, phi)
        assert pins.c.shape == (CRANKS.shape[0], count)
        for row in (0, 17, 59):
            own = phi if phi.ndim == 1 else phi[row]
            alone = solve_input(1.0 - 2.0j, float(CRANKS[row, 0]), own)
            np.testing.assert_array_equal(pins.c[row], alone.c)
            np.testing.assert_array_equal(pins.angle_i[row], own)
        assert pins.exists.all() and (pins.margin == 1.0).all()


def test_undefined_pins_in_every_block_are_reported_as_in_small_calls() -> None:
    assert CRANKS.shape[0] * ANGLES.size > 2 * BLOCK  # the call is cut into blocks
    pins = solve_input(0j, CRANKS, ANGLES).c.copy()
    pins[::5, 7] = np.nan  # an earlier group failed there: some row of every block
    whole = solve_rrr(pins, 100.0 + 0j, 70.0, 90.0, 1.0)
    assert (whole.reason[::5, 7] == Reason.UNDEFINED_INPUT).all()
    assert not whole.exists[::5, 7].any()
    assert whole.exists.any() and not whole.exists.all()  # long cranks fail part of a turn
    for row in range(0, CRANKS.shape[0], 4):
        alone = solve_rrr(pins[row], 100.0 + 0j, 70.0, 90.0, 1.0)
        np.testing.assert_array_equal(whole.exists[row], alone.exists)
        np.testing.assert_array_equal(whole.reason[row], alone.reason)
        np.testing.assert_array_equal(whole.margin[row], alone.margin)
        np.testing.assert_array_equal(whole.c[row], alone.c)
