"""The triad's kernels: the corrector and the analogs of a triad without a P–P leash
(unknowns W and θ).

Per position, with the operations of the group's methods: Newton's method on
:meth:`~assur.kinematics.higher.groups.Triad.equations`; the Jacobian and the margin of
:meth:`~assur.kinematics.higher.groups.Triad.lines`; the closed-form coefficients of
:meth:`~assur.kinematics.higher.groups.Triad.coefficients` and the root's separation test;
the analogs by the implicit differentiation of
:func:`~assur.kinematics.higher.continuation.analogs`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from assur.kinematics.higher.compiled._jit import (
    blank,
    close,
    cross,
    design,
    det3,
    dot,
    inline,
    kernel,
    over,
    per_design,
    per_position,
    solve3,
    square,
)
from assur.kinematics.higher.groups import Leash, Triad, TriadInputs
from assur.kinematics.jets import Jet

__all__ = ["analogs_triad", "correct_triad"]

#: Leash forms as the kernel numbers them.
_CODES = {Leash.RR: 0, Leash.RP: 1, Leash.PR: 2}
_RR, _RP = 0, 1


@inline
def _leash(kind: int, p1: complex, e: complex, a: complex, u: complex, r: float, b: complex,
           g: complex) -> tuple[complex, complex, complex]:
    """The base point P₁ + b·E of a leash, its line's direction ν and a point X of the line
    (:meth:`Triad._constraints`)."""
    point = p1 + b * e
    if kind == _RR:
        return point, over(point - a, r), point
    if kind == _RP:
        return point, 1j * u, point
    return point, 1j * g * e, a


@inline
def _residual(kind: int, point: complex, nu: complex, a: complex, r: float) -> float:
    """f of a leash (:meth:`Triad.equations`)."""
    arm = point - a
    if kind == _RR:
        return ((arm.conjugate() * arm).real - r * r) / (2.0 * r)
    return (nu.conjugate() * arm).real


@inline
def _leash_line(kind: int, a_i: complex, a_0: complex, u_i: complex, g_i: complex,
                b_i: complex, r_i: float, r_0: float) -> tuple[complex, complex, float, complex]:
    """(α₀, α₁, c, γ) of the leash's line a·W = p (:meth:`Triad._leash_line`)."""
    d = a_i - a_0
    if kind == _RR:
        c = (r_i * r_i - r_0 * r_0 - square(b_i) - square(d)) / 2.0
        return -d, b_i, c, d.conjugate() * b_i / 2.0
    if kind == _RP:
        n = 1j * u_i
        return n, 0j, dot(n, d), -n.conjugate() * b_i / 2.0
    gg = 1j * g_i
    return 0j, gg, -dot(gg, b_i), gg * d.conjugate() / 2.0


@inline
def _cross_terms(a0: complex, a1: complex, b0: complex, b1: complex) -> tuple[float, complex]:
    """x₀ and x₁ of cross(a, a′) = x₀ + x₁E + x̄₁/E (groups._cross_terms)."""
    return (cross(a0, b0) + cross(a1, b1),
            (a0.conjugate() * b1 - a1 * b0.conjugate()) / 2j)


