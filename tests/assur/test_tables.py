"""Table reading: every problem collected at once, in English and Russian; atomic writes."""

from __future__ import annotations

import os
import stat

import pytest

from assur import TableError, TableReader, atomic_write_text
from synthesis.cli import main

BAD = """mechanism:
  framee: 0
  links: [0, 1]
  pairs:
    - {id: A, type: Q, links: [0, 1]}
"""


def _read(data: dict) -> TableReader:
    reader = TableReader.from_data(data, source="t.yaml")
    top = reader.root(allowed={"links", "frame", "pairs"})
    top.get("links", kind="list")
    top.get("frame", kind="id")
    for row in top.rows("pairs", allowed={"id", "type"}, label=lambda r: f"id {r.get('id')!r}"):
        row.choice("type", ("R", "P"))
        row.get("id", kind="id", check=lambda v: ("must not be 0", "не может быть 0")
                if v == 0 else None)
    return reader


def test_every_problem_is_collected_with_its_place() -> None:
    reader = _read({"links": 3, "framee": 0, "pairs": [{"id": 0, "type": "Q"}, 7]})
    texts = [issue.text("en") for issue in reader.issues]
    assert texts == [
        "unknown key 'framee'; did you mean 'frame'?",
        "'links': expected a list; found 3",
        "'frame': this field is missing; expected an id (a whole number or a text)",
        "pairs[0] (id 0) 'type': expected one of 'R', 'P'; found 'Q' (a text)",
        "pairs[0] (id 0) 'id': must not be 0; found 0",
        "pairs[1]: expected a row (a mapping such as {id: A, ...}); found 7",
    ]
    with pytest.raises(TableError, match=r"^6 problems in t\.yaml:"):
        reader.raise_if_any()


def test_russian_wording_of_the_same_problems() -> None:
    reader = _read({"links": 3, "framee": 0, "pairs": [{"id": 0, "type": "Q"}]})
    texts = [issue.text("ru") for issue in reader.issues]
    assert texts[0] == "неизвестный ключ 'framee'; возможно, имелось в виду 'frame'?"
    assert texts[1] == "'links': ожидалось список; найдено 3"
    assert texts[3] == "pairs[0] (id 0) 'type': ожидалось одно из: 'R', 'P'; найдено 'Q' (текст)"
    assert texts[4] == "pairs[0] (id 0) 'id': не может быть 0; найдено 0"
    error = TableError("t.yaml", reader.issues)
    assert error.text("ru").splitlines()[0] == "t.yaml: найдено ошибок: 5"


def test_command_line_reports_in_the_chosen_language(tmp_path, capsys) -> None:
    table = tmp_path / "bad.yaml"
    table.write_text(BAD, encoding="utf-8")
    assert main(["check", str(table), "--lang", "ru"]) == 2
    err = capsys.readouterr().err
    assert "неизвестный ключ 'framee'" in err and "Traceback" not in err
    assert main(["check", str(table)]) == 2
    assert "3 problems in" in capsys.readouterr().err


def test_invalid_yaml_names_line_and_column(tmp_path) -> None:
    table = tmp_path / "broken.yaml"
    table.write_text("mechanism:\n  links: [0, 1\n", encoding="utf-8")
    with pytest.raises(TableError) as caught:
        TableReader.from_path(table)
    issue = caught.value.issues[0]
    assert issue.location.startswith("line ") and "not valid YAML" in issue.message


def test_atomic_write_leaves_no_temporary_file_and_honours_umask(tmp_path) -> None:
    target = tmp_path / "out" / "result.txt"
    atomic_write_text(target, "first")
    atomic_write_text(target, "second")
    assert target.read_text(encoding="utf-8") == "second"
    assert os.listdir(target.parent) == ["result.txt"]
    mask = os.umask(0o022)
    os.umask(mask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~mask
