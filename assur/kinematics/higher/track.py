"""The candidate path of the sketched mode over a grid of crank angles, all angles at once.

At every angle of a grid (the requested ones and a uniform one of ``BASE`` per turn) and for
every design, the real roots of the eliminant are bracketed in one vectorised call
(:func:`~assur.kinematics.higher.roots.real_roots`). Real roots never cross: a root at one
angle goes on as a root at the next with the same sign of Φ′, or it meets its neighbour (of
the other sign) at a change point. The path from the sketched root takes at each angle the
nearest root that is nearest back and has the same sign, forward from φ = 0 and, where that
chain is lost, backward from φ = 2π; its roots are then polished, with the separation bound
of each from every other root of p, real or complex. The path is only a
candidate: a root and its neighbour may meet and a new pair appear between two angles, or a
pair closer than the samples' spacing may be missed. The caller
(:func:`~assur.kinematics.higher.continuation.follow_mode`) accepts a link only where the
root's own analogs predict the next root, and the previous one back, within a quarter of
their separation bounds: the test of a step of the continuation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from assur.kinematics.higher.groups import HigherGroup, K, row_offsets
from assur.kinematics.higher.modes import coefficients
from assur.kinematics.higher.roots import (
    RealRoots,
    chord,
    derivatives,
    polish,
    real_roots,
    separation,
    trig_form,
)

__all__ = ["Chains", "chains", "grid"]

TWO_PI = 2.0 * np.pi
#: Columns of the uniform grid per turn, besides the requested angles.
BASE = 72
#: A column of the uniform grid this close to a requested angle (rad) is left out.
SAME = 1e-9
#: The uniform grid.
_UNIFORM = TWO_PI / BASE * np.arange(BASE)


@dataclass(frozen=True, eq=False)
class _Column:
    """The real roots at the crank angles of a grid, per design: θ (a first estimate), the sign
    of Φ′ and the bracket of each, shape (..., R), NaN (sign 0) after the last
    (:class:`~assur.kinematics.higher.roots.RealRoots`, R the most real roots at any of
    them); the coefficients of p, (..., 2m + 1), and those of Φ, (..., m + 1) each
    (:func:`~assur.kinematics.higher.roots.trig_form`)."""

    theta: np.ndarray
    slope: np.ndarray
    low: np.ndarray
    high: np.ndarray
    coef: np.ndarray
    a: np.ndarray
    b: np.ndarray


def _columns(group: HigherGroup[K], k: K, u: int) -> _Column:
    """The real roots of the group's eliminant at the first ``u`` rows of the inputs ``k``
    (plain, shape (U + 1, D))."""
    with np.errstate(all="ignore"):
        coef = coefficients(group, k)[:u]
    shape = coef.shape[:-1]
    flat = coef.reshape(-1, coef.shape[-1])
    a, b = trig_form(flat)
    found: RealRoots = real_roots(a, b)
    # the roots come first in each row: the columns beyond the most at any angle are empty
    width = max(1, int(np.count_nonzero(found.slope, axis=-1).max(initial=0)))
    theta, slope, low, high = (getattr(found, f)[:, :width].reshape(shape + (width,))
                               for f in ("theta", "slope", "low", "high"))
    return _Column(theta, slope, low, high, coef, a.reshape(shape + a.shape[-1:]),
                   b.reshape(shape + b.shape[-1:]))


def _links(col: _Column) -> np.ndarray:
    """For each root at each column (U, D, R), the index of the nearest root at the next
    column (the last column's next is the first), where that root is also the nearest back
    and has the same sign of Φ′; −1 elsewhere."""
    theta = np.concatenate([col.theta[1:], col.theta[:1]])
    slope = np.concatenate([col.slope[1:], col.slope[:1]])
    with np.errstate(invalid="ignore"):
        dist = chord(col.theta[..., :, None], theta[..., None, :])
    dist[np.isnan(dist)] = np.inf
    forward = np.argmin(dist, axis=-1)
    at = row_offsets(forward.shape) + forward
    backward = np.argmin(dist, axis=-2)
    width = forward.shape[-1]
    ok = (slope.reshape(-1)[at] == col.slope) & (col.slope != 0) \
        & (backward.reshape(-1)[at] == np.arange(width))
    return np.asarray(np.where(ok, forward, -1))


def _from_first(links: np.ndarray) -> np.ndarray:
    """The maps from the first column to every column (U + 1, D, R), composed from the links
    of each column to the next (U, D, R; −1 where a root has none) by doubling: after the
    step of k, the map of column c starts at column max(0, c − 2k); log₂ U steps. A lost
    root goes to an extra slot R that every map keeps, −1 again in the result."""
    width = links.shape[-1]
    maps = np.empty((links.shape[0] + 1,) + links.shape[1:-1] + (width + 1,), dtype=links.dtype)
    maps[0] = np.arange(width + 1)
    maps[1:, ..., :width] = np.where(links >= 0, links, width)
    maps[1:, ..., width] = width
    rows = row_offsets(maps.shape)
    k = 1
    while k < maps.shape[0]:
        maps[k:] = maps.reshape(-1)[rows[k:] + maps[:-k]]
        k *= 2
    return np.asarray(np.where(maps[..., :width] == width, -1, maps[..., :width]))


@dataclass(frozen=True, eq=False)
class Chains:
    """The candidate path of the sketched mode's root over one turn: forward from φ = 0 and,
    where that is lost, backward from φ = 2π.

    Attributes
    ----------
    columns : ndarray, shape (U + 1,)
        The crank angles of the columns, increasing from 0 to 2π (the last is the first a
        turn later).
    theta, apart, slope : ndarray, shape (U + 1, D)
        The root on the path at each column, its separation bound from every other root of
        p, and the sign of Φ′ there; NaN (0 for the sign) off the path.
    forward, backward : ndarray, bool, shape (U + 1, D)
        The root at the column is on the chain of nearest roots from the sketched root at
        φ = 0, or on the one from it at φ = 2π going down (followed only where the forward
        one is lost before 2π). Where both hold it is the same root (the chains are then
        one). A sketched root in no bracket is on both at φ = 0 and 2π only.
    bracketed : ndarray, bool, shape (D,)
        The sketched root lies in a bracket at φ = 0 (the chains start from it).
    closed : ndarray, bool, shape (D,)
        The path reaches φ = 2π at the root where it started.
    """

    columns: np.ndarray
    theta: np.ndarray
    apart: np.ndarray
    slope: np.ndarray
    forward: np.ndarray
    backward: np.ndarray
    bracketed: np.ndarray
    closed: np.ndarray


def _inverse(links: np.ndarray) -> np.ndarray:
    """The links of each column back to the previous one (U, D, R): the root at the previous
    column linked to each root, −1 where none is (a link is mutual, so at most one is)."""
    out = np.full(links.shape, -1)
    c, d, i = np.nonzero(links >= 0)
    out[c, d, links[c, d, i]] = i
    return out


def _chain(maps: np.ndarray, start: np.ndarray) -> np.ndarray:
    """The index of the root reached at every column (U + 1, D) from the roots ``start`` (D,)
    of the first (−1 where a start is missing or the chain is lost)."""
    index = maps.reshape(-1)[row_offsets(maps.shape)[..., 0] + np.maximum(start, 0)]
    return np.asarray(np.where(start >= 0, index, -1))


def grid(wanted: np.ndarray) -> np.ndarray:
    """The columns of the path, increasing in [0, 2π): φ = 0, the requested angles ``wanted``
    (in [0, 2π)) and ``BASE`` uniform ones per turn, but for a uniform one within roundoff of
    a requested angle (that angle is the column)."""
    asked = np.unique(np.append(wanted, 0.0))
    # the distance of each uniform column to the nearest requested angle (sorted)
    after = np.minimum(np.searchsorted(asked, _UNIFORM), asked.size - 1)
    apart = np.minimum(np.abs(asked[after] - _UNIFORM), np.abs(_UNIFORM - asked[after - 1]))
    return np.asarray(np.unique(np.append(asked, _UNIFORM[apart > SAME])))


def chains(group: HigherGroup[K], k: K, columns: np.ndarray, theta0: np.ndarray,
           found: np.ndarray) -> Chains:
    """The path of the roots θ₀ (D,) of the sketch over a turn, from root to nearest root.

    Parameters
    ----------
    group : HigherGroup
        The group, drawn values of shape () or (D,).
    k : TriadInputs or ClassIVInputs
        The inputs (plain arrays) at the columns and at 2π, shape (U + 1, D).
    columns : ndarray, shape (U,)
        The columns (:func:`grid`).
    theta0 : ndarray, shape (D,)
        The eliminated angle of the sketched mode.
    found : ndarray, bool, shape (D,)
        Where the sketch picks a mode (the others are not followed).

    Returns
    -------
    Chains
        A chain is lost where the sketched mode's root is in no bracket at φ = 0, or where
        the nearest root at the next column is not nearest back, or has the other sign of
        Φ′; the path is the forward chain, and the backward one from φ = 2π where the forward
        one is lost. The path is a candidate: the caller checks every link against the
        root's analogs before it takes it for the mode's.
    """
    d = theta0.shape[0]
    u = columns.size
    col = _columns(group, k, u)  # the row at 2π is the first a turn later
    with np.errstate(invalid="ignore"):
        inside = np.mod(theta0[:, None] - col.low[0], TWO_PI) <= col.high[0] - col.low[0]
    alive = found & inside.any(axis=-1)
    links = _links(col)
    start = np.where(alive, np.argmax(inside, axis=-1), -1)
    ahead = _chain(_from_first(links), start)
    lost = (start >= 0) & (ahead[-1] < 0)
    behind = (_chain(_from_first(_inverse(links)[::-1]), np.where(lost, start, -1))[::-1]
              if lost.any() else np.full(ahead.shape, -1))
    index = np.where(ahead >= 0, ahead, behind)
    rows = np.arange(d)
    on = index >= 0
    at = np.append(np.arange(u), 0)[:, None], rows[None, :], np.maximum(index, 0)

    coef = col.coef[at[:2]]
    a, b = (v[at[:2]].reshape(-1, v.shape[-1]) for v in (col.a, col.b))
    # a sketched root in no bracket (its neighbour closer than the samples' spacing) is the
    # path's root at φ = 0 and 2π all the same, on neither chain beyond
    seed = found & ~alive
    ends = np.zeros(on.shape, dtype=bool)
    ends[[0, -1]] = seed
    with np.errstate(all="ignore"):
        theta = polish(a, b, np.where(on, col.low[at], np.nan).reshape(-1, 1),
                       np.where(on, col.high[at], np.nan).reshape(-1, 1)).reshape(on.shape)
        theta = np.where(ends, theta0, theta)
        apart = separation(coef, theta)
        # Φ′ is wanted only at the seeds off the chains (rare)
        slope = np.where(on, col.slope[at], np.where(ends, np.sign(derivatives(coef, theta)[1]), 0.0)
                         if ends.any() else 0.0)
    return Chains(np.append(columns, TWO_PI), theta, apart, slope, (ahead >= 0) | ends,
                  ((behind >= 0) & (index == behind)) | ends, alive,
                  (on[-1] & (index[-1] == start)) | seed)
