"""Reading chain tables and identification tables."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from assur import chain_from_dict, load_chain
from assur.errors import TableError
from assur.model import Allowable, General, PairType

BROKEN = sorted((Path(__file__).parent / "broken").glob("*.yaml"))
ROOT = Path(__file__).resolve().parents[2]


def _expectations(path: Path) -> tuple[str, str]:
    text = path.read_text(encoding="utf-8")
    expect = re.search(r"^# expect: (.*)$", text, re.MULTILINE).group(1)
    where = re.search(r"^# where: (.*)$", text, re.MULTILINE).group(1)
    return expect, where


@pytest.mark.parametrize("path", BROKEN, ids=[p.stem for p in BROKEN])
def test_broken_table_names_file_row_and_field(path: Path) -> None:
    expect, where = _expectations(path)
    with pytest.raises(TableError) as info:
        load_chain(path)
    text = str(info.value)
    assert str(path) in text.splitlines()[0]
    line = next((line for line in text.splitlines() if expect in line), None)
    assert line is not None, text
    assert where in line or where in text.splitlines()[0], text


def test_every_problem_is_reported_at_once() -> None:
    data = {"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 0]},
        {"id": "B", "type": "X", "links": [1, 2]},
        {"id": "C", "type": "P", "links": [2, 0]}], "inputs": [1], "framee": 0}}
    with pytest.raises(TableError) as info:
        chain_from_dict(data, source="many.yaml")
    messages = [str(issue.message) for issue in info.value.issues]
    assert len(messages) == 4
    assert any("self pair" in m for m in messages)
    assert any("found 'X'" in m for m in messages)
    assert any("guide" in m for m in messages)
    assert any("did you mean 'frame'" in m for m in messages)


def _four_bar(**extra: object) -> dict:
    return {"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": ["0", "1"]},
        {"id": "B", "type": "R", "links": ["1", "2"]},
        {"id": "C", "type": "R", "links": ["2", "3"]},
        {"id": "D", "type": "P", "links": ["3", "0"], "guide": "0"}],
        "inputs": [{"link": "1"}], **extra}}


def test_digit_texts_are_link_numbers_and_the_frame_defaults_to_zero() -> None:
    chain = chain_from_dict(_four_bar())
    assert chain.frame == 0
    assert chain.links == (0, 1, 2, 3)
    assert chain.pair("D").links == (3, 0) and chain.pair("D").guide == 0
    assert chain.pair("D").type is PairType.P
    assert chain.inputs[0].link == 1


def test_text_link_ids_are_kept() -> None:
    data = {"mechanism": {"frame": "ground", "pairs": [
        {"id": "A", "type": "R", "links": ["ground", "crank"]},
        {"id": "B", "type": "R", "links": ["crank", "rod"]},
        {"id": "C", "type": "P", "links": ["rod", "ground"], "guide": "ground"}],
        "inputs": ["crank"]}}
    chain = chain_from_dict(data)
    assert chain.frame == "ground" and set(chain.moving_links) == {"crank", "rod"}


_SKETCH = {"A": {"point": [0, 0]}, "B": {"point": [0, 30]}, "C": {"point": [80, 60]},
           "D": {"point": [100, 60], "direction": [3, 4]},
           "input": {"rotation": "cw"}, "margin": 0.05,
           "tracing": {"K": {"link": "2", "point": [10, 50]}}}


def test_geometry_is_read_once_into_a_typed_sketch() -> None:
    data = _four_bar()
    data["geometry"] = _SKETCH
    data["general"] = {"omega": 12}
    chain = chain_from_dict(data)
    sketch = chain.geometry
    assert sketch.points == {"A": 0j, "B": 30j, "C": complex(80, 60), "D": complex(100, 60)}
    assert sketch.directions["D"].vector == complex(3, 4)
    assert sketch.directions["D"].angle == pytest.approx(math.atan2(4, 3))
    assert sketch.directions["D"].unit == pytest.approx(complex(0.6, 0.8))
    assert (sketch.rotation, sketch.margin, sketch.stroke) == (-1, 0.05, None)
    assert [(t.name, t.link, t.point) for t in sketch.tracing] == [("K", 2, complex(10, 50))]
    assert chain.general == General(omega=12.0)
    inner = chain_from_dict(_four_bar(geometry=_SKETCH))
    assert inner.geometry == sketch


def test_every_problem_of_the_sketch_is_reported_when_the_chain_is_read() -> None:
    geometry = {"A": {"pont": [0, 0]}, "B": {"point": [0, "y"]}, "C": [1, 2],
                "D": {"point": [0, 0], "direction": [0, 0]}, "anything": {},
                "input": {"stroke": [5, 1]}, "margin": {"L1(2,3)": 2},
                "tracing": {"K": {"link": 0, "point": [1, 1]}}}
    with pytest.raises(TableError) as info:
        chain_from_dict(_four_bar(geometry=geometry), source="sketch.yaml")
    lines = str(info.value).splitlines()
    assert lines[0] == "8 problems in sketch.yaml:"  # the misspelt 'pont' is not also missing
    assert set(lines[1:]) == {
        "  - geometry 'anything': unknown key; did you mean 'tracing'?",
        "  - geometry 'A': unknown key 'pont'; did you mean 'point'?",
        "  - geometry 'B' 'point': expected two numbers [x, y] (mm); found a list of 2 items",
        ("  - geometry 'C': expected {point: [x, y]} (and 'direction' for a slider pair); "
         "found a list of 2 items"),
        ("  - geometry 'D' 'direction': expected an angle in degrees or a vector [dx, dy]; "
         "found a list of 2 items"),
        ("  - geometry 'input' 'stroke': expected [min, max] actuator lengths (mm), "
         "0 < min < max; found [5, 1]"),
        "  - geometry 'margin' 'L1(2,3)': δ must lie in [0, 1); found 2",
        "  - geometry.tracing 'K' 'link': expected a moving link of the mechanism; found 0"}


def test_geometry_given_twice_is_an_error() -> None:
    data = _four_bar(geometry={"A": {"point": [0, 0]}})
    data["geometry"] = {"A": {"point": [0, 0]}}
    with pytest.raises(TableError, match="give the geometry once"):
        chain_from_dict(data)


def test_compound_hinge_becomes_k_minus_1_pairs_with_origin() -> None:
    data = {"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 1]},
        {"id": "K", "type": "R", "links": [1, 2, 3, 0]}], "inputs": [1]}}
    chain = chain_from_dict(data)
    k_pairs = [p for p in chain.pairs if p.origin == "K"]
    assert len(k_pairs) == 3
    assert all(0 in p.links for p in k_pairs)       # centred on the frame, known first
    assert chain.pair("K").origin == "K"


def test_compound_prismatic_pair_is_refused() -> None:
    data = {"mechanism": {"pairs": [
        {"id": "A", "type": "P", "links": [0, 1, 2], "guide": 0}], "inputs": [1]}}
    with pytest.raises(TableError, match="only a revolute hinge"):
        chain_from_dict(data)


def test_identification_table_rebuilds_the_course_chain() -> None:
    chain = load_chain(ROOT / "input_tables" / "course_11_link.yaml")
    rebuilt = load_chain(ROOT / "input_tables" / "course_11_link_table.yaml")

    def pairs(c: object) -> set:
        return {(p.id, p.type, frozenset(p.links), p.guide) for p in c.pairs}

    # the 16 pairs of method.md §3.5, with the same names, types and guide carriers
    assert pairs(rebuilt) == pairs(chain)
    assert rebuilt.inputs[0].link == 1
    assert rebuilt.claims == {"n_moving_links": 11, "p5": 16, "p4": 0, "W": 1, "N_Q": 6}
    assert len(rebuilt.identification) == 6


def test_row_params_are_read_with_their_rows() -> None:
    crank = {"x_O1": 0, "y_O1": 0, "l_1": 40, "phi_1_0": 90, "s": -1}
    dyad = {"x_Hi": "A", "y_Hi": "A", "x_Hj": 100, "y_Hj": 0, "l_i": 120, "l_j": 90,
            "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0, "delta": 0.1, "l_K": 30,
            "beta_K": 45, "tracing": [{"name": "K", "link": 2}]}
    data = {"structure_identification": [
        {"L": 0, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None, "params": crank},
        {"L": 1, "i_minus_1": 1, "j_minus_1": 0, "i": 2, "j": 3, "params": dyad}],
        "general": {"allowable": [{"links": [2, 3], "pressure_angle": 50}]}}
    chain = chain_from_dict(data)
    assert set(chain.group_params) == {(1,), (2, 3)}
    first, second = chain.group_params[(1,)], chain.group_params[(2, 3)]
    assert first.values == {"x_O1": 0.0, "y_O1": 0.0, "l_1": 40.0, "phi_1_0": 90.0}
    assert first.direction == -1
    assert "x_Hi" not in second.values and second.values["x_Hj"] == 100.0
    assert second.values["delta"] == 0.1 and second.values["beta_K"] == 45.0
    assert second.tracing == (("K", 2),)
    assert chain.identification[1].params is second
    assert chain.general == General(allowable=(Allowable((2, 3), 50.0),))
    assert chain.geometry is None


def test_row_params_values_are_checked_when_the_table_is_read() -> None:
    params = {"x_Hi": "A", "l_i": [1, 2, 3], "l_j": "x", "s": 2,
              "tracing": ["K"]}
    data = {"structure_identification": [
        {"L": 0, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None},
        {"L": 1, "i_minus_1": 1, "j_minus_1": 0, "i": 2, "j": 3, "params": params}]}
    found = chain_from_dict(data, source="rows.yaml").group_params[(2, 3)]
    where = "structure_identification (L1(2,3)) 'params'"
    assert [issue.text() for issue in found.problems] == [
        (f"{where} 'l_i': a range [initial, lower, upper] belongs in the parameters table of "
         "a synthesis problem (assur synthesize); a mechanism table takes one number; "
         "found [1, 2, 3]"),
        (f"{where} 'l_j': expected a number or 'A' (supplied by an earlier group); "
         "found 'x' (a text)"),
        f"{where} 's': s must be +1 or −1; found 2",
        (f"{where} 'tracing': expected rows {{name: Ж, link: L}} with columns l_<name>, "
         "beta_<name>; found 'K' (a text)")]
    assert found.supplied == {"x_Hi"} and found.values == {}


def test_chain_form_may_carry_a_table_to_check() -> None:
    data = _four_bar()
    data["structure_identification"] = [
        {"L": 0, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None}]
    chain = chain_from_dict(data)
    row = chain.identification[0]
    assert (row.L, row.i, row.i_minus_1, row.j, row.variant) == (0, 1, 0, None, None)
    assert row.key == (1,) and row.get("i") == 1 and row.get("params") is None


def test_a_missing_pairs_table_is_not_blamed_on_the_inputs() -> None:
    with pytest.raises(TableError) as info:
        chain_from_dict({"mechanism": {"pairz": [], "inputs": [1]}}, source="typo.yaml")
    assert [str(issue.message) for issue in info.value.issues] == [
        "unknown key 'pairz'; did you mean 'pairs'?"]  # not also missing
