"""Speed paths of the group solvers on plain arrays: the crank pin and the RRR dyad.

:mod:`assur.kinematics.dyads` holds the readable formulas, for numbers, arrays and jets alike.
For plain float arrays, the two groups of every mechanism (the crank and the RRR dyad) are
computed here instead, with the same formulas in the same order of operations: lengths in
real arithmetic, points as complex numbers, few numpy calls and few temporaries. The RRR
kernel keeps its scratch arrays between calls (per thread, for the last few call shapes), with
the arrays it makes of the last few pairs of link lengths, finds the smallest margin by one
``argmin`` and cuts large calls into blocks that stay in cache. ``tests/assur/test_dyads_fast.py``
checks that both paths give the same positions, margins, existence and reasons;
``tests/assur/test_dyads_scratch.py`` that no result shares the scratch arrays;
``tests/assur/test_dyads_speed_path.py`` the usual call against answers found another way.
"""

from __future__ import annotations

import cmath
import math
import threading
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from assur.kinematics.jets import HALF
from assur.kinematics.jets import unit as unit_vectors

__all__ = ["BLOCK", "NUMBERS", "REALS", "crank_pin", "finite", "positive", "rrr", "smallest"]

#: Positions per block of the RRR kernel in large calls.
BLOCK = 8192

#: Number types (shape (), never a jet).
NUMBERS = frozenset({int, float, complex, np.float64, np.complex128})
REALS = frozenset({int, float, np.float64})

#: The RRR limits of a call where some position may not assemble: ``(l_i, l_j, d, margin)``
#: → margin settled, toggle mask, ``x`` at the toggles (``dyads._rrr_limits``).
Limits = Callable[..., tuple[np.ndarray, np.ndarray, np.ndarray]]

#: What the RRR kernel gives: C, φ_i, φ_j, the margin, the hinge distance d (arrays of the
#: call's shape) and the smallest margin. C, the angles and the margin are the caller's; d
#: may be a scratch array, valid until the thread's next call of the kernel.
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
    unit = unit_vectors(angle)
    parts = unit.view(np.float64)  # x, y, x, y, …
    if type(length) is np.ndarray:
        pairs = parts.reshape(*unit.shape, 2)
        pin = np.multiply(length[..., None], pairs).view(np.complex128)[..., 0]
    else:
        pin = unit
        np.multiply(parts, length, parts)
    if o != 0:
        pin += o
    return pin


