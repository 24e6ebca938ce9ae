"""The class IV group with hinged couplers solved by its own elimination: an oracle of the tests.

:class:`ClassIV` eliminates the hinge-only forms of the class IV group of order 2 differently
from the library's one solver (:class:`~assur.kinematics.higher.coupled.ClassIVCoupled`): in
the unknowns θ_a, θ_c (a hinged link's rotation), s (a sliding link's slide) or, with both
external pairs sliding, ψ and ρ of the coupler b, with the class IV eliminant written out for
each form (``docs/higher_groups.md`` §3.2). The tests compare the two on the forms both solve;
the continuation follows either (the same :class:`~assur.kinematics.higher.groups.HigherGroup`
interface).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.higher.groups import (
    ClassIVDrawing,
    ClassIVInputs,
    Unknowns,
    plain,
    plain_cross,
    plain_dot,
    present,
    unknown_columns,
)
from assur.typing import Value

__all__ = ["ClassIV"]


@dataclass(frozen=True, eq=False)
class ClassIV(ClassIVDrawing):
    """The class IV group of order 2: the contour a–b–c–d, external pairs on a and c.

    An external pair is a hinge, or a prismatic pair on a guide of the known link: then the
    link (a or c) turns with the known link and slides along its guide, and its unknown is
    the slide s from the drawing instead of its rotation θ (``docs/higher_groups.md`` §3.2
    of the note). With both pairs prismatic the unknowns are the rotation ψ of b from the
    sketch and the length ρ of C − D (the two slides follow linearly from C − D).

    Parameters
    ----------
    h_a, c, f, h_c, d, e, u_a, u_c
        The drawing (:class:`ClassIVDrawing`); C, D, E, F are hinges.

    Examples
    --------
    >>> g = ClassIV(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
    >>> g.degree, g.n
    (3, 2)
    >>> ClassIV(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j, u_c=1j).degree
    3
    """

    n = 2

    @property
    def eliminated(self) -> int:  # type: ignore[override]
        """θ_c (index 1) when only a slides, else index 0 (θ_a, or ψ of b when both slide)."""
        return 1 if self.slides == (True, False) else 0

    @property
    def lengths(self) -> tuple[bool, ...]:  # type: ignore[override]
        """(θ_a, θ_c), (θ_a, s_c), (s_a, θ_c) or (ψ, ρ)."""
        a, c = self.slides
        return (False, True) if a and c else (a, c)

    @property
    def degree(self) -> int:
        """3, or 1 when both external pairs slide (§3.2)."""
        return 1 if all(self.slides) else 3

    def drawn(self) -> np.ndarray:
        """Zero rotations and slides; (0, l_b) when both slide."""
        zero = np.zeros(np.shape(self.size))
        second = plain(self._arms()[4]) + zero if all(self.slides) else zero
        return np.stack(np.broadcast_arrays(zero, second), axis=-1)

    def _arms(self, k: ClassIVInputs | None = None
              ) -> tuple[Value, Value, Value, Value, Value, Value]:
        """γ_C, γ_F, δ_D, δ_E and the lengths l_b, l_d (drawn, or an actuator's from ``k``)."""
        g_c, g_f = np.asarray(self.c) - self.h_a, np.asarray(self.f) - self.h_a
        d_d, d_e = np.asarray(self.d) - self.h_c, np.asarray(self.e) - self.h_c
        l_b = np.abs(np.asarray(self.c) - self.d) if k is None or k.l_b is None else k.l_b
        l_d = np.abs(np.asarray(self.f) - self.e) if k is None or k.l_d is None else k.l_d
        return g_c, g_f, d_d, d_e, l_b, l_d

    def _turns(self, x: Sequence[Value], k: ClassIVInputs) -> tuple[Value, Value]:
        """E_a, E_c: e^{iθ} of a hinged link, u/u⁰ of a sliding one."""
        a, c = self.slides
        return (present(k.u_a) / present(self.u_a) if a else J.expi(x[0]),
                present(k.u_c) / present(self.u_c) if c else J.expi(x[1]))

    def _origins(self, x: Sequence[Value], k: ClassIVInputs, turns: tuple[Value, Value]
                 ) -> tuple[Value, Value]:
        """The points O_a, O_c of a and c drawn at H_a⁰, H_c⁰: H + s·u of a sliding link."""
        a, c = self.slides
        if not (a and c):
            return (k.h_a + x[0] * present(k.u_a) if a else k.h_a,
                    k.h_c + x[1] * present(k.u_c) if c else k.h_c)
        u_a, u_c = present(k.u_a), present(k.u_c)
        w = self._coupler(x) - self._rest(k, turns)[0]
        t = J.cross(u_c, w) / J.cross(u_c, u_a)
        s = J.cross(u_a, w) / J.cross(u_c, u_a)
        return k.h_a + t * u_a, k.h_c + s * u_c

    def _coupler(self, x: Sequence[Value]) -> Value:
        """C − D = ρ·e^{iψ}·(C⁰ − D⁰)/l_b (both external pairs sliding)."""
        drawn = np.asarray(self.c) - self.d
        return x[1] * J.expi(x[0]) * (drawn / np.abs(drawn))

    def _rest(self, k: ClassIVInputs, turns: tuple[Value, Value]) -> tuple[Value, Value]:
        """C̃ − D̃ and F̃ − Ẽ: the couplers' ends at zero slides (both pairs sliding)."""
        g_c, g_f, d_d, d_e, _, _ = self._arms(k)
        ea, ec = turns
        return (k.h_a + g_c * ea - k.h_c - d_d * ec, k.h_a + g_f * ea - k.h_c - d_e * ec)

    def _points(self, x: Unknowns, k: ClassIVInputs) -> tuple[Value, ...]:
        """C, F, D, E and the origins O_a, O_c."""
        cols = unknown_columns(x)
        g_c, g_f, d_d, d_e, _, _ = self._arms(k)
        turns = self._turns(cols, k)
        oa, oc = self._origins(cols, k, turns)
        ea, ec = turns
        return oa + g_c * ea, oa + g_f * ea, oc + d_d * ec, oc + d_e * ec, oa, oc

    def residual(self, x: Unknowns, k: ClassIVInputs) -> list[Value]:
        """g_b = (|C − D|² − l_b²)/(2l_b), g_d = (|F − E|² − l_d²)/(2l_d)."""
        c, f, d, e, _, _ = self._points(x, k)
        *_, lb, ld = self._arms(k)
        return [(J.dot(c - d, c - d) - lb * lb) / (2.0 * lb),
                (J.dot(f - e, f - e) - ld * ld) / (2.0 * ld)]

    def lines(self, x: np.ndarray, k: ClassIVInputs) -> tuple[np.ndarray, np.ndarray]:
        """The Jacobian and the margin rows.

        Row b holds ν_b·∂(C − D)/∂q, row d ν_d·∂(F − E)/∂q, ν the unit coupler directions: for
        a rotation ∂C/∂θ_a = i(C − O_a), for a slide ∂C/∂s_a = u_a (c likewise, with the
        opposite sign). The margin rows take these physical columns, a rotation's divided by
        the RMS radius of the link's internal hinges about its external pair (§3.2); with both
        pairs sliding the Jacobian's columns are those of ψ and ρ, ∂(C − D)/∂ψ = i(C − D),
        ∂(C − D)/∂ρ = (C − D)/ρ, the same for F − E.
        """
        c, f, d, e, oa, oc = (plain(p) for p in self._points(x, k))
        g_c, g_f, d_d, d_e, lb, ld = (plain(v) for v in self._arms(k))
        nb, nd = (c - d) / lb, (f - e) / ld
        a_slides, c_slides = self.slides
        radius_a = np.sqrt((np.abs(g_c) ** 2 + np.abs(g_f) ** 2) / 2.0)
        radius_c = np.sqrt((np.abs(d_d) ** 2 + np.abs(d_e) ** 2) / 2.0)
        columns = [((plain(present(k.u_a)),) * 2 if a_slides else (1j * (c - oa), 1j * (f - oa)),
                    radius_a),
                   ((-plain(present(k.u_c)),) * 2 if c_slides else (-1j * (d - oc), -1j * (e - oc)),
                    radius_c)]
        physical = _tangent_rows(nb, nd, [pair for pair, _ in columns])
        rows = _tangent_rows(nb, nd, [(pb / (1.0 if slide else r), pd / (1.0 if slide else r))
                                      for ((pb, pd), r), slide in zip(columns, self.slides,
                                                                       strict=True)])
        if not (a_slides and c_slides):
            return physical, rows
        coupler = c - d
        spin, stretch = 1j * coupler, coupler / np.abs(coupler)
        return _tangent_rows(nb, nd, [(spin, spin), (stretch, stretch)]), rows

    def _linear(self, e: np.ndarray, k: ClassIVInputs) -> tuple[Any, Any, Any, Any]:
        """α_b·E_c = π_b, α_d·E_c = π_d at E_a = e (§3.2)."""
        g_c, g_f, d_d, d_e, lb, ld = (plain(v) for v in self._arms(k))
        c = np.asarray(k.h_a) + g_c * e - k.h_c
        f = np.asarray(k.h_a) + g_f * e - k.h_c
        return (c * np.conj(d_d), (np.abs(c) ** 2 + np.abs(d_d) ** 2 - lb ** 2) / 2.0,
                f * np.conj(d_e), (np.abs(f) ** 2 + np.abs(d_e) ** 2 - ld ** 2) / 2.0)

    def _slider(self, e: np.ndarray, k: ClassIVInputs) -> tuple[Any, Any, Any]:
        """One pair sliding: V_b = X_b − Y_b, V_d = X_d − Y_d (X on the turning link at its
        rotation e, Y on the sliding one at zero slide, so that |V − s·u| = l) and u."""
        g_c, g_f, d_d, d_e, _, _ = self._arms(k)
        if self.slides[1]:
            ec = np.asarray(k.u_c) / self.u_c
            return (np.asarray(k.h_a) + g_c * e - k.h_c - d_d * ec,
                    np.asarray(k.h_a) + g_f * e - k.h_c - d_e * ec, np.asarray(k.u_c))
        ea = np.asarray(k.u_a) / self.u_a
        return (np.asarray(k.h_c) + d_d * e - k.h_a - g_c * ea,
                np.asarray(k.h_c) + d_e * e - k.h_a - g_f * ea, np.asarray(k.u_a))

    def _slide(self, e: np.ndarray, k: ClassIVInputs) -> tuple[Any, Any, Any]:
        """s = N/Σ from the difference of the two circle equations, and N, Σ, with
        N = (|X_d − Y_d|² − l_d²) − (|X_b − Y_b|² − l_b²), Σ = 2u·((X_d − Y_d) − (X_b − Y_b))."""
        vb, vd, u = self._slider(e, k)
        lb, ld = (plain(v) for v in self._arms(k)[4:])
        n = (np.abs(vd) ** 2 - ld ** 2) - (np.abs(vb) ** 2 - lb ** 2)
        sigma = 2.0 * plain_dot(u, vd - vb)
        return n / sigma, n, sigma

    def eliminant(self, e: np.ndarray, k: ClassIVInputs) -> np.ndarray:
        """Φ_IV(θ_a) = |π_bα_d − π_dα_b|² − cross(α_b, α_d)²; one pair sliding
        Φ = N² − 2NΣ u·(X_b − Y_b) + Σ²(|X_b − Y_b|² − l_b²) in the turning link's rotation;
        both sliding |(F̃ − Ẽ) − (C̃ − D̃) + (C − D)|² − l_d² in ψ, C − D at ρ = l_b."""
        a_slides, c_slides = self.slides
        if a_slides and c_slides:
            lb, ld = (plain(v) for v in self._arms(k)[4:])
            b_rest, d_rest = self._rest(k, (plain(present(k.u_a)) / plain(present(self.u_a)),
                                            plain(present(k.u_c)) / plain(present(self.u_c))))
            gap = plain(d_rest - b_rest + self._coupler([np.angle(e), lb]))
            return np.asarray(np.abs(gap) ** 2 - ld ** 2)
        if a_slides or c_slides:
            vb, _, u = self._slider(e, k)
            _, n, sigma = self._slide(e, k)
            lb = plain(self._arms(k)[4])
            return np.asarray(n * n - 2.0 * n * sigma * plain_dot(u, vb)
                              + sigma * sigma * (np.abs(vb) ** 2 - lb ** 2))
        ab, pb, ad, pd = self._linear(e, k)
        return np.asarray(np.abs(pb * ad - pd * ab) ** 2 - plain_cross(ab, ad) ** 2)

    def recover(self, e: np.ndarray, k: ClassIVInputs) -> np.ndarray:
        """θ_a = arg E_a, θ_c = arg E_c with E_c = −i(π_bα_d − π_dα_b)/cross(α_b, α_d); one
        pair sliding the turning link's arg e and s = N/Σ; both (ψ, ρ) = (arg e, l_b)."""
        a_slides, c_slides = self.slides
        if a_slides and c_slides:
            return np.stack(np.broadcast_arrays(np.angle(e), plain(self._arms(k)[4])), axis=-1)
        if a_slides or c_slides:
            s = self._slide(e, k)[0]
            pair = (s, np.angle(e)) if a_slides else (np.angle(e), s)
            return np.stack(np.broadcast_arrays(*pair), axis=-1)
        ab, pb, ad, pd = self._linear(e, k)
        ec = -1j * (pb * ad - pd * ab) / plain_cross(ab, ad)
        return np.stack(np.broadcast_arrays(np.angle(e), np.angle(ec)), axis=-1)

    def joints(self, x: Unknowns, k: ClassIVInputs) -> dict[str, Value]:
        """C, D, E, F, and Ha, Hc: the points of a and c drawn at their external pairs (the
        external hinges, or the sliding points of prismatic pairs)."""
        c, f, d, e, oa, oc = self._points(x, k)
        return {"C": c, "D": d, "E": e, "F": f, "Ha": oa, "Hc": oc}

    def rotations(self, x: Unknowns, k: ClassIVInputs) -> dict[str, Value]:
        """a, c: θ_a, θ_c (of a sliding link, the known link's rotation u/u⁰); b: of C→D; d:
        of F→E; all from the sketch."""
        cols = unknown_columns(x)
        c, f, d, e, _, _ = self._points(cols, k)
        a_slides, c_slides = self.slides
        return {"a": J.arg(present(k.u_a) / present(self.u_a)) if a_slides else cols[0],
                "b": J.arg((d - c) / (np.asarray(self.d) - self.c)),
                "c": J.arg(present(k.u_c) / present(self.u_c)) if c_slides else cols[1],
                "d": J.arg((e - f) / (np.asarray(self.e) - self.f))}


def _tangent_rows(nb: np.ndarray, nd: np.ndarray, columns: list[tuple[Any, Any]]
                  ) -> np.ndarray:
    """The 2×2 matrix [[ν_b·t_bj], [ν_d·t_dj]] of the columns j = (t_bj, t_dj)."""
    return np.stack([np.stack(np.broadcast_arrays(*(plain_dot(nb, tb) for tb, _ in columns)), axis=-1),
                     np.stack(np.broadcast_arrays(*(plain_dot(nd, td) for _, td in columns)), axis=-1)],
                    axis=-2)
