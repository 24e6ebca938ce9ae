"""YAML that cannot be read as a table: the spot named in plain words, in English and
Russian, with the line shown and a caret under the spot; keys written twice refused.

The expected line and column of every case are found in the test's own text (the line that
holds the opening bracket, the tab, the repeated key), not taken from the program.
"""

from __future__ import annotations

from itertools import pairwise
from pathlib import Path

import pytest

from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = (ROOT / "input_tables" / "four_bar.yaml").read_text(encoding="utf-8")


def _run(tmp_path: Path, text: str, capsys: pytest.CaptureFixture[str], *words: str,
         lang: str = "en", name: str = "t.yaml") -> tuple[int, str]:
    table = tmp_path / name
    table.write_text(text, encoding="utf-8")
    code = main(["--lang", lang, *(words or ("check",)), str(table)])
    return code, capsys.readouterr().err


def _spot(text: str, needle: str, occurrence: int = 1) -> tuple[int, int, str]:
    """Line and column (from 1) of the ``occurrence``-th ``needle`` in ``text``, and its line."""
    index = -1
    for _ in range(occurrence):
        index = text.index(needle, index + 1)
    line = text.count("\n", 0, index)
    column = index - (text.rfind("\n", 0, index) + 1)
    return line + 1, column + 1, text.splitlines()[line]


def _caret_under(err: str, source_line: str, column: int) -> bool:
    """Whether ``err`` shows ``source_line`` with a caret under ``column`` on the next line."""
    lines = err.splitlines()
    for shown, below in pairwise(lines):
        if shown.strip() == source_line.strip() and below.strip() == "^":
            start = len(shown) - len(shown.lstrip())
            indent = start - (len(source_line) - len(source_line.lstrip()))
            return below.index("^") == indent + column - 1
    return False


UNCLOSED = FOUR_BAR.replace("{id: B, type: R, links: [1, 2]}", "{id: B, type: R, links: [1, 2]")


@pytest.mark.parametrize("lang, words", [
    ("en", ("the '{' opened here is not closed", "a ',' or '}' is expected before line")),
    ("ru", ("открытая здесь скобка '{' не закрыта", "ожидается ',' или '}'"))])
def test_an_unclosed_bracket_is_named_where_it_was_opened(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], lang: str,
        words: tuple[str, ...]) -> None:
    line, column, source = _spot(UNCLOSED, "{id: B")
    code, err = _run(tmp_path, UNCLOSED, capsys, lang=lang)
    assert code == 2
    head = {"en": f"line {line}, column {column}: ", "ru": f"строка {line}, столбец {column}: "}
    assert head[lang] + words[0] in err
    assert words[1] in err
    next_line = {"en": f"before line {line + 1},", "ru": f"до строки {line + 1},"}
    assert next_line[lang] in err  # the parser stops on the next line; the bracket is named
    assert _caret_under(err, source, column)
    assert "expected ','" not in err and "<scalar>" not in err