def _blocks(shape: tuple[int, ...]) -> list[slice]:
    """Slices of the first axis cutting ``shape`` into blocks of about ``BLOCK`` positions."""
    row = math.prod(shape[1:])
    step = max(1, BLOCK // max(row, 1))
    return [slice(k, k + step) for k in range(0, shape[0], step)]


@np.errstate(all="ignore")
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
    c, angles, margin, d = (np.empty(shape, complex), np.empty((2, *shape)), np.empty(shape),
                            np.empty(shape))
    lowest = np.inf
    for rows in _blocks(shape):
        h_i, h_j, l_i, l_j, s = (x if getattr(x, "ndim", 0) == 0 else x[rows] for x in args)
        out = (c[rows], angles[:, rows], margin[rows], d[rows])
        lowest = np.minimum(lowest, _rrr_block(h_i, h_j, l_i, l_j, s, out[0].shape, limits,
                                               out)[-1])
    return c, angles[0], angles[1], margin, d, lowest  # the minimum keeps a NaN


def smallest(x: np.ndarray) -> float:
    """The smallest element of the array ``x``: NaN if any is NaN, +inf if it is empty.

    Found by ``argmin``, which costs less than a ufunc reduction for a few hundred elements.
    """
    return x.item(x.argmin()) if x.size else math.inf


def positive(x: Any) -> bool:
    """Whether the number or every element of the array ``x`` is positive."""
    return bool((x if type(x) in REALS else np.minimum.reduce(x, axis=None)) > 0.0)


#: Call shapes whose scratch arrays each thread keeps (the oldest is dropped first).
SCRATCH_SHAPES = 4


class _Lengths(NamedTuple):
    """What the RRR kernel uses of the link lengths l_i, l_j.

    l_i + l_j, l_i − l_j, (l_i − l_j)(l_i + l_j) and 2·l_i as arrays of shape () for numbers
    (cheaper ufunc operands) or the per-design arrays, and whether both lengths are positive.
    """

    l_sum: np.ndarray
    l_dif: np.ndarray
    l_squares: np.ndarray
    two_l_i: np.ndarray
    positive: bool


def _lengths(l_i: Any, l_j: Any) -> _Lengths:
    """The :class:`_Lengths` of the link lengths ``l_i``, ``l_j``."""
    total, difference = l_i + l_j, l_i - l_j  # numbers, or per-design arrays
    return _Lengths(np.asarray(total), np.asarray(difference), np.asarray(difference * total),
                    np.asarray(2.0 * l_i), positive(l_i) and positive(l_j))


#: Pairs of link lengths (numbers) whose :class:`_Lengths` a scratch set keeps.
KEPT_LENGTHS = 8


class _Work:
    """Scratch arrays of the RRR kernel over one call shape, with the views it writes through.

    Three buffers hold everything, as in the kernel's order of work: r and x + jσy; d² and d;
    the four factors of the margins, whose products, then Δ and 1/(2d²), take the place of
    the first two. Once x + jσy is used, the arms C − H_i and C − H_j take the place of the
    factors and their parts, laid out for ``arctan2``, the place of r and x + jσy. None of
    them is ever part of a result. The :class:`_Lengths` of the last few pairs of link lengths
    given as numbers are kept with them (:meth:`lengths_of`).
    """

    __slots__ = ("above", "arm_i", "arm_j", "arm_parts", "below", "both", "d", "d2", "factors",
                 "firsts", "kept", "r", "r_parts", "seconds", "turn", "turn_parts", "x", "y")

    def __init__(self, shape: tuple[int, ...]) -> None:
        points = np.empty((2, *shape), complex)
        self.r, self.turn = points  #: H_j − H_i; x + jσy, first the squares of the parts of r
        self.r_parts, self.turn_parts = self.r.view(np.float64), self.turn.view(np.float64)
        self.x, self.y = self.turn.real, self.turn.imag
        #: the parts of both arms as (x or y, arm, *shape), contiguous, over r and x + jσy
        self.both = points.reshape(-1).view(np.float64).reshape(2, 2, *shape)
        self.d2, self.d = np.empty((2, *shape))
        #: l_i + l_j − d, d + (l_i − l_j) | d − (l_i − l_j), d + l_i + l_j: the factors of the
        #: products below | above (2·l_i·d·(1 ∓ c)), which are written over the first half
        self.factors = np.empty((4, *shape))
        self.firsts, self.seconds = self.factors[:2], self.factors[2:]
        self.below, self.above = self.firsts
        arms = self.factors.reshape(-1).view(complex).reshape(2, *shape)
        self.arm_i, self.arm_j = arms  #: C − H_i and C − H_j, over the factors
        self.arm_parts = np.moveaxis(arms.view(np.float64).reshape(2, *shape, 2), -1, 0)
        self.kept: dict[tuple[Any, ...], _Lengths] = {}

    def lengths_of(self, l_i: Any, l_j: Any) -> _Lengths:
        """The :class:`_Lengths` of ``l_i``, ``l_j``; kept if both are numbers."""
        if type(l_i) not in REALS or type(l_j) not in REALS:
            return _lengths(l_i, l_j)
        key = (type(l_i), l_i, type(l_j), l_j)
        lengths = self.kept.get(key)
        if lengths is None:
            if len(self.kept) >= KEPT_LENGTHS:
                self.kept.clear()
            lengths = self.kept[key] = _lengths(l_i, l_j)
        return lengths


class _Scratch(threading.local):
    """The RRR kernel's scratch arrays by call shape, one set per thread.

    Calls at one resolution, again and again, reuse arrays that are warm in cache and views
    made once, instead of taking new ones from the allocator.
    """

    def __init__(self) -> None:
        self.by_shape: dict[tuple[int, ...], _Work] = {}

    def get(self, shape: tuple[int, ...]) -> _Work:
        """The scratch arrays for ``shape``."""
        work = self.by_shape.get(shape)
        if work is None:
            if len(self.by_shape) >= SCRATCH_SHAPES:
                del self.by_shape[next(iter(self.by_shape))]
            work = self.by_shape[shape] = _Work(shape)
        return work


_SCRATCH = _Scratch()


def _rrr_block(
    h_i: Any, h_j: Any, l_i: Any, l_j: Any, s: Any, shape: tuple[int, ...], limits: Limits,
    out: tuple[np.ndarray, ...] | None = None,
) -> Rrr:
    """``dyads._rrr_readable`` for plain arrays of ``shape``, with the same operations.

    ``out`` optionally gives the arrays for C, the link angles (stacked, shape ``(2, *shape)``),
    the margin and d. The distances are computed in real arithmetic on the parts of
    r = H_j − H_i; the two products of the margins' four factors come from one
    multiplication; the arms C − H_i = r·(x + jσy) and C − H_j are complex, and both link
    angles come from one ``arctan2`` over their parts, copied contiguous by one call. Number
    operands enter as arrays of shape () (cheaper ufunc calls, the same values).
    """
    c, angles, margin, d = out if out is not None else (None,) * 4
    work = _SCRATCH.get(shape)
    l_sum, l_dif, l_squares, two_l_i, lengths_positive = work.lengths_of(l_i, l_j)
    r, x, y, d2, factors = work.r, work.x, work.y, work.d2, work.factors
    np.subtract(h_j, h_i, r)  # complex whatever the points' type
    np.multiply(work.r_parts, work.r_parts, work.turn_parts)
    r_x2, r_y2 = x, y  # turn holds the squares of the parts of r until x is computed
    np.add(r_x2, r_y2, d2)
    d = np.sqrt(d2, work.d if d is None else d)
    np.subtract(l_sum, d, factors[0])
    np.add(d, l_dif, factors[1])
    np.subtract(d, l_dif, factors[2])
    np.add(l_sum, d, factors[3])
    np.multiply(work.firsts, work.seconds, work.firsts)
    below, above = work.below, work.above  # 2·l_i·d·(1 ∓ c)
    margin = np.minimum(below, above, out=margin)
    margin /= d
    margin /= two_l_i
    heron = np.multiply(below, above, below)  # Δ = 16·area²
    half_inv_d2 = np.divide(HALF, d2, above)  # 1/(2d²)
    np.multiply(np.add(d2, l_squares, d2), half_inv_d2, x)
    lowest = smallest(margin)
    if not (lowest >= 0.0 and lengths_positive):
        settled, toggle, x_at_toggle = limits(l_i, l_j, d, margin)
        np.copyto(margin, settled)
        heron[toggle] = 0.0
        np.copyto(x, x_at_toggle, where=toggle)
        lowest = smallest(margin)
    np.multiply(np.sqrt(heron, heron), half_inv_d2, y)  # NaN where the dyad does not assemble
    if type(s) is not float:
        y *= s
    elif s < 0.0:
        np.negative(y, y)  # σ·y
    arm_i = np.multiply(r, work.turn, work.arm_i)
    c = np.add(h_i, arm_i, c)
    np.subtract(arm_i, r, work.arm_j)
    both = work.both
    np.copyto(both, work.arm_parts)
    angles = np.arctan2(both[1], both[0], angles)
    return c, angles[0], angles[1], margin, d, lowest
