"""Built-in case: impact in a four-bar with a clearance in the coupler–rocker bearing.

An impulse balance at the instant the pin on the coupler strikes the bearing on the rocker,
in two models: the source's (every velocity may jump, the crank's included) and
Townsend–Mansour's (the crank speed is held by the drive). See ``docs/case_impact.md``.
"""

from __future__ import annotations

from synthesis.cases.impact.data import PAPER, TABLE_1, ImpactData
from synthesis.cases.impact.energy import EnergyBalance, energy_balance
from synthesis.cases.impact.models import ImpactResult, solve_paper, solve_townsend_mansour
from synthesis.cases.impact.position import ImpactPosition, impact_position
from synthesis.cases.impact.study import ImpactStudy, run_study

__all__ = [
    "PAPER",
    "TABLE_1",
    "EnergyBalance",
    "ImpactData",
    "ImpactPosition",
    "ImpactResult",
    "ImpactStudy",
    "energy_balance",
    "impact_position",
    "run_study",
    "solve_paper",
    "solve_townsend_mansour",
]
