"""Reading the input table of the impact case (``input_tables/case_impact.yaml``).

Every problem of the file (and of the command-line overrides, which go through the same
checks) is collected and reported at once, naming the table and field.
"""

from __future__ import annotations

import math
import os
from typing import Any

from assur.io.reader import TableReader, describe, positive
from assur.text import Message
from synthesis.cases.impact.data import ImpactData

__all__ = ["impact_data_from_dict", "impact_table_dict", "read_impact_table"]

_TOP = ("schema_version", "lengths_mm", "masses_kg", "inertias_kg_mm2", "clearance_mm", "crank",
        "omega4_rad_s", "k", "mu", "sigma")


def _non_negative(value: float) -> Message | None:
    return None if value >= 0 else Message("rule.non_negative")


def _unit_interval(value: float) -> Message | None:
    return None if 0 <= value <= 1 else Message("rule.restitution")


def read_impact_table(path: str | os.PathLike[str]) -> ImpactData:
    """Read the case's YAML table; raises :class:`assur.TableError` listing every problem."""
    reader = TableReader.from_path(path, kind="impact")
    return _read(reader)


def impact_data_from_dict(data: dict[str, Any], source: str = "<data>") -> ImpactData:
    """The same checks on a table that is already parsed (e.g. with command-line overrides)."""
    return _read(TableReader.from_data(data, source))


def _read(reader: TableReader) -> ImpactData:
    top = reader.root(allowed=_TOP)
    top.get("schema_version", kind="int", required=False, default=1,
            check=lambda v: None if v == 1 else Message("rule.schema_version", {"version": 1}))
    values: dict[str, Any] = {}
    lengths = top.child("lengths_mm", allowed=("r1", "r2", "r3", "r4"))
    if lengths is not None:
        for key in ("r1", "r2", "r3", "r4"):
            values[key] = lengths.get(key, kind="number", check=positive)
    masses = top.child("masses_kg", allowed=("m2", "m3", "m4"))
    if masses is not None:
        for key in ("m2", "m3", "m4"):
            values[key] = masses.get(key, kind="number", check=positive)
    inertias = top.child("inertias_kg_mm2", allowed=("I_O2", "I3", "I4"))
    if inertias is not None:
        for key, name in (("I_O2", "inertia_o2"), ("I3", "inertia3"), ("I4", "inertia4")):
            values[name] = inertias.get(key, kind="number", check=positive)
    values["clearance"] = top.get("clearance_mm", kind="number", check=positive)
    crank = top.child("crank", allowed=("theta2_deg", "omega2_rad_s"))
    if crank is not None:
        values["theta2"] = crank.get("theta2_deg", kind="number")
        values["omega2"] = crank.get("omega2_rad_s", kind="number")
    omega4 = top.get("omega4_rad_s", kind="list",
                     check=lambda v: None if v else Message("rule.rocker_speeds"))
    values["k"] = top.get("k", kind="number", check=_unit_interval)
    values["mu"] = top.get("mu", kind="number", check=_non_negative)
    values["sigma"] = top.choice("sigma", (1, -1))
    if isinstance(omega4, list):
        for index, item in enumerate(omega4):
            if isinstance(item, bool) or not isinstance(item, (int, float)) \
                    or not math.isfinite(item):
                reader.problem(f"'omega4_rad_s'[{index}]", "table.wrong_kind",
                               expected=Message("value.kind.number"), found=describe(item))
    r4, clearance = values.get("r4"), values["clearance"]
    if r4 and clearance and clearance >= 2 * r4:
        reader.problem("'clearance_mm'", "case.impact.table.clearance", limit=2 * r4,
                       found=clearance)
    reader.raise_if_any()
    return ImpactData(
        r1=values["r1"] / 1e3, r2=values["r2"] / 1e3, r3=values["r3"] / 1e3,
        r4=values["r4"] / 1e3, m2=float(values["m2"]), m3=float(values["m3"]),
        m4=float(values["m4"]), inertia_o2=values["inertia_o2"] / 1e6,
        inertia3=values["inertia3"] / 1e6, inertia4=values["inertia4"] / 1e6,
        clearance=values["clearance"] / 1e3, omega2=float(values["omega2"]),
        theta2=math.radians(values["theta2"]), omega4=tuple(float(w) for w in omega4),
        k=float(values["k"]), mu=float(values["mu"]), sigma=int(values["sigma"]))


def impact_table_dict(data: ImpactData) -> dict[str, Any]:
    """The table form of the data (the inverse of :func:`impact_data_from_dict`)."""
    return {
        "schema_version": 1,
        "lengths_mm": {"r1": data.r1 * 1e3, "r2": data.r2 * 1e3, "r3": data.r3 * 1e3,
                       "r4": data.r4 * 1e3},
        "masses_kg": {"m2": data.m2, "m3": data.m3, "m4": data.m4},
        "inertias_kg_mm2": {"I_O2": data.inertia_o2 * 1e6, "I3": data.inertia3 * 1e6,
                            "I4": data.inertia4 * 1e6},
        "clearance_mm": data.clearance * 1e3,
        "crank": {"theta2_deg": math.degrees(data.theta2), "omega2_rad_s": data.omega2},
        "omega4_rad_s": list(data.omega4),
        "k": data.k, "mu": data.mu, "sigma": data.sigma,
    }
