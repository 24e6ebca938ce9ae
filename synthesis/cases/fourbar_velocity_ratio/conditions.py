"""The synthesis conditions of the case, in the paper's form and in its two variants.

A request prescribes the peak ratio n* (its maximum over the stroke; n* < 0 asks for the
return stroke, where the peak is the most negative ratio), the zone before the peak ψ′ and
two of the three quantities e, δ, ψ″. The ratio must reach n* at θ2, be stationary there, and
fall to the end value ``n_end = n*·(1 − δ)`` at θ1 = θ2 − ψ′ (14) and θ3 = θ2 + ψ″ (15):

=========  ===================  ==================  =========================
form       given                found               conditions
=========  ===================  ==================  =========================
``paper``  e, n*, δ, ψ′         c, r, θ2 (then ψ″)  (9)/(18), (11)/(19), (12)/(20)
``delta``  e, n*, ψ′, ψ″        c, r, θ2, δ         the above and (13)
``crank``  n*, δ, ψ′, ψ″        c, r, θ2, e         the above and (13)
=========  ===================  ==================  =========================

The paper's functions (18)–(20) are written here as re-derived from (7) and (8): (19) has
``− e·sin θ2``, (20) uses the end value and θ1, φ1, and (13) has ``cos φ3`` in its denominator.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from assur import AssurError
from assur.text import Message
from assur.typing import FloatArray
from synthesis.cases.fourbar_velocity_ratio.kinematics import (
    as_real,
    grashof_margin,
    ratio_and_derivative,
    rocker_angle,
    velocity_ratio,
)

__all__ = [
    "FORMS",
    "Design",
    "NoSolution",
    "Request",
    "condition_residuals",
    "design_defect",
    "design_from_unknowns",
    "form_residuals",
    "paper_functions",
    "ratio_function",
    "stationarity_function",
    "zone_end",
]

FORMS = ("paper", "delta", "crank")
_ZONE_STEPS = 720
_PEAK_SAMPLES = 2880
_ANGLE_TOL = 1e-7


class NoSolution(AssurError):
    """No crank-rocker can satisfy the request; ``message`` says why (in both languages).

    Parameters
    ----------
    message : Message
        The reason.
    """

    def __init__(self, message: Message) -> None:
        self.message = message
        super().__init__(str(message))


@dataclass(frozen=True)
class Request:
    """A design request (angles in radians).

    Parameters
    ----------
    n_star : float
        Prescribed peak of the velocity ratio (n* > 0 forward stroke, n* < 0 return stroke).
    psi1 : float
        Zone before the peak, ψ′ = θ2 − θ1.
    e, delta, psi2 : float or None
        Crank length, allowed relative variation δ and zone after the peak ψ″; exactly one of
        them is left out (None) and found by the synthesis.
    """

    n_star: float
    psi1: float
    e: float | None = None
    delta: float | None = None
    psi2: float | None = None

    @property
    def form(self) -> str:
        """``'paper'`` (ψ″ found), ``'delta'`` (δ found) or ``'crank'`` (e found)."""
        if self.psi2 is None:
            return "paper"
        return "delta" if self.delta is None else "crank"

    @property
    def sign(self) -> float:
        """+1 on the forward stroke, −1 on the return stroke."""
        return 1.0 if self.n_star > 0 else -1.0

    def check(self) -> None:
        """Raise :class:`NoSolution` when no crank-rocker can meet the request.

        Raises
        ------
        NoSolution
            With every reason found, e.g. n* ≥ 1 on the forward stroke.
        """
        missing = [name for name, value in (("e", self.e), ("delta", self.delta),
                                            ("psi2", self.psi2)) if value is None]
        if len(missing) != 1:
            raise NoSolution(Message("case.fourbar.unknowns",
                                     {"missing": ", ".join(missing) or "—"}))
        reasons = []
        if not math.isfinite(self.n_star) or self.n_star == 0.0:
            reasons.append(Message("case.fourbar.n_star_zero", {"n_star": self.n_star}))
        elif self.n_star >= 1.0:
            reasons.append(Message("case.fourbar.forward_ge_one", {"n_star": self.n_star}))
        if self.e is not None and not 0.0 < self.e < 1.0:
            reasons.append(Message("case.fourbar.crank_range", {"e": self.e}))
        if self.delta is not None and not 0.0 < self.delta < 1.0:
            reasons.append(Message("case.fourbar.delta_range", {"delta": self.delta}))
        for name, value in (("ψ′", self.psi1), ("ψ″", self.psi2)):
            if value is not None and not 0.0 < value < math.pi:
                reasons.append(Message("case.fourbar.zone_range",
                                       {"name": name, "value": math.degrees(value)}))
        if reasons:
            details = reasons[-1]
            for reason in reversed(reasons[:-1]):
                details = Message("case.common.joined", {"first": reason, "rest": details})
            raise NoSolution(Message("case.fourbar.no_such_mechanism", {"details": details}))


@dataclass(frozen=True)
class Design:
    """A synthesised crank-rocker and the zone it was designed for (angles in radians)."""

    e: float
    c: float
    r: float
    theta2: float
    n_star: float
    delta: float
    psi1: float
    psi2: float

    @property
    def n_end(self) -> float:
        """The ratio at the ends of the zone, n*(1 − δ)."""
        return self.n_star * (1.0 - self.delta)

    @property
    def theta1(self) -> float:
        """Start of the zone, (14)."""
        return self.theta2 - self.psi1

    @property
    def theta3(self) -> float:
        """End of the zone, (15)."""
        return self.theta2 + self.psi2

    def as_dict(self) -> dict[str, float]:
        """Plain numbers for reports (angles in degrees)."""
        return {"e": self.e, "c": self.c, "r": self.r, "n_star": self.n_star,
                "delta": self.delta, "n_end": self.n_end,
                "theta1_deg": math.degrees(self.theta1), "theta2_deg": math.degrees(self.theta2),
                "theta3_deg": math.degrees(self.theta3), "psi1_deg": math.degrees(self.psi1),
                "psi2_deg": math.degrees(self.psi2)}


def stationarity_function(e: ArrayLike, r: ArrayLike, n: ArrayLike, theta: ArrayLike,
                          phi: ArrayLike) -> NDArray[np.floating]:
    """F1 of (18): (9) cleared of fractions; zero where (7) equals n and (8) holds.

    ``F1 = e·r·(1 − n)²·sin(θ − φ) + e·cos θ + r·n²·sin φ``.
    """
    e, r, n, theta, phi = (as_real(v) for v in (e, r, n, theta, phi))
    f1: NDArray[np.floating] = (e * r * (1.0 - n) ** 2 * np.sin(np.subtract(theta, phi))
                                + e * np.cos(theta) + r * np.square(n) * np.sin(phi))
    return f1


def ratio_function(e: ArrayLike, r: ArrayLike, n: ArrayLike, theta: ArrayLike,
                   phi: ArrayLike) -> NDArray[np.floating]:
    """F2 of (19) and F3 of (20): (7) = n cleared of fractions.

    ``F = e·r·(1 − n)·cos(θ − φ) − e·sin θ + r·n·cos φ``, which equals
    ``r·[e·cos(θ − φ) − cos φ]·(n(θ) − n)``.
    """
    e, r, n, theta, phi = (as_real(v) for v in (e, r, n, theta, phi))
    f: NDArray[np.floating] = (e * r * (1.0 - n) * np.cos(np.subtract(theta, phi))
                               - e * np.sin(theta) + r * n * np.cos(phi))
    return f


def paper_functions(e: ArrayLike, n_star: float, delta: float, psi1: float, c: ArrayLike,
                    r: ArrayLike, theta2: ArrayLike) -> tuple[NDArray[np.floating], ...]:
    """The paper's F1, F2, F3 (18)–(20) with φ2, φ1 from (10), (16) and θ1 from (14)."""
    phi2, _ = rocker_angle(e, c, r, theta2)
    theta1 = np.subtract(theta2, psi1)
    phi1, _ = rocker_angle(e, c, r, theta1)
    n_end = n_star * (1.0 - delta)
    return (stationarity_function(e, r, n_star, theta2, phi2),
            ratio_function(e, r, n_star, theta2, phi2),
            ratio_function(e, r, n_end, theta1, phi1))


