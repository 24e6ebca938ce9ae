"""Existence of every dyad kind against an exact decision, over 10⁵ random designs per kind.

Lengths are log-uniform over 1e-3 … 1e6 mm (so one group may hold lengths 1e9 apart), the
group is placed anywhere from 1e-3 to 1e6 mm from the origin, and half of the designs are put
near a limit of existence, as close as the rounding of their coordinates allows. The test
decides existence independently of the solvers: L1–L3 in exact integer arithmetic on the
float inputs (each input is an integer times one common power of two, and every condition is
compared squared, so no square root is taken); L4 and L5, whose condition is on the sine of
an angle, by reducing the exact angle (a rational number) by a multiple of π known to 50
digits, where the sine is the angle to 1e-12 relative.

A solver must agree with that decision on every design but those inside the tolerance band
``|deficit| <= ROUNDOFF·size`` of the boundary (which it reads as the toggle itself); the band
is counted. Inside the band the solver must read the design as assembling, except within
4·ε of the band's edge. On every design that assembles, the group's constraints hold to 1e-9
of the group's size (plus the rounding of coordinates far from the origin).
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import numpy as np
import pytest

from assur.kinematics.dyads import (
    ROUNDOFF,
    Reason,
    solve_prp,
    solve_rpp,
    solve_rpr,
    solve_rrp,
    solve_rrr,
)

DESIGNS = 100_000
EPS = np.finfo(float).eps
SLACK = 4 * EPS  # rounding of the solver's deficit, relative to the group's size
CLOSURE = 1e-9
PI = Fraction("3.14159265358979323846264338327950288419716939937510582097494459")


# --- random designs -----------------------------------------------------------------------

def log_uniform(rng: np.random.Generator, low: float, high: float, n: int) -> np.ndarray:
    return np.exp(rng.uniform(np.log(low), np.log(high), n))


def near(rng: np.random.Generator, limit: np.ndarray) -> np.ndarray:
    """Half generic values up to twice ``limit`` (down to 1e-9 of it), half just at it."""
    n = limit.size
    generic = limit * 10.0 ** rng.uniform(-9.0, 0.3, n)
    nudged = limit * (1.0 + rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(-17.0, -1.0, n))
    return np.where(rng.random(n) < 0.5, generic, nudged)


def places(rng: np.random.Generator, n: int) -> np.ndarray:
    """Points from 1e-3 to 1e6 mm away from the origin, in any direction."""
    return log_uniform(rng, 1e-3, 1e6, n) * np.exp(2j * np.pi * rng.random(n))


def direction(rng: np.random.Generator, n: int) -> np.ndarray:
    return np.exp(1j * rng.uniform(-np.pi, np.pi, n))


def integers(*arrays: np.ndarray) -> tuple[list[np.ndarray], int]:
    """Float arrays as exact integers: ``x = n·2^-k`` with one k for all (object arrays)."""
    parts = [np.frexp(a) for a in arrays]
    k = 53 - min(int(e.min()) for _, e in parts)
    return [(np.ldexp(m, 53).astype(np.int64).astype(object)
             << (e.astype(np.int64) + (k - 53)).astype(object)) for m, e in parts], k


def to_float(n: np.ndarray, k: int) -> np.ndarray:
    """Object array of integers scaled by 2^k → floats (correctly rounded)."""
    return np.ldexp(n.astype(float), -k)


@cache
def designs(kind: str) -> dict:
    """Arguments of ``DESIGNS`` designs of ``kind``, the exact decision, the relative deficit
    (negative where the exact decision fails) and the group's size."""
    rng = np.random.default_rng({"RRR": 1, "RRP": 2, "RPR": 3, "PRP": 4, "RPP": 5}[kind])
    n = DESIGNS
    return {"RRR": rrr_designs, "RRP": rrp_designs, "RPR": rpr_designs,
            "PRP": prp_designs, "RPP": rpp_designs}[kind](rng, n)


