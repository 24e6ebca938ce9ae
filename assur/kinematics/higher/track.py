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
from assur.kinematics.reasons import Reason

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
    """The sketched mode's root at every column, forward and backward from φ = 0.

    Attributes
    ----------
    columns : ndarray, shape (U,)
        The crank angles of the columns in [0, 2π), increasing, the first 0.
    theta : ndarray, shape (U, D, R)
        Every real root at every column.
    ahead, behind : ndarray, int, shape (U + 1, D)
        The index of the mode's root at each column (column U is φ = 2π: column 0 a turn
        later) along the forward pass and along the backward pass; −1 where not reached.
    end, why : ndarray, shape (D, 2)
        Where the forward and the backward pass ended (crank angle in (0, 2π); NaN where
        not) and why (0 where not).
    """

    columns: np.ndarray
    theta: np.ndarray
    ahead: np.ndarray
    behind: np.ndarray
    end: np.ndarray
    why: np.ndarray


def chains(group: HigherGroup[K], inputs: Any, wanted: np.ndarray, theta0: np.ndarray,
           found: np.ndarray) -> Chains | None:
    """Follow the roots θ₀ (D,) of the sketch over a turn, forward and backward.

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
    Chains or None
        None where a sketched mode is not among the roots at φ = 0.
    """
    d = theta0.shape[0]
    columns = np.union1d(np.concatenate([[0.0], wanted]), TWO_PI / BASE * np.arange(BASE))
    u = columns.size
    k = values(inputs(np.broadcast_to(columns[:, None], (u, d))))
    col = _columns(group, k)
    width = col.theta.shape[-1]
    start_dist = _chord(col.theta[0], theta0[:, None])
    start_dist = np.where(np.isnan(start_dist), np.inf, start_dist)
    i0 = np.argmin(start_dist, axis=-1)
    if (found & (start_dist[np.arange(d), i0] > 1e-6)).any():
        return None
    ahead_to = np.append(columns[1:], TWO_PI)
    nxt = _Column(*(np.concatenate([getattr(col, f)[1:], getattr(col, f)[:1]])
                    for f in ("theta", "slope", "apart", "count", "defined")))
    forward, fok = _link(col.theta, col.slope, col.apart, nxt)
    backward, bok = _link(nxt.theta, nxt.slope, nxt.apart, col)
    # a link holds both ways
    fok &= np.take_along_axis(backward, forward, axis=-1) == np.arange(width)
    bok &= np.take_along_axis(forward, backward, axis=-1) == np.arange(width)
    fmap = np.where(fok, forward, -1)
    bmap = np.where(bok, backward, -1)
    end = np.full((d, 2), np.nan)
    why = np.zeros((d, 2), dtype=np.int8)
    ahead = _walk_chain(group, inputs, col, nxt, fmap, columns, ahead_to, i0, found,
                        end[:, 0], why[:, 0])
    around = ahead[-1] >= 0
    back_from = np.append(columns, TWO_PI)
    behind = _walk_chain_back(group, inputs, col, bmap, back_from, i0, found & ~around,
                              end[:, 1], why[:, 1])
    return Chains(columns, col.theta, ahead, behind, end, why)


def _walk_chain(group: HigherGroup[K], inputs: Any, col: _Column, nxt: _Column,
                fmap: np.ndarray, columns: np.ndarray, to: np.ndarray, i0: np.ndarray,
                alive: np.ndarray, end: np.ndarray, why: np.ndarray) -> np.ndarray:
    """The forward chain: index per column (U + 1, D), −1 once ended; fills ``end``/``why``."""
    u, d = fmap.shape[:2]
    out = np.full((u + 1, d), -1)
    idx = np.where(alive, i0, -1)
    out[0] = idx
    rows = np.arange(d)
    for c in range(u):
        live = idx >= 0
        nxt_idx = np.where(live, fmap[c, rows, np.maximum(idx, 0)], -1)
        stuck = live & (nxt_idx < 0)
        if stuck.any():
            at = col.theta[c, rows, np.maximum(idx, 0)]
            got, stop, code = _step_over(group, inputs, stuck, columns[c], to[c], at,
                                         col.slope[c, rows, np.maximum(idx, 0)],
                                         col.apart[c, rows, np.maximum(idx, 0)],
                                         col.count[c], _take_column(nxt, c))
            nxt_idx = np.where(stuck, got, nxt_idx)
            ended = stuck & (got < 0)
            end[ended], why[ended] = stop[ended], code[ended]
        idx = nxt_idx
        out[c + 1] = idx
    return out


