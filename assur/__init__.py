"""Structural analysis and Assur-group kinematics of planar lever mechanisms.

The public API is re-exported here; :mod:`synthesis` uses nothing else.
"""

from assur.errors import AssemblyError, AssurError, AssurWarning, Issue, StructureError, TableError
from assur.io.files import atomic_write_bytes, atomic_write_text
from assur.io.reader import (
    MISSING,
    Node,
    TableReader,
    describe,
    normalise_id,
)
from assur.text import Message

__all__ = [
    "AssemblyError",
    "AssurError",
    "AssurWarning",
    "Issue",
    "MISSING",
    "Message",
    "Node",
    "StructureError",
    "TableError",
    "TableReader",
    "atomic_write_bytes",
    "atomic_write_text",
    "describe",
    "normalise_id",
]

# --- structure: chains, decomposition, diagnostics, identification tables (structure owner) ---
from assur.io.chain_table import chain_from_dict, load_chain  # noqa: E402
from assur.io.sketch import with_sketch  # noqa: E402
from assur.kinds import KINDS, GroupKind, kind_of  # noqa: E402
from assur.model import GroupParams, Sketch  # noqa: E402
from assur.structure.classification import AssurGroup  # noqa: E402
from assur.structure.diagnostics import Diagnostic  # noqa: E402
from assur.structure.identification import (  # noqa: E402
    IdentificationRow,
    Mismatch,
    check_identification,
    identification_table,
)
from assur.model import Chain, Drive, Input, Link, LinkId, Pair, PairId, PairType  # noqa: E402
from assur.structure.analysis import StructuralAnalysis, analyse_structure  # noqa: E402
from assur.structure.identification import COLUMNS as IDENTIFICATION_COLUMNS  # noqa: E402
from assur.structure.report import group_description, structure_report  # noqa: E402

__all__ += [
    "AssurGroup",
    "Chain",
    "Diagnostic",
    "Drive",
    "IdentificationRow",
    "Input",
    "Link",
    "LinkId",
    "Mismatch",
    "Pair",
    "PairId",
    "PairType",
    "StructuralAnalysis",
    "analyse_structure",
    "chain_from_dict",
    "with_sketch",
    "Sketch",
    "GroupParams",
    "GroupKind",
    "KINDS",
    "kind_of",
    "check_identification",
    "identification_table",
    "load_chain",
    "structure_report",
    "group_description",
    "IDENTIFICATION_COLUMNS",
]

# --- kinematics: group solvers, mechanism analysis, existence (kinematics owner) ---
from assur.kinematics import jets  # noqa: E402
from assur.kinematics.dyads import (  # noqa: E402
    REASONS,
    DyadSolution,
    Reason,
    reason_text,
    solve_input,
    solve_prp,
    solve_rpp,
    solve_rpr,
    solve_rrp,
    solve_rrr,
)
from assur.kinematics.jets import Jet  # noqa: E402

__all__ += [
    "REASONS",
    "DyadSolution",
    "Jet",
    "Reason",
    "jets",
    "reason_text",
    "solve_input",
    "solve_prp",
    "solve_rpp",
    "solve_rpr",
    "solve_rrp",
    "solve_rrr",
]
from assur.kinematics.existence import (  # noqa: E402
    CONDITIONS,
    ExistenceReport,
    FailureInterval,
    GroupExistence,
    check_existence,
    first_failure,
)
from assur.kinematics.build import (  # noqa: E402
    build_model,
    load_model,
    model_from_params,
    model_from_sketch,
)
from assur.kinematics.model import KIND_COLUMNS, GroupModel, KinematicModel  # noqa: E402
from assur.kinematics.analysis import (  # noqa: E402
    Motion,
    SliderState,
    acceleration,
    analyse,
    input_grid,
    unwrap,
    values,
    velocity,
)
from assur.kinematics.transmission import (  # noqa: E402
    JointRotation,
    PressureAngle,
    binary_links,
    joint_rotations,
    pressure_angles,
)

__all__ += [
    "CONDITIONS",
    "ExistenceReport",
    "FailureInterval",
    "GroupExistence",
    "GroupModel",
    "JointRotation",
    "KIND_COLUMNS",
    "KinematicModel",
    "Motion",
    "PressureAngle",
    "SliderState",
    "acceleration",
    "analyse",
    "binary_links",
    "build_model",
    "check_existence",
    "first_failure",
    "input_grid",
    "joint_rotations",
    "load_model",
    "model_from_params",
    "model_from_sketch",
    "pressure_angles",
    "unwrap",
    "values",
    "velocity",
]
from assur.plot.mechanism import (  # noqa: E402
    draw_mechanism,
    figure_for,
    save_animation_gif,
    save_mechanism_png,
)

__all__ += ["draw_mechanism", "figure_for", "save_animation_gif", "save_mechanism_png"]

# --- schemes: structural scheme pictures (coursework owner) ---
from assur.plot.schemes import (  # noqa: E402
    PictureFormatError,
    SchemeLayout,
    draw_formalised_scheme,
    draw_structural_scheme,
    group_graph,
    roman,
    save_schemes,
    scheme_bytes,
    scheme_figure,
    scheme_layout,
)

__all__ += [
    "PictureFormatError",
    "SchemeLayout",
    "draw_formalised_scheme",
    "draw_structural_scheme",
    "group_graph",
    "roman",
    "save_schemes",
    "scheme_bytes",
    "scheme_figure",
    "scheme_layout",
]
