"""Kinetic energy before and after impact, what is lost, and the size of the α-sign slip.

In the source's model the drive does no work during the impact (its torque is finite); in
Townsend–Mansour's the drive holds the crank speed with an angular impulse M and so does the
work θ2'·M. The energy lost is ``before + drive_work − after``; with k = 1 and μ = 0 it is zero
for the exact restitution lever and not quite zero for the lever printed in (7)–(8), whose α
has the wrong sign.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from assur.typing import FloatArray
from synthesis.cases.impact.data import ImpactData
from synthesis.cases.impact.models import (
    ImpactResult,
    pin_offset,
    restitution_lever,
    solve_paper,
    solve_townsend_mansour,
)
from synthesis.cases.impact.position import ImpactPosition

__all__ = ["AlphaSlip", "EnergyBalance", "alpha_slip", "energy_balance", "kinetic_energy"]


def kinetic_energy(data: ImpactData, position: ImpactPosition, omega2: FloatArray,
                   omega3: FloatArray,
                   omega4: FloatArray) -> FloatArray:
    """Kinetic energy of crank, coupler and rocker, J.

    The crank turns about O2 (inertia I_O2), the rocker about O4 (I_O4 by parallel axes);
    the coupler's centre of mass moves with A plus the rotation about A.
    """
    v3 = (1j * data.r2 * omega2 * np.exp(1j * position.theta2)
          + 1j * (data.r3 / 2.0) * omega3 * np.exp(1j * position.theta3))
    energy: FloatArray = 0.5 * (data.inertia_o2 * omega2 ** 2 + data.m3 * np.abs(v3) ** 2
                                         + data.inertia3 * omega3 ** 2
                                         + data.inertia_o4 * omega4 ** 2)
    return energy


@dataclass(frozen=True, slots=True)
class EnergyBalance:
    """Kinetic energy through the impact, J (arrays of the positions' shape).

    Attributes
    ----------
    before, after : ndarray
        Kinetic energy of the mechanism before and after impact.
    drive_work : ndarray
        Work of the drive's angular impulse (Townsend–Mansour's model only; zero otherwise).
    loss : ndarray
        ``before + drive_work − after``: energy dissipated by the impact (≥ 0 physically).
    """

    before: FloatArray
    after: FloatArray
    drive_work: FloatArray
    loss: FloatArray

    @property
    def relative_loss(self) -> FloatArray:
        """The loss as a fraction of the energy supplied (before + drive work)."""
        return self.loss / (self.before + self.drive_work)


def energy_balance(data: ImpactData, position: ImpactPosition,
                   result: ImpactResult) -> EnergyBalance:
    """The energy balance of one solved impact."""
    before = kinetic_energy(data, position, position.omega2, position.omega3, position.omega4)
    after = kinetic_energy(data, position, result.omega2, result.omega3, result.omega4)
    drive_work = position.omega2 * result.drive
    return EnergyBalance(before=before, after=after, drive_work=drive_work,
                         loss=before + drive_work - after)


@dataclass(frozen=True, slots=True)
class AlphaSlip:
    """How much the sign of α in (7)–(8) matters, for an elastic frictionless impact.

    Attributes
    ----------
    alpha : ndarray
        The angle α of (8), rad.
    lever_error : ndarray
        Relative error of the printed rocker lever ρ·sin(ψ − θ4 + α) against the exact
        r4·sin(ψ − θ4).
    energy_error : dict of str to ndarray
        Per model, the relative energy gain (−relative loss) with k = 1, μ = 0 and the
        printed lever.
    exact_energy_error : dict of str to ndarray
        The same with the exact lever (zero up to rounding).
    restitution : dict of str to ndarray
        Per model, the effective coefficient of restitution (exact normal velocities after
        over before) that the printed lever gives for k = 1.
    """

    alpha: FloatArray
    lever_error: FloatArray
    energy_error: dict[str, FloatArray]
    exact_energy_error: dict[str, FloatArray]
    restitution: dict[str, FloatArray]


def alpha_slip(data: ImpactData, position: ImpactPosition) -> AlphaSlip:
    """Quantify the α-sign slip of the source's restitution law at the given positions."""
    _, alpha = pin_offset(data, position)
    energy: dict[str, FloatArray] = {}
    exact: dict[str, FloatArray] = {}
    restitution: dict[str, FloatArray] = {}
    for solve in (solve_townsend_mansour, solve_paper):
        printed = solve(data, position, k=1.0, mu=0.0, lever="paper")
        right = solve(data, position, k=1.0, mu=0.0, lever="exact")
        energy[printed.model] = -energy_balance(data, position, printed).relative_loss
        exact[right.model] = -energy_balance(data, position, right).relative_loss
        restitution[printed.model] = -printed.approach_after / printed.approach_before
    lever_error = (restitution_lever(data, position, "paper")
                   / restitution_lever(data, position, "exact") - 1.0)
    return AlphaSlip(alpha=alpha, lever_error=lever_error,
                     energy_error=energy, exact_energy_error=exact, restitution=restitution)
