"""The class IV group's kernel: the corrector of :class:`~assur.kinematics.higher.coupled.
ClassIVCoupled` (unknowns y_a, y_c), every form.

Per position: the matrices M_j of
:meth:`~assur.kinematics.higher.coupled.ClassIVCoupled._matrices`, in closed form from the
inputs, the arms and the coupler's length or guide where both links are hinged, else fitted
as the group fits them (the lifted loop equations of
:meth:`~assur.kinematics.higher.coupled.ClassIVCoupled._loops` at y_a, y_c ∈ {0, π/2, π});
Newton's method on
:meth:`~assur.kinematics.higher.coupled.ClassIVCoupled.equations` (w(y), w′(y) contracted
with M, the lifting factors of sliding links, none for a PP coupler); the Jacobian and the
margin of :meth:`~assur.kinematics.higher.coupled.ClassIVCoupled.lines`; the coefficients of
the eliminant from M (:meth:`~assur.kinematics.higher.coupled.ClassIVCoupled.coefficients`,
as products of Laurent polynomials in e^{iy_ε} rather than from samples) and the root's
separation bound. The drawing is read per design, the inputs per position.
"""

from __future__ import annotations

import math

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.higher.compiled._jit import (
    blank,
    close,
    cross,
    design,
    det2,
    inline,
    kernel,
    per_design,
    per_position,
    solve2,
    square,
)
from assur.kinematics.higher.coupled import (
    FULL_DEGREE,
    SAMPLES,
    ClassIVCoupled,
)
from assur.kinematics.higher.groups import ClassIVInputs, Leash, plain

__all__ = ["correct_coupled"]

#: Coupler forms as the kernel numbers them.
_CODES = {Leash.RR: 0, Leash.PR: 1, Leash.RP: 2, Leash.PP: 3}
_RR, _PR, _PP = 0, 1, 3
#: e^{iy} and e^{iy/2} at the samples y ∈ {0, π/2, π} of the fit, as the group takes them.
_UNITS, _HALF_UNITS = plain(J.expi(SAMPLES)), plain(J.expi(0.5 * SAMPLES))


@inline
def _link(slides: bool, unit: complex, half: complex, h: complex, u: complex, drawn: complex,
          size: float) -> tuple[complex, float, complex, complex]:
    """A link a or c at the unknown y, ``unit`` = e^{iy}, ``half`` = e^{iy/2}: its turn E,
    the weight κ, κ·O and κ·E (:meth:`ClassIVCoupled._links`)."""
    if not slides:
        return unit, 1.0, h, unit
    weight = half.real
    turn = u / drawn
    return turn, weight, weight * h + size * half.imag * u, weight * turn


@inline
def _loop(kind: int, a: tuple[complex, float, complex, complex],
          c: tuple[complex, float, complex, complex], arm_a: complex, arm_c: complex,
          length: float, guide_a: complex, guide_c: complex, side: complex) -> float:
    """F̂_j of a coupler (:meth:`ClassIVCoupled._loops`): its pairs' points on a and on c,
    ``arm_a``, ``arm_c`` from the external pairs, the bar's length, the guides of its pairs
    (on a, on c), ``side`` the first pair's point less the second's as drawn."""
    turn_a, weight_a, origin_a, carried_a = a
    turn_c, weight_c, origin_c, carried_c = c
    both = weight_a * weight_a * weight_c * weight_c
    gap = weight_c * (origin_a + carried_a * arm_a) - weight_a * (origin_c + carried_c * arm_c)
    if kind == _RR:
        return (gap.conjugate() * gap).real - length * length * both
    if kind == _PP:
        return cross(turn_a, turn_c)
    turn, guide = (turn_a, guide_a) if kind == _PR else (turn_c, guide_c)
    return weight_a * weight_c * cross(turn * guide, gap) - cross(guide, side) * both


