"""The DGTU structure-identification table: building it and checking a filled one.

Reference data: table 1.6 of the course as transcribed in method.md §3.3
(input_tables/course_11_link_table.yaml, rows in the printed order).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from assur import analyse_structure, chain_from_dict, load_chain
from assur.errors import StructureError
from assur.structure.identification import check_identification, identification_table

ROOT = Path(__file__).resolve().parents[2]
COURSE = ROOT / "input_tables" / "course_11_link.yaml"
TABLE = ROOT / "input_tables" / "course_11_link_table.yaml"


@pytest.fixture(scope="module")
def course() -> object:
    return analyse_structure(load_chain(COURSE))


@pytest.fixture
def rows() -> list[dict]:
    return [row.to_dict() for row in load_chain(TABLE).identification]


def _row(rows: list[dict], kind: int) -> dict:
    return next(r for r in rows if r["L"] == kind)


def _found(mismatches: list) -> list[tuple]:
    return [(m.row, m.field, m.expected, m.found) for m in mismatches]


def test_the_printed_table_agrees_with_the_chain(course: object, rows: list[dict]) -> None:
    assert check_identification(course, rows) == []


def test_built_table_equals_table_1_6_in_layering_order(course: object,
                                                        rows: list[dict]) -> None:
    built = identification_table(course)
    printed = sorted(rows, key=lambda r: r["seq"])
    keys = ("L", "seq", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1", "j_plus_1")
    assert [[getattr(b, k) for k in keys] for b in built] == \
        [[p[k] for k in keys] for p in printed]
    assert [b.L for b in built] == [0, 1, 4, 3, 2, 5]


def test_the_table_alone_gives_the_course_result() -> None:
    chain = load_chain(TABLE)
    analysis = analyse_structure(chain)
    assert (analysis.n, analysis.p5, analysis.W) == (11, 16, 1)
    assert analysis.formula == "I(0,1) → II₁(2,3) → II₄(4,5) → II₃(6,7) → II₂(8,9) → II₅(10,11)"
    assert check_identification(analysis, chain.identification) == []


def test_swapped_roles_are_reported_once(course: object, rows: list[dict]) -> None:
    # L3: i must be the slotted lever 6; only i and j are swapped, the neighbour columns
    # still describe 6 as i, so they are not reported again.
    row = _row(rows, 3)
    row["i"], row["j"] = 7, 6
    index = rows.index(row)
    assert _found(check_identification(course, rows)) == [
        (index, "i", 6, 7), (index, "j", 7, 6)]


def test_swapped_roles_with_consistent_columns(course: object, rows: list[dict]) -> None:
    # L1: link 3 is hinged to the frame, so it must be j; the student wrote the whole row
    # for i = 3, j = 2 consistently (i−1 = 0, j−1 = 1, j+1 = 6).
    row = _row(rows, 1)
    row.update(i=3, j=2, i_minus_1=0, j_minus_1=1, i_plus_1=None, j_plus_1=6)
    index = rows.index(row)
    assert _found(check_identification(course, rows)) == [
        (index, "i", 2, 3), (index, "j", 3, 2)]


def test_wrong_kind_and_wrong_successor(course: object, rows: list[dict]) -> None:
    row = _row(rows, 2)
    row["L"] = 5
    row["j_plus_1"] = None
    index = rows.index(row)
    result = check_identification(course, rows)
    assert _found(result) == [(index, "L", 2, 5), (index, "j_plus_1", 10, None)]
    assert "structure_identification[2]" in result[0].text("en")
    assert "'j_plus_1': expected 10, found null" in result[1].text("en")
    assert "ожидалось 10" in result[1].text("ru")


def test_guided_link_is_not_a_successor(course: object, rows: list[dict]) -> None:
    # link 3 carries the guide of slider 4 but no hinge: j+1 of L1 must stay a dash
    row = _row(rows, 1)
    row["j_plus_1"] = 4
    result = check_identification(course, rows)
    assert _found(result) == [(rows.index(row), "j_plus_1", None, 4)]
    assert "guided by it" in result[0].text("en")


def test_missing_row(course: object, rows: list[dict]) -> None:
    rows.remove(_row(rows, 5))
    assert _found(check_identification(course, rows)) == [(None, "row", "II₅(10,11)", None)]


def test_wrong_partner_link(course: object, rows: list[dict]) -> None:
    row = _row(rows, 4)
    row["j"] = 9
    assert _found(check_identification(course, rows)) == [(rows.index(row), "j", 5, 9)]


def test_sequence_must_follow_the_layering(course: object, rows: list[dict]) -> None:
    # L2 (8,9) hangs on the kulisa 6 of L3 (seq 4): seq 3 is too early. L4 moved to 5 is
    # still after L1, which is all it needs.
    _row(rows, 2)["seq"] = 3
    _row(rows, 4)["seq"] = 5
    assert _found(check_identification(course, rows)) == [
        (rows.index(_row(rows, 2)), "seq", 5, 3)]


def test_same_level_groups_may_swap_places(course: object, rows: list[dict]) -> None:
    _row(rows, 3)["seq"] = 3
    _row(rows, 4)["seq"] = 4
    assert check_identification(course, rows) == []


def test_variant_must_suit_the_kind(course: object, rows: list[dict]) -> None:
    _row(rows, 4)["variant"] = 1
    _row(rows, 1)["variant"] = 0
    assert _found(check_identification(course, rows)) == [
        (rows.index(_row(rows, 1)), "variant", [1, -1], 0),
        (rows.index(_row(rows, 4)), "variant", None, 1)]


def test_header_counts_are_checked() -> None:
    chain = load_chain(TABLE)
    data = {"W": 2, "p5": 15, "structure_identification": [
        row.to_dict() for row in chain.identification]}
    rebuilt = chain_from_dict(data, source="claims.yaml")
    found = _found(check_identification(analyse_structure(rebuilt), rebuilt.identification))
    assert found == [(None, "p5", 16, 15), (None, "W", 1, 2)]


def _watt_i() -> object:
    pairs = [("A", 0, 1), ("B", 1, 2), ("C", 2, 3), ("D", 2, 5), ("E", 3, 4), ("F", 4, 5),
             ("G", 0, 5)]
    return analyse_structure(chain_from_dict({"mechanism": {"pairs": [
        {"id": p, "type": "R", "links": [a, b]} for p, a, b in pairs], "inputs": [1]}}))


def test_free_choice_of_roles_when_no_rule_applies() -> None:
    # Watt I: the dyad (3,4) has neither link on the frame; the course lets i be either one.
    analysis = _watt_i()
    rows = [
        {"L": 0, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None, "i_plus_1": 2},
        {"L": 1, "i_minus_1": 1, "j_minus_1": 0, "i": 2, "j": 5, "i_plus_1": 3,
         "j_plus_1": 4},
        {"L": 1, "i_minus_1": 5, "j_minus_1": 2, "i": 4, "j": 3, "i_plus_1": None,
         "j_plus_1": None}]
    assert check_identification(analysis, rows) == []


def test_table_needs_dyads_only() -> None:
    pairs = [("A", "R", 0, 1), ("B", "R", 1, 2), ("C", "R", 2, 4), ("D", "R", 3, 4),
             ("E", "R", 3, 0), ("F", "R", 4, 5), ("G", "R", 5, 0)]
    triad = analyse_structure(chain_from_dict({"mechanism": {"pairs": [
        {"id": p, "type": t, "links": [a, b]} for p, t, a, b in pairs], "inputs": [1]}}))
    with pytest.raises(StructureError, match="not dyads"):
        identification_table(triad)


def test_row_for_a_triad_is_reported() -> None:
    # the triad of tests/assur/chains/x01_triad.yaml (all R here) written as a dyad row
    pairs = [("A", 0, 1), ("B", 1, 2), ("C", 2, 4), ("D", 3, 4), ("E", 3, 0), ("F", 4, 5),
             ("G", 5, 0)]
    triad = analyse_structure(chain_from_dict({"mechanism": {"pairs": [
        {"id": p, "type": "R", "links": [a, b]} for p, a, b in pairs], "inputs": [1]}}))
    rows = [{"L": 0, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None},
            {"L": 1, "i_minus_1": 1, "j_minus_1": 4, "i": 2, "j": 3}]
    assert _found(check_identification(triad, rows)) == [(1, "L", None, 1)]


def test_no_table_when_a_link_is_in_no_group() -> None:
    # double parallelogram: the third crank 4 is placed in no group (redundant constraint)
    pairs = [("A", 0, 1), ("B", 1, 2), ("C", 2, 3), ("D", 3, 0), ("E", 2, 4), ("F", 4, 0)]
    analysis = analyse_structure(chain_from_dict({"mechanism": {"pairs": [
        {"id": p, "type": "R", "links": [a, b]} for p, a, b in pairs], "inputs": [1]}}))
    with pytest.raises(StructureError, match="links 4 are in no group"):
        identification_table(analysis)
