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

from dataclasses import dataclass

import numpy as np

__all__ = ["RealRoots", "polish", "real_roots", "separation", "trig_form"]

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


def _values(a: np.ndarray, b: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Φ and Φ′ at θ (Q, K) of the polynomials (Q, m + 1), cos nθ and sin nθ by the angle-sum
    recurrence."""
    c1, s1 = np.cos(theta), np.sin(theta)
    cn, sn = c1, s1
    value = a[:, :1] + a[:, 1:2] * c1 + b[:, 1:2] * s1
    slope = b[:, 1:2] * c1 - a[:, 1:2] * s1
    for n in range(2, a.shape[-1]):
        cn, sn = cn * c1 - sn * s1, sn * c1 + cn * s1
        value = value + a[:, n:n + 1] * cn + b[:, n:n + 1] * sn
        slope = slope + n * (b[:, n:n + 1] * cn - a[:, n:n + 1] * sn)
    return value, slope


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
    n = np.arange(m1)
    good = np.isfinite(a).all(axis=-1) & np.isfinite(b).all(axis=-1)
    a, b = np.where(good[:, None], a, 0.0), np.where(good[:, None], b, 0.0)
    h = TWO_PI / SAMPLES
    grid = OFFSET + h * np.arange(SAMPLES + 1)
    value = a @ np.cos(np.outer(n, grid)) + b @ np.sin(np.outer(n, grid))
    above = value >= 0.0
    change = (above[:, :-1] != above[:, 1:]) & good[:, None]
    rank = np.cumsum(change, axis=1, dtype=np.int16) - 1
    rows, cols = np.nonzero(change & (rank < width))
    va, vb = value[rows, cols], value[rows, cols + 1]
    out = [np.full((count_p, width), np.nan) for _ in range(3)]
    signs = np.zeros((count_p, width))
    at = rows, rank[rows, cols]
    with np.errstate(all="ignore"):
        out[0][at] = np.mod(grid[cols] + h * va / (va - vb), TWO_PI)
    out[1][at], out[2][at] = grid[cols], grid[cols + 1]
    signs[at] = np.where(va >= 0.0, -1.0, 1.0)
    order = np.argsort(out[0], axis=-1)
    theta, low, high = (np.take_along_axis(v, order, axis=-1) for v in out)
    return RealRoots(theta=theta, slope=np.take_along_axis(signs, order, axis=-1),
                     low=low, high=high)


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
    lo, hi = low.reshape(-1).copy(), high.reshape(-1).copy()
    out = np.full(lo.shape, np.nan)
    todo = np.flatnonzero(np.isfinite(lo) & np.isfinite(hi))
    v_lo = _values(a[rows[todo]], b[rows[todo]], lo[todo, None])[0][:, 0]
    v_hi = _values(a[rows[todo]], b[rows[todo]], hi[todo, None])[0][:, 0]
    positive = np.zeros(lo.shape, dtype=bool)
    positive[todo] = v_lo >= 0.0
    x = out.copy()
    with np.errstate(all="ignore"):
        x[todo] = lo[todo] + (hi[todo] - lo[todo]) * v_lo / (v_lo - v_hi)
        x[todo] = np.where((x[todo] >= lo[todo]) & (x[todo] <= hi[todo]), x[todo],
                           0.5 * (lo[todo] + hi[todo]))
        for _ in range(POLISH):
            if not todo.size:
                break
            xs, low_t, high_t = x[todo], lo[todo], hi[todo]
            v, d = (part[:, 0] for part in _values(a[rows[todo]], b[rows[todo]], xs[:, None]))
            below = (v >= 0.0) == positive[todo]
            low_t, high_t = np.where(below, xs, low_t), np.where(below, high_t, xs)
            newton = xs - v / d
            moved = np.where((newton >= low_t) & (newton <= high_t), newton,
                             0.5 * (low_t + high_t))
            x[todo], lo[todo], hi[todo] = moved, low_t, high_t
            todo = todo[np.abs(moved - xs) > POLISHED]
    return np.asarray(np.mod(x, TWO_PI).reshape(shape))


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
    shifted = []
    for order in range(n + 1):
        for i in range(1, n + 1 - order):
            b[i] = b[i] + z * b[i - 1]
        shifted.append(b[n - order])
    q = shifted[1:]
    with np.errstate(all="ignore"):
        worst = np.max([np.abs(q[j] / q[0]) ** (1.0 / j) for j in range(1, len(q))], axis=0)
        return np.asarray(0.5 / worst)
