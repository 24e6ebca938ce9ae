"""Closed-form, vectorised position solvers of the input group L0 and the dyads L1–L5.

Formulas and sign conventions follow ``method.md`` §2.0–2.6; ``docs/group_solvers.md`` gives
the summary. Points are complex numbers ``x + 1j*y``; angles are radians. Every argument may
be a number, an ndarray or a :class:`~assur.kinematics.jets.Jet`; all of them broadcast together, so
parameters shaped ``(D, 1)`` (D candidate designs) and crank angles shaped ``(N,)`` give
results shaped ``(D, N)``. When any argument is a jet, every geometric output is a jet
carrying exact first and second derivatives (velocity and acceleration analogs).

A position where the group cannot be assembled is data, not an error: the solver returns NaN
for the geometric outputs there, ``exists = False``, the normalised ``margin`` (negative or
below the assigned tolerance δ) and a ``reason`` code (see :data:`REASONS`).
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from enum import IntEnum
from functools import lru_cache

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.jets import Jet
from assur.text import render

__all__ = [
    "REASONS",
    "DyadSolution",
    "Reason",
    "reason_text",
    "solve_input",
    "solve_prp",
    "solve_rpp",
    "solve_rpr",
    "solve_rrp",
    "solve_rrr",
]

Value = Jet | np.ndarray | complex | float

#: A negative margin no larger than this is roundoff at a toggle position and is read as 0.
ROUNDOFF = 64.0 * np.finfo(float).eps

#: Positions per block in the plain-array kernels of large calls.
BLOCK = 8192

#: Number types (shape (), never a jet).
_NUMBERS = frozenset({int, float, complex, np.float64, np.complex128})
_REALS = frozenset({int, float, np.float64})


class Reason(IntEnum):
    """Why a group does not assemble at a position (``DyadSolution.reason``)."""

    ASSEMBLES = 0
    STRETCHED = 1
    FOLDED = 2
    ROD_TOO_SHORT = 3
    OFFSET_TOO_LARGE = 4
    GUIDES_PARALLEL = 5
    COINCIDENT_HINGES = 6
    UNDEFINED_INPUT = 7


def reason_text(code: int, lang: str = "en") -> str:
    """Why a group does not assemble, as a sentence in ``lang``.

    The sentence of :class:`Reason` ``R`` is the catalogue entry ``reason.<r>``
    (``Reason.FOLDED`` → ``reason.folded``, :mod:`assur.text`).

    >>> reason_text(Reason.FOLDED), reason_text(Reason.FOLDED, "ru")
    ('hinges too close (folded)', 'шарниры слишком близко (цепь сложена)')
    """
    return render(f"reason.{Reason(code).name.lower()}", lang)


class _Reasons(Mapping[int, tuple[str, str]]):
    """Reason code → (English sentence, Russian sentence), read from the catalogue."""

    def __getitem__(self, code: int) -> tuple[str, str]:
        if code not in set(Reason):
            raise KeyError(code)
        return reason_text(code, "en"), reason_text(code, "ru")

    def __iter__(self) -> Iterator[int]:
        return iter(int(r) for r in Reason)

    def __len__(self) -> int:
        return len(Reason)


#: Reason code → (English sentence, Russian sentence); :func:`reason_text` gives any language.
REASONS: Mapping[int, tuple[str, str]] = _Reasons()


@dataclass(frozen=True)
class DyadSolution:
    """Positions of one group over all requested positions.

    Attributes
    ----------
    c : ndarray or Jet, complex
        The internal joint C (L1, L2, L4), the reference point of the internal slider (L3: the
        point of the kulisa axis abreast of the block hinge, ``H_i + T·u(φ_i)``; L5: the
        intersection of the two guide paths), or the crank pin A (L0).
    origin_i, angle_i, origin_j, angle_j : ndarray or Jet
        Local frames of links i and j (``method.md`` §2.0): a point fixed on link i with local
        coordinate ``z`` is ``origin_i + z * exp(1j*angle_i)``. Angles are in (−π, π] where
        the solver computes them, or the given guide angles. L0 has only link i
        (``origin_j``, ``angle_j`` are None).
    s_i, s_j : ndarray or Jet or None
        Slider coordinates: L2 ``s_i = S``; L3 ``s_i = T``; L4 ``s_i = S_i``, ``s_j = S_j``;
        L5 ``s_i = S``, ``s_j = T``; None where the kind has no such coordinate.
    margin : ndarray, real
        Normalised existence margin (``method.md`` §5.4): L1 ``1 − |c|``, L2 ``1 − |h|/l_j``,
        L3 ``1 − |h|/ρ``, L4 ``|sin(θ_j − θ_i)|``, L5 ``|sin γ|``, L0 1.
    exists : ndarray, bool
        ``margin >= delta``; False where the margin is NaN (an input is undefined) and, for L4
        and L5, where the guides are parallel within roundoff (``margin <= ROUNDOFF``).
    reason : ndarray, int8
        0 where the group exists, else a :class:`Reason` code (the condition that fails, or
        the nearest one when the margin is only below δ).

    Notes
    -----
    Every output has the broadcast shape of the arguments; outputs that are constant over it
    (a fixed origin, an all-true mask) are read-only views rather than copies.
    Geometric outputs are NaN wherever ``exists`` is False. To see the geometry inside the
    tolerance band, solve with ``delta=0`` and compare ``margin`` with δ yourself.
    """

    c: Value
    origin_i: Value
    angle_i: Value
    origin_j: Value | None
    angle_j: Value | None
    s_i: Value | None
    s_j: Value | None
    margin: np.ndarray
    exists: np.ndarray
    reason: np.ndarray


def _branch(sigma: float | np.ndarray) -> float | np.ndarray:
    """Assembly sign as ±1.0; 0 (the L3 default of table 1.6) reads as +1."""
    if getattr(sigma, "ndim", 0) == 0:
        return -1.0 if sigma < 0 else 1.0
    return np.where(sigma < 0, -1.0, 1.0)


def _layout(*args: object) -> tuple[tuple[int, ...], bool]:
    """Broadcast shape of the values of ``args`` and whether any of them is a jet."""
    shape: tuple[int, ...] = ()
    jets = False
    for a in args:
        kind = type(a)
        if kind in _NUMBERS:
            continue
        if kind is np.ndarray:
            this = a.shape
        elif kind is Jet:
            this, jets = a.v.shape, True
        else:
            this = np.shape(a)
        if this != shape and this:
            shape = np.broadcast_shapes(shape, this) if shape else this
    return shape, jets


@lru_cache(maxsize=256, typed=True)
def _constant(x: object, shape: tuple[int, ...]) -> np.ndarray:
    """A read-only array of ``shape`` whose every element is the number ``x``, without a copy.

    Cached: solvers called again and again at one resolution share these views.
    """
    base = np.array([x])
    base.flags.writeable = False
    return np.ndarray(shape, base.dtype, base, 0, (0,) * len(shape))


def _finite(x: np.ndarray) -> bool:
    """Whether every element of the array ``x`` is finite.

    Also False when a square overflows (elements beyond about 1e154): then the caller takes
    its general path, which gives the same result.

    One dot product (a single library call) for a vector, else one sum.
    """
    return cmath.isfinite(x.dot(x) if x.ndim == 1 else np.add.reduce(x, axis=None))


def _zero_dim(*values: Value) -> tuple[Value, ...]:
    """Real Python numbers as 0-d float64 arrays, other values unchanged.

    With a float64 array, numpy applies a 0-d array sooner than a Python number, with the
    same result.
    """
    return tuple(np.array(x, np.float64) if type(x) in _REALS else x for x in values)


@lru_cache(maxsize=64)
def _assembled(shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Margin 1, ``exists`` True and reason 0 over ``shape``: read-only views, cached."""
    return (_constant(1.0, shape), _constant(True, shape),
            _constant(np.int8(Reason.ASSEMBLES), shape))


