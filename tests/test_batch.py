"""Batch check of a folder of mixed good and broken tables, in parallel.

Every table is written here with its expected verdict, worked out by hand: the counts, the
Chebyshev formula, and for the four-bar that does not assemble the crank angles where the
coupler and the rocker cannot reach each other (law of cosines).  Every other entry of the
folder (a text file, a hidden file, links that lead nowhere or in a loop, a FIFO, a folder
named like a table) gets a row that says why it is skipped.
"""

from __future__ import annotations

import csv
import json
import math
import os
import shutil
from dataclasses import replace
from pathlib import Path

import pytest
import yaml

from synthesis.app.batch import check_table, run_batch
from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent


def _circles(a: complex, ra: float, b: complex, rb: float) -> complex:
    """The intersection of two circles left of the line a→b (hand-written construction)."""
    d = abs(b - a)
    x = (ra ** 2 - rb ** 2 + d ** 2) / (2 * d)
    h = math.sqrt(ra ** 2 - x ** 2)
    u = (b - a) / d
    return a + u * (x + 1j * h)


def four_bar(crank: float, coupler: float, rocker: float, frame: float,
             identification: list | None = None, *, left: bool = True) -> dict:
    """A four-bar chain table with a sketch at crank angle 0; the joint C left of B → D
    (the course's variant +1 of the RRR dyad) or, mirrored in the line BD, right of it."""
    a, d = 0j, complex(frame, 0)
    b = a + crank
    c = _circles(b, coupler, d, rocker)
    c = c if left else c.conjugate()  # B and D lie on the x-axis
    table = {"mechanism": {"name": "four-bar", "pairs": [
        {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
        {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
        "inputs": [{"link": 1}]},
        "geometry": {k: {"point": [p.real, p.imag]} for k, p in
                     (("A", a), ("B", b), ("C", c), ("D", d))}}
    table["geometry"]["input"] = {"rotation": "ccw"}
    if identification is not None:
        table["structure_identification"] = identification
    return table


GOOD_ROWS = [
    {"L": 0, "seq": 1, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None, "i_plus_1": 2,
     "j_plus_1": None, "variant": None, "out_code": "0"},
    {"L": 1, "seq": 2, "i_minus_1": 1, "j_minus_1": 0, "i": 2, "j": 3, "i_plus_1": None,
     "j_plus_1": None, "variant": 1, "out_code": "8;2"}]

# crank 40, coupler 50, rocker 30, frame 100: the crank pin B is |BD|² = 40² + 100² −
# 2·40·100·cos φ from the rocker pivot D and the dyad needs |BD| ≤ 50 + 30, so it assembles
# only while cos φ ≥ (40² + 100² − 80²)/(2·40·100) = 0.65.
FAIL_FROM = math.degrees(math.acos(0.65))
FAIL_TO = 360.0 - FAIL_FROM


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("class")

    def put(name: str, data: object) -> None:
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(data if isinstance(data, str) else yaml.safe_dump(data,
                                                                           allow_unicode=True),
                        encoding="utf-8")

    put("a_good.yaml", four_bar(30, 90, 80, 100, GOOD_ROWS))
    wrong = [dict(GOOD_ROWS[0]), dict(GOOD_ROWS[1], L=2)]  # the student calls RRR kind 2
    put("b_wrong_kind.yaml", four_bar(30, 90, 80, 100, wrong))
    put("c_broken_yaml.yaml", "mechanism: [links, 0, 1\npairs: {\n")
    typo = four_bar(30, 90, 80, 100)
    typo["mechanism"]["pairz"] = typo["mechanism"].pop("pairs")
    put("d_typo.yaml", typo)
    put("e_five_bar.yaml", {"mechanism": {"pairs": [
        {"id": i, "type": "R", "links": links} for i, links in
        enumerate(([0, 1], [1, 2], [2, 3], [3, 4], [4, 0]))], "inputs": [1]}})
    put("f_does_not_assemble.yaml", four_bar(40, 50, 30, 100))
    put("g_empty.yaml", "")
    put("notes.txt", "not a table")
    put(".hidden.yaml", "mechanism: {}")
    put("x.yaml/inside.yaml", four_bar(30, 90, 80, 100, GOOD_ROWS))  # a folder named x.yaml
    (root / "loop.yaml").symlink_to("loop.yaml")
    (root / "dangling.yaml").symlink_to("nowhere.yaml")
    (root / "link_to_group.yaml").symlink_to("group2")
    os.mkfifo(root / "pipe.yaml")  # opening it would block: it must never be opened
    shutil.copy(ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml",
                root / "i_problem.yaml")  # a synthesis problem: its mechanism as first given
    (root / "group2").mkdir()
    shutil.copy(ROOT / "input_tables" / "course_11_link_table.yaml",
                root / "group2" / "h_course.yaml")
    return root


SKIPPED = ("not checked", "not checked")
EXPECTED = {  # file: (verdict, words of the first problem, identification, existence)
    ".hidden.yaml": ("skipped", "hidden file", *SKIPPED),
    "a_good.yaml": ("correct", "", "matches", "whole cycle"),
    "b_wrong_kind.yaml": ("wrong", "kind 1", "differs", "whole cycle"),
    "c_broken_yaml.yaml": ("unreadable", "is not closed", *SKIPPED),
    "d_typo.yaml": ("unreadable", "did you mean 'pairs'", *SKIPPED),
    "dangling.yaml": ("skipped", "link to nothing", *SKIPPED),
    # the local finding first (its advice), the mobility that differs from the inputs after it
    "e_five_bar.yaml": ("wrong", "inputs to add: 1", "not given", "no dimensions"),
    "f_does_not_assemble.yaml": ("wrong", "does not assemble", "not given", "fails"),
    "g_empty.yaml": ("unreadable", "found nothing", *SKIPPED),
    # a table without a sketch: nothing confirms its assembly variants
    "group2/h_course.yaml": ("not verified", "no sketch", "matches", "whole cycle"),
    "i_problem.yaml": ("correct", "", "matches", "whole cycle"),
    "link_to_group.yaml": ("skipped", "link to a folder", *SKIPPED),
    "loop.yaml": ("skipped", "loop", *SKIPPED),
    "notes.txt": ("skipped", "not a table", *SKIPPED),
    "pipe.yaml": ("skipped", "special file (fifo)", *SKIPPED),
    "x.yaml": ("skipped", "folder named like a table", *SKIPPED),
    "x.yaml/inside.yaml": ("correct", "", "matches", "whole cycle"),
}


def test_one_row_per_entry_with_the_right_verdict(folder):
    rows = run_batch(folder, jobs=2)
    assert [r.file for r in rows] == sorted(EXPECTED)  # every entry, in sorted order
    for row in rows:
        verdict, words, identification, existence = EXPECTED[row.file]
        assert row.verdict == verdict, row
        assert words in row.problem, row
        assert row.identification == identification, row
        assert row.existence == existence, row
        assert (row.problem == "") == (verdict == "correct")
    by_file = {r.file: r for r in rows}
    good = by_file["a_good.yaml"]
    assert (good.n, good.p5, good.W) == (3, 4, 3 * 3 - 2 * 4)
    five = by_file["e_five_bar.yaml"]
    assert (five.n, five.p5, five.W) == (4, 5, 3 * 4 - 2 * 5)
    course = by_file["group2/h_course.yaml"]
    assert (course.n, course.p5, course.W) == (11, 16, 1)
    assert by_file["i_problem.yaml"].formula == "I(0,1) → II₁(2,3)"  # a four-bar


def test_failure_interval_matches_the_law_of_cosines(folder):
    row = check_table(folder / "f_does_not_assemble.yaml")
    assert "L1(2,3)" in row.problem
    assert f"{FAIL_FROM:.1f}°" in row.problem and f"{FAIL_TO:.1f}°" in row.problem
    ru = check_table(folder / "f_does_not_assemble.yaml", lang="ru")
    assert "не собирается" in ru.problem and f"{FAIL_FROM:.1f}°" in ru.problem


def test_parallel_and_serial_runs_agree(folder):
    def strip(rows):
        return [replace(r, seconds=0.0) for r in rows]

    assert strip(run_batch(folder, jobs=2)) == strip(run_batch(folder, jobs=1))


def test_command_line_writes_csv_and_json_with_the_words_of_the_text(folder, tmp_path, capsys):
    out = tmp_path / "class.csv"
    assert main(["batch", str(folder), "--csv", str(out), "--json", "--jobs", "2"]) == 0
    captured = capsys.readouterr()
    rows = json.loads(captured.out)
    assert {r["file"]: r["verdict"] for r in rows} == {k: v[0] for k, v in EXPECTED.items()}
    assert captured.err.strip().splitlines() == [f"written: {out}"]
    raw = out.read_bytes()
    assert raw.startswith(b"\xef\xbb\xbf")  # the UTF-8 byte-order mark, for spreadsheets
    records = list(csv.DictReader(raw.decode("utf-8-sig").splitlines()))
    assert {r["file"]: r["verdict"] for r in records} == {k: v[0] for k, v in EXPECTED.items()}
    assert main(["batch", str(folder), "--jobs", "1", "--quiet"]) == 0
    text = capsys.readouterr().out.splitlines()
    for name, (verdict, *_rest) in EXPECTED.items():  # the text shows the same words
        line = next(x for x in text if x.startswith(name + " "))
        assert line[len(name):].strip().startswith(verdict), line
    assert "wrong (1)" in next(x for x in text if x.startswith("b_wrong_kind.yaml "))


def test_csv_without_the_byte_order_mark(folder, tmp_path, capsys):
    out = tmp_path / "class.csv"
    assert main(["batch", str(folder / "group2"), "--csv", str(out), "--no-bom"]) == 0
    assert out.read_bytes().startswith(b"file,verdict,")


def test_summary_in_russian(folder, capsys):
    assert main(["batch", str(folder), "--lang", "ru", "--jobs", "2", "--quiet"]) == 0
    lines = capsys.readouterr().out.splitlines()
    verdicts = {"correct": "верно", "not verified": "не проверено", "wrong": "неверно",
                "unreadable": "не читается", "skipped": "пропущено"}
    for name, (verdict, *_rest) in EXPECTED.items():
        line = next(x for x in lines if x.startswith(name + " "))
        assert line[len(name):].strip().startswith(verdicts[verdict]), line
    counts = {v: sum(e[0] == v for e in EXPECTED.values()) for v in verdicts}
    assert lines[-1] == (f"верно: {counts['correct']}, вне программы: 0, не проверено: "
                         f"{counts['not verified']}, неверно: "
                         f"{counts['wrong']}, не читается: {counts['unreadable']}, пропущено: "
                         f"{counts['skipped']}; всего: {len(EXPECTED)}")


def test_correct_mechanisms_outside_the_course_program(tmp_path):
    """The hydraulic boom (an actuator input) and the five-bar with two inputs are correct
    mechanisms; the course's method covers neither (its conditions 3 and 5)."""
    for name in ("hydraulic_boom.yaml", "five_bar_two_inputs.yaml"):
        shutil.copy(ROOT / "input_tables" / name, tmp_path / name)
    rows = run_batch(tmp_path, jobs=1)
    assert [(r.verdict, r.problems) for r in rows] == [("outside program", 1)] * 2
    assert "condition 5" in rows[0].problem and "condition 3" in rows[1].problem


def test_reports_for_readable_tables(tmp_path):
    class_dir = tmp_path / "class"
    class_dir.mkdir()
    (class_dir / "good.yaml").write_text(yaml.safe_dump(four_bar(30, 90, 80, 100)), "utf-8")
    (class_dir / "sub").mkdir()
    (class_dir / "sub" / "five_bar.yaml").write_text(yaml.safe_dump({"mechanism": {"pairs": [
        {"id": i, "type": "R", "links": ab} for i, ab in
        enumerate(([0, 1], [1, 2], [2, 3], [3, 4], [4, 0]))], "inputs": [1]}}), "utf-8")
    (class_dir / "broken.yaml").write_text("mechanism: [\n", "utf-8")
    reports = tmp_path / "reports"
    rows = run_batch(class_dir, jobs=2, reports=reports)
    assert [r.verdict for r in rows] == ["unreadable", "correct", "wrong"]
    written = sorted(str(p.relative_to(reports)) for p in reports.rglob("*.html"))
    assert written == ["good.html", "sub/five_bar.html"]
    assert "I(0,1) → II₁(2,3)" in (reports / "good.html").read_text("utf-8")


def test_not_a_folder(tmp_path, capsys):
    assert main(["batch", str(tmp_path / "missing")]) == 2
    assert "not a folder" in capsys.readouterr().err


def test_assembly_variant_against_the_sketch(tmp_path):
    right = tmp_path / "right.yaml"  # C drawn right of B → D: variant −1, the table says +1
    right.write_text(yaml.safe_dump(four_bar(30, 90, 80, 100, GOOD_ROWS, left=False)), "utf-8")
    row = check_table(right)
    assert (row.verdict, row.identification) == ("wrong", "differs")
    assert "'variant'" in row.problem and "variant -1, the table says 1" in row.problem
    fixed = [dict(GOOD_ROWS[0]), dict(GOOD_ROWS[1], variant=-1)]
    right.write_text(yaml.safe_dump(four_bar(30, 90, 80, 100, fixed, left=False)), "utf-8")
    assert check_table(right).identification == "matches"


def test_a_report_that_fails_keeps_the_verdict(tmp_path, monkeypatch, capsys):
    """The pictures of a report may fail (a design that never assembles); the row keeps the
    verdict of the table and says the report was not written."""
    class_dir = tmp_path / "class"
    class_dir.mkdir()
    (class_dir / "never.yaml").write_text(yaml.safe_dump(four_bar(40, 50, 30, 100)), "utf-8")

    def pictures_fail(*_args, **_kwargs):
        raise IndexError("index 0 is out of bounds for axis 0 with size 0")

    monkeypatch.setattr("synthesis.app.coursework.build_report", pictures_fail)
    reports = tmp_path / "reports"
    assert main(["batch", str(class_dir), "--jobs", "1", "--reports", str(reports)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("never.yaml") and "wrong (1)" in out[0]
    assert "report not written" in out[1] and "IndexError" in out[1]
    row = check_table(class_dir / "never.yaml")
    assert row.verdict == "wrong" and not list(reports.rglob("*.html"))
