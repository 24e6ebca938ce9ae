"""The text catalogue: every code in every language, translated, with the same fields.

The catalogue files are read here with a parser independent of :mod:`assur.text` (Babel's
PO reader), and every code the source names is looked up in them.
"""

from __future__ import annotations

import ast
import re
import shutil
import string
from pathlib import Path

import pytest
from babel.messages.pofile import read_po, write_po

from assur import TableError, text
from assur.errors import Issue
from assur.text import Message

ROOT = Path(__file__).resolve().parents[1]
#: A flag on an entry whose text is the same in every language (a symbol, a unit).
SAME = "same-in-all-languages"


def _entries(lang: str) -> dict[str, tuple[tuple[str, ...], set[str]]]:
    with (text.LOCALE / f"{lang}.po").open("rb") as stream:
        catalog = read_po(stream)
    out = {}
    for message in catalog:
        if not message.id:
            continue
        key = message.id[0] if isinstance(message.id, tuple) else message.id
        strings = message.string if isinstance(message.string, tuple) else (message.string,)
        out[key] = (tuple(strings), set(message.flags))
    return out


def _fields(template: str) -> set[str]:
    return {name.split(".")[0].split("[")[0]
            for _, name, _, _ in string.Formatter().parse(template) if name}


def test_english_and_russian_catalogues_exist() -> None:
    assert text.languages()[:1] == ("en",)
    assert "ru" in text.languages()


@pytest.mark.parametrize("lang", [lang for lang in text.languages() if lang != "en"])
def test_every_code_is_translated_with_the_same_fields(lang: str) -> None:
    english, other = _entries("en"), _entries(lang)
    missing = sorted(set(english) - set(other))
    extra = sorted(set(other) - set(english))
    assert not missing, f"{lang}.po lacks {missing}"
    assert not extra, f"{lang}.po has codes that en.po does not: {extra}"
    problems = []
    for code, (strings, flags) in english.items():
        translated, _ = other[code]
        if any(not s.strip() for s in translated):
            problems.append(f"{code}: empty")
            continue
        if SAME not in flags and set(translated) & set(strings):
            problems.append(f"{code}: same text as English")
        wanted = set().union(*(_fields(s) for s in strings))
        for s in translated:
            if not _fields(s) <= wanted:
                problems.append(f"{code}: fields {_fields(s) - wanted} not in English")
        if not set().union(*(_fields(s) for s in translated)) >= wanted - {"n"}:
            problems.append(f"{code}: drops fields of English")
    assert not problems, "\n".join(problems)


def test_every_code_named_in_the_source_is_in_the_catalogue() -> None:
    known = set(_entries("en"))
    pattern = re.compile(r"""(?:Message|render)\(\s*["']([a-z0-9_]+(?:\.[a-z0-9_]+)+)["']""")
    named = {}
    for path in list((ROOT / "assur").rglob("*.py")) + list((ROOT / "synthesis").rglob("*.py")):
        for code in pattern.findall(path.read_text(encoding="utf-8")):
            named.setdefault(code, path.relative_to(ROOT).as_posix())
    unknown = {code: where for code, where in named.items() if code not in known}
    assert not unknown, f"codes missing from en.po: {unknown}"


def test_render_falls_back_and_never_raises() -> None:
    assert text.render("count.problems", "ru", n=21) == "21 ошибка"
    assert text.render("count.problems", "ru", n=12) == "12 ошибок"
    assert text.render("no.such.code", "ru", x=1) == "no.such.code(x=1)"
    with pytest.raises(ValueError, match="languages are en"):
        text.check_lang("xx")


#: Latin words a Russian sentence may hold: YAML's literals (acronyms such as YAML pass too).
LATIN_ALLOWED = {"true", "false", "null"}


def _prose(template: str) -> str:
    """A sentence without its fields, quoted literals and identifiers (``schema_version``)."""
    plain = "".join(literal for literal, _, _, _ in string.Formatter().parse(template))
    plain = re.sub(r"'[^']*'|\w*_\w*", " ", plain)
    return plain


def test_russian_sentences_are_russian() -> None:
    problems = []
    for code, (strings, flags) in _entries("ru").items():
        if SAME in flags:
            continue
        for s in strings:
            prose = _prose(s)
            latin = {w for w in re.findall(r"[A-Za-z]{3,}", prose) if not w.isupper()}
            if not re.search("[а-яё]", prose, re.IGNORECASE) or latin - LATIN_ALLOWED:
                problems.append(f"{code}: {s!r}")
    assert not problems, "English left in ru.po:\n" + "\n".join(problems)


