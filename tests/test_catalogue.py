"""The text catalogue: every code in every language, translated, with the same fields.

The catalogue files are read here with a parser independent of :mod:`assur.text` (Babel's
PO reader), and every code the source names is looked up in them.
"""

from __future__ import annotations

import ast
import re
import shutil
import string
from collections.abc import Mapping
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
    out: dict[str, tuple[tuple[str, ...], set[str]]] = {}
    for message in catalog:
        if not message.id:
            continue
        key = message.id[0] if isinstance(message.id, (tuple, list)) else message.id
        strings = (message.string if isinstance(message.string, (tuple, list))
                   else (message.string,))
        out[str(key)] = (tuple(str(s) for s in strings), set(message.flags))
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
    named: dict[str, str] = {}
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


#: Slips of Russian grammar met in the catalogue before: (pattern, what is right).
RUSSIAN_SLIPS = (
    (r"\bне корректн", "некорректный: written as one word"),
    (r"\bожидалось (?:список|словарь|строка|пара|точка)\b",
     "ожидался список / ожидался словарь / ожидалась строка …: the verb agrees with the noun"),
    (r"\w\((?:и|ы|а|ов|ей|ая|ые)\)",
     "a word with an optional ending in brackets: rephrase (\"пар: {k}\") instead"),
    (r"\{\w+\} кинематические пары\b", "the number decides the case"),
)


def _russian_problems(entries: Mapping[str, tuple[tuple[str, ...], set[str]]],
                      english: Mapping[str, tuple[tuple[str, ...], set[str]]]) -> list[str]:
    """Entries of a Russian catalogue left in English or with a known slip of grammar.

    An entry is English when its text equals the English one, when its words (fields,
    quoted literals and identifiers left out) hold a Latin word other than YAML's literals
    and acronyms, or when it has Latin letters and no Cyrillic ones; a text of fields and
    signs only (``"{group} — {kind}"``) is no sentence and passes.
    """
    problems = []
    for code, (strings, flags) in entries.items():
        if SAME in flags:
            continue
        if code in english and set(strings) & set(english[code][0]):
            problems.append(f"{code}: the same text as English")
        for s in strings:
            prose = _prose(s)
            latin = {w for w in re.findall(r"[A-Za-z]{3,}", prose) if not w.isupper()}
            cyrillic = re.search("[а-яё]", prose, re.IGNORECASE)
            if latin - LATIN_ALLOWED or (not cyrillic and re.search("[A-Za-z]", prose)):
                problems.append(f"{code}: English words in {s!r}")
            problems += [f"{code}: {why} in {s!r}" for pattern, why in RUSSIAN_SLIPS
                         if re.search(pattern, s, re.IGNORECASE)]
    return problems


def test_russian_sentences_are_russian() -> None:
    problems = _russian_problems(_entries("ru"), _entries("en"))
    assert not problems, "English or slips left in ru.po:\n" + "\n".join(problems)


def test_the_russian_check_finds_english_and_slips() -> None:
    english = {"a": (("expected a list",), set()), "b": (("{x} — {y}",), set()),
               "c": (("found {n} pairs",), set()), "d": (("value",), set()),
               "e": (("unit",), {SAME})}
    russian = {"a": (("ожидалось список",), set()), "b": (("{x} — {y}",), set()),
               "c": (("найдено {n} кинематические пары, не корректно",), set()),
               "d": (("value: число",), set()), "e": (("mm",), {SAME})}
    assert _russian_problems(russian, english) == [
        ("a: ожидался список / ожидался словарь / ожидалась строка …: the verb agrees with "
         "the noun in 'ожидалось список'"),
        "b: the same text as English",
        ("c: некорректный: written as one word in 'найдено {n} кинематические пары, "
         "не корректно'"),
        "c: the number decides the case in 'найдено {n} кинематические пары, не корректно'",
        "d: English words in 'value: число'"]


#: Places where a sentence is still written in the code rather than in the catalogue.
LEFT_IN_CODE = re.compile(r"""message_ru|\blang\s*[!=]=\s*["'](?:ru|en)["']|"""
                          r"""\bREASONS\[[^\]]*\]\s*\[|\breader\.add\(|"""
                          r"""\b(?:help|description|HELP)\s*=\s*\(?\s*f?["']""")


#: The end of a line whose Cyrillic literal is a set of letters (look-alikes, a pattern), not
#: words a user reads.
LETTERS_NOT_TEXT = "# letters, not text"


def _places_left(paths: list[Path]) -> list[str]:
    """``path:line`` of every sentence in a language outside the catalogue.

    A place is a Russian string literal other than a docstring, a ``message_ru`` field, a
    comparison of ``lang`` with a language, an (English, Russian) pair taken from
    ``REASONS``, a table problem recorded as English text (``reader.add``), or the help of a
    command or an option written as a literal (``help="…"``); a literal on a
    line marked :data:`LETTERS_NOT_TEXT` is letters, not a sentence.
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
        lines = source.splitlines()
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str)
                    and id(node) not in docstrings and re.search("[а-яё]", node.value, re.IGNORECASE)
                    and not lines[node.lineno - 1].endswith(LETTERS_NOT_TEXT)):
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
                      '    reader.add("x", "must be positive")  # английский\n'
                      'def h(parser):\n'
                      '    parser.add_argument("--k", help=render("cli.k", "en"))\n'
                      '    parser.add_argument("--x", help="the x option")\n'
                      'HELP = ("a command "\n'
                      '        "in two lines")\n', encoding="utf-8")
    assert _places_left([module]) == ["module.py:2", "module.py:5", "module.py:7",
                                      "module.py:10", "module.py:11"]


def test_no_sentence_is_left_in_the_code() -> None:
    paths = sorted((ROOT / "assur").rglob("*.py")) + sorted((ROOT / "synthesis").rglob("*.py"))
    assert _places_left(paths) == []


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
        data = {"n": 1, **dict.fromkeys(set().union(*(_fields(s) for s in strings)), 1)}
        assert text.render(code, "xx", **data) == f"«{text.render(code, 'en', **data)}»"
    error = TableError("t.yaml", [Issue("'x'", Message("value.kind.list"))] * 2)
    assert error.text("xx").splitlines() == ["«2 problems in t.yaml:»", *["  - 'x': «a list»"] * 2]


def test_no_sentence_is_left_in_the_built_in_cases() -> None:
    assert _places_left(sorted((ROOT / "synthesis" / "cases").rglob("*.py"))) == []
