"""The real roots of many trigonometric polynomials at once, bracketed by samples.

The eliminant of a four-link group is a real trigonometric polynomial of degree m,

    Φ(θ) = Σ_{n=0..m} a_n cos nθ + b_n sin nθ,

whose real roots are the group's assembly modes (``docs/higher_groups.md`` §1.3). Here the
roots of P such polynomials are found together: Φ is sampled on a uniform grid of θ (one
matrix product), every sign change brackets a root, and the brackets are polished by
safeguarded Newton steps. Two roots closer than the spacing of the samples may be missed
(a caller that follows a root checks every step with :func:`separation`, a lower bound on
the distance from a root to every other root of p(E) = E^m·Φ, real or complex, so a missed
root can only make a check fail, never pass).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from assur.kinematics.jets import expi

__all__ = ["RealRoots", "chord", "derivatives", "polish", "real_roots", "separation", "trig_form"]

TWO_PI = 2.0 * np.pi
#: θ samples per turn.
SAMPLES = 32
#: At most this many safeguarded Newton steps polish each bracketed root; they stop once
#: every step is below ``POLISHED`` (rad: the pose recovered from the root is polished on
#: the group's own equations afterwards).
POLISH = 40
POLISHED = 1e-10
#: The samples start here (rad), off the angles where roots lie by construction (θ = 0 at
#: the sketch, multiples of π/2 in symmetric drawings).
OFFSET = 0.1234567
#: The spacing of the samples and the samples, from ``OFFSET`` to ``OFFSET`` + 2π.
STEP = TWO_PI / SAMPLES
GRID = OFFSET + STEP * np.arange(SAMPLES + 1)


def trig_form(coef: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The real coefficients (a_n, b_n), n = 0 … m, of Φ from those of p(E) = E^m·Φ.

    Parameters
    ----------
    coef : ndarray, complex, shape (..., 2m + 1)
        p_0 … p_2m in increasing powers of E, p_{m+n} = φ_n with φ_{−n} = conj(φ_n).

    Returns
    -------
    a, b : ndarray, shape (..., m + 1)
        Φ(θ) = Σ a_n cos nθ + b_n sin nθ (b_0 = 0).

    Examples
    --------
    >>> a, b = trig_form(np.array([-0.5j, 1.0, 0.5j]))  # Φ = 1 − sin θ
    >>> a.tolist(), b.tolist()
    ([1.0, 0.0], [0.0, -1.0])
    """
    m = (coef.shape[-1] - 1) // 2
    phi = coef[..., m:]
    a = 2.0 * phi.real
    b = -2.0 * phi.imag
    a[..., 0] = phi[..., 0].real
    b[..., 0] = 0.0
    return a, b