def rrr_designs(rng: np.random.Generator, n: int) -> dict:
    l_i, l_j = log_uniform(rng, 1e-3, 1e6, n), log_uniform(rng, 1e-3, 1e6, n)
    limit = np.where(rng.random(n) < 0.5, l_i + l_j, np.abs(l_i - l_j))
    h_i = places(rng, n)
    h_j = h_i + near(rng, limit) * direction(rng, n)
    sigma = rng.choice([-1.0, 1.0], n)
    (xi, yi, xj, yj, li, lj), k = integers(h_i.real, h_i.imag, h_j.real, h_j.imag, l_i, l_j)
    d2 = (xj - xi) ** 2 + (yj - yi) ** 2
    stretch2, fold2 = (li + lj) ** 2 - d2, d2 - (li - lj) ** 2  # signs of the two deficits
    exact = (stretch2 >= 0) & (fold2 >= 0) & (d2 > 0)
    d = np.abs(h_j - h_i)
    size = l_i + l_j + d  # the perimeter of the triangle H_i C H_j
    # deficit = min(l_i + l_j − d, d − |l_i − l_j|) from the exact squared forms
    deficit = np.minimum(to_float(stretch2, 2 * k) / (l_i + l_j + d),
                         to_float(fold2, 2 * k) / (d + np.abs(l_i - l_j)))
    return {"args": (h_i, h_j, l_i, l_j, sigma), "exact": exact.astype(bool),
            "deficit": deficit / size, "size": size, "places": np.abs(h_i) + np.abs(h_j)}


def rrp_designs(rng: np.random.Generator, n: int) -> dict:
    l_j = log_uniform(rng, 1e-3, 1e6, n)
    theta = rng.uniform(-np.pi, np.pi, n)
    e = rng.choice([-1.0, 0.0, 1.0], n) * log_uniform(rng, 1e-3, 1e6, n)
    a = places(rng, n)
    h = rng.choice([-1.0, 1.0], n) * near(rng, l_j)  # offset of H_j from the path of C
    p = rng.choice([-1.0, 1.0], n) * log_uniform(rng, 1e-3, 1e6, n)
    u = np.cos(theta) + 1j * np.sin(theta)  # the guide direction, as the solver reads θ
    h_j = a + (p + 1j * (h + e)) * u
    sigma = rng.choice([-1.0, 1.0], n)
    (xa, ya, xj, yj, ee, lj, cu, su), k = integers(a.real, a.imag, h_j.real, h_j.imag, e, l_j,
                                                   u.real, u.imag)
    offset = cu * (yj - ya) - su * (xj - xa) - (ee << k)  # h·2^(2k), exactly
    reach2 = (lj << k) ** 2 - offset ** 2  # (l_j² − h²)·2^(4k)
    exact = reach2 >= 0
    habs = np.abs(to_float(offset, 2 * k))
    size = l_j + np.abs(h_j - a) + np.abs(e)
    deficit = to_float(reach2, 4 * k) / (l_j + habs)
    return {"args": (h_j, a, theta, e, l_j, sigma), "exact": exact.astype(bool),
            "deficit": deficit / size, "size": size, "places": np.abs(h_j) + np.abs(a)}


def rpr_designs(rng: np.random.Generator, n: int) -> dict:
    rho = log_uniform(rng, 1e-3, 1e6, n)
    h_i = places(rng, n)
    h_j = h_i + rho * direction(rng, n)
    h = rng.choice([-1.0, 1.0], n) * near(rng, rho)
    sigma = rng.choice([-1.0, 0.0, 1.0], n)
    (xi, yi, xj, yj, hh), k = integers(h_i.real, h_i.imag, h_j.real, h_j.imag, h)
    rho2 = (xj - xi) ** 2 + (yj - yi) ** 2
    reach2 = rho2 - hh ** 2
    exact = (reach2 >= 0) & (rho2 > 0)
    distance = np.abs(h_j - h_i)
    size = distance + np.abs(h)
    deficit = to_float(reach2, 2 * k) / (distance + np.abs(h))
    return {"args": (h_i, h_j, h, sigma), "exact": exact.astype(bool),
            "deficit": deficit / size, "size": size, "places": np.abs(h_i) + np.abs(h_j)}


