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

Whether a group assembles is an exact condition on its inputs (the triangle inequality for
L1, the rod reaching the path for L2, the offset within the hinge distance for L3, guides not
parallel for L4 and L5; each solver's Notes state it), decided up to a tolerance
``ROUNDOFF`` relative to the group's own size, so that the decision holds for any proportions
of the group's dimensions. Plain-array calls of the crank and the RRR dyad take the speed
paths of :mod:`assur.kinematics._fast`, which compute the same numbers.
"""

from __future__ import annotations

import cmath
from collections.abc import Callable
from functools import lru_cache
from typing import Any, NamedTuple, cast

import numpy as np

from assur.kinematics import _fast
from assur.kinematics import jets as J
from assur.kinematics.jets import Jet
from assur.kinematics.reasons import REASONS, Reason, reason_text
from assur.typing import Value

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
    "solve_slide",
]


#: The geometric outputs of a solver: C, origin_i, angle_i, origin_j, angle_j, s_i, s_j.
Geometry = tuple[Value, Value, Value, Value | None, Value | None, Value | None, Value | None]

#: Relative tolerance of the existence decisions: a limit passed by no more than this times the
#: group's size is read as the toggle position itself (margin 0); guides parallel within it
#: (|sin| <= ROUNDOFF) do not assemble.
ROUNDOFF = 64.0 * np.finfo(float).eps

_NUMBERS, _REALS = _fast.NUMBERS, _fast.REALS


class DyadSolution(NamedTuple):
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
        L3 ``1 − |h|/ρ``, L4 ``|sin(θ_j − θ_i)|``, L5 ``|sin γ|``, L0 1. It is 0 at a
        position read as a toggle (see :func:`solve_rrr`) and NaN where it is undefined: an
        input is NaN, or two hinges of the group coincide (a link of zero length, or
        coincident outer hinges).
    exists : ndarray, bool
        ``margin >= delta``; False where the margin is NaN and, for L4 and L5, where the
        guides are parallel within roundoff (``margin <= ROUNDOFF``).
    reason : ndarray, int8
        0 where the group exists, else a :class:`Reason` code (the condition that fails, or
        the nearest one when the margin is only below δ).

    Notes
    -----
    Every output has the broadcast shape of the arguments; outputs that are constant over it
    (a fixed origin, an all-true mask) are read-only views rather than copies.
    Geometric outputs are NaN wherever ``exists`` is False. To see the geometry inside the
    tolerance band, solve with ``delta=0`` and compare ``margin`` with δ yourself.
    A solution is an immutable named tuple: its fields are read by name.
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
    if type(sigma) in _REALS or getattr(sigma, "ndim", 0) == 0:
        return -1.0 if sigma < 0 else 1.0
    return np.where(sigma < 0, -1.0, 1.0)


def _layout(*args: Any) -> tuple[tuple[int, ...], bool]:
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
    view: np.ndarray = np.ndarray(shape, base.dtype, base, 0, (0,) * len(shape))
    return view


@lru_cache(maxsize=64)
def _assembled(shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Margin 1, ``exists`` True and reason 0 over ``shape``: read-only views, cached."""
    return (_constant(1.0, shape), _constant(True, shape),
            _constant(np.int8(Reason.ASSEMBLES), shape))


@lru_cache(maxsize=64, typed=True)
def _pivot_and_assembled(o: complex, shape: tuple[int, ...],
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The pivot number ``o`` over ``shape`` and the outputs of :func:`_assembled`: cached."""
    return (_constant(o, shape), *_assembled(shape))


def _spread(x: Value, shape: tuple[int, ...]) -> Value:
    """``x`` with its value broadcast to ``shape``: ``x`` itself, or a read-only view."""
    if type(x) in _NUMBERS:
        number: Any = x
        return _constant(number, shape) if shape else number
    if type(x) is Jet:
        return x if x.v.shape == shape else Jet(np.broadcast_to(x.v, shape), x.d1, x.d2)
    if getattr(x, "shape", ()) == shape:
        return x
    if getattr(x, "ndim", 0) == 0:
        number = x[()] if type(x) is np.ndarray else x
        return _constant(number, shape)
    return np.broadcast_to(cast(np.ndarray, x), shape)  # neither a jet nor a number


def _lowest(margin: Any) -> float:
    """The smallest margin (NaN if any is NaN; +inf for no position), in one reduction."""
    return np.minimum.reduce(margin, axis=None) if np.size(margin) else np.inf


def _settled(lowest: float, *lengths: Value) -> bool:
    """Whether one reduction already shows every position assembling (no limit to settle).

    True when no margin is negative or NaN and every length in ``lengths`` is positive.
    """
    return lowest >= 0.0 and all(_fast.positive(J.value(x)) for x in lengths)


def _settle(margin: Any, deficit: Any, size: Any, degenerate: Any,
            ) -> tuple[np.ndarray, np.ndarray]:
    """The margin with toggles read as 0 and degenerate groups as NaN, and the toggle mask.

    ``deficit`` is the length by which the nearest limit of the group is passed (negative
    when it is); the group assembles where ``deficit >= −ROUNDOFF·size``, ``size`` being the
    group's own size. A negative margin inside that band is a toggle position: margin 0.
    ``degenerate`` marks positions where two hinges of the group coincide: margin NaN.
    """
    toggle = (margin < 0.0) & (deficit >= -ROUNDOFF * size) & ~degenerate
    return np.where(degenerate, np.nan, np.where(toggle, 0.0, margin)), toggle


def _blank(geometry: Geometry, bad: np.ndarray, owned: tuple[Value, ...]) -> Geometry:
    """The outputs ``geometry`` with NaN where ``bad`` (an output repeated is blanked once).

    Arrays in ``owned`` (made by the solver for this call) are blanked in place; the others
    (inputs passed through, constant views) are copied.
    """
    done: dict[int, Value] = {}
    fresh = {id(x) for x in owned if type(x) is np.ndarray and x.shape == bad.shape}
    for x in geometry:
        if x is not None and id(x) not in done:
            nan = complex(np.nan, np.nan) if np.iscomplexobj(J.value(x)) else np.nan
            if id(x) in fresh and isinstance(x, np.ndarray):
                np.copyto(x, nan, where=bad)
                done[id(x)] = x
            else:
                done[id(x)] = J.where(bad, nan, x)
    return cast(Geometry, tuple(None if x is None else done[id(x)] for x in geometry))


def _undefined(inputs: tuple[Value, ...]) -> np.ndarray | bool:
    """Mask of the positions where some input is NaN or infinite (False: nowhere).

    An array input found finite by one reduction needs no elementwise test.
    """
    undefined: np.ndarray | bool = False
    for x in inputs:
        v = J.value(x)
        kind = type(v)
        if kind in _NUMBERS and cmath.isfinite(v) or isinstance(v, np.ndarray) and _fast.finite(v):
            continue
        undefined = undefined | ~np.isfinite(v)
    return undefined


def _finish(
    shape: tuple[int, ...],
    inputs: tuple[Value, ...],
    margin: np.ndarray,
    delta: float | np.ndarray,
    failure: Callable[[], np.ndarray | int],
    geometry: Geometry,
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
        geometry = cast(Geometry, tuple(x if x is None or isinstance(x, Jet) else Jet(x)
                                        for x in geometry))
    if lowest is None:
        lowest = _lowest(margin)
    if lowest >= (delta if type(delta) in _NUMBERS else np.max(delta)) and (
            above is None or lowest > above):
        return _assembling(geometry, shape, margin)  # one reduction: every position assembles
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
    return tuple.__new__(DyadSolution, (*geometry, margin, exists, reason))  # no Python __new__


def _assembling(geometry: Geometry, shape: tuple[int, ...], margin: np.ndarray | None = None,
                ) -> DyadSolution:
    """The solution of outputs ``geometry`` where every position of ``shape`` assembles.

    ``exists`` and ``reason`` are the cached constant views of ``shape``, and so is the
    margin unless given (1: an input group). The named tuple is made without its Python
    constructor.
    """
    one, exists, reason = _assembled(shape)
    return tuple.__new__(DyadSolution, (*geometry, one if margin is None else margin, exists,
                                        reason))


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

    Examples
    --------
    A 2 mm crank at 90° from the x axis puts its pin on the y axis:

    >>> import numpy as np
    >>> from assur import solve_input
    >>> pin = solve_input(0j, 2.0, np.pi / 2).c
    >>> print(f"{pin.real:.3f} {pin.imag:.3f}")
    0.000 2.000
    """
    pin = _fast.crank_pin(o, length, angle)
    if pin is not None:
        shape = pin.shape
        origin, one, exists, reason = _pivot_and_assembled(cast(complex, o), shape)  # a number
        return tuple.__new__(DyadSolution, (pin, origin, _spread(angle, shape), None, None, None,
                                            None, one, exists, reason))
    return _along(o, length, angle, crank=True)


def solve_slide(base: Value, angle: Value, s: Value) -> DyadSolution:
    """L0 of a slider driven along a frame guide: its point ``base + s·u(angle)``.

    Parameters
    ----------
    base : complex
        The guide's point at s = 0 (the slider's sketched point).
    angle : float
        The guide's direction, radians.
    s : float, array or Jet
        The slider's displacement (the input coordinate), mm.

    Returns
    -------
    DyadSolution
        ``c`` = ``origin_i`` = the slider's point, ``angle_i`` = the guide's direction,
        ``s_i`` = s; margin 1 (a slider always assembles; its stroke is checked by the
        analysis, :mod:`assur.kinematics.laws`).

    Examples
    --------
    >>> import numpy as np
    >>> solve_slide(1 + 1j, np.pi / 2, np.array([0.0, 2.0])).c.round(12).tolist()
    [(1+1j), (1+3j)]
    """
    return _along(base, s, angle, crank=False)


def _along(origin: Value, length: Value, angle: Value, *, crank: bool) -> DyadSolution:
    """The point ``origin + length·u(angle)`` of an input group: a crank's pin (the crank's
    frame at ``origin``) or a driven slider's point (its frame at the point, ``length`` its
    displacement s); it assembles wherever the inputs are defined."""
    shape, jets = _layout(origin, length, angle)
    with np.errstate(all="ignore"):
        point = length * J.expi(angle) + origin
        margin = np.where(np.isfinite(J.value(point)), 1.0, np.nan)
    frame = _spread(origin, shape) if crank else point
    return _finish(
        shape, (origin, length, angle), margin, 0.0, lambda: Reason.UNDEFINED_INPUT,
        (point, frame, _spread(angle, shape), None, None, None if crank else length, None),
        jets,
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
    With ``d = |H_j − H_i|`` the group assembles where the three deficits

    ``l_i + l_j − d`` (stretched), ``d − (l_i − l_j)`` and ``d + (l_i − l_j)`` (folded)

    are all ``>= −ROUNDOFF·(l_i + l_j + d)``: the triangle inequality
    ``|l_i − l_j| <= d <= l_i + l_j``, decided up to a tolerance relative to the perimeter of
    the triangle H_i C H_j, whatever the proportions of the three sides. A deficit inside that
    band is read as the toggle position itself: margin 0, C on the line H_i H_j at
    ``l_i`` from H_i. Two coincident hinges (``d = 0``, or a link of zero length) leave a
    direction undefined: the group does not assemble there, with margin NaN and the reason
    ``COINCIDENT_HINGES``, whichever side the zero is on. Negative lengths never pass the
    triangle inequality.

    The cosine of the angle at H_i is ``c = (l_i² + d² − l_j²)/(2·l_i·d)``. It is evaluated
    through the factored forms ``1 − c = (l_i + l_j − d)(d − l_i + l_j)/(2·l_i·d)`` and
    ``1 + c = (d + l_i − l_j)(l_i + l_j + d)/(2·l_i·d)``, which keep full relative accuracy
    near both toggle positions; C − H_i = r·(x + jσy) with r = H_j − H_i,
    ``x = (d² + (l_i − l_j)(l_i + l_j))/(2d²)`` and ``y = sqrt(Δ)/(2d²)``, Δ the product of
    the four factors (Heron: 16 times the squared area of the triangle), so the branch is σ.
    Each factor is a difference of inputs, so its round-off is a few ε times the perimeter.

    Examples
    --------
    Hinges 5 mm apart and links of 3 and 4 mm: the right triangle 3–4–5, C above the line for
    σ = +1; with the hinges 8 mm apart the links cannot reach (3 + 4 < 8):

    >>> from assur import solve_rrr
    >>> group = solve_rrr(0j, 5 + 0j, 3.0, 4.0, sigma=1)
    >>> print(f"{group.c.real:.3f} {group.c.imag:.3f}", bool(group.exists))
    1.800 2.400 True
    >>> bool(solve_rrr(0j, 8 + 0j, 3.0, 4.0, sigma=1).exists)
    False
    """
    if (type(h_i) is np.ndarray and h_i.ndim and type(h_j) in _NUMBERS and type(l_i) in _REALS
            and type(l_j) in _REALS and type(sigma) in _REALS):  # joints of an array, numbers
        s: float | np.ndarray = -1.0 if sigma < 0 else 1.0  # what _branch and _layout give
        shape, jets = h_i.shape, False
    else:
        s = _branch(sigma)
        shape, jets = _layout(h_i, h_j, l_i, l_j, s)
    if jets or not shape:
        c, angle_i, angle_j, margin, d, lowest = _rrr_readable(h_i, h_j, l_i, l_j, s)
    else:
        c, angle_i, angle_j, margin, d, lowest = _fast.rrr(h_i, h_j, l_i, l_j, s, shape,
                                                           _rrr_limits)
    geometry: Geometry = (c, _spread(h_i, shape), angle_i, _spread(h_j, shape), angle_j, None,
                          None)
    if not jets and type(delta) in _REALS and lowest >= delta:
        return _assembling(geometry, shape, margin)  # what _finish gives, without its arguments
    return _finish(
        shape, (h_i, h_j, l_i, l_j, s), margin, delta, lambda: _rrr_failure(l_i, l_j, d),
        geometry, jets, lowest=lowest, owned=(c, angle_i, angle_j),
    )


def _rrr_failure(l_i: Value, l_j: Value, d: Any) -> np.ndarray:
    """RRR reason codes of every position as if it failed (``d`` the hinge distance)."""
    long_i, long_j = J.value(l_i), J.value(l_j)
    coincident = (d == 0.0) | (long_i == 0.0) | (long_j == 0.0)
    return np.where(coincident, Reason.COINCIDENT_HINGES,
                    np.where(d > np.maximum(long_i, long_j), Reason.STRETCHED, Reason.FOLDED))


@np.errstate(all="ignore")
def _rrr_readable(h_i: Value, h_j: Value, l_i: Value, l_j: Value, s: float | np.ndarray,
                  ) -> tuple[Value, Value, Value, np.ndarray, Value, float]:
    """RRR dyad for any arguments (jets too): the formulas of :func:`solve_rrr`.

    Returns C, φ_i, φ_j, the margin, the hinge distance d (value) and the smallest margin.
    :func:`assur.kinematics._fast.rrr` computes the same, in the same order, for plain arrays.
    """
    r = h_j - h_i
    if not isinstance(r, (Jet, np.ndarray)):  # numpy arithmetic: 1/0 is inf, not an error
        r = np.complex128(r)
    rx, ry = J.real(r), J.imag(r)
    d2 = rx * rx + ry * ry
    d = J.sqrt(d2)
    l_sum, l_dif = l_i + l_j, l_i - l_j
    below = (l_sum - d) * (d - l_dif)  # 2·l_i·d·(1 − c)
    above = (d + l_dif) * (l_sum + d)  # 2·l_i·d·(1 + c)
    margin = np.minimum(J.value(below), J.value(above)) / J.value(d) / (2.0 * J.value(l_i))
    heron = below * above  # Δ
    half_inv_d2 = 0.5 / d2  # 1/(2d²)
    along = (d2 + l_dif * l_sum) * half_inv_d2  # x
    lowest = _lowest(margin)
    if not _settled(lowest, l_i, l_j):
        margin, toggle, along_at_toggle = _rrr_limits(
            J.value(l_i), J.value(l_j), J.value(d), margin)
        heron = J.where(toggle, 0.0, heron)
        along = J.where(toggle, along_at_toggle, along)
        lowest = _lowest(margin)
    across = J.sqrt(heron) * half_inv_d2 * s  # σ·y
    arm_i = r * (along + 1j * across)  # C − H_i
    return h_i + arm_i, J.arg(arm_i), J.arg(arm_i - r), margin, J.value(d), lowest


def _rrr_limits(l_i: Any, l_j: Any, d: Any, margin: Any,
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """RRR existence where some position may not assemble (see :func:`solve_rrr`).

    Returns the margin with toggles read as 0 and coincident hinges as NaN, the toggle mask
    and ``x`` there: C on the line H_i H_j at ``l_i`` from H_i, beyond H_i from H_j when the
    dyad folds over H_i (``l_j > l_i + d``).
    """
    l_sum, l_dif = l_i + l_j, l_i - l_j
    deficit = np.minimum(l_sum - d, np.minimum(d - l_dif, d + l_dif))
    degenerate = (l_i <= 0.0) | (l_j <= 0.0) | (d == 0.0)
    margin, toggle = _settle(margin, deficit, l_sum + d, degenerate)
    along = np.where(d + l_dif < 0.0, -l_i, l_i) / d
    return margin, toggle, along


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

    Notes
    -----
    With ``w = conj(u(θ))·(H_j − A) − j·e = p + j·h`` (H_j in the frame of the path of C),
    the group assembles where ``l_j − |h| >= −ROUNDOFF·(l_j + |H_j − A| + |e|)``: the rod
    reaches the path, decided up to a tolerance relative to the lengths that h is computed
    from (the round-off of h is a few ε times ``|H_j − A| + |e|``). A deficit inside that band
    is read as the tangency itself: margin 0, C at the foot of the perpendicular. A rod of
    zero length (C on H_j) does not assemble: margin NaN, reason ``COINCIDENT_HINGES``.
    ``S = p + σ·sqrt((l_j − |h|)(l_j + |h|))``.

    Examples
    --------
    A 5 mm rod hinged 3 mm above a guide along the x axis meets it 4 mm ahead (3–4–5):

    >>> from assur import solve_rrp
    >>> c = solve_rrp(3j, 0j, 0.0, 0.0, 5.0, sigma=1).c
    >>> print(f"{c.real:.3f} {c.imag:.3f}")
    4.000 0.000
    """
    s = _branch(sigma)
    shape, jets = _layout(h_j, a, theta, e, l_j, s)
    c, angle_j, slide, margin, lowest = _rrp_geometry(h_j, a, theta, e, l_j, s)

    def failure() -> np.ndarray:
        return np.where(J.value(l_j) == 0.0, Reason.COINCIDENT_HINGES, Reason.ROD_TOO_SHORT)

    return _finish(
        shape, (h_j, a, theta, e, l_j, s), margin, delta, failure,
        (c, c, _spread(theta, shape), _spread(h_j, shape), angle_j, slide, None), jets,
        lowest=lowest, owned=(c, angle_j, slide),
    )


@np.errstate(all="ignore")
def _rrp_geometry(
    h_j: Value, a: Value, theta: Value, e: Value, l_j: Value, s: float | np.ndarray,
) -> tuple[Value, Value, Value, np.ndarray, float]:
    """RRP dyad: C, φ_j, S, the margin and the smallest margin."""
    u = J.expi(theta)
    reach = h_j - a
    w = J.conj(u) * reach - 1j * e  # (p + j·h): H_j in the frame of the path of C
    p, h = J.real(w), J.imag(w)
    habs = J.abs(h)
    rod: Any = J.value(l_j)
    offset = J.value(habs)
    margin = 1.0 - offset / rod
    leg2 = (l_j - habs) * (l_j + habs)
    lowest = _lowest(margin)
    if not _settled(lowest, l_j):
        size = rod + np.abs(J.value(reach)) + np.abs(J.value(e))
        margin, toggle = _settle(margin, rod - offset, size, rod <= 0.0)
        leg2 = J.where(toggle, 0.0, leg2)
        lowest = _lowest(margin)
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
    The group assembles where ``ρ − |h| >= −ROUNDOFF·(ρ + |h|)`` and ``ρ > 0``; a deficit
    inside that band is read as the toggle (T = 0, margin 0). Coincident hinges (ρ = 0) do not
    assemble: margin NaN, reason ``COINCIDENT_HINGES``. ``T = σ·sqrt((ρ − |h|)(ρ + |h|))``.
    From ``H_j − H_i = (T + j·h)·u(φ_i)``: ``φ_i = arg((H_j − H_i)·(T − j·h))``, one polar
    angle with no branch ambiguity.

    Examples
    --------
    With no offset the kulisa axis passes through the block hinge, 5 mm from H_i:

    >>> from assur import solve_rpr
    >>> group = solve_rpr(0j, 3 + 4j, 0.0, sigma=1)
    >>> print(f"{group.s_i:.3f} {group.c.real:.3f} {group.c.imag:.3f}")
    5.000 3.000 4.000
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
def _rpr_geometry(h_i: Value, h_j: Value, h: Value, s: float | np.ndarray,
                  ) -> tuple[Value, Value, Value, np.ndarray, Value, float]:
    """RPR dyad: H_i + T·u(φ_i), φ_i, T, the margin, ρ (value) and the smallest margin."""
    r = h_j - h_i
    rho = J.abs(r)
    habs = J.abs(h)
    distance, offset = J.value(rho), J.value(habs)
    margin = 1.0 - offset / distance
    leg2 = (rho - habs) * (rho + habs)
    lowest = _lowest(margin)
    if not lowest >= 0.0:
        margin, toggle = _settle(margin, distance - offset, distance + offset, distance == 0.0)
        leg2 = J.where(toggle, 0.0, leg2)
        lowest = _lowest(margin)
    t = s * J.sqrt(leg2)
    turned = r * (t - 1j * h)  # = ρ²·u(φ_i)
    c = h_i + t * turned / (rho * rho)
    return c, J.arg(turned), t, margin, distance, lowest


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

    Examples
    --------
    A guide along the x axis and a vertical one through (2, 0) cross at (2, 0):

    >>> import numpy as np
    >>> from assur import solve_prp
    >>> c = solve_prp(0j, 0.0, 0.0, 2 + 0j, np.pi / 2, 0.0).c
    >>> print(f"{c.real:.3f} {c.imag:.3f}")
    2.000 0.000
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
) -> tuple[Value, Value, Value, np.ndarray]:
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

    Examples
    --------
    Link j hinged at (2, 3) carries a guide at γ = 90° to a slider guide along the x axis: the
    guides cross at (2, 0), 3 mm below the hinge (T = −3):

    >>> import numpy as np
    >>> from assur import solve_rpp
    >>> group = solve_rpp(2 + 3j, np.pi / 2, 0j, 0.0, 0.0)
    >>> print(f"{group.c.real:.3f} {group.c.imag:.3f} {group.s_j:.3f}")
    2.000 0.000 -3.000
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
def _rpp_geometry(h_j: Value, gamma: Value, a: Value, theta_s: Value, e: Value,
                  ) -> tuple[Value, Value, Value, Value, np.ndarray]:
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