@inline
def _fit(kinds: np.ndarray, sa: bool, sc: bool, unit: np.ndarray, half: np.ndarray,
         h: np.ndarray, u: np.ndarray, drawn: np.ndarray, length: np.ndarray, arm: np.ndarray,
         guide: np.ndarray, side: np.ndarray, size: float, p: int, d: int, values: np.ndarray,
         m: np.ndarray) -> None:
    """M_j (2, 3, 3) at position ``p`` of design ``d`` into ``m``
    (:meth:`ClassIVCoupled._matrices`): scale_j·F̂_j at y_a, y_c ∈ ``coupled.SAMPLES``
    (e^{iy} ``unit``, e^{iy/2} ``half``) into ``values``, then FROM·values_j·FROMᵀ
    (``coupled.FROM_SAMPLES``: F(0), 2F(π/2) − F(0) − F(π), F(π) along each axis)."""
    links_c = (_link(sc, unit[0], half[0], h[1, p], u[1, p], drawn[1, d], size),
               _link(sc, unit[1], half[1], h[1, p], u[1, p], drawn[1, d], size),
               _link(sc, unit[2], half[2], h[1, p], u[1, p], drawn[1, d], size))
    scales = (0.5 / length[0, p] if kinds[0] == _RR else size if kinds[0] == _PP else 1.0,
              0.5 / length[1, p] if kinds[1] == _RR else size if kinds[1] == _PP else 1.0)
    for ia in range(3):
        a = _link(sa, unit[ia], half[ia], h[0, p], u[0, p], drawn[0, d], size)
        for ic in range(3):
            for j in range(2):
                values[j, ia, ic] = scales[j] * _loop(
                    kinds[j], a, links_c[ic], arm[2 * j, d], arm[2 * j + 1, d], length[j, p],
                    guide[2 * j, d], guide[2 * j + 1, d], side[j, d])
    for j in range(2):
        for ia in range(3):  # rows: FROM·values_j
            v0, v1, v2 = values[j, 0, ia], values[j, 1, ia], values[j, 2, ia]
            values[j, 0, ia], values[j, 1, ia] = v0, -v0 + 2.0 * v1 - v2
            values[j, 2, ia] = v2
        for ia in range(3):  # columns: ·FROMᵀ
            v0, v1, v2 = values[j, ia, 0], values[j, ia, 1], values[j, ia, 2]
            m[j, ia, 0], m[j, ia, 1], m[j, ia, 2] = v0, -v0 + 2.0 * v1 - v2, v2


@inline
def _hinged(kind: int, gap: complex, arm_a: complex, arm_c: complex, length: float,
            guide_a: complex, guide_c: complex, side: complex, size: float, m: np.ndarray,
            j: int) -> None:
    """M_j of a coupler between hinged links a and c in closed form into ``m``: the matrix
    of :func:`_fit` to roundoff.

    With E_a = e^{iy_a}, E_c = e^{iy_c}, P = H_a − H_c (``gap``), A, C the arms, the gap of
    the coupler's pairs is P + A·E_a − C·E_c, and F̂_j (:func:`_loop`) has the coefficients
    T of (1, cos y, sin y) of y_a (rows) and of y_c (columns):

    - a bar of length l: |P + A·E_a − C·E_c|² − l² = K + 2Re(P̄A·E_a) − 2Re(P̄C·E_c) −
      2Re(ĀC·Ē_aE_c), K = |P|² + |A|² + |C|² − l², scale 1/(2l);
    - a block turning with a (guide g on a): Im(ḡP·Ē_a) + Im(ḡA) − Im(ḡC·Ē_aE_c) −
      cross(g, side); with c (guide g on c): Im(ḡP·Ē_c) + Im(ḡA·E_aĒ_c) − Im(ḡC) −
      cross(g, side);
    - a PP coupler: Im(Ē_aE_c), scale L.

    Then 1 = w₀ + w₂, cos y = w₀ − w₂, sin y = 2w₁ in w(y) = (κ², κσ, σ²): M_j = scale·LTLᵀ,
    L = [[1, 1, 0], [0, 0, 2], [1, −1, 0]].
    """
    t00, t01, t02, t10, t20 = 0.0, 0.0, 0.0, 0.0, 0.0
    if kind == _RR:
        za, zc, q = gap.conjugate() * arm_a, gap.conjugate() * arm_c, arm_a.conjugate() * arm_c
        t00 = square(gap) + square(arm_a) + square(arm_c) - length * length
        t10, t20, t01, t02 = 2.0 * za.real, -2.0 * za.imag, -2.0 * zc.real, 2.0 * zc.imag
        t11, t12, t21, t22 = -2.0 * q.real, 2.0 * q.imag, -2.0 * q.imag, -2.0 * q.real
        scale = 0.5 / length
    elif kind == _PP:
        t11, t12, t21, t22 = 0.0, 1.0, -1.0, 0.0
        scale = size
    elif kind == _PR:
        z1, z2 = guide_a.conjugate() * gap, guide_a.conjugate() * arm_c
        t00 = cross(guide_a, arm_a) - cross(guide_a, side)
        t10, t20 = z1.imag, -z1.real
        t11, t12, t21, t22 = -z2.imag, -z2.real, z2.real, -z2.imag
        scale = 1.0
    else:
        z1, z2 = guide_c.conjugate() * gap, guide_c.conjugate() * arm_a
        t00 = -cross(guide_c, arm_c) - cross(guide_c, side)
        t01, t02 = z1.imag, -z1.real
        t11, t12, t21, t22 = z2.imag, -z2.real, z2.real, z2.imag
        scale = 1.0
    rows = ((t00 + t10, t01 + t11, t02 + t12), (2.0 * t20, 2.0 * t21, 2.0 * t22),
            (t00 - t10, t01 - t11, t02 - t12))
    for r in range(3):
        r0, r1, r2 = rows[r]
        m[j, r, 0] = scale * (r0 + r1)
        m[j, r, 1] = scale * (2.0 * r2)
        m[j, r, 2] = scale * (r0 - r1)


