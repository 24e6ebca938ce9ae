"""The reciprocal condition number of the batched equilibrium solve (``assur.forces.linear``)
against the exact one computed here from the explicit inverse, ``1/(‖A‖₁·‖A⁻¹‖₁)``.

The estimate of ``‖A⁻¹‖₁`` is a lower bound (in exact arithmetic), so the reported number is
not below the exact one (beyond the round-off of the inverse of a nearly singular matrix), and
it stays within a factor of 10 of it on well-conditioned, badly scaled and nearly singular
matrices alike (the dead position of a group is a nearly singular matrix).
"""

from __future__ import annotations

import numpy as np

from assur.forces.linear import _solve


def exact_rcond(matrix: np.ndarray) -> np.ndarray:
    inverse = np.linalg.inv(matrix)
    return np.asarray(1.0 / (np.abs(matrix).sum(axis=-2).max(axis=-1)
                             * np.abs(inverse).sum(axis=-2).max(axis=-1)))


def test_the_condition_estimate_is_never_below_and_close_to_the_exact_one() -> None:
    rng = np.random.default_rng(26)
    n, count = 12, 600
    u, _ = np.linalg.qr(rng.standard_normal((count, n, n)))
    v, _ = np.linalg.qr(rng.standard_normal((count, n, n)))
    smallest = 10.0 ** rng.uniform(-13.0, 0.0, count)  # down to the dead position
    sigma = np.concatenate([np.ones((count, n - 1)) * rng.uniform(0.5, 2.0, (count, 1)),
                            smallest[:, None]], axis=-1)
    matrix = np.einsum("bij,bj,bkj->bik", u, sigma, v)
    matrix[::3] *= 10.0 ** rng.uniform(-3.0, 3.0, (len(matrix[::3]), n, 1))  # row scales
    rhs = rng.standard_normal((count, n))
    x, rcond = _solve(matrix, rhs)
    exact = exact_rcond(matrix)
    solved = rcond > 1e-14
    assert np.all(rcond[solved] >= exact[solved] * (1 - 1e-2))
    assert np.all(rcond[solved] <= 10.0 * exact[solved])
    assert np.median(rcond / exact) < 1.01  # mostly the exact number
    residual = np.einsum("bij,bj->bi", matrix, x) - rhs
    scale = np.abs(matrix).sum(axis=-1) * np.abs(x).max(axis=-1, keepdims=True)
    assert np.all(np.abs(residual[solved]) <= 1e-9 * scale[solved] + 1e-12)
