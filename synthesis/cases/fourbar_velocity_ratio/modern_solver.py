"""The modern solver: a vectorised scan of the design space for starting points, then
``scipy.optimize.root`` on the conditions in ratio form from every promising start.

The scan covers the whole Grashof crank-rocker domain: the rocker as ``r = r_min/u`` with
``r_min = max(e, e/|n*|)`` (every design has r ≥ e/|n*|, because n = ±e/r where crank and rocker
are parallel) and ``u ∈ (0, 1)``; the coupler as ``c = c_lo + t·(c_hi − c_lo)`` with
``t ∈ (0, 1)`` between the Grashof limits (spaced densely near both limits, down to about 5e-5
of the interval, because the peak becomes sharp and the design curve ends there); for the
``crank`` form also e ∈ (0, 1). At each grid design the peak of the ratio over the turn and
the zone widths at the end value are read from a sampled n(θ); the local minima of the
mismatch with the request are the starts. Every root is then classified
(:func:`~.conditions.design_defect`), so that the answer lists every distinct design that meets
the request, best transmission first, and names the roots that do not.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq, root

from assur.text import Message
from assur.typing import FloatArray
from synthesis.cases.fourbar_velocity_ratio.conditions import (
    Design,
    Request,
    design_defect,
    design_from_unknowns,
    form_residuals,
)
from synthesis.cases.fourbar_velocity_ratio.kinematics import (
    coupler_bounds,
    rocker_angle,
    transmission_angle,
    velocity_ratio,
)

__all__ = ["ModernResult", "attainable_zone", "min_transmission_angle", "solve_modern"]

_GRID = {"paper": (1, 40, 40), "delta": (1, 40, 40), "crank": (20, 24, 24)}
_SAMPLES = 360
_CHUNK = 4096
_CLUSTER = 5.0
_MAX_STARTS = 24
_ACCEPT = 1e-11


@dataclass
class ModernResult:
    """Outcome of :func:`solve_modern`.

    Attributes
    ----------
    designs : list of Design
        Every distinct design meeting the request, largest minimum transmission angle first.
    rejected : list of (Design, Message)
        Roots of the conditions that are not acceptable designs, with the reason.
    reason : Message or None
        Why there is no design, when ``designs`` is empty.
    evaluations : int
        Designs evaluated (grid points plus residual calls of the root finders).
    seconds : float
        Wall time.
    """

    request: Request
    designs: list[Design] = field(default_factory=list)
    rejected: list[tuple[Design, Message]] = field(default_factory=list)
    reason: Message | None = None
    evaluations: int = 0
    seconds: float = 0.0

    @property
    def design(self) -> Design | None:
        """The first (best) design, or None."""
        return self.designs[0] if self.designs else None


def min_transmission_angle(design: Design, samples: int = 1440) -> float:
    """Smallest transmission angle over the turn (radians), from (5) on a dense grid."""
    theta = np.linspace(0.0, 2.0 * np.pi, samples, endpoint=False)
    phi, _ = rocker_angle(design.e, design.c, design.r, theta)
    return float(np.min(transmission_angle(design.e, design.r, theta, phi)))


def _grid(request: Request) -> dict[str, FloatArray]:
    """Grid designs covering the crank-rocker domain, axes (e, u, t)."""
    count_e, count_u, count_t = _GRID[request.form]
    u = np.linspace(0.0, 1.0, count_u + 2)[1:-1]
    t = 0.5 + 0.5 * np.tanh(_CLUSTER * np.linspace(-1.0, 1.0, count_t))
    e = (np.linspace(0.0, 1.0, count_e + 2)[1:-1] if request.form == "crank"
         else np.array([request.e]))
    ee, uu, tt = np.meshgrid(e, u, t, indexing="ij")
    r = np.maximum(ee, ee / abs(request.n_star)) / uu
    lo, hi = coupler_bounds(ee, r)
    return {"e": ee, "c": lo + tt * (hi - lo), "r": r}


def _crossing(excess: FloatArray, peak: NDArray[np.intp], offset: NDArray[np.intp],
              direction: int) -> FloatArray:
    """Fractional number of samples from the peak to where ``excess`` first reaches zero
    (NaN where the sampled peak itself is below the level)."""
    count = excess.shape[-1]
    order = (peak[:, None] + direction * offset) % count
    walk = np.take_along_axis(excess, order, axis=1)
    below = walk <= 0.0
    first = np.where(below.any(axis=1), np.argmax(below, axis=1), count - 1)
    rows = np.arange(len(peak))
    high, low = walk[rows, np.maximum(first - 1, 0)], walk[rows, first]
    with np.errstate(invalid="ignore", divide="ignore"):
        part = high / (high - low)
    return np.where(first > 0, first - 1 + part, np.nan)


def _sample(request: Request, e: FloatArray, c: FloatArray,
            r: FloatArray) -> tuple[FloatArray, ...]:
    """Mismatch with the request at grid designs (flat arrays), the peak angle, the start
    value of the extra unknown, and the peak height."""
    samples = _SAMPLES
    step = 2.0 * np.pi / samples
    theta = np.arange(samples) * step
    phi, exists = rocker_angle(e[:, None], c[:, None], r[:, None], theta)
    n = velocity_ratio(e[:, None], r[:, None], theta, phi)
    target = abs(request.n_star)
    value = np.where(exists, request.sign * n, -np.inf)
    peak = np.argmax(value, axis=1)
    rows = np.arange(len(peak))
    height = value[rows, peak]
    mismatch = [(height - target) / target]
    offset = np.arange(samples)
    if request.delta is None:  # the 'delta' form: ψ″ given, δ found
        assert request.psi2 is not None
        shifts = np.array([-request.psi1, request.psi2]) / step
        ends = []
        for shift in shifts:
            low = np.floor(shift).astype(int)
            part = shift - low
            ends.append((1 - part) * value[rows, (peak + low) % samples]
                        + part * value[rows, (peak + low + 1) % samples])
        mismatch.append((ends[0] - ends[1]) / target)
        extra = 1.0 - ends[0] / target
    else:
        excess = value - target * (1.0 - request.delta)
        mismatch.append(_crossing(excess, peak, offset, -1) * step - request.psi1)
        if request.psi2 is not None:  # the 'crank' form: ψ″ given, e found
            mismatch.append(_crossing(excess, peak, offset, 1) * step - request.psi2)
        extra = e
    return np.stack(mismatch), theta[peak], extra, height


@dataclass
class _Scan:
    """The sampled grid: designs (axes e, u, t), mismatch fields, peak angle and height."""

    grid: dict[str, FloatArray]
    fields: FloatArray
    theta_peak: FloatArray
    extra: FloatArray
    height: FloatArray


def _scan(request: Request) -> _Scan:
    """Sample n(θ) at every grid design (in chunks) and measure the mismatch."""
    grid = _grid(request)
    shape = grid["e"].shape
    flat = {k: v.ravel() for k, v in grid.items()}
    parts = [_sample(request, *(flat[k][i:i + _CHUNK] for k in ("e", "c", "r")))
             for i in range(0, flat["e"].size, _CHUNK)]
    mismatch, theta_peak, extra, height = (np.concatenate(p, axis=-1) for p in zip(*parts))
    return _Scan(grid, mismatch.reshape(-1, *shape), theta_peak.reshape(shape),
                 extra.reshape(shape), height.reshape(shape))


def _cell_starts(request: Request, scan: _Scan) -> list[FloatArray]:
    """Centres of the grid cells in which every mismatch changes sign (``crank`` form)."""
    fields, shape = scan.fields, scan.grid["e"].shape
    lows, highs = np.full(fields.shape, np.inf), np.full(fields.shape, -np.inf)
    cell = (slice(None), slice(0, -1), slice(0, -1), slice(0, -1))
    for corner in np.ndindex(2, 2, 2):
        pick = (slice(None), *(slice(b, shape[k] - 1 + b) for k, b in enumerate(corner)))
        lows[cell] = np.minimum(lows[cell], fields[pick])
        highs[cell] = np.maximum(highs[cell], fields[pick])
    straddle = np.all((lows <= 0.0) & (highs >= 0.0) & np.isfinite(lows) & np.isfinite(highs),
                      axis=0)
    centre_mismatch = np.sqrt(np.sum(np.square(fields), axis=0))
    cells = np.argwhere(straddle)
    cells = cells[np.argsort(centre_mismatch[tuple(cells.T)])]
    kept: list[NDArray[np.intp]] = []
    for index in cells:
        if len(kept) < _MAX_STARTS and all(np.abs(index - other).max() > 1 for other in kept):
            kept.append(index)
    starts = []
    for index in kept:
        corners = [tuple(index + np.array(b)) for b in np.ndindex(2, 2, 2)]
        starts.append(np.array([np.mean([scan.grid["c"][p] for p in corners]),
                                np.mean([scan.grid["r"][p] for p in corners]),
                                _mean_angle([scan.theta_peak[p] for p in corners]),
                                np.mean([scan.extra[p] for p in corners])]))
    return starts


def _curve_seeds(request: Request, scan: _Scan
                 ) -> list[tuple[FloatArray, float, int]]:
    """Segments of the design curve (peak = n*) along which the reduced equation is
    followed: a point on each grid row of constant r with the r of the next row (axis 1),
    and the cap at the least rocker from one branch to the other in c (axis 0)."""
    gap = scan.fields[0, 0]
    r = scan.grid["r"][0, :, 0]
    seeds = []
    for i, j in np.argwhere((np.sign(gap[:, :-1]) != np.sign(gap[:, 1:]))
                            & np.isfinite(gap[:, :-1] + gap[:, 1:])):
        part = gap[i, j] / (gap[i, j] - gap[i, j + 1])
        c = (1 - part) * scan.grid["c"][0, i, j] + part * scan.grid["c"][0, i, j + 1]
        x = [c, r[i], scan.theta_peak[0, i, j if part < 0.5 else j + 1]]
        if request.form != "paper":
            x.append(scan.extra[0, i, j])
        for neighbour in (i - 1, i + 1):
            if 0 <= neighbour < len(r):
                seeds.append((np.array(x), float(r[neighbour]), 1))
    # the cap of the curve, where its two branches meet at the least rocker: follow it in c
    # from the small-c to the large-c crossing of the last row with both
    rows = [seed for seed in seeds if seed[0][1] == min(x[1] for x, _, _ in seeds)]
    if len({float(x[0]) for x, _, _ in rows}) > 1:
        low = min(rows, key=lambda seed: seed[0][0])[0]
        high = max(float(x[0]) for x, _, _ in rows)
        seeds.append((low, high, 0))
    return seeds


def _ranges(request: Request, scan: _Scan) -> dict[str, float]:
    """Peaks and zone widths seen on the grid, for the no-solution message."""
    height = scan.height[np.isfinite(scan.height)]
    ranges = {"peak_min": float(request.sign * np.min(height)) if height.size else math.nan,
              "peak_max": float(request.sign * np.max(height)) if height.size else math.nan}
    if request.form == "paper":
        peak_gap, width_gap = scan.fields[0, 0], scan.fields[1, 0]
        cross = (np.sign(peak_gap[:, :-1]) != np.sign(peak_gap[:, 1:])) & np.isfinite(
            peak_gap[:, :-1] + peak_gap[:, 1:] + width_gap[:, :-1] + width_gap[:, 1:])
        if cross.any():
            a, b = peak_gap[:, :-1][cross], peak_gap[:, 1:][cross]
            wa, wb = width_gap[:, :-1][cross], width_gap[:, 1:][cross]
            widths = wa + (wb - wa) * a / (a - b) + request.psi1
            widths = widths[widths > 0.0]
            if widths.size:
                ranges["psi1_min"], ranges["psi1_max"] = float(widths.min()), float(widths.max())
    return ranges


def _mean_angle(angles: list[float]) -> float:
    return float(np.angle(np.mean(np.exp(1j * np.asarray(angles)))))


class _Reduced:
    """The request reduced to one equation along the design curve.

    The curve is parametrised by one length, r (``axis = 1``) or c (``axis = 0``): for a
    given value the peak conditions (7) = n*, (8) fix the other length and θ2 (a
    well-conditioned 2×2 solve, continued from the last point); what is left is
    ``g = n(θ1) − n_end`` for the paper's form and ``g = n(θ1) − n(θ3)`` for ``delta`` (δ then
    follows from n(θ1)).
    """

    def __init__(self, request: Request, start: FloatArray, axis: int) -> None:
        self.request = request
        self.x = start.copy()
        self.free = [1 - axis, 2]
        self.axis = axis
        self.evaluations = 0

    def __call__(self, value: float) -> float:
        x = self.x.copy()
        x[self.axis] = value

        def peak_conditions(y: FloatArray) -> FloatArray:
            x[self.free] = y
            return form_residuals(self.request, x)[:2]

        solution = root(peak_conditions, self.x[self.free], method="hybr",
                        options={"xtol": 1e-14})
        self.evaluations += int(solution.nfev)
        x[self.free] = solution.x
        residual = form_residuals(self.request, x)
        if not (np.all(np.isfinite(residual)) and np.all(np.abs(residual[:2]) < _ACCEPT)):
            return math.nan
        if self.request.form == "delta":
            n_first = residual[2] * abs(self.request.n_star) + self.request.n_star * (1 - x[3])
            x[3] = 1.0 - n_first / self.request.n_star
            self.x = x
            return float(residual[2] - residual[3])
        self.x = x
        return float(residual[2])


def _roots_on_segment(request: Request, seed: FloatArray, end: float, xtol: float,
                      axis: int = 1, max_step: float = 0.03
                      ) -> tuple[list[FloatArray], int]:
    """Follow the design curve from a seed until r (``axis = 1``) or c (``axis = 0``) reaches
    ``end``, in relative steps of at most ``max_step``, and bisect (``brentq``) every sign
    change of the reduced equation."""
    reduced = _Reduced(request, seed, axis)
    start = float(seed[axis])
    value = reduced(start)
    steps = max(1, math.ceil(abs(math.log(end / start)) / max_step))
    roots = []
    for point in np.geomspace(start, end, steps + 1)[1:]:
        before = reduced.x
        following = reduced(float(point))
        if not (math.isfinite(value) and math.isfinite(following)):
            break
        if np.sign(following) != np.sign(value):
            after = reduced.x
            reduced.x = before
            try:
                found = brentq(reduced, start, float(point), xtol=xtol, rtol=max(xtol, 1e-15))
            except ValueError:  # the peak conditions lost their solution on the way
                break
            if math.isfinite(reduced(found)):
                roots.append(reduced.x.copy())
            reduced.x = after
        start, value = float(point), following
    return roots, reduced.evaluations


def _polish(request: Request, x0: FloatArray, xtol: float
            ) -> tuple[FloatArray, int]:
    """Newton-type polish (``hybr``) of all the unknowns together."""
    solution = root(lambda x: form_residuals(request, x), x0, method="hybr",
                    options={"xtol": xtol})
    return solution.x.copy(), int(solution.nfev)


def _no_design_reason(request: Request, ranges: dict[str, float]) -> Message:
    """Why the scan and the root finder found no design."""
    low, high = sorted((ranges["peak_min"], ranges["peak_max"]))
    if request.form != "crank" and not low <= request.n_star <= high:
        return Message("case.fourbar.peak_range", {"e": request.e, "n_star": request.n_star,
                                                   "low": low, "high": high})
    if "psi1_min" in ranges:
        values = {"e": request.e, "n_star": request.n_star, "delta": request.delta,
                  "psi1": math.degrees(request.psi1)}
        if request.psi1 > ranges["psi1_max"]:
            return Message("case.fourbar.zone_wide",
                           {**values, "edge": math.degrees(ranges["psi1_max"])})
        if request.psi1 < ranges["psi1_min"]:
            return Message("case.fourbar.zone_narrow",
                           {**values, "edge": math.degrees(ranges["psi1_min"])})
        return Message("case.fourbar.zone_gap", {**values, "low": math.degrees(ranges["psi1_min"]),
                                                 "high": math.degrees(ranges["psi1_max"])})
    return Message("case.fourbar.no_design")


def attainable_zone(request: Request) -> tuple[float, float] | None:
    """Estimated range of zones ψ′ before the peak that crank-rockers with the request's e,
    n* and δ reach (radians, from the grid scan; paper's form only); None if the scan finds
    no design with that peak.  Values inside the range may still fall in a gap between the
    branches of the design curve."""
    request.check()
    if request.form != "paper":
        raise ValueError("the zone range is defined for the paper's form (e, n*, δ, ψ′ given)")
    ranges = _ranges(request, _scan(request))
    return (ranges["psi1_min"], ranges["psi1_max"]) if "psi1_min" in ranges else None


def solve_modern(request: Request, *, xtol: float = 1e-13) -> ModernResult:
    """Find every crank-rocker that meets the request.

    Parameters
    ----------
    request : Request
        The design request (any of the three forms).
    xtol : float
        Tolerance on the unknowns: of the bisection of the reduced equation (``brentq``) and
        of the final polish (``scipy.optimize.root``, ``hybr``); a root is accepted when every
        condition holds to ``max(1e-11, 100·xtol)``.

    Returns
    -------
    ModernResult
        The designs (best first), the rejected roots, or the reason there is none.

    Raises
    ------
    NoSolution
        When the request is impossible on its face (e.g. n* ≥ 1 on the forward stroke).
    """
    request.check()
    clock = time.perf_counter()
    scan = _scan(request)
    evaluations = scan.height.size
    result = ModernResult(request)
    found: list[FloatArray] = []
    if request.form == "crank":
        candidates = _cell_starts(request, scan)
    else:
        candidates = []
        for seed, end, axis in _curve_seeds(request, scan):
            near, count = _roots_on_segment(request, seed, end, xtol, axis)
            candidates.extend(near)
            evaluations += count
    for x0 in candidates:
        x, count = _polish(request, x0, xtol)
        evaluations += count
        residual = form_residuals(request, x)
        if not np.all(np.abs(residual) < max(_ACCEPT, 100.0 * xtol)):
            continue
        x[2] = x[2] % (2.0 * np.pi)
        if any(np.allclose(x, other, rtol=0.0, atol=1e-7) for other in found):
            continue
        found.append(x)
        design = design_from_unknowns(request, x)
        defect = design_defect(design, accuracy=max(1e-9, xtol))
        if defect is None:
            result.designs.append(design)
        else:
            result.rejected.append((design, defect))
    result.designs.sort(key=min_transmission_angle, reverse=True)
    if not result.designs:
        result.reason = _no_design_reason(request, _ranges(request, scan))
    result.evaluations = evaluations
    result.seconds = time.perf_counter() - clock
    return result