def zone_end(e: float, c: float, r: float, theta2: float, level: float, sign: float,
             direction: float = 1.0) -> float:
    """The first crank angle after (direction +1) or before (−1) θ2 where the ratio falls to
    ``level``; NaN if it never does within a turn.

    Parameters
    ----------
    level : float
        The end value n*(1 − δ).
    sign : float
        +1 on the forward stroke (the ratio falls below the level), −1 on the return stroke.
    """
    steps = theta2 + direction * np.linspace(0.0, 2.0 * np.pi, _ZONE_STEPS + 1)
    phi, exists = rocker_angle(e, c, r, steps)
    excess = sign * (velocity_ratio(e, r, steps, phi) - level)
    below = np.flatnonzero(~(excess > 0.0))
    if below.size == 0 or below[0] == 0 or not exists[:below[0] + 1].all():
        return math.nan

    def gap(theta: float) -> float:
        angle, _ = rocker_angle(e, c, r, theta)
        return float(velocity_ratio(e, r, theta, angle) - level)

    ends = sorted((float(steps[below[0] - 1]), float(steps[below[0]])))
    return float(brentq(gap, *ends, xtol=1e-15, rtol=4 * np.finfo(float).eps))


def condition_residuals(design: Design) -> dict[str, float]:
    """Every condition of the case at a design, in two forms.

    The ratio form (values of n and dn/dθ, to be compared with n*, 0 and n_end) and the
    paper's cleared form (18)–(20) with (13) as F4.

    Returns
    -------
    dict
        ``n(θ2) − n*`` (7)/(11), ``dn/dθ(θ2)`` (8), ``n(θ1) − n_end`` (12),
        ``n(θ3) − n_end`` (13), ``F1``…``F4``.
    """
    d = design
    angles = np.array([d.theta1, d.theta2, d.theta3])
    n, dn, phi, _ = ratio_and_derivative(d.e, d.c, d.r, angles)
    return {
        "n(θ2) − n*": float(n[1] - d.n_star),
        "dn/dθ(θ2)": float(dn[1]),
        "n(θ1) − n_end": float(n[0] - d.n_end),
        "n(θ3) − n_end": float(n[2] - d.n_end),
        "F1": float(stationarity_function(d.e, d.r, d.n_star, angles[1], phi[1])),
        "F2": float(ratio_function(d.e, d.r, d.n_star, angles[1], phi[1])),
        "F3": float(ratio_function(d.e, d.r, d.n_end, angles[0], phi[0])),
        "F4": float(ratio_function(d.e, d.r, d.n_end, angles[2], phi[2])),
    }