_new = object.__new__


def _solution(
    c: Value, origin_i: Value, angle_i: Value, origin_j: Value | None, angle_j: Value | None,
    s_i: Value | None, s_j: Value | None, margin: np.ndarray, exists: np.ndarray,
    reason: np.ndarray,
) -> DyadSolution:
    """A :class:`DyadSolution` with its fields stored directly.

    The generated frozen ``__init__`` sets them one by one through ``object.__setattr__``.
    """
    solution = _new(DyadSolution)
    fields = solution.__dict__
    fields["c"], fields["origin_i"], fields["angle_i"] = c, origin_i, angle_i
    fields["origin_j"], fields["angle_j"], fields["s_i"], fields["s_j"] = (
        origin_j, angle_j, s_i, s_j)
    fields["margin"], fields["exists"], fields["reason"] = margin, exists, reason
    return solution


def _spread(x: Value, shape: tuple[int, ...]) -> Value:
    """``x`` with its value broadcast to ``shape``: ``x`` itself, or a read-only view."""
    if type(x) is Jet:
        return x if x.v.shape == shape else Jet(np.broadcast_to(x.v, shape), x.d1, x.d2)
    if getattr(x, "shape", ()) == shape:
        return x
    if getattr(x, "ndim", 0) == 0:
        return _constant(x[()] if type(x) is np.ndarray else x, shape)
    return np.broadcast_to(x, shape)


