"""Table reading: every problem collected at once, in English and Russian; atomic writes."""

from __future__ import annotations

import os
import stat

import pytest

from assur import TableError
from assur.io.files import atomic_write_text
from assur.io.reader import TableReader
from assur.text import Message
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
        row.get("id", kind="id", check=lambda v: Message("rule.not_zero", {"name": "id"})
                if v == 0 else None)
    return reader


def test_every_problem_is_collected_with_its_place() -> None:
    reader = _read({"links": 3, "framee": 0, "pairs": [{"id": 0, "type": "Q"}, 7]})
    texts = [issue.text("en") for issue in reader.issues]
    assert texts == [
        "unknown key 'framee'; did you mean 'frame'?",
        "'links': expected a list; found 3",
        "pairs[0] (id 0) 'type': expected one of 'R', 'P'; found 'Q' (a text)",
        "pairs[0] (id 0) 'id': id must not be zero; found 0",
        "pairs[1]: expected a row (a mapping such as {id: A, ...}); found 7",
    ]  # the misspelt 'framee' is not also reported missing
    with pytest.raises(TableError, match=r"^5 problems in t\.yaml:"):
        reader.raise_if_any()


def test_russian_wording_of_the_same_problems() -> None:
    reader = _read({"links": 3, "framee": 0, "pairs": [{"id": 0, "type": "Q"}]})
    texts = [issue.text("ru") for issue in reader.issues]
    assert texts[0] == "неизвестный ключ 'framee'; возможно, имелось в виду 'frame'?"
    assert texts[1] == "'links': ожидается список; найдено: 3"
    assert texts[2] == "pairs[0] (id 0) 'type': ожидается одно из: 'R', 'P'; найдено: 'Q' (текст)"
    assert texts[3] == "pairs[0] (id 0) 'id': значение id не может быть нулём; найдено: 0"
    error = TableError("t.yaml", reader.issues)
    assert error.text("ru").splitlines()[0] == "t.yaml: найдены 4 ошибки"


@pytest.mark.parametrize(("count", "english", "russian"), [
    (1, "1 problem in t.yaml:", "t.yaml: найдена 1 ошибка"),
    (3, "3 problems in t.yaml:", "t.yaml: найдены 3 ошибки"),
    (11, "11 problems in t.yaml:", "t.yaml: найдено 11 ошибок"),
    (21, "21 problems in t.yaml:", "t.yaml: найдена 21 ошибка"),
    (24, "24 problems in t.yaml:", "t.yaml: найдены 24 ошибки"),
])
def test_header_counts_problems_with_plural_forms(count, english, russian) -> None:
    reader = TableReader.from_data({"links": list(range(count))}, source="t.yaml")
    for row in reader.root().rows("links"):
        pass
    error = TableError("t.yaml", reader.issues)
    assert len(error.issues) == count
    assert error.text("en").splitlines()[0] == english
    assert error.text("ru").splitlines()[0] == russian


@pytest.mark.parametrize(("value", "english", "russian"), [
    (None, "nothing (null)", "пусто (null)"),
    (True, "True (true/false)", "True (true/false)"),
    (2.5, "2.5", "2.5"),
    ("abc", "'abc' (a text)", "'abc' (текст)"),
    ([1], "a list of 1 item", "список из 1 элемента"),
    ([1, 2, 3], "a list of 3 items", "список из 3 элементов"),
    ({"a": 1}, "a mapping", "словарь"),
])
def test_a_found_value_is_described_in_both_languages(value, english, russian) -> None:
    reader = TableReader.from_data({"x": value}, source="t.yaml")
    reader.root().get("x", kind="int")
    prefix_en = "'x': expected a whole number; found "
    prefix_ru = "'x': ожидается целое число; найдено: "
    assert reader.issues[0].text("en") == prefix_en + english
    assert reader.issues[0].text("ru") == prefix_ru + russian


def test_command_line_reports_in_the_chosen_language(tmp_path, capsys) -> None:
    table = tmp_path / "bad.yaml"
    table.write_text(BAD, encoding="utf-8")
    assert main(["check", str(table), "--lang", "ru"]) == 2
    err = capsys.readouterr().err
    assert "неизвестный ключ 'framee'" in err and "Traceback" not in err
    assert main(["check", str(table)]) == 2
    assert "3 problems in" in capsys.readouterr().err


def test_top_of_the_file_must_be_a_mapping() -> None:
    reader = TableReader.from_data([1, 2], source="t.yaml")
    reader.root()
    assert [issue.text("ru") for issue in reader.issues] == [
        "в начале файла ожидается словарь таблиц; найдено: список из 2 элементов"]


def test_invalid_yaml_names_line_and_column(tmp_path) -> None:
    table = tmp_path / "broken.yaml"
    table.write_text("mechanism:\n  links: [0, 1\n", encoding="utf-8")
    with pytest.raises(TableError) as caught:
        TableReader.from_path(table)
    issue = caught.value.issues[0]
    assert issue.text("en").startswith("line 2, column 10: the '[' opened here is not closed")
    assert issue.text("ru").startswith("строка 2, столбец 10: открытая здесь скобка '[' не")


def test_missing_file_and_folder_are_named(tmp_path) -> None:
    for path, english, russian in [(tmp_path / "none.yaml", "the file does not exist",
                                    "такого файла нет"),
                                   (tmp_path, "this is a folder, not a table file",
                                    "это папка, а не файл таблицы")]:
        with pytest.raises(TableError) as caught:
            TableReader.from_path(path)
        assert caught.value.text("en") == f"1 problem in {path}:\n  - {english}"
        assert caught.value.text("ru") == f"{path}: найдена 1 ошибка\n  - {russian}"


def test_atomic_write_leaves_no_temporary_file_and_honours_umask(tmp_path) -> None:
    target = tmp_path / "out" / "result.txt"
    atomic_write_text(target, "first")
    atomic_write_text(target, "second")
    assert target.read_text(encoding="utf-8") == "second"
    assert os.listdir(target.parent) == ["result.txt"]
    mask = os.umask(0o022)
    os.umask(mask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~mask
