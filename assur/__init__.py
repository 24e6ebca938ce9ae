"""Structural analysis and Assur-group kinematics of planar lever mechanisms.

The names below are what a user calls: read a table, analyse its structure, check a
student's identification table, build the kinematic model, analyse it over the cycle, judge
existence and transmission, solve a group directly, draw. Everything else lives in the
submodules (`assur.io`, `assur.structure`, `assur.kinematics`, `assur.forces`, `assur.plot`,
`assur.text`), which :mod:`synthesis` imports directly. ``import assur`` stays quick because
the modules import the heavy libraries (matplotlib, networkx, scipy) and the higher groups
only inside the functions that need them.

Examples
--------
>>> from pathlib import Path
>>> import assur
>>> table = Path(assur.__file__).parent.parent / "input_tables" / "four_bar.yaml"
>>> result = assur.analyse_structure(assur.load_chain(table))
>>> result.W
1
"""

from __future__ import annotations

from assur.api import Analysis, analyse, check, load
from assur.assessment import Assessment
from assur.errors import AssemblyError, AssurError, StructureError, TableError
from assur.io.chain_table import chain_from_dict, load_chain
from assur.kinds import KINDS, GroupKind, kind_of
from assur.kinematics.analysis import Motion, cycle_model, input_grid
from assur.kinematics.build import build_model, load_model
from assur.kinematics.dyads import (
    solve_input,
    solve_prp,
    solve_rpp,
    solve_rpr,
    solve_rrp,
    solve_rrr,
)
from assur.kinematics.existence import ExistenceReport, check_existence
from assur.kinematics.jets import Jet
from assur.kinematics.model import KinematicModel
from assur.kinematics.transmission import joint_rotations, pressure_angles
from assur.model import Chain, Sketch
from assur.plot.mechanism import draw_mechanism
from assur.plot.schemes import draw_structural_scheme, save_schemes
from assur.structure.analysis import StructuralAnalysis, analyse_structure
from assur.structure.classification import AssurGroup
from assur.structure.diagnostics import Diagnostic
from assur.structure.identification import check_identification, identification_table
from assur.structure.report import structure_report

__all__ = [  # noqa: RUF022 - grouped by topic, as the comments say
    # the verbs of the four tasks and their results (docs/api.md)
    "Analysis",
    "Assessment",
    "analyse",
    "check",
    "load",
    # errors
    "AssemblyError",
    "AssurError",
    "StructureError",
    "TableError",
    # tables and the chain
    "Chain",
    "Sketch",
    "chain_from_dict",
    "load_chain",
    # group kinds
    "KINDS",
    "GroupKind",
    "kind_of",
    # structure
    "AssurGroup",
    "Diagnostic",
    "StructuralAnalysis",
    "analyse_structure",
    "check_identification",
    "identification_table",
    "structure_report",
    # kinematics
    "ExistenceReport",
    "Jet",
    "KinematicModel",
    "Motion",
    "build_model",
    "check_existence",
    "cycle_model",
    "input_grid",
    "joint_rotations",
    "load_model",
    "pressure_angles",
    "solve_input",
    "solve_prp",
    "solve_rpp",
    "solve_rpr",
    "solve_rrp",
    "solve_rrr",
    # pictures
    "draw_mechanism",
    "draw_structural_scheme",
    "save_schemes",
]