def _clip_roundoff(margin: np.ndarray, radicand: Value) -> tuple[np.ndarray, Value, float]:
    """Margin and radicand with deficits within roundoff set to 0, and the smallest margin.

    A deficit within roundoff is read as the toggle position itself. In the usual case of no
    negative margin one reduction finds that out (and the smallest margin).
    """
    lowest = np.minimum.reduce(margin, axis=None) if margin.size else np.inf
    if lowest >= 0.0:
        return margin, radicand, lowest
    tiny = (margin < 0.0) & (margin > -ROUNDOFF)
    if tiny.any():
        margin = np.where(tiny, 0.0, margin)
        radicand = J.where(tiny, 0.0, radicand)
        lowest = np.minimum.reduce(margin, axis=None)
    return margin, radicand, lowest


def _blank(
    geometry: tuple[Value | None, ...], bad: np.ndarray, owned: tuple[Value, ...],
) -> tuple[Value | None, ...]:
    """The outputs ``geometry`` with NaN where ``bad`` (an output repeated is blanked once).

    Arrays in ``owned`` (made by the solver for this call) are blanked in place; the others
    (inputs passed through, constant views) are copied.
    """
    done: dict[int, Value] = {}
    fresh = {id(x) for x in owned if type(x) is np.ndarray and x.shape == bad.shape}
    for x in geometry:
        if x is not None and id(x) not in done:
            nan = complex(np.nan, np.nan) if np.iscomplexobj(J.value(x)) else np.nan
            if id(x) in fresh:
                np.copyto(x, nan, where=bad)
                done[id(x)] = x
            else:
                done[id(x)] = J.where(bad, nan, x)
    return tuple(None if x is None else done[id(x)] for x in geometry)


def _undefined(inputs: tuple[Value, ...]) -> np.ndarray | bool:
    """Mask of the positions where some input is NaN or infinite (False: nowhere).

    An array input found finite by one reduction needs no elementwise test.
    """
    undefined: np.ndarray | bool = False
    for x in inputs:
        v = J.value(x)
        kind = type(v)
        if kind in _NUMBERS and cmath.isfinite(v) or kind is np.ndarray and _finite(v):
            continue
        undefined = undefined | ~np.isfinite(v)
    return undefined


def _finish(
    shape: tuple[int, ...],
    inputs: tuple[Value, ...],
    margin: np.ndarray,
    delta: float | np.ndarray,
    failure: Callable[[], np.ndarray],
    geometry: tuple[Value | None, ...],
    jets: bool,
    above: float | None = None,
    lowest: float | None = None,
    owned: tuple[Value, ...] = (),
) -> DyadSolution:
    """Existence mask, reason codes and NaN blanking common to all solvers.

    ``shape`` is the broadcast shape of the solver's arguments ``inputs``; ``geometry`` holds
    the outputs ``c, origin_i, angle_i, origin_j, angle_j, s_i, s_j``, made jets if ``jets``
    (some argument is a jet). ``failure()`` returns the reason code of each position as if it
    failed; it is evaluated only when some position does fail. ``above`` (optional) is a
    further condition of existence, ``margin > above``; ``lowest`` is the smallest margin when
    the caller already knows it; ``owned`` lists the outputs made for this call (blanked in
    place).
    """
    margin = margin if margin.shape == shape else np.broadcast_to(margin, shape)
    if jets:  # constant outputs become jets too
        geometry = tuple(x if x is None or type(x) is Jet else Jet(x) for x in geometry)
    if lowest is None:
        lowest = np.minimum.reduce(margin, axis=None) if margin.size else np.inf
    if lowest >= (delta if type(delta) in _NUMBERS else np.max(delta)) and (
            above is None or lowest > above):
        _, exists, reason = _assembled(shape)  # one reduction found every position assembled
    else:
        exists = margin >= delta
        if above is not None:
            exists &= margin > above
        bad = ~exists
        reason = np.zeros(bad.shape, dtype=np.int8)
        np.copyto(reason, failure(), where=bad)
        undefined = _undefined(inputs)
        if undefined is not False:
            np.copyto(reason, Reason.UNDEFINED_INPUT, where=bad & undefined)
        geometry = _blank(geometry, bad, owned)
    return _solution(*geometry, margin, exists, reason)


