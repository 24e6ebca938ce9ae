"""The force a higher pair transmits: along the common normal at its contact, and only pushing.

Without friction a higher pair (cam and follower, two teeth) transmits a force along the
common normal n of its profiles only. In the replacing mechanism (:mod:`assur.kinematics.
contact`) the pair is a massless link joining the two centres of curvature — a two-force
member lying on that normal — so the group-by-group kinetostatics
(:func:`~assur.forces.solver.kinetostatics`) of the replacing mechanism gives the contact
force as the reaction in either hinge of the replacing link. :func:`contact_force` reads it
along n; the contact holds where it pushes (N ≥ 0). Where the follower's motion would need
the cam to pull it (a force-closed follower whose spring or weight is too weak for its
inertia), the contact is lost: :func:`lost_intervals` gives those intervals of the input
with :attr:`~assur.kinematics.reasons.Reason.CONTACT_LOST`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from assur.forces.solver import ForceAnalysis
from assur.kinematics import jets as J
from assur.kinematics.analysis import Motion
from assur.kinematics.contact import followers
from assur.kinematics.existence import FailureInterval
from assur.kinematics.reasons import Reason
from assur.model import LinkId, PairId
from assur.typing import BoolArray, FloatArray, Value

__all__ = ["ContactForce", "contact_force", "contact_forces", "contact_record",
           "lost_intervals"]


class ContactForce(NamedTuple):
    """The force of a higher pair over the positions.

    Attributes
    ----------
    normal : ndarray
        N, the force of the cam on the follower along the common normal (N; > 0 pushing).
    tangential : ndarray
        Its component across the normal (N): zero up to round-off for a massless replacing
        link — the check that the pair transmits the normal force only.
    holds : ndarray, bool
        Where the contact holds (N ≥ 0; False where the forces are not solved).
    reason : ndarray, int8
        0 where it holds, :attr:`Reason.CONTACT_LOST` where the cam would have to pull, and
        the kinematic reason of the pair where it does not assemble.
    """

    normal: FloatArray
    tangential: FloatArray
    holds: BoolArray
    reason: np.ndarray


def contact_force(forces: ForceAnalysis, pair: PairId, normal: Value, follower: LinkId,
                  kinematic: np.ndarray | None = None) -> ContactForce:
    """The normal force of a higher pair from the reaction in a hinge of its replacing link.

    Parameters
    ----------
    forces : ForceAnalysis
        The kinetostatics of the replacing mechanism.
    pair : pair id
        The revolute pair joining the replacing link to the follower (or to the cam).
    normal : complex ndarray or Jet
        The unit common normal at the contact, from the cam towards the follower
        (:attr:`assur.kinematics.contact.Contact.normal`).
    follower : link id
        The follower's link, or the replacing link when ``pair`` joins it to the cam: the
        reaction is turned into the force acting on the follower's side.
    kinematic : ndarray of int8, optional
        The pair's kinematic reason per position (:attr:`~assur.kinematics.contact.Contact.
        reason`); it is kept where it is not 0.

    Returns
    -------
    ContactForce

    Examples
    --------
    See ``tests/assur/test_contact.py``: the cam of an eccentric with a rocking roller
    follower against a Newton–Euler solve of the whole mechanism.
    """
    reaction = forces.reactions[pair]
    on_follower = 1.0 if reaction.links[1] == follower else -1.0
    along = on_follower * (reaction.x + 1j * reaction.y) * np.conj(np.asarray(J.value(normal)))
    push, across = along.real, along.imag
    solved = forces.reason == 0
    holds = solved & (push >= 0.0)
    reason = np.where(solved & ~holds, Reason.CONTACT_LOST, Reason.ASSEMBLES)
    if kinematic is not None:
        reason = np.where(kinematic != 0, kinematic, reason)
    return ContactForce(push, across, holds & (reason == 0), reason.astype(np.int8))


def contact_forces(motion: Motion, forces: ForceAnalysis) -> dict[PairId, ContactForce]:
    """The normal force of every higher pair of an analysed mechanism whose contact normal
    is known: along the replacing link hinged to the follower, or normal to a flat face.

    Parameters
    ----------
    motion : Motion
        The kinematics (:func:`~assur.kinematics.analysis.analyse`, with analogs).
    forces : ForceAnalysis
        Its kinetostatics.

    Returns
    -------
    dict
        Higher pair → :class:`ContactForce`.
    """
    return {follower.pair: contact_force(forces, follower.hinge, follower.normal.v,
                                         follower.link, follower.reason)
            for follower in followers(motion) if follower.normal is not None}


def contact_record(found: dict[PairId, ContactForce], q: FloatArray, crank: bool
                   ) -> dict[str, dict[str, object]]:
    """The ``contacts`` of the forces' JSON: per higher pair its normal force (N), the
    reason per position (null where the contact holds) and the intervals where it is lost
    (crank positions in degrees), each with its reason and sentence."""
    from assur.records import floats

    return {str(pair): {
        "normal": floats(force.normal), "tangential": floats(force.tangential),
        "reason": [None if r == 0 else int(r) for r in np.ravel(force.reason)],
        "lost": [interval.to_dict(crank)
                 for interval in lost_intervals(q, np.ravel(force.normal), periodic=crank)]}
        for pair, force in found.items()}


def lost_intervals(q: FloatArray, normal: FloatArray, *, periodic: bool = True
                   ) -> list[FailureInterval]:
    """The intervals of the input where the contact force would pull (N < 0).

    Each end is where N crosses 0, interpolated linearly between the two grid positions
    around it; for a full-turn crank (``periodic``) an interval may wrap past 2π (then
    ``end < start``).

    Parameters
    ----------
    q : ndarray, shape (N,)
        The input positions (rad, increasing, one turn for ``periodic``).
    normal : ndarray, shape (N,)
        The normal force N at them (N), NaN where not solved.
    periodic : bool
        The positions cover a full turn: the last one is followed by the first.

    Returns
    -------
    list of FailureInterval
        Reason :attr:`Reason.CONTACT_LOST`; ``worst_margin`` the most negative N over the
        largest |N| of the cycle, ``shortfall`` that N (newtons, unit ``'N'``).

    Examples
    --------
    >>> import numpy as np
    >>> q = np.radians(np.arange(0.0, 360.0, 30.0))
    >>> [np.degrees([i.start, i.end]).round(6).tolist() for i in lost_intervals(q, np.cos(q) + 0.5)]
    [[120.0, 240.0]]
    """
    pulls = normal < 0.0
    if not pulls.any():
        return []
    size = len(q)
    scale = float(np.nanmax(np.abs(normal)))
    period = 2.0 * math.pi if periodic else math.inf
    # positions in cycle order from one where the contact holds, so that no run wraps
    order = np.roll(np.arange(size), -int(np.argmin(pulls))) if periodic else np.arange(size)
    edges = np.diff(np.concatenate(([0], pulls[order].astype(int), [0])))
    out = []
    for first, last in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1,
                           strict=True):
        start = _crossing(q, normal, order[first - 1], order[first], period) if first > 0 \
            else float(q[order[first]])
        beyond = order[(last + 1) % size] if periodic or last + 1 < size else None
        end = float(q[order[last]]) if beyond is None or pulls[beyond] \
            else _crossing(q, normal, order[last], beyond, period)
        run = order[first:last + 1]
        worst = int(run[np.argmin(normal[run])])
        out.append(FailureInterval(start % period if periodic else start,
                                   end % period if periodic else end, int(Reason.CONTACT_LOST),
                                   float(normal[worst]) / scale, float(q[worst]),
                                   float(normal[worst]), "N"))
    return out


def _crossing(q: FloatArray, normal: FloatArray, before: int, after: int, period: float
              ) -> float:
    """Where N, linear between the positions ``before`` and ``after``, is 0."""
    q0, q1 = float(q[before]), float(q[after])
    if q1 < q0:
        q1 += period
    n0, n1 = float(normal[before]), float(normal[after])
    return q0 + (q1 - q0) * n0 / (n0 - n1)