@inline
def _half(kinds: np.ndarray, degree: int, a0: complex, a1: complex, a2: complex,
          u0: complex, u1: complex, u2: complex, r0: float, r1: float, r2: float,
          b0: complex, b1: complex, b2: complex, g0: complex, g1: complex, g2: complex
          ) -> tuple[complex, complex, complex, complex]:
    """φ₀ … φ₃ of Φ(θ) = Σ φ_n Eⁿ (:meth:`Triad._half`; zero above the degree)."""
    l0 = _leash_line(kinds[0], a0, a0, u0, g0, b0, r0, r0)
    l1 = _leash_line(kinds[1], a1, a0, u1, g1, b1, r1, r0)
    l2 = _leash_line(kinds[2], a2, a0, u2, g2, b2, r2, r0)
    if kinds[0] == _RR:
        (al2, be2, c2, ga2), (al3, be3, c3, ga3) = l1, l2
        h2, h3 = ga2.conjugate(), ga3.conjugate()
        m0 = h2 * al3 - h3 * al2
        m1 = c2 * al3 + h2 * be3 - c3 * al2 - h3 * be2
        m2 = ga2 * al3 + c2 * be3 - ga3 * al2 - c3 * be2
        m3 = ga2 * be3 - ga3 * be2
        x0, x1 = _cross_terms(al2, be2, al3, be3)
        rr = r0 * r0
        top = m3 * m0.conjugate() if degree == 3 else 0j
        return ((m0 * m0.conjugate() + m1 * m1.conjugate() + m2 * m2.conjugate()
                 + m3 * m3.conjugate()) - rr * (x0 * x0 + 2.0 * square(x1)),
                (m1 * m0.conjugate() + m2 * m1.conjugate() + m3 * m2.conjugate())
                - rr * (2.0 * x0 * x1),
                (m2 * m0.conjugate() + m3 * m1.conjugate()) - rr * (x1 * x1), top)
    h0, h1, h2 = 0j, 0j, 0j
    for own, one, two in ((l0, l1, l2), (l1, l2, l0), (l2, l0, l1)):
        x0, x1 = _cross_terms(one[0], one[1], two[0], two[1])
        h0 = h0 + own[2] * x0 + 2.0 * dot(x1, own[3])
        h1 = h1 + own[2] * x1 + own[3] * x0
        h2 = h2 + own[3] * x1
    return h0, h1, (h2 if degree == 2 else 0j), 0j


@inline
def _coefficients(half: tuple[complex, complex, complex, complex], degree: int,
                  out: np.ndarray) -> None:
    """p₀ … p_2m of p(E) = E^m·Φ from φ₀ … φ_m into ``out`` as
    :meth:`~assur.kinematics.higher.groups.Triad.coefficients` lays them out (p_{m±n} = φ_n
    and its conjugate); all NaN where one is not finite."""
    for n in range(degree + 1):
        out[degree + n] = half[n]
        out[degree - n] = half[n].conjugate()
    total = 0j
    for n in range(2 * degree + 1):
        total += out[n]
    if not (math.isfinite(total.real) and math.isfinite(total.imag)):
        out[:] = complex(math.nan, math.nan)


