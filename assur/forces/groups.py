"""The closed-form equilibrium of each kind of dyad (``docs/forces.md`` §3).

One function per kind, looked up by the kind's code in :data:`assur.forces.solver.EQUILIBRIA`.
Each takes the group and a :class:`Loads` view of the known loads of its links (everything
later groups exert on them included) and returns a :class:`Solved`: the reactions of its pairs
as :class:`Transfer` records (force of one link on another, its point, and for a prismatic
pair the normal force and the couple) and the group's normalised determinant, whose zero is
the toggle or the parallel guides of the group.

Units: points in m (complex x + i·y), forces in N (complex), moments in N·m. Every value is an
array over the positions (and designs); nothing loops over them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING, Protocol

import numpy as np

from assur.model import LinkId, PairId

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.model import GroupModel

__all__ = ["ForceReason", "Loads", "Solved", "Transfer", "cross", "dot", "equilibrium_prp",
           "equilibrium_rpp", "equilibrium_rpr", "equilibrium_rrp", "equilibrium_rrr",
           "outer_link"]


class ForceReason(IntEnum):
    """Why the reactions at a position are not given (``ForceAnalysis.reason``)."""

    SOLVED = 0
    NOT_ASSEMBLED = 1
    TOGGLE = 2
    PARALLEL_GUIDES = 3
    INDETERMINATE = 4


@dataclass(frozen=True, slots=True)
class Transfer:
    """The reaction in one pair as the group equations give it.

    ``force`` is the force of ``source`` on ``target`` (N), acting at ``point`` (m); for a
    prismatic pair ``normal`` is its component along the guide's left normal n and ``couple``
    the moment about ``point`` of everything ``source`` exerts on ``target`` (N·m).
    """

    pair: PairId
    source: LinkId
    target: LinkId
    force: np.ndarray
    point: np.ndarray
    normal: np.ndarray | None = None
    couple: np.ndarray | None = None


@dataclass(frozen=True, slots=True)
class Solved:
    """The reactions of one group and its normalised determinant (0 where singular)."""

    transfers: tuple[Transfer, ...]
    determinant: np.ndarray
    singular: ForceReason


class Loads(Protocol):
    """What the group equations read: joint points, guide normals and the known loads."""

    def joint(self, pair: PairId) -> np.ndarray:
        """The point of a pair (m): a hinge, or the slider point K of a prismatic pair."""

    def normal(self, pair: PairId) -> np.ndarray:
        """The unit left normal n = i·u of a prismatic pair's current guide direction u."""

    def pair(self, pair: PairId) -> tuple[str, tuple[LinkId, LinkId]]:
        """The type of a pair (``"R"`` or ``"P"``) and its two links as the table lists them."""

    def force(self, link: LinkId) -> np.ndarray:
        """The resultant known force on a link (N)."""

    def moment(self, link: LinkId, point: np.ndarray) -> np.ndarray:
        """The resultant known moment on a link about a point (N·m)."""


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Planar cross product ``a_x·b_y − a_y·b_x`` of complex vectors.

    Examples
    --------
    >>> float(cross(np.array(1 + 0j), np.array(1j)))
    1.0
    """
    return np.asarray(a.real * b.imag - a.imag * b.real)


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Planar dot product ``a_x·b_x + a_y·b_y`` of complex vectors.

    Examples
    --------
    >>> float(dot(np.array(1 + 2j), np.array(3 - 1j)))
    1.0
    """
    return np.asarray(a.real * b.real + a.imag * b.imag)


def outer_link(group: GroupModel, side: str) -> LinkId:
    """The link p (side ``'i'``) or q (``'j'``) that a dyad's external pair joins.

    Examples
    --------
    >>> import assur
    >>> from pathlib import Path; import assur
    >>> TABLES = Path(assur.__file__).parents[1] / "input_tables"
    >>> model = assur.load_model(TABLES / "four_bar.yaml")
    >>> outer_link(model.groups[1], "i"), outer_link(model.groups[1], "j")
    (1, 0)
    """
    hinge = group.hinge_i if side == "i" else group.hinge_j
    if hinge is not None:
        return hinge.link
    guide = group.guide_i if side == "i" else group.guide_j
    assert guide is not None, "a dyad's external pair is a hinge or a guide"
    return guide.carrier


def _dyad(group: GroupModel) -> tuple[Mapping[str, PairId], LinkId, LinkId]:
    """The pair roles and the two links of a dyad."""
    assert group.j is not None, "a dyad has two links"
    return group.pairs, group.i, group.j


