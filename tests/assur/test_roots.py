"""Real roots of trigonometric polynomials, bracketed by samples, against numpy's roots.

``roots.real_roots`` and ``roots.polish`` on random polynomials of degree 3 (the eliminant's
form): every real root that numpy's companion-matrix eigenvalues put on the unit circle is
found to 1e-10, with the sign of Φ′ computed here, unless it has a neighbour closer than the
samples' spacing; no root is invented; and ``roots.separation`` is never more than the true
distance to the nearest other root of p (a lower bound).
"""

from __future__ import annotations

import numpy as np

from assur.kinematics.higher.roots import SAMPLES, polish, real_roots, separation, trig_form

TWO_PI = 2.0 * np.pi


def _random(count: int, seed: int) -> np.ndarray:
    """Coefficients of p(E) = E³Φ for random Φ of degree 3 (φ₋ₙ = conj φₙ)."""
    rng = np.random.default_rng(seed)
    phi = rng.normal(size=(count, 4)) + 1j * rng.normal(size=(count, 4))
    phi[:, 0] = phi[:, 0].real
    return np.concatenate([np.conj(phi[:, :0:-1]), phi], axis=1)


def test_the_roots_are_numpys_on_the_unit_circle() -> None:
    coef = _random(400, 5)
    a, b = trig_form(coef)
    found = real_roots(a, b)
    theta = polish(a, b, found.low, found.high)
    missed = total = 0
    for p in range(len(coef)):
        every = np.roots(coef[p, ::-1])
        on = np.sort(np.mod(np.angle(every[np.abs(np.abs(every) - 1.0) < 1e-7]), TWO_PI))
        got = theta[p][~np.isnan(theta[p])]
        # nothing invented: every root found is one of numpy's
        assert all(np.min(np.abs(np.angle(np.exp(1j * (on - t))))) < 1e-10 for t in got)
        total += len(on)
        for t in on:
            near = np.abs(np.angle(np.exp(1j * (got - t)))) < 1e-10
            if not near.any():
                # only a root with a neighbour closer than the samples' spacing is missed
                gap = np.sort(np.abs(np.angle(np.exp(1j * (on - t)))))[1]
                assert gap < TWO_PI / SAMPLES
                missed += 1
                continue
            # the sign of Φ′ there, by a central difference of Φ(θ) = Re Σ φₙ e^{inθ}
            n = np.arange(-3, 4)
            h = 1e-6
            ahead, behind = (np.real(coef[p] @ np.exp(1j * n * (t + s))) for s in (h, -h))
            assert found.slope[p][~np.isnan(theta[p])][near][0] == np.sign(ahead - behind)
    assert missed <= 0.01 * total  # pairs that close are rare


def test_the_separation_bound_is_below_the_nearest_other_root() -> None:
    coef = _random(400, 6)
    a, b = trig_form(coef)
    found = real_roots(a, b)
    theta = polish(a, b, found.low, found.high)
    bound = separation(coef[:, None, :], theta)
    for p in range(len(coef)):
        every = np.roots(coef[p, ::-1])
        for t, rho in zip(theta[p], bound[p], strict=True):
            if np.isnan(t):
                continue
            distance = np.sort(np.abs(every - np.exp(1j * t)))[1]
            assert 0.0 < rho <= distance
