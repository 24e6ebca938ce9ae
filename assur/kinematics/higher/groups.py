"""Geometry and equations of the triad (class III) and the class IV group of order 2.

Each group is a frozen record of its drawn (sketch) geometry. Its methods give the reduced
loop equations F(x) = 0 and their Jacobian, the constraint lines that fix the margin, the
eliminant Φ(θ) and the coefficients of p(E) = E^m·Φ, the recovery of the other unknowns from
θ, and the joints and link rotations of a solution (``docs/higher_groups.md`` §1–§3).

Points are complex numbers; every drawn value may be a number or an array of shape (D,)
(D candidate designs). The inputs at a crank position (the external hinges and guides carried
by known links) come as :class:`TriadInputs` or :class:`ClassIVInputs`, numbers, arrays or
:class:`~assur.kinematics.jets.Jet`. The residuals accept jets, so that the analogs follow by
implicit differentiation; the Jacobians, the lines and the eliminant take plain arrays.
"""

from __future__ import annotations

import dataclasses
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum
from functools import cached_property
from typing import Any, Generic, TypeVar

import numpy as np

from assur.kinematics import jets as J
from assur.text import render
from assur.typing import Value

__all__ = [
    "AnyGroup", "ClassIVDrawing", "ClassIVInputs", "HigherGroup", "K", "Leash", "Triad",
    "TriadInputs", "Value", "expand", "plain", "present", "values",
]

#: The unknowns: an ndarray (..., n) or a sequence of n values (jets for the analogs).
Unknowns = Sequence[Value] | np.ndarray


class Leash(str, Enum):
    """The form of a triad's leash or of a class IV group's coupler, by its two pairs.

    A triad's leash names its internal pair (on the base) first: RR a bar, RP a block hinged
    to the base on a guide of a known link, PR a leash hinged to a known link sliding along a
    guide of the base, PP a leash sliding on both (its guides fix the base's rotation to the
    known link's). A class IV coupler names its pair on a first (C or F), then on c (D or E).

    Examples
    --------
    >>> Leash.of(False, True), Leash.RP.bar, Leash.RP.slides
    (<Leash.RP: 'RP'>, False, (False, True))
    """

    RR = "RR"
    RP = "RP"
    PR = "PR"
    PP = "PP"

    @classmethod
    def of(cls, first: bool, second: bool) -> Leash:
        """The form whose first (second) pair is prismatic where ``first`` (``second``)."""
        return cls(("P" if first else "R") + ("P" if second else "R"))

    @property
    def slides(self) -> tuple[bool, bool]:
        """Whether its first, its second pair is prismatic."""
        return self[0] == "P", self[1] == "P"

    @property
    def bar(self) -> bool:
        """Both pairs revolute: a bar of fixed (or actuated) length."""
        return self is Leash.RR

    @property
    def block(self) -> bool:
        """Exactly one pair prismatic (RP or PR): one line constraint, no length."""
        return self.slides[0] != self.slides[1]

    @property
    def text(self) -> str:
        """As messages write it: ``R–P``."""
        return "–".join(self.value)


_LEASH_OF: dict[str, Leash] = {kind.value: kind for kind in Leash}  # str or Leash → Leash

T = TypeVar("T")


def expand(record: T) -> T:
    """A copy of a dataclass record with every array field given a trailing axis.

    Design values of shape (D,) then broadcast against candidates or samples of shape (D, K).
    """
    def grow(v: Any) -> Any:
        if v is None or isinstance(v, str):
            return v
        if isinstance(v, tuple):
            return tuple(grow(item) for item in v)
        return np.asarray(v)[..., None]

    changes = {f.name: grow(getattr(record, f.name)) for f in dataclasses.fields(record)  # type: ignore[arg-type]
               if f.init}
    return dataclasses.replace(record, **changes)  # type: ignore[type-var]


def values(record: T) -> T:
    """A copy of an inputs record with every jet replaced by its value."""
    changes = {f.name: (tuple(J.value(v) if v is not None else None for v in item)
                        if isinstance(item := getattr(record, f.name), tuple) else J.value(item))
               for f in dataclasses.fields(record)}  # type: ignore[arg-type]
    return dataclasses.replace(record, **changes)  # type: ignore[type-var]


def present(v: Value | None) -> Value:
    """``v``, which the group's form requires to be given (a guide, a prismatic pair's
    direction): the record's checks have made sure of it."""
    assert v is not None
    return v


def plain(v: Value) -> np.ndarray:
    """``v`` as an ndarray where it holds no jet: a drawn value, or an input on the paths that
    take plain arrays (the Jacobian, the lines, the eliminant, the recovery)."""
    assert not isinstance(v, J.Jet)
    return np.asarray(v)


#: Stacked matrices of more numbers than this are copied entry by entry before their
#: cofactors are formed (the products then run over contiguous arrays).
CONTIGUOUS = 1 << 14


def _entries(m: np.ndarray) -> list[list[np.ndarray]]:
    """The entries m[..., i, j] of stacked square matrices (copied to contiguous arrays where
    there are more than ``CONTIGUOUS`` numbers)."""
    n = m.shape[-1]
    if m.size > CONTIGUOUS:
        return [list(row) for row in np.ascontiguousarray(np.moveaxis(m, (-2, -1), (0, 1)))]
    return [[m[..., i, j] for j in range(n)] for i in range(n)]


