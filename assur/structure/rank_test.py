"""Numeric rank test of the velocity constraints at a given pose (``structure.md`` §3.4).

Every moving link has velocity unknowns (vx, vy, ω) about the global origin. An R pair at
point c between links a and b gives two rows (equal velocities of the material points at c);
a P pair gives the row ω_a − ω_b = 0 and the row n·(v_a(c) − v_b(c)) = 0 with n the normal
of the slide line through c. With the frame columns dropped, ``W_geom = 3n − rank J`` and
``q_geom = rows − rank J``. Counting cannot see special dimensions (a parallelogram with an
extra parallel crank); this test can, and it names the passive-link candidates.

The pose is the chain's sketch (:class:`~assur.model.Sketch`, the table's ``geometry:``),
which gives every joint a point and every slider pair a direction; without a sketch the
test is skipped.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from assur.model import Chain, LinkId, Pair, PairId, PairType

__all__ = ["RankResult", "constraint_jacobian", "pose_from_geometry", "rank_test"]

_RTOL = 1e-9


@dataclass(frozen=True)
class RankResult:
    """Outcome of the rank test.

    Attributes
    ----------
    rows, rank : int
        Size and numeric rank of the constraint Jacobian.
    W_geom, q_geom : int
        Mobility and number of redundant constraints with the given dimensions.
    passive : tuple
        Passive-link candidates (removing one keeps W_geom and removes its constraints).
    singular : tuple of tuple
        Links of groups that lose rank at this pose (dead centres).
    """

    rows: int
    rank: int
    W_geom: int
    q_geom: int
    passive: tuple[LinkId, ...]
    singular: tuple[tuple[LinkId, ...], ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {"rows": self.rows, "rank": self.rank, "W_geom": self.W_geom,
                "q_geom": self.q_geom, "passive": list(self.passive),
                "singular": [list(group) for group in self.singular]}


def pose_from_geometry(chain: Chain) -> dict[PairId, tuple[complex, complex | None]] | None:
    """Pair points (and slide directions) from the chain's sketch, or None without one.

    >>> from assur.io.chain_table import chain_from_dict
    >>> chain = chain_from_dict({"mechanism": {"pairs": [
    ...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "P", "links": [1, 0],
    ...      "guide": 0}], "inputs": [1]},
    ...     "geometry": {"A": {"point": [0, 0]}, "B": {"point": [5, 0], "direction": [2, 0]}}})
    >>> pose_from_geometry(chain)
    {'A': (0j, None), 'B': ((5+0j), (2+0j))}
    """
    return None if chain.geometry is None else chain.geometry.pose(chain.pairs)


def constraint_jacobian(pairs: Iterable[Pair], pose: dict[PairId, tuple[complex, complex | None]],
                        columns: list[LinkId], *, locked: Iterable[Pair] = ()) -> np.ndarray:
    """Velocity-constraint rows of ``pairs`` over the (vx, vy, ω) columns of ``columns``.

    Links not in ``columns`` are fixed. A ``locked`` pair (a frozen actuator) gets one more
    row that stops its own relative motion.
    """
    index = {link: k for k, link in enumerate(columns)}
    points = [point for point, _ in pose.values()] or [1.0]
    scale = max(1.0, max(abs(c) for c in points))
    rows: list[np.ndarray] = []

    def row_for(pair: Pair, vec: complex, rotation: bool) -> np.ndarray:
        c = pose[pair.id][0] / scale
        row = np.zeros(3 * len(columns))
        for link, sign in zip(pair.links, (1.0, -1.0), strict=True):
            if link not in index:
                continue
            k = 3 * index[link]
            if rotation:
                row[k + 2] = sign
            else:
                row[k:k + 3] = sign * np.array([vec.real, vec.imag,
                                                -vec.real * c.imag + vec.imag * c.real])
        return row

    for pair in pairs:
        _, direction = pose[pair.id]
        if pair.type is PairType.R:
            rows += [row_for(pair, 1.0 + 0j, False), row_for(pair, 1j, False)]
        else:
            assert direction is not None  # a P pair has its slide direction
            normal = 1j * direction / abs(direction)
            rows += [row_for(pair, 0j, True), row_for(pair, normal, False)]
    for pair in locked:
        _, direction = pose[pair.id]
        if pair.type is PairType.R:
            rows.append(row_for(pair, 0j, True))
        else:
            assert direction is not None
            rows.append(row_for(pair, direction / abs(direction), False))
    if not rows:
        return np.zeros((0, 3 * len(columns)))
    return np.vstack(rows)


def _rank(matrix: np.ndarray) -> int:
    if matrix.size == 0:
        return 0
    values = np.linalg.svd(matrix, compute_uv=False)
    return int(np.sum(values > _RTOL * max(values[0], 1.0)))


def rank_test(chain: Chain, pose: dict[PairId, tuple[complex, complex | None]], *,
              fixed: Iterable[LinkId] = (),
              groups: Iterable[tuple[tuple[LinkId, ...], tuple[Pair, ...], tuple[Pair, ...]]] = ()
              ) -> RankResult:
    """Rank of the constraint Jacobian at ``pose``; passive links and singular groups.

    Parameters
    ----------
    chain : Chain
    pose : dict
        From :func:`pose_from_geometry`.
    fixed : iterable of link ids
        Links never proposed as passive (frame, inputs, actuator members).
    groups : iterable of (links, pairs, locked pairs)
        The accepted groups, tested one by one with the known links held fixed.
    """
    moving = [link for link in chain.links if link != chain.frame]
    matrix = constraint_jacobian(chain.pairs, pose, moving)
    rank = _rank(matrix)
    rows = matrix.shape[0]
    w_geom, q_geom = 3 * len(moving) - rank, rows - rank
    passive = []
    if q_geom > 0:
        skip = set(fixed) | {chain.frame}
        for link in moving:
            if link in skip:
                continue
            kept = [p for p in chain.pairs if link not in p.links]
            degree = len(chain.pairs) - len(kept)
            others = [x for x in moving if x != link]
            reduced = constraint_jacobian(kept, pose, others)
            r = _rank(reduced)
            if 3 * len(others) - r == w_geom and q_geom - (reduced.shape[0] - r) == 2 * degree - 3:
                passive.append(link)
    singular = []
    for links, pairs, locked in groups:
        block = constraint_jacobian(pairs, pose, list(links), locked=locked)
        if _rank(block) < 3 * len(links):
            singular.append(tuple(links))
    return RankResult(rows, rank, w_geom, q_geom, tuple(passive), tuple(singular))