@inline
def _halves(y: float) -> tuple[float, float, float, float, float, float]:
    """w(y) = (κ², κσ, σ²) and w′(y) = (−κσ, (κ² − σ²)/2, κσ), κ = cos(y/2), σ = sin(y/2)
    (:func:`~assur.kinematics.higher.coupled._halves_turning`)."""
    k, s = math.cos(0.5 * y), math.sin(0.5 * y)
    w0, w1, w2 = k * k, k * s, s * s
    return w0, w1, w2, -w1, (w0 - w2) * 0.5, w1


@inline
def _form(m: np.ndarray, j: int, a0: float, a1: float, a2: float, c0: float,
          c1: float, c2: float) -> float:
    """w_a·M_j·w_c."""
    form: float = (a0 * (m[j, 0, 0] * c0 + m[j, 0, 1] * c1 + m[j, 0, 2] * c2)
                   + a1 * (m[j, 1, 0] * c0 + m[j, 1, 1] * c1 + m[j, 1, 2] * c2)
                   + a2 * (m[j, 2, 0] * c0 + m[j, 2, 1] * c1 + m[j, 2, 2] * c2))
    return form


@inline
def _row(m: np.ndarray, j: int, ha: tuple[float, float, float, float, float, float],
         hc: tuple[float, float, float, float, float, float], lifted: bool, qa: float,
         da: float, qc: float, dc: float) -> tuple[float, float, float]:
    """g_j and ∂g_j/∂y_a, ∂g_j/∂y_c from M_j, w and w′ of y_a (``ha``) and of y_c (``hc``),
    divided by the lifting factor qa·qc (slopes da·qc, qa·dc) where ``lifted``."""
    wa0, wa1, wa2, ta0, ta1, ta2 = ha
    wc0, wc1, wc2, tc0, tc1, tc2 = hc
    g = _form(m, j, wa0, wa1, wa2, wc0, wc1, wc2)
    ga = _form(m, j, ta0, ta1, ta2, wc0, wc1, wc2)
    gc = _form(m, j, wa0, wa1, wa2, tc0, tc1, tc2)
    if not lifted:
        return g, ga, gc
    lift = qa * qc
    g = g / lift
    return g, (ga - g * (da * qc)) / lift, (gc - g * (qa * dc)) / lift


