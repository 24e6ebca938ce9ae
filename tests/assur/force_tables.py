"""Reading a shipped table with force sections."""

from __future__ import annotations

from pathlib import Path

import assur
from assur.forces import ForceData
from assur.kinematics.build import load_with_forces

ROOT = Path(__file__).resolve().parents[2]
TABLES = ROOT / "input_tables"


def load(name: str) -> tuple[assur.KinematicModel, ForceData]:
    """The kinematic model and the force data of ``input_tables/<name>``."""
    model, forces = load_with_forces(TABLES / name)
    assert forces is not None
    return model, forces
