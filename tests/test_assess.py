"""``assess`` (a student's table checked once) and ``assur.analyse`` (the analysis of
``assur analyze``), checked against hand calculations and against the pieces they compose.

The four-bar tables come from ``test_batch``: their joint C is constructed by hand from two
circles, and the crank angles where the dyad cannot close follow from the law of cosines.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from test_batch import FAIL_FROM, FAIL_TO, GOOD_ROWS, four_bar

from assur import TableError, analyse_structure, load_chain
from assur.api import analyse
from synthesis.app.assess import assess
from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
COURSE = ROOT / "input_tables" / "course_11_link.yaml"


def _write(path: Path, data: dict) -> Path:
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    return path


def test_variant_of_a_mirrored_sketch(tmp_path: Path) -> None:
    # C drawn right of B → D is the course's variant −1 of the RRR dyad; the table says +1
    table = _write(tmp_path / "right.yaml", four_bar(30, 90, 80, 100, GOOD_ROWS, left=False))
    found = assess(table, points=None)
    (finding,) = found.variants
    assert (finding.row, finding.given, finding.group.sigma) == (1, 1, -1)
    assert (finding.group.i, finding.group.j) == (2, 3)
    assert found.mismatches == () and found.identification == "differs"
    assert [row.variant for row in found.table] == [None, -1]
    assert finding.message.text("en") == (
        "structure_identification[1] (L1, links 2, 3) 'variant': the dimensions assemble "
        "this group in the variant -1, the table says 1")
    assert finding.message.text("ru").endswith(
        "по размерам группа собирается в варианте -1, в таблице указано 1")
    left = assess(_write(tmp_path / "left.yaml", four_bar(30, 90, 80, 100, GOOD_ROWS)),
                  points=None)
    assert left.variants == () and left.identification == "matches"


def test_existence_intervals_follow_the_law_of_cosines(tmp_path: Path) -> None:
    found = assess(_write(tmp_path / "short.yaml", four_bar(40, 50, 30, 100)), points=90)
    assert found.identification == "not given" and found.mismatches is None
    assert found.existence is not None and not found.existence.all_exist
    (group,) = found.existence.groups
    (interval,) = group.intervals
    assert math.degrees(interval.start) == pytest.approx(FAIL_FROM, abs=1e-6)
    assert math.degrees(interval.end) == pytest.approx(FAIL_TO, abs=1e-6)


def test_existence_is_left_out_on_request() -> None:
    found = assess(COURSE, points=None)
    assert found.model is not None and found.existence is None
    assert assess(COURSE, points=36).existence.all_exist


def test_a_chain_read_elsewhere_is_assessed_like_its_file() -> None:
    chain = load_chain(COURSE)
    by_chain, by_path = assess(chain, points=None), assess(COURSE, points=None)
    assert by_chain.chain is chain
    assert by_chain.table == by_path.table
    assert by_chain.analysis.formula == analyse_structure(chain).formula


def test_why_there_is_no_kinematic_model(tmp_path: Path) -> None:
    sketchless = assess(ROOT / "docs" / "tutorial_class" / "petrova.yaml")
    assert sketchless.model is None and sketchless.existence is None
    assert sketchless.why_no_model.code == "term.no_geometry"
    assert [m.field for m in sketchless.mismatches] == ["L"]  # kind 1 written for an RRP
    data = four_bar(30, 90, 80, 100)
    del data["geometry"]["D"]  # the rocker pivot is not drawn: the sketch cannot be read,
    undrawn = assess(_write(tmp_path / "no_d.yaml", data))  # the structure needs none
    assert undrawn.analysis.formula == "I(0,1) → II₁(2,3)" and undrawn.model is None
    assert undrawn.verdict == "wrong" and undrawn.problems == 1
    assert "the R pair 'D'" in undrawn.first.text() and "needs 'point" in undrawn.first.text()
    five = {"mechanism": {"pairs": [{"id": i, "type": "R", "links": links} for i, links in
                                    enumerate(([0, 1], [1, 2], [2, 3], [3, 4], [4, 0]))],
                          "inputs": [1]}}
    not_dgtu = assess(_write(tmp_path / "five.yaml", five))
    assert not_dgtu.analysis.W == 3 * 4 - 2 * 5 and not not_dgtu.analysis.applicable
    assert not_dgtu.why_no_model.code == "term.no_geometry"


def test_unreadable_table_raises_with_every_problem(tmp_path: Path) -> None:
    data = four_bar(30, 90, 80, 100)
    data["mechanism"]["pairz"] = data["mechanism"].pop("pairs")
    with pytest.raises(TableError, match="did you mean 'pairs'"):
        assess(_write(tmp_path / "typo.yaml", data))


def test_analysis_positions_and_the_nearest_one() -> None:
    result = analyse(COURSE, points=24, omega=2.0)
    assert result.crank and result.omega == 2.0
    assert result.motion.q.shape == (24,)
    assert result.motion.q[1] - result.motion.q[0] == pytest.approx(2 * math.pi / 24)
    assert result.index_at(90.0) == 6  # 90° in steps of 15°
    assert result.index_at(355.0) == 0  # 5° from 360° = 0°, 10° from 345°
    assert result.existence.all_exist


def test_too_few_positions(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(TableError, match="expected at least 2 positions; found 1"):
        analyse(COURSE, points=1)
    assert main(["analyze", str(COURSE), "--points", "0", "--lang", "ru"]) == 2
    # the command refuses the option before the run, naming it and its range
    assert "--points: ожидалось целое число от 2 до 100000; найдено: 0" in capsys.readouterr().err


def test_a_mechanism_with_a_triad_is_outside_the_course_but_analysed_over_the_cycle() -> None:
    """Class III is outside the course's method (condition 8) yet has a kinematic model: the
    existence check finds the gap its table documents (φ ≈ 168°…256°, found there by a dense
    scan through every assembly mode), and the coursework report shows kinematics and forces."""
    from synthesis.app.coursework.report import build_report, render_html

    found = assess(ROOT / "input_tables" / "six_bar_triad_fails.yaml", points=360)
    assert not found.analysis.applicable and found.model is not None
    assert found.existence is not None
    ((start, end),) = [(i.start, i.end) for g in found.existence.groups for i in g.intervals]
    assert abs(math.degrees(start) - 168) < 0.5 and abs(math.degrees(end) - 256) < 0.5
    html = render_html(build_report(ROOT / "input_tables" / "six_bar_triad_forces.yaml",
                                    points=24))
    for section in ('id="existence"', 'id="kinematics"', 'id="forces"', 'id="play"'):
        assert section in html