def parallel(rng: np.random.Generator, n: int) -> np.ndarray:
    """Angles between two guides: half generic, half within 1e-17 … 1e-1 of 0 or ±π."""
    close = rng.choice([-np.pi, 0.0, np.pi], n) + rng.choice([-1.0, 1.0], n) * 10.0 ** (
        rng.uniform(-17.0, -1.0, n))
    return np.where(rng.random(n) < 0.5, rng.uniform(-np.pi, np.pi, n), close)


def sine_margin(first: np.ndarray, second: np.ndarray) -> np.ndarray:
    """``|sin(second − first)| − ROUNDOFF`` of the exact difference of the float angles.

    Where the float sine is far from ``ROUNDOFF`` it decides; elsewhere the exact difference
    (a rational) is reduced by the nearest multiple of π, and |sin x| = |x|(1 − x²/6 …) is |x|
    to 1e-12 relative.
    """
    margin = np.abs(np.sin(second - first)) - ROUNDOFF
    for k in np.flatnonzero(np.abs(margin) < 1e-6):
        angle = Fraction(float(second[k])) - Fraction(float(first[k]))
        x = angle - round(angle / PI) * PI
        margin[k] = float(abs(x)) - ROUNDOFF
    return margin


def prp_designs(rng: np.random.Generator, n: int) -> dict:
    theta_i = rng.uniform(-np.pi, np.pi, n)
    theta_j = theta_i + parallel(rng, n)
    a, b = places(rng, n), places(rng, n)
    e_i, e_j = (rng.choice([-1.0, 1.0], n) * log_uniform(rng, 1e-3, 1e6, n) for _ in "ij")
    margin = sine_margin(theta_i, theta_j)
    size = np.abs(b - a) + np.abs(e_i) + np.abs(e_j)
    return {"args": (a, theta_i, e_i, b, theta_j, e_j), "exact": margin > 0,
            "deficit": margin, "size": size, "places": np.abs(a) + np.abs(b)}


def rpp_designs(rng: np.random.Generator, n: int) -> dict:
    gamma = parallel(rng, n)
    h_j, a = places(rng, n), places(rng, n)
    theta_s = rng.uniform(-np.pi, np.pi, n)
    e = rng.choice([-1.0, 1.0], n) * log_uniform(rng, 1e-3, 1e6, n)
    margin = sine_margin(np.zeros(n), gamma)
    size = np.abs(h_j - a) + np.abs(e)
    return {"args": (h_j, gamma, a, theta_s, e), "exact": margin > 0,
            "deficit": margin, "size": size, "places": np.abs(h_j) + np.abs(a)}


SOLVERS = {"RRR": solve_rrr, "RRP": solve_rrp, "RPR": solve_rpr, "PRP": solve_prp,
           "RPP": solve_rpp}


def misjudged(kind: str) -> tuple[int, int, int, int]:
    """How the solver's decision compares with the exact one over the designs of ``kind``.

    Returns the designs misjudged outside the tolerance band and its edge; the designs in the
    band (L1–L3: failing the exact test by at most ROUNDOFF·size, read as toggles); those of
    them the solver reads as failing; the designs within SLACK of the band's edge (L4, L5: of
    ``|sin| = ROUNDOFF``), where either answer is right.
    """
    data = designs(kind)
    exists, exact, deficit = SOLVERS[kind](*data["args"]).exists, data["exact"], data["deficit"]
    if kind in ("PRP", "RPP"):  # the condition |sin| > ROUNDOFF has no band
        band, edge = np.zeros(deficit.shape, bool), np.abs(deficit) <= SLACK
    else:
        band = (deficit < 0.0) & (deficit >= -ROUNDOFF - SLACK)
        edge = np.abs(deficit + ROUNDOFF) <= SLACK
    clear = ~band & ~edge
    return (int(np.sum(exists[clear] != exact[clear])), int(band.sum()),
            int(np.sum(~exists[band & ~edge])), int(edge.sum()))


# --- existence --------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", sorted(SOLVERS))
def test_existence_agrees_with_the_exact_decision(kind: str) -> None:
    wrong, band, toggles_failed, edge = misjudged(kind)
    assert wrong == 0, f"{kind}: {wrong} of {DESIGNS} designs misjudged"
    assert toggles_failed == 0  # inside the band: a toggle
    assert ROUNDOFF + SLACK < 2e-14  # the band is 2e-14 of the group's size
    assert band + edge < DESIGNS // 10, (band, edge)