def solve_input(o: Value, length: Value, angle: Value) -> DyadSolution:
    """L0, the input group: crank pin ``A = O + l·u(φ₁)`` (``method.md`` §2.6).

    Parameters
    ----------
    o : complex
        Crank pivot O₁.
    length : float
        Crank length l₁.
    angle : float
        Absolute crank angle φ₁ = φ₁⁰ + s·φ; pass ``Jet(angle, s, 0.0)`` for analogs.

    Returns
    -------
    DyadSolution
        ``c`` = crank pin, ``origin_i`` = O₁, ``angle_i`` = φ₁; margin 1 (always assembles).
    """
    if type(angle) is np.ndarray and angle.ndim and type(o) in _NUMBERS and cmath.isfinite(o) \
            and (type(length) in _REALS and math.isfinite(length)
                 or type(length) is np.ndarray and length.dtype == float and _finite(length)) \
            and _finite(angle):
        pin = J.expi(angle)  # finite inputs: the fast path needs no error state
        if type(length) is np.ndarray:  # scale the (x, y) pairs by the lengths (many designs)
            xy = np.multiply(length[..., None], pin.view(np.float64).reshape(*pin.shape, 2))
            pin = xy.view(np.complex128)[..., 0]
        else:  # scale the interleaved (x, y) pairs in place
            xy = pin.view(np.float64)
            xy *= length
        if o != 0:
            pin += o
        shape = pin.shape
        return _solution(pin, _constant(o, shape), _spread(angle, shape), None, None, None,
                         None, *_assembled(shape))
    shape, jets = _layout(o, length, angle)
    with np.errstate(all="ignore"):
        pin = length * J.expi(angle)
        pin = np.add(pin, o, out=pin) if type(pin) is np.ndarray else pin + o
        margin = np.where(np.isfinite(J.value(pin)), 1.0, np.nan)
    return _finish(
        shape, (o, length, angle), margin, 0.0, lambda: Reason.UNDEFINED_INPUT,
        (pin, _spread(o, shape), _spread(angle, shape), None, None, None, None), jets,
    )


def solve_rrr(
    h_i: Value, h_j: Value, l_i: Value, l_j: Value, sigma: float | np.ndarray,
    delta: float | np.ndarray = 0.0,
) -> DyadSolution:
    """L1, the RRR dyad (``method.md`` §2.1).

    Parameters
    ----------
    h_i, h_j : complex
        Outer hinges H_i, H_j.
    l_i, l_j : float
        Link lengths |H_i C| and |H_j C|.
    sigma : {+1, -1}
        Assembly variant: +1 puts C left of the directed line H_i → H_j.
    delta : float
        Assigned tolerance δ₁: the group exists where ``1 − |c| >= delta``.

    Returns
    -------
    DyadSolution
        ``c`` = C; link frames at H_i and H_j with axes towards C.

    Notes
    -----
    With ``d = |H_j − H_i|`` the cosine of the angle at H_i is
    ``c = (l_i² + d² − l_j²)/(2·l_i·d)``. It is evaluated through the factored forms
    ``1 − c = (d + l_j − l_i)(l_i + l_j − d)/(2·l_i·d)`` and
    ``1 + c = (d + l_i − l_j)(l_i + l_j + d)/(2·l_i·d)``, which keep full relative accuracy
    near both toggle positions; ``sin = σ·sqrt((1 − c)(1 + c))`` then fixes the branch.
    """
    s = _branch(sigma)
    shape, jets = _layout(h_i, h_j, l_i, l_j, s)
    if jets or not shape:
        c, angle_i, angle_j, margin, d, lowest = _rrr_generic(h_i, h_j, l_i, l_j, s)
    else:
        c, angle_i, angle_j, margin, d, lowest = _rrr_arrays(h_i, h_j, l_i, l_j, s, shape)

    def failure() -> np.ndarray:
        longest = np.maximum(J.value(l_i), J.value(l_j))
        return np.where(d == 0.0, Reason.COINCIDENT_HINGES,
                        np.where(d > longest, Reason.STRETCHED, Reason.FOLDED))

    return _finish(
        shape, (h_i, h_j, l_i, l_j, s), margin, delta, failure,
        (c, _spread(h_i, shape), angle_i, _spread(h_j, shape), angle_j, None, None), jets,
        lowest=lowest, owned=(c, angle_i, angle_j),
    )