def _walk_chain_back(group: HigherGroup[K], inputs: Any, col: _Column, bmap: np.ndarray,
                     at: np.ndarray, i0: np.ndarray, alive: np.ndarray, end: np.ndarray,
                     why: np.ndarray) -> np.ndarray:
    """The backward chain from φ = 2π (column U, the roots of column 0) down to column 0:
    index per column (U + 1, D), −1 where not reached; fills ``end``/``why`` (as angles)."""
    u, d = bmap.shape[:2]
    out = np.full((u + 1, d), -1)
    idx = np.where(alive, i0, -1)
    out[u] = idx
    rows = np.arange(d)
    for c in range(u - 1, -1, -1):
        here = (c + 1) % u
        live = idx >= 0
        prev = np.where(live, bmap[c, rows, np.maximum(idx, 0)], -1)
        stuck = live & (prev < 0)
        if stuck.any():
            theta = col.theta[here, rows, np.maximum(idx, 0)]
            got, stop, code = _step_over(group, inputs, stuck, at[c + 1], at[c], theta,
                                         col.slope[here, rows, np.maximum(idx, 0)],
                                         col.apart[here, rows, np.maximum(idx, 0)],
                                         col.count[here], _take_column(col, c))
            prev = np.where(stuck, got, prev)
            ended = stuck & (got < 0)
            end[ended], why[ended] = stop[ended], code[ended]
        idx = prev
        out[c] = idx
    return out


def _take_column(col: _Column, c: int) -> _Column:
    return _Column(col.theta[c], col.slope[c], col.apart[c], col.count[c], col.defined[c])


def _step_over(group: HigherGroup[K], inputs: Any, rows: np.ndarray, start: float,
               goal: float, theta: np.ndarray, slope: np.ndarray, apart: np.ndarray,
               count: np.ndarray, there: _Column) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Step the roots of the ``rows`` (D,) from the crank angle ``start`` to ``goal`` under
    step control, with the test of :func:`_link` at every step.

    Returns the index of the root reached among the roots at ``goal`` (``there``; −1 where
    the mode ended), the angle where it ended and the reason.
    """
    d = rows.shape[0]
    phi = np.full(d, start)
    span = goal - start
    h = np.full(d, span)
    active = rows.copy()
    got = np.full(d, -1)
    stop = np.full(d, np.nan)
    code = np.zeros(d, dtype=np.int8)
    while active.any():
        trial = np.where(active, phi + h, phi)
        k = values(inputs(trial[None, :]))
        col = _columns(group, k)
        col = _Column(col.theta[0], col.slope[0], col.apart[0], col.count[0], col.defined[0])
        j, ok = _link(theta[:, None], slope[:, None], apart[:, None], col)
        j, ok = j[:, 0], ok[:, 0] & active
        theta = np.where(ok, col.theta[np.arange(d), j], theta)
        slope = np.where(ok, col.slope[np.arange(d), j], slope)
        apart = np.where(ok, col.apart[np.arange(d), j], apart)
        count = np.where(ok, col.count, count)
        phi = np.where(ok, trial, phi)
        arrived = ok & ((goal - phi) * np.sign(span) <= 0.0)
        if arrived.any():
            jj, _ = _link(theta[:, None], slope[:, None], apart[:, None], there)
            got = np.where(arrived, jj[:, 0], got)
        remaining = goal - phi
        h = np.where(ok, np.where(np.abs(2.0 * h) < np.abs(remaining), 2.0 * h, remaining),
                     0.5 * h)
        small = active & ~ok & (np.abs(h) < NARROWEST)
        if small.any():
            reason = np.where(~col.defined, Reason.UNDEFINED_INPUT,
                              np.where(col.count < count, Reason.MODE_ENDS,
                                       Reason.NOT_FOLLOWED))
            stop = np.where(small, np.mod(phi, TWO_PI), stop)
            code = np.where(small, reason, code).astype(np.int8)
        active &= ~arrived & ~small
    return got, stop, code
