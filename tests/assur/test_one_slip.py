"""One slip, one message: a shipped table with one typical mistake gets exactly one finding,
at the place of the mistake, naming it; the findings that would only follow from it (a
misspelt key also "missing", the rows that use a value that failed to read) are not reported.

Each case changes one place of a shipped table; the expected place and kind of the finding
are those of the change (``benchmarks/one_slip.py`` runs every such mistake on every table).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import yaml

from assur.errors import Issue, TableError
from assur.io.chain_table import chain_from_dict
from assur.kinematics.build import load_model
from assur.structure.analysis import analyse_structure

TABLES = Path(__file__).resolve().parents[2] / "input_tables"


def _table(name: str) -> dict[str, Any]:
    return yaml.safe_load((TABLES / name).read_text(encoding="utf-8"))


def _rename(mapping: dict[str, Any], old: str, new: str) -> None:
    items = list(mapping.items())
    mapping.clear()
    mapping.update({(new if key == old else key): value for key, value in items})


def _swap(row: dict[str, Any], a: str, b: str) -> None:
    row[a], row[b] = row[b], row[a]


def _only_issue(data: dict[str, Any], source: str) -> Issue:
    with pytest.raises(TableError) as caught:
        chain_from_dict(data, source)
    issues = caught.value.issues
    assert len(issues) == 1, "\n".join(issue.text("en") for issue in issues)
    assert caught.value.source == source
    return issues[0]


#: (table, the change, the place of the finding, its code, data it must hold)
Slip = tuple[str, Callable[[dict[str, Any]], None], str, str, dict[str, Any]]

SLIPS: dict[str, Slip] = {
    "look-alike letter in a section key": (
        "four_bar.yaml", lambda t: _rename(t["mechanism"], "pairs", "pаirs"),
        "mechanism", "table.unknown_key_lookalike", {"key": "pаirs", "hint": "pairs"}),
    "misspelt section key": (
        "four_bar.yaml", lambda t: _rename(t["mechanism"], "pairs", "piars"),
        "mechanism", "table.unknown_key_hint", {"key": "piars", "hint": "pairs"}),
    "look-alike letter in a column of a pair": (
        "four_bar.yaml", lambda t: _rename(t["mechanism"]["pairs"][1], "type", "tуpe"),
        "mechanism.pairs[1] (id 'B')", "table.unknown_key_lookalike", {"hint": "type"}),
    "misspelt key of a sketch point": (
        "four_bar.yaml", lambda t: _rename(t["geometry"]["B"], "point", "pont"),
        "geometry 'B'", "table.unknown_key_hint", {"key": "pont", "hint": "point"}),
    "look-alike letter in a pair id, not in the sketch": (
        "four_bar.yaml", lambda t: t["mechanism"]["pairs"][0].update(id="А"),
        "geometry 'A'", "sketch.unknown_key_lookalike", {"hint": "А", "letters": "А"}),
    "type and links of a pair swapped": (
        "four_bar.yaml", lambda t: _swap(t["mechanism"]["pairs"][2], "type", "links"),
        "mechanism.pairs[2] (id 'C')", "table.swapped", {"a": "type", "b": "links"}),
    "id and name of a link swapped": (
        "whitworth.yaml", lambda t: _swap(t["mechanism"]["links"][4], "id", "name"),
        "mechanism.links[4]", "table.swapped", {"a": "name", "b": "id"}),
    "point and direction of a slider swapped": (
        "whitworth.yaml", lambda t: _swap(t["geometry"]["C"], "point", "direction"),
        "geometry 'C'", "table.swapped", {"a": "point", "b": "direction"}),
    "a link missing from the links table": (
        "whitworth.yaml", lambda t: t["mechanism"]["links"].pop(3),
        "mechanism.pairs[2] (id 'C') 'links'", "chain.unknown_link_pairs",
        {"link": "3", "pairs": "'D', 'E'"}),
    "the input link missing from the links table": (
        "slotted_lever.yaml", lambda t: t["mechanism"]["links"].pop(1),
        "mechanism.pairs[0] (id 'A') 'links'", "chain.unknown_link_pairs",
        {"link": "1", "pairs": "'B'"}),
    "the frame missing from the links table": (
        "whitworth.yaml", lambda t: t["mechanism"]["links"].pop(0),
        "mechanism 'frame'", "chain.frame_not_a_link", {"frame": "0"}),
    "the driven pair missing from the pairs table": (
        "hydraulic_boom.yaml", lambda t: t["mechanism"]["pairs"].pop(
            next(k for k, p in enumerate(t["mechanism"]["pairs"]) if p["id"] == "Pd")),
        "mechanism.inputs[0] 'pair'", "chain.unknown_pair", {"pair": "'Pd'"}),
    "look-alike letter in the id of the driven pair": (
        "hydraulic_boom.yaml", lambda t: next(
            p for p in t["mechanism"]["pairs"] if p["id"] == "Pd").update(id="Рd"),
        "mechanism.inputs[0] 'pair'", "chain.unknown_pair", {"pair": "'Pd'"}),
    "an assembly variant out of range": (
        "course_11_link_table.yaml", lambda t: t["structure_identification"][1].update(variant=7),
        "structure_identification[1] (L1, i = 2, j = 3) 'variant'", "table.rule_broken", {}),
    "a group kind out of range": (
        "course_11_link_table.yaml", lambda t: t["structure_identification"][3].update(L=7),
        "structure_identification[3] (L7, i = 6, j = 7) 'L'", "table.rule_broken", {}),
    "an identification row missing": (
        "course_11_link_table.yaml", lambda t: t["structure_identification"].pop(3),
        "structure_identification[1] (L1, i = 2, j = 3) 'i_plus_1'",
        "chain.link_not_in_rows_also",
        {"link": "6", "places": "structure_identification[2] (L2, i = 9, j = 8) 'j_minus_1'"}),
    "look-alike letter in the key of a load's point": (
        "slider_crank_press.yaml", lambda t: _rename(t["loads"][0], "point", "рoint"),
        "loads[0]", "table.unknown_key_lookalike", {"hint": "point"}),
    "look-alike letter in the key of a mass centre": (
        "slider_crank_press.yaml", lambda t: _rename(t["masses"][3], "centre", "сentre"),
        "masses.3", "table.unknown_key_lookalike", {"hint": "centre"}),
}


@pytest.mark.parametrize("name", SLIPS)
def test_one_slip_of_a_table_gets_one_message_at_its_place(name: str) -> None:
    table, change, where, code, data = SLIPS[name]
    mutant = copy.deepcopy(_table(table))
    change(mutant)
    issue = _only_issue(mutant, table)
    assert issue.location == where
    assert issue.message.code == code
    for key, value in data.items():
        assert str(issue.message.data[key]) == value


def test_a_variant_out_of_range_names_the_rule_and_the_value() -> None:
    mutant = _table("course_11_link_table.yaml")
    mutant["structure_identification"][1]["variant"] = 7
    issue = _only_issue(mutant, "t.yaml")
    assert issue.message.data["rule"].code == "rule.variant"
    assert issue.message.data["found"].data["value"] == 7


def test_a_look_alike_params_column_is_one_message(tmp_path: Path) -> None:
    mutant = _table("course_11_link_table.yaml")
    _rename(mutant["structure_identification"][0]["params"], "x_O1", "х_O1")
    path = tmp_path / "t.yaml"
    path.write_text(yaml.safe_dump(mutant, allow_unicode=True), encoding="utf-8")
    with pytest.raises(TableError) as caught:
        load_model(path)
    issues = caught.value.issues
    assert [(i.location, i.message.code) for i in issues] == [
        ("structure_identification (L0(1)) 'params'", "model.unknown_column_lookalike")]
    assert issues[0].message.data["hint"] == "x_O1"


def _verdict(change: Callable[[dict[str, Any]], None]) -> list[str]:
    """The failed DGTU conditions of the four-bar without its links table, changed once."""
    table = _table("four_bar.yaml")
    del table["mechanism"]["links"], table["geometry"]
    change(table["mechanism"])
    return [m.code for m in analyse_structure(chain_from_dict(table)).applicability]


@pytest.mark.parametrize("pair, links", [(2, [2, 33]), (0, [10, 1])])
def test_a_mistyped_link_number_fails_the_closed_chain_condition_only(pair: int,
                                                                      links: list[int]) -> None:
    """Link 33 (10) hangs on one pair; nothing else is wrong with the four-bar."""
    assert _verdict(lambda m: m["pairs"][pair].update(links=links)) == [
        "structure.condition.closed"]


def test_a_chain_without_its_input_fails_the_mobility_condition_only() -> None:
    assert _verdict(lambda m: m.update(inputs=[])) == ["structure.condition.mobility"]


def test_a_chain_short_of_an_input_fails_the_mobility_condition_only() -> None:
    """The five-bar with one of its two inputs left out: W = 2, one input."""
    table = _table("five_bar_two_inputs.yaml")
    table["mechanism"]["inputs"].pop(1)
    assert [m.code for m in analyse_structure(chain_from_dict(table)).applicability] == [
        "structure.condition.mobility"]
