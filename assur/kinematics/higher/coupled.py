"""The class IV group of order 2 with prismatic internal pairs (``docs/higher_groups.md`` §2).

One code path solves every form of the contour a–b–c–d: each external pair (H_a on a, H_c on
c) a hinge or a prismatic pair on a known link's guide, each coupler (b between a and c at C,
D; d at F, E) a bar (RR), a block turning with a (PR: C prismatic), with c (RP: D
prismatic) or with both (PP).

The unknowns are two angles y_a, y_c: a hinged link's rotation θ from the sketch, a sliding
link's lifted slide t with s = L·tan(t/2) (L the group's size). Multiplied by cos²(t/2) of
each sliding link it involves, every loop equation F̂_j is trigonometrically linear in y_a
and in y_c separately (span{1, cos y, sin y}): a raw equation is at most quadratic in a slide
s with a constant s² coefficient and bilinear in E_a, E_c, and s²cos²(t/2) = L²(1 − cos t)/2,
s·cos²(t/2) = L·sin t/2, cos²(t/2) = (1 + cos t)/2. So F̂_j = 0 is Re(ᾱ_j E_o) = π_j in the
kept unknown o at a fixed eliminated one ε, and the eliminant of the two lines is the class
IV form Φ = |π_bα_d − π_dα_b|² − cross(α_b, α_d)², of degree at most 4 in y_ε.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields
from functools import cached_property
from weakref import WeakKeyDictionary

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.higher.groups import (
    ClassIVDrawing,
    ClassIVInputs,
    Leash,
    Unknowns,
    plain,
    plain_cross,
    plain_dot,
    present,
    unknown_columns,
)
from assur.text import render
from assur.typing import Value

__all__ = ["ClassIVCoupled"]

#: Two drawn directions whose cross product is at most this are parallel.
PARALLEL = 1e-9
#: The degree of Φ before deflation.
FULL_DEGREE = 4
#: Φ sampled at these points (not at −1) gives its coefficients: SPLIT[n] · Φ(GRID) = φ_{n−4}.
GRID = np.exp(1j * np.pi * (2 * np.arange(2 * FULL_DEGREE + 2) + 1) / (2 * FULL_DEGREE + 2))
SPLIT = GRID[None, :] ** -np.arange(-FULL_DEGREE, FULL_DEGREE + 1)[:, None] / GRID.size


def _unit_halves(e: np.ndarray) -> np.ndarray:
    """w(y) = ((1 + cos y)/2, sin y/2, (1 − cos y)/2) on a last axis, y = arg e."""
    unit = e / np.abs(e)
    return np.stack(np.broadcast_arrays(0.5 + 0.5 * unit.real, 0.5 * unit.imag,
                                        0.5 - 0.5 * unit.real), axis=-1)


#: w(y) at the samples ``GRID``.
GRID_HALVES = _unit_halves(GRID)
#: A coefficient of Φ at most this times the largest vanishes for the form.
VANISH = 1e-10


#: The unknown's samples 0, π/2, π, and the map from a loop equation's values there to its
#: coefficients of w(y) = (κ², κσ, σ²), κ = cos(y/2), σ = sin(y/2): F(0), 2F(π/2) − F(0) − F(π),
#: F(π). Half angles keep the lifting factor κ² exact near y = π (a slide far out).
SAMPLES = np.array([0.0, 0.5 * np.pi, np.pi])
FROM_SAMPLES = np.array([[1.0, 0.0, 0.0], [-1.0, 2.0, -1.0], [0.0, 0.0, 1.0]])


#: (p, m) of each form (couplers' kinds, slides, ε) once read (see ClassIVCoupled.form).
_FORMS: dict[tuple[tuple[Leash, Leash], tuple[bool, bool], int], tuple[int, int]] = {}


def _everywhere(holds: np.ndarray, values: np.ndarray) -> bool:
    """Whether ``holds`` on every design where ``values`` is finite."""
    return bool(np.all(holds | ~np.isfinite(values)))


def _deflate(series: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The quotient and the remainder of the polynomials (increasing powers) by E + 1."""
    n = series.shape[-1] - 1
    quotient = np.empty(series.shape[:-1] + (n,), dtype=complex)
    carry = series[..., n]
    for i in range(n - 1, -1, -1):
        quotient[..., i] = carry
        carry = series[..., i] - carry
    return quotient, carry