@inline
def _lines(m: np.ndarray, j: int, eliminated: int
           ) -> tuple[complex, complex, complex, float, float, float]:
    """α_j = Σ_r w_r·A_r and π_j = Σ_r w_r·P_r at y_ε, w = w(y_ε): A_r, P_r of Re(ᾱ_j E_o) =
    π_j (:meth:`ClassIVCoupled._linear`: the coefficients (d₀, d₁, d₂) of F̂_j in w(y_o) are
    M_j contracted with w(y_ε), α_j = (d₀ − d₂ + i·d₁)/2, π_j = −(d₀ + d₂)/2)."""
    if eliminated == 0:
        e0, e1, e2 = m[j, 0, 0], m[j, 0, 1], m[j, 0, 2]
        f0, f1, f2 = m[j, 1, 0], m[j, 1, 1], m[j, 1, 2]
        g0, g1, g2 = m[j, 2, 0], m[j, 2, 1], m[j, 2, 2]
    else:
        e0, e1, e2 = m[j, 0, 0], m[j, 1, 0], m[j, 2, 0]
        f0, f1, f2 = m[j, 0, 1], m[j, 1, 1], m[j, 2, 1]
        g0, g1, g2 = m[j, 0, 2], m[j, 1, 2], m[j, 2, 2]
    return (0.5 * complex(e0 - e2, e1), 0.5 * complex(f0 - f2, f1), 0.5 * complex(g0 - g2, g1),
            -0.5 * (e0 + e2), -0.5 * (f0 + f2), -0.5 * (g0 + g2))


@inline
def _laurent(a0: complex, a1: complex, a2: complex) -> tuple[complex, complex, complex]:
    """The coefficients of E⁻¹, 1, E of Σ_r w_r·a_r on |E| = 1, w = w(arg E): w₀ = 1/2 +
    (E + E⁻¹)/4, w₁ = (E − E⁻¹)/(4i), w₂ = 1/2 − (E + E⁻¹)/4."""
    return 0.25 * (a0 - a2 + 1j * a1), 0.5 * (a0 + a2), 0.25 * (a0 - a2 - 1j * a1)


@inline
def _times(x: tuple[complex, complex, complex], y: tuple[complex, complex, complex]
           ) -> tuple[complex, complex, complex, complex, complex]:
    """The coefficients of E⁻² … E² of the product of two Laurent polynomials of degree 1."""
    return (x[0] * y[0], x[0] * y[1] + x[1] * y[0], x[0] * y[2] + x[1] * y[1] + x[2] * y[0],
            x[1] * y[2] + x[2] * y[1], x[2] * y[2])


@inline
def _coefficients(m: np.ndarray, eliminated: int, linear_kept: bool, deflations: int,
                  series: np.ndarray, out: np.ndarray) -> None:
    """p₀ … p_2m of p(E) = E^m·Φ̃ into ``out`` (:meth:`ClassIVCoupled.coefficients`): Φ =
    |π_bα_d − π_dα_b|² − cross(α_b, α_d)² (cross(α_b, α_d) where both lines are linear in
    a kept slide) as a Laurent polynomial in E = e^{iy_ε}, the coefficients of E⁴Φ into
    ``series``, the root −1 divided out ``deflations`` times, the middle 2m + 1 kept.

    α_j, π_j are Laurent polynomials of degree 1 (:func:`_laurent`); the gap g = π_bα_d −
    π_dα_b and h = ᾱ_bα_d of degree 2 (:func:`_times`, ᾱ_b = Σ ā_k E⁻ᵏ on the unit
    circle). Φ is real there: φ₋ₙ = φ̄ₙ, and for n ≥ 0 |g|² has the coefficients
    Σ_k g_k·ḡ_{k−n}, cross(α_b, α_d) = Im h the coefficients c_n = (h_n − h̄₋ₙ)/(2i) and
    its square Σ_k c_k·c_{n−k}: the coefficients that sampling Φ off −1 gives, without
    the samples.
    """
    b0, b1, b2, q0, q1, q2 = _lines(m, 0, eliminated)
    d0, d1, d2, r0, r1, r2 = _lines(m, 1, eliminated)
    ab, ad = _laurent(b0, b1, b2), _laurent(d0, d1, d2)
    h = _times((ab[2].conjugate(), ab[1].conjugate(), ab[0].conjugate()), ad)
    c0 = h[2].imag
    c1 = (h[3] - h[1].conjugate()) * -0.5j
    c2 = (h[4] - h[0].conjugate()) * -0.5j
    if linear_kept:
        phi = (complex(c0), c1, c2, 0j, 0j)
    else:
        pb = _laurent(complex(q0), complex(q1), complex(q2))
        pd = _laurent(complex(r0), complex(r1), complex(r2))
        x, y = _times(pb, ad), _times(pd, ab)
        g0, g1, g2, g3, g4 = x[0] - y[0], x[1] - y[1], x[2] - y[2], x[3] - y[3], x[4] - y[4]
        phi = (complex(square(g0) + square(g1) + square(g2) + square(g3) + square(g4)
                       - 2.0 * (square(c2) + square(c1)) - c0 * c0),
               g1 * g0.conjugate() + g2 * g1.conjugate() + g3 * g2.conjugate()
               + g4 * g3.conjugate() - 2.0 * (c1.conjugate() * c2 + c0 * c1),
               g2 * g0.conjugate() + g3 * g1.conjugate() + g4 * g2.conjugate()
               - 2.0 * c0 * c2 - c1 * c1,
               g3 * g0.conjugate() + g4 * g1.conjugate() - 2.0 * c1 * c2,
               g4 * g0.conjugate() - c2 * c2)
    for n in range(FULL_DEGREE + 1):
        series[FULL_DEGREE + n] = phi[n]
        series[FULL_DEGREE - n] = phi[n].conjugate()
    top = series.shape[0] - 1
    scale = 1.0
    for _ in range(deflations):  # the quotient by E + 1 in place (coupled._deflate)
        scale *= 2.0
        carry = series[top]
        for i in range(top - 1, -1, -1):
            rest = series[i]
            series[i] = carry
            carry = rest - carry
        top -= 1
    start = FULL_DEGREE - deflations // 2 - (out.shape[0] - 1) // 2
    for n in range(out.shape[0]):
        out[n] = series[start + n] * scale


