"""Force analysis (kinetostatics) of a mechanism by Assur groups (``docs/forces.md``).

:func:`kinetostatics` gives the reaction in every kinematic pair and the driving torque at
every analysed position, with the power balance and the Newton–Euler residual of every link;
:func:`read_forces` reads the ``masses:``, ``loads:`` and ``gravity:`` sections of a table.

The group equations (:mod:`assur.forces.groups`) are given to the group-kind registry
(:mod:`assur.kinds`), which the kinematics imports; the solver itself needs the kinematics,
so it is loaded on first use.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from assur.forces.checks import LinkResidual
from assur.forces.groups import ForceReason
from assur.forces.model import ForceData, Load, Mass, Tabulated
from assur.forces.table import read_forces

if TYPE_CHECKING:  # pragma: no cover
    from assur.forces.solver import ForceAnalysis, Reaction, kinetostatics

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

_SOLVER = ("ForceAnalysis", "Reaction", "kinetostatics")


def __getattr__(name: str) -> object:
    """The solver's names, imported on first use (it depends on the kinematics)."""
    if name in _SOLVER:
        return getattr(importlib.import_module("assur.forces.solver"), name)
    raise AttributeError(f"module 'assur.forces' has no attribute {name!r}")
