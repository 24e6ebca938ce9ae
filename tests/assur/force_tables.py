"""Reading a shipped table with force sections, until the chain reader reads them itself.

The chain reader does not know the ``masses:``, ``loads:`` and ``gravity:`` sections yet: the
mechanism is built from the rest of the table, and the sections are read with
:func:`assur.forces.read_forces` from the whole parsed table.
"""

from __future__ import annotations

from pathlib import Path

import yaml

import assur
from assur.forces import ForceData, read_forces
from assur.forces.table import SECTIONS

ROOT = Path(__file__).resolve().parents[2]
TABLES = ROOT / "input_tables"


def load(name: str) -> tuple[assur.KinematicModel, ForceData]:
    """The kinematic model and the force data of ``input_tables/<name>``."""
    path = TABLES / name
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    chain = assur.chain_from_dict({k: v for k, v in data.items() if k not in SECTIONS},
                                  str(path))
    reader = assur.TableReader.from_data(data, str(path))
    forces = read_forces(reader.root(), chain)
    reader.raise_if_any()
    assert forces is not None
    return assur.build_model(assur.analyse_structure(chain)), forces
