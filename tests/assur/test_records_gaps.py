"""A position where a group does not assemble is written to JSON as a missing point: both
coordinates null, for the joints, link origins, slider points and their analogs, whatever
the kind of the group (a dyad's gap and a triad's gap alike).

The expectation is the group's own existence mask in the motion, not a stored output: every
point of the group's joints is null in x and in y exactly where the group does not assemble.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

import assur
from assur.records import analysis_record

TABLES = Path(assur.__file__).parents[1] / "input_tables"


def point_records(record: Any, path: str = "") -> list[tuple[str, dict[str, Any]]]:
    """Every ``{"x": [...], "y": [...]}`` entry of a record, with where it is."""
    found = []
    if isinstance(record, dict):
        if isinstance(record.get("x"), list) and isinstance(record.get("y"), list):
            found.append((path, record))
        for key, value in record.items():
            found += point_records(value, f"{path}/{key}")
    elif isinstance(record, list):
        for k, value in enumerate(record):
            found += point_records(value, f"{path}/{k}")
    return found


@pytest.mark.parametrize(("table", "label", "roles"), [
    ("six_bar_triad_fails.yaml", "III(2,3,4,5)", ("C1", "C2", "C3")),  # a triad's gap
    ("course_11_link_fails.yaml", "L2(9,8)", ("C",)),  # a dyad not reached (L3 breaks)
])
def test_a_gap_writes_both_coordinates_null(table: str, label: str,
                                            roles: tuple[str, ...]) -> None:
    result = assur.analyse(TABLES / table, points=72, omega=10.0)
    record = analysis_record(result)
    gap = ~np.asarray(result.motion.solutions[label].exists)
    assert gap.any() and not gap.all()  # the table has a gap and assembles elsewhere
    points = point_records(record)
    assert points
    for path, point in points:
        x_null = np.array([v is None for v in point["x"]])
        y_null = np.array([v is None for v in point["y"]])
        np.testing.assert_array_equal(x_null, y_null, err_msg=path)
    group = result.model.group(label)
    for role in roles:
        joint = record["joints"][group.pairs[role]]
        for entry in (joint, joint["d1"], joint["d2"], joint["velocity"]):
            np.testing.assert_array_equal([v is None for v in entry["x"]], gap)
            np.testing.assert_array_equal([v is None for v in entry["y"]], gap)
