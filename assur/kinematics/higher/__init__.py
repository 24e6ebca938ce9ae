"""Kinematics of the triad (class III) and the class IV group of order 2.

``docs/higher_groups.md`` describes the method: all assembly modes at one position from the
eliminant's companion matrix (:func:`assembly_modes`), the sketched mode followed over the
crank cycle by continuation (:func:`follow_mode`), and the analogs by implicit
differentiation (:func:`analogs`).
"""

from assur.kinematics.higher.continuation import (
    HigherSolution,
    analogs,
    follow_mode,
)
from assur.kinematics.higher.coupled import ClassIVCoupled
from assur.kinematics.higher.groups import (
    ClassIVInputs,
    HigherGroup,
    Leash,
    Triad,
    TriadInputs,
)
from assur.kinematics.higher.modes import AssemblyModes, assembly_modes, select_mode

__all__ = [
    "AssemblyModes",
    "ClassIVCoupled",
    "ClassIVInputs",
    "HigherGroup",
    "HigherSolution",
    "Leash",
    "Triad",
    "TriadInputs",
    "analogs",
    "assembly_modes",
    "follow_mode",
    "select_mode",
]
