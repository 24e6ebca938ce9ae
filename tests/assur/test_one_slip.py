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
    "j and i_plus_1 of the input group's identification row swapped": (
        "course_11_link_table.yaml",
        lambda t: _swap(t["structure_identification"][0], "j", "i_plus_1"),
        "structure_identification[0] (L0, i = 1, j = 2)", "table.swapped",
        {"a": "j", "b": "i_plus_1"}),
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
    "i_minus_1 and j_minus_1 of the input group's row swapped": (
        "course_11_link_table.yaml",
        lambda t: _swap(t["structure_identification"][0], "i_minus_1", "j_minus_1"),
        "structure_identification[0] (L0, i = 1)", "table.swapped",
        {"a": "i_minus_1", "b": "j_minus_1"}),
    "an identification row missing": (
        "course_11_link_table.yaml", lambda t: t["structure_identification"].pop(3),
        "structure_identification[1] (L1, i = 2, j = 3) 'i_plus_1'",
        "chain.link_not_in_rows_also",
        {"link": "6", "places": "structure_identification[2] (L2, i = 9, j = 8) 'j_minus_1'"}),
    "look-alike letter in the key of a load's point": (
        "slider_crank_press.yaml", lambda t: _rename(t["loads"][0], "point", "рoint"),
        "loads[0]", "table.unknown_key_lookalike", {"hint": "point"}),
    "misspelt torque of a load": (
        "four_bar_gravity.yaml", lambda t: _rename(t["loads"][0], "torque", "troque"),
        "loads[0]", "table.unknown_key_hint", {"key": "troque", "hint": "torque"}),
    "link and force of a load swapped": (
        "slider_crank_press.yaml", lambda t: _swap(t["loads"][0], "link", "force"),
        "loads[0]", "table.swapped", {"a": "link", "b": "force"}),
    "look-alike letter in the pairs key of a table with masses and loads": (
        "slider_crank_press.yaml", lambda t: _rename(t["mechanism"], "pairs", "рairs"),
        "mechanism", "table.unknown_key_lookalike", {"hint": "pairs"}),
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
    found = {key: str(issue.message.data[key]) for key in data}
    if code == "table.swapped":  # the two fields, in either order
        assert {found["a"], found["b"]} == {data["a"], data["b"]}
    else:
        assert found == data


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


# ------------------------------------------------------- problem and identification tables

PROBLEMS = TABLES / "problems"


def _problem(name: str) -> dict[str, Any]:
    return yaml.safe_load((PROBLEMS / name).read_text(encoding="utf-8"))


def _only_problem_issue(data: dict[str, Any]) -> Issue:
    from synthesis.problem_table import problem_from_dict

    with pytest.raises(TableError) as caught:
        problem_from_dict(data, "p.yaml", PROBLEMS)
    issues = caught.value.issues
    assert len(issues) == 1, "\n".join(issue.text("en") for issue in issues)
    return issues[0]


@pytest.mark.parametrize("table, row", [("class1_fourbar_rocker.yaml", 0),
                                        ("class1_fourbar_rocker.yaml", 4),
                                        ("class1_fourbar_velocity_ratio.yaml", 15),
                                        ("class4_fourbar_timed.yaml", 9)])
def test_a_control_point_row_left_out_is_told_once_with_its_number(table: str,
                                                                    row: int) -> None:
    """Row K is deleted: the rows after it are not renumbered, and the header's count
    still counts it; one finding names K, at the row that now stands in its place."""
    data = _problem(table)
    deleted = data["control_points"].pop(row)
    issue = _only_problem_issue(data)
    assert issue.message.code == "problem.control_row_missing"
    assert issue.location == f"control_points[{row}] 'K'"
    assert issue.message.data["missing"] == str(deleted["K"])
    numbers = issue.message.data["numbers"]
    assert str(deleted["K"] + 1) in numbers.split(", ")
    assert str(deleted["K"]) not in numbers.split(", ")


def test_every_control_point_row_left_out_gets_one_finding() -> None:
    rows = len(_problem("class2_six_bar_triad.yaml")["control_points"])
    for row in range(rows):
        data = _problem("class2_six_bar_triad.yaml")
        data["control_points"].pop(row)
        issue = _only_problem_issue(data)
        if row < rows - 1:  # a gap in the numbers
            assert issue.message.data["missing"] == str(row)
        else:  # the last row: only the header's count tells
            assert issue.message.code == "problem.control_count"
            assert (issue.message.data["rows"], issue.message.data["found"]) == (rows - 1, rows)