def _cofactors(e: list[list[np.ndarray]], rows: int) -> list[list[np.ndarray]]:
    """The first ``rows`` rows of the cofactors C[i][j] of stacked 2×2 or 3×3 matrices of
    the entries ``e``."""
    if len(e) == 2:
        return [[e[1][1], -e[1][0]], [-e[0][1], e[0][0]]][:rows]
    return [[e[(i + 1) % 3][(j + 1) % 3] * e[(i + 2) % 3][(j + 2) % 3]
             - e[(i + 1) % 3][(j + 2) % 3] * e[(i + 2) % 3][(j + 1) % 3]
             for j in range(3)] for i in range(rows)]


def _determinant(e: list[list[np.ndarray]], first: list[np.ndarray]) -> np.ndarray:
    """Σ_j m[0][j]·C[0][j] from the entries ``e`` and the cofactors ``first`` of row 0."""
    return np.asarray(sum(e[0][j] * first[j] for j in range(len(e))))


def cofactors(m: np.ndarray) -> tuple[list[list[np.ndarray]], np.ndarray]:
    """Cofactors C[i][j] and determinants of stacked 2×2 or 3×3 matrices, in closed form.

    NaN entries give NaN results; a singular matrix gives determinant 0, never an error.

    Examples
    --------
    >>> m = np.array([[2.0, 1.0, 0.0], [0.0, 3.0, 1.0], [1.0, 0.0, 1.0]])
    >>> cof, det = cofactors(m)
    >>> float(det), bool(np.allclose(np.transpose(cof) / det, np.linalg.inv(m)))
    (7.0, True)
    """
    e = _entries(m)
    cof = _cofactors(e, len(e))
    return cof, _determinant(e, cof[0])


def det_rows(rows: np.ndarray) -> np.ndarray:
    """Determinants of stacked 2×2 or 3×3 matrices (by the first row's cofactors)."""
    e = _entries(rows)
    return _determinant(e, _cofactors(e, 1)[0])


def row_sums(a: np.ndarray) -> np.ndarray:
    """Σ_j a[..., j] over a short last axis, term by term (as ``a.sum(axis=-1)`` adds them).

    Examples
    --------
    >>> row_sums(np.array([[1.0, 3.0, 2.0], [0.5, 0.25, 1.0]])).tolist()
    [6.0, 1.75]
    """
    return _fold(a, np.add)


def row_max(a: np.ndarray) -> np.ndarray:
    """max_j a[..., j] over a short last axis, element by element (NaN where any is NaN,
    as ``a.max(axis=-1)``).

    Examples
    --------
    >>> row_max(np.array([[1.0, 3.0, 2.0], [0.0, np.nan, 1.0]])).tolist()
    [3.0, nan]
    """
    return _fold(a, np.maximum)


def row_offsets(shape: tuple[int, ...]) -> np.ndarray:
    """The flat index of the first element of each row of an array of ``shape`` (..., R),
    shape (..., 1): ``a.reshape(-1)[row_offsets(a.shape) + i]`` is ``a[..., i]`` row by row,
    for an index array ``i`` (..., K) — what ``np.take_along_axis`` gives, in one flat take.

    Examples
    --------
    >>> a = np.arange(6.0).reshape(2, 3)
    >>> a.reshape(-1)[row_offsets(a.shape) + np.array([[2, 0], [1, 1]])].tolist()
    [[2.0, 0.0], [4.0, 4.0]]
    """
    return np.arange(0, int(np.prod(shape)), shape[-1]).reshape(shape[:-1] + (1,))


def _fold(a: np.ndarray, op: np.ufunc) -> np.ndarray:
    """``op`` applied along a short last axis term by term, from the first:
    op(…op(a[..., 0], a[..., 1])…, a[..., −1]) — no reduction call over a short axis."""
    total = a[..., 0]
    for j in range(1, a.shape[-1]):
        total = op(total, a[..., j])
    return np.asarray(total)


def hadamard(rows: np.ndarray) -> np.ndarray:
    """|det R| / Π‖R_k‖: 1 for orthogonal rows, 0 for dependent ones (the margin's form)."""
    norms = np.sqrt(row_sums(rows * rows))
    return np.asarray(np.abs(det_rows(rows)) / _fold(norms, np.multiply))


#: The inputs record of a group: :class:`TriadInputs` or :class:`ClassIVInputs`.
K = TypeVar("K", "TriadInputs", "ClassIVInputs")


