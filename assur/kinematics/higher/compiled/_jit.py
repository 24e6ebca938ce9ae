"""What the kernels share: how they are compiled, the scalar steps of more than one, and
how their arguments are laid out.

Every function here but :func:`per_position`, :func:`per_design` and :func:`design` is
compiled by numba; importing this module imports numba.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, TypeVar, cast

import numba
import numpy as np

from assur.kinematics.higher.groups import plain

__all__ = ["blank", "close", "cross", "design", "det2", "det3", "dot", "inline", "kernel",
           "over", "per_design", "per_position", "predict", "solve2", "solve3", "square"]

F = TypeVar("F", bound=Callable[..., Any])


def kernel(f: F) -> F:
    """``f`` compiled for the CPU and cached on disk; floating-point errors give inf and NaN
    as in numpy, never an exception. Where no cache directory is writable (neither next to
    the module nor the user's), it is compiled anew in each process instead."""
    try:
        return cast(F, numba.njit(cache=True, nogil=True, error_model="numpy")(f))
    except RuntimeError:  # numba found no cache directory it can write
        return cast(F, numba.njit(nogil=True, error_model="numpy")(f))


def inline(f: F) -> F:
    """A step of the kernels, compiled into each caller (no call, no array references)."""
    return cast(F, numba.njit(inline="always", error_model="numpy")(f))


@inline
def blank(p: int, x: np.ndarray, jac: np.ndarray, margin: np.ndarray, ok: np.ndarray) -> None:
    """Position ``p`` not corrected: its unknowns, Jacobian and margin NaN, its tests failed."""
    x[p, :] = math.nan
    jac[p, :, :] = math.nan
    margin[p], ok[p] = math.nan, False


def per_position(values: tuple[Any, ...], shape: tuple[int, ...], dtype: type) -> np.ndarray:
    """Values (None for 0) at the positions of ``shape``, laid flat, one row each:
    shape (len(values), P)."""
    out: np.ndarray = np.empty((len(values),) + shape, dtype=dtype)
    for i, v in enumerate(values):
        out[i] = 0.0 if v is None else plain(v)
    return out.reshape(len(values), -1)


def per_design(values: tuple[Any, ...], shape: tuple[int, ...], dtype: type) -> np.ndarray:
    """Drawn values (None for 0), each a number or one per design (the positions' last
    axis), as rows (len(values), D): the design of flat position p is p mod D."""
    out: np.ndarray = np.empty((len(values), shape[-1] if shape else 1), dtype=dtype)
    for i, v in enumerate(values):
        out[i] = 0.0 if v is None else design(v, shape)
    return out


def design(v: Any, shape: tuple[int, ...]) -> np.ndarray:
    """A drawn value (a number or one per design) or the sign of a mode per design, along
    the positions' last axis: shape (D,)."""
    row: np.ndarray = np.broadcast_to(plain(v), shape)[(0,) * (len(shape) - 1)]
    return np.asarray(row).reshape(-1)


@inline
def cross(a: complex, b: complex) -> float:
    """Im(ā b) (:func:`~assur.kinematics.jets.cross`)."""
    return (a.conjugate() * b).imag


@inline
def dot(a: complex, b: complex) -> float:
    """Re(ā b) (:func:`~assur.kinematics.jets.dot`)."""
    return (a.conjugate() * b).real


@inline
def det2(e00: float, e01: float, e10: float, e11: float) -> float:
    """The determinant by the first row's cofactors (:func:`~assur.kinematics.higher.groups.
    cofactors`)."""
    return e00 * e11 + e01 * -e10


@inline
def solve2(e00: float, e01: float, e10: float, e11: float, f0: float, f1: float
           ) -> tuple[float, float]:
    """x with e·x = f by Cramer's rule (:func:`~assur.kinematics.higher.modes.solve`)."""
    det = e00 * e11 + e01 * -e10
    return (e11 * f0 + -e01 * f1) / det, (-e10 * f0 + e00 * f1) / det


@inline
def det3(e00: float, e01: float, e02: float, e10: float, e11: float, e12: float,
         e20: float, e21: float, e22: float) -> float:
    """The determinant by the first row's cofactors (:func:`~assur.kinematics.higher.groups.
    cofactors`)."""
    return (e00 * (e11 * e22 - e12 * e21) + e01 * (e12 * e20 - e10 * e22)
            + e02 * (e10 * e21 - e11 * e20))


@inline
def solve3(e00: float, e01: float, e02: float, e10: float, e11: float, e12: float,
           e20: float, e21: float, e22: float, f0: float, f1: float, f2: float
           ) -> tuple[float, float, float]:
    """x with e·x = f by Cramer's rule (:func:`~assur.kinematics.higher.modes.solve`)."""
    c00, c01, c02 = e11 * e22 - e12 * e21, e12 * e20 - e10 * e22, e10 * e21 - e11 * e20
    c10, c11, c12 = e21 * e02 - e22 * e01, e22 * e00 - e20 * e02, e20 * e01 - e21 * e00
    c20, c21, c22 = e01 * e12 - e02 * e11, e02 * e10 - e00 * e12, e00 * e11 - e01 * e10
    det = e00 * c00 + e01 * c01 + e02 * c02
    return ((c00 * f0 + c10 * f1 + c20 * f2) / det, (c01 * f0 + c11 * f1 + c21 * f2) / det,
            (c02 * f0 + c12 * f1 + c22 * f2) / det)


@inline
def over(z: complex, r: float) -> complex:
    """z/r of a real r, part by part: numpy's complex division by a real, to the bit."""
    return complex(z.real / r, z.imag / r)


@inline
def square(z: complex) -> float:
    """|z|² = Re(z)² + Im(z)²."""
    return z.real * z.real + z.imag * z.imag


@inline
def close(coef: np.ndarray, theta: float, reach: float, work: np.ndarray) -> bool:
    """Whether ``reach`` is at most a quarter of the separation bound of the root e^{iθ} of p
    (coefficients ``coef`` in increasing powers; ``work`` holds as many numbers).

    The bound is :func:`~assur.kinematics.higher.roots.separation`'s: the Taylor shift
    q_j = p⁽ʲ⁺¹⁾(E*)/(j+1)! by synthetic division, and ρ = 1/(2·max_j |q_j/q_0|^{1/j}).
    ``reach`` ≤ ρ/4 is tested as |q_j|²·(8·reach)^{2j} ≤ |q_0|² for every j ≥ 1, the same
    inequality without its roots and divisions; False where a number is NaN.
    """
    n = coef.shape[0] - 1
    for i in range(n + 1):
        work[i] = coef[n - i]
    z = complex(math.cos(theta), math.sin(theta))
    for order in range(n):
        for i in range(1, n - order if order == 0 else n + 1 - order):
            work[i] = work[i] + z * work[i - 1]
    first = square(work[n - 1])
    step = (8.0 * reach) ** 2
    power = 1.0
    for j in range(1, n):
        power *= step
        if not square(work[n - 1 - j]) * power <= first:
            return False
    return True


@kernel
def predict(t: np.ndarray, x: np.ndarray, x1: np.ndarray, x2: np.ndarray, nearest: np.ndarray,
            targets: np.ndarray, s: float, out: np.ndarray) -> None:
    """The predictor x + s·h·x′ + ½h²·x″ (h = target − t) of every target from its state
    ``nearest`` (flat arrays: states (S,) and (S, n), targets (P,)), into ``out`` (P, n)."""
    for p in range(targets.shape[0]):
        q = nearest[p]
        h = targets[p] - t[q]
        for i in range(x.shape[1]):
            out[p, i] = x[q, i] + (s * h) * x1[q, i] + (0.5 * (h * h)) * x2[q, i]