def test_a_control_point_row_given_as_a_list_is_one_finding() -> None:
    data = _problem("class1_fourbar_torque_limit.yaml")
    data["control_points"][5] = [1, 2]
    issue = _only_problem_issue(data)
    assert (issue.location, issue.message.code) == ("control_points[5]", "table.not_a_row")


def test_two_rows_left_out_are_told_together() -> None:
    data = _problem("class3_fourbar_path.yaml")
    del data["control_points"][7], data["control_points"][3]  # K = 7, then K = 3
    issue = _only_problem_issue(data)
    assert issue.message.code == "problem.control_rows_missing"
    assert issue.message.data["missing"] == "3, 7"
    assert issue.text("ru").startswith("control_points[3] 'K': нет строк K = 3, 7")


def _misspell(key: str, new: str, section: str | None = None, path: tuple[Any, ...] = ()
              ) -> Callable[[dict[str, Any]], None]:
    def change(t: dict[str, Any]) -> None:
        for step in path:
            t = t[step]
        _rename(t[section] if section else t, key, new)

    return change


PROBLEM_SLIPS: dict[str, tuple[str, Callable[[dict[str, Any]], None], str, str]] = {
    "misspelt output quantity": (
        "class1_fourbar_velocity_ratio.yaml", _misspell("output", "otuput", "general"),
        "general", "table.unknown_key_hint"),
    "look-alike letter in the output quantity": (
        "class1_fourbar_velocity_ratio.yaml", lambda t: t["general"].update(output="rаtio"),
        "general 'output'", "table.option_lookalike"),
    "misspelt control-point table": (
        "class1_fourbar_velocity_ratio.yaml", _misspell("control_points", "cnotrol_points"),
        "", "table.unknown_key_hint"),
    "misspelt identification table": (
        "class3_fourbar_path.yaml",
        _misspell("structure_identification", "srtucture_identification"),
        "", "table.unknown_key_hint"),
    "misspelt parameters table": (
        "class2_six_bar_triad.yaml", _misspell("parameters", "praameters"),
        "", "table.unknown_key_hint"),
    "misspelt task class": (
        "class1_fourbar_velocity_ratio.yaml", _misspell("task_class", "tsak_class", "general"),
        "general", "table.unknown_key_hint"),
    "look-alike letter in the parameters table of the identification form": (
        "class1_fourbar_torque_limit.yaml", _misspell("parameters", "рarameters"),
        "", "table.unknown_key_lookalike"),
    "the parameters table given as a number": (
        "class2_course_11_link.yaml", lambda t: t.update(parameters=5),
        "'parameters'", "table.wrong_kind"),
    "a link of a parameters row out of range": (
        "class2_six_bar_triad.yaml", lambda t: t["parameters"][0]["links"].__setitem__(
            -1, 10 ** 12), "parameters[0] 'links'", "problem.links_unknown"),
    "pressure angle and rotations of an allowable row swapped": (
        "class1_fourbar_torque_limit.yaml",
        lambda t: _swap(t["allowable"][0], "pressure_angle", "rotations"),
        "allowable[0]", "table.swapped"),
    "links and pressure angle of an allowable row swapped": (
        "class1_fourbar_velocity_ratio.yaml",
        lambda t: _swap(t["allowable"][0], "links", "pressure_angle"),
        "allowable[0]", "table.swapped"),
    "j and i_minus_1 of an identification row swapped": (
        "class1_fourbar_rocker.yaml",
        lambda t: _swap(t["structure_identification"][1], "j", "i_minus_1"),
        "structure_identification[1]", "table.swapped"),
    "a number and an 'A' of a parameters row swapped": (
        "class1_fourbar_zone.yaml", lambda t: _swap(t["parameters"][1], "y_Hi", "x_Hj"),
        "parameters[1]", "table.swapped"),
    "a link of a parameters row mistyped, not blamed on the identification row": (
        "class1_fourbar_rocker.yaml", lambda t: t["parameters"][1].update(links=[2, 4]),
        "parameters[1] 'links'", "problem.links_unknown"),
    "j and i_minus_1 of the input group's row swapped": (
        "class1_fourbar_torque_limit.yaml",
        lambda t: _swap(t["structure_identification"][0], "j", "i_minus_1"),
        "structure_identification[0] (L0, i = 1, j = 0)", "table.swapped"),
    "K and phi of a control point swapped": (
        "class1_fourbar_velocity_ratio.yaml",
        lambda t: _swap(t["control_points"][10], "K", "phi"),
        "control_points[10]", "table.swapped"),
    "the output link given as a word": (
        "class1_fourbar_zone.yaml", lambda t: t["output"].update(link="ten"),
        "output 'link'", "problem.output_link_unknown"),
    "a link of an identification row out of range": (
        "class1_fourbar_rocker.yaml",
        lambda t: t["structure_identification"][1].update(i=10 ** 12),
        "structure_identification[1]", "problem.row_links"),
    "the dyad's identification row left out": (
        "class1_fourbar_rocker.yaml", lambda t: t["structure_identification"].pop(1),
        "structure_identification", "problem.rows_missing"),
    "the input group's identification row left out": (
        "class4_fourbar_timed.yaml", lambda t: t["structure_identification"].pop(0),
        "structure_identification", "problem.rows_missing"),
    "look-alike letter in the centre of a mass that follows the design": (
        "class1_fourbar_inertia_limit.yaml", _misspell("centre", "сentre", None, ("forces",
                                                                                  "masses", 2)),
        "forces.masses.2", "table.unknown_key_lookalike"),
    "look-alike letter in the loads of the force conditions": (
        "class1_fourbar_torque_limit.yaml", _misspell("loads", "lоads", "forces"),
        "forces", "table.unknown_key_lookalike"),
}


