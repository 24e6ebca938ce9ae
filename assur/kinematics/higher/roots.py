"""Every real root of many trigonometric polynomials at once, each isolated with a certificate.

The eliminant of a four-link group is a real trigonometric polynomial of degree m,

    Φ(θ) = Σ_{n=0..m} a_n cos nθ + b_n sin nθ,

whose real roots are the group's assembly modes (``docs/higher_groups.md`` §1.3). Here the
roots of P such polynomials are found together: Φ is sampled on a uniform grid of θ, and each
interval between two samples is certified to hold no root or exactly one, from the bound
|Φ″| ≤ B = Σ n²·√(a_n² + b_n²):

* a sign change and |Φ′| > B·h at one end: Φ is monotone there, one root;
* no sign change and either Φ monotone or |Φ| > B·h²/2 at one end: no root (two roots in an
  interval of width h, by Rolle's theorem, keep |Φ| ≤ B·h²/2 at both its ends).

An interval that is neither is split, and its parts are tested in turn; the bracketed roots
are then polished by safeguarded Newton steps. The separation of a root from every other
root of p(E) = E^m·Φ, real or complex, is bounded below by Fujiwara's bound on the
polynomial deflated at the root (:func:`separation`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["RealRoots", "real_roots", "separation", "trig_form"]

TWO_PI = 2.0 * np.pi
#: θ samples per turn of the first pass.
SAMPLES = 32
#: An interval that is not certified is split into this many.
SPLIT = 8
#: An interval narrower than this (rad) is taken as certified: one root where Φ changes sign
#: over it, none where it does not (two roots closer than this are one double root).
NARROWEST = 1e-12
#: At most this many safeguarded Newton steps polish each bracketed root; they stop once
#: every step is below ``POLISHED`` (rad).
POLISH = 40
POLISHED = 4e-15
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
    >>> a, b = trig_form(np.array([0.5j, 1.0, -0.5j]))  # Φ = 1 + sin θ
    >>> a.tolist(), b.tolist()
    ([1.0, 0.0], [0.0, 1.0])
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


def _certify(va: np.ndarray, vb: np.ndarray, da: np.ndarray, db: np.ndarray,
             limit: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """Per interval of width h (values va, vb and slopes da, db at its ends, |Φ″| ≤ limit):
    where it holds exactly one root, and where it must be split (neither one root nor
    none is certified).

    One root: a sign change, and Φ′ at an end too large to vanish within h. No root: no sign
    change, and Φ kept off zero by its Taylor bound from either end, Φ(a + t) ≥ |va| −
    |da|·t − limit·t²/2 in the sign of va (the bound is concave: its least value on [0, h]
    is at t = 0 or t = h), or Φ monotone.
    """
    change = (va >= 0.0) != (vb >= 0.0)
    monotone = np.maximum(np.abs(da), np.abs(db)) > limit * h
    if h < NARROWEST:
        return change, np.zeros(change.shape, dtype=bool)
    sign = np.where(va >= 0.0, 1.0, -1.0)
    drop = 0.5 * limit * h * h
    from_a = sign * (va + da * h) - drop
    from_b = sign * (vb - db * h) - drop
    empty = (np.minimum(np.abs(va), from_a) > 0.0) | (np.minimum(np.abs(vb), from_b) > 0.0)
    one = change & monotone
    return one, ~one & (change | ~(monotone | empty))


@dataclass(frozen=True, eq=False)
class RealRoots:
    """The real roots of P trigonometric polynomials.

    Attributes
    ----------
    theta : ndarray, shape (P, 2m)
        The roots in [0, 2π), increasing; NaN after the last.
    count : ndarray, int, shape (P,)
        The number of real roots.
    slope : ndarray, shape (P, 2m)
        The sign of Φ′ at each root (0 after the last).
    """

    theta: np.ndarray
    count: np.ndarray
    slope: np.ndarray


def real_roots(a: np.ndarray, b: np.ndarray) -> RealRoots:
    """Every real root of Φ(θ) = Σ a_n cos nθ + b_n sin nθ, for P polynomials at once.

    Parameters
    ----------
    a, b : ndarray, shape (P, m + 1)
        The coefficients (:func:`trig_form`); a polynomial with a coefficient that is not
        finite, or that is identically zero, has no root.

    Returns
    -------
    RealRoots

    Examples
    --------
    >>> found = real_roots(np.array([[0.0, 0.0, 1.0]]), np.zeros((1, 3)))  # cos 2θ
    >>> np.round(np.degrees(found.theta[0]), 9).tolist(), found.slope[0].tolist()
    ([45.0, 135.0, 225.0, 315.0], [-1.0, 1.0, -1.0, 1.0])
    """
    count_p, m1 = a.shape
    width = 2 * (m1 - 1)
    n = np.arange(m1)
    good = np.isfinite(a).all(axis=-1) & np.isfinite(b).all(axis=-1)
    a, b = np.where(good[:, None], a, 0.0), np.where(good[:, None], b, 0.0)
    bound = (n * n * np.hypot(a, b)).sum(axis=-1)
    good &= bound > 0.0
    h = TWO_PI / SAMPLES
    grid = OFFSET + h * np.arange(SAMPLES + 1)
    cos, sin = np.cos(np.outer(n, grid)), np.sin(np.outer(n, grid))
    value = a @ cos + b @ sin
    slope = (b * n) @ cos - (a * n) @ sin
    one, split = _certify(value[:, :-1], value[:, 1:], slope[:, :-1], slope[:, 1:],
                          bound[:, None], h)
    split &= good[:, None]
    rows, cols = np.nonzero(one & good[:, None])
    bracket_rows, bracket_lo, bracket_h = [rows], [grid[cols]], [np.full(rows.size, h)]
    bracket_v = [value[rows, cols]]
    bracket_w = [value[rows, cols + 1]]
    rows, cols = np.nonzero(split)
    lo = grid[cols]
    while rows.size:
        h = h / SPLIT
        points = lo[:, None] + h * np.arange(SPLIT + 1)
        v, d = _values(a[rows], b[rows], points)
        one, split = _certify(v[:, :-1], v[:, 1:], d[:, :-1], d[:, 1:],
                              bound[rows, None], h)
        parent, cols = np.nonzero(one)
        bracket_rows.append(rows[parent])
        bracket_lo.append(points[parent, cols])
        bracket_h.append(np.full(parent.size, h))
        bracket_v.append(v[parent, cols])
        bracket_w.append(v[parent, cols + 1])
        parent, cols = np.nonzero(split)
        rows, lo = rows[parent], points[parent, cols]
    which = np.concatenate(bracket_rows)
    left = np.concatenate(bracket_lo)
    right = left + np.concatenate(bracket_h)
    theta, sign = _polish(a[which], b[which], left, right, np.concatenate(bracket_v),
                          np.concatenate(bracket_w))
    order = np.lexsort((theta, which))
    which, theta, sign = which[order], theta[order], sign[order]
    count = np.bincount(which, minlength=count_p)
    rank = np.arange(which.size) - (np.cumsum(count) - count)[which]
    keep = rank < width
    out = np.full((count_p, width), np.nan)
    signs = np.zeros((count_p, width))
    out[which[keep], rank[keep]] = theta[keep]
    signs[which[keep], rank[keep]] = sign[keep]
    return RealRoots(theta=out, count=np.minimum(count, width), slope=signs)


def _polish(a: np.ndarray, b: np.ndarray, lo: np.ndarray, hi: np.ndarray, at_lo: np.ndarray,
            at_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The root in each bracket [lo, hi] (Φ = ``at_lo`` and ``at_hi`` there, of opposite signs)
    from the secant point by Newton steps kept inside the shrinking bracket (a step leaving it
    is a bisection), iterated on the roots not yet polished only; and the sign of Φ′ there
    (that of −Φ(lo))."""
    positive = at_lo >= 0.0
    with np.errstate(all="ignore"):
        x = lo + (hi - lo) * at_lo / (at_lo - at_hi)
    x = np.where((x >= lo) & (x <= hi), x, 0.5 * (lo + hi))
    todo = np.arange(x.size)
    with np.errstate(all="ignore"):
        for _ in range(POLISH):
            xs, low, high = x[todo], lo[todo], hi[todo]
            v, d = (part[:, 0] for part in _values(a[todo], b[todo], xs[:, None]))
            below = (v >= 0.0) == positive[todo]
            low, high = np.where(below, xs, low), np.where(below, high, xs)
            newton = xs - v / d
            moved = np.where((newton >= low) & (newton <= high), newton, 0.5 * (low + high))
            x[todo], lo[todo], hi[todo] = moved, low, high
            todo = todo[np.abs(moved - xs) > POLISHED]
            if not todo.size:
                break
    return np.mod(x, TWO_PI), np.where(positive, -1.0, 1.0)


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
