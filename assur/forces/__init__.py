"""Force analysis (kinetostatics) of a mechanism by Assur groups (``docs/forces.md``).

:func:`kinetostatics` gives the reaction in every kinematic pair and the driving torque at
every analysed position, with the power balance and the Newton–Euler residual of every link;
:func:`read_forces` reads the ``masses:``, ``loads:`` and ``gravity:`` sections of a table.
"""

from assur.forces.checks import LinkResidual
from assur.forces.groups import EQUATIONS, ForceReason
from assur.forces.kinetostatics import ForceAnalysis, Reaction, kinetostatics
from assur.forces.model import ForceData, Load, Mass, Tabulated
from assur.forces.table import read_forces

__all__ = [
    "EQUATIONS",
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
