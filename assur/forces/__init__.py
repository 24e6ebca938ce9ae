"""Force analysis (kinetostatics) of a mechanism by Assur groups (``docs/forces.md``).

:func:`kinetostatics` gives the reaction in every kinematic pair and the driving torque at
every analysed position, with the power balance and the Newton–Euler residual of every link;
:func:`read_forces` reads the ``masses:``, ``loads:`` and ``gravity:`` sections of a table
into the chain's :class:`ForceData` (:mod:`assur.model`).
"""

from __future__ import annotations

from assur.forces.checks import LinkResidual
from assur.forces.groups import ForceReason
from assur.forces.solver import ForceAnalysis, Reaction, kinetostatics
from assur.forces.table import read_forces
from assur.model import ForceData, Load, Mass, Tabulated

__all__ = [
    "ForceAnalysis",
    "ForceData",
    "ForceReason",
    "LinkResidual",
    "Load",
    "Mass",
    "Reaction",
    "Tabulated",
    "kinetostatics",
    "read_forces",
]
