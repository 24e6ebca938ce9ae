"""Checks that a small change of the code would break: each fails on a mutation that the rest
of the suite lets through (the comment of each test names the mutation it was seen to catch).

- the identification table's duplicate-row check;
- the atomic write (a failure between writing and renaming leaves the old file);
- criterion P1 where a group's violation is undefined (NaN) or infinite;
- the sign and size of the shortfall of every dyad kind, for a design just outside
  existence, against a hand computation (``docs/kinematics.md`` §5: the violation in the
  group's own terms, positive where it fails).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from assur.io.chain_table import chain_from_dict, load_chain
from assur.io.files import atomic_write_text
from assur.kinematics.build import build_model
from assur.kinematics.existence import check_existence
from assur.structure.analysis import analyse_structure
from assur.structure.identification import check_identification, identification_table
from synthesis.criteria import existence_penalty

TABLES = Path(__file__).resolve().parents[2] / "input_tables"


# ------------------------------------------------------------ identification duplicate row


def test_a_row_given_twice_is_one_mismatch_naming_the_first() -> None:
    # caught: removing the 'already described' branch (two rows, no mismatch) and keying
    # 'used' by the row instead of the group
    analysis = analyse_structure(load_chain(TABLES / "course_11_link_table.yaml"))
    rows = [row.to_dict() for row in identification_table(analysis)]
    assert check_identification(analysis, rows) == []
    twice = [*rows[:3], rows[1], *rows[3:]]
    found = check_identification(analysis, twice)
    assert [(m.row, m.field) for m in found] == [(3, "row")]
    assert "row 1" in found[0].text("en") and "строке 1" in found[0].text("ru")
    # a missing row is told apart from a repeated one
    missing = check_identification(analysis, [rows[0], *rows[2:]])
    assert [(m.row, m.field) for m in missing] == [(None, "row")]


# ------------------------------------------------------------------------- atomic write


def test_a_failed_rename_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch) -> None:
    # caught: writing straight to the path, and not removing the temporary on failure
    target = tmp_path / "result.yaml"
    target.write_text("old\n", encoding="utf-8")

    def refuse(src: Any, dst: Any) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", refuse)
    with pytest.raises(OSError):
        atomic_write_text(target, "new\n")
    assert target.read_text(encoding="utf-8") == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.yaml"]
    monkeypatch.undo()
    atomic_write_text(target, "new\n")
    assert target.read_text(encoding="utf-8") == "new\n"


def test_an_interrupted_write_leaves_the_old_file(tmp_path, monkeypatch) -> None:
    target = tmp_path / "out.txt"
    target.write_text("old", encoding="utf-8")

    def interrupt(src: Any, dst: Any) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "replace", interrupt)
    with pytest.raises(KeyboardInterrupt):
        atomic_write_text(target, "new")
    assert target.read_text(encoding="utf-8") == "old" and len(list(tmp_path.iterdir())) == 1


# ------------------------------------------------------------------------------------ P1


def test_p1_with_an_undefined_violation() -> None:
    # caught: nan=0.0 (a NaN violation would count as 'just fails'), dropping the clip at 0
    # and reading +inf as NaN; by hand with N_Q = 4: π = (4 − g) + v/(1 + v)
    first = np.array([[2, 3, 0, 2, 4]])
    violation = np.array([[np.nan, np.inf, np.nan, -5.0, 1.0]])
    by_hand = (4 - 2) + 1 / 2 + (4 - 3) + 1.0 + 0 + (4 - 2) + 0.0 + (4 - 4) + 1 / 2
    assert existence_penalty(first, violation, 4)[0] == pytest.approx(by_hand, rel=1e-12)
    assert math.isfinite(existence_penalty(first, np.full((1, 5), np.nan), 4)[0])


# ----------------------------------------------------------------- shortfall of each kind


def _shortfall(kind: int, params: dict[str, float]) -> tuple[float, str]:
    """The shortfall of a dyad hung from the frame on both sides (its geometry is the same
    at every crank angle), driven beside an idle crank.  (Links 2 and 3 of the symmetric L4
    are named in the order the analysis gives them, 3 first.)"""
    i, j = (3, 2) if kind == 4 else (2, 3)
    data = {"frame": 0, "structure_identification": [
        {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None,
         "params": {"x_O1": 0, "y_O1": 0, "l_1": 30, "phi_1_0": 0}},
        {"L": kind, "i": i, "j": j, "i_minus_1": 0, "j_minus_1": 0,
         "params": {"l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0, **params}}]}
    model = build_model(analyse_structure(chain_from_dict(data)))
    (group,) = [g for g in check_existence(model, points=12).groups if g.verdict == "fails"]
    (interval,) = group.intervals
    return interval.shortfall, interval.unit


SHORTFALLS = [
    # L1 stretched: the hinges 100 mm apart, the links reach 40 + 50 = 90 mm
    (1, {"x_Hi": 200, "y_Hi": 0, "x_Hj": 300, "y_Hj": 0, "l_i": 40, "l_j": 50},
     100 - (40 + 50), "mm"),
    # L1 folded: |200 − 50| = 150 mm cannot fit between hinges 100 mm apart
    (1, {"x_Hi": 200, "y_Hi": 0, "x_Hj": 300, "y_Hj": 0, "l_i": 200, "l_j": 50},
     (200 - 50) - 100, "mm"),
    # L2: the path of C is the x axis, H_j 80 mm above it, the rod 50 mm long
    (2, {"x_Hj": 100, "y_Hj": 80, "l_j": 50, "x_Ak": 0, "y_Ak": 0, "beta_g": 0, "e": 0},
     80 - 50, "mm"),
    # L3: the guide 50 mm from H_j, the hinges 40 mm apart
    (3, {"x_Hi": 0, "y_Hi": 0, "x_Hj": 40, "y_Hj": 0, "d": 50}, 50 - 40, "mm"),
    # L4: guides 3° apart against the margin δ = 0.1 (asin 0.1 = 5.739°)
    (4, {"x_Ak": 0, "y_Ak": 0, "beta_i": 0, "e_i": 0, "x_Bk": 100, "y_Bk": 0, "beta_j": 3,
         "e_j": 0, "delta": 0.1}, math.degrees(math.asin(0.1)) - 3, "deg"),
    # L5: the slide of link j at 3° to the guide of link i, δ = 0.1
    (5, {"x_Hj": 100, "y_Hj": 50, "gamma": 3, "x_Ak": 0, "y_Ak": 0, "beta_S": 0, "e": 0,
         "delta": 0.1}, math.degrees(math.asin(0.1)) - 3, "deg"),
]


@pytest.mark.parametrize(("kind", "params", "by_hand", "unit"), SHORTFALLS,
                         ids=["L1-stretched", "L1-folded", "L2", "L3", "L4", "L5"])
def test_the_shortfall_is_positive_and_as_computed_by_hand(kind, params, by_hand,
                                                           unit) -> None:
    # caught: the sign of any _shortfall_* turned, max → min in the RRR rule, |l_i − l_j|
    # without the abs, asin(δ) and the angle swapped
    shortfall, found_unit = _shortfall(kind, params)
    assert by_hand > 0 and found_unit == unit
    assert shortfall == pytest.approx(by_hand, rel=1e-9)
