"""The follower against a plain step-by-step continuation on 1,000 random designs.

``follow_mode`` (predictor from the exact analogs, step control, the neighbour tests, change
points from the extended system) against a continuation written here with none of that: plain
Newton steps of at most 1° of crank from the last accepted pose, each accepted where Newton
converges, det J keeps its sign and the unknowns move little; a failed step is halved, and
where the step falls below 1e-11 rad the mode ends at the last accepted angle. Forward from the sketch, and backward where the forward pass ends. On every
design both agree: the same positions at every requested angle (1e-9 of the group's size),
and the same ends of existence (1e-6°).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_higher_properties import Designs, random_class_iv, random_triads

from assur.kinematics.higher import (
    HigherSolution,
    assembly_modes,
    compiled,
    continuation,
    follow_mode,
)
from assur.kinematics.higher.groups import values
from assur.kinematics.higher.modes import select_mode

TWO_PI = 2.0 * np.pi
#: The plain continuation's largest step (rad).
STEP = np.radians(1.0)
#: Below this step (rad) the plain continuation ends.
END = 1e-11
#: Requested angles.
PHI = np.radians(np.arange(0.0, 360.0, 5.0))


def _solve(designs: Designs, x: np.ndarray, phi: np.ndarray, alive: np.ndarray,
           sign: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method from x at the angles ``phi`` (D,), and where the solve is accepted:
    converged (the last step at most 1e-8 in W/L and angles, the residual at most 1e-10 L;
    beyond a change point Newton's steps keep the size of the square root of the distance
    to it), det J of the sketch's sign, moved at most 0.05."""
    group = designs.group
    n = x.shape[-1]
    k = values(designs.inputs(phi))
    size = np.asarray(group.size)
    scale = np.where(np.asarray(group.lengths), 1.0 / size[:, None], 1.0)
    y = x.copy()
    last = np.full(len(x), np.inf)
    with np.errstate(all="ignore"):
        for _ in range(12):
            f = np.stack(np.broadcast_arrays(*group.residual(y, k)), axis=-1)
            jac = group.jacobian(y, k)
            safe = alive & np.isfinite(jac).all(axis=(-2, -1)) & np.isfinite(f).all(axis=-1)
            safe &= np.abs(np.linalg.det(np.where(safe[:, None, None], jac, np.eye(n)))) > 0
            dx = np.linalg.solve(np.where(safe[:, None, None], jac, np.eye(n)),
                                 np.where(safe[:, None], -f, 0.0)[..., None])[..., 0]
            y = y + dx
            last = (np.abs(dx) * scale).sum(axis=-1)
            if not (last[alive] > 1e-14).any():
                break
        f = np.stack(np.broadcast_arrays(*group.residual(y, k)), axis=-1)
        same = np.sign(np.linalg.det(group.jacobian(y, k))) == sign
        moved = (np.abs(y - x) * scale).sum(axis=-1)
        ok = alive & (np.abs(f).max(axis=-1) <= 1e-10 * size) & (last <= 1e-8) & same \
            & (moved <= 0.05)
    return y, ok


