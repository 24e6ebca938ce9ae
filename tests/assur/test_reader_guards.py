"""What every table reader refuses before and while parsing, and what a student types.

Each test writes a table with one typical mistake, runs the command that reads it in-process
and checks the exit code 2 and the sentence of the catalogue (English and Russian) against
the mistake made: the limit, the look-alike letter, the decimal comma, the encoding, the
command that reads the table.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
import yaml

from assur.errors import TableError
from assur.io.reader import LARGEST, MAX_BYTES, MAX_DEPTH, SMALLEST, TableReader, positive
from assur.text import render
from synthesis.cli.main import main

TABLES = Path(__file__).resolve().parents[2] / "input_tables"
FOUR_BAR = (TABLES / "four_bar.yaml").read_text(encoding="utf-8")


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out + captured.err


def write(folder: Path, text: str | bytes, name: str = "t.yaml") -> str:
    path = folder / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text, encoding="utf-8")
    return str(path)


# ------------------------------------------------------------------ before parsing


def test_a_file_too_large_is_refused_before_parsing(tmp_path, capsys) -> None:
    table = write(tmp_path, FOUR_BAR + "#" * MAX_BYTES)
    code, text = run(capsys, "check", table)
    size = os.path.getsize(table)
    assert code == 2 and f"{size} bytes" in text and f"at most {MAX_BYTES} bytes" in text
    assert table in text


def test_deep_nesting_is_refused_with_its_line(tmp_path, capsys) -> None:
    deep = "[" * (MAX_DEPTH + 1) + "]" * (MAX_DEPTH + 1)
    table = write(tmp_path, f"name: x\nmechanism:\n  frame: {deep}\n")
    code, text = run(capsys, "analyze", table)
    assert code == 2 and f"more than {MAX_DEPTH} deep" in text and "line 3" in text
    # exactly at the limit the file is parsed (and refused for what it says, not its depth)
    shallow = "[" * (MAX_DEPTH - 2) + "]" * (MAX_DEPTH - 2)
    code, text = run(capsys, "check", write(tmp_path, f"mechanism:\n  frame: {shallow}\n"))
    assert code == 2 and "nested more than" not in text


def test_ten_thousand_brackets_end_in_a_message(tmp_path, capsys) -> None:
    code, text = run(capsys, "check", write(tmp_path, "[" * 10_000))
    assert code == 2 and "nested more than" in text


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_windows_1251_is_named_with_the_fix(tmp_path, capsys, lang) -> None:
    plain = FOUR_BAR.encode("ascii", errors="ignore").decode()
    russian = plain.replace("name:", "# кривошипно-коромысловый механизм\nname:", 1)
    table = write(tmp_path, russian.encode("cp1251"))
    code, text = run(capsys, "check", table, "--lang", lang)
    line = next(n for n, text in enumerate(russian.splitlines(), 1) if "кривошипно" in text)
    assert code == 2 and "Windows-1251" in text and "UTF-8" in text
    assert re.search(rf"(line|строка) {line}:", text)


def test_other_bytes_are_named_as_not_utf8(tmp_path, capsys) -> None:
    code, text = run(capsys, "check", write(tmp_path, b"name: \x80\x81\n"))
    assert code == 2 and "not UTF-8" in text and "0x80" in text


def test_a_byte_order_mark_is_accepted(tmp_path, capsys) -> None:
    code, _ = run(capsys, "check", write(tmp_path, b"\xef\xbb\xbf" + FOUR_BAR.encode()))
    assert code == 0


def test_a_fifo_is_refused_without_waiting(tmp_path, capsys) -> None:
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    code, text = run(capsys, "check", str(fifo))
    assert code == 2 and "not a regular file" in text


# ---------------------------------------------------------------- what a student types


def test_a_key_with_a_cyrillic_letter_is_named_as_such(tmp_path, capsys) -> None:
    table = write(tmp_path, FOUR_BAR.replace("pairs:", "p\u0430irs:", 1))
    for lang, words in (("en", "Cyrillic letters that look like Latin"),
                        ("ru", "кириллическими буквами, похожими на латинские")):
        code, text = run(capsys, "check", table, "--lang", lang)
        assert code == 2 and words in text and "\u0430" in text and "'pairs'" in text


def test_a_pair_type_typed_in_cyrillic_is_named_as_such(tmp_path, capsys) -> None:
    table = write(tmp_path, FOUR_BAR.replace("type: R", "type: \u0420", 1))
    code, text = run(capsys, "check", table)
    assert code == 2 and "Cyrillic" in text and "type 'P' in Latin letters" in text
    assert "expected one of" not in text


def test_a_russian_word_is_not_taken_for_look_alikes(tmp_path, capsys) -> None:
    code, text = run(capsys, "check", write(tmp_path, FOUR_BAR.replace("type: R", "type: шар",
                                                                          1)))
    assert code == 2 and "Cyrillic" not in text and "'шар' (a text)" in text


@pytest.mark.parametrize("written", ["{point: [0, 0], direction: 90,27}",
                                     "{point: [0, 0], direction: '90,27'}"])
def test_a_decimal_comma_is_explained_alike_by_check_and_analyze(tmp_path, capsys,
                                                                 written) -> None:
    """Both explain it; ``analyze`` needs the sketch and stops, ``check`` reports it beside
    the structure when the sketch alone is wrong (a YAML-level slip stops both)."""
    table = (TABLES / "course_11_link.yaml").read_text(encoding="utf-8")
    table = write(tmp_path, _edited(table, "{point: [150, 0], direction: 90.27}", written))
    code, answer = run(capsys, "analyze", table)
    assert code == 2 and "decimal comma" in answer and "90.27" in answer
    lines = [line.strip(" -") for line in answer.splitlines()[1:] if "decimal comma" in line]
    code, checked = run(capsys, "check", table)
    assert lines and all(line in checked for line in lines)


WRONG = [
    ("problems/class1_fourbar_rocker.yaml", ["case", "tracker", "--table"],
     "assur synthesize FILE"),
    ("four_bar.yaml", ["synthesize"], "assur check FILE"),
    ("case_impact.yaml", ["analyze"], "assur case impact --table FILE"),
    ("case_tracker.yaml", ["check"], "assur case tracker --table FILE"),
    ("case_fourbar_velocity_ratio.yaml", ["case", "impact", "--table"],
     "assur case fourbar-velocity-ratio --table FILE"),
]


@pytest.mark.parametrize(("table", "command", "right"), WRONG)
def test_a_table_given_to_the_wrong_command_names_the_right_one(capsys, table, command,
                                                                right) -> None:
    code, text = run(capsys, *command, str(TABLES / table))
    assert code == 2 and right in text and "unknown key" not in text
    assert len(text.strip().splitlines()) == 2  # the header and the one problem
    code, text = run(capsys, *command, str(TABLES / table), "--lang", "ru")
    assert code == 2 and right in text and "её читает команда" in text


# ---------------------------------------------------------------- values out of range


def _edited(text: str, old: str, new: str) -> str:
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("value", ["1.0e+308", ".nan", "-.inf", "null",
                                   "[1, 2]", "{a: 1}"])
def test_a_sketch_coordinate_must_be_an_ordinary_number(tmp_path, capsys, value) -> None:
    joint = "C"
    assert yaml.safe_load(FOUR_BAR)["geometry"][joint] == {"point": [110, 80]}
    text = _edited(FOUR_BAR, "C: {point: [110, 80]}", f"C: {{point: [{value}, 80]}}")
    code, out = run(capsys, "analyze", write(tmp_path, text), "--points", "8")
    assert code == 2 and f"geometry {joint!r} 'point'" in out


@pytest.mark.parametrize(("old", "new", "field"), [
    ("r1: 100 ", "r1: 1.0e+308 ", "'r1'"),
    ("r1: 100 ", "r1: 5.0e-324 ", "'r1'"),
    ("r1: 100 ", "r1: null ", "'r1'"),
    ("m2: 0.012", "m2: .nan", "'m2'"),
    ("sigma: 1 ", "sigma: [1] ", "'sigma'"),
])
def test_a_case_table_refuses_odd_numbers(tmp_path, capsys, old, new, field) -> None:
    table = write(tmp_path, _edited((TABLES / "case_impact.yaml").read_text(), old, new))
    code, text = run(capsys, "case", "impact", "--table", table)
    assert code == 2 and table in text and field in text


@pytest.mark.parametrize(("old", "new"), [("l1_mm: 300", "l1_mm: 5.0e-324"),
                                          ("l1_mm: 300", "l1_mm: 1.0e+308"),
                                          ("l1_mm: 300", "l1_mm: null"),
                                          ("k5: [2.0]", "k5: [1.0e+300]")])
def test_the_tracker_table_error_names_the_users_file(tmp_path, capsys, old, new) -> None:
    table = write(tmp_path, _edited((TABLES / "case_tracker.yaml").read_text(), old, new))
    code, text = run(capsys, "case", "tracker", "--table", table, "--budget", "0")
    assert code == 2 and table in text and "mechanism.yaml" not in text


def test_every_number_field_refuses_huge_values_and_a_size_tiny_ones(tmp_path) -> None:
    reader = TableReader.from_data({"x": LARGEST * 10, "y": LARGEST, "z": 1e-300, "n": 10 ** 12,
                                    "c": 1e-300})
    top = reader.root()
    assert top.get("y", kind="number") == LARGEST
    assert top.get("c", kind="number") == 1e-300  # a coordinate near 0 is a coordinate
    for key, kind in (("x", "number"), ("z", "number"), ("n", "int")):
        top.get(key, kind=kind, check=positive)
    assert [issue.location for issue in reader.issues] == ["'x'", "'z'", "'n'"]
    assert render("rule.number_size", high=LARGEST) in reader.issues[0].text()
    assert render("rule.positive_size", low=SMALLEST) in reader.issues[1].text()


# ------------------------------------------------------------- what the docs refuse


def test_an_assembly_variant_other_than_plus_minus_one_is_refused(tmp_path, capsys) -> None:
    text = (TABLES / "course_11_link_table.yaml").read_text(encoding="utf-8")
    table = write(tmp_path, _edited(text, "variant: -1", "variant: 7"))
    code, out = run(capsys, "check", table)
    assert code == 2 and "'variant'" in out and "+1 or -1" in out and "found 7" in out


def _problem(tmp_path: Path, old: str, new: str) -> str:
    text = (TABLES / "problems" / "class1_fourbar_rocker.yaml").read_text(encoding="utf-8")
    (tmp_path / "problems").mkdir(exist_ok=True)
    return write(tmp_path / "problems", _edited(text, old, new))


def test_a_varied_column_that_changes_nothing_is_refused(tmp_path, capsys) -> None:
    table = _problem(tmp_path, "l_N: 0, beta_N: 0", "l_N: 0, beta_N: 0, l_Q: [1, 0, 2]")
    code, out = run(capsys, "synthesize", table, "--budget", "1", "--quiet")
    assert code == 2 and "'l_Q'" in out and "change nothing" in out


def test_two_targets_at_one_crank_angle_are_refused(tmp_path, capsys) -> None:
    problem = yaml.safe_load((TABLES / "problems" / "class1_fourbar_rocker.yaml").read_text())
    first, second = problem["control_points"][:2]
    assert first["psi"] != second["psi"]
    table = _problem(tmp_path, f"phi: {second['phi']},", f"phi: {first['phi'] + 360},")
    code, out = run(capsys, "synthesize", table, "--budget", "1", "--quiet")
    assert code == 2 and "control_points[1] 'phi'" in out and "control_points[0]" in out
    # the same target twice is no contradiction
    same = _problem(tmp_path, f"phi: {second['phi']}, psi: {second['psi']}",
                    f"phi: {first['phi']}, psi: {first['psi']}")
    code, out = run(capsys, "synthesize", same, "--budget", "1", "--quiet")
    assert "'phi'" not in out


def test_an_id_written_as_a_list_is_refused_in_a_problem(tmp_path, capsys) -> None:
    table = _problem(tmp_path, "- {L: 1, i: 2,", "- {L: 1, i: [[1, 2], [3]],")
    code, out = run(capsys, "synthesize", table, "--budget", "1", "--quiet")
    assert code == 2 and "'i'" in out


def test_a_grid_too_large_to_allocate_is_refused(tmp_path, capsys) -> None:
    table = _problem(tmp_path, "grid: 360", "grid: 100000000")
    code, out = run(capsys, "synthesize", table, "--budget", "1", "--quiet")
    assert code == 2 and "'grid'" in out


def test_an_unknown_output_point_is_refused(tmp_path, capsys) -> None:
    text = (TABLES / "problems" / "class3_fourbar_path.yaml").read_text(encoding="utf-8")
    (tmp_path / "problems").mkdir()
    table = write(tmp_path / "problems", _edited(text, "output: {link: 2, point: N}",
                                                 "output: {link: 2, point: Q}"))
    code, out = run(capsys, "synthesize", table, "--budget", "1", "--quiet")
    assert code == 2 and "output 'point'" in out and "'Q'" in out and "N" in out


def test_the_reader_raises_one_error_for_an_unreadable_file(tmp_path) -> None:
    with pytest.raises(TableError) as caught:
        TableReader.from_path(tmp_path / "absent.yaml")
    assert caught.value.issues[0].text() == render("table.file_missing")


@pytest.mark.parametrize("field", ["psi1_deg: 20 ", "n_star: 0.5 "])
def test_a_required_case_value_may_not_be_null(tmp_path, capsys, field) -> None:
    name = field.split(":")[0]
    text = (TABLES / "case_fourbar_velocity_ratio.yaml").read_text(encoding="utf-8")
    table = write(tmp_path, _edited(text, field, f"{name}: null "))
    code, out = run(capsys, "case", "fourbar-velocity-ratio", "--table", table)
    assert code == 2 and f"'{name}': expected a number; found nothing (null)" in out
