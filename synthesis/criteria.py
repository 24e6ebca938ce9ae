"""Block B3: the Peisakh criteria Q, P1, P2 and their combination, as pure array functions.

Every function works on a whole batch of candidate designs at once: arrays have a leading
axis of length D (designs); control points run along the last axis (K), positions of the
analysis grid along the last axis (N).  Nothing here knows about mechanisms; block B2
(:mod:`synthesis.evaluate`) supplies the reproduced outputs, the existence data, the pressure
angles and the joint rotations.

The formulas are those of ``method.md`` §5.2–5.6; each is written out in the docstring of the
function that computes it.

Examples
--------
Two designs, three control points of a class-2 task (slider stroke law):

>>> import numpy as np
>>> s = np.array([[0.0, 1.0, 2.0], [0.0, 1.5, 2.0]])
>>> d = value_deviations(s, np.array([0.0, 1.0, 2.0]), np.array([1.0, 2.0, 1.0]))
>>> criterion_q(d).tolist()
[0.0, 1.0]
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import numpy.typing as npt

from assur.typing import BoolArray, ComplexArray, FloatArray, IntArray

__all__ = [
    "Criteria",
    "bounds_penalty",
    "criterion",
    "criterion_q",
    "criterion_rms",
    "desirable_penalty",
    "existence_penalty",
    "margin_penalty",
    "merit",
    "nearest_on_path",
    "path_deviations",
    "pressure_penalty",
    "rotation_penalty",
    "timed_path_deviations",
    "value_deviations",
    "workspace_penalty",
    "zone_deviations",
    "zone_residuals",
]

Objective = Literal["lexicographic", "weighted"]


# ----------------------------------------------------------------------------- deviations (§5.2)

def value_deviations(output: FloatArray, target: FloatArray, weights: FloatArray) -> FloatArray:
    """Weighted deviations of a scalar output (task classes 1 and 2).

    Class 1 (rotating output ψ, or its velocity ratio n = dψ/dφ) and class 2 (slider
    output S)::

        Δ_K = E_K · (F(φ_K, x) − F*_K),   F = ψ, n or S

    Parameters
    ----------
    output : array_like, shape (D, K)
        Reproduced output F(φ_K, x) of each design at the control angles.
    target : array_like, shape (K,)
        Required values F*_K.
    weights : array_like, shape (K,)
        Weights E_K.

    Returns
    -------
    ndarray, shape (D, K)
        Signed weighted deviations (NaN where the output is NaN).
    """
    return np.asarray(weights) * (np.asarray(output) - np.asarray(target))


def zone_deviations(output: FloatArray, lower: FloatArray, upper: FloatArray,
                    weights: FloatArray) -> FloatArray:
    """Weighted deviations from a tolerance zone (task class 1, zone form).

    The output may lie anywhere between the lower and the upper limit curve::

        Δ(φ_K) = max(0, ψ_lo,K − ψ(φ_K), ψ(φ_K) − ψ_hi,K),   Δ_K = E_K · Δ(φ_K)

    With the velocity ratio as the output (``output: ratio``) ψ is replaced by
    n = dψ/dφ and the limits by n_lo,K, n_hi,K; a band [n*(1 − δ), n*] over a zone of crank
    angles keeps the ratio within δ of its prescribed maximum n*, and a row with
    n_lo = n_hi is an equality n(φ_K) = n_K.

    Parameters
    ----------
    output : array_like, shape (D, K)
        Reproduced ψ(φ_K) (or n(φ_K)).
    lower, upper : array_like, shape (K,)
        Limit curves at the control angles (lower ≤ upper).
    weights : array_like, shape (K,)
        Weights E_K.

    Returns
    -------
    ndarray, shape (D, K)
        Non-negative weighted deviations (0 inside the zone).

    Notes
    -----
    With lower ≤ upper and E_K ≥ 0 (both checked by the problem reader) at most one of the
    two overshoots is positive, so Δ_K = |r_K| of :func:`zone_residuals`.
    """
    return np.abs(zone_residuals(output, lower, upper, weights))


def zone_residuals(output: FloatArray, lower: FloatArray, upper: FloatArray,
                   weights: FloatArray) -> FloatArray:
    """Signed form of :func:`zone_deviations`, for the least-squares refinement.

    Notes
    -----
    ::

        r_K = E_K · [min(0, F(φ_K) − F_lo,K) + max(0, F(φ_K) − F_hi,K)],   |r_K| = Δ_K

    negative below the lower limit, positive above the upper one, 0 inside.  Where the two
    limits coincide (an equality row, F_lo = F_hi = F_K) this is the smooth
    ``E_K·(F(φ_K) − F_K)``; the unsigned Δ_K would have a V-shaped kink at the solution that
    spoils a finite-difference Jacobian.

    Parameters
    ----------
    output : array_like, shape (D, K)
        Reproduced ψ(φ_K) or n(φ_K).
    lower, upper : array_like, shape (K,)
        Limit curves at the control angles (lower ≤ upper).
    weights : array_like, shape (K,)
        Weights E_K.

    Returns
    -------
    ndarray, shape (D, K)
    """
    output = np.asarray(output)
    below = np.minimum(output - np.asarray(lower), 0.0)
    above = np.maximum(output - np.asarray(upper), 0.0)
    out: FloatArray = np.asarray(weights) * (below + above)
    return out


def timed_path_deviations(points: ComplexArray, targets: ComplexArray,
                          weights: FloatArray) -> FloatArray:
    """Weighted deviations of a tracing point with timing (task class 4).

    ::

        Δ_K = E_K · sqrt((x_Ж(φ_K) − x_K)² + (y_Ж(φ_K) − y_K)²) = E_K · |Ж(φ_K) − P_K|

    Parameters
    ----------
    points : array_like of complex, shape (D, K)
        Position of the tracing point at the control angles φ_K.
    targets : array_like of complex, shape (K,)
        Required points P_K = x_K + i·y_K.
    weights : array_like, shape (K,)
        Weights E_K.
    """
    return np.asarray(weights) * np.abs(np.asarray(points) - np.asarray(targets))


def path_deviations(nearest: ComplexArray, targets: ComplexArray,
                    weights: FloatArray) -> FloatArray:
    """Weighted deviations of a tracing point without timing (task class 3).

    ::

        Δ_K = E_K · min_φ |Ж(φ) − P_K|

    the shortest distance from the K-th required point to the traced path.  The minimising
    points come from :func:`nearest_on_path` (refined by block B2 on the true path).

    Parameters
    ----------
    nearest : array_like of complex, shape (D, K)
        The point of each design's path nearest to each required point.
    targets : array_like of complex, shape (K,)
        Required points.
    weights : array_like, shape (K,)
        Weights E_K.
    """
    return timed_path_deviations(nearest, targets, weights)


def nearest_on_path(path: ComplexArray, targets: ComplexArray, *, closed: bool = True,
                    chunk: int = 128) -> tuple[FloatArray, ComplexArray]:
    """Nearest points of polygonal paths to given points.

    The path of each design is the polygon through its grid points; for each required point
    P_K the nearest vertex m is found, then P_K is projected onto the two segments that meet
    at m::

        t = clip(dot(P − V_a, V_b − V_a) / |V_b − V_a|², 0, 1),   Q = V_a + t·(V_b − V_a)

    and the nearer projection is kept.

    Parameters
    ----------
    path : array_like of complex, shape (D, N)
        Grid positions of the tracing point (NaN where a design does not exist).
    targets : array_like of complex, shape (K,)
        Required points.
    closed : bool
        Whether the last grid point joins the first (full-turn crank).
    chunk : int
        Designs handled per block, to bound memory (D·K·N distances per block).

    Returns
    -------
    index : ndarray, shape (D, K)
        Fractional grid index of the nearest point (m + t or m − 1 + t).
    point : ndarray of complex, shape (D, K)
        The nearest point of the polygon.
    """
    path = np.asarray(path, dtype=complex)
    targets = np.asarray(targets, dtype=complex)
    n = path.shape[-1]
    index = np.empty((path.shape[0], targets.size))
    point = np.empty((path.shape[0], targets.size), dtype=complex)
    for start in range(0, path.shape[0], chunk):
        block = path[start:start + chunk]
        gap = np.abs(block[:, None, :] - targets[None, :, None])
        gap = np.where(np.isnan(gap), np.inf, gap)
        m = np.argmin(gap, axis=-1)
        best_i, best_p, best_d = None, None, None
        for side in (-1, 1):
            a_i = m if side == 1 else m - 1
            b_i = a_i + 1
            if closed:
                a_i, b_i = a_i % n, b_i % n
            else:
                a_i, b_i = np.clip(a_i, 0, n - 1), np.clip(b_i, 0, n - 1)
            a = np.take_along_axis(block[:, None, :], a_i[..., None], axis=-1)[..., 0]
            b = np.take_along_axis(block[:, None, :], b_i[..., None], axis=-1)[..., 0]
            seg = b - a
            length2 = np.abs(seg) ** 2
            with np.errstate(invalid="ignore", divide="ignore"):
                t = np.where(length2 > 0, ((np.conj(seg) * (targets[None, :] - a)).real)
                             / np.where(length2 > 0, length2, 1.0), 0.0)
            t = np.clip(np.nan_to_num(t), 0.0, 1.0)
            p = a + t * seg
            d = np.abs(p - targets[None, :])
            frac = (m if side == 1 else m - 1) + t
            if best_d is None:
                best_i, best_p, best_d = frac, p, d
            else:
                take = d < best_d
                best_i = np.where(take, frac, best_i)
                best_p = np.where(take, p, best_p)
                best_d = np.where(take, d, best_d)
        index[start:start + chunk] = best_i
        point[start:start + chunk] = best_p
    return index, point


# --------------------------------------------------------------------------------- Q (§5.3)

def criterion_q(deviations: FloatArray) -> FloatArray:
    """Criterion Q: the largest absolute weighted deviation over the control points.

    ::

        Q(x) = max_K |Δ_K(x)|

    Parameters
    ----------
    deviations : array_like, shape (D, K)

    Returns
    -------
    ndarray, shape (D,)
        NaN for a design whose deviations are not all defined.
    """
    out: FloatArray = np.max(np.abs(np.asarray(deviations)), axis=-1)
    return out


def criterion_rms(deviations: FloatArray, weights: FloatArray) -> FloatArray:
    """The root-mean-square form of the accuracy criterion (reported beside Q).

    With unweighted deviations δ_K = Δ_K / E_K::

        Q_rms = sqrt(Σ_K E_K·δ_K² / Σ_K E_K)

    Parameters
    ----------
    deviations : array_like, shape (D, K)
        Weighted deviations Δ_K.
    weights : array_like, shape (K,)
        Weights E_K (positive).
    """
    weights = np.asarray(weights, dtype=float)
    delta = np.asarray(deviations) / weights
    out: FloatArray = np.sqrt(np.sum(weights * delta ** 2, axis=-1) / np.sum(weights))
    return out


def criterion(deviations: FloatArray, weights: FloatArray, kind: str = "max") -> FloatArray:
    """Q built from the deviations the way the problem asks (``general: criterion``).

    The course takes Q as the largest deviation and adds that "other ways to build Q on
    the known deviation function are possible"; the root mean square is the other one::

        max:  Q = max_K |Δ_K|                       (:func:`criterion_q`)
        rms:  Q = sqrt(Σ_K E_K·δ_K² / Σ_K E_K)      (:func:`criterion_rms`, δ_K = Δ_K/E_K)

    Parameters
    ----------
    deviations : array_like, shape (D, K)
    weights : array_like, shape (K,)
    kind : {'max', 'rms'}

    Examples
    --------
    >>> d = np.array([[3.0, 4.0]])
    >>> criterion(d, np.ones(2)).tolist(), criterion(d, np.ones(2), "rms").round(6).tolist()
    ([4.0], [3.535534])
    """
    if kind == "rms":
        return criterion_rms(deviations, weights)
    return criterion_q(deviations)


# -------------------------------------------------------------------------------- P1 (§5.4)

def existence_penalty(first_failed: IntArray, violation: FloatArray,
                      n_groups: int) -> FloatArray:
    """Criterion P1: how badly the chain fails to close over the analysis grid.

    At each grid position φ_m the groups are solved in layering order; if group g (ordinal
    2..N_Q, L0 being 1) is the first that does not assemble, with normalised violation
    v > 0 of its existence condition::

        π_m = (N_Q − g) + v / (1 + v),        π_m = 0 if every group exists,
        P1(x) = Σ_m π_m

    P1 = 0 exactly on the feasible set; it is smaller for designs that break later in the
    chain, at fewer positions, and by less, so that the search can move towards feasibility.

    Parameters
    ----------
    first_failed : array_like of int, shape (D, N)
        Ordinal of the first failing group at each position, 0 where every group exists.
    violation : array_like, shape (D, N)
        v ≥ 0 of that group (ignored where ``first_failed`` is 0).
    n_groups : int
        N_Q, the number of groups including L0.

    Returns
    -------
    ndarray, shape (D,)
    """
    first_failed = np.asarray(first_failed)
    v = np.maximum(np.nan_to_num(np.asarray(violation, dtype=float), nan=1.0,
                                 posinf=1e300), 0.0)
    pi = np.where(first_failed > 0, (n_groups - first_failed) + v / (1.0 + v), 0.0)
    out: FloatArray = np.sum(pi, axis=-1)
    return out


# -------------------------------------------------------------------------------- P2 (§5.5)

def bounds_penalty(x: FloatArray, lower: FloatArray, upper: FloatArray) -> FloatArray:
    """Desirable condition 1: the varied parameters stay inside their bounds.

    ::

        P2_b = Σ_i [max(0, x_i⁻ − x_i) + max(0, x_i − x_i⁺)] / (x_i⁺ − x_i⁻)

    Parameters
    ----------
    x : array_like, shape (D, q)
        Varied parameters of each design.
    lower, upper : array_like, shape (q,)
        Bounds, lower < upper.
    """
    lower = np.asarray(lower, dtype=float)
    upper = np.asarray(upper, dtype=float)
    x = np.asarray(x, dtype=float)
    outside = np.maximum(lower - x, 0.0) + np.maximum(x - upper, 0.0)
    out: FloatArray = np.sum(outside / (upper - lower), axis=-1)
    return out


def pressure_penalty(alpha_max: FloatArray, allowed: FloatArray) -> FloatArray:
    """Desirable condition 2: the pressure angles do not exceed the allowable ones.

    For each group k whose pressure angle is computed (L1, L2 with a two-hinge link)::

        P2_α = Σ_k max(0, α_max,k − [α]_k) / [α]_k,   α_max,k = max_φ α_k(φ)

    Parameters
    ----------
    alpha_max : array_like, shape (D, G)
        Largest pressure angle of each such group over the cycle (radians).
    allowed : array_like, shape (G,)
        Allowable pressure angles [α]_k (radians, positive).
    """
    allowed = np.asarray(allowed, dtype=float)
    if allowed.size == 0:
        return np.zeros(np.shape(alpha_max)[0])
    out: FloatArray = np.sum(np.maximum(np.asarray(alpha_max) - allowed, 0.0) / allowed, axis=-1)
    return out


def rotation_penalty(rotation: FloatArray, allowed: FloatArray) -> FloatArray:
    """Desirable condition 3: relative rotations in revolute joints stay allowable.

    For each revolute joint ab with relative angle θ_ab(φ) = φ_a − φ_b unwrapped over the
    cycle, Δθ_ab = max_φ θ_ab − min_φ θ_ab, and::

        P2_r = Σ_ab max(0, Δθ_ab − [Δθ_ab]) / [Δθ_ab]

    Parameters
    ----------
    rotation : array_like, shape (D, J)
        Δθ_ab of each checked joint (radians).
    allowed : array_like, shape (J,)
        Allowable rotations [Δθ_ab] (radians, positive).
    """
    return pressure_penalty(rotation, allowed)


def margin_penalty(margins: FloatArray) -> FloatArray:
    """The share of P2 of the conditions given by signed margins.

    A pressure angle, a joint swing or a workspace box is held when its margin is ≤ 0::

        m_α = (α_max − [α]) / [α],   m_r = (Δθ − [Δθ]) / [Δθ],
        m_w = max_φ s_P(φ) / L_P,    P2 share = Σ max(0, m)

    with s_P the summed excursion of point P outside its box (as in
    :func:`workspace_penalty`) where it is outside and minus its distance to the nearest
    side where it is inside; so the share equals :func:`pressure_penalty`,
    :func:`rotation_penalty` and :func:`workspace_penalty` together.

    Parameters
    ----------
    margins : array_like, shape (D, M)

    Returns
    -------
    ndarray, shape (D,)

    Examples
    --------
    >>> margin_penalty(np.array([[-0.5, 0.25], [-0.1, -0.2]])).tolist()
    [0.25, 0.0]
    """
    out: FloatArray = np.sum(np.maximum(np.asarray(margins, dtype=float), 0.0), axis=-1)
    return out


def workspace_penalty(excess: FloatArray, scale: FloatArray) -> FloatArray:
    """Desirable condition 4: tracked points stay inside their allowed boxes.

    For each tracked point P with box [x_min, x_max] × [y_min, y_max] and length scale L
    (the box diagonal)::

        e_P = max_φ [max(0, x_min − x_P, x_P − x_max) + max(0, y_min − y_P, y_P − y_max)]
        P2_w = Σ_P e_P / L_P

    Parameters
    ----------
    excess : array_like, shape (D, J)
        e_P of each tracked point (mm).
    scale : array_like, shape (J,)
        L_P (mm, positive).
    """
    scale = np.asarray(scale, dtype=float)
    if scale.size == 0:
        return np.zeros(np.shape(excess)[0])
    out: FloatArray = np.sum(np.asarray(excess) / scale, axis=-1)
    return out


def desirable_penalty(bounds: FloatArray, pressure: FloatArray, rotation: FloatArray,
                      workspace: FloatArray | float = 0.0, *,
                      weights: tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
                      ) -> FloatArray:
    """Criterion P2: the weighted sum of the desirable-condition penalties.

    ::

        P2 = w_b·P2_b + w_α·P2_α + w_r·P2_r + w_w·P2_w          (default weights 1)

    P2 = 0 iff every desirable condition holds.  It is meaningful only where P1 = 0.
    """
    w_b, w_a, w_r, w_w = weights
    return (w_b * np.asarray(bounds) + w_a * np.asarray(pressure) + w_r * np.asarray(rotation)
            + w_w * np.asarray(workspace))


# ---------------------------------------------------------------------- combination (§5.6)

@dataclass(frozen=True)
class Criteria:
    """The criteria of a batch of designs.

    Attributes
    ----------
    p1, p2, q : ndarray, shape (D,)
        P1 everywhere; P2 and Q are NaN where P1 > 0 (they are not defined there).
    deviations : ndarray, shape (D, K)
        Weighted deviations Δ_K (NaN where P1 > 0).
    residuals : ndarray, shape (D, R)
        Smooth signed components whose sum of squares is Σ_K Δ_K² (for the local
        refinement): Δ_K itself for classes 1–2 (for a class-1 zone the signed
        overshoot of :func:`zone_residuals`), the two coordinates of E_K·(Ж − P_K) for
        classes 3–4.
    margins : ndarray, shape (D, M)
        Signed, normalised margin of each desirable condition that has one (pressure
        angles, joint swings, workspace boxes; :func:`margin_penalty`): ≤ 0 where the
        condition holds, and its positive part is that condition's share of P2 — so the
        refinement can hold the conditions as inequality constraints and slide along
        their boundary.  Empty (M = 0) when none is given; NaN where P1 > 0.
    """

    p1: FloatArray
    p2: FloatArray
    q: FloatArray
    deviations: FloatArray
    residuals: FloatArray
    margins: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))

    def __post_init__(self) -> None:
        if self.margins.shape[0] != self.p1.shape[0] and self.margins.size == 0:
            object.__setattr__(self, "margins", np.zeros((self.p1.shape[0], 0)))

    def __len__(self) -> int:
        return int(self.p1.shape[0])

    def arrays(self) -> tuple[FloatArray, ...]:
        """The six arrays, in field order."""
        return self.p1, self.p2, self.q, self.deviations, self.residuals, self.margins

    def take(self, index: Sequence[int] | npt.NDArray[np.intp]) -> Criteria:
        """The criteria of a subset of the designs."""
        return Criteria(*(array[index] for array in self.arrays()))

    @property
    def feasible(self) -> BoolArray:
        """Which designs meet every obligatory and desirable condition (P1 = P2 = 0).

        The one definition of a feasible design: the search, the result and the reports
        all read it here.
        """
        feasible: BoolArray = (self.p1 == 0) & (self.p2 == 0)
        return feasible

    def favourable(self, q_required: float | None) -> BoolArray:
        """Which designs are favourable: feasible and Q ≤ [Q] (none without a [Q]).

        Parameters
        ----------
        q_required : float or None
            [Q] in the internal unit of Q (radians for an angle ψ).

        Examples
        --------
        >>> c = Criteria(np.zeros(3), np.array([0.0, 0.0, 1.0]), np.array([0.1, 2.0, 0.1]),
        ...              np.zeros((3, 1)), np.zeros((3, 1)))
        >>> c.feasible.tolist(), c.favourable(0.5).tolist(), c.favourable(None).tolist()
        ([True, True, False], [True, False, False], [False, False, False])
        """
        if q_required is None:
            return np.zeros(len(self), dtype=bool)
        with np.errstate(invalid="ignore"):
            return self.feasible & (self.q <= q_required)


def merit(criteria: Criteria, *, objective: Objective = "lexicographic",
          q_ref: float = 1.0, p2_weight: float = 1.0) -> FloatArray:
    """The scalar objective P(x) used to rank designs (smaller is better).

    Lexicographic (default, strict priority of P1 over P2 over Q)::

        P = 2 + P1/(1 + P1)        if P1 > 0
        P = 1 + P2/(1 + P2)        if P1 = 0 and P2 > 0
        P = Q/(Q + [Q])            if P1 = P2 = 0

    The three maps are increasing and land in the disjoint ranges [2, 3), [1, 2), [0, 1),
    so comparing P is the same as comparing (P1, P2, Q) lexicographically.

    Weighted (the designer trades desirable conditions for accuracy, weight λ)::

        P = 2 + P1/(1 + P1)        if P1 > 0
        P = R/(R + [Q]),  R = Q + λ·P2     otherwise

    Parameters
    ----------
    criteria : Criteria
    objective : {'lexicographic', 'weighted'}
    q_ref : float
        The required accuracy [Q] (> 0); only scales the Q range.
    p2_weight : float
        λ of the weighted form.

    Returns
    -------
    ndarray, shape (D,)
        Finite for every design; a design with undefined Q (NaN) ranks last among those of
        its class.
    """
    p1 = np.asarray(criteria.p1, dtype=float)
    p2 = np.nan_to_num(np.asarray(criteria.p2, dtype=float), nan=np.inf)
    q = np.nan_to_num(np.asarray(criteria.q, dtype=float), nan=np.inf)
    with np.errstate(invalid="ignore"):
        infeasible = 2.0 + _squash(p1)
        if objective == "weighted":
            r = q + p2_weight * p2
            feasible = np.where(np.isfinite(r), r / (r + q_ref), 1.0 - 1e-16)
        else:
            feasible = np.where(p2 > 0, 1.0 + _squash(p2),
                                np.where(np.isfinite(q), q / (q + q_ref), 1.0 - 1e-16))
    return np.where(p1 > 0, infeasible, feasible)


def _squash(t: FloatArray) -> FloatArray:
    """t ↦ t/(1 + t), with +inf ↦ a value just below 1."""
    return np.where(np.isfinite(t), t / (1.0 + np.where(np.isfinite(t), t, 0.0)), 1.0 - 1e-16)