@kernel
def _correct_kernel(kinds: np.ndarray, degree: int, iterations: int, converged: float,
                    a: np.ndarray, u: np.ndarray, r: np.ndarray, b: np.ndarray,
                    g: np.ndarray, size: np.ndarray, sign: np.ndarray, guess: np.ndarray,
                    mask: np.ndarray, x: np.ndarray, jac: np.ndarray, margin: np.ndarray,
                    ok: np.ndarray) -> None:
    """Every position of the flat arrays where ``mask`` corrected and tested
    (:func:`correct_triad`), the others NaN and failed. ``a``, ``u``, ``r`` hold the inputs
    per position (3, P); ``b``, ``g``, ``size``, ``sign`` the drawing per design (3, D), the
    design of position p being p mod D (the positions' last axis)."""
    k0, k1, k2 = kinds[0], kinds[1], kinds[2]
    width = size.shape[0]
    coef = np.empty(2 * degree + 1, dtype=np.complex128)
    work = np.empty(2 * degree + 1, dtype=np.complex128)
    for p in range(guess.shape[0]):
        if not mask[p]:
            blank(p, x, jac, margin, ok)
            continue
        d = p % width
        a0, a1, a2 = a[0, p], a[1, p], a[2, p]
        u0, u1, u2 = u[0, p], u[1, p], u[2, p]
        r0, r1, r2 = r[0, p], r[1, p], r[2, p]
        b0, b1, b2 = b[0, d], b[1, d], b[2, d]
        g0, g1, g2 = g[0, d], g[1, d], g[2, d]
        inv = 1.0 / size[d]
        w0, w1, th = guess[p, 0], guess[p, 1], guess[p, 2]
        step = math.inf
        for iteration in range(iterations + 1):
            e = complex(math.cos(th), math.sin(th))
            p1 = a0 + complex(w0, w1)
            q0, n0, x0 = _leash(k0, p1, e, a0, u0, r0, b0, g0)
            q1, n1, x1 = _leash(k1, p1, e, a1, u1, r1, b1, g1)
            q2, n2, x2 = _leash(k2, p1, e, a2, u2, r2, b2, g2)
            e02, e12, e22 = cross(x0 - p1, n0), cross(x1 - p1, n1), cross(x2 - p1, n2)
            if iteration == iterations or step <= converged:
                break
            d0, d1, d2 = solve3(n0.real, n0.imag, e02, n1.real, n1.imag, e12,
                                n2.real, n2.imag, e22,
                                -_residual(k0, q0, n0, a0, r0), -_residual(k1, q1, n1, a1, r1),
                                -_residual(k2, q2, n2, a2, r2))
            w0, w1, th = w0 + d0, w1 + d1, th + d2
            step = abs(d0 * inv) + abs(d1 * inv) + abs(d2)
        x[p, 0], x[p, 1], x[p, 2] = w0, w1, th
        jac[p, 0, 0], jac[p, 0, 1], jac[p, 0, 2] = n0.real, n0.imag, e02
        jac[p, 1, 0], jac[p, 1, 1], jac[p, 1, 2] = n1.real, n1.imag, e12
        jac[p, 2, 0], jac[p, 2, 1], jac[p, 2, 2] = n2.real, n2.imag, e22
        centre = (q0 + q1 + q2) / 3.0
        spread = math.sqrt((abs(q0 - centre) ** 2 + abs(q1 - centre) ** 2
                            + abs(q2 - centre) ** 2) / 3.0)
        v0, v1, v2 = n0 / abs(n0), n1 / abs(n1), n2 / abs(n2)
        m02 = cross(x0 - centre, v0) / spread
        m12 = cross(x1 - centre, v1) / spread
        m22 = cross(x2 - centre, v2) / spread
        norms = (math.sqrt(v0.real ** 2 + v0.imag ** 2 + m02 ** 2)
                 * math.sqrt(v1.real ** 2 + v1.imag ** 2 + m12 ** 2)
                 * math.sqrt(v2.real ** 2 + v2.imag ** 2 + m22 ** 2))
        margin[p] = abs(det3(v0.real, v0.imag, m02, v1.real, v1.imag, m12,
                             v2.real, v2.imag, m22)) / norms
        det = det3(n0.real, n0.imag, e02, n1.real, n1.imag, e12, n2.real, n2.imag, e22)
        apart = (abs(w0 - guess[p, 0]) * inv + abs(w1 - guess[p, 1]) * inv
                 + abs(th - guess[p, 2]))
        _coefficients(_half(kinds, degree, a0, a1, a2, u0, u1, u2, r0, r1, r2, b0, b1, b2,
                            g0, g1, g2), degree, coef)
        ok[p] = (step <= converged) and (np.sign(det) == sign[d]) and close(coef, th, apart, work)


@inline
def _jmul(a: complex, a1: complex, a2: complex, b: complex, b1: complex, b2: complex
          ) -> tuple[complex, complex, complex]:
    """The product of two jets (value, first and second derivative; :class:`~assur.
    kinematics.jets.Jet`)."""
    return a * b, a1 * b + a * b1, a2 * b + 2.0 * a1 * b1 + a * b2


