"""The class IV group's residual and Jacobian on many designs at once (more than
``coupled.FEW``, where the Jacobian is contracted in steps rather than at once): against
central differences of the residual, as on a few designs in ``test_higher_coupled.py``."""

from __future__ import annotations

import numpy as np
import pytest
from test_higher_coupled import COUPLED, SHARED, random_designs

from assur.kinematics.higher.coupled import FEW
from assur.kinematics.higher.groups import plain


@pytest.mark.parametrize("form", SHARED + COUPLED)
def test_jacobian_of_many_designs_against_central_differences(form: str) -> None:
    d = FEW + 44
    designs = random_designs(form, 170 + (SHARED + COUPLED).index(form), d)
    g = designs.group
    k = designs.inputs(np.full(d, 0.4))
    x = np.random.default_rng(17).uniform(-2.5, 2.5, (d, 2))
    size = np.asarray(g.size)[..., None]

    def residual(at: np.ndarray) -> np.ndarray:
        return np.stack(np.broadcast_arrays(*map(plain, g.residual(at, k))), axis=-1)

    f, jac = g.equations(x, k)
    assert np.allclose(f, residual(x), rtol=1e-12, atol=1e-12 * size)
    h = 1e-6
    for i in range(2):
        step = np.zeros(2)
        step[i] = h
        slope = (residual(x + step) - residual(x - step)) / (2.0 * h)
        scale = np.abs(slope).max(axis=-1, keepdims=True) + size * 1e-3
        assert (np.abs(jac[..., i] - slope) <= 1e-6 * scale).all(), i
