"""The ends of a mode against change points located here by another method.

``follow_mode`` ends a pass at a change point solved on the extended system F = 0, det J = 0.
Here the same point is found from the closure of the group written out in the test: one link
turns through θ, the next joint closes as a circle–circle intersection on the branch of the
followed mode, and the last constraint is the residual f(θ; φ). At the change point the mode's
zero of f and its partner merge, so the extremum of f between them touches zero: its value
m(φ) changes sign there, and φ is bisected on that sign to roundoff (the extremum by Brent's
method to 1e-13 rad, where f is flat to second order). The ends must agree to 1e-10 rad.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from test_higher_properties import Designs, random_class_iv, random_triads

from assur.kinematics import jets as J
from assur.kinematics.higher import ClassIVCoupled, ClassIVInputs, assembly_modes, follow_mode
from assur.kinematics.higher.groups import expand

#: A point, or an array of points over θ.
Point = complex | np.ndarray
#: The closure of one design: (φ, θ, branch) → residual f, and the joint closed as a dyad.
Closure = Callable[[float, Point, float], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class Sweep:
    """A closure, the joint it closes as a dyad, and the unknown of the mode it turns."""

    closure: Closure
    joint: str
    turned: int


def _meet(c1: Point, r1: float, c2: Point, r2: float, sigma: float) -> Point:
    """The intersection of the circles (c1, r1) and (c2, r2) on the branch sigma = ±1."""
    gap = c2 - c1
    cos = (r1 * r1 + np.abs(gap) ** 2 - r2 * r2) / (2.0 * r1 * np.abs(gap))
    return c1 + r1 * gap / np.abs(gap) * np.exp(1j * sigma * np.arccos(np.clip(cos, -1, 1)))


def _triad(designs: Designs, i: int, roles: tuple[int, int, int]) -> Sweep:
    """RRR triad, leashes (i, j, k) = ``roles``: the base turns through θ; P_i on the circles
    about A_i (r_i) and about A_j − (P_j⁰ − P_i⁰)e^{iθ} (r_j);
    f = |P_i + (P_k⁰ − P_i⁰)e^{iθ} − A_k|² − r_k². A₁ is the crank pin."""
    g = designs.group
    p = [complex(np.asarray(b)[i]) for b in g.base]
    a = [complex(np.asarray(e)[i]) for e in g.external]
    r = [abs(p[k] - a[k]) for k in range(3)]
    first, second, last = roles

    def closure(phi: float, theta: Point, sigma: float) -> tuple[np.ndarray, np.ndarray]:
        turn = np.exp(1j * theta)
        hinge = [a[0] * np.exp(1j * phi), a[1], a[2]]
        point = _meet(hinge[first], r[first], hinge[second] - (p[second] - p[first]) * turn,
                      r[second], sigma)
        residual = np.abs(point + (p[last] - p[first]) * turn - hinge[last]) ** 2 - r[last] ** 2
        return np.asarray(residual), np.asarray(point)

    return Sweep(closure, f"P{first + 1}", 2)


def _class_iv(designs: Designs, i: int, turned: int) -> Sweep:
    """Class IV: a (``turned`` 0) or c (1) turns through θ; the far joint of the other link
    (D, or C) on the circles about its external hinge and about the near end of the coupler
    b (l_b); the other link's second joint follows; f = |F − E|² − l_d²."""
    g = designs.group
    h_a, c, f, h_c, d, e = (complex(np.asarray(v)[i]) for v in (g.h_a, g.c, g.f, g.h_c, g.d, g.e))

    def closure(phi: float, theta: Point, sigma: float) -> tuple[np.ndarray, np.ndarray]:
        hinges = (h_a * np.exp(1j * phi), h_c)
        links = ((h_a, c, f), (h_c, d, e))
        hinge, (drawn, near, far) = hinges[turned], links[turned]
        other, (drawn_o, near_o, far_o) = hinges[1 - turned], links[1 - turned]
        turn = np.exp(1j * theta)
        point_near, point_far = hinge + (near - drawn) * turn, hinge + (far - drawn) * turn
        point = _meet(other, abs(near_o - drawn_o), point_near, abs(c - d), sigma)
        point_other = other + (far_o - drawn_o) * (point - other) / (near_o - drawn_o)
        residual = np.abs(point_far - point_other) ** 2 - abs(f - e) ** 2
        return np.asarray(residual), np.asarray(point)

    return Sweep(closure, "DC"[turned], turned)


