"""Independent check of a design: n(θ) from a plain circle-intersection construction.

Nothing here uses the ratio formula (7) or the closure (5): the crank pin is placed at
``e·u(θ)``, the rocker end is the intersection of the circles of radius c about the crank pin
and r about the rocker pivot (:func:`assur.solve_rrr`, the branch with the rocker end to the
left of the line from crank pin to rocker pivot, which is the paper's branch), and the
rocker angle is read from that point. The ratio n = dφ/dθ is a fourth-order central
difference of the rocker angle, on a dense periodic grid over the turn and on a short
stencil at the angles that matter (the peak, refined by a bounded scalar search, and the
zone ends).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import cast

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from assur import solve_rrr
from assur.kinematics.dyads import DyadSolution
from assur.typing import ComplexArray, FloatArray
from synthesis.cases.fourbar_velocity_ratio.conditions import Design

__all__ = ["CheckResult", "check_design", "grashof_type", "ratio_by_construction"]

_STENCIL = 2e-4
_BRANCH = 1.0


@dataclass
class CheckResult:
    """What the construction says about a design (angles in radians).

    Attributes
    ----------
    passed : bool
        Every item below within its tolerance.
    failures : list of (str, dict)
        Failed items as a code and the numbers that go with it (the report words them).
    """

    passed: bool
    failures: list[tuple[str, dict[str, float | str]]] = field(default_factory=list)
    peak: float = math.nan
    peak_angle: float = math.nan
    ratio_theta1: float = math.nan
    ratio_theta3: float = math.nan
    zone_low: float = math.nan
    assembles: bool = False
    worst_margin: float = math.nan
    grashof: str = ""
    grashof_excess: float = math.nan
    min_transmission: float = math.nan
    min_transmission_angle: float = math.nan
    samples: int = 0
    value_tol: float = 0.0
    angle_tol: float = 0.0

    def as_dict(self) -> dict[str, object]:
        """Plain values for JSON (angles in degrees)."""
        return {"passed": self.passed,
                "failures": [{"item": code, **values} for code, values in self.failures],
                "peak": self.peak, "peak_angle_deg": math.degrees(self.peak_angle),
                "ratio_theta1": self.ratio_theta1, "ratio_theta3": self.ratio_theta3,
                "zone_low": self.zone_low, "assembles": self.assembles,
                "worst_margin": self.worst_margin, "grashof": self.grashof,
                "grashof_excess": self.grashof_excess,
                "min_transmission_deg": math.degrees(self.min_transmission),
                "min_transmission_at_deg": math.degrees(self.min_transmission_angle),
                "samples": self.samples, "value_tol": self.value_tol,
                "angle_tol_deg": math.degrees(self.angle_tol)}


def _rocker_end(e: float, c: float, r: float, theta: ArrayLike) -> DyadSolution:
    """The dyad solution (rocker end and existence) at crank angles θ."""
    crank_pin = e * np.exp(1j * np.asarray(theta, dtype=float))
    return solve_rrr(crank_pin, 1.0 + 0.0j, c, r, _BRANCH)


def _points(dyad: DyadSolution) -> ComplexArray:
    """The rocker ends of :func:`_rocker_end`: an array, since its arguments are arrays."""
    return cast(ComplexArray, dyad.c)


def _rocker_angle(end: ComplexArray) -> FloatArray:
    """φ from the rocker end: the rocker points along (−sin φ, cos φ) = i·u(φ)."""
    return np.angle((end - 1.0) / 1j)


def _difference(phi: FloatArray, step: float, axis: int = -1) -> FloatArray:
    """Fourth-order central difference of an angle on a periodic grid (wrap-safe)."""
    def shift(k: int) -> FloatArray:
        turn: FloatArray = np.angle(np.exp(1j * (np.roll(phi, -k, axis=axis) - phi)))
        return turn

    derivative: FloatArray = (8.0 * (shift(1) - shift(-1))
                                       - (shift(2) - shift(-2))) / (12.0 * step)
    return derivative


def ratio_by_construction(e: float, c: float, r: float, theta: ArrayLike,
                          step: float = _STENCIL) -> FloatArray:
    """n(θ) at given crank angles from the construction, by a five-point stencil.

    NaN where the dyad does not assemble at a stencil point.
    """
    theta = np.asarray(theta, dtype=float)
    offsets = np.array([-2.0, -1.0, 0.0, 1.0, 2.0]) * step
    end = _points(_rocker_end(e, c, r, theta[..., None] + offsets))
    return _difference(_rocker_angle(end), step)[..., 2]


def grashof_type(e: float, c: float, r: float) -> tuple[str, float]:
    """Grashof type of the four-bar (frame 1, crank e, coupler c, rocker r).

    Returns
    -------
    kind : str
        ``crank-rocker``, ``double-crank``, ``double-rocker``, ``rocker-crank`` (shortest link
        the rocker), ``change-point`` or ``non-Grashof``.
    excess : float
        ``p + q − s − l`` (positive for a Grashof linkage).
    """
    lengths = {"frame": 1.0, "crank": e, "coupler": c, "rocker": r}
    ordered = sorted(lengths.items(), key=lambda item: item[1])
    excess = ordered[1][1] + ordered[2][1] - ordered[0][1] - ordered[3][1]
    if abs(excess) <= 1e-12:
        return "change-point", excess
    if excess < 0:
        return "non-Grashof", excess
    shortest = ordered[0][0]
    kind = {"crank": "crank-rocker", "frame": "double-crank", "coupler": "double-rocker",
            "rocker": "rocker-crank"}[shortest]
    return kind, excess


def check_design(design: Design, *, samples: int = 4096, value_tol: float = 1e-7,
                 angle_tol: float = 1e-5) -> CheckResult:
    """Check a design against its request by the construction.

    Parameters
    ----------
    design : Design
        The design and the zone it was made for.
    samples : int
        Crank positions over the turn.
    value_tol : float
        Allowed relative error of the peak and of the end values (relative to |n*|).
    angle_tol : float
        Allowed error of the location of the peak (radians).

    Returns
    -------
    CheckResult
        The measured quantities and the verdict.
    """
    d = design
    sign = 1.0 if d.n_star > 0 else -1.0
    out = CheckResult(passed=False, samples=samples, value_tol=value_tol, angle_tol=angle_tol)
    out.grashof, out.grashof_excess = grashof_type(d.e, d.c, d.r)
    if out.grashof != "crank-rocker":
        out.failures.append(("grashof", {"kind": out.grashof}))

    step = 2.0 * np.pi / samples
    theta = d.theta2 - np.pi + step * np.arange(samples)
    dyad = _rocker_end(d.e, d.c, d.r, theta)
    out.assembles = bool(np.all(dyad.exists))
    out.worst_margin = float(np.min(dyad.margin))
    if not out.assembles:
        first = int(np.argmin(dyad.exists))
        out.failures.append(("assembly", {"theta_deg": math.degrees(theta[first]) % 360.0,
                                          "reason_code": int(dyad.reason[first])}))
        return out

    end = _points(dyad)
    crank_pin = d.e * np.exp(1j * theta)
    coupler, rocker = end - crank_pin, end - 1.0
    sine = np.abs((np.conj(coupler) * rocker).imag) / (np.abs(coupler) * np.abs(rocker))
    mu = np.arcsin(np.clip(sine, 0.0, 1.0))
    worst = int(np.argmin(mu))
    out.min_transmission, out.min_transmission_angle = float(mu[worst]), float(
        theta[worst] % (2 * np.pi))

    n = _difference(_rocker_angle(end), step)
    top = int(np.argmax(sign * n))

    def minus_ratio(angle: float) -> float:
        return float(-sign * ratio_by_construction(d.e, d.c, d.r, angle))

    best = minimize_scalar(minus_ratio, bounds=(theta[top] - step, theta[top] + step),
                           method="bounded", options={"xatol": 1e-12})
    out.peak, out.peak_angle = -sign * float(best.fun), float(best.x) % (2 * np.pi)
    out.ratio_theta1, out.ratio_theta3 = (float(v) for v in ratio_by_construction(
        d.e, d.c, d.r, np.array([d.theta1, d.theta3])))
    inside = (theta > d.theta1) & (theta < d.theta3)
    out.zone_low = float(sign * np.min(sign * n[inside])) if inside.any() else out.ratio_theta1

    scale = abs(d.n_star)
    if abs(out.peak - d.n_star) > value_tol * scale:
        out.failures.append(("peak_value", {"found": out.peak, "wanted": d.n_star}))
    miss = abs(math.remainder(out.peak_angle - d.theta2, 2 * math.pi))
    if miss > angle_tol:
        out.failures.append(("peak_angle", {"found_deg": math.degrees(out.peak_angle),
                                            "wanted_deg": math.degrees(d.theta2) % 360.0}))
    for code, found in (("end_theta1", out.ratio_theta1), ("end_theta3", out.ratio_theta3)):
        if abs(found - d.n_end) > value_tol * scale:
            out.failures.append((code, {"found": found, "wanted": d.n_end}))
    if sign * out.zone_low < abs(d.n_end) * (1.0 - value_tol):
        out.failures.append(("zone_band", {"found": out.zone_low, "wanted": d.n_end}))
    out.passed = not out.failures
    return out
