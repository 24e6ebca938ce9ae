"""Messages of the structural analysis point at the row and the link a student must fix.

The identification table of the course's example (table 1.6) is given alone, so the kind
of each row decides the type of its group's pairs. A wrong kind in one row changes the
pairs that a neighbouring row's successor column counts; the message on that column must
name the row whose kind decided, and say the same in Russian.
"""

from __future__ import annotations

from pathlib import Path

import yaml  # type: ignore[import-untyped]

from assur.io.chain_table import chain_from_dict
from assur.structure.analysis import analyse_structure
from assur.structure.identification import Mismatch, check_identification
from assur.structure.report import structure_report

ROOT = Path(__file__).resolve().parents[2]
TABLE = ROOT / "input_tables" / "course_11_link_table.yaml"


def _check_with_kind(links: tuple[int, int], kind: int) -> tuple[list[Mismatch], int]:
    """Mismatches of the table with the row of the dyad ``links`` given ``kind``, and the
    index of that row."""
    data = yaml.safe_load(TABLE.read_text(encoding="utf-8"))
    rows = data["structure_identification"]
    index = next(k for k, row in enumerate(rows) if {row["i"], row["j"]} == set(links))
    rows[index]["L"] = kind
    chain = chain_from_dict(data, source="table.yaml")
    assert chain.identification is not None
    return check_identification(analyse_structure(chain), chain.identification), index


def test_a_wrong_kind_that_makes_a_pair_prismatic_names_its_row() -> None:
    # the RPR dyad (6, 7) hangs on link 2 by a hinge; written as kind 2 (RRP) its link 6
    # slides on link 2, so link 2 has no hinged successor and row 1's i+1 = 6 is wrong
    found, index = _check_with_kind((6, 7), 2)
    blamed = [m for m in found if m.field == "i_plus_1"]
    assert [(m.label.split(" ")[0], m.expected, m.found) for m in blamed] == [
        ("structure_identification[1]", None, 6)]
    row = f"structure_identification[{index}] (L2)"
    assert f"link 6 of row {row} is guided by link 2" in blamed[0].text("en")
    assert f"звено 6 из строки {row} скользит по звену 2" in blamed[0].text("ru")


def test_a_wrong_kind_that_makes_a_pair_a_hinge_names_its_row() -> None:
    # the PRP dyad (4, 5) slides on link 3; written as kind 1 (RRR) link 4 is hinged to 3
    found, index = _check_with_kind((4, 5), 1)
    blamed = [m for m in found if m.field == "j_plus_1"]
    assert [(m.expected, m.found) for m in blamed] == [(4, None)]
    row = f"structure_identification[{index}] (L1)"
    assert f"link 4 of row {row} is hinged to link 3" in blamed[0].text("en")
    assert f"звено 4 из строки {row} шарнирно присоединено к звену 3" in blamed[0].text("ru")


def test_a_single_allowed_variant_is_named_plainly() -> None:
    found, _ = _check_with_kind((4, 5), 4)
    assert found == []
    found, index = _check_with_kind((10, 11), 2)   # RPP written as RRP: a variant is due
    variant = [m for m in found if m.field == "variant"]
    assert [(m.row, m.expected, m.found) for m in variant] == [(index, [1, -1], None)]
    found, index = _check_with_kind((2, 3), 4)     # RRR written as PRP: no variant allowed
    variant = next(m for m in found if m.field == "variant")
    assert "expected null (–), found 1" in variant.text("en")
    assert "one of" not in variant.text("en")


def test_the_report_has_no_english_in_russian() -> None:
    found, _ = _check_with_kind((6, 7), 2)
    data = yaml.safe_load(TABLE.read_text(encoding="utf-8"))
    analysis = analyse_structure(chain_from_dict(data, source="table.yaml"))
    russian = structure_report(analysis, lang="ru", mismatches=found, checked_rows=6)
    english = structure_report(analysis, lang="en", mismatches=found, checked_rows=6)
    for word in ("expected", "found", "link", "group", "pair", "level", "input"):
        assert word not in russian.lower(), word
        assert word in english.lower(), word


def test_successor_columns_swapped_in_a_row_are_one_finding() -> None:
    # row 1 (dyad 2, 3): link 6 hangs on link 2, so i_plus_1 = 6 and j_plus_1 = null; the
    # two values written the other way round are one slip
    data = yaml.safe_load(TABLE.read_text(encoding="utf-8"))
    row = data["structure_identification"][1]
    assert (row["i_plus_1"], row["j_plus_1"]) == (6, None)
    row["i_plus_1"], row["j_plus_1"] = None, 6
    chain = chain_from_dict(data, source="table.yaml")
    assert chain.identification is not None
    found = check_identification(analyse_structure(chain), chain.identification)
    assert [(m.row, m.field, m.message.code) for m in found] == [(1, "i_plus_1", "ident.swapped")]
    assert "'i_plus_1' and 'j_plus_1' look swapped" in found[0].text("en")
    assert "'i_plus_1' и 'j_plus_1', похоже, перепутаны местами" in found[0].text("ru")