def _change_point(closure: Closure, inside: float, outside: float, theta: float,
                  joint: complex) -> float | None:
    """The crank angle between ``inside`` (the mode exists, at θ with the joint ``joint``) and
    ``outside`` where the extremum of f between the mode's zero and its partner touches 0;
    None where the partner is not on the mode's branch of the dyad (this sweep cannot tell)."""
    sigma = min((1.0, -1.0), key=lambda s: float(np.abs(closure(inside, theta, s)[1] - joint)))
    grid = theta + np.linspace(-0.02, 0.02, 4000)  # θ itself is not a sample
    values = closure(inside, grid, sigma)[0]
    crossings = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))
    if len(crossings) < 2:
        return None
    # the mode's zero and its partner: the two crossings nearest θ, the extremum between them
    pair = np.sort(crossings[np.argsort(np.abs(grid[crossings] - theta))[:2]])
    low, high = grid[pair[0]], grid[pair[1] + 1]
    side = -np.sign(values[(pair[0] + pair[1]) // 2 + 1])  # the extremum is a minimum of side·f

    def extremum(phi: float) -> float:
        best = minimize_scalar(lambda t: side * closure(phi, t, sigma)[0], bounds=(low, high),
                               method="bounded", options={"xatol": 1e-13})
        return float(best.fun)  # the value at the extremum: flat there, θ to 1e-13 is ample

    if not extremum(inside) < 0 < extremum(outside):
        return None
    while abs(outside - inside) > 1e-13:
        middle = 0.5 * (inside + outside)
        if extremum(middle) < 0:
            inside = middle
        else:
            outside = middle
    return 0.5 * (inside + outside)


@pytest.mark.parametrize("kind", ["RRR triad", "class IV"])
def test_the_ends_of_a_mode_are_change_points_to_1e_10_rad(kind: str) -> None:
    triad = kind == "RRR triad"
    designs = random_triads(17, 24) if triad else random_class_iv(17, 24)
    g = designs.group
    solution = follow_mode(g, designs.inputs, [0.0])
    ends = solution.ends.copy()
    ends[solution.overlap, 1] = np.nan  # there the forward pass gives the positions after φ_b
    rows, sides = np.nonzero(np.isfinite(ends))
    end = ends[rows, sides]
    # the mode exists before a forward end and after a backward one
    inside, outside = end + np.where(sides == 0, -1e-7, 1e-7), end + np.where(sides == 0, 1e-7, -1e-7)
    near = follow_mode(g, designs.inputs, inside)
    assert near.exists[rows, np.arange(len(rows))].all()
    for column, i in enumerate(rows):
        sweeps = ([_triad(designs, int(i), roles) for roles in ((0, 1, 2), (1, 2, 0), (2, 0, 1))]
                  if triad else [_class_iv(designs, int(i), turned) for turned in (0, 1)])
        found = None
        for sweep in sweeps:  # the first whose dyad has the partner zero on the mode's branch
            found = _change_point(sweep.closure, inside[column], outside[column],
                                  float(near.x[i, column, sweep.turned]),
                                  complex(near.joints[sweep.joint][i, column]))
            if found is not None:
                break
        assert found is not None and abs(found - end[column]) <= 1e-10, (i, found, end[column])
    assert len(rows) >= 20


def test_the_gap_of_a_class_iv_group_on_two_turning_guides_has_a_finite_margin() -> None:
    """a slides on a guide of the crank, c on a guide of the frame: the drawn mode ends where
    the guides become parallel (twice a turn) and its partner modes go on there with
    unbounded slides, so no root of p leaves the unit circle. In such a gap the margin is
    −|sin| of the angle between the guides, computed here from the guides' directions."""
    designs = random_class_iv(23, 24)
    g = designs.group
    rng = np.random.default_rng(23)
    u_a, u_c = (np.exp(2j * np.pi * rng.uniform(size=24)) for _ in range(2))
    group = ClassIVCoupled(g.h_a, g.c, g.f, g.h_c, g.d, g.e, u_a, u_c)

    def inputs(phi: Any) -> ClassIVInputs:
        return ClassIVInputs(g.h_a * J.expi(phi), g.h_c, u_a * J.expi(phi), u_c)

    phi = np.radians(np.arange(0.5, 360.0, 1.0))
    solution = follow_mode(group, inputs, phi)
    turn = np.exp(1j * phi)
    grid = ClassIVInputs(g.h_a[:, None] * turn, g.h_c[:, None], u_a[:, None] * turn,
                         u_c[:, None])
    counts = assembly_modes(expand(group), grid).count
    guides = -np.abs(np.sin(np.angle(u_c[:, None] / (u_a[:, None] * turn))))
    gap = ~solution.exists
    on_circle = gap & (counts == 2)  # every root of p (degree 2) is a real mode
    assert on_circle.any(axis=1).sum() >= 2  # two of the designs have such a gap
    assert np.isfinite(solution.margin[gap]).all()
    assert np.allclose(solution.margin[on_circle], guides[on_circle], rtol=1e-12, atol=1e-15)