#: Places where a sentence is still written in the code rather than in the catalogue.
LEFT_IN_CODE = re.compile(r"""message_ru|\blang\s*[!=]=\s*["'](?:ru|en)["']|"""
                          r"""\bREASONS\[[^\]]*\]\s*\[|\breader\.add\(""")


def _places_left(paths: list[Path]) -> list[str]:
    """``path:line`` of every sentence in a language outside the catalogue.

    A place is a Russian string literal other than a docstring, a ``message_ru`` field, a
    comparison of ``lang`` with a language, an (English, Russian) pair taken from
    ``REASONS``, or a table problem recorded as English text (``reader.add``).
    """
    places = set()
    for path in paths:
        source = path.read_text(encoding="utf-8")
        name = path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else path.name
        tree = ast.parse(source)
        docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                      if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef,
                                           ast.AsyncFunctionDef))
                      and node.body and isinstance(node.body[0], ast.Expr)}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str)
                    and id(node) not in docstrings and re.search("[а-яё]", node.value, re.I)):
                places.add((name, node.lineno))
        for number, line in enumerate(source.splitlines(), 1):
            if LEFT_IN_CODE.search(line.split("#")[0]):
                places.add((name, number))
    return [f"{name}:{line}" for name, line in sorted(places)]


def test_the_scan_finds_a_sentence_left_in_the_code(tmp_path) -> None:
    module = tmp_path / "module.py"
    module.write_text('"""Модуль: a docstring may quote Russian."""\n'
                      'TABLE = {1: ("one", "один")}\n'
                      'def f(lang):\n'
                      '    """Функция."""\n'
                      '    return "two" if lang != "ru" else TABLE[1][1]\n'
                      'def g(reader):\n'
                      '    reader.add("x", "must be positive")  # английский\n', encoding="utf-8")
    assert _places_left([module]) == ["module.py:2", "module.py:5", "module.py:7"]


@pytest.mark.xfail(strict=False, reason="modules still being moved into the catalogue")
def test_no_sentence_is_left_in_the_code() -> None:
    paths = sorted((ROOT / "assur").rglob("*.py")) + sorted((ROOT / "synthesis").rglob("*.py"))
    left = _places_left(paths)
    files: dict[str, int] = {}
    for place in left:
        files[place.split(":")[0]] = files.get(place.split(":")[0], 0) + 1
    summary = "\n".join(f"{count:4d}  {name}" for name, count in
                        sorted(files.items(), key=lambda item: -item[1]))
    assert not left, f"{len(left)} places in {len(files)} files:\n{summary}"


@pytest.fixture
def fresh_catalogues():
    """Catalogues read anew before and after the test (it changes where they live)."""
    text.languages.cache_clear()
    text.catalogue.cache_clear()
    yield
    text.languages.cache_clear()
    text.catalogue.cache_clear()


def test_a_third_language_is_one_file(tmp_path, monkeypatch, fresh_catalogues) -> None:
    for lang in ("en", "ru"):
        shutil.copy(text.LOCALE / f"{lang}.po", tmp_path / f"{lang}.po")
    with (text.LOCALE / "en.po").open("rb") as stream:
        catalog = read_po(stream)
    for message in catalog:
        if message.id:
            message.string = (tuple(f"«{s}»" for s in message.string)
                              if isinstance(message.string, tuple) else f"«{message.string}»")
    with (tmp_path / "xx.po").open("wb") as stream:
        write_po(stream, catalog)
    monkeypatch.setattr(text, "LOCALE", tmp_path)

    assert text.languages() == ("en", "ru", "xx") and text.check_lang("xx") == "xx"
    for code, (strings, _) in _entries("en").items():
        data = dict.fromkeys(set().union(*(_fields(s) for s in strings)), 1)
        assert text.render(code, "xx", **data) == f"«{text.render(code, 'en', **data)}»"
    error = TableError("t.yaml", [Issue("'x'", Message("value.kind.list"))] * 2)
    assert error.text("xx").splitlines() == ["«2 problems in t.yaml:»", *["  - 'x': «a list»"] * 2]


def test_no_sentence_is_left_in_the_built_in_cases() -> None:
    assert _places_left(sorted((ROOT / "synthesis" / "cases").rglob("*.py"))) == []
