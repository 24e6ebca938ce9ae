"""The class IV kernel's closed forms against the group's own sampled numpy computations.

The kernel writes the matrices M_j of couplers between hinged links in closed form
(``compiled.coupled._hinged``) and the eliminant's coefficients as products of Laurent
polynomials (``compiled.coupled._coefficients``); the group fits M_j from the loop equations
at nine sample poses (:meth:`ClassIVCoupled._matrices`) and reads the coefficients off Φ
sampled on the unit circle (:meth:`ClassIVCoupled.coefficients`). On random designs and
inputs both agree to roundoff, for every form.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_higher_coupled import COUPLED, SHARED, random_designs

from assur.kinematics.higher.compiled import coupled as compiled_coupled
from assur.kinematics.higher.coupled import ClassIVCoupled
from assur.kinematics.higher.groups import ClassIVInputs, plain

D = 24
FORMS = SHARED + COUPLED


def _inputs(form: str, seed: int) -> tuple[ClassIVCoupled, ClassIVInputs]:
    """Random designs of ``form`` at a crank angle per design anywhere on the turn."""
    designs = random_designs(form, seed, D)
    phi = np.random.default_rng(seed).uniform(0.0, 2 * np.pi, D)
    return designs.group, designs.inputs(phi)


@pytest.mark.parametrize(("form", "actuated"), [
    ("RR RR/RR", False), ("RR RR/RR", True), ("PR RR/RR", False), ("RP RR/RR", False),
    ("PP RR/RR", False), ("PR RP/RR", False)])
def test_hinged_links_matrices_in_closed_form_are_the_fitted_ones(form: str,
                                                                   actuated: bool) -> None:
    group, k = _inputs(form, 11 + FORMS.index(form))
    if actuated:  # bar b an actuator: its length from the inputs, not the drawing
        length = np.abs(np.asarray(group.c) - group.d) * np.linspace(0.97, 1.03, D)
        k = ClassIVInputs(k.h_a, k.h_c, k.u_a, k.u_c, l_b=length)
    assert not any(group.slides)
    fitted = group._matrices(k)
    gap = plain(k.h_a) - plain(k.h_c)
    sides = (np.asarray(group.c) - group.d, np.asarray(group.f) - group.e)
    m = np.full((2, 3, 3), np.nan)
    for j, kind in enumerate(group.kinds):
        (arm_a, arm_c), guides = group.arms[j], group._guides(j)
        length = np.broadcast_to(plain(group.coupler_length(j, k)), D)
        guide_a, guide_c = (np.broadcast_to(plain(0.0 if g is None else g), D) for g in guides)
        for d in range(D):
            compiled_coupled._hinged(
                compiled_coupled._CODES[kind], complex(gap[d]), complex(arm_a[d]),
                complex(arm_c[d]), float(length[d]), complex(guide_a[d]), complex(guide_c[d]),
                complex(sides[j][d]), float(group.size[d]), m, j)
            scale = np.abs(fitted[d, j]).max()
            assert np.abs(m[j] - fitted[d, j]).max() <= 1e-13 * scale


@pytest.mark.parametrize("form", FORMS)
def test_the_coefficients_from_laurent_products_are_the_sampled_ones(form: str) -> None:
    group, k = _inputs(form, 41 + FORMS.index(form))
    matrices = group._matrices(k)
    expected = group.coefficients(k)
    deflations, degree = group.form
    series = np.empty(9, dtype=complex)
    out = np.empty(2 * degree + 1, dtype=complex)
    for d in range(D):
        compiled_coupled._coefficients(np.ascontiguousarray(matrices[d]), group.eliminated,
                                       group.linear_kept, deflations, series, out)
        scale = np.abs(expected[d]).max()
        assert np.abs(out - expected[d]).max() <= 1e-11 * scale