def _pass(designs: Designs, x0: np.ndarray, alive: np.ndarray, s: float,
          targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The mode from x0 at φ = s·t for the increasing ``targets`` t in (0, 2π]: the unknowns
    there (D, N, n), NaN from the end on, and the end (t, NaN where every target is reached).

    Each design steps on its own: a step of h (at most ``STEP``, cut at the next target) is
    taken where :func:`_solve` accepts it, and h doubles; elsewhere h halves, and below
    ``END`` the mode ends at the last accepted angle."""
    d, n = x0.shape
    sign = np.sign(np.linalg.det(designs.group.jacobian(x0, values(designs.inputs(
        np.zeros(d))))))
    out = np.full((d, len(targets), n), np.nan)
    x, t, h = x0.copy(), np.zeros(d), np.full(d, STEP)
    following = np.zeros(d, dtype=int)
    end = np.full(d, np.nan)
    rows = np.arange(d)
    while alive.any():
        goal = targets[np.minimum(following, len(targets) - 1)]
        trial = np.where(alive, np.minimum(t + h, goal), t)
        y, ok = _solve(designs, x, s * trial, alive, sign)
        x, t = np.where(ok[:, None], y, x), np.where(ok, trial, t)
        hit = ok & (trial == goal)
        out[rows[hit], following[hit]] = x[hit]
        following = np.where(hit, following + 1, following)
        h = np.where(ok, np.minimum(2.0 * h, STEP), 0.5 * h)
        stuck = alive & ~ok & (h < END)
        end = np.where(stuck, t, end)
        alive = alive & ~stuck & (following < len(targets))
    return out, end


@pytest.mark.slow
@pytest.mark.parametrize(("kind", "count"), [("RR-RR-RR", 400), ("RR-RR-RP", 200),
                                             ("IV", 400)])
def test_the_follower_equals_a_plain_continuation(kind: str, count: int,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    """Both ways of following a turn: by steps, and by the path of the root through every
    root at every angle (a design's path taken where all its links pass the step test); by
    steps also with the group's compiled corrector, which only larger grids use."""
    designs = (random_class_iv(91, count) if kind == "IV"
               else random_triads(90, count, kind[-2:]))
    group = designs.group
    k0 = values(designs.inputs(np.zeros(count)))
    x0, found = select_mode(group, k0, assembly_modes(group, k0))
    assert found.mean() > 0.9
    ahead, forward = _pass(designs, x0, found, 1.0, np.append(PHI[1:], TWO_PI))
    ended = ~np.isnan(forward)
    back_targets = np.append(np.sort(TWO_PI - PHI[1:]), TWO_PI)
    behind, backward = _pass(designs, x0, found & ended, -1.0, back_targets)
    assert 0.1 < ended.mean() < 0.9
    for method in ("steps", "roots"):
        _agree(follow_mode(group, designs.inputs, PHI, method=method), designs, x0, found,
               (ahead, forward), (behind, backward))
    if compiled.supports(group):
        monkeypatch.setattr(continuation, "KERNEL_POSITIONS", 1)
        _agree(follow_mode(group, designs.inputs, PHI, method="steps"), designs, x0, found,
               (ahead, forward), (behind, backward))


def _agree(solution: HigherSolution, designs: Designs, x0: np.ndarray, found: np.ndarray,
           ahead_pass: tuple[np.ndarray, np.ndarray],
           behind_pass: tuple[np.ndarray, np.ndarray]) -> None:
    """The solution has the plain continuation's ends (1e-6°) and positions (1e-9 L)."""
    group = designs.group
    (ahead, forward), (behind, backward) = ahead_pass, behind_pass
    ended = ~np.isnan(forward)
    back_targets = np.append(np.sort(TWO_PI - PHI[1:]), TWO_PI)
    # the same ends of existence, to 1e-6°
    tol = np.radians(1e-6)
    assert (np.isnan(solution.ends[:, 0]) == ~ended).all()
    assert (np.abs(solution.ends[ended, 0] - forward[ended]) <= tol).all()
    back_end = TWO_PI - backward
    assert (np.isnan(solution.ends[ended, 1]) == np.isnan(back_end[ended])).all()
    assert (np.abs(solution.ends[ended, 1] - back_end[ended]) <= tol)[
        ~np.isnan(back_end[ended])].all()
    # the same positions: ahead where the forward pass reaches, else behind
    expected = np.concatenate([x0[:, None], ahead[:, :-1]], axis=1)
    back = behind[:, np.searchsorted(back_targets, TWO_PI - PHI[1:])]
    expected[:, 1:] = np.where(np.isnan(expected[:, 1:, :1]), back, expected[:, 1:])
    expected[~found] = np.nan
    reached = ~np.isnan(expected[..., 0])
    assert (solution.exists == reached).all()
    k = values(designs.inputs(np.broadcast_to(PHI, reached.shape).T))
    want = group.joints(expected.transpose(1, 0, 2), k)
    size = np.asarray(group.size)[:, None]
    for name, points in want.items():
        point = np.asarray(points)
        point = point.T if point.ndim == 2 else point[:, None]
        error = np.abs(solution.joints[name] - point) / size
        assert (error[reached] <= 1e-9).all(), (name, error[reached].max())
