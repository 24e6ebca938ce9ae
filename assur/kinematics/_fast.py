"""Speed paths of the group solvers on plain arrays: the crank pin and the RRR dyad.

:mod:`assur.kinematics.dyads` holds the readable formulas, for numbers, arrays and jets alike.
For plain float arrays, the two groups of every mechanism (the crank and the RRR dyad) are
computed here instead, with the same formulas in the same order of operations, in real
arithmetic, with few temporaries and, for large calls, in blocks that stay in cache.
``tests/assur/test_dyads_fast.py`` checks that both paths give the same positions, margins,
existence and reasons.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["BLOCK", "NUMBERS", "REALS", "crank_pin", "finite", "positive", "rrr"]

#: Positions per block of the RRR kernel in large calls.
BLOCK = 8192

#: Number types (shape (), never a jet).
NUMBERS = frozenset({int, float, complex, np.float64, np.complex128})
REALS = frozenset({int, float, np.float64})

#: The RRR limits of a call where some position may not assemble: ``(l_i, l_j, d, margin)``
#: → margin settled, toggle mask, ``x`` at the toggles (``dyads._rrr_limits``).
Limits = Callable[..., tuple[np.ndarray, np.ndarray, np.ndarray]]

#: What the RRR kernel gives: C, φ_i, φ_j, the margin, the hinge distance d (arrays of the
#: call's shape) and the smallest margin.
Rrr = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]


def finite(x: np.ndarray) -> bool:
    """Whether every element of the array ``x`` is finite.

    Also False when a square overflows (elements beyond about 1e154): then the caller takes
    its general path, which gives the same result.

    One dot product (a single library call) for a vector, else one sum.
    """
    return cmath.isfinite(x.dot(x) if x.ndim == 1 else np.add.reduce(x, axis=None))


def crank_pin(o: Any, length: Any, angle: Any) -> np.ndarray | None:
    """Crank pin ``O + l·u(φ₁)`` of the crank solver's arguments, or None if not served here.

    Served: a finite pivot number, a finite length (a number, or per-design lengths of shape
    ``(D, 1)``) and a finite float array of angles. The unit vectors are scaled as
    interleaved (x, y) pairs: in place for one length, into a new array for many designs.
    """
    if not (type(angle) is np.ndarray and angle.ndim > 0 and angle.dtype == float
            and type(o) in NUMBERS and cmath.isfinite(o)
            and (type(length) in REALS and math.isfinite(length)
                 or type(length) is np.ndarray and length.dtype == float and finite(length))
            and finite(angle)):
        return None
    unit = np.empty(angle.shape, dtype=complex)
    np.cos(angle, out=unit.real)
    np.sin(angle, out=unit.imag)
    if type(length) is np.ndarray:
        unit_xy = unit.view(np.float64).reshape(*unit.shape, 2)
        pin = np.multiply(length[..., None], unit_xy).view(np.complex128)[..., 0]
    else:
        pin = unit
        np.multiply(unit.view(np.float64), length, out=unit.view(np.float64))
    if o != 0:
        pin += o
    return pin


def _blocks(shape: tuple[int, ...]) -> list[slice]:
    """Slices of the first axis cutting ``shape`` into blocks of about ``BLOCK`` positions."""
    row = math.prod(shape[1:])
    step = max(1, BLOCK // max(row, 1))
    return [slice(k, k + step) for k in range(0, shape[0], step)]


def rrr(h_i: Any, h_j: Any, l_i: Any, l_j: Any, s: Any, shape: tuple[int, ...],
        limits: Limits) -> Rrr:
    """``dyads._rrr_readable`` for plain numbers and arrays, over blocks of ``BLOCK`` positions.

    Returns C, φ_i, φ_j, the margin, the hinge distance d and the smallest margin. ``limits``
    settles toggles and coincident hinges where some position may not assemble. Blocking
    keeps the temporaries in cache and off the allocator for large calls (many designs × many
    angles); the blocks are written into the full-size outputs.
    """
    if math.prod(shape) <= 2 * BLOCK:
        return _rrr_block(h_i, h_j, l_i, l_j, s, shape, limits)
    args = [x if getattr(x, "ndim", 0) == 0 else np.broadcast_to(x, shape)
            for x in (h_i, h_j, l_i, l_j, s)]
    outputs = (np.empty(shape, complex), np.empty(shape), np.empty(shape), np.empty(shape),
               np.empty(shape))
    lowest = np.inf
    for rows in _blocks(shape):
        h_i, h_j, l_i, l_j, s = (x if getattr(x, "ndim", 0) == 0 else x[rows] for x in args)
        block = tuple(out[rows] for out in outputs)
        lowest = np.minimum(lowest, _rrr_block(h_i, h_j, l_i, l_j, s, block[0].shape, limits,
                                               block)[-1])
    return (*outputs, lowest)  # the minimum keeps a NaN


def positive(x: Any) -> bool:
    """Whether the number or every element of the array ``x`` is positive."""
    return bool((x if type(x) in REALS else np.minimum.reduce(x, axis=None)) > 0.0)


@np.errstate(all="ignore")
def _rrr_block(
    h_i: Any, h_j: Any, l_i: Any, l_j: Any, s: Any, shape: tuple[int, ...], limits: Limits,
    out: tuple[np.ndarray, ...] | None = None,
) -> Rrr:
    """``dyads._rrr_readable`` for plain arrays of ``shape``, in real arithmetic.

    ``out`` optionally gives the arrays for C, φ_i, φ_j, the margin and d. Every buffer is
    named after what it holds; a buffer reused for another quantity gets that quantity's name.
    """
    rx = np.subtract(h_j.real, h_i.real)  # r = H_j − H_i, as contiguous x and y
    ry = np.subtract(h_j.imag, h_i.imag)
    if rx.shape != shape:
        rx, ry = (np.array(np.broadcast_to(t, shape)) for t in (rx, ry))
    l_sum, l_dif, two_l_i = l_i + l_j, l_i - l_j, 2.0 * l_i
    l_squares = l_dif * l_sum
    c, angle_i, angle_j, margin, d = out if out is not None else (None,) * 5
    d2 = rx * rx
    d2 += ry * ry
    d = np.sqrt(d2, out=d)
    below = l_sum - d
    below *= d - l_dif  # 2·l_i·d·(1 − c), c = cos of the angle at H_i
    above = d + l_dif
    above *= l_sum + d  # 2·l_i·d·(1 + c)
    margin = np.minimum(below, above, out=margin)
    margin /= d
    margin /= two_l_i
    heron = np.multiply(below, above, out=below)  # Δ = 16·area²
    half_inv_d2 = np.divide(0.5, d2)  # 1/(2d²)
    along = np.add(d2, l_squares, out=d2)
    along *= half_inv_d2  # x
    lowest = np.minimum.reduce(margin, axis=None) if margin.size else np.inf
    if not (lowest >= 0.0 and positive(l_i) and positive(l_j)):
        settled, toggle, along_at_toggle = limits(l_i, l_j, d, margin)
        np.copyto(margin, settled)
        heron[toggle] = 0.0
        np.copyto(along, along_at_toggle, where=toggle)
        lowest = np.minimum.reduce(margin, axis=None)
    across = np.sqrt(heron, out=heron)  # NaN only where the dyad does not assemble
    across *= half_inv_d2  # y
    if type(s) is not float:
        across *= s
    elif s < 0.0:
        np.negative(across, out=across)  # σ·y
    arm_x = np.multiply(rx, along, out=above)  # (arm_x, arm_y) = C − H_i = r·(x + jσy)
    arm_x -= np.multiply(ry, across, out=half_inv_d2)
    arm_y = np.multiply(rx, across, out=across)
    arm_y += np.multiply(ry, along, out=along)
    angle_i = np.arctan2(arm_y, arm_x, out=angle_i)
    c = np.empty(shape, dtype=complex) if c is None else c
    np.add(h_i.real, arm_x, out=c.real)
    np.add(h_i.imag, arm_y, out=c.imag)
    arm_jx = np.subtract(arm_x, rx, out=arm_x)  # (arm_jx, arm_jy) = C − H_j
    arm_jy = np.subtract(arm_y, ry, out=arm_y)
    angle_j = np.arctan2(arm_jy, arm_jx, out=angle_j)
    return c, angle_i, angle_j, margin, d, lowest
