"""The source's data and its Table 1, typed from the paper.

All quantities are held in SI units (m, kg, kg·m², rad, rad/s, N·s); the paper prints lengths
in mm, inertias in kg·mm² and the impulses of Table 1 in units of 10⁻⁴ N·s (its column heads
say "Ns": a unit slip, see the report).
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass, replace
from typing import Any

__all__ = [
    "PAPER",
    "PAPER_IMPULSE_UNIT",
    "TABLE_1",
    "TABLE_1_COLUMNS",
    "TABLE_1_OMEGA4",
    "ImpactData",
]

#: The unit in which Table 1 prints the impulses F, r_A and r_O2, in N·s.
PAPER_IMPULSE_UNIT = 1.0e-4


@dataclass(frozen=True, slots=True)
class ImpactData:
    """Dimensions, masses and the state before impact of the four-bar with a clearance.

    Parameters
    ----------
    r1, r2, r3, r4 : float
        Frame O2O4, crank O2A, coupler AB and rocker O4B lengths, m.
    m2, m3, m4 : float
        Masses of crank, coupler and rocker, kg. The crank's centre of mass is at r2/2, the
        coupler's and rocker's at their middles.
    inertia_o2 : float
        Moment of inertia of the crank about its pivot O2, kg·m².
    inertia3, inertia4 : float
        Moments of inertia of coupler and rocker about their centres of mass, kg·m².
    clearance : float
        Radial clearance ξ of the bearing B (bearing radius minus pin radius), m.
    omega2 : float
        Crank angular velocity before impact, rad/s.
    theta2 : float
        Crank angle at the instant of impact, rad.
    omega4 : tuple of float
        Rocker angular velocities before impact, rad/s (one impact per value).
    k : float
        Coefficient of restitution of the normal impulse, 0 ≤ k ≤ 1.
    mu : float
        Coefficient of friction (full slip, f = μF), μ ≥ 0.
    sigma : int
        Assembly of the rigid closure: +1 puts B to the left of the line A→O4 (the source's
        assembly, B above the frame), −1 to the right.
    """

    r1: float
    r2: float
    r3: float
    r4: float
    m2: float
    m3: float
    m4: float
    inertia_o2: float
    inertia3: float
    inertia4: float
    clearance: float
    omega2: float
    theta2: float
    omega4: tuple[float, ...]
    k: float = 1.0
    mu: float = 0.0
    sigma: int = 1

    @property
    def inertia_o4(self) -> float:
        """Moment of inertia of the rocker about its pivot O4 (parallel axes), kg·m²."""
        return self.inertia4 + self.m4 * (self.r4 / 2.0) ** 2

    @property
    def inertia_a3(self) -> float:
        """Moment of inertia of the coupler about the joint A (parallel axes), kg·m²."""
        return self.inertia3 + self.m3 * (self.r3 / 2.0) ** 2

    def same_as(self, other: ImpactData, rel: float = 1e-12) -> bool:
        """Whether every field equals the other's up to a relative tolerance."""
        if len(self.omega4) != len(other.omega4):
            return False
        mine, theirs = (_flatten(astuple(data)) for data in (self, other))
        return all(math.isclose(x, y, rel_tol=rel) for x, y in zip(mine, theirs))

    def with_changes(self, **changes: Any) -> ImpactData:
        """A copy with some fields replaced (the command line's overrides)."""
        return replace(self, **changes)


def _flatten(values: tuple[object, ...]) -> list[float]:
    return [float(x) for v in values for x in (v if isinstance(v, tuple) else (v,))]


#: The source's example (section 3 and Table 1), after Townsend and Mansour.
PAPER = ImpactData(
    r1=0.100, r2=0.050, r3=0.080, r4=0.080,
    m2=0.012, m3=0.018, m4=0.018,
    inertia_o2=10.0e-6, inertia3=10.0e-6, inertia4=10.0e-6,
    clearance=0.5e-3, omega2=188.5, theta2=math.radians(150.0),
    omega4=(0.0, -30.0, -60.0), k=1.0, mu=0.0, sigma=1,
)

#: The rocker velocities before impact of the three rows of Table 1, rad/s.
TABLE_1_OMEGA4 = (0.0, -30.0, -60.0)

#: Column keys of Table 1 and their printed units.
TABLE_1_COLUMNS = {
    "omega2": "rad/s",
    "omega3": "rad/s",
    "F": "1e-4 N·s",
    "r_A": "1e-4 N·s",
    "r_O2": "1e-4 N·s",
}

#: Table 1 of the source as printed: column → model → the three rows (θ4' = 0, −30, −60).
#: Model "TM" is Townsend–Mansour's [2], "P" the source's own. Velocities after impact in
#: rad/s, impulses in units of 1e-4 N·s (:data:`PAPER_IMPULSE_UNIT`).
TABLE_1: dict[str, dict[str, tuple[float, float, float]]] = {
    "omega2": {"TM": (188.5, 188.5, 188.5), "P": (159.0, 150.9, 142.8)},
    "omega3": {"TM": (112.3, 139.7, 167.2), "P": (90.2, 111.6, 133.0)},
    "F": {"TM": (745.8, 950.3, 1154.7), "P": (726.4, 925.4, 1125.0)},
    "r_A": {"TM": (613.2, 781.3, 949.3), "P": (458.2, 583.8, 709.4)},
    "r_O2": {"TM": (613.2, 781.3, 949.3), "P": (455.4, 580.2, 705.0)},
}
