"""The sketched mode over a grid of crank angles, from every real mode at every angle at once.

At every angle of a grid (the requested ones and a uniform one of ``BASE`` per turn) and for
every design, all real roots of the eliminant are isolated in one vectorised call
(:func:`~assur.kinematics.higher.roots.real_roots`). A root at one angle continues as the
root at the next angle nearest to it when that one moves by at most ``SHARE`` of the
separation of both from every other root of p, real or complex, and keeps the sign of Φ′
(two merging modes have opposite signs); real roots never cross, so these links are the
modes' own paths. The sketched mode is the chain of links from its root at φ = 0. Where a
link is not certified (two roots come closer than the step can separate, or a pair of roots
appears or vanishes between the angles), the root is stepped over that interval alone by
halving and doubling the step, with the same test at every step; below ``NARROWEST`` of
crank the mode ends there: at a change point where the pair of roots is gone beyond it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from assur.kinematics.higher.groups import HigherGroup, K, values
from assur.kinematics.higher.modes import coefficients
from assur.kinematics.higher.roots import RealRoots, real_roots, separation, trig_form

__all__ = ["Chains", "chains"]

TWO_PI = 2.0 * np.pi
#: Columns of the uniform grid per turn, besides the requested angles.
BASE = 72
#: A root moves between two columns by at most this share of its separation bound.
SHARE = 0.25
#: A mode ends where a step of this (rad) is not certified.
NARROWEST = 1e-9


@dataclass(frozen=True, eq=False)
class _Column:
    """All real roots at one crank angle per design: θ, the sign of Φ′, the separation bound
    (chord) of each, the count, and whether the inputs are defined, shapes (..., R)/(...)."""

    theta: np.ndarray
    slope: np.ndarray
    apart: np.ndarray
    count: np.ndarray
    defined: np.ndarray


def _columns(group: HigherGroup[K], k: K) -> _Column:
    """Every real root of the group's eliminant at the inputs ``k`` (plain, shape (..., D))."""
    with np.errstate(all="ignore"):
        coef = coefficients(group, k)
    shape = coef.shape[:-1]
    flat = coef.reshape(-1, coef.shape[-1])
    a, b = trig_form(flat)
    found: RealRoots = real_roots(a, b)
    width = found.theta.shape[-1]
    with np.errstate(all="ignore"):
        apart = separation(flat[:, None, :], found.theta)
    return _Column(found.theta.reshape(shape + (width,)), found.slope.reshape(shape + (width,)),
                   apart.reshape(shape + (width,)), found.count.reshape(shape),
                   np.isfinite(coef).all(axis=-1))


