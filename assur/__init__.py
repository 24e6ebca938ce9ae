"""Structural analysis and Assur-group kinematics of planar lever mechanisms.

The public API is re-exported here; :mod:`synthesis` uses nothing else.
"""

from assur.errors import AssemblyError, AssurError, AssurWarning, Issue, StructureError, TableError
from assur.tables import TableReader, atomic_write_bytes, atomic_write_text

__all__ = [
    "AssemblyError",
    "AssurError",
    "AssurWarning",
    "Issue",
    "StructureError",
    "TableError",
    "TableReader",
    "atomic_write_bytes",
    "atomic_write_text",
]

# --- structure: chains, decomposition, diagnostics, identification tables (structure owner) ---

# --- kinematics: group solvers, mechanism analysis, existence (kinematics owner) ---
