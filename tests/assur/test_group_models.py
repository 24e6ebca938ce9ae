"""Table 1.5 (the identification array of the group models), N_Q, table 1.6 in the course's
order and the output-parameter codes, on the course's worked example (fig. 1.25).

The expectations come from the course text, not from the program:

- N_Q: "Таким образом, в рассматриваемом механизме имеем Q=6 групп звеньев";
- the pairs of every group: the links a group's links join (columns i−1, j−1, i+1, j+1 of the
  course's table 1.6, copied below), each pair named by its two links as in
  ``course_11_link.yaml``;
- the base points: L4 (4, 5) "базовая точка A_3 … должна быть на звене 3", its j's point "на
  стойке"; L3 "базовая точка … находится на кулисе i" and "должна совпадать с" its hinge;
  L2 "находится на направляющей звена i", taken "на стойке"; L5 takes "за базу отсчета" of
  T the hinge of j and the base of S "на стойке"; the index k is the group's place in
  layering (L4 third: A_3, B_3; L2 fifth: A_5);
- L1: "Положение точки [M] на звене 3 не фиксированное" (link 4 slides on link 3).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
import yaml

from assur import analyse_structure, load_chain
from assur.structure.analysis import StructuralAnalysis
from assur.structure.group_models import GroupModelRow, check_group_models, group_models_table
from assur.structure.identification import check_identification, identification_table
from synthesis.cli import main

ROOT = Path(__file__).resolve().parents[2]
COURSE = ROOT / "input_tables" / "course_11_link.yaml"
COURSE_TABLE = ROOT / "input_tables" / "course_11_link_table.yaml"

#: Table 1.6 as the course prints it: L, i−1, j−1, i, j, i+1, j+1, variant (None: the dash).
TABLE_1_6 = [(0, 0, None, 1, None, 2, None, None),
             (1, 1, 0, 2, 3, 6, None, 1),
             (2, 0, 6, 9, 8, None, 10, -1),
             (3, 2, 0, 6, 7, 8, None, 0),
             (4, 3, 0, 4, 5, None, None, None),
             (5, 0, 8, 11, 10, None, None, None)]
#: The layering order of the course's structure formula I(0,1) → II₁ → II₄ → II₃ → II₂ → II₅.
LAYERING = [0, 1, 4, 3, 2, 5]


def _pair(a: int, b: int) -> str:
    """The course example's name of the pair joining links a and b: the frame last, else
    the smaller link first, the crank pivot ``0-1`` (as ``course_11_link.yaml`` writes them)."""
    if {a, b} == {0, 1}:
        return "0-1"
    if a == 0 or (b != 0 and b < a):
        a, b = b, a
    return f"{a}-{b}"


@pytest.fixture(scope="module")
def analysis() -> StructuralAnalysis:
    return analyse_structure(load_chain(COURSE))


@pytest.fixture(scope="module")
def models(analysis: StructuralAnalysis) -> dict[int, GroupModelRow]:
    return {row.L: row for row in group_models_table(analysis)}


def test_six_groups_in_every_output(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(COURSE), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["N_Q"] == 6
    assert main(["check", str(COURSE)]) == 0
    assert "N_Q = 6" in capsys.readouterr().out
    assert main(["analyze", str(COURSE), "--points", "8", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["N_Q"] == 6
    assert main(["analyze", str(COURSE), "--points", "8", "--lang", "ru"]) == 0
    assert "Число групп N_Q = 6" in capsys.readouterr().out


def test_every_group_has_a_record_with_its_place_in_layering(models: dict[int, GroupModelRow]) -> None:
    assert sorted(models) == [0, 1, 2, 3, 4, 5]
    assert [models[kind].k for kind in LAYERING] == [1, 2, 3, 4, 5, 6]


@pytest.mark.parametrize("row", TABLE_1_6, ids=lambda r: f"L{r[0]}")
def test_pairs_are_those_table_1_6_implies(models: dict[int, GroupModelRow], row: tuple[Any, ...]) -> None:
    kind, i_1, j_1, i, j, i_plus, j_plus, _ = row
    built = models[kind]
    assert (built.i, built.j) == (i, j)
    external_i = built.pair("H_i") or built.pair("P_i")
    assert external_i == _pair(i, i_1)
    if j is not None:
        assert (built.pair("H_j") or built.pair("P_j")) == _pair(j, j_1)
        assert (built.pair("C") or built.pair("P_c")) == _pair(i, j)
    # a link hinged to i (j) in the column i+1 (j+1) is attached at the point N (M)
    for point, later, link in ((built.N, i_plus, i), (built.M, j_plus, j)):
        if later is not None:
            assert point is not None and point.hinges == (_pair(link, later),)


def test_l1_point_on_rocker_3_is_not_fixed(models: dict[int, GroupModelRow]) -> None:
    point = models[1].M
    assert point is not None and point.link == 3
    assert point.hinges == () and point.guides == ("3-4",) and not point.fixed


@pytest.mark.parametrize(("kind", "letter", "name", "link", "at"), [
    (4, "A", "A_3", 3, None),      # on link 3, the guide of i = 4
    (4, "B", "B_3", 0, None),      # anywhere on the frame
    (3, "A", "A_4", 6, "2-6"),     # on the kulisa 6, at its hinge with link 2
    (2, "A", "A_5", 0, None),      # on the frame guide of i = 9
    (5, "A", "A_6", 0, None),      # the base of S, on the frame
    (5, "B", "B_6", 10, "8-10"),   # the base of T: the hinge of j = 10 with link 8
])
def test_base_points_of_the_course(models: dict[int, GroupModelRow], kind: int, letter: str, name: str,
                                    link: int, at: str | None) -> None:
    point = getattr(models[kind], letter)
    assert point is not None
    assert (point.name, point.link, point.at) == (name, link, at)


@pytest.mark.parametrize(("kind", "letter"), [(0, "A"), (1, "A"), (1, "B"), (2, "B"),
                                              (3, "B")])
def test_no_base_point_without_a_guide(models: dict[int, GroupModelRow], kind: int, letter: str
                                      ) -> None:
    assert getattr(models[kind], letter) is None


def test_student_copy_agrees_and_is_reported(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(COURSE_TABLE), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found["group_models_check"] == []
    assert len(found["group_models"]) == 6


@pytest.mark.parametrize(("row", "key", "wrong"), [
    (2, "A", 0),            # A_3 is on link 3, not the frame
    (1, "H_j", "2-3"),      # 2-3 is the internal pair of L1, its H_j is 3-0
    (3, "N", None),         # the kulisa 6 carries the hinge 6-8 of rod 8
    (4, "k", 4),            # L2 is fifth in layering
    (5, "B", {"link": 10, "at": "10-11"}),   # the course puts B_6 at the hinge 8-10
])
def test_one_wrong_field_is_named(analysis: StructuralAnalysis, row: int, key: str,
                                  wrong: Any) -> None:
    given = yaml.safe_load(COURSE_TABLE.read_text(encoding="utf-8"))["group_models"]
    given[row][key] = wrong
    found = check_group_models(analysis, given)
    assert [(m.row, m.field) for m in found] == [(row, key)]
    assert f"'{key}'" in found[0].text() and f"'{key}'" in found[0].text("ru")


def test_a_missing_record_is_reported(analysis: StructuralAnalysis) -> None:
    given = yaml.safe_load(COURSE_TABLE.read_text(encoding="utf-8"))["group_models"]
    found = check_group_models(analysis, given[:5])
    assert [(m.field, m.expected) for m in found] == [("row", "L5(11,10)")]


def test_table_1_6_in_course_order_without_invented_codes(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(COURSE)]) == 0
    lines = capsys.readouterr().out.splitlines()
    start = next(k for k, line in enumerate(lines) if "table 1.6" in line)
    assert lines[start + 1].split() == ["L", "i-1", "j-1", "i", "j", "i+1", "j+1", "variant",
                                        "code"]
    printed = [line.split() for line in lines[start + 2:start + 8]]
    dash = "–"
    expected = [[dash if v is None else str(v) for v in row] + [dash] for row in TABLE_1_6]
    assert printed == expected
    assert main(["check", str(COURSE), "--order", "layering"]) == 0
    lines = capsys.readouterr().out.splitlines()
    start = next(k for k, line in enumerate(lines) if "table 1.6" in line)
    assert [int(line.split()[0]) for line in lines[start + 2:start + 8]] == LAYERING


def test_codes_only_where_the_caller_knows_the_output(analysis: StructuralAnalysis) -> None:
    assert all(row.out_code is None for row in identification_table(analysis))
    # the caller knows the output of group L1 (2, 3), keyed by its links (i, j)
    rows = identification_table(analysis, out_codes={(2, 3): "psi3"})
    assert [(row.L, row.out_code) for row in rows if row.out_code] == [(1, "psi3")]


def test_student_codes_checked_for_form_or_against_a_known_output(analysis: StructuralAnalysis) -> None:
    given = [row.to_dict() for row in load_chain(COURSE_TABLE).identification or ()]
    assert check_identification(analysis, given) == []   # the course's own codes
    given[1]["out_code"] = "8,2"
    assert [m.field for m in check_identification(analysis, given)] == ["out_code"]
    given[1]["out_code"] = "8;2"
    found = check_identification(analysis, given, out_codes={(2, 3): "psi3"})
    assert [(m.field, m.expected, m.found) for m in found] == [("out_code", "psi3", "8;2")]


def test_points_are_marked_on_both_schemes_apart(analysis: StructuralAnalysis) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    from assur.plot.schemes import scheme_figure

    fig = scheme_figure(analysis.chain, analysis)
    renderer = FigureCanvasAgg(fig).get_renderer()
    structural, formalised = fig.axes
    points = [t for t in structural.texts if t.get_gid() == "label-point"]
    names = sorted(t.get_text() for t in points)
    assert names == sorted(["N₁", "N₂", "M₂~", "A₃", "B₃", "A₄", "N₄", "A₅", "M₅", "A₆",
                            "B₆"])
    boxes = [Text.get_window_extent(t, renderer) for t in structural.texts]
    for label in points:  # legible: no name covers another text of the scheme
        box = Text.get_window_extent(label, renderer)
        others = [b for b, t in zip(boxes, structural.texts, strict=True) if t is not label]
        assert not any(box.overlaps(b) for b in others), label.get_text()
    shown = " ".join(t.get_text() for t in formalised.texts)
    for name in ("N₁", "M₂~", "A₃ ∈ 3", "B₃ ∈ 0", "A₄ = 2-6", "A₅ ∈ 0", "B₆ = 8-10"):
        assert name in shown


def test_coursework_report_shows_table_1_5_and_n_q() -> None:
    from synthesis.app.coursework import build_report, render_html

    report = build_report(COURSE_TABLE, points=8, lang="ru")
    assert report.facts["N_Q"] == 6
    assert report.facts["group_models_check"] == []
    page = render_html(report)
    assert 'id="group-models"' in page and 'id="student-models"' in page
    assert "A_3 ∈ 3" in page and "B_6 = 8-10" in page


def test_rpp_with_the_slot_on_i_has_both_base_points() -> None:
    """A Scotch yoke's L5: the yoke 3 (i) slides on a frame guide and carries the slot of the
    block 2 (j). As in the course's L5, A_k is the base of S on the frame guide and B_k the
    base of T on the link carrying the internal guide, here anywhere on the yoke (no hinge)."""
    table = ROOT / "input_tables" / "scotch_yoke.yaml"
    row = group_models_table(analyse_structure(load_chain(table)))[1]
    assert (row.L, row.i, row.j) == (5, 3, 2)
    assert row.A is not None and (row.A.name, row.A.link, row.A.at) == ("A_2", 0, None)
    assert row.B is not None and (row.B.name, row.B.link, row.B.at) == ("B_2", 3, None)


def test_a_drive_between_moving_links_has_no_l0(capsys: pytest.CaptureFixture[str]) -> None:
    """The hydraulic boom is driven by its cylinder, "входное звено не связано со стойкой":
    its one group is the dyad with the frozen cylinder, and no input-link group is counted."""
    table = ROOT / "input_tables" / "hydraulic_boom.yaml"
    assert main(["check", str(table), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found["N_Q"] == len(found["groups"]) == 1 and found["input_groups"] == []
    assert main(["check", str(table)]) == 0
    assert "N_Q = 1 (no input-link group L0" in capsys.readouterr().out