class HigherGroup(ABC, Generic[K]):
    """What the mode finder and the continuation need from a four-link group."""

    #: Number of unknowns (3 for a triad, 2 for the class IV group).
    n: int
    #: Index of the eliminated angle θ among the unknowns.
    eliminated: int
    #: Scale of each unknown for step norms: True for a length (divided by L).
    lengths: tuple[bool, ...]

    @property
    @abstractmethod
    def degree(self) -> int:
        """Degree m of the trigonometric eliminant Φ(θ); p(E) = E^m Φ has degree 2m."""

    @property
    @abstractmethod
    def size(self) -> np.ndarray:
        """L, the largest distance between the drawn joints of the group."""

    @abstractmethod
    def drawn(self) -> np.ndarray:
        """The unknowns of the drawn pose, shape (..., n)."""

    @property
    @abstractmethod
    def sketch(self) -> dict[str, Value]:
        """The drawn positions of the joints named as in :meth:`joints`."""

    @abstractmethod
    def residual(self, x: Unknowns, k: K) -> list[Value]:
        """The reduced loop equations F(x) (lengths, in the drawing's unit)."""

    @abstractmethod
    def lines(self, x: np.ndarray, k: K) -> tuple[np.ndarray, np.ndarray]:
        """The Jacobian (..., n, n) and the margin rows (..., n, n) of the constraint lines."""

    @abstractmethod
    def eliminant(self, e: np.ndarray, k: K) -> np.ndarray:
        """Φ at the unit complex numbers ``e`` (group and inputs expanded by one axis)."""

    @abstractmethod
    def recover(self, e: np.ndarray, k: K) -> np.ndarray:
        """The unknowns (..., n) at the root ``e`` of Φ (group and inputs expanded)."""

    @abstractmethod
    def joints(self, x: Unknowns, k: K) -> dict[str, Value]:
        """The internal joints of the group by name."""

    @abstractmethod
    def rotations(self, x: Unknowns, k: K) -> dict[str, Value]:
        """The rotation of each link of the group from the sketch, by name."""

    def coefficients(self, k: K) -> np.ndarray:
        """Coefficients p_0 … p_2m of p(E) = E^m·Φ (increasing powers), read off the FFT of
        Φ at 2m + 2 points of the unit circle (see :func:`~assur.kinematics.higher.modes.
        coefficients`)."""
        m = self.degree
        samples = 2 * m + 2
        e = np.exp(2j * np.pi * np.arange(samples) / samples)
        with np.errstate(all="ignore"):
            phi = expand(self).eliminant(e, expand(k))
        bins = np.fft.fft(phi, axis=-1) / samples
        return np.asarray(bins[..., np.arange(-m, m + 1) % samples])

    def residuals(self, x: np.ndarray, k: K) -> np.ndarray:
        """F(x) of plain inputs, stacked: shape (..., n)."""
        return stack_last([plain(v) for v in self.residual(x, k)])

    def assessed(self, x: np.ndarray, k: K) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """F(x) (..., n), the Jacobian and the margin rows (..., n, n): what tells whether x
        is a pose of the group and how far from a change point it is."""
        jac, rows = self.lines(x, k)
        return self.residuals(x, k), jac, rows

    def equations(self, x: np.ndarray, k: K) -> tuple[np.ndarray, np.ndarray]:
        """F(x), shape (..., n), and the Jacobian: the data of one Newton step."""
        return self.residuals(x, k), self.jacobian(x, k)

    def jacobian(self, x: np.ndarray, k: K) -> np.ndarray:
        """∂F/∂x, shape (..., n, n)."""
        return self.lines(x, k)[0]

    def margin(self, x: np.ndarray, k: K) -> np.ndarray:
        """The Hadamard ratio of the constraint lines, 0 at a change point (§1.7, §3.2)."""
        return hadamard(self.lines(x, k)[1])


def stack_last(parts: Sequence[Any]) -> np.ndarray:
    """The values ``parts`` broadcast together and stacked on a new last axis, as
    ``np.stack(np.broadcast_arrays(*parts), axis=-1)`` but written into one array.

    Examples
    --------
    >>> stack_last([np.arange(3.0), 1j]).tolist()
    [[0j, 1j], [(1+0j), 1j], [(2+0j), 1j]]
    """
    shapes = {np.shape(part) for part in parts}
    shape = shapes.pop() if len(shapes) == 1 else np.broadcast_shapes(*shapes)
    out = np.empty(shape + (len(parts),), dtype=np.result_type(*parts))
    for i, part in enumerate(parts):
        out[..., i] = part
    return out


def unknown_columns(x: Unknowns) -> list[Value]:
    if isinstance(x, np.ndarray):
        return [x[..., i] for i in range(x.shape[-1])]
    return list(x)


def plain_cross(a: Any, b: Any) -> np.ndarray:
    """cross(a, b) = Im(ā b) of plain complex arrays."""
    return np.asarray((np.conj(a) * b).imag)


def _line_rows(nu: np.ndarray, at: np.ndarray, origin: np.ndarray, radius: Any) -> np.ndarray:
    """Rows [ν_k, cross(X_k − O, ν_k)/radius] of the lines through X_k along ν_k."""
    moment = np.asarray(J.cross(at - origin, nu) / radius)
    out = np.empty(moment.shape + (3,))
    out[..., 0], out[..., 1], out[..., 2] = nu.real, nu.imag, moment
    return out


def _cross_terms(one: tuple[Any, ...], two: tuple[Any, ...]) -> tuple[Any, Any]:
    """cross(a, a′) = x₀ + x₁E + x̄₁/E of two lines' a = α₀ + α₁E, a′ = α′₀ + α′₁E
    (:meth:`Triad._leash_line`): x₀ = cross(α₀, α′₀) + cross(α₁, α′₁), x₁ = (ᾱ₀α′₁ − α₁ᾱ′₀)/2i."""
    (a0, a1, _, _), (b0, b1, _, _) = one, two
    return (plain_cross(a0, b0) + plain_cross(a1, b1),
            (np.conj(a0) * b1 - a1 * np.conj(b0)) / 2j)


@dataclass(frozen=True, eq=False)
class TriadInputs:
    """The known data of a triad at one crank position.

    Attributes
    ----------
    a : tuple of 3 complex
        Per leash: the external hinge A_k (R–R, P–R) or the point Q_k of the guide (R–P, the
        drawn hinge P_k⁰ carried by the guide's link).
    u : tuple of 3 complex or None
        Per leash: the unit direction u_k of the known link's guide of an R–P or P–P leash;
        None otherwise.
    lengths : tuple of 3 float or None
        Per bar leash: its length r_k where it is an input (a linear actuator, cylinder and
        rod hinged at the bar's two ends: the input coordinate q, a jet in q for the analogs);
        None for the drawn length |P_k⁰ − A_k⁰|.
    """

    a: tuple[Value, Value, Value]
    u: tuple[Value | None, Value | None, Value | None] = (None, None, None)
    lengths: tuple[Value | None, Value | None, Value | None] = (None, None, None)