@pytest.mark.parametrize("kind", sorted(SOLVERS))
def test_closure_where_the_group_assembles(kind: str) -> None:
    data = designs(kind)
    args = data["args"]
    sol = SOLVERS[kind](*args)
    ok = sol.exists
    assert ok.sum() > DESIGNS // 4 and (~ok).sum() > DESIGNS // 20
    c = sol.c
    if kind == "RRR":
        h_i, h_j, l_i, l_j, _ = args
        residuals = [np.abs(c - h_i) - l_i, np.abs(c - h_j) - l_j]
    elif kind == "RRP":
        h_j, a, theta, e, l_j, _ = args
        u = np.exp(1j * theta)
        residuals = [np.abs(c - h_j) - l_j, ((c - a) * np.conj(u)).imag - e,
                     ((c - a) * np.conj(u)).real - sol.s_i]
    elif kind == "RPR":
        h_i, h_j, h, _ = args
        frame = (sol.s_i + 1j * h) * np.exp(1j * sol.angle_i)  # H_j − H_i in the kulisa frame
        residuals = [np.abs(frame - (h_j - h_i)), np.abs(c - h_i - sol.s_i * np.exp(
            1j * sol.angle_i))]
    elif kind == "PRP":
        a, theta_i, e_i, b, theta_j, e_j = args
        u_i, u_j = np.exp(1j * theta_i), np.exp(1j * theta_j)
        residuals = [np.abs(c - (a + (sol.s_i + 1j * e_i) * u_i)),
                     np.abs(c - (b + (sol.s_j + 1j * e_j) * u_j))]
    else:
        h_j, gamma, a, theta_s, e = args
        u_s, u_t = np.exp(1j * theta_s), np.exp(1j * (theta_s + gamma))
        residuals = [np.abs(c - (h_j + sol.s_j * u_t)),
                     np.abs(c - (a + (sol.s_i + 1j * e) * u_s))]
    scale = data["size"]
    if kind in ("PRP", "RPP"):  # C lies |r|/|sin| away: the size of the solution counts
        scale = scale + np.abs(sol.s_i) + np.abs(sol.s_j)
    allowed = CLOSURE * scale + 8 * EPS * (data["places"] + np.abs(c))  # coordinates' rounding
    for residual in residuals:
        assert np.all(np.abs(residual[ok]) <= allowed[ok]), (kind, np.max(
            np.abs(residual[ok]) / scale[ok]))


# --- the reported case, symmetry, zero lengths ------------------------------------------------

def test_extreme_proportions_decided_on_the_lengths() -> None:
    # |C − H_j| would be 0.06 − 0 … the rod of 0.01 cannot reach: stretched by 0.05 mm
    for sol in (solve_rrr(0j, 1e6 + 0.06 + 0j, 1e6, 0.01, 1),
                solve_rrr(0j, 1e6 + 0.06 + 0j, 0.01, 1e6, 1)):
        assert not sol.exists and sol.reason == Reason.STRETCHED


def test_closure_of_thin_triangles() -> None:
    # links of 1e6 mm on hinges 1e-3 … 2e-3 mm apart: l_i² − l_j² is a difference of nearly
    # equal squares, to be taken as (l_i − l_j)(l_i + l_j)
    rng = np.random.default_rng(6)
    l_i = np.full(1000, 1e6)
    l_j = l_i + rng.uniform(-1e-3, 1e-3, l_i.size)
    h_i = 0.3 + 0.2j
    h_j = h_i + 1e-3 * rng.uniform(1.0, 2.0, l_i.size) * direction(rng, l_i.size)
    sol = solve_rrr(h_i, h_j, l_i, l_j, 1.0)
    size = l_i + l_j + np.abs(h_j - h_i)
    assert sol.exists.all()
    for residual in (np.abs(sol.c - h_i) - l_i, np.abs(sol.c - h_j) - l_j):
        assert np.all(np.abs(residual) <= CLOSURE * size)