def equilibrium_rrr(group: GroupModel, loads: Loads) -> Solved:
    """L1 RRR: R_pi at H_i, R_qj at H_j, R_ji at C."""
    roles, i, j = _dyad(group)
    h_i, h_j, c = (loads.joint(roles[r]) for r in ("H_i", "H_j", "C"))
    a, b = h_i - c, h_j - c
    f_i = loads.force(i)
    f = f_i + loads.force(j)
    d = cross(a, b)
    r1 = -loads.moment(i, c)
    r2 = loads.moment(j, c) - cross(b, f)
    r_pi = (r1 * b - r2 * a) / d
    return Solved((
        Transfer(roles["H_i"], outer_link(group, "i"), i, r_pi, h_i),
        Transfer(roles["H_j"], outer_link(group, "j"), j, -f - r_pi, h_j),
        Transfer(roles["C"], j, i, -(r_pi + f_i), c),
    ), np.abs(d) / (np.abs(a) * np.abs(b)), ForceReason.TOGGLE)


def equilibrium_rrp(group: GroupModel, loads: Loads) -> Solved:
    """L2 RRP: slider i on the guide of p (N·n and M_pi at C), rod j."""
    roles, i, j = _dyad(group)
    c, h_j = loads.joint(roles["C"]), loads.joint(roles["H_j"])
    n = loads.normal(roles["P_i"])
    b = h_j - c
    f_i = loads.force(i)
    f = f_i + loads.force(j)
    bn = cross(b, n)
    normal = (loads.moment(j, c) - cross(b, f)) / bn
    along = normal * n
    return Solved((
        Transfer(roles["P_i"], outer_link(group, "i"), i, along, c, normal,
                 -loads.moment(i, c)),
        Transfer(roles["H_j"], outer_link(group, "j"), j, -f - along, h_j),
        Transfer(roles["C"], j, i, -(along + f_i), c),
    ), np.abs(bn) / np.abs(b), ForceReason.TOGGLE)


def equilibrium_rpr(group: GroupModel, loads: Loads) -> Solved:
    """L3 RPR: kulisa i (H_i to p), block j (H_j to q), internal N·n and M_ij at K = H_j."""
    roles, i, j = _dyad(group)
    h_i, k = loads.joint(roles["H_i"]), loads.joint(roles["H_j"])
    n = loads.normal(roles["P_c"])
    couple = -loads.moment(j, k)
    t = cross(k - h_i, n)
    normal = (loads.moment(i, h_i) - couple) / t
    along = normal * n
    return Solved((
        Transfer(roles["H_i"], outer_link(group, "i"), i, along - loads.force(i),
                 h_i),
        Transfer(roles["H_j"], outer_link(group, "j"), j, -along - loads.force(j), k),
        Transfer(roles["P_c"], i, j, along, k, normal, couple),
    ), np.abs(t) / np.abs(k - h_i), ForceReason.INDETERMINATE)


def equilibrium_prp(group: GroupModel, loads: Loads) -> Solved:
    """L4 PRP: i on the guide of p, j on the guide of q, hinge C."""
    roles, i, j = _dyad(group)
    c = loads.joint(roles["C"])
    n_i, n_j = loads.normal(roles["P_i"]), loads.normal(roles["P_j"])
    f_i = loads.force(i)
    f = f_i + loads.force(j)
    den = cross(n_i, n_j)
    normal_i = cross(n_j, f) / den
    normal_j = cross(f, n_i) / den
    return Solved((
        Transfer(roles["P_i"], outer_link(group, "i"), i, normal_i * n_i, c, normal_i,
                 -loads.moment(i, c)),
        Transfer(roles["P_j"], outer_link(group, "j"), j, normal_j * n_j, c, normal_j,
                 -loads.moment(j, c)),
        Transfer(roles["C"], j, i, -(normal_i * n_i + f_i), c),
    ), np.abs(den), ForceReason.PARALLEL_GUIDES)


def equilibrium_rpp(group: GroupModel, loads: Loads) -> Solved:
    """L5 RPP: j hinged at H_j carries the guide u_T of i; i also slides on the guide u_S of
    p; both prismatic pairs act at K = C."""
    roles, i, j = _dyad(group)
    c, h_j = loads.joint(roles["P_c"]), loads.joint(roles["H_j"])
    n_t, n_s = loads.normal(roles["P_c"]), loads.normal(roles["P_i"])
    f_i = loads.force(i)
    den = cross(n_t, n_s)
    inner = cross(n_s, f_i) / den
    outer = cross(f_i, n_t) / den
    couple = loads.moment(j, h_j) - inner * cross(c - h_j, n_t)
    return Solved((
        Transfer(roles["P_c"], j, i, inner * n_t, c, inner, couple),
        Transfer(roles["P_i"], outer_link(group, "i"), i, outer * n_s, c, outer,
                 -loads.moment(i, c) - couple),
        Transfer(roles["H_j"], outer_link(group, "j"), j, inner * n_t - loads.force(j), h_j),
    ), np.abs(den), ForceReason.PARALLEL_GUIDES)
