"""Kinematics of the crank-rocker four-bar in the paper's frame.

Frame S = 1 from the crank pivot (0, 0) to the rocker pivot (1, 0); crank end
``e·(cos θ, sin θ)``; rocker end ``(1, 0) + r·(−sin φ, cos φ)`` (φ measured from the
perpendicular to the frame); coupler length c. The loop closure (4) is
``b·sin φ + d·cos φ = a`` with the coefficients (5a); the paper's branch is (5) with the minus
sign in front of the root, continuous over the whole turn for a Grashof crank-rocker.

All functions broadcast over their arguments (designs of shape ``(D, 1)`` against crank
angles of shape ``(N,)`` give ``(D, N)``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from assur.typing import BoolArray

__all__ = [
    "coupler_bounds",
    "grashof_margin",
    "ratio_and_derivative",
    "ratio_derivative",
    "rocker_angle",
    "transmission_angle",
    "velocity_ratio",
]


def as_real(value: ArrayLike) -> NDArray[np.floating]:
    """An array of reals that keeps an extended precision (``np.longdouble``) if given."""
    array = np.asarray(value)
    return array if np.issubdtype(array.dtype, np.floating) else array.astype(float)


def rocker_angle(e: ArrayLike, c: ArrayLike, r: ArrayLike,
                 theta: ArrayLike) -> tuple[NDArray[np.floating], BoolArray]:
    """Rocker angle φ(θ) on the paper's branch, equation (5).

    Parameters
    ----------
    e, c, r : array_like
        Crank, coupler and rocker lengths divided by the frame length.
    theta : array_like
        Crank angle, radians.

    Returns
    -------
    phi : ndarray
        ``atan2(b, d) − arccos(a / sqrt(b² + d²))``, the angle whose sine is (5) with the minus
        sign; NaN where the chain does not close.
    exists : ndarray of bool
        Whether the chain closes (``b² + d² ≥ a²``).
    """
    e, c, r, theta = (as_real(v) for v in (e, c, r, theta))
    cos, sin = np.cos(theta), np.sin(theta)
    a = 1.0 + e * e + r * r - c * c - 2.0 * e * cos
    b = 2.0 * r * (1.0 - e * cos)
    d = 2.0 * r * e * sin
    radius = np.hypot(b, d)
    exists = np.abs(a) <= radius
    with np.errstate(invalid="ignore", divide="ignore"):
        phi = np.arctan2(b, d) - np.arccos(np.where(exists, a / radius, np.nan))
    return phi, exists


def velocity_ratio(e: ArrayLike, r: ArrayLike, theta: ArrayLike,
                   phi: ArrayLike) -> NDArray[np.floating]:
    """Velocity ratio n = dφ/dθ, equation (7).

    ``n = (e/r)·[r·cos(θ − φ) − sin θ] / [e·cos(θ − φ) − cos φ]``.
    """
    e, r, theta, phi = (as_real(v) for v in (e, r, theta, phi))
    ratio: NDArray[np.floating] = e / r * (r * np.cos(theta - phi) - np.sin(theta)) / (
        e * np.cos(theta - phi) - np.cos(phi))
    return ratio


def ratio_derivative(e: ArrayLike, r: ArrayLike, theta: ArrayLike, phi: ArrayLike,
                     n: ArrayLike) -> NDArray[np.floating]:
    """dn/dθ from the quotient rule applied to (7); its numerator set to zero is (8).

    With ``N = r·cos(θ−φ) − sin θ`` and ``D = e·cos(θ−φ) − cos φ``,
    ``N′ = −r(1−n)·sin(θ−φ) − cos θ`` and ``D′ = −e(1−n)·sin(θ−φ) + n·sin φ``, so
    ``dn/dθ = (e/r)·(N′D − N D′)/D²``.
    """
    e, r, theta, phi, n = (as_real(v) for v in (e, r, theta, phi, n))
    s = np.sin(theta - phi)
    k = np.cos(theta - phi)
    num = r * k - np.sin(theta)
    den = e * k - np.cos(phi)
    dnum = -r * (1.0 - n) * s - np.cos(theta)
    dden = -e * (1.0 - n) * s + n * np.sin(phi)
    derivative: NDArray[np.floating] = e / r * (dnum * den - num * dden) / (den * den)
    return derivative


def ratio_and_derivative(e: ArrayLike, c: ArrayLike, r: ArrayLike, theta: ArrayLike
                         ) -> tuple[NDArray[np.floating], NDArray[np.floating],
                                    NDArray[np.floating], BoolArray]:
    """n(θ), dn/dθ, φ(θ) and the closure mask for the given designs and crank angles."""
    phi, exists = rocker_angle(e, c, r, theta)
    n = velocity_ratio(e, r, theta, phi)
    return n, ratio_derivative(e, r, theta, phi, n), phi, exists


def grashof_margin(e: ArrayLike, c: ArrayLike, r: ArrayLike) -> NDArray[np.floating]:
    """How far the design is inside the Grashof crank-rocker domain (frame = 1, crank e).

    The design is a crank-rocker iff the three sums ``c + r − 1 − e``, ``1 + r − e − c`` and
    ``1 + c − e − r`` are positive (they make e the shortest link and s + l < p + q); the
    margin is the smallest of them (zero on a change-point linkage).
    """
    e, c, r = (as_real(v) for v in (e, c, r))
    margin: NDArray[np.floating] = np.minimum(np.minimum(c + r - 1.0 - e, 1.0 + r - e - c),
                                              1.0 + c - e - r)
    return margin


def coupler_bounds(e: ArrayLike, r: ArrayLike) -> tuple[NDArray[np.floating], NDArray[np.floating]]:
    """The open interval of coupler lengths c that make (e, c, r) a Grashof crank-rocker."""
    e, r = as_real(e), as_real(r)
    return np.maximum(1.0 + e - r, r + e - 1.0), 1.0 - e + r


def transmission_angle(e: ArrayLike, r: ArrayLike, theta: ArrayLike,
                       phi: ArrayLike) -> NDArray[np.floating]:
    """Transmission angle μ ∈ [0°, 90°] between coupler and rocker (radians).

    The angle between the coupler line (crank end to rocker end) and the rocker, folded into
    [0, π/2] so that 0 is a dead position and π/2 the best transmission.
    """
    e, r, theta, phi = (as_real(v) for v in (e, r, theta, phi))
    crank_end = e * np.exp(1j * theta)
    rocker = r * 1j * np.exp(1j * phi)
    coupler = 1.0 + rocker - crank_end
    sine = np.abs((np.conj(coupler) * rocker).imag) / (np.abs(coupler) * r)
    angle: NDArray[np.floating] = np.arcsin(np.clip(sine, 0.0, 1.0))
    return angle