def form_residuals(request: Request, x: ArrayLike) -> FloatArray:
    """The conditions of the request's form at unknowns ``x``, in ratio form scaled by |n*|.

    ``x`` is ``(c, r, θ2)`` for the paper's form, ``(c, r, θ2, δ)`` for ``delta`` and
    ``(c, r, θ2, e)`` for ``crank``; a leading axis of candidates broadcasts
    (``x`` of shape ``(k, D)`` gives ``(k, D)``); ``np.longdouble`` input is evaluated in
    extended precision.
    """
    x = np.asarray(x)
    if not np.issubdtype(x.dtype, np.floating):
        x = x.astype(float)
    c, r, theta2 = x[0], x[1], x[2]
    e = x[3] if request.e is None else request.e
    delta = x[3] if request.delta is None else request.delta
    angles = [theta2, theta2 - request.psi1]
    if request.form != "paper":
        angles.append(theta2 + request.psi2)
    theta = np.stack(np.broadcast_arrays(*angles))
    n, dn, _, _ = ratio_and_derivative(e, c, r, theta)
    n_end = request.n_star * (1.0 - delta)
    rows = [n[0] - request.n_star, dn[0], *(n[k] - n_end for k in range(1, len(angles)))]
    return np.stack(rows) / abs(request.n_star)


def design_from_unknowns(request: Request, x: ArrayLike) -> Design:
    """The design for the unknowns of :func:`form_residuals`; ψ″ of the paper's form is found
    from (13) as the first angle after θ2 where the ratio is back at the end value."""
    c, r, theta2, *rest = (float(v) for v in np.asarray(x, dtype=float))
    e = rest[0] if request.e is None else request.e
    delta = rest[0] if request.delta is None else request.delta
    psi2 = request.psi2
    if psi2 is None:
        theta3 = zone_end(e, c, r, theta2, request.n_star * (1.0 - delta), request.sign)
        psi2 = theta3 - theta2
    return Design(e=e, c=c, r=r, theta2=theta2, n_star=request.n_star, delta=delta,
                  psi1=request.psi1, psi2=psi2)


def design_defect(design: Design, accuracy: float = 1e-9) -> Message | None:
    """Why a root of the conditions is not the design asked for; None if it is.

    A root of (18)–(20) can sit on a minimum of the ratio, on a local peak lower than the
    stroke's maximum, outside the crank-rocker domain, or have the ratio leave the band
    ``[n_end, n*]`` inside the zone; each is named.

    Parameters
    ----------
    design : Design
        A root of the conditions.
    accuracy : float
        Relative accuracy of the root: a higher peak elsewhere must exceed n* by more than
        this, a zone end must miss θ1 or θ3 by more than ``100·accuracy`` radians (at least
        1e-7).
    """
    d = design
    margin = float(grashof_margin(d.e, d.c, d.r))
    if margin <= 0.0:
        return Message("case.fourbar.not_grashof", {"margin": margin})
    sign = 1.0 if d.n_star > 0 else -1.0
    theta = d.theta2 + np.linspace(-np.pi, np.pi, _PEAK_SAMPLES + 1)
    n, _, _, exists = ratio_and_derivative(d.e, d.c, d.r, theta)
    if not exists.all():
        return Message("case.fourbar.no_closure")
    step = 1e-4
    _, slope, _, _ = ratio_and_derivative(d.e, d.c, d.r, d.theta2 + np.array([-step, step]))
    if sign * (slope[1] - slope[0]) >= 0.0:
        return Message("case.fourbar.trough")
    peak = float(np.max(sign * n))
    if peak > abs(d.n_star) * (1.0 + accuracy):
        at = math.degrees(float(theta[np.argmax(sign * n)]) % (2 * math.pi))
        return Message("case.fourbar.local_peak", {"peak": sign * peak, "at": at})
    for direction, edge in ((-1.0, d.theta1), (1.0, d.theta3)):
        end = zone_end(d.e, d.c, d.r, d.theta2, d.n_end, sign, direction)
        if not abs(end - edge) <= max(_ANGLE_TOL, 100.0 * accuracy):
            return Message("case.fourbar.leaves_band",
                           {"end": math.degrees(end), "edge": math.degrees(edge)})
    return None