@np.errstate(all="ignore")
def _rrr_generic(h_i: Value, h_j: Value, l_i: Value, l_j: Value, s: float | np.ndarray) -> tuple:
    """RRR dyad for any arguments (jets too).

    Returns C, φ_i, φ_j, the margin, the hinge distance d (value) and the smallest margin.
    """
    r = h_j - h_i
    d = J.abs(r)
    two_ld = 2.0 * l_i * d
    one_minus_c = (d + l_j - l_i) * (l_i + l_j - d) / two_ld
    one_plus_c = (d + l_i - l_j) * (l_i + l_j + d) / two_ld
    margin = np.minimum(J.value(one_minus_c), J.value(one_plus_c))
    margin, sin2, lowest = _clip_roundoff(margin, one_minus_c * one_plus_c)
    k = l_i / d
    # C − H_i = r · (l_i/d) · (cos + j·σ·sin), cos = ((1 + c) − (1 − c))/2
    arm_i = r * (k * 0.5 * (one_plus_c - one_minus_c) + 1j * (k * s * J.sqrt(sin2)))
    return h_i + arm_i, J.arg(arm_i), J.arg(arm_i - r), margin, J.value(d), lowest


def _blocks(shape: tuple[int, ...]) -> list[slice]:
    """Slices of the first axis cutting ``shape`` into blocks of about ``BLOCK`` positions."""
    row = math.prod(shape[1:])
    step = max(1, BLOCK // max(row, 1))
    return [slice(k, k + step) for k in range(0, shape[0], step)]


def _rrr_arrays(
    h_i: Value, h_j: Value, l_i: Value, l_j: Value, s: float | np.ndarray,
    shape: tuple[int, ...],
) -> tuple:
    """:func:`_rrr_kernel` over blocks of ``BLOCK`` positions (one block if small).

    Blocking keeps the temporaries in cache and off the allocator for large calls (many
    designs × many angles); results are written into the full-size outputs.
    """
    if math.prod(shape) <= 2 * BLOCK:
        return _rrr_kernel(h_i, h_j, l_i, l_j, s, shape)
    args = [x if getattr(x, "ndim", 0) == 0 else np.broadcast_to(x, shape)
            for x in (h_i, h_j, l_i, l_j, s)]
    outputs = (np.empty(shape, complex), *(np.empty(shape) for _ in range(4)))
    lowest = np.inf
    for rows in _blocks(shape):
        part = [x if getattr(x, "ndim", 0) == 0 else x[rows] for x in args]
        block = tuple(out[rows] for out in outputs)
        lowest = np.minimum(lowest, _rrr_kernel(*part, block[0].shape, block)[-1])  # NaN stays
    return (*outputs, lowest)


@np.errstate(all="ignore")
def _rrr_kernel(
    h_i: Value, h_j: Value, l_i: Value, l_j: Value, s: float | np.ndarray,
    shape: tuple[int, ...], out: tuple[np.ndarray, ...] | None = None,
) -> tuple:
    """:func:`_rrr_generic` for plain arrays, in real arithmetic with few temporaries.

    ``out`` optionally gives the arrays for C, φ_i, φ_j, the margin and d.

    Also returns the smallest margin (found anyway to detect roundoff at a toggle).

    With ``r = H_j − H_i``, ``d = |r|``: ``C − H_i = r·(x + jσy)``, where
    ``x = (d² + l_i² − l_j²)/(2d²)`` and ``y = sqrt(Δ)/(2d²)`` with the discriminant in
    factored form ``Δ = g₁·g₂``, ``g₁ = (l_i + l_j − d)(d + l_j − l_i) = 2·l_i·d·(1 − c)``,
    ``g₂ = (d − l_j + l_i)(l_i + l_j + d) = 2·l_i·d·(1 + c)`` (Heron: 16 times the squared
    area of the triangle H_i C H_j). The small factor at each toggle is a difference of
    inputs, so Δ and the margin ``min(g₁, g₂)/(2·l_i·d)`` keep full relative accuracy there.
    """
    rx = np.subtract(h_j.real, h_i.real)  # r = H_j − H_i, as contiguous x and y
    ry = np.subtract(h_j.imag, h_i.imag)
    if rx.shape != shape:
        rx, ry = (np.array(np.broadcast_to(t, shape)) for t in (rx, ry))
    half, k, l_sum, l_dif, two_l = 0.5, l_i * l_i - l_j * l_j, l_i + l_j, l_j - l_i, 2.0 * l_i
    if rx.dtype == np.float64:
        half, k, l_sum, l_dif, two_l = _zero_dim(half, k, l_sum, l_dif, two_l)
    d2 = rx * rx
    d2 += ry * ry
    q = np.divide(half, d2)
    x = d2 + k
    x *= q
    c, angle_i, angle_j, margin, d = out if out is not None else (None,) * 5
    d = np.sqrt(d2, out=d)
    disc = l_sum - d
    disc *= d + l_dif  # 2·l_i·d·(1 − c), c = cos of the angle at H_i
    wx = d - l_dif
    wx *= l_sum + d  # 2·l_i·d·(1 + c)
    margin = np.minimum(disc, wx, out=margin)
    margin /= d
    margin /= two_l
    disc *= wx
    lowest = np.minimum.reduce(margin, axis=None) if margin.size else np.inf
    if not lowest >= 0.0:
        tiny = (margin < 0.0) & (margin > -ROUNDOFF)
        margin[tiny] = 0.0
        disc[tiny] = 0.0
        lowest = np.minimum.reduce(margin, axis=None)
    y = np.sqrt(disc, out=disc)  # NaN only where the dyad does not exist
    y *= q
    if type(s) is not float:
        y *= s
    elif s < 0.0:
        np.negative(y, out=y)
    np.multiply(rx, x, out=wx)
    wx -= np.multiply(ry, y, out=q)
    wy = np.multiply(rx, y, out=y)
    wy += np.multiply(ry, x, out=x)  # (wx, wy) = C − H_i
    angle_i = np.arctan2(wy, wx, out=angle_i)
    c = np.empty(shape, dtype=complex) if c is None else c
    np.add(h_i.real, wx, out=c.real)
    np.add(h_i.imag, wy, out=c.imag)
    wx -= rx
    wy -= ry  # C − H_j
    angle_j = np.arctan2(wy, wx, out=angle_j)
    return c, angle_i, angle_j, margin, d, lowest


def solve_rrp(
    h_j: Value, a: Value, theta: Value, e: Value, l_j: Value, sigma: float | np.ndarray,
    delta: float | np.ndarray = 0.0,
) -> DyadSolution:
    """L2, the RRP dyad: rod j hinged at H_j, slider i on a guide (``method.md`` §2.2).

    Parameters
    ----------
    h_j : complex
        Rod hinge H_j.
    a : complex
        Guide base point A_k.
    theta : float
        Guide direction θ (absolute).
    e : float
        Signed offset of the path of C from the guide line (along n(θ)).
    l_j : float
        Rod length |H_j C|.
    sigma : {+1, -1}
        +1 puts C ahead (along +u(θ)) of the foot of the perpendicular from H_j onto its path.
    delta : float
        Assigned tolerance δ₂: the group exists where ``1 − |h|/l_j >= delta``.

    Returns
    -------
    DyadSolution
        ``c`` = C; link i frame at C along θ, link j frame at H_j towards C; ``s_i`` = S.
    """
    s = _branch(sigma)
    shape, jets = _layout(h_j, a, theta, e, l_j, s)
    c, angle_j, slide, margin, lowest = _rrp_geometry(h_j, a, theta, e, l_j, s)
    return _finish(
        shape, (h_j, a, theta, e, l_j, s), margin, delta, lambda: Reason.ROD_TOO_SHORT,
        (c, c, _spread(theta, shape), _spread(h_j, shape), angle_j, slide, None), jets,
        lowest=lowest, owned=(c, angle_j, slide),
    )


@np.errstate(all="ignore")
def _rrp_geometry(
    h_j: Value, a: Value, theta: Value, e: Value, l_j: Value, s: float | np.ndarray,
) -> tuple:
    """RRP dyad: C, φ_j, S, the margin and the smallest margin."""
    u = J.expi(theta)
    w = J.conj(u) * (h_j - a) - 1j * e  # (p + j·h): H_j in the frame of the path of C
    p, h = J.real(w), J.imag(w)
    habs = J.abs(h)
    margin = 1.0 - J.value(habs) / J.value(l_j)
    margin, leg2, lowest = _clip_roundoff(margin, (l_j - habs) * (l_j + habs))
    slide = p + s * J.sqrt(leg2)
    c = a + (slide + 1j * e) * u
    return c, J.arg(c - h_j), slide, margin, lowest


def solve_rpr(
    h_i: Value, h_j: Value, h: Value, sigma: float | np.ndarray, delta: float | np.ndarray = 0.0,
) -> DyadSolution:
    """L3, the RPR dyad: kulisa i hinged at H_i, block j hinged at H_j (``method.md`` §2.3).

    Parameters
    ----------
    h_i, h_j : complex
        Kulisa hinge H_i (= base point A_k) and block hinge H_j.
    h : float
        Signed offset of the block's path from H_i (h = d + e_j), along n(φ_i).
    sigma : {+1, 0, -1}
        +1 (and 0, the default of table 1.6) puts the block on the positive ray of the kulisa
        axis, T > 0.
    delta : float
        Assigned tolerance δ₃: the group exists where ``1 − |h|/ρ >= delta``, ρ = |H_j − H_i|.

    Returns
    -------
    DyadSolution
        ``c`` = ``H_i + T·u(φ_i)``; link i frame at H_i, link j frame at H_j, both along the
        kulisa axis φ_i; ``s_i`` = T.

    Notes
    -----
    From ``H_j − H_i = (T + j·h)·u(φ_i)``: ``φ_i = arg((H_j − H_i)·(T − j·h))``, one polar
    angle with no branch ambiguity.
    """
    s = _branch(sigma)
    shape, jets = _layout(h_i, h_j, h, s)
    c, angle_i, t, margin, rho, lowest = _rpr_geometry(h_i, h_j, h, s)

    def failure() -> np.ndarray:
        return np.where(rho == 0.0, Reason.COINCIDENT_HINGES, Reason.OFFSET_TOO_LARGE)

    return _finish(
        shape, (h_i, h_j, h, s), margin, delta, failure,
        (c, _spread(h_i, shape), angle_i, _spread(h_j, shape), angle_i, t, None), jets,
        lowest=lowest, owned=(c, angle_i, t),
    )


@np.errstate(all="ignore")
def _rpr_geometry(h_i: Value, h_j: Value, h: Value, s: float | np.ndarray) -> tuple:
    """RPR dyad: H_i + T·u(φ_i), φ_i, T, the margin, ρ (value) and the smallest margin."""
    r = h_j - h_i
    rho = J.abs(r)
    habs = J.abs(h)
    margin = 1.0 - J.value(habs) / J.value(rho)
    margin, leg2, lowest = _clip_roundoff(margin, (rho - habs) * (rho + habs))
    t = s * J.sqrt(leg2)
    turned = r * (t - 1j * h)  # = ρ²·u(φ_i)
    c = h_i + t * turned / (rho * rho)
    return c, J.arg(turned), t, margin, J.value(rho), lowest


def solve_prp(
    a: Value, theta_i: Value, e_i: Value, b: Value, theta_j: Value, e_j: Value,
    delta: float | np.ndarray = 0.0,
) -> DyadSolution:
    """L4, the PRP dyad: two sliders joined by the hinge C (``method.md`` §2.4).

    Parameters
    ----------
    a, theta_i, e_i : complex, float, float
        Guide of slider i: base point A_k, direction θ_i, offset of C along n(θ_i).
    b, theta_j, e_j : complex, float, float
        Guide of slider j: base point B_k, direction θ_j, offset of C along n(θ_j).
    delta : float
        Assigned tolerance δ₄: the group exists where ``|sin(θ_j − θ_i)| >= delta``.

    Returns
    -------
    DyadSolution
        ``c`` = C; both link frames at C along their guides; ``s_i`` = S_i, ``s_j`` = S_j.

    Notes
    -----
    ``sin(θ_j − θ_i)`` is taken from the angle difference, not from the cross product of the
    two unit vectors, so nearly parallel guides keep full relative accuracy in the divisor.
    """
    shape, jets = _layout(a, theta_i, e_i, b, theta_j, e_j)
    c, slide_i, slide_j, margin = _prp_geometry(a, theta_i, e_i, b, theta_j, e_j)
    return _finish(
        shape, (a, theta_i, e_i, b, theta_j, e_j), margin, delta, lambda: Reason.GUIDES_PARALLEL,
        (c, c, _spread(theta_i, shape), c, _spread(theta_j, shape), slide_i, slide_j), jets,
        above=ROUNDOFF, owned=(c, slide_i, slide_j),
    )


@np.errstate(all="ignore")
def _prp_geometry(
    a: Value, theta_i: Value, e_i: Value, b: Value, theta_j: Value, e_j: Value,
) -> tuple:
    """PRP dyad: C, S_i, S_j and the margin (NaN where C is undefined)."""
    u_i, u_j = J.expi(theta_i), J.expi(theta_j)
    sin_ij = J.imag(J.expi(theta_j - theta_i))
    r = (b + 1j * e_j * u_j) - (a + 1j * e_i * u_i)
    slide_i = J.cross(r, u_j) / sin_ij
    slide_j = J.cross(r, u_i) / sin_ij
    c = a + (slide_i + 1j * e_i) * u_i
    margin = np.where(np.isfinite(J.value(c)), np.abs(J.value(sin_ij)), np.nan)
    return c, slide_i, slide_j, margin


def solve_rpp(
    h_j: Value, gamma: Value, a: Value, theta_s: Value, e: Value,
    delta: float | np.ndarray = 0.0,
) -> DyadSolution:
    """L5, the RPP dyad: link j hinged at H_j carries a guide for slider i (``method.md`` §2.5).

    Parameters
    ----------
    h_j : complex
        Hinge H_j of link j; its guide passes through H_j with direction θ_T = θ_S + γ.
    gamma : float
        Constant angle γ between the guides.
    a, theta_s, e : complex, float, float
        Guide of slider i: base point A_k, direction θ_S, offset of C along n(θ_S).
    delta : float
        Assigned tolerance δ₅: the group exists where ``|sin γ| >= delta``.

    Returns
    -------
    DyadSolution
        ``c`` = C (``H_j + T·u(θ_T)``); link i frame at C along θ_S, link j frame at H_j along
        θ_T; ``s_i`` = S, ``s_j`` = T.
    """
    shape, jets = _layout(h_j, gamma, a, theta_s, e)
    c, theta_t, slide, t, margin = _rpp_geometry(h_j, gamma, a, theta_s, e)
    return _finish(
        shape, (h_j, gamma, a, theta_s, e), margin, delta, lambda: Reason.GUIDES_PARALLEL,
        (c, c, _spread(theta_s, shape), _spread(h_j, shape), _spread(theta_t, shape), slide,
         t),
        jets, above=ROUNDOFF, owned=(c, slide, t),
    )


@np.errstate(all="ignore")
def _rpp_geometry(h_j: Value, gamma: Value, a: Value, theta_s: Value, e: Value) -> tuple:
    """RPP dyad: C, θ_T, S, T and the margin (NaN where C is undefined)."""
    theta_t = theta_s + gamma
    u_s, u_t = J.expi(theta_s), J.expi(theta_t)
    minus_sin = -J.imag(J.expi(gamma))  # cross(u_T, u_S) = −sin γ
    r = a + 1j * e * u_s - h_j
    t = J.cross(r, u_s) / minus_sin
    slide = J.cross(r, u_t) / minus_sin
    c = h_j + t * u_t
    margin = np.where(np.isfinite(J.value(c)), np.abs(J.value(minus_sin)), np.nan)
    return c, theta_t, slide, t, margin