def _halves_turning(y: np.ndarray) -> np.ndarray:
    """w(y) = (κ², κσ, σ²) (κ = cos(y/2), σ = sin(y/2)) and w′(y) = (−κσ, (κ² − σ²)/2, κσ)
    of plain angles, on a last axis, the two stacked on a leading one."""
    k, s = np.cos(0.5 * y), np.sin(0.5 * y)
    out = np.empty((2,) + np.shape(y) + (3,))
    w, turning = out
    np.multiply(k, k, out=w[..., 0])
    np.multiply(k, s, out=w[..., 1])
    np.multiply(s, s, out=w[..., 2])
    np.negative(w[..., 1], out=turning[..., 0])
    turning[..., 2] = w[..., 1]
    np.subtract(w[..., 0], w[..., 2], out=turning[..., 1])
    turning[..., 1] *= 0.5
    return out


#: Up to this many positions and designs the form and its Jacobian are one contraction.
FEW = 256
#: w, w′, w of y_a against w, w, w′ of y_c: the form and its two partial derivatives.
_SIDES = (np.array([0, 1, 0]), np.array([0, 0, 1]))


def _times(weight: Value, v: Value) -> Value:
    """weight·v, v itself for the weight 1.0 of a hinged link."""
    return v if isinstance(weight, float) and weight == 1.0 else weight * v


def _square(v: Value) -> Value:
    """|v|² of a complex array or jet (the terms of the product rule as in ``J.dot(v, v)``)."""
    if not isinstance(v, J.Jet):
        return J.dot(v, v)
    square = (np.conj(v.v) * v.v).real
    first = (np.conj(v.v) * v.d1).real
    second = (np.conj(v.v) * v.d2).real
    return J.Jet(square, first + first, second + 2.0 * (np.conj(v.d1) * v.d1).real + second)


@dataclass(frozen=True)
class _Link:
    """A link a or c at one pose: its turn E, the weight κ (cos(t/2) of a sliding link, 1 of
    a hinged one), κ·O, O its point drawn at the external pair, and κ·E."""

    turn: Value
    weight: Value
    origin: Value
    carried: Value

    def reach(self, arm: Value) -> Value:
        """κ times the point of the link drawn at ``arm`` from its external pair."""
        return self.origin + self.carried * arm