@inline
def _residual_jet(kind: int, p: complex, p1: complex, p2: complex, e: complex, e1: complex,
                  e2: complex, a: complex, a1: complex, a2: complex, u: complex, u1: complex,
                  u2: complex, r: float, r1: float, r2: float, b: complex, g: complex
                  ) -> tuple[float, float]:
    """The first and second derivative of a leash's f (:meth:`Triad.residual`) with P₁, E,
    the input point, guide and length as jets (p, e, a, u, r)."""
    m, m1, m2 = p + b * e - a, p1 + b * e1 - a1, p2 + b * e2 - a2  # P_k − A_k
    if kind == _RR:
        d, d1, d2 = _jmul(m.conjugate(), m1.conjugate(), m2.conjugate(), m, m1, m2)
        n, n1, n2 = d.real - r * r, d1.real - 2.0 * r * r1, d2.real - 2.0 * (r1 * r1 + r * r2)
        q = n / (2.0 * r)
        q1 = (n1 - q * 2.0 * r1) / (2.0 * r)
        return q1, (n2 - 2.0 * q1 * 2.0 * r1 - q * 2.0 * r2) / (2.0 * r)
    if kind == _RP:  # the line's normal ν
        v, v1, v2 = 1j * u, 1j * u1, 1j * u2
    else:
        v, v1, v2 = _jmul(1j * g, 0j, 0j, e, e1, e2)
    _, f1, f2 = _jmul(v.conjugate(), v1.conjugate(), v2.conjugate(), m, m1, m2)
    return f1.real, f2.real


@inline
def _leash_jet(i: int, kinds: np.ndarray, a: np.ndarray, u: np.ndarray, r: np.ndarray,
               b: np.ndarray, g: np.ndarray, p: int, d: int, p0: complex, p1: complex,
               p2: complex, e: complex, e1: complex, e2: complex) -> tuple[float, float]:
    """:func:`_residual_jet` of leash ``i`` at position ``p`` of the design ``d``."""
    return _residual_jet(kinds[i], p0, p1, p2, e, e1, e2, a[0, i, p], a[1, i, p], a[2, i, p],
                         u[0, i, p], u[1, i, p], u[2, i, p], r[0, i, p].real,
                         r[1, i, p].real, r[2, i, p].real, b[i, d], g[i, d])


@inline
def _derivatives(kinds: np.ndarray, a: np.ndarray, u: np.ndarray, r: np.ndarray,
                 b: np.ndarray, g: np.ndarray, x: np.ndarray, jac: np.ndarray, p: int, d: int,
                 w1: complex, t1: float, part: int) -> tuple[float, float, float]:
    """y with J y = −(derivative ``part`` of F) at position ``p`` of the design ``d``, the
    unknowns a jet with first derivative (w1, t1) and none of second order."""
    e = complex(math.cos(x[p, 2]), math.sin(x[p, 2]))
    e1, e2 = 1j * e * t1, -e * t1 * t1
    p0 = a[0, 0, p] + complex(x[p, 0], x[p, 1])
    p1, p2 = a[1, 0, p] + w1, a[2, 0, p]
    f0 = _leash_jet(0, kinds, a, u, r, b, g, p, d, p0, p1, p2, e, e1, e2)
    f1 = _leash_jet(1, kinds, a, u, r, b, g, p, d, p0, p1, p2, e, e1, e2)
    f2 = _leash_jet(2, kinds, a, u, r, b, g, p, d, p0, p1, p2, e, e1, e2)
    return solve3(jac[p, 0, 0], jac[p, 0, 1], jac[p, 0, 2], jac[p, 1, 0], jac[p, 1, 1],
                  jac[p, 1, 2], jac[p, 2, 0], jac[p, 2, 1], jac[p, 2, 2],
                  -f0[part], -f1[part], -f2[part])


@kernel
def _analogs_kernel(kinds: np.ndarray, a: np.ndarray, u: np.ndarray, r: np.ndarray,
                    b: np.ndarray, g: np.ndarray, x: np.ndarray, jac: np.ndarray,
                    out1: np.ndarray, out2: np.ndarray) -> None:
    """x′ and x″ of every position (:func:`analogs_triad`); ``a``, ``u``, ``r`` hold the
    inputs' value and both derivatives on their first axis, ``b`` and ``g`` the drawing per
    design (:func:`_correct_kernel`)."""
    width = b.shape[1]
    for p in range(x.shape[0]):
        d = p % width
        v0, v1, v2 = _derivatives(kinds, a, u, r, b, g, x, jac, p, d, 0j, 0.0, 0)
        out1[p, 0], out1[p, 1], out1[p, 2] = v0, v1, v2
        out2[p, 0], out2[p, 1], out2[p, 2] = _derivatives(kinds, a, u, r, b, g, x, jac, p, d,
                                                          complex(v0, v1), v2, 1)