@pytest.mark.parametrize("name", PROBLEM_SLIPS)
def test_one_slip_of_a_problem_table_gets_one_message_at_its_place(name: str) -> None:
    table, change, where, code = PROBLEM_SLIPS[name]
    data = _problem(table)
    change(data)
    issue = _only_problem_issue(data)
    assert (issue.location, issue.message.code) == (where, code)


def test_a_swapped_pair_of_a_row_names_the_two_columns() -> None:
    data = _problem("class1_fourbar_rocker.yaml")
    _swap(data["structure_identification"][1], "j", "i_minus_1")
    issue = _only_problem_issue(data)
    assert {issue.message.data["a"], issue.message.data["b"]} == {"j", "i_minus_1"}


def test_a_row_left_out_names_the_groups_the_other_tables_give() -> None:
    data = _problem("class1_fourbar_rocker.yaml")
    row = data["structure_identification"].pop(1)
    issue = _only_problem_issue(data)
    assert issue.message.data["links"] == str([row["i"], row["j"]])
    assert (issue.message.data["rows"], issue.message.data["found"]) == (
        1, data["general"]["groups"])
    assert issue.message.data["places"] == "parameters[1], allowable[0]"


def test_a_decimal_comma_in_a_zone_row_is_one_finding(tmp_path: Path) -> None:
    from synthesis.problem_table import load_problem

    text = (PROBLEMS / "class1_fourbar_velocity_ratio.yaml").read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    row = next(n for n, line in enumerate(lines) if "n_hi: 0.5}" in line)
    lines[row] = lines[row].replace("n_hi: 0.5}", "n_hi: 0,5}")
    path = tmp_path / "p.yaml"
    path.write_text("".join(lines), encoding="utf-8")
    with pytest.raises(TableError) as caught:
        load_problem(path)
    assert [issue.message.code for issue in caught.value.issues] == ["table.yaml_decimal_comma_key"]


def _identification_rows() -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = _table("course_11_link_table.yaml")["structure_identification"]
    return rows


def test_a_dyad_row_left_out_is_one_finding_naming_both_links() -> None:
    """Deleting the row of a dyad whose links other rows name: one finding, both links."""
    rows = _identification_rows()
    told = 0
    for index, row in enumerate(rows):
        rest = rows[:index] + rows[index + 1:]
        named = {other[key] for other in rest
                 for key in ("i_minus_1", "j_minus_1", "i_plus_1", "j_plus_1")}
        dangling = sorted({row["i"], row["j"]} & named - {None})
        if len(dangling) < 2:
            continue
        told += 1
        table = _table("course_11_link_table.yaml")
        table["structure_identification"].pop(index)
        issue = _only_issue(table, "t.yaml")
        assert issue.message.code == "chain.links_not_in_rows"
        assert issue.message.data["links"] == ", ".join(map(str, dangling))
    assert told, "the table has a dyad both of whose links other rows name"


def test_an_identification_row_left_out_with_nothing_naming_it_is_told_by_its_seq() -> None:
    """A row no other row names: the seq numbers have a gap, and the header's counts are
    not judged against the rows that are left."""
    rows = _identification_rows()
    named = {row[key] for row in rows
             for key in ("i_minus_1", "j_minus_1", "i_plus_1", "j_plus_1")}
    loose = [n for n, row in enumerate(rows)
             if not {row["i"], row["j"]} & named and row["seq"] < len(rows)]
    assert loose, "the table has a row no other row names"
    table = _table("course_11_link_table.yaml")
    row = table["structure_identification"].pop(loose[0])
    issue = _only_issue(table, "t.yaml")
    assert issue.message.code == "chain.seq_row_missing"
    assert issue.message.data["missing"] == str(row["seq"])