@inline
def _column(slides: bool, y: float, size: float, radius: float) -> float:
    """The margin rows' scale of a column: ∂t/∂s = 2L/(L² + s²) of a slide s = L·tan(t/2),
    1/radius of a rotation (:meth:`~assur.kinematics.higher.coupled.ClassIVCoupled.lines`)."""
    if slides:
        s = size * math.tan(0.5 * y)
        return 2.0 * size / (size ** 2 + s * s)
    return 1.0 / radius


@kernel
def _correct_kernel(kinds: np.ndarray, slides: np.ndarray, eliminated: int,
                    linear_kept: bool, deflations: int, degree: int, unit: np.ndarray,
                    half: np.ndarray, iterations: int, converged: float, h: np.ndarray,
                    u: np.ndarray, length: np.ndarray,
                    drawn: np.ndarray, arm: np.ndarray, guide: np.ndarray, side: np.ndarray,
                    size: np.ndarray, radius: np.ndarray, sign: np.ndarray, guess: np.ndarray,
                    mask: np.ndarray, x: np.ndarray, jac: np.ndarray, margin: np.ndarray,
                    ok: np.ndarray) -> None:
    """Every position of the flat arrays where ``mask`` corrected and tested
    (:func:`correct_coupled`), the others NaN and failed. ``h``, ``u``, ``length`` hold the
    inputs per position (2, P), ``sign`` (P,); ``drawn``, ``arm``, ``guide``, ``side``,
    ``radius`` the drawing per design as rows (n, D), ``size`` (D,), the design of position p
    being p mod D (the positions' last axis). With both links hinged M is written in closed
    form (:func:`_hinged`), with a sliding link fitted (:func:`_fit`)."""
    sa, sc = slides[0] != 0, slides[1] != 0
    lift0, lift1 = (sa or sc) and kinds[0] != _PP, (sa or sc) and kinds[1] != _PP
    width = size.shape[0]
    values = np.empty((2, 3, 3))
    m = np.empty((2, 3, 3))
    series = np.empty(2 * FULL_DEGREE + 1, dtype=np.complex128)
    coef = np.empty(2 * degree + 1, dtype=np.complex128)
    work = np.empty(2 * degree + 1, dtype=np.complex128)
    for p in range(guess.shape[0]):
        if not mask[p]:
            blank(p, x, jac, margin, ok)
            continue
        d = p % width
        if sa or sc:
            _fit(kinds, sa, sc, unit, half, h, u, drawn, length, arm, guide, side, size[d], p,
                 d, values, m)
        else:
            for j in range(2):
                _hinged(kinds[j], h[0, p] - h[1, p], arm[2 * j, d], arm[2 * j + 1, d],
                        length[j, p], guide[2 * j, d], guide[2 * j + 1, d], side[j, d],
                        size[d], m, j)
        ya, yc = guess[p, 0], guess[p, 1]
        step = math.inf
        for iteration in range(iterations + 1):
            ha, hc = _halves(ya), _halves(yc)
            qa, da = (ha[0], -ha[1]) if sa else (1.0, 0.0)
            qc, dc = (hc[0], -hc[1]) if sc else (1.0, 0.0)
            g0, e00, e01 = _row(m, 0, ha, hc, lift0, qa, da, qc, dc)
            g1, e10, e11 = _row(m, 1, ha, hc, lift1, qa, da, qc, dc)
            if iteration == iterations or step <= converged:
                break
            d0, d1 = solve2(e00, e01, e10, e11, -g0, -g1)
            ya, yc = ya + d0, yc + d1
            step = abs(d0) + abs(d1)
        x[p, 0], x[p, 1] = ya, yc
        jac[p, 0, 0], jac[p, 0, 1], jac[p, 1, 0], jac[p, 1, 1] = e00, e01, e10, e11
        ka = _column(sa, ya, size[d], radius[0, d])
        kc = _column(sc, yc, size[d], radius[1, d])
        r00, r01, r10, r11 = e00 * ka, e01 * kc, e10 * ka, e11 * kc
        margin[p] = abs(det2(r00, r01, r10, r11)) / (math.sqrt(r00 * r00 + r01 * r01)
                                                     * math.sqrt(r10 * r10 + r11 * r11))
        ok[p] = (step <= converged) and (np.sign(det2(e00, e01, e10, e11)) == sign[p])
        if ok[p]:  # the bound only where the other tests pass
            _coefficients(m, eliminated, linear_kept, deflations, series, coef)
            ok[p] = close(coef, ya if eliminated == 0 else yc,
                          abs(ya - guess[p, 0]) + abs(yc - guess[p, 1]), work)


