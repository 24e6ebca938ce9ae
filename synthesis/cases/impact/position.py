"""The mechanism at the instant of impact: rigid closure, rates, clearance geometry, normal ψ.

The pin on the coupler sits at the point B of the rigid four-bar closure (the RRR group
coupler–rocker solved by :func:`assur.solve_rrr` on the crank's joint A and the rocker's pivot
O4); the rocker, whose velocity before impact differs from its rigid-kinematics value, has its
bearing centre on the same circle about O4 at the distance ξ (the clearance) from the pin,
behind it when the rocker lags and ahead when it leads. The impact normal ψ is the direction
of the clearance vector from the bearing centre to the pin centre; the pin moves towards the
bearing wall along ψ.

Every function broadcasts over the crank angle and the rocker velocity before impact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from assur import Jet, solve_rrr
from assur.kinematics.jets import as_jet
from assur.typing import BoolArray, ComplexArray, FloatArray, IntArray
from synthesis.cases.impact.data import ImpactData

__all__ = ["REASONS", "ImpactPosition", "impact_position"]

#: Why a position has no impact: reason code → catalogue code of the sentence.
REASONS: tuple[str, ...] = ("case.impact.reason.impact", "case.impact.reason.not_assembled",
                            "case.impact.reason.no_approach")


@dataclass(frozen=True, slots=True)
class ImpactPosition:
    """The mechanism at the instant of impact; every array has the broadcast shape.

    Attributes
    ----------
    theta2, theta3 : ndarray
        Crank and coupler angles, rad (the coupler from A towards the pin).
    theta4_rigid : ndarray
        Rocker angle of the rigid closure (from O4 towards the pin), rad.
    theta4 : ndarray
        Rocker angle at impact (from O4 towards the bearing centre), rad.
    omega2, omega3 : ndarray
        Crank and coupler angular velocities before impact, rad/s (the coupler's is its
        rigid-kinematics value).
    omega4_rigid, omega4 : ndarray
        Rocker angular velocity of rigid kinematics and the prescribed one before impact.
    a, pin, bearing, o4 : ndarray of complex
        Joint A, pin centre (on the coupler), bearing centre (on the rocker), rocker pivot;
        the crank pivot O2 is the origin.
    psi : ndarray
        Impact normal: direction of the clearance vector bearing centre → pin centre, rad.
    exists : ndarray of bool
        Whether there is an impact at this position (the four-bar assembles and the pin
        approaches the wall).
    reason : ndarray of int
        Code of :data:`REASONS`.
    margin : ndarray
        Assembly margin of the RRR group (see :func:`assur.solve_rrr`).
    """

    theta2: FloatArray
    theta3: FloatArray
    theta4_rigid: FloatArray
    theta4: FloatArray
    omega2: FloatArray
    omega3: FloatArray
    omega4_rigid: FloatArray
    omega4: FloatArray
    a: ComplexArray
    pin: ComplexArray
    bearing: ComplexArray
    o4: ComplexArray
    psi: FloatArray
    exists: BoolArray
    reason: IntArray
    margin: FloatArray

    @property
    def shape(self) -> tuple[int, ...]:
        """The broadcast shape of the positions."""
        return self.psi.shape


def impact_position(data: ImpactData, theta2: ArrayLike | None = None,
                    omega4: ArrayLike | None = None) -> ImpactPosition:
    """Place the mechanism at the instant of impact.

    Parameters
    ----------
    data : ImpactData
        Dimensions, clearance, crank speed and assembly σ.
    theta2 : array_like, optional
        Crank angle(s), rad; default ``data.theta2``.
    omega4 : array_like, optional
        Rocker velocity(ies) before impact, rad/s; default ``data.omega4``. Broadcasts with
        ``theta2``.

    Returns
    -------
    ImpactPosition
        Positions where the four-bar does not assemble, or where the rocker moves exactly
        with the pin, have ``exists`` False, a reason code and NaN geometry.

    Notes
    -----
    The rigid closure is the RRR group with outer hinges A (on the crank) and O4, lengths r3
    and r4; A is passed as a jet in the crank angle, so the closure's rates are exact analogs
    (dθ3/dθ2, dθ4/dθ2) times the crank speed. The bearing centre is on the circle of radius
    r4 about O4, a chord ξ from the pin: θ4 = θ4,rigid − s·2·arcsin(ξ / 2r4), with
    s = sign(θ4'rigid − θ4') (s = +1: the rocker lags).
    """
    theta2 = np.asarray(data.theta2 if theta2 is None else theta2, dtype=float)
    omega4 = np.asarray(data.omega4 if omega4 is None else omega4, dtype=float)
    theta2, omega4 = np.broadcast_arrays(theta2, omega4)
    crank = np.asarray(data.r2 * np.exp(1j * theta2), dtype=np.complex128)
    o4 = np.full(theta2.shape, complex(data.r1, 0.0))
    group = solve_rrr(Jet(crank, 1j * crank, -crank), o4, data.r3, data.r4, data.sigma)
    assert group.angle_j is not None  # an RRR group turns both its links
    angle_i, angle_j = as_jet(group.angle_i), as_jet(group.angle_j)
    assembles = np.asarray(group.exists, dtype=bool) & np.isfinite(angle_i.v)
    omega2 = np.full(theta2.shape, float(data.omega2))
    theta3 = np.where(assembles, angle_i.v, np.nan)
    theta4_rigid = np.where(assembles, angle_j.v, np.nan)
    omega3 = np.where(assembles, angle_i.d1 * omega2, np.nan)
    omega4_rigid = np.where(assembles, angle_j.d1 * omega2, np.nan)
    lag = np.sign(np.where(assembles, omega4_rigid - omega4, 0.0))
    chord = 2.0 * np.arcsin(data.clearance / (2.0 * data.r4))
    theta4 = np.where(lag != 0, theta4_rigid - lag * chord, np.nan)
    pin = np.where(assembles, crank + data.r3 * np.exp(1j * theta3), np.nan)
    bearing = np.asarray(o4 + data.r4 * np.exp(1j * theta4), dtype=np.complex128)
    psi = np.angle(pin - bearing)
    reason = np.where(~assembles, 1, np.where(lag == 0, 2, 0))
    return ImpactPosition(
        theta2=theta2, theta3=theta3, theta4_rigid=theta4_rigid, theta4=theta4,
        omega2=omega2, omega3=omega3, omega4_rigid=omega4_rigid, omega4=omega4,
        a=crank, pin=pin, bearing=bearing, o4=o4, psi=psi, exists=reason == 0,
        reason=reason, margin=np.asarray(group.margin, dtype=float) * np.ones(theta2.shape))
