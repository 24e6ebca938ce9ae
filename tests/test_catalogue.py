"""The text catalogue: every code in every language, translated, with the same fields.

The catalogue files are read here with a parser independent of :mod:`assur.text` (Babel's
PO reader), and every code the source names is looked up in them.
"""

from __future__ import annotations

import re
import string
from pathlib import Path

import pytest
from babel.messages.pofile import read_po

from assur import text

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