def correct_coupled(group: ClassIVCoupled, k: ClassIVInputs, guess: np.ndarray,
                    sign: np.ndarray, iterations: int, converged: float,
                    mask: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`~assur.kinematics.higher.compiled.correct` for a class IV group: unknowns
    (y_a, y_c); drawn values numbers or one per design, the positions' last axis; ``sign``
    broadcasting against the positions."""
    shape = guess.shape[:-1]
    count = int(np.prod(shape))
    x = np.empty((count, 2))
    jac = np.empty((count, 2, 2))
    margin = np.empty(count)
    ok = np.empty(count, dtype=bool)
    wanted = np.ones(shape, dtype=bool)
    if mask is not None:
        wanted &= mask
    deflations, degree = group.form
    (arm_c, arm_d), (arm_f, arm_e) = group.arms
    _correct_kernel(
        np.array([_CODES[kind] for kind in group.kinds], dtype=np.int64),
        np.array(group.slides, dtype=np.int64), group.eliminated, group.linear_kept,
        deflations, degree, _UNITS, _HALF_UNITS, iterations, converged,
        per_position((k.h_a, k.h_c), shape, complex),
        per_position((k.u_a, k.u_c), shape, complex),
        per_position((group.coupler_length(0, k), group.coupler_length(1, k)), shape, float),
        per_design((group.u_a, group.u_c), shape, complex),
        per_design((arm_c, arm_d, arm_f, arm_e), shape, complex),
        per_design((group.w_c, group.w_d, group.w_f, group.w_e), shape, complex),
        per_design((np.asarray(group.c) - group.d, np.asarray(group.f) - group.e), shape,
                   complex),
        design(group.size, shape).astype(float), per_design(group.radii, shape, float),
        per_position((sign,), shape, float)[0],
        np.ascontiguousarray(guess, dtype=float).reshape(count, 2), wanted.reshape(-1),
        x, jac, margin, ok)
    return (x.reshape(shape + (2,)), jac.reshape(shape + (2, 2)), margin.reshape(shape),
            ok.reshape(shape))
