"""Two modes of a triad that pass close to each other, and two that meet.

An RRR triad driven by a crank, its third frame hinge moved along x by μ: at μ* two modes of
the drawn circuit touch near φ = 357.54°. A little before μ* they pass about 2e-4 mm apart
without meeting, the drawn mode goes on and nothing is missing; a little beyond it they meet
twice and the drawn mode does not assemble between the two change points. Both are checked
against a computation written here: the loop closure reduced to one equation f(θ) = 0 in the
base's rotation (leashes 2 and 3 minus leash 1 are linear in P₁), its pair of roots near the
touching point by bracketing, and the change points where the extremum of f between them
vanishes, by nested scalar root finding.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from assur.kinematics import jets as J
from assur.kinematics.higher import Leash, Triad, TriadInputs, follow_mode

#: The design (mm), drawn at φ = 0: base hinges P1–P3, the crank pin A1 (crank pivot at the
#: origin) and the frame hinges A2, A3; twice a seeded random design, so L ≈ 240 mm.
BASE = (-73.21859221179466 - 1.9498046773950708j, -131.5932863107245 - 101.38318969265j,
        -31.196926893123554 - 59.89063827611992j)
PIN = 21.078588027217194 + 1.9102240747499774j
FRAME = (-210.9335081282451 - 85.2126986542801j, -131.89279113116188 - 53.66468800665452j)
#: μ* (mm), where the two modes touch.
TOUCH = 5.599698599260015
#: Where they touch (rad), and the base's rotation there.
NEAR, THETA = np.radians(357.5408), -0.0037


def _triad(mu: float) -> tuple[Triad, Any]:
    """The triad with A3 moved by μ along x, and its inputs at the crank angles."""
    a3 = FRAME[1] + mu

    def inputs(phi: Any) -> TriadInputs:
        return TriadInputs((PIN * J.expi(phi), FRAME[0], a3))

    return Triad((Leash.RR,) * 3, BASE, (PIN, FRAME[0], a3)), inputs


def _closure(mu: float, phi: float, theta: float) -> tuple[float, complex]:
    """f(θ) = |P₁ − A₁|² − r₁² with P₁ from leashes 2 and 3 minus leash 1 (linear in P₁)."""
    a = (PIN * np.exp(1j * phi), FRAME[0], FRAME[1] + mu)
    drawn = (PIN, FRAME[0], FRAME[1] + mu)
    r2 = [abs(b - d) ** 2 for b, d in zip(BASE, drawn, strict=True)]
    e = np.exp(1j * theta)
    rows, rhs = [], []
    for k in (1, 2):
        c = (BASE[k] - BASE[0]) * e - a[k] + a[0]
        rows.append([c.real, c.imag])
        rhs.append((r2[k] - r2[0] - abs((BASE[k] - BASE[0]) * e - a[k]) ** 2 + abs(a[0]) ** 2)
                   / 2.0)
    x, y = np.linalg.solve(np.array(rows), np.array(rhs))
    p1 = complex(x, y)
    return abs(p1 - a[0]) ** 2 - r2[0], p1


def _extremum(mu: float, phi: float) -> tuple[float, float]:
    """θ_c, the minimum of f between the pair near the touching point, and f(θ_c)."""
    found = minimize_scalar(lambda th: _closure(mu, phi, th)[0],
                            bounds=(THETA - 0.01, THETA + 0.01), method="bounded",
                            options={"xatol": 1e-14})
    return float(found.x), _closure(mu, phi, float(found.x))[0]


def _top(mu: float) -> tuple[float, float]:
    """The crank angle where the pair comes closest (the largest min of f), and that min."""
    found = minimize_scalar(lambda p: -_extremum(mu, p)[1],
                            bounds=(NEAR - 1e-4, NEAR + 1e-4), method="bounded",
                            options={"xatol": 1e-14})
    return float(found.x), -float(found.fun)


def _pair(mu: float, phi: float) -> tuple[float, float]:
    """The two roots θ of f about the minimum between them (the pair is real at φ)."""
    centre, _ = _extremum(mu, phi)

    def f(th: float) -> float:
        return _closure(mu, phi, th)[0]

    return (brentq(f, centre - 0.01, centre, xtol=1e-16),
            brentq(f, centre, centre + 0.01, xtol=1e-16))


def _joints(mu: float, phi: float, theta: float) -> np.ndarray:
    """P1, P2, P3 at the base rotation θ."""
    p1 = _closure(mu, phi, theta)[1]
    return np.array([p1 + (b - BASE[0]) * np.exp(1j * theta) for b in BASE])


#: A little before μ*: the pair comes within about 2e-4 mm and parts again.
PASS = TOUCH - 4e-8
#: Beyond μ*: the pair meets twice, a few thousandths of a degree apart.
MEET = TOUCH + 2e-5
#: Requested angles: a whole turn every 2°, and 0.00002° apart across the touching point.
GRID = np.concatenate([np.radians(np.arange(0.0, 360.0, 2.0)),
                       NEAR + np.radians(np.linspace(-0.01, 0.01, 1001))])


def test_two_modes_passing_2e_4_mm_apart_leave_no_gap() -> None:
    """The drawn mode assembles at every angle, stays on its own root of the pair (the
    upper or the lower one everywhere across the touching point) and its joints are the
    computation's to 1e-9 L."""
    angle, closest = _top(PASS)
    assert closest < 0.0  # the pair is real at every angle: the modes never meet
    lo, hi = _pair(PASS, angle)
    apart = np.abs(_joints(PASS, angle, lo) - _joints(PASS, angle, hi)).max()
    assert 1.5e-4 <= apart <= 2.5e-4
    group, inputs = _triad(PASS)
    solution = follow_mode(group, inputs, GRID)
    assert solution.exists.all()
    assert np.isnan(solution.ends).all()
    size = float(group.size)
    near = np.abs(GRID - NEAR) <= np.radians(0.01)
    sides = []
    for phi, theta, p1 in zip(GRID[near], solution.x[near, 2], solution.joints["P1"][near],
                              strict=True):
        roots = _pair(PASS, float(phi))
        side = int(np.argmin(np.abs(np.asarray(roots) - theta)))
        sides.append(side)
        expected = _joints(PASS, float(phi), roots[side])[0]
        assert abs(p1 - expected) <= 1e-9 * size
    assert len(set(sides)) == 1


def _change(mu: float, low: float, high: float) -> float:
    """The crank angle between ``low`` and ``high`` where the minimum of f between the pair
    reaches 0: the two modes meet there."""
    return float(brentq(lambda p: _extremum(mu, p)[1], low, high, xtol=1e-15))


def test_two_modes_that_meet_leave_a_gap_with_its_ends_to_1e_6_degrees() -> None:
    angle, closest = _top(MEET)
    assert closest > 0.0  # the pair is complex at the closest angle: a gap
    first = _change(MEET, NEAR - np.radians(0.01), angle)
    last = _change(MEET, angle, NEAR + np.radians(0.01))
    group, inputs = _triad(MEET)
    solution = follow_mode(group, inputs, GRID)
    assert np.degrees(abs(solution.ends[0] - first)) <= 1e-6
    assert np.degrees(abs(solution.ends[1] - last)) <= 1e-6
    inside = (GRID > first) & (GRID < last)
    assert inside.sum() >= 10
    assert (~solution.exists[inside]).all() and (solution.reason[inside] == 8).all()
    assert solution.exists[~inside].all()
