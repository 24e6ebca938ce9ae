"""Task class 5: rigid-body guidance, the deviations of a guided segment.

The course's third kind of driven object is a mechanism that "reproduces a given plane
motion of a segment (or a plane figure) fixed on the coupler".  The segment AB is fixed on
the output link: A is the link's point Ж (``output: point``), B lies ``length`` = L mm from
A in the direction θ = (angle of the link's local frame) + γ, where γ, the angle of the
segment on the link, is fixed or varied (``output: angle``).  A control position K gives
the required pose of the segment, (x_K, y_K, θ_K): A_K = x_K + i·y_K and
B_K = A_K + L·e^(iθ_K).  The deviation at K is the larger deviation of the two end points::

    Δ_K = E_K · max(|A(φ_K) − A_K|, |B(φ_K) − B_K|)

in mm.  Δ_K = 0 exactly when the segment is in its required pose, and every point of the
segment deviates by at most Δ_K/E_K (a point between A and B moves by a convex combination
of the end points' deviations), so Q = max_K Δ_K bounds the deviation of the whole segment.
A task without timing (rows without ``phi``) compares each required pose with the nearest
pose of the cycle, the one where |A − A_K|² + |B − B_K|² is least.

Examples
--------
A segment of length 10 in its required pose, and one turned by 90° about A:

>>> import numpy as np
>>> a = np.array([[0j, 0j]])
>>> theta = np.array([[0.0, np.pi / 2]])
>>> segment_deviations(a, theta, np.array([0j, 0j]), np.zeros(2), 10.0,
...                    np.ones(2)).round(9).tolist()
[[0.0, 14.142135624]]
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from assur.typing import ComplexArray, FloatArray

__all__ = ["nearest_pose", "segment_deviations", "segment_ends", "segment_residuals"]


def segment_ends(point: ComplexArray, angle: FloatArray, length: float
                 ) -> tuple[ComplexArray, ComplexArray]:
    """The end points A, B of segments starting at ``point`` in the directions ``angle``.

    ::

        A = point,   B = point + L·e^(iθ)
    """
    a: ComplexArray = np.asarray(point, dtype=complex)
    b: ComplexArray = a + length * np.exp(1j * np.asarray(angle, dtype=float))
    return a, b


def segment_deviations(point: ComplexArray, angle: FloatArray, target: ComplexArray,
                       target_angle: FloatArray, length: float,
                       weights: FloatArray) -> FloatArray:
    """Weighted deviations of a guided segment (task class 5).

    ::

        Δ_K = E_K · max(|A − A_K|, |B − B_K|)

    Parameters
    ----------
    point : array_like of complex, shape (D, K)
        The start A of each design's segment at the control positions.
    angle : array_like, shape (D, K)
        Its direction θ (radians).
    target : array_like of complex, shape (K,)
        Required starts A_K.
    target_angle : array_like, shape (K,)
        Required directions θ_K (radians).
    length : float
        L, mm (> 0).
    weights : array_like, shape (K,)
        Weights E_K.

    Returns
    -------
    ndarray, shape (D, K)
    """
    gap_a, gap_b = _gaps(point, angle, target, target_angle, length)
    out: FloatArray = np.asarray(weights) * np.maximum(np.abs(gap_a), np.abs(gap_b))
    return out


def segment_residuals(point: ComplexArray, angle: FloatArray, target: ComplexArray,
                      target_angle: FloatArray, length: float,
                      weights: FloatArray) -> FloatArray:
    """Smooth components of the class-5 deviations, for the least-squares refinement.

    The coordinates of E_K·(A − A_K) and E_K·(B − B_K), shape (D, 4K): their sum of squares
    is Σ_K E_K²·(|A − A_K|² + |B − B_K|²), zero exactly where every Δ_K is, and each Δ_K²
    lies between half of its two terms' sum and the sum.
    """
    gap_a, gap_b = _gaps(point, angle, target, target_angle, length)
    w = np.asarray(weights)
    return np.concatenate([(w * gap_a).real, (w * gap_a).imag, (w * gap_b).real,
                           (w * gap_b).imag], axis=-1)


def nearest_pose(a: ComplexArray, b: ComplexArray, a_k: ComplexArray, b_k: ComplexArray, *,
                 chunk: int = 128) -> npt.NDArray[np.intp]:
    """The grid position of each design's pose nearest to each required pose (no timing).

    ::

        m_K = argmin_m (|A_m − A_K|² + |B_m − B_K|²)

    Parameters
    ----------
    a, b : array_like of complex, shape (D, N)
        The segment's ends at the grid positions (NaN where a design does not exist).
    a_k, b_k : array_like of complex, shape (K,)
        The required ends.
    chunk : int
        Designs handled per block, to bound memory (D·K·N distances per block).

    Returns
    -------
    ndarray of int, shape (D, K)

    Examples
    --------
    >>> a = np.array([[0j, 1 + 0j, 2 + 0j]])
    >>> nearest_pose(a, a + 1j, np.array([1.9 + 0j]), np.array([1.9 + 1j])).tolist()
    [[2]]
    """
    a, b = np.asarray(a, dtype=complex), np.asarray(b, dtype=complex)
    a_k, b_k = np.asarray(a_k, dtype=complex), np.asarray(b_k, dtype=complex)
    index = np.empty((a.shape[0], a_k.size), dtype=np.intp)
    for start in range(0, a.shape[0], chunk):
        block = slice(start, start + chunk)
        gap = (np.abs(a[block, None, :] - a_k[None, :, None]) ** 2
               + np.abs(b[block, None, :] - b_k[None, :, None]) ** 2)
        index[block] = np.argmin(np.where(np.isnan(gap), np.inf, gap), axis=-1)
    return index


def _gaps(point: ComplexArray, angle: FloatArray, target: ComplexArray,
          target_angle: FloatArray, length: float) -> tuple[ComplexArray, ComplexArray]:
    """A − A_K and B − B_K."""
    a, b = segment_ends(point, angle, length)
    a_k, b_k = segment_ends(target, target_angle, length)
    return a - a_k, b - b_k