def _chord(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.asarray(np.abs(np.exp(1j * a) - np.exp(1j * b)))


def _link(theta: np.ndarray, slope: np.ndarray, apart: np.ndarray, there: _Column
          ) -> tuple[np.ndarray, np.ndarray]:
    """The continuation at the column ``there`` of the roots (θ, sign of Φ′, separation;
    shape (..., S)): the index of the nearest root there and where the link is certified."""
    with np.errstate(invalid="ignore"):
        dist = _chord(theta[..., :, None], there.theta[..., None, :])
        dist = np.where(np.isnan(dist), np.inf, dist)
        j = np.argmin(dist, axis=-1)
        near = np.take_along_axis(dist, j[..., None], axis=-1)[..., 0]
        other = np.take_along_axis(there.apart[..., None, :], j[..., None], axis=-1)[..., 0]
        same = np.take_along_axis(there.slope[..., None, :], j[..., None], axis=-1)[..., 0]
        ok = (near <= SHARE * np.minimum(apart, other)) & (same == slope) & (slope != 0)
    return j, ok


@dataclass(frozen=True, eq=False)
class Chains:
    """The sketched mode's root at every column over one turn forward from φ = 0.

    Attributes
    ----------
    columns : ndarray, shape (U,)
        The crank angles of the columns in [0, 2π), increasing, the first 0.
    theta : ndarray, shape (U, D, R)
        Every real root at every column.
    index : ndarray, int, shape (U + 1, D)
        The index of the mode's root at each column (column U is φ = 2π: column 0 a turn
        later); −1 after the chain is lost.
    around : ndarray, bool, shape (D,)
        The chain reaches φ = 2π: the mode assembles over the whole turn.
    """

    columns: np.ndarray
    theta: np.ndarray
    index: np.ndarray
    around: np.ndarray


def chains(group: HigherGroup[K], inputs: Any, wanted: np.ndarray, theta0: np.ndarray,
           found: np.ndarray) -> Chains:
    """Follow the roots θ₀ (D,) of the sketch over a turn.

    Parameters
    ----------
    group : HigherGroup
        The group, drawn values of shape () or (D,).
    inputs : callable
        The inputs at crank angles of shape (U, D).
    wanted : ndarray
        The requested angles in [0, 2π).
    theta0 : ndarray, shape (D,)
        The eliminated angle of the sketched mode.
    found : ndarray, bool, shape (D,)
        Where the sketch picks a mode (the others are not followed).

    Returns
    -------
    Chains
        A chain is lost where the sketched mode is not among the roots at φ = 0 (within
        1e-6), or where a link is not certified even by steps of ``NARROWEST``: there the
        mode ends, or the roots leave a doubt, and the caller follows it step by step.
    """
    d = theta0.shape[0]
    columns = np.union1d(np.concatenate([[0.0], wanted]), TWO_PI / BASE * np.arange(BASE))
    u = columns.size
    k = values(inputs(np.broadcast_to(columns[:, None], (u, d))))
    col = _columns(group, k)
    start = _chord(col.theta[0], theta0[:, None])
    start = np.where(np.isnan(start), np.inf, start)
    i0 = np.argmin(start, axis=-1)
    alive = found & (start[np.arange(d), i0] <= 1e-6)
    to = np.append(columns[1:], TWO_PI)
    nxt = _Column(*(np.concatenate([getattr(col, f)[1:], getattr(col, f)[:1]])
                    for f in ("theta", "slope", "apart", "count", "defined")))
    forward, ok = _link(col.theta, col.slope, col.apart, nxt)
    backward, _ = _link(nxt.theta, nxt.slope, nxt.apart, col)
    ok &= np.take_along_axis(backward, forward, axis=-1) == np.arange(forward.shape[-1])
    links = np.where(ok, forward, -1)
    index = np.full((u + 1, d), -1)
    idx = np.where(alive, i0, -1)
    index[0] = idx
    rows = np.arange(d)
    for c in range(u):
        here = np.maximum(idx, 0)
        step = np.where(idx >= 0, links[c, rows, here], -1)
        stuck = (idx >= 0) & (step < 0)
        if stuck.any():
            got = _step_over(group, inputs, stuck, columns[c], to[c], col.theta[c, rows, here],
                             col.slope[c, rows, here], col.apart[c, rows, here],
                             _Column(*(getattr(nxt, f)[c] for f in
                                       ("theta", "slope", "apart", "count", "defined"))))
            step = np.where(stuck, got, step)
        idx = step
        index[c + 1] = idx
    return Chains(columns, col.theta, index, index[-1] >= 0)


def _step_over(group: HigherGroup[K], inputs: Any, rows: np.ndarray, start: float,
               goal: float, theta: np.ndarray, slope: np.ndarray, apart: np.ndarray,
               there: _Column) -> np.ndarray:
    """Step the roots of the ``rows`` (D,) from the crank angle ``start`` to ``goal`` under
    step control, with the test of :func:`_link` at every step: the index of the root
    reached among the roots at ``goal`` (``there``), −1 where a step of ``NARROWEST`` fails."""
    d = rows.shape[0]
    every = np.arange(d)
    phi = np.full(d, start)
    h = np.full(d, goal - start)
    active = rows.copy()
    got = np.full(d, -1)
    while active.any():
        trial = np.where(active, np.where(np.abs(h) >= np.abs(goal - phi), goal, phi + h), phi)
        k = values(inputs(trial[None, :]))
        col = _columns(group, k)
        j, ok = _link(theta[:, None], slope[:, None], apart[:, None],
                      _Column(*(getattr(col, f)[0] for f in
                                ("theta", "slope", "apart", "count", "defined"))))
        j, ok = j[:, 0], ok[:, 0] & active
        theta = np.where(ok, col.theta[0, every, j], theta)
        slope = np.where(ok, col.slope[0, every, j], slope)
        apart = np.where(ok, col.apart[0, every, j], apart)
        phi = np.where(ok, trial, phi)
        arrived = ok & (trial == goal)
        if arrived.any():
            there_j, _ = _link(theta[:, None], slope[:, None], apart[:, None], there)
            got = np.where(arrived, there_j[:, 0], got)
        remaining = goal - phi
        h = np.where(ok, np.where(np.abs(2.0 * h) < np.abs(remaining), 2.0 * h, remaining),
                     0.5 * h)
        active &= ~arrived & ~(~ok & (np.abs(h) < NARROWEST))
    return got