def _jets(values: tuple[Any, ...], shape: tuple[int, ...]) -> np.ndarray:
    """Three inputs (None for 0; a jet or a plain value): their value and both derivatives
    at the positions of ``shape``, laid flat, shape (3 parts, 3 inputs, P)."""
    out: np.ndarray = np.zeros((3, 3) + shape, dtype=complex)
    for i, v in enumerate(values):
        if v is not None:
            for j, part in enumerate((v.v, v.d1, v.d2) if isinstance(v, Jet) else (v,)):
                out[j, i] = part
    return out.reshape(3, 3, -1)


def _codes(group: Triad) -> np.ndarray:
    return np.array([_CODES[kind] for kind in group.leashes], dtype=np.int64)


def correct_triad(group: Triad, k: TriadInputs, guess: np.ndarray, sign: np.ndarray,
                  iterations: int, converged: float, mask: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`~assur.kinematics.higher.compiled.correct` for a triad without a P–P leash:
    unknowns (W_x, W_y, θ); drawn values and ``sign`` numbers or one per design, the
    positions' last axis."""
    shape = guess.shape[:-1]
    count = int(np.prod(shape))
    wanted = np.ones(shape, dtype=bool)
    if mask is not None:
        wanted &= mask
    lengths = tuple(group.leash_length(i, k) for i in range(3))
    x, jac = np.empty((count, 3)), np.empty((count, 3, 3))
    margin, ok = np.empty(count), np.empty(count, dtype=bool)
    _correct_kernel(
        _codes(group), group.degree, iterations, converged,
        per_position(k.a, shape, complex), per_position(k.u, shape, complex),
        per_position(lengths, shape, float), per_design(group.offsets, shape, complex),
        per_design(group.guide, shape, complex), design(group.size, shape).astype(float),
        design(sign, shape).astype(float),
        np.ascontiguousarray(guess, dtype=float).reshape(count, 3), wanted.reshape(-1),
        x, jac, margin, ok)
    return (x.reshape(shape + (3,)), jac.reshape(shape + (3, 3)), margin.reshape(shape),
            ok.reshape(shape))


def analogs_triad(group: Triad, k: TriadInputs, x: np.ndarray, jac: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The analogs x′, x″ of a triad's unknowns by implicit differentiation
    (:func:`~assur.kinematics.higher.continuation.analogs`): J x′ = −∂F/∂φ, and
    J x″ = −d²F/dφ² with x′ known and x″ = 0.

    Parameters
    ----------
    group : Triad
        A triad without a P–P leash; drawn values numbers or one per design.
    k : TriadInputs
        Its inputs at the positions, as jets in the crank angle φ.
    x : ndarray, shape (..., D, 3)
        A solution at each position.
    jac : ndarray, shape (..., D, 3, 3)
        The Jacobian there.

    Returns
    -------
    x1, x2 : ndarray, shape (..., D, 3)
    """
    shape = x.shape[:-1]
    count = int(np.prod(shape))
    lengths = tuple(group.leash_length(i, k) for i in range(3))
    x1, x2 = np.empty((count, 3)), np.empty((count, 3))
    _analogs_kernel(_codes(group), _jets(k.a, shape), _jets(k.u, shape), _jets(lengths, shape),
                    per_design(group.offsets, shape, complex),
                    per_design(group.guide, shape, complex),
                    np.ascontiguousarray(x, dtype=float).reshape(count, 3),
                    np.ascontiguousarray(jac, dtype=float).reshape(count, 3, 3), x1, x2)
    return x1.reshape(shape + (3,)), x2.reshape(shape + (3,))
