"""Kinematic model of the rhomboid orientation mechanism over the actuator's stroke.

The chain (``mechanism.yaml`` beside this module): base 4, short rocker 1 (platform),
coupler 2, long rocker 3, actuator cylinder 5 and rod 6; hinges A = 4–1, B = 1–2, C = 2–3
(the rod's hinge 6–3 sits on the same axis), D = 3–4, E = 4–5; the driven prismatic pair
5–6 is the input. Frozen, the cylinder and rod form one link of length ``s`` (the input
coordinate), and the chain splits into two RRR dyads (``structure.md`` T21):

1. ``({5,6}, 3)`` on the base hinges E and D, internal joint C;
2. ``(1, 2)`` on the base hinge A and on C, internal joint B — taken on the kite branch
   (B is the mirror image of D in the diagonal AC; the other assembly is D itself).

Coordinates: A at the origin (the post), D at ``−l1`` and E at ``l5 − l1`` on the x axis,
C above it. Angles in radians, lengths in the caller's unit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from assur import Jet, solve_rrr

__all__ = ["KITE_BRANCH", "Motion", "actuator_positions", "simulate"]

Array = npt.NDArray[np.float64]
Points = npt.NDArray[np.complex128]

KITE_BRANCH: dict[str, int] = {"C": -1, "B": -1}
"""Assembly signs σ of the two dyads: C above the base line (left of D→E is below, so the
dyad (E, D) takes σ = −1 with H_i = E), B on the far side of AC from D."""


@dataclass(frozen=True)
class Motion:
    """The mechanism over the actuator's stroke; arrays of shape ``(..., N)``.

    Attributes
    ----------
    s : ndarray
        Actuator length ``|EC|`` (the input coordinate).
    a, d, e : ndarray, complex
        Base hinges A (the post), D and E (broadcast to the shape of ``s``).
    b, c : ndarray, complex
        Moving joints B and C (NaN where the chain does not assemble).
    platform : ndarray
        Angle of the short rocker AB (the platform), unwrapped along the stroke.
    angle_b : ndarray
        Angle at B between BA and BC, in [0, π] (the patent's transmission angle b).
    angle_c : ndarray
        Angle at C between CE (actuator) and CD (long rocker), in [0, π].
    angle_adc : ndarray
        Angle ADC of the base and the long rocker, in [0, π].
    post_distance : ndarray
        Signed distance from A to the actuator's axis EC (positive: A on the right of E→C).
    lever_arm : ndarray
        ``ds/dφ``, the actuator's length change per radian of the platform: by virtual work,
        the torque on the platform per unit of actuator force (its effective lever arm).
    exists : ndarray of bool
        Both dyads assemble.
    margin : ndarray
        The smaller of the two dyads' existence margins (``1 − |cos|`` at their outer hinge).
    reason : ndarray of int
        Where the chain does not assemble, the failing dyad's reason code
        (:data:`assur.REASONS`), the actuator's dyad checked first; 0 elsewhere.
    """

    s: Array
    a: Points
    d: Points
    e: Points
    b: Points
    c: Points
    platform: Array
    angle_b: Array
    angle_c: Array
    angle_adc: Array
    post_distance: Array
    lever_arm: Array
    exists: npt.NDArray[np.bool_]
    margin: Array
    reason: npt.NDArray[np.int8]

    @property
    def stroke(self) -> Array:
        """Platform stroke: the range of the platform angle over the positions."""
        return np.ptp(self.platform, axis=-1)

    @property
    def transmission(self) -> Array:
        """Transmission angles at B and C folded into [0, π/2]: shape ``(2, ..., N)``."""
        both = np.stack([self.angle_b, self.angle_c])
        return np.minimum(both, np.pi - both)

    @property
    def min_transmission(self) -> Array:
        """Smallest transmission angle at B over the stroke (the patent's ``b_min``)."""
        return self.transmission[0].min(axis=-1)

    @property
    def min_clearance(self) -> Array:
        """Smallest distance from the post to the actuator's axis over the stroke."""
        return np.abs(self.post_distance).min(axis=-1)


def _angle(p: Points, q: Points, r: Points) -> Array:
    """Angle at q between q→p and q→r, in [0, π]."""
    return np.abs(np.angle((r - q) / (p - q)))


def actuator_positions(l_i: npt.ArrayLike, l_d: npt.ArrayLike, n: int) -> Array:
    """``n`` actuator lengths evenly spread from ``l_i`` to ``l_d`` (shape ``(..., n)``)."""
    t = np.linspace(0.0, 1.0, n)
    l_i = np.asarray(l_i, dtype=float)[..., None]
    return l_i + (np.asarray(l_d, dtype=float)[..., None] - l_i) * t


def simulate(l1: npt.ArrayLike, l2: npt.ArrayLike, l5: npt.ArrayLike, s: npt.ArrayLike,
             *, delta: float = 0.0) -> Motion:
    """Solve the mechanism at the given actuator lengths.

    Parameters
    ----------
    l1, l2, l5 : array_like
        Short rocker (= base), coupler (= long rocker), and ``|DE|``; shape ``(..., 1)`` for
        several designs at once.
    s : array_like
        Actuator lengths ``|EC|``, broadcasting with the dimensions (e.g. from
        :func:`actuator_positions`).
    delta : float
        Assigned existence tolerance of the two dyads.

    Returns
    -------
    Motion
    """
    l1, l2, l5, s = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (l1, l2, l5, s)))
    a = np.zeros_like(s, dtype=complex)
    d = -l1 + 0j
    e = (l5 - l1) + 0j
    first = solve_rrr(e, d, Jet(s, 1.0), l2, KITE_BRANCH["C"], delta)
    second = solve_rrr(a, first.c, l1, l2, KITE_BRANCH["B"], delta)
    c, b = first.c.v, second.c.v
    with np.errstate(invalid="ignore", divide="ignore"):
        arm = c - e
        post = np.imag(np.conj(arm) * (a - e)) / np.abs(arm)
        return Motion(
            s=s, a=a, d=d, e=e, b=b, c=c,
            platform=np.unwrap(np.angle(b - a), axis=-1),
            angle_b=_angle(a, b, c), angle_c=_angle(e, c, d), angle_adc=_angle(a, d, c),
            post_distance=-post, lever_arm=1.0 / second.angle_i.d1,
            exists=first.exists & second.exists, margin=np.fmin(first.margin, second.margin),
            reason=np.where(first.exists, second.reason, first.reason))