@pytest.mark.parametrize("long_j", [False, True])
def test_toggles_inside_the_band_close_at_any_proportions(long_j: bool) -> None:
    # folded over H_j (or H_i): l_i − l_j = 1e-3 mm with links of 1e6 mm; the hinge distance
    # falls short of 1e-3 by up to the tolerance band
    l_i, l_j = 1e6 + 1e-3, 1e6
    if long_j:
        l_i, l_j = l_j, l_i
    size = l_i + l_j
    short = np.linspace(0.0, 0.9, 10) * ROUNDOFF * size
    h_j = (1e-3 - short) * np.exp(0.7j)
    sol = solve_rrr(0j, h_j, l_i, l_j, 1.0)
    assert sol.exists.all() and (sol.margin == 0.0).all()
    for residual in (np.abs(sol.c) - l_i, np.abs(sol.c - h_j) - l_j):
        assert np.all(np.abs(residual) <= ROUNDOFF * size)


def test_swapping_the_sides_of_an_rrr_dyad() -> None:
    h_i, h_j, l_i, l_j, sigma = designs("RRR")["args"]
    one = solve_rrr(h_i, h_j, l_i, l_j, sigma)
    other = solve_rrr(h_j, h_i, l_j, l_i, -sigma)  # the same triangle, seen from H_j
    np.testing.assert_array_equal(one.exists, other.exists)
    np.testing.assert_array_equal(one.reason, other.reason)
    ok = one.exists
    size = designs("RRR")["size"] + designs("RRR")["places"]
    assert np.all(np.abs(one.c - other.c)[ok] <= 1e-9 * size[ok])


def test_mirroring_an_rrr_dyad() -> None:
    h_i, h_j, l_i, l_j, sigma = designs("RRR")["args"]
    one = solve_rrr(h_i, h_j, l_i, l_j, sigma)
    image = solve_rrr(np.conj(h_i), np.conj(h_j), l_i, l_j, -sigma)  # reflected in the x-axis
    np.testing.assert_array_equal(one.exists, image.exists)
    np.testing.assert_array_equal(one.margin, image.margin)
    np.testing.assert_array_equal(np.conj(one.c), image.c)


@pytest.mark.parametrize(("solution", "what"), [
    (lambda: solve_rrr(0j, 30.0 + 0j, 0.0, 30.0, 1), "l_i = 0, H_j at l_j from H_i"),
    (lambda: solve_rrr(0j, 30.0 + 0j, 30.0, 0.0, 1), "l_j = 0, H_j at l_i from H_i"),
    (lambda: solve_rrr(0j, 30.0 + 0j, 0.0, 10.0, 1), "l_i = 0, H_j too far"),
    (lambda: solve_rrr(0j, 30.0 + 0j, 10.0, 0.0, 1), "l_j = 0, H_j too far"),
    (lambda: solve_rrr(0j, 0j, 10.0, 10.0, 1), "H_i = H_j"),
    (lambda: solve_rrp(20j, 0j, 0.0, 20.0, 0.0, 1), "rod of 0, H_j on the path"),
    (lambda: solve_rrp(20j, 0j, 0.0, 0.0, 0.0, 1), "rod of 0, H_j off the path"),
    (lambda: solve_rpr(5j, 5j, 0.0, 1), "H_i = H_j, no offset"),
])
def test_zero_lengths_make_coincident_hinges(solution: object, what: str) -> None:
    sol = solution()
    assert not sol.exists and sol.reason == Reason.COINCIDENT_HINGES, what
    assert np.isnan(sol.margin) and np.isnan(sol.c)


@pytest.mark.parametrize("kind", sorted(SOLVERS))
def test_nan_inputs_never_assemble(kind: str) -> None:
    args = [np.array(x[:4]) for x in designs(kind)["args"]]
    args[0] = np.array([np.nan, 1.0, np.nan, 2.0]) * args[0]
    sol = SOLVERS[kind](*args)
    assert not sol.exists[0] and not sol.exists[2]
    assert sol.reason[0] == sol.reason[2] == Reason.UNDEFINED_INPUT