def test_an_unclosed_bracket_before_a_comma_is_named_where_it_was_opened(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = FOUR_BAR.replace("{id: B, type: R, links: [1, 2]}", "{id: B, type: R, links: [1, 2],")
    line, column, source = _spot(text, "{id: B")
    code, err = _run(tmp_path, text, capsys)
    assert code == 2
    assert f"line {line}, column {column}: the '{{' opened here is not closed" in err
    assert _caret_under(err, source, column)


def test_an_unclosed_list_under_analyze_and_in_a_problem_table(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    problem = (ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml").read_text(
        encoding="utf-8")
    opened = problem.index("links: [") + len("links: ")
    broken = problem[:opened + 1] + problem[opened + 1:].replace("]", "", 1)
    line, column, source = _spot(broken, "links: [")
    column += len("links: ")
    code, err = _run(tmp_path, broken, capsys, "synthesize", name="p.yaml")
    assert code == 2 and f"line {line}, column {column}: the '[' opened here" in err
    assert _caret_under(err, source, column)
    code, err = _run(tmp_path, UNCLOSED, capsys, "analyze")
    assert code == 2 and "opened here is not closed" in err


@pytest.mark.parametrize("lang, words", [
    ("en", "a tab character; indent with spaces, not tabs"),
    ("ru", "символ табуляции; делайте отступы пробелами, а не табуляцией")])
def test_a_tab_says_indent_with_spaces(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                       lang: str, words: str) -> None:
    text = FOUR_BAR.replace("    - {id: C,", "\t- {id: C,")
    line, column, source = _spot(text, "\t")
    code, err = _run(tmp_path, text, capsys, lang=lang)
    assert code == 2
    assert words in err
    assert (f"line {line}, column {column}" if lang == "en"
            else f"строка {line}, столбец {column}") in err
    assert _caret_under(err, source.replace("\t", " "), column)
    assert "cannot start any token" not in err


@pytest.mark.parametrize("text, needle, en, ru", [
    ("mechanism:\n  name: a: b\n", ": b", "a ':' where a value was expected",
     "':' там, где ожидалось значение"),
    ("mechanism:\n  name: x\n frame: 0\n", "frame",
     "this line is not indented like the lines above it",
     "отступ этой строки не совпадает"),
    ("mechanism:\n  name: @x\n", "@", "a value cannot start with '@'",
     "значение не может начинаться с '@'"),
    ("mechanism:\n  name: \"x\n  frame: 0\n", "\"", "the quote opened here is not closed",
     "открытая здесь кавычка не закрыта"),
    ("mechanism:\n  name: !!python/object:os.system x\n", "!!", "a tag ('!…') is not allowed",
     "тег ('!…') в таблице не допускается"),
    ("mechanism:\n  name: *x\n", "*x", "a reference ('*name') to no anchor",
     "ссылка ('*имя') на якорь ('&имя'), которого выше нет"),
])
def test_other_syntax_errors_in_plain_words(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                            text: str, needle: str, en: str, ru: str) -> None:
    line, column, source = _spot(text, needle)
    code, err = _run(tmp_path, text, capsys)
    assert code == 2 and f"line {line}, column {column}: {en}" in err
    assert _caret_under(err, source, column)
    code, err = _run(tmp_path, text, capsys, lang="ru")
    assert code == 2 and f"строка {line}, столбец {column}: {ru}" in err
    assert not any(word in err for word in ("scanning", "parsing", "expected <", "token"))


# ---------------------------------------------------------------------------- repeated keys

FORCES = (ROOT / "input_tables" / "four_bar_gravity.yaml").read_text(encoding="utf-8")


def _twice(text: str, key: str) -> tuple[str, int, int]:
    """``text`` with the block ``key:`` (a top-level section) written again at the end, and the
    lines of the two."""
    start = text.index(f"\n{key}:") + 1
    end = text.find("\n", start)
    while end != -1 and end + 1 < len(text) and text[end + 1] in " #":
        end = text.find("\n", end + 1)
    section = text[start:end if end != -1 else len(text)]
    doubled = text.rstrip("\n") + "\n" + section + "\n"
    first = text.count("\n", 0, start) + 1
    second = doubled.count("\n", 0, doubled.rindex(f"\n{key}:") + 1) + 1
    return doubled, first, second


@pytest.mark.parametrize("lang, words", [
    ("en", ("the key 'masses' is written twice, on lines {a} and {b}; YAML would keep the "
            "last in silence: keep one")),
    ("ru", "ключ 'masses' записан дважды, в строках {a} и {b}; YAML молча оставил бы последний")])
def test_a_section_written_twice_is_refused_naming_both_lines(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], lang: str, words: str) -> None:
    text, first, second = _twice(FORCES, "masses")
    code, err = _run(tmp_path, text, capsys, "analyze", lang=lang)
    assert code == 2
    assert words.format(a=first, b=second) in err


def test_a_row_of_a_mapping_and_a_key_inside_a_row_written_twice(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    masses = FORCES.index("\nmasses:") + 1
    row_start = FORCES.index("\n", masses) + 1
    row = FORCES[row_start:FORCES.index("\n", row_start) + 1]
    text = FORCES[:row_start] + row + row + FORCES[row_start + len(row):]
    line = text.count("\n", 0, row_start) + 1
    key = row.split(":")[0].strip()
    code, err = _run(tmp_path, text, capsys, "analyze")
    assert code == 2
    assert f"line {line + 1}, column" in err
    assert f"the key '{key}' is written twice, on lines {line} and {line + 1}" in err

    text = FOUR_BAR.replace("{id: 2, name: {en: coupler, ru: шатун}}",
                            "{id: 2, name: {en: coupler, ru: шатун}, name: rod}")
    line, column, source = _spot(text, "name: rod")
    code, err = _run(tmp_path, text, capsys)
    assert code == 2
    assert f"line {line}, column {column}: the key 'name' is written twice in this row" in err
    assert _caret_under(err, source, column)
    code, err = _run(tmp_path, text, capsys, lang="ru")
    assert "ключ 'name' записан в этой строке дважды" in err


def test_a_key_written_twice_in_a_problem_table(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    problem = (ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml").read_text(
        encoding="utf-8")
    first_key = next(line.split(":")[0] for line in problem.splitlines()
                     if line and line[0].isalpha())
    text, first, second = _twice(problem, first_key)
    code, err = _run(tmp_path, text, capsys, "synthesize", name="p.yaml")
    assert code == 2
    assert f"the key '{first_key}' is written twice, on lines {first} and {second}" in err


def test_a_repeated_key_through_a_yaml_merge_is_not_a_repetition(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = FOUR_BAR.replace("geometry:\n", "base: &p {point: [0, 0]}\ngeometry:\n").replace(
        "A: {point: [0, 0]}", "A: {<<: *p, point: [0, 0]}")
    _, err = _run(tmp_path, text, capsys)
    assert "written twice" not in err
