"""Reading the design task of the tracker case from a table and command-line options.

The table (``input_tables/case_tracker.yaml``) has one mapping ``design_task:`` with the
fields of :data:`FIELDS`; options given on the command line replace the table's values.
Every problem (unknown key, wrong type, value out of range) is collected and reported at
once as a :class:`~assur.TableError` naming the file and the field.
"""

from __future__ import annotations

import math
import os
from typing import Any

from assur.io.reader import TableReader, is_number, positive
from assur.text import Message
from synthesis.cases.tracker.design import PATENT_TASK, DesignTask

__all__ = ["FIELDS", "OPTIONS", "load_task", "task_from_data"]

FIELDS: dict[str, str] = {
    "stroke_deg": "platform stroke a, degrees",
    "min_transmission_deg": "smallest allowed transmission angle b_min.ad, degrees",
    "l1_mm": "short rocker l1, mm",
    "actuator_stroke_mm": "stroke of the available actuator, mm",
    "min_clearance_mm": "least distance from the post to the extended actuator's axis, mm",
    "k2": "values of l2/l1",
    "k5": "values of l5/l1",
}
"""The fields of ``design_task:`` and what they mean."""

OPTIONS: dict[str, str] = {
    "stroke_deg": "--stroke", "min_transmission_deg": "--min-transmission", "l1_mm": "--l1",
    "actuator_stroke_mm": "--actuator-stroke", "min_clearance_mm": "--min-clearance",
    "k2": "--k2", "k5": "--k5",
}
"""The command-line option that overrides each field."""

#: The largest proportion ``l2/l1`` or ``l5/l1`` (the patent's are 1.4 to 2.2): beyond it the
#: kite or the actuator's base is a hundred times the rocker, not a tracker.
MAX_RATIO = 100.0

_RANGES: dict[str, tuple[float, float, Message]] = {
    "stroke_deg": (1.0, 360.0, Message("rule.strictly_between", {"low": 1, "high": 360})),
    "min_transmission_deg": (0.0, 90.0, Message("rule.in_range", {"range": "[0, 90)"})),
    "l1_mm": (0.0, math.inf, Message("rule.positive")),
    "actuator_stroke_mm": (0.0, math.inf, Message("rule.positive")),
    "min_clearance_mm": (0.0, math.inf, Message("rule.non_negative")),
}


def _defaults() -> dict[str, Any]:
    task = PATENT_TASK
    return {"stroke_deg": math.degrees(task.stroke),
            "min_transmission_deg": math.degrees(task.min_transmission),
            "l1_mm": task.l1, "actuator_stroke_mm": task.actuator_stroke,
            "min_clearance_mm": task.min_clearance, "k2": list(task.k2), "k5": list(task.k5)}


def _in_range(name: str) -> Any:
    low, high, rule = _RANGES[name]

    def check(value: float) -> Message | None:
        inside = low <= value < high if name in ("min_transmission_deg", "min_clearance_mm") \
            else low < value < high and (high < math.inf or positive(value) is None)
        return None if inside else rule
    return check


def _ratios(value: list[Any]) -> Message | None:
    if not value:
        return Message("rule.list_not_empty")
    if not all(is_number(v) for v in value):
        return Message("rule.list_numbers")
    outside = [f"{v:g}" for v in value if not 1.0 < v <= MAX_RATIO]
    if outside:
        return Message("rule.list_within", {"low": 1, "high": MAX_RATIO,
                                            "values": ", ".join(outside)})
    return None


def _read(reader: TableReader, overrides: dict[str, Any], *, required: bool = True) -> DesignTask:
    top = reader.root(allowed=("schema_version", "design_task"))
    top.get("schema_version", kind="int", required=False, default=1,
            check=lambda v: None if v == 1 else Message("rule.schema_version", {"version": 1}))
    body = top.child("design_task", allowed=tuple(FIELDS), required=required)
    values = _defaults()
    if body is not None:
        for name in _RANGES:
            values[name] = body.get(name, kind="number", required=False, default=values[name],
                                    check=_in_range(name))
        for name in ("k2", "k5"):
            values[name] = body.get(name, kind="list", required=False, default=values[name],
                                    check=_ratios)
    options = TableReader.from_data({OPTIONS[name]: value for name, value in overrides.items()},
                                    reader.source)
    given = options.root(name="option")
    for name in overrides:
        kind, check = ("list", _ratios) if name in ("k2", "k5") else ("number", _in_range(name))
        values[name] = given.get(OPTIONS[name], kind=kind, check=check)
    reader.issues.extend(options.issues)
    reader.raise_if_any()
    return DesignTask(stroke=math.radians(values["stroke_deg"]),
                      min_transmission=math.radians(values["min_transmission_deg"]),
                      l1=float(values["l1_mm"]),
                      actuator_stroke=float(values["actuator_stroke_mm"]),
                      min_clearance=float(values["min_clearance_mm"]),
                      k2=tuple(float(v) for v in values["k2"]),
                      k5=tuple(float(v) for v in values["k5"]))


def load_task(path: str | os.PathLike[str] | None = None,
              overrides: dict[str, Any] | None = None) -> DesignTask:
    """The design task from a table file (or the patent's example) and overrides.

    Parameters
    ----------
    path : path-like or None
        The YAML table; None starts from the patent's worked example.
    overrides : dict, optional
        Field → value (the fields of :data:`FIELDS`), e.g. from command-line options.

    Returns
    -------
    DesignTask

    Raises
    ------
    TableError
        Listing every problem of the table and of the overrides.
    """
    if path is None:
        return _read(TableReader.from_data({}, source="command line"), dict(overrides or {}),
                     required=False)
    return _read(TableReader.from_path(path, kind="tracker"), dict(overrides or {}))


def task_from_data(data: Any, source: str = "<data>",
                   overrides: dict[str, Any] | None = None) -> DesignTask:
    """Like :func:`load_task` for data already parsed (a dict)."""
    return _read(TableReader.from_data(data, source), dict(overrides or {}))