@dataclass(frozen=True, eq=False)
class Triad(HigherGroup["TriadInputs"]):
    """A class III group of order 3: a base with three internal pairs and three leashes.

    Parameters
    ----------
    leashes : tuple of 3 Leash (or their names)
        Leash kinds, internal pair first. A bar, if there is one, must come first; a triad
        without a bar has all three equations linear in W (§2.2). A P–P leash comes last
        (at most one): it fixes the base's rotation θ to the known link's. After a bar the
        unknowns become the rotation ψ of W = P₁ − A₁ from the sketch, its length ρ and θ;
        without a bar the other two leashes are lines that place P₁ at θ = θ_K
        (``docs/higher_groups.md``, "A P–P leash").
    base : tuple of 3 complex
        Drawn points of the base: the hinge P_k⁰ (R–R, R–P) or a point of the base's guide
        (P–R, usually the drawn slider point).
    external : tuple of 3 complex
        Drawn external points: the hinge A_k⁰ (R–R, P–R) or a point of the guide (R–P, P–P).
    guide : tuple of 3 complex or None
        Drawn unit guide directions: of the known link's guide (R–P, P–P) or of the base's
        guide (P–R); None for a bar.

    Examples
    --------
    >>> t = Triad(("RR", "RR", "RR"), (169.5+57j, 174+92.5j, 127.5+52j),
    ...           (112.8+67.2j, 189.5+151j, -4.9+124.9j))
    >>> t.degree, round(float(t.size), 3)
    (3, 196.144)
    """

    leashes: tuple[Leash, Leash, Leash]
    base: tuple[Value, Value, Value]
    external: tuple[Value, Value, Value]
    guide: tuple[Value | None, Value | None, Value | None] = (None, None, None)

    n = 3

    def __post_init__(self) -> None:
        try:
            leashes = tuple(_LEASH_OF[kind] for kind in self.leashes)
        except KeyError as missing:
            raise ValueError(render("higher.error.leash_kind", found=missing.args[0])) from None
        object.__setattr__(self, "leashes", leashes)
        if any(kind.bar for kind in leashes) and not leashes[0].bar:
            raise ValueError(render("higher.error.first_leash", found=leashes[0].text))
        if Leash.PP in leashes[:2]:
            raise ValueError(render("higher.error.pp_leash",
                                    found=", ".join(k.text for k in leashes)))
        for kind, u in zip(leashes, self.guide, strict=True):
            if not kind.bar and u is None:
                raise ValueError(render("higher.error.guide_missing", found=kind.value))

    # --- drawn dimensions -----------------------------------------------------------------

    @cached_property
    def offsets(self) -> tuple[np.ndarray, ...]:
        """b_k (or s_k for P–R) = drawn base point − P₁⁰."""
        return tuple(np.asarray(b) - np.asarray(self.base[0]) for b in self.base)

    @cached_property
    def _lengths(self) -> tuple[np.ndarray, ...]:
        """|P_k⁰ − A_k⁰| (the leash length r_k of a bar)."""
        return tuple(np.abs(np.asarray(b) - np.asarray(a))
                     for b, a in zip(self.base, self.external, strict=True))

    def _offset(self, k: int) -> np.ndarray:
        return self.offsets[k]

    def leash_length(self, i: int, k: TriadInputs) -> Value:
        """r_i: the input's length of an actuator leash, else the drawn one."""
        given = k.lengths[i]
        return self._lengths[i] if given is None else given

    @property
    def pinned(self) -> bool:
        """The last leash slides on both its pairs: θ is the known link's rotation."""
        return self.leashes[2] is Leash.PP

    @property
    def unique(self) -> bool:
        """A P–P leash and no bar: exactly one mode, the crossing of two lines at θ = θ_K,
        solved in closed form (:func:`~assur.kinematics.higher.pinned.place`)."""
        return self.pinned and self.barless

    @property
    def polar(self) -> bool:
        """A bar and a P–P leash: the unknowns are (ψ, ρ, θ), W = ρ·e^{iψ}·W⁰/|W⁰|."""
        return self.pinned and not self.barless

    @property
    def eliminated(self) -> int:  # type: ignore[override]
        """ψ (index 0) with a bar and a P–P leash, else θ (index 2)."""
        return 0 if self.polar else 2

    @property
    def lengths(self) -> tuple[bool, ...]:  # type: ignore[override]
        """(ψ, ρ, θ) with a bar and a P–P leash, else (W_x, W_y, θ)."""
        return (False, True, False) if self.polar else (True, True, False)

    @property
    def barless(self) -> bool:
        """No leash is a bar: every equation is linear in W at a fixed θ."""
        return not any(kind.bar for kind in self.leashes)

    @property
    def degree(self) -> int:
        """3, or 2 when leashes 2 and 3 are both R–P or both P–R; without a bar 1 when the
        three leashes are of one kind, else 2 (§2.2); 1 with a P–P leash (with a bar at most
        2 modes; without one Φ = L·sin(θ − θ_K) and a single mode, :meth:`recover`)."""
        if self.pinned:
            return 1
        if self.barless:
            return 1 if len(set(self.leashes)) == 1 else 2
        return 2 if self.leashes[1] is self.leashes[2] and self.leashes[1].block else 3

    @cached_property
    def size(self) -> np.ndarray:
        """L of the drawn base and external points."""
        pts = np.broadcast_arrays(*(np.asarray(p, dtype=complex)
                                    for p in self.base + self.external))
        stack = np.stack(pts, axis=-1)
        return np.asarray(np.abs(stack[..., :, None] - stack[..., None, :]).max(axis=(-2, -1)))

    def drawn(self) -> np.ndarray:
        """(W⁰_x, W⁰_y, 0) with W⁰ = P₁⁰ − A₁⁰; (0, |W⁰|, 0) with a bar and a P–P leash."""
        w = np.asarray(self.base[0]) - np.asarray(self.external[0])
        first = (0.0 * np.abs(w), np.abs(w)) if self.polar else (w.real, w.imag)
        return np.stack(np.broadcast_arrays(*first, np.zeros(np.shape(w))), axis=-1)

    @property
    def sketch(self) -> dict[str, Value]:
        """P1, P2, P3 as drawn."""
        return {f"P{i + 1}": (self.external[i] if kind is Leash.PR else self.base[i])
                for i, kind in enumerate(self.leashes)}

    # --- equations ------------------------------------------------------------------------

    def _pose(self, x: Unknowns, k: TriadInputs) -> tuple[Value, Value]:
        """P₁ and E = e^{iθ}."""
        w = x[1] * self._heading * J.expi(x[0]) if self.polar else x[0] + 1j * x[1]
        return k.a[0] + w, J.expi(x[2])

    @cached_property
    def _heading(self) -> np.ndarray:
        """W⁰/|W⁰|: the drawn direction of the first leash, from which ψ is measured."""
        w = np.asarray(self.base[0]) - np.asarray(self.external[0])
        return np.asarray(w / np.abs(w))

    def _turn(self, k: TriadInputs) -> Value:
        """E_K = u_K/u_K⁰: the rotation of the known link carrying a P–P leash's guide."""
        return present(k.u[2]) / present(self.guide[2])

    def residual(self, x: Unknowns, k: TriadInputs) -> list[Value]:
        """f_k: (|P_k − A_k|² − r_k²)/(2r_k), n_k·(P_k − Q_k), n_k·(P₁ + s_kE − A_k) or,
        for a P–P leash, L·sin(θ − θ_K)."""
        p1, e = self._pose(unknown_columns(x), k)
        out: list[Value] = []
        for i, kind in enumerate(self.leashes):
            point = p1 + self._offset(i) * e
            if kind is Leash.RR:
                r = self.leash_length(i, k)
                arm = point - k.a[i]
                out.append((J.dot(arm, arm) - r * r) / (2.0 * r))
            elif kind is Leash.RP:
                out.append(J.dot(1j * present(k.u[i]), point - k.a[i]))
            elif kind is Leash.PP:
                out.append(self.size * J.cross(self._turn(k), e))
            else:
                out.append(J.dot(1j * present(self.guide[i]) * e, point - k.a[i]))
        return out

    def _constraints(self, x: np.ndarray, k: TriadInputs
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Line directions ν_k, line points X_k, base points and P₁, stacked over k."""
        p1, e = self._pose(unknown_columns(x), k)
        parts = []
        for i, kind in enumerate(self.leashes):
            point = p1 + self._offset(i) * e
            if kind is Leash.RR:
                parts.append(((point - k.a[i]) / self.leash_length(i, k), point, point))
            elif kind.slides[1]:  # on a known link's guide; a P–P row is replaced in lines()
                parts.append((1j * np.asarray(k.u[i]), point, point))
            else:
                parts.append((1j * np.asarray(self.guide[i]) * e, np.asarray(k.a[i]), point))
        out = np.empty((3,) + np.broadcast_shapes(*(np.shape(v) for part in parts for v in part))
                       + (3,), dtype=complex)
        for i, part in enumerate(parts):
            out[0, ..., i], out[1, ..., i], out[2, ..., i] = part
        return out[0], out[1], out[2], np.asarray(p1)

    @staticmethod
    def _margin_rows(nu: np.ndarray, at: np.ndarray, base: np.ndarray) -> np.ndarray:
        """The rows of the unit constraint lines about the base centroid, moments over the
        base's spread (:meth:`lines`)."""
        count = base.shape[-1]
        centre = (row_sums(base) / count)[..., None]
        spread = np.sqrt(row_sums(np.abs(base - centre) ** 2) / count)[..., None]
        return _line_rows(nu / np.abs(nu), at, centre, spread)

    def _forms(self, nu: np.ndarray, base: np.ndarray, k: TriadInputs) -> np.ndarray:
        """F(x) from the constraint lines: with the arm P_k − A_k, f_k = ν_k·(P_k − A_k) of a
        line, (|P_k − A_k|² − r_k²)/(2r_k) of a bar, the same operations as :meth:`residual`
        (no P–P leash)."""
        arm = base - stack_last([plain(a) for a in k.a])
        f = (np.conj(nu) * arm).real
        for i, kind in enumerate(self.leashes):
            if kind.bar:
                r = plain(self.leash_length(i, k))
                f[..., i] = ((np.conj(arm[..., i]) * arm[..., i]).real - r * r) / (2.0 * r)
        return np.asarray(f)

    def lines(self, x: np.ndarray, k: TriadInputs) -> tuple[np.ndarray, np.ndarray]:
        """The Jacobian and the margin rows about the base centroid.

        The Jacobian over (W_x, W_y, θ) has the rows [ν_k, cross(X_k − P₁, ν_k)], the line
        coordinates of the constraint lines. A P–P leash's row is [0, 0, L cos(θ − θ_K)] (the
        line at infinity, [0, 0, 1] in the margin); after a bar the columns of W become those
        of ψ and ρ by ∂W/∂ψ = iW, ∂W/∂ρ = W/ρ (W = ρ·e^{iψ}·W⁰/|W⁰|).
        """
        nu, at, base, p1 = self._constraints(x, k)
        rows = self._margin_rows(nu, at, base)
        jac = _line_rows(nu, at, p1[..., None], 1.0)
        if not self.pinned:
            return jac, rows
        turn = np.asarray(np.cos(x[..., 2] - np.angle(plain(self._turn(k)))) * self.size)
        jac, rows = jac.copy(), rows.copy()
        jac[..., 2, :] = np.stack(np.broadcast_arrays(0.0 * turn, 0.0 * turn, turn), axis=-1)
        rows[..., 2, :] = (0.0, 0.0, 1.0)
        if self.barless:
            return jac, rows
        heading = self._heading[..., None] * np.exp(1j * x[..., None, 0])
        along = np.conj(jac[..., 0] + 1j * jac[..., 1]) * heading
        jac[..., 0], jac[..., 1] = (1j * along).real * x[..., None, 1], along.real
        return jac, rows

    def equations(self, x: np.ndarray, k: TriadInputs) -> tuple[np.ndarray, np.ndarray]:
        """F(x) and the Jacobian from one evaluation of the constraint lines (:meth:`_forms`;
        a P–P leash: as :meth:`HigherGroup.equations`)."""
        if self.pinned:
            return super().equations(x, k)
        nu, at, base, p1 = self._constraints(x, k)
        return self._forms(nu, base, k), _line_rows(nu, at, p1[..., None], 1.0)

    def assessed(self, x: np.ndarray, k: TriadInputs
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """F(x), the Jacobian and the margin rows from one evaluation of the constraint lines
        (a P–P leash: as :meth:`HigherGroup.assessed`)."""
        if self.pinned:
            return super().assessed(x, k)
        nu, at, base, p1 = self._constraints(x, k)
        return (self._forms(nu, base, k), _line_rows(nu, at, p1[..., None], 1.0),
                self._margin_rows(nu, at, base))

    def jacobian(self, x: np.ndarray, k: TriadInputs) -> np.ndarray:
        """∂F/∂x: the rows [ν_k, cross(X_k − P₁, ν_k)] of :meth:`lines` without the margin
        rows (a P–P leash: from :meth:`lines`)."""
        if self.pinned:
            return self.lines(x, k)[0]
        nu, at, _, p1 = self._constraints(x, k)
        return _line_rows(nu, at, p1[..., None], 1.0)

    def _linear(self, e: np.ndarray, k: TriadInputs) -> tuple[list[Any], list[Any]]:
        """a_k·W = p_k at the base rotation E (§2.2): k = 2, 3 after a bar, all three
        without one (the first two beside a P–P leash)."""
        a1 = np.asarray(k.a[0])
        r1 = self.leash_length(0, k)
        coef, rhs = [], []
        for i in (((0, 1) if self.pinned else (0, 1, 2)) if self.barless else (1, 2)):
            kind = self.leashes[i]
            ai = np.asarray(k.a[i])
            offset = self._offset(i) * e
            if kind is Leash.RR:
                v = offset - (ai - a1)
                coef.append(v)
                rhs.append((self.leash_length(i, k) ** 2 - r1 ** 2 - np.abs(v) ** 2) / 2.0)
            else:
                normal = (1j * np.asarray(k.u[i]) if kind is Leash.RP
                          else 1j * plain(present(self.guide[i])) * e)
                coef.append(normal)
                rhs.append(J.dot(normal, ai - a1 - offset))
        return coef, rhs

    def _leash_line(self, i: int, k: TriadInputs) -> tuple[Any, Any, Any, Any]:
        """The line a_i·W = p_i of leash i (:meth:`_linear`) as polynomials in E: a_i = α₀ + α₁E
        and p_i = c + γE + γ̄/E (c real), returned as (α₀, α₁, c, γ).

        With d = A_i − A₁ and b the base's offset b_i: a bar a = bE − d, p = (r_i² − r₁²
        − |bE − d|²)/2; an R–P leash a = n = iu_i, p = n·(d − bE); a P–R leash a = igE (g the
        base's guide), p = a·(d − bE).
        """
        d = plain(k.a[i]) - plain(k.a[0])
        b = self._offset(i)
        kind = self.leashes[i]
        if kind is Leash.RR:
            c = (plain(self.leash_length(i, k)) ** 2 - plain(self.leash_length(0, k)) ** 2
                 - np.abs(b) ** 2 - np.abs(d) ** 2) / 2.0
            return -d, b, c, np.conj(d) * b / 2.0
        if kind is Leash.RP:
            n = 1j * plain(present(k.u[i]))
            return n, 0.0, plain_dot(n, d), -np.conj(n) * b / 2.0
        g = 1j * plain(present(self.guide[i]))
        return 0.0, g, -plain_dot(g, b), g * np.conj(d) / 2.0

    def _half(self, k: TriadInputs) -> list[Any]:
        """φ₀ … φ_m of Φ(θ) = Σ φ_n Eⁿ (φ₋ₙ = φ̄ₙ) in closed form (see :meth:`coefficients`)."""
        if self.unique:
            return [0.0, self.size * np.conj(plain(self._turn(k))) / 2j]
        if self.polar:
            turn = plain(self._turn(k))
            v = plain(k.a[0]) + self._offset(1) * turn - plain(k.a[1])
            w = plain(self.leash_length(0, k)) * self._heading
            kind = self.leashes[1]
            if kind is Leash.RR:
                r2 = plain(self.leash_length(1, k))
                return [(np.abs(v) ** 2 + np.abs(w) ** 2 - r2 ** 2) / (2.0 * r2),
                        np.conj(v) * w / (2.0 * r2)]
            n = 1j * plain(present(k.u[1]) if kind is Leash.RP
                           else present(self.guide[1]) * turn)
            return [plain_dot(n, v), np.conj(n) * w / 2.0]
        if self.barless:
            out: list[Any] = [0.0, 0.0, 0.0]
            lines = [self._leash_line(i, k) for i in range(3)]
            for i in range(3):
                _, _, c, g = lines[i]
                x0, x1 = _cross_terms(lines[(i + 1) % 3], lines[(i + 2) % 3])
                out = [out[0] + c * x0 + 2.0 * plain_dot(x1, g), out[1] + c * x1 + g * x0,
                       out[2] + g * x1]
            return out[:self.degree + 1]
        line2, line3 = self._leash_line(1, k), self._leash_line(2, k)
        (a2, b2, c2, g2), (a3, b3, c3, g3) = line2, line3
        h2, h3 = np.conj(g2), np.conj(g3)
        m = [h2 * a3 - h3 * a2, c2 * a3 + h2 * b3 - c3 * a2 - h3 * b2,
             g2 * a3 + c2 * b3 - g3 * a2 - c3 * b2, g2 * b3 - g3 * b2]  # M = p₂a₃ − p₃a₂
        x0, x1 = _cross_terms(line2, line3)
        r1 = plain(self.leash_length(0, k)) ** 2
        cross = [x0 * x0 + 2.0 * np.abs(x1) ** 2, 2.0 * x0 * x1, x1 * x1, 0.0]
        conj = [np.conj(v) for v in m]
        return [sum(m[j] * conj[j - n] for j in range(n, 4)) - r1 * cross[n]
                for n in range(self.degree + 1)]

    def coefficients(self, k: TriadInputs) -> np.ndarray:
        """Coefficients p_0 … p_2m of p(E) = E^m·Φ (increasing powers) in closed form.

        Each leash's line a_k·W = p_k is a polynomial of degree 1 in E and 1/E
        (:meth:`_leash_line`); with a bar, M = p₂a₃ − p₃a₂ has the powers E⁻¹ … E² and
        Φ = M·M̄ − r₁²·cross(a₂, a₃)² is read off their products; without one Φ = Σ p_i
        cross(a_{i+1}, a_{i+2}); with a P–P leash Φ is the second leash's equation on the
        circle |W| = r₁ (or L·sin(θ − θ_K)). A row with an input that is not finite is NaN.

        Examples
        --------
        >>> t = Triad(("RR", "RR", "RR"), (169.5+57j, 174+92.5j, 127.5+52j),
        ...           (112.8+67.2j, 189.5+151j, -4.9+124.9j))
        >>> k = TriadInputs(t.external)
        >>> p = t.coefficients(k)
        >>> p.shape, bool(np.allclose(p, np.conj(p[::-1])))
        ((7,), True)

        The drawn pose is a root (θ = 0, E = 1):

        >>> bool(abs(t.eliminant(np.ones(1), k)[0]) < 1e-12 * np.abs(p).max())
        True
        """
        with np.errstate(all="ignore"):
            half = self._half(k)
            m = len(half) - 1
            shape = np.broadcast_shapes(*map(np.shape, half))
            out = np.empty((2 * m + 1,) + shape, dtype=complex)
            for n, v in enumerate(half):
                out[m + n] = v
                np.conjugate(out[m + n, ...], out=out[m - n, ...])
            bad = ~np.isfinite(out.sum(axis=0))
            if bad.any():
                out[:, bad] = np.nan
        return np.moveaxis(out, 0, -1)

    def eliminant(self, e: np.ndarray, k: TriadInputs) -> np.ndarray:
        """Φ(θ) = |p₂a₃ − p₃a₂|² − r₁² cross(a₂, a₃)²; without a bar the determinant of the
        three rows [a_k, p_k] (the three lines a_k·W = p_k meet in one W); with a bar and a
        P–P leash the second leash's equation at ρ = r₁, θ = θ_K; with a P–P leash and no
        bar the P–P leash's own equation L·sin(θ − θ_K): the polynomial of
        :meth:`coefficients` at E = e."""
        coef = self.coefficients(k)
        m = self.degree
        powers = e[..., None] ** np.arange(-m, m + 1)
        return np.asarray((coef * powers).sum(axis=-1).real)

    def recover(self, e: np.ndarray, k: TriadInputs) -> np.ndarray:
        """W = −i(p_ia_j − p_ja_i)/cross(a_i, a_j) (after a bar i, j = 2, 3; without one the
        two lines that meet at the widest angle), θ = arg E; with a bar and a P–P leash
        (ψ, ρ, θ) = (arg e, r₁, θ_K), ψ the first leash's rotation from the sketch.

        With a P–P leash and no bar, θ = θ_K and W is where the lines of the other two
        leashes cross at E_K, for both roots ±E_K of Φ: the leash turns with the base and with
        the known link, so the antiparallel root −E_K is no pose of its own, and the
        deduplication of :func:`~assur.kinematics.higher.modes.assembly_modes` keeps one mode.
        """
        if self.unique:
            e = plain(self._turn(k)) * np.ones(np.shape(e))
        elif self.pinned:
            theta = np.angle(plain(self._turn(k)))
            return np.stack(np.broadcast_arrays(np.angle(e), plain(self.leash_length(0, k)), theta),
                            axis=-1)
        coef, rhs = self._linear(e, k)
        pairs = ((1, 2), (2, 0), (0, 1)) if len(coef) == 3 else ((0, 1),)
        best, w = None, None
        for i, j in pairs:
            det = plain_cross(coef[i], coef[j])
            here = -1j * (rhs[i] * coef[j] - rhs[j] * coef[i]) / det
            if best is None or w is None:
                best, w = np.abs(det), here
            else:
                wider = np.abs(det) > best
                best, w = np.where(wider, np.abs(det), best), np.where(wider, here, w)
        assert w is not None
        return stack_last([w.real, w.imag, np.angle(e)])

    def joints(self, x: Unknowns, k: TriadInputs) -> dict[str, Value]:
        """P1, P2, P3: the internal pairs (for a P–R leash, the slider at its hinge A_k); O:
        the base's point drawn at P₁⁰ carried by the base, the origin of its frame (P1 itself
        unless the first leash slides on the base, where P1 is the hinge A₁ on the leash)."""
        p1, e = self._pose(unknown_columns(x), k)
        out = {f"P{i + 1}": (k.a[i] if kind is Leash.PR else p1 + self._offset(i) * e)
               for i, kind in enumerate(self.leashes)}
        out["O"] = p1
        return out

    def rotations(self, x: Unknowns, k: TriadInputs) -> dict[str, Value]:
        """base: θ; leash1–3: the rotation of each leash (a P–R leash turns with the base)."""
        cols = unknown_columns(x)
        p1, e = self._pose(cols, k)
        out: dict[str, Value] = {"base": cols[2]}
        for i, kind in enumerate(self.leashes):
            if kind is Leash.RR:
                drawn = np.asarray(self.base[i]) - np.asarray(self.external[i])
                out[f"leash{i + 1}"] = J.arg((p1 + self._offset(i) * e - k.a[i]) / drawn)
            elif kind.slides[1]:
                out[f"leash{i + 1}"] = J.arg(k.u[i] / np.asarray(self.guide[i]))
            else:
                out[f"leash{i + 1}"] = cols[2]
        return out


@dataclass(frozen=True, eq=False)
class ClassIVInputs:
    """The known data of a class IV group at one crank position.

    Attributes
    ----------
    h_a, h_c : complex
        The external hinge H_a (H_c) of a revolute pair; for a prismatic pair, the point of
        the known link's guide drawn at the pair's point H_a⁰ (H_c⁰), carried by that link.
    u_a, u_c : complex or None
        The unit direction of the known link's guide of a prismatic external pair, carried by
        that link; None for a revolute pair.
    l_b, l_d : float or None
        The length of the coupler b (d) where it is an input (a linear actuator, cylinder and
        rod hinged at C and D, or at F and E: the input coordinate q, a jet in q for the
        analogs); None for the drawn length.
    """

    h_a: Value
    h_c: Value
    u_a: Value | None = None
    u_c: Value | None = None
    l_b: Value | None = None
    l_d: Value | None = None


@dataclass(frozen=True, eq=False)
class ClassIVDrawing(HigherGroup[ClassIVInputs]):
    """The drawing every class IV group of order 2 is given by: the six points of links a
    and c and the guides of their external pairs (:class:`~assur.kinematics.higher.coupled.ClassIVCoupled`).

    Parameters
    ----------
    h_a, c, f : complex
        Drawn points of link a: its external pair's point H_a⁰ and the internal pairs C (to
        b), F (to d).
    h_c, d, e : complex
        Drawn points of link c: its external pair's point H_c⁰ and the internal pairs D (to
        b), E (to d).
    u_a, u_c : complex or None
        The drawn unit direction of the guide of a prismatic external pair on a (on c); None
        for a hinge.
    """

    h_a: Value
    c: Value
    f: Value
    h_c: Value
    d: Value
    e: Value
    u_a: Value | None = None
    u_c: Value | None = None

    @cached_property
    def size(self) -> np.ndarray:
        """L of the six drawn points."""
        pts = np.broadcast_arrays(*(np.asarray(p, dtype=complex) for p in
                                    (self.h_a, self.c, self.f, self.h_c, self.d, self.e)))
        stack = np.stack(pts, axis=-1)
        return np.asarray(np.abs(stack[..., :, None] - stack[..., None, :]).max(axis=(-2, -1)))

    @cached_property
    def slides(self) -> tuple[bool, bool]:
        """Whether the external pair of a, of c, is prismatic."""
        return self.u_a is not None, self.u_c is not None

    @property
    def sketch(self) -> dict[str, Value]:
        """C, D, E, F as drawn."""
        return {"C": self.c, "D": self.d, "E": self.e, "F": self.f}


def plain_dot(a: Any, b: Any) -> np.ndarray:
    """a·b = Re(ā b) of plain complex arrays."""
    return np.asarray((np.conj(a) * b).real)


#: A triad or a class IV group.
AnyGroup = HigherGroup[TriadInputs] | HigherGroup[ClassIVInputs]