def derivatives(coef: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Φ, Φ′ and Φ″ at θ (...) of the eliminants whose p has the coefficients ``coef``
    (..., 2m + 1): Φ(θ) = Σ φ_n e^{inθ}, n = −m … m.

    Examples
    --------
    >>> value, slope, bend = derivatives(np.array([-0.5j, 1.0, 0.5j]), np.array(0.0))
    >>> float(value), float(slope), float(bend)  # Φ = 1 − sin θ
    (1.0, -1.0, 0.0)
    """
    m = (coef.shape[-1] - 1) // 2
    n = np.arange(-m, m + 1)
    e = coef * np.exp(1j * n * theta[..., None])
    return e.sum(axis=-1).real, (1j * n * e).sum(axis=-1).real, (-n * n * e).sum(axis=-1).real


def chord(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|e^{ia} − e^{ib}|: the distance of two angles as points of the unit circle; NaN where
    either is NaN."""
    d = np.asarray(np.subtract(a, b, dtype=float))
    d *= 0.5
    np.sin(d, out=d)
    np.abs(d, out=d)
    d *= 2.0
    return d


def _value(phi: list[np.ndarray], e: np.ndarray) -> np.ndarray:
    """Φ at E = e^{iθ} from its columns φ_n, n = 0 … m (each (Q,) or (Q, 1)): Φ = φ₀ + 2 Re g
    with g = Σ_{n≥1} φ_nEⁿ by Horner's rule in E."""
    m = len(phi) - 1
    g = phi[m]
    for n in range(m - 1, 0, -1):
        g = g * e + phi[n]
    return np.asarray(phi[0].real + 2.0 * (g * e).real)


def _values(phi: list[np.ndarray], slopes: list[np.ndarray], e: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
    """Φ and Φ′ at E = e^{iθ} from the columns φ_n and nφ_n, n = 0 … m: Φ as in
    :func:`_value` and Φ′ = −2 Im h with h = Σ nφ_nEⁿ, by Horner's rule in E."""
    m = len(phi) - 1
    g, h = phi[m], slopes[m]
    for n in range(m - 1, 0, -1):
        g, h = g * e + phi[n], h * e + slopes[n]
    return phi[0].real + 2.0 * (g * e).real, -2.0 * (h * e).imag


@dataclass(frozen=True, eq=False)
class RealRoots:
    """The real roots of P trigonometric polynomials, bracketed.

    Attributes
    ----------
    theta : ndarray, shape (P, 2m)
        Each root's first estimate, where the chord between the samples of its bracket
        crosses zero, in [0, 2π), increasing; NaN after the last (:func:`polish` refines it).
    slope : ndarray, shape (P, 2m)
        The sign of Φ′ at each root (0 after the last).
    low, high : ndarray, shape (P, 2m)
        The bracket of each root: Φ changes sign from θ = ``low`` to ``high`` (high − low =
        2π/``SAMPLES``, both possibly above 2π).
    """

    theta: np.ndarray
    slope: np.ndarray
    low: np.ndarray
    high: np.ndarray


def real_roots(a: np.ndarray, b: np.ndarray) -> RealRoots:
    """The real roots of Φ(θ) = Σ a_n cos nθ + b_n sin nθ bracketed by ``SAMPLES`` samples, for
    P polynomials at once.

    Parameters
    ----------
    a, b : ndarray, shape (P, m + 1)
        The coefficients (:func:`trig_form`); a polynomial with a coefficient that is not
        finite has no root.

    Returns
    -------
    RealRoots
        Every root where Φ changes sign between two samples (a pair of roots closer than
        2π/``SAMPLES`` may be missed).

    Examples
    --------
    >>> a, b = np.array([[0.0, 0.0, 1.0]]), np.zeros((1, 3))  # cos 2θ
    >>> found = real_roots(a, b)
    >>> found.slope[0].tolist()
    [-1.0, 1.0, -1.0, 1.0]
    >>> np.round(np.degrees(polish(a[[0]], b[[0]], found.low[:, :1], found.high[:, :1])), 9)
    array([[45.]])
    """
    count_p, m1 = a.shape
    width = 2 * (m1 - 1)
    good = np.isfinite(a).all(axis=-1) & np.isfinite(b).all(axis=-1)
    cos, sin = _grid(m1)
    if not good.all():
        a, b = np.where(good[:, None], a, 0.0), np.where(good[:, None], b, 0.0)
    value = a @ cos + b @ sin
    above = value >= 0.0
    change = (above[:, :-1] != above[:, 1:]) & good[:, None]
    # every sign change, row by row, and its rank in its row: its place in that list less
    # the number of changes in the rows before
    rows, cols = np.divmod(np.flatnonzero(change), SAMPLES)
    before = np.bincount(rows, minlength=count_p)
    rank = np.arange(rows.size) - (np.cumsum(before) - before)[rows]
    first = rank < width
    rows, cols, rank = rows[first], cols[first], rank[first]
    va, vb = value[rows, cols], value[rows, cols + 1]
    # the chord's zero in each bracket, increasing along a row; those past 2π (the samples
    # end at OFFSET + 2π) come first once reduced, so each row is turned by their number
    theta = GRID[cols] + STEP * va / (va - vb)
    wrapped = theta >= TWO_PI
    theta = np.where(wrapped, theta - TWO_PI, theta)
    count = np.bincount(rows, minlength=count_p)[rows]
    turn = np.bincount(rows, weights=wrapped, minlength=count_p).astype(np.int64)[rows]
    at = rows * width + (rank + turn) % np.maximum(count, 1)
    out = np.full((4, count_p, width), np.nan)
    out[3] = 0.0
    out.reshape(4, -1)[:, at] = (theta, GRID[cols], GRID[cols + 1], np.where(va >= 0.0, -1.0, 1.0))
    return RealRoots(theta=out[0], slope=out[3], low=out[1], high=out[2])


@functools.cache
def _grid(m1: int) -> tuple[np.ndarray, np.ndarray]:
    """cos nθ and sin nθ, n = 0 … m, at the samples ``GRID``, shape (m + 1, SAMPLES + 1)."""
    n = np.arange(m1)
    return np.cos(np.outer(n, GRID)), np.sin(np.outer(n, GRID))


def polish(a: np.ndarray, b: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """The root of Φ in each bracket [low, high] (Φ of opposite signs at its ends), in [0, 2π).

    Parameters
    ----------
    a, b : ndarray, shape (P, m + 1)
        The polynomials (:func:`trig_form`).
    low, high : ndarray, shape (P, S)
        Brackets of S roots of each (:class:`RealRoots`); NaN for none.

    Returns
    -------
    ndarray, shape (P, S)
        From the secant point, Newton steps kept inside the shrinking bracket (a step leaving
        it is a bisection), on the roots not yet polished only, until the step is below
        ``POLISHED``.
    """
    shape = low.shape
    rows = np.broadcast_to(np.arange(shape[0])[:, None], shape).reshape(-1)
    lo, hi = low.reshape(-1), high.reshape(-1)
    out = np.full(lo.shape, np.nan)
    todo = np.flatnonzero(np.isfinite(lo) & np.isfinite(hi))
    lo, hi, rows = lo[todo], hi[todo], rows[todo]
    n = np.arange(a.shape[-1])
    every = ((a - 1j * b) / np.where(n > 0, 2.0, 1.0))[rows]
    phi = [every[:, j] for j in n]
    slopes = [j * every[:, j] for j in n]
    ends = _value([v[:, None] for v in phi], np.asarray(expi(np.stack([lo, hi], axis=-1))))
    v_lo, v_hi = ends[:, 0], ends[:, 1]
    positive = v_lo >= 0.0
    live = np.ones(todo.shape, dtype=bool)
    with np.errstate(all="ignore"):
        x = lo + (hi - lo) * v_lo / (v_lo - v_hi)
        x = np.where((x >= lo) & (x <= hi), x, 0.5 * (lo + hi))
        for _ in range(POLISH):
            v, d = _values(phi, slopes, np.asarray(expi(x)))
            below = (v >= 0.0) == positive
            lo, hi = np.where(below, x, lo), np.where(below, hi, x)
            newton = x - v / d
            moved = np.where((newton >= lo) & (newton <= hi), newton, 0.5 * (lo + hi))
            x, live = np.where(live, moved, x), live & (np.abs(moved - x) > POLISHED)
            if not live.any():
                break
    out[todo] = x
    return np.asarray(np.mod(out, TWO_PI).reshape(shape))


def _root(r: np.ndarray, j: int) -> np.ndarray:
    """r^{1/j} of non-negative r, by square and cube roots where they serve."""
    if j in (2, 4):
        return _root(np.sqrt(r), j // 2)
    return np.asarray(np.cbrt(r) if j == 3 else r if j == 1 else r ** (1.0 / j))


def separation(coef: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """A lower bound on the distance from E* = e^{iθ} to every other root of p, real or not.

    The Taylor shift q_j = p⁽ʲ⁺¹⁾(E*)/(j+1)! (synthetic division) and Fujiwara's bound on the
    deflated polynomial: ρ ≥ 1 / (2·max_j |q_j/q_0|^{1/j}) (``docs/higher_groups.md`` §1.6).

    Parameters
    ----------
    coef : ndarray, complex, shape (..., 2m + 1)
        The coefficients of p in increasing powers.
    theta : ndarray, shape (...)
        A real root of Φ for each polynomial.

    Returns
    -------
    ndarray
        The bound, a chord length on the unit circle (NaN where θ is NaN).

    Examples
    --------
    >>> p = np.array([-1.0, 0.0, 1.0]) + 0j  # E² − 1: roots ±1, 2 apart
    >>> float(separation(p, np.array(0.0)))
    1.0
    """
    z = np.exp(1j * theta)
    n = coef.shape[-1] - 1
    b = [coef[..., i] for i in range(n, -1, -1)]
    for order in range(n):
        # p(E*) itself (b[n] after the first pass) is not needed
        for i in range(1, n - order if order == 0 else n + 1 - order):
            b[i] = b[i] + z * b[i - 1]
    size = [np.abs(b[n - 1 - j]) for j in range(n)]  # |q_j|, j = 0 … n − 1
    with np.errstate(all="ignore"):
        scale = 1.0 / size[0]
        worst = size[1] * scale
        for j in range(2, n):
            np.maximum(worst, _root(size[j] * scale, j), out=worst)
        return np.asarray(0.5 / worst)
