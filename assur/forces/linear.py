"""The equilibrium of an Assur group of any class as one linear solve (``docs/forces.md`` §3.1).

A group of n links with p lower pairs is statically determinate: 3n = 2p. Every revolute
pair has two unknowns (the force of one link on the other), every prismatic pair two (the
normal force N along the guide's left normal n and the couple M about the slider point K).
The three equilibrium equations of each link (d'Alembert, its known loads included) make one
square system per position, solved for all positions (and designs) at once with a batched
:func:`numpy.linalg.solve`, after the force of each external revolute pair has been condensed
out (read off its link's force equations: a triad's 12 unknowns become 6). It serves the
triads and the class IV groups (their entries in :data:`assur.forces.solver.EQUILIBRIA`); for
a dyad it gives what the closed forms of :mod:`assur.forces.groups` give.

Scaling: each link's moment equation is taken about the mean of its pair points and divided
by a length of the group (the RMS distance of its pair points from their mean), and a couple
is solved for in the same length's units, so that every entry of the matrix is of the order
of 1. The group's normalised determinant is the reciprocal condition number of the condensed
matrix, which is singular exactly where the whole one is (its 1-norm one,
``1/(‖A‖₁·‖A⁻¹‖₁)``, with ``‖A⁻¹‖₁`` estimated as LAPACK's condition estimator starts,
from one more batched solve): 0 where the reactions are indeterminate (the
constraint lines of the group's pairs meet in one point, the dead position). There, and where
the group is not assembled, the reactions are NaN; the solve never raises.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from assur.forces.groups import ForceReason, Loads, Solved, Transfer, cross
from assur.model import LinkId, PairId

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.model import GroupModel

__all__ = ["equilibrium_linear"]

#: A matrix with a reciprocal condition number at or below this is not solved (NaN).
_DEGENERATE = 1e-14


def _pairs(group: GroupModel, loads: Loads) -> list[tuple[PairId, str, LinkId, LinkId]]:
    """Every pair of the group with its type, the link whose reaction it solves for (the
    source: the link outside the group for an external pair) and the link it acts on."""
    layout = group.layout
    assert layout is not None, "a triad or a class IV group has a layout"
    members = set(layout.links)
    out = []
    for pair in (*layout.internal, *layout.external):
        kind, (first, second) = loads.pair(pair)
        source, target = (second, first) if second not in members else (first, second)
        out.append((pair, kind, source, target))
    return out


def equilibrium_linear(group: GroupModel, loads: Loads) -> Solved:
    """The reactions of every pair of a group of any class from one linear solve per position.

    Parameters
    ----------
    group : GroupModel
        A triad or a class IV group (its ``layout`` names its links and pairs).
    loads : Loads
        The joint points, guide normals and known loads of the group's links (SI units).

    Returns
    -------
    Solved
        One :class:`~assur.forces.groups.Transfer` per pair (for an external pair, the force
        of the outside link on the group's link), the reciprocal condition number of the
        scaled matrix, and :attr:`ForceReason.TOGGLE` as the reason where it is 0.

    Examples
    --------
    The eight-bar of ``input_tables`` with a torque on a leash of its triad:

    >>> from pathlib import Path
    >>> import numpy as np, assur
    >>> from assur.forces import ForceData, Load, kinetostatics
    >>> TABLES = Path(assur.__file__).parents[1] / "input_tables"
    >>> model = assur.load_model(TABLES / "eight_bar_triad.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, np.radians([0.0, 120.0]), analogs=True)
    >>> result = kinetostatics(motion, ForceData(loads=(Load(6, torque=-5.0),)))
    >>> bool(np.all(np.abs(result.power_balance) < 1e-12))
    True
    """
    layout = group.layout
    assert layout is not None, "a triad or a class IV group has a layout"
    pairs = _pairs(group, loads)
    if 2 * len(pairs) != 3 * len(layout.links):
        raise ValueError(f"group {group.label}: {len(layout.links)} links and {len(pairs)} "
                         "pairs are not statically determinate")
    points = {pair: loads.joint(pair) for pair, *_ in pairs}
    normals = {pair: loads.normal(pair) for pair, kind, *_ in pairs if kind == "P"}
    with np.errstate(invalid="ignore", divide="ignore"):
        centroid = sum(points.values()) / len(points)
        length = np.sqrt(sum(np.abs(p - centroid) ** 2 for p in points.values()) / len(points))
        matrix, rhs = _system(layout.links, pairs, points, normals, loads, length)
        unknowns, determinant = _condensed_solve(matrix, rhs, _eliminated(layout.links, pairs))
    transfers = []
    for k, (pair, kind, source, target) in enumerate(pairs):
        first, second = unknowns[..., 2 * k], unknowns[..., 2 * k + 1]
        if kind == "R":
            transfers.append(Transfer(pair, source, target, first + 1j * second,
                                      points[pair]))
        else:
            transfers.append(Transfer(pair, source, target, first * normals[pair],
                                      points[pair], first, second * length))
    return Solved(tuple(transfers), determinant, ForceReason.TOGGLE)


def _system(links: tuple[LinkId, ...], pairs: list[tuple[PairId, str, LinkId, LinkId]],
            points: dict[PairId, np.ndarray], normals: dict[PairId, np.ndarray],
            loads: Loads, length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The scaled equilibrium equations of the group's links: matrix (…, 3n, 3n) and right-hand
    side (…, 3n); rows x, y and moment/length per link, columns two per pair.

    The entries are written with the positions along the last axis (each entry one
    contiguous row of positions) and the matrices then laid out one after another, as the
    batched solve reads them.
    """
    shape = np.broadcast_shapes(*(np.shape(p) for p in points.values()), np.shape(length))
    size = 3 * len(links)
    row = {link: 3 * k for k, link in enumerate(links)}
    centres = {link: _mean([points[pair] for pair, _, source, target in pairs
                            if link in (source, target)]) for link in links}
    matrix = np.zeros((size, size, *shape))
    rhs = np.zeros((size, *shape))
    for k, (pair, kind, source, target) in enumerate(pairs):
        for link, sign in ((target, 1.0), (source, -1.0)):
            if link not in row:
                continue
            r, arm = row[link], (points[pair] - centres[link]) / length
            if kind == "R":
                matrix[r, 2 * k] += sign
                matrix[r + 1, 2 * k + 1] += sign
                matrix[r + 2, 2 * k] -= sign * arm.imag
                matrix[r + 2, 2 * k + 1] += sign * arm.real
            else:
                n = normals[pair]
                matrix[r, 2 * k] += sign * n.real
                matrix[r + 1, 2 * k] += sign * n.imag
                matrix[r + 2, 2 * k] += sign * cross(arm, n)
                matrix[r + 2, 2 * k + 1] += sign
    for link in links:
        r, force = row[link], loads.force(link)
        rhs[r] = -force.real
        rhs[r + 1] = -force.imag
        rhs[r + 2] = -loads.moment(link, centres[link]) / length
    return matrix, rhs


def _eliminated(links: tuple[LinkId, ...], pairs: list[tuple[PairId, str, LinkId, LinkId]]
                ) -> dict[int, int]:
    """The external revolute pairs whose force is read off their link's two force equations
    (at most one per link): the pair's index in ``pairs`` → the link's index in ``links``."""
    out: dict[int, int] = {}
    for k, (_, kind, source, target) in enumerate(pairs):
        if kind == "R" and source not in links and links.index(target) not in out.values():
            out[k] = links.index(target)
    return out


def _condensed_solve(matrix: np.ndarray, rhs: np.ndarray, eliminated: dict[int, int]
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Solve the system of :func:`_system` (positions last) with the external revolute pairs
    of ``eliminated`` condensed out; the unknowns (…, 3n) and the reciprocal condition number
    of the condensed matrix.

    The force of an external revolute pair on its link enters only that link's force rows,
    with the identity as coefficient: F = b_f − A_f·x for the other unknowns x. Put into the
    link's moment row, it leaves a system of 3n − 2e unknowns, singular exactly where the
    whole one is (the Schur complement of an identity block): a triad's 12 unknowns become 6,
    an eighth of the factorisation's arithmetic. ``matrix`` and ``rhs`` are changed in place.
    """
    size = matrix.shape[0]
    for pair, link in eliminated.items():
        force, moment = 3 * link, 3 * link + 2
        for column, source in ((2 * pair, force), (2 * pair + 1, force + 1)):
            factor = matrix[moment, column].copy()
            matrix[moment] -= factor * matrix[source]
            rhs[moment] -= factor * rhs[source]
    dropped_rows = [3 * link + i for link in eliminated.values() for i in (0, 1)]
    dropped = [2 * pair + i for pair in eliminated for i in (0, 1)]
    kept_rows = [r for r in range(size) if r not in dropped_rows]
    kept = [c for c in range(size) if c not in dropped]
    positions, m = matrix.shape[2:], len(kept)
    condensed = matrix[np.ix_(kept_rows, kept)].reshape(m * m, -1)
    x, rcond = _solve(np.ascontiguousarray(condensed.T).reshape(*positions, m, m),
                      np.ascontiguousarray(rhs[kept_rows].reshape(m, -1).T).reshape(*positions, m))
    unknowns = np.empty((*x.shape[:-1], size))
    unknowns[..., kept] = x
    coupling = matrix[np.ix_(dropped_rows, kept)]
    unknowns[..., dropped] = np.moveaxis(rhs[dropped_rows], 0, -1) - np.einsum(
        "rc...,...c->...r", coupling, x)
    return unknowns, rcond


def _mean(points: list[np.ndarray]) -> np.ndarray:
    return np.asarray(sum(points) / len(points))


def _solve(matrix: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Batched solve of ``matrix @ x = rhs`` and the reciprocal condition numbers; NaN (and a
    condition number of 0) where a matrix is not finite or singular, never an error.

    The reciprocal condition number is the 1-norm one, ``1/(‖A‖₁·‖A⁻¹‖₁)``, with ``‖A⁻¹‖₁``
    estimated from below by one step of Hager's method and Higham's alternating vector (as
    LAPACK's condition estimator starts): two batched solves in all, the unknowns included,
    instead of the singular values of every matrix. The estimate is exact for a diagonal
    matrix, mostly exact otherwise, and within a factor of 10 near a singular matrix, where it
    follows the direction in which the inverse grows (a power-method step).
    """
    n = matrix.shape[-1]
    eye = np.eye(n)
    finite = np.all(np.isfinite(matrix), axis=(-2, -1)) & np.all(np.isfinite(rhs), axis=-1)
    try:
        x, inverse_norm = _solve_regular(
            matrix if finite.all() else np.where(finite[..., None, None], matrix, eye), rhs)
    except np.linalg.LinAlgError:  # a matrix singular to the last bit: the batch's
        # singular values find every matrix that is singular or nearly so, left out
        values = np.linalg.svd(np.where(finite[..., None, None], matrix, eye), compute_uv=False)
        finite &= values[..., -1] > _DEGENERATE * values[..., 0]
        x, inverse_norm = _solve_regular(np.where(finite[..., None, None], matrix, eye), rhs)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        rcond = 1.0 / (np.einsum("...ij->...j", np.abs(matrix)).max(axis=-1) * inverse_norm)
    rcond = np.where(finite & np.isfinite(rcond), rcond, 0.0)
    good = rcond > _DEGENERATE
    return np.where(good[..., None], x, np.nan), rcond


def _solve_regular(matrix: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``matrix⁻¹ @ rhs`` and the estimate of ``‖matrix⁻¹‖₁`` (see :func:`_solve`); raises
    :class:`numpy.linalg.LinAlgError` if a matrix is singular to the last bit.

    With ``y = A⁻¹·(1/n, …, 1/n)`` and ``z = A⁻ᵀ·sign(y)``, both ``‖y‖₁`` and ``‖z‖∞`` are
    lower bounds of ``‖A⁻¹‖₁`` (``|zⱼ| = |sign(y)ᵀ·A⁻¹eⱼ| ≤ ‖A⁻¹eⱼ‖₁``), and so is
    ``‖A⁻¹b‖₁/‖b‖₁`` for Higham's ``bᵢ = (−1)ⁱ(1 + i/(n−1))``, ``‖b‖₁ = 3n/2``.
    """
    n = matrix.shape[-1]
    i = np.arange(n)
    start = np.stack(np.broadcast_arrays(np.where(np.isfinite(rhs), rhs, 0.0), 1.0 / n,
                                         (-1.0) ** i * (1.0 + i / max(n - 1, 1))), axis=-1)
    first = np.linalg.solve(matrix, start)
    x, uniform, alternating = first[..., 0], first[..., 1], first[..., 2]
    ascent = np.linalg.solve(np.swapaxes(matrix, -1, -2),
                             np.where(uniform >= 0.0, 1.0, -1.0)[..., None])[..., 0]
    inverse_norm = np.maximum(np.maximum(_norm1(uniform), np.max(np.abs(ascent), axis=-1)),
                              2.0 * _norm1(alternating) / (3.0 * n))
    return x, inverse_norm


def _norm1(x: np.ndarray) -> np.ndarray:
    """The 1-norm of each vector of a batch (last axis)."""
    return np.asarray(np.sum(np.abs(x), axis=-1))