@dataclass(frozen=True, eq=False)
class ClassIVCoupled(ClassIVDrawing):
    """The class IV group of order 2 with any internal and external pairs.

    Parameters
    ----------
    h_a, c, f, h_c, d, e, u_a, u_c
        The drawing (:class:`ClassIVDrawing`).
    w_c, w_d, w_e, w_f : complex or None
        The drawn unit direction of the guide of a prismatic internal pair C, D, E, F; None: a
        hinge. The guide may be carried by either link of the pair: the equation is the same.

    Notes
    -----
    The eliminated unknown ε is chosen from the drawn data: the kept one must enter both
    equations (a PP coupler does not involve a slide, a prismatic coupler does not involve a
    slide parallel to its guide). :attr:`determinate` is False where no choice works (both
    external pairs sliding with a PP coupler, a PP coupler with parallel guides, a coupler
    guide parallel to the slide it would have to fix); two PP couplers are refused.

    Examples
    --------
    >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j, w_c=1)
    >>> g.kinds, g.degree, g.determinate, g.eliminated
    ((<Leash.PR: 'PR'>, <Leash.RR: 'RR'>), 3, True, 0)
    """

    w_c: Value | None = None
    w_d: Value | None = None
    w_e: Value | None = None
    w_f: Value | None = None

    n = 2
    lengths = (False, False)

    def __post_init__(self) -> None:
        if self.kinds == (Leash.PP, Leash.PP):
            raise ValueError(render("higher.coupled.two_pp"))

    # --- form -----------------------------------------------------------------------------

    @cached_property
    def kinds(self) -> tuple[Leash, Leash]:
        """The forms of b (pairs C, D) and d (pairs F, E), the pair on a first."""
        return (Leash.of(self.w_c is not None, self.w_d is not None),
                Leash.of(self.w_f is not None, self.w_e is not None))

    def _guides(self, j: int) -> tuple[Value | None, Value | None]:
        """The guides of coupler j (0: b, 1: d), the pair on a first."""
        return (self.w_c, self.w_d) if j == 0 else (self.w_f, self.w_e)

    def _depends(self, j: int, link: int) -> bool:
        """Whether coupler j's equation involves the unknown of link (0: a, 1: c)."""
        kind = self.kinds[j]
        if not self.slides[link]:
            return True
        if kind is Leash.PP:
            return False
        u = (self.u_a, self.u_c)[link]
        return not any(w is not None and bool(np.any(np.abs(plain_cross(w, u)) <= PARALLEL))
                       for w in self._guides(j))

    @cached_property
    def _choice(self) -> int | None:
        """ε: a (0) or c (1) such that the other enters both equations and ε one, a rotation
        rather than a slide where both would do; None."""
        for eps in sorted((0, 1), key=lambda i: self.slides[i]):
            keep = 1 - eps
            if all(self._depends(j, keep) for j in (0, 1)) and any(
                    self._depends(j, eps) for j in (0, 1)):
                return eps
        return None

    @property
    def linear_kept(self) -> bool:
        """Whether both equations are linear in the kept unknown, a slide (both couplers PR
        or RP): lifted, both then vanish at y_o = π (s = ∞) for every ε, so Φ ≡ 0, and the
        eliminant is the resultant of the two lines instead (:meth:`_full`)."""
        return self.slides[1 - self.eliminated] and all(kind.block for kind in self.kinds)

    @property
    def determinate(self) -> bool:
        """Whether the drawn form fixes the group: an elimination exists, no PP coupler
        slides along parallel guides."""
        parallel = any(kind is Leash.PP and bool(np.any(np.abs(plain_cross(*self._guides(j)))
                                                     <= PARALLEL))
                       for j, kind in enumerate(self.kinds))
        return self._choice is not None and not parallel

    @property
    def eliminated(self) -> int:  # type: ignore[override]
        """The index of ε (y_a: 0, y_c: 1)."""
        return 0 if self._choice is None else self._choice

    @property
    def degree(self) -> int:
        """The degree m of the deflated eliminant Φ̃ (see :meth:`eliminant`)."""
        return self.form[1]

    @property
    def form(self) -> tuple[int, int]:
        """The multiplicity p of the root e = −1 that Φ has on every design and input, and
        the degree of Φ̃: both structural, read once per form off Φ at generic inputs."""
        key = (self.kinds, self.slides, self.eliminated)
        if key not in _FORMS:
            _FORMS[key] = self._probe()
        return _FORMS[key]

    def _probe(self) -> tuple[int, int]:
        """(p, m) of this group's Φ at generic inputs (designs where Φ is undefined aside)."""
        turn = np.exp(0.4j)
        size = self.size
        probe = ClassIVInputs(self.h_a + 0.1 * size * np.exp(0.7j),
                              self.h_c - 0.13 * size * np.exp(0.3j),
                              None if self.u_a is None else self.u_a * turn,
                              None if self.u_c is None else self.u_c / turn)
        with np.errstate(all="ignore"):
            series = self._series(probe, True)
        p = 0
        while p < FULL_DEGREE * 2:
            quotient, rest = _deflate(series)
            if not _everywhere(np.abs(rest) <= VANISH * np.abs(series).max(axis=-1), rest):
                break
            series, p = quotient, p + 1
        top = np.abs(series).max(axis=-1)
        half = FULL_DEGREE - p // 2
        vanish = [_everywhere(np.abs(series[..., -1 - n]) <= VANISH * top, top)
                  for n in range(half)]
        return p, half - (vanish.index(False) if False in vanish else half)

    def drawn(self) -> np.ndarray:
        """Zero rotations and slides."""
        zero = np.zeros(np.shape(self.size))
        return np.stack([zero, zero], axis=-1)

    # --- poses ----------------------------------------------------------------------------

    def _links(self, y: Sequence[Value], k: ClassIVInputs) -> tuple[_Link, _Link]:
        """a and c at the unknowns y (angles; plain arrays or jets)."""
        def link(angle: Value, h: Value, u: Value | None, drawn: Value | None) -> _Link:
            if drawn is None or u is None:
                unit = J.expi(angle)
                return _Link(unit, 1.0, h, unit)
            half = J.expi(0.5 * angle)
            weight = J.real(half)
            turn = u / drawn
            return _Link(turn, weight, weight * h + self.size * J.imag(half) * u, weight * turn)
        return (link(y[0], k.h_a, k.u_a, self.u_a), link(y[1], k.h_c, k.u_c, self.u_c))

    def _lifted(self, y: Sequence[Value], k: ClassIVInputs) -> list[Value]:
        """F̂_b, F̂_d at the unknowns y (the loop equations times their lifting factors)."""
        return self._loops(*self._links(y, k), k)

    def _loops(self, a: _Link, c: _Link, k: ClassIVInputs) -> list[Value]:
        """F̂_b, F̂_d of the links a and c at a pose (:meth:`_lifted`)."""
        both = a.weight * a.weight * c.weight * c.weight
        out: list[Value] = []
        for j, ((first, second), (arm_a, arm_c), kind, (wa, wc)) in enumerate(zip(
                ((self.c, self.d), (self.f, self.e)), self.arms, self.kinds,
                (self._guides(0), self._guides(1)), strict=True)):
            pa = a.reach(arm_a)     # κ_a·(the point of a at the pair on a)
            pc = c.reach(arm_c)     # κ_c·(the point of c at the pair on c)
            gap = _times(c.weight, pa) - _times(a.weight, pc)  # κ_aκ_c·(that on a − on c)
            drawn = np.asarray(first) - second
            if kind is Leash.RR:  # a bar: its drawn length, or an actuator's from the inputs
                length = self.coupler_length(j, k)
                out.append(_square(gap) - length * length * both)
            elif kind is Leash.PP:
                out.append(J.cross(a.turn, c.turn))
            else:
                turn, w = (a.turn, wa) if kind is Leash.PR else (c.turn, wc)
                offset = plain_cross(w, drawn)
                out.append(a.weight * c.weight * J.cross(turn * present(w), gap)
                           - offset * both)
        return out

    def coupler_length(self, j: int, k: ClassIVInputs) -> Value:
        """The length of bar j (0: b, 1: d): drawn, or an actuator's from the inputs."""
        given = k.l_b if j == 0 else k.l_d
        return self._drawn_lengths[j] if given is None else given

    @cached_property
    def _drawn_lengths(self) -> tuple[np.ndarray, np.ndarray]:
        """|C − D| and |F − E| as drawn."""
        return (np.abs(np.asarray(J.value(self.c)) - J.value(self.d)),
                np.abs(np.asarray(J.value(self.f)) - J.value(self.e)))

    @cached_property
    def arms(self) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """C − H_a, D − H_c (coupler b) and F − H_a, E − H_c (coupler d) as drawn."""
        return ((np.asarray(self.c) - self.h_a, np.asarray(self.d) - self.h_c),
                (np.asarray(self.f) - self.h_a, np.asarray(self.e) - self.h_c))

    def __getstate__(self) -> dict[str, object]:
        """The record without the fitted matrices of :meth:`_matrices` (weak references do
        not pickle; they are fitted again on demand)."""
        return {name: value for name, value in self.__dict__.items() if name != "_memo"}

    @cached_property
    def _memo(self) -> WeakKeyDictionary[ClassIVInputs, np.ndarray]:
        """The matrices of :meth:`_matrices` of the inputs records at hand."""
        return WeakKeyDictionary()

    def _matrices(self, k: ClassIVInputs) -> np.ndarray:
        """M_j, shape (..., 2, 3, 3): scale_j·F̂_j = Σ_pq w(y_a)_p·M_jpq·w(y_c)_q
        (w(y) = (κ², κσ, σ²), :func:`_halves_turning`), scale_j that of the natural residual
        (:meth:`_scales`).

        F̂_j is trigonometrically linear in y_a and in y_c separately (a quadratic form in
        (κ, σ) of each), so its values at y_a, y_c ∈ {0, π/2, π} give M_j, once per inputs
        record; the Jacobian, the eliminant and the recovery are contractions of M (a
        positive factor per equation moves no root of Φ). Plain inputs only (no jets).
        """
        memo = self._memo
        if k not in memo:
            depth = max([self._depth] + [np.ndim(J.value(v)) for v in vars(k).values()
                                         if v is not None])
            tail = (1,) * depth
            lifted = [f * scale for f, scale in zip(
                self._lifted([SAMPLES.reshape((3, 1) + tail), SAMPLES.reshape((1, 3) + tail)],
                             k), self._scales(k), strict=True)]
            samples = np.stack(np.broadcast_arrays(
                *(plain(f) for f in lifted), np.ones((3, 3) + tail)))[:-1]
            memo[k] = np.einsum("pa,jab...,qb->...jpq", FROM_SAMPLES, samples, FROM_SAMPLES)
        return memo[k]

    @cached_property
    def _depth(self) -> int:
        """The number of axes of the drawing's values (designs)."""
        return max(np.ndim(J.value(getattr(self, f.name))) for f in fields(self)
                   if getattr(self, f.name) is not None)

    def _scales(self, k: ClassIVInputs) -> list[Value]:
        """Per coupler, the natural residual's scale: 1/(2l) of a bar, L of a PP coupler, 1."""
        return [0.5 / self.coupler_length(j, k) if kind is Leash.RR else self.size
                if kind is Leash.PP else 1.0 for j, kind in enumerate(self.kinds)]

    def residual(self, x: Unknowns, k: ClassIVInputs) -> list[Value]:
        """g_b, g_d: RR (|C − D|² − l²)/(2l), PR/RP the offset of the hinge from the guide
        minus its drawn value, PP L·sin(θ_a − θ_c) (rotations of a sliding link its guide's).

        Straight from the loop equations at x (:meth:`_loops`), not from the fitted matrices:
        with jets of the inputs (the analogs) that fit would be needed once only."""
        a, c = self._links(unknown_columns(x), k)
        lift = a.weight * a.weight * c.weight * c.weight
        hinged = isinstance(lift, float) and lift == 1.0
        return [f * scale if kind is Leash.PP or hinged else f * scale / lift
                for f, scale, kind in zip(self._loops(a, c, k), self._scales(k), self.kinds,
                                          strict=True)]

    def lines(self, x: np.ndarray, k: ClassIVInputs) -> tuple[np.ndarray, np.ndarray]:
        """The Jacobian in (y_a, y_c) and the margin rows in physical columns.

        ∂g_j/∂y = scale_j·(∂F̂_j/∂y − F̂_j·∂lift_j/∂y/lift_j)/lift_j, ∂F̂_j/∂y from M and
        w′(y). A rotation's column is divided by the RMS radius of the
        link's internal pairs about its external pair, a slide's is ∂/∂s = ∂/∂t·2L/(L² + s²).
        """
        ya, yc = unknown_columns(x)
        jac = self.equations(x, k)[1]
        scales = []
        for y, slides, radius in zip((ya, yc), self.slides, self.radii, strict=True):
            if slides:
                s = self.size * np.tan(0.5 * plain(y))
                scales.append(2.0 * self.size / (self.size ** 2 + s * s))
            else:
                scales.append(1.0 / radius)
        rows = jac * np.stack(np.broadcast_arrays(*scales), axis=-1)[..., None, :]
        return jac, rows

    @cached_property
    def radii(self) -> tuple[np.ndarray, np.ndarray]:
        """The RMS radius of the internal pairs of a, of c, about its external pair."""
        return tuple(np.sqrt((np.abs(np.asarray(p) - h) ** 2 + np.abs(np.asarray(q) - h) ** 2)
                             / 2.0) for (p, q), h in zip(((self.c, self.f), (self.d, self.e)),
                                                         (self.h_a, self.h_c), strict=True))

    def equations(self, x: np.ndarray, k: ClassIVInputs) -> tuple[np.ndarray, np.ndarray]:
        """g (..., 2) and the Jacobian in (y_a, y_c), from one evaluation of w(y_a), w(y_c):
        ∂g_j/∂y = (∂(scale_j·F̂_j)/∂y − g_j·∂lift_j/∂y)/lift_j, the first from M and w′(y)."""
        m = self._matrices(k)
        halves = _halves_turning(np.asarray(x, dtype=float))
        wa, wc = halves[0, ..., 0, :], halves[0, ..., 1, :]
        if m[..., 0, 0, 0].size <= FEW:  # one contraction: the fewest calls
            f = np.einsum("n...p,...jpq,n...q->...jn", halves[_SIDES[0], ..., 0, :], m,
                          halves[_SIDES[1], ..., 1, :])
            g, jac = f[..., 0], f[..., 1:]
        else:  # M·w(y_c) and M·w′(y_c) once, then the three sides: the fewest operations
            mc = np.einsum("...jpq,n...q->n...jp", m, halves[:, ..., 1, :])
            g = np.einsum("...jp,...p->...j", mc[0], wa)
            jac = np.empty(g.shape + (2,))
            np.einsum("...jp,...p->...j", mc[0], halves[1, ..., 0, :], out=jac[..., 0])
            np.einsum("...jp,...p->...j", mc[1], wa, out=jac[..., 1])
        if not any(self.slides):
            return g, jac
        (qa, da), (qc, dc) = ((w[..., 0], -w[..., 1]) if slides else (1.0, 0.0)
                              for w, slides in zip((wa, wc), self.slides, strict=True))
        pp = self._pp
        lift = np.where(pp, 1.0, np.asarray(qa * qc)[..., None])
        slopes = np.stack(np.broadcast_arrays(np.where(pp, 0.0, np.asarray(da * qc)[..., None]),
                                              np.where(pp, 0.0, np.asarray(qa * dc)[..., None])),
                          axis=-1)
        g = g / lift
        return g, (jac - g[..., None] * slopes) / lift[..., None]

    @cached_property
    def _pp(self) -> np.ndarray:
        """Which coupler is PP (its equation has no lifting factor)."""
        return np.array([kind is Leash.PP for kind in self.kinds])

    # --- elimination ----------------------------------------------------------------------

    def _linear(self, w: np.ndarray, k: ClassIVInputs, spread: bool = False
                ) -> list[tuple[np.ndarray, np.ndarray]]:
        """α_j, π_j of Re(ᾱ_j E_o) = π_j at y_ε, w = w(y_ε) (:func:`_unit_halves`): the
        coefficients (d₀, d₁, d₂) of F̂_j in w(y_o) are M_j contracted with w(y_ε); with
        κ² = (1 + cos)/2, κσ = sin/2, σ² = (1 − cos)/2, α_j = (d₀ − d₂ + i·d₁)/2 and
        π_j = −(d₀ + d₂)/2. With ``spread`` the samples lie on a new axis before the last
        (group and inputs not expanded)."""
        spec = "...p,...jpq->...jq" if self.eliminated == 0 else "...q,...jpq->...jp"
        m = self._matrices(k)
        d = np.einsum(spec, w, m[..., None, :, :, :] if spread else m)
        alpha = 0.5 * (d[..., 0] - d[..., 2] + 1j * d[..., 1])
        pi = -0.5 * (d[..., 0] + d[..., 2])
        return [(alpha[..., 0], pi[..., 0]), (alpha[..., 1], pi[..., 1])]

    def _full(self, k: ClassIVInputs, spread: bool = False) -> np.ndarray:
        """Φ(y_ε) = |π_bα_d − π_dα_b|² − cross(α_b, α_d)² at y_ε = arg e, e ∈ ``GRID``.

        Where both equations are linear in the kept slide s_o (:attr:`linear_kept`), each
        is A_j·s_o + B_j = 0, lifted α_j = B_j/2 + i·L·A_j/2 and π_j = −Re α_j: then Φ ≡ 0
        (the common root y_o = π), and Φ is the resultant A_b·B_d − A_d·B_b ∝ cross(α_b, α_d)
        instead, of degree at most 2.
        """
        (ab, pb), (ad, pd) = self._linear(GRID_HALVES, k, spread)
        if self.linear_kept:
            return np.asarray(plain_cross(ab, ad))
        return np.asarray(np.abs(pb * ad - pd * ab) ** 2 - plain_cross(ab, ad) ** 2)

    def _series(self, k: ClassIVInputs, spread: bool) -> np.ndarray:
        """Coefficients of E⁴Φ (increasing powers, shape (..., 9)) from Φ sampled off −1
        (with ``spread`` on group and inputs as given, else on both expanded)."""
        return np.asarray(np.einsum("...k,nk->...n", self._full(k, spread), SPLIT))

    def _kept(self, series: np.ndarray) -> np.ndarray:
        """The coefficients φ₋ₘ … φₘ of Φ̃ from those of E⁴Φ (see :meth:`eliminant`)."""
        p, m = self.form
        for _ in range(p):
            series = _deflate(series)[0]
        half = FULL_DEGREE - p // 2
        return np.asarray(series[..., half - m:half + m + 1] * 2.0 ** p)

    def coefficients(self, k: ClassIVInputs) -> np.ndarray:
        """The coefficients of p(E) = E^m·Φ̃ straight from the fitted matrices (no samples of
        :meth:`eliminant`)."""
        return self._kept(self._series(k, True))

    def eliminant(self, e: np.ndarray, k: ClassIVInputs) -> np.ndarray:
        """Φ̃ = Φ/((1 + cos y_ε)/2)^{p/2} at e (group and inputs expanded).

        With ε a lifted slide, Φ vanishes to an even order p at y_ε = π (s = ∞) for every
        input (all α_j vanish there, or both lines coincide); that root is no pose, and
        divided out, as are the top coefficients that vanish for the form.
        """
        m = self.form[1]
        powers = np.arange(-m, m + 1)
        kept = self._kept(self._series(k, False))
        return np.asarray(np.einsum("...n,...kn->...k", kept,
                                    np.asarray(e)[..., None] ** powers).real)

    def recover(self, e: np.ndarray, k: ClassIVInputs) -> np.ndarray:
        """y_ε = arg e, y_o = arg E_o with E_o = −i(π_bα_d − π_dα_b)/cross(α_b, α_d) (−α/ᾱ of
        the larger α where both equations are linear in the kept slide); NaN where a PP
        coupler would be turned by π from one of its links."""
        (ab, pb), (ad, pd) = self._linear(_unit_halves(e), k)
        if self.linear_kept:  # s_o = −L·Re α/Im α of either line: E_o = −α/ᾱ
            alpha = np.where(np.abs(ab) >= np.abs(ad), ab, ad)
            other = np.angle(-alpha / np.conj(alpha))
        else:
            other = np.angle(-1j * (pb * ad - pd * ab) / plain_cross(ab, ad))
        pair = [np.angle(e), other] if self.eliminated == 0 else [other, np.angle(e)]
        x = np.stack(np.broadcast_arrays(*pair), axis=-1)
        if Leash.PP in self.kinds:
            a, c = self._links(unknown_columns(x), k)
            x = np.where((plain_dot(a.turn, c.turn) > 0.0)[..., None], x, np.nan)
        return x

    # --- results --------------------------------------------------------------------------

    def _points(self, x: Unknowns, k: ClassIVInputs) -> dict[str, Value]:
        a, c = self._links(unknown_columns(x), k)
        out = {"Ha": a.origin / a.weight, "Hc": c.origin / c.weight}
        for j, ((p, q), (on_a, on_c)) in enumerate(zip((("C", "D"), ("F", "E")),
                                                       (("Ca", "Dc"), ("Fa", "Ec")), strict=True)):
            first, second = getattr(self, p.lower()), getattr(self, q.lower())
            arm_a, arm_c = self.arms[j]
            pa, pc = a.reach(arm_a) / a.weight, c.reach(arm_c) / c.weight
            drawn = np.asarray(second) - first
            kind = self.kinds[j]
            wa, wc = self._guides(j)
            if kind is Leash.RR:
                ends = (pa, pc)
            elif kind is Leash.PR:
                ends = (pc - a.turn * drawn, pc)
            elif kind is Leash.RP:
                ends = (pa, pa + c.turn * drawn)
            else:
                rest = J.conj(a.turn) * (pc - pa) - drawn
                start = pa + J.cross(rest, present(wc)) / plain_cross(wa, wc) * a.turn * present(wa)
                ends = (start, start + a.turn * drawn)
            out.update({p: ends[0], q: ends[1], on_a: pa, on_c: pc})
        return out

    def joints(self, x: Unknowns, k: ClassIVInputs) -> dict[str, Value]:
        """C, D (of b), F, E (of d) drawn at the pairs; Ca, Fa of a; Dc, Ec of c (equal to
        the coupler's at a hinge); Ha, Hc: the points of a and c at their external pairs."""
        return self._points(x, k)

    def rotations(self, x: Unknowns, k: ClassIVInputs) -> dict[str, Value]:
        """a, c: θ (of a sliding link its guide's turn); b, d: of the coupler (a prismatic
        coupler turns with the link carrying its guide pair); all from the sketch."""
        cols = unknown_columns(x)
        a, c = self._links(cols, k)
        p = self._points(cols, k)
        turn_a, turn_c = (J.arg(link.turn) if slides else y
                          for link, slides, y in zip((a, c), self.slides, cols, strict=True))
        return {"a": turn_a, "c": turn_c,
                "b": J.arg((p["D"] - p["C"]) / (np.asarray(self.d) - self.c)),
                "d": J.arg((p["E"] - p["F"]) / (np.asarray(self.e) - self.f))}
