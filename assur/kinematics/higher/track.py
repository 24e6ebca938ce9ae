"""The candidate path of the sketched mode over a grid of crank angles, all angles at once.

At every angle of a grid (the requested ones and a uniform one of ``BASE`` per turn) and for
every design, the real roots of the eliminant are bracketed in one vectorised call
(:func:`~assur.kinematics.higher.roots.real_roots`). Real roots never cross: a root at one
angle goes on as a root at the next with the same sign of Φ′, or it meets its neighbour (of
the other sign) at a change point. The path from the sketched root takes at each angle the
nearest root that is nearest back and has the same sign; its roots are then polished, with
the separation bound of each from every other root of p, real or complex. The path is only a
candidate: a root and its neighbour may meet and a new pair appear between two angles, or a
pair closer than the samples' spacing may be missed. The caller
(:func:`~assur.kinematics.higher.continuation.follow_mode`) accepts a link only where the
root's own analogs predict the next root, and the previous one back, within a quarter of
their separation bounds: the test of a step of the continuation.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from assur.kinematics.higher.groups import HigherGroup, K, values
from assur.kinematics.higher.modes import coefficients
from assur.kinematics.higher.roots import (
    RealRoots,
    polish,
    real_roots,
    separation,
    trig_form,
)

__all__ = ["Chains", "chains"]

TWO_PI = 2.0 * np.pi
#: Columns of the uniform grid per turn, besides the requested angles.
BASE = 72


@dataclass(frozen=True, eq=False)
class _Column:
    """The real roots at the crank angles of a grid, per design: θ (a first estimate), the sign
    of Φ′ and the bracket of each, shape (..., R), NaN (sign 0) after the last
    (:class:`~assur.kinematics.higher.roots.RealRoots`); and the coefficients of p,
    (..., 2m + 1)."""

    theta: np.ndarray
    slope: np.ndarray
    low: np.ndarray
    high: np.ndarray
    coef: np.ndarray


def _columns(group: HigherGroup[K], k: K) -> _Column:
    """The real roots of the group's eliminant at the inputs ``k`` (plain, shape (..., D))."""
    with np.errstate(all="ignore"):
        coef = coefficients(group, k)
    shape = coef.shape[:-1]
    flat = coef.reshape(-1, coef.shape[-1])
    a, b = trig_form(flat)
    found: RealRoots = real_roots(a, b)
    width = found.theta.shape[-1]
    theta, slope, low, high = (getattr(found, f).reshape(shape + (width,))
                               for f in ("theta", "slope", "low", "high"))
    return _Column(theta, slope, low, high, coef)


def _chord(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|e^{ia} − e^{ib}|, NaN where either is NaN."""
    return np.asarray(2.0 * np.abs(np.sin(0.5 * (a - b))))


def _links(here: _Column, there: _Column) -> np.ndarray:
    """For each root at ``here`` (..., R), the index of the nearest root at ``there``, where
    that root is also the nearest back and has the same sign of Φ′; −1 elsewhere."""
    with np.errstate(invalid="ignore"):
        dist = _chord(here.theta[..., :, None], there.theta[..., None, :])
    dist = np.where(np.isnan(dist), np.inf, dist)
    forward = np.argmin(dist, axis=-1)
    backward = np.argmin(dist, axis=-2)
    width = forward.shape[-1]
    same = np.take_along_axis(there.slope, forward, axis=-1) == here.slope
    ok = same & (here.slope != 0) \
        & (np.take_along_axis(backward, forward, axis=-1) == np.arange(width))
    return np.asarray(np.where(ok, forward, -1))


def _from_first(links: np.ndarray) -> np.ndarray:
    """The maps from the first column to every column (U + 1, D, R), composed from the links
    of each column to the next (U, D, R; −1 where a root has none) by doubling: after the
    step of k, the map of column c starts at column max(0, c − 2k); log₂ U steps."""
    width = links.shape[-1]
    same = np.broadcast_to(np.arange(width), links.shape[1:])
    maps = np.concatenate([same[None], links])
    k = 1
    while k < maps.shape[0]:
        before = maps[:-k]
        went = np.take_along_axis(maps[k:], np.maximum(before, 0), axis=-1)
        maps = np.concatenate([maps[:k], np.where(before >= 0, went, -1)])
        k *= 2
    return maps


@dataclass(frozen=True, eq=False)
class Chains:
    """The candidate path of the sketched mode's root over one turn forward from φ = 0.

    Attributes
    ----------
    columns : ndarray, shape (U + 1,)
        The crank angles of the columns, increasing from 0 to 2π (the last is the first a
        turn later).
    theta, apart, slope : ndarray, shape (U + 1, D)
        The root on the path at each column, its separation bound from every other root of
        p, and the sign of Φ′ there; NaN (0 for the sign) off the path.
    around : ndarray, bool, shape (D,)
        The path reaches φ = 2π.
    closed : ndarray, bool, shape (D,)
        It reaches φ = 2π at the root where it started.
    """

    columns: np.ndarray
    theta: np.ndarray
    apart: np.ndarray
    slope: np.ndarray
    around: np.ndarray
    closed: np.ndarray


def chains(group: HigherGroup[K], inputs: Any, wanted: np.ndarray, theta0: np.ndarray,
           found: np.ndarray) -> Chains:
    """The path of the roots θ₀ (D,) of the sketch over a turn, from root to nearest root.

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
        A path is lost where the sketched mode's root is in no bracket at φ = 0, or where
        the nearest root at the next column is not nearest back, or has the other sign of
        Φ′. The path is a candidate: the caller checks every link against the root's
        analogs before it takes it for the mode's.
    """
    d = theta0.shape[0]
    columns = np.union1d(np.concatenate([[0.0], wanted]), TWO_PI / BASE * np.arange(BASE))
    u = columns.size
    k = values(inputs(np.broadcast_to(columns[:, None], (u, d))))
    col = _columns(group, k)
    with np.errstate(invalid="ignore"):
        start = np.mod(theta0[:, None] - col.low[0], TWO_PI) <= col.high[0] - col.low[0]
    i0 = np.argmax(start, axis=-1)
    alive = found & start.any(axis=-1)
    nxt = _Column(*(np.concatenate([getattr(col, f)[1:], getattr(col, f)[:1]])
                    for f in ("theta", "slope", "low", "high", "coef")))
    links = _links(col, nxt)
    start_at = np.where(alive, i0, -1)[None, :, None]
    index = np.take_along_axis(_from_first(links), np.maximum(start_at, 0), axis=-1)[..., 0]
    index = np.where(start_at[..., 0] >= 0, index, -1)
    rows = np.arange(d)
    on = index >= 0
    at = np.append(np.arange(u), 0)[:, None], rows[None, :], np.maximum(index, 0)

    coef = col.coef[at[:2]]
    a, b = trig_form(coef.reshape(-1, coef.shape[-1]))
    with np.errstate(all="ignore"):
        theta = polish(a, b, np.where(on, col.low[at], np.nan).reshape(-1, 1),
                       np.where(on, col.high[at], np.nan).reshape(-1, 1)).reshape(on.shape)
        apart = separation(coef, theta)
    return Chains(np.append(columns, TWO_PI), theta, apart, np.where(on, col.slope[at], 0.0),
                  on[-1], on[-1] & (index[-1] == index[0]))
