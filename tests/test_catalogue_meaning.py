"""The Russian catalogue keeps the meaning of the English one for negations and opposites.

A sentence turned to its opposite (a negation dropped, "parallel" for "perpendicular",
"inside" for "outside", "lower" for "upper", "min" for "max") keeps its fields and reads
as good Russian, so no other test of the catalogue notices it. Here every entry of
``en.po`` is compared with the same entry of ``ru.po``: for each pair of opposite concepts,
the English names one exactly when the Russian does. The few entries where the two
languages legitimately say it differently are listed in :data:`ALLOWED`, each with the
reason.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from babel.messages.pofile import read_po

LOCALE = Path(__file__).resolve().parents[1] / "assur" / "locale"

#: Start and end of a Russian word (``\\b`` of the ``re`` module also sees Cyrillic, but
#: the explicit classes say what is meant).
_RU = "(?<![а-яё])"
_RU_END = "(?![а-яё])"

#: Each concept: an English pattern and a Russian pattern (case-insensitive); an entry
#: that matches one must match the other. Opposites stand next to each other, so turning
#: one into the other breaks the pair on both sides.
CONCEPTS: dict[str, tuple[str, str]] = {
    "not": ((r"\b(?:not|no|(?-i:none)|never|nor|neither|cannot|without|nowhere|missing|absent"
             r"|leave out|left out|indeterminate|incomplete|unreadable|undefined)\b|n't\b"),
            (rf"{_RU}(?:не(?! (?:больше|меньше|более|менее){_RU_END})|нет|ни|нельзя|без|ничего"
             rf"|некуда|нигде|отсутств\w*){_RU_END}")),
    "parallel": (r"\bparallel", "параллел"),
    "perpendicular": (r"\bperpendicular", "перпендикуляр"),
    "inside": (r"\binside\b|\binner\b|\binternal", "внутр"),
    "outside": (r"\boutside\b|\bouter\b|\bexternal", rf"{_RU}вне{_RU_END}|снаружи|внешн|за предел"),
    "at least": (r"\bat least\b|\bor more\b", rf"{_RU}(?:не (?:меньше|менее)|хотя бы){_RU_END}"),
    "at most": (r"\bat most\b|\bor less\b", rf"{_RU}не (?:больше|более){_RU_END}"),
    "lower": (r"\blower\b|\bbelow\b|\bsmaller\b|\bfewer\b|\bshorter\b|\bless than\b",
              rf"нижн|низш|{_RU}(?<!не )(?:меньш|ниже|короче)|'lower'"),
    "upper": (r"\bupper\b|\babove\b|\bgreater\b|\blarger\b|\bhigher\b|\bexceed|\bmore than\b",
              rf"верхн|высш|{_RU}(?<!не )(?:больш|выше|более|превыш)|'upper'"),
    "min": (r"\bmin\b|\bminim|\bsmallest\b|(?<!at )\bleast\b|\blowest\b|\bshortest\b",
            rf"{_RU}(?:мин|наим){_RU_END}|миним|наименьш|кратчайш|{_RU}сам\w+ коротк|\bmin\b"),
    "max": (r"\bmax\b|\bmaxim|\blargest\b|(?<!at )\bmost\b|\bgreatest\b|\bhighest\b|\bpeaks?\b|\bworst\b",
            rf"{_RU}(?:макс|наиб){_RU_END}|максим|наибольш|наихудш|{_RU}пик|\bmax\b"),
    "left": (r"\bleft\b(?! out)", rf"{_RU}лев"),
    "right": (r"\bright\b", rf"{_RU}прав(?:ая|ой|ую|ое|ый|ом|ее|ей|о){_RU_END}"),
    "before": (r"\bbefore\b|\bearlier\b", rf"{_RU}(?:перед|прежде|раньше){_RU_END}|предыдущ"),
    "after": (r"\bafter\b", rf"{_RU}после{_RU_END}"),
    "clockwise": (r"(?<!counter)(?<!counter-)(?<!anti)clockwise", rf"{_RU}по часовой"),
    "counter-clockwise": (r"counter-?clockwise|anticlockwise", "против часовой"),
}

#: Entries whose Russian legitimately says a concept differently, with the reason.
_ZERO_OR_POSITIVE = "'zero or positive' is said 'not negative' in Russian"
_NOT_VALID = "'not valid' is one word in Russian ('некорректный')"
_BOUND = ("the bounds of a search interval are its left and right ends in Russian "
          "('левая/правая граница'), as on the number line")
_UP_TO = ("'before' is 'до' here, a word that mostly means 'up to' and so is no term of "
          "its own")
_MORE = "'more than' is said by a comparative ('глубже', 'длиннее', 'больше')"
ALLOWED: dict[tuple[str, str], str] = {
    ("analyze.alpha_within", "not"): "'within' the allowable angle is 'не превышен'",
    ("case.fourbar.grashof.non_grashof", "not"): "'non-Grashof' is 'не удовлетворяет Грасгофу'",
    ("cli.case.tracker.budget", "not"): "'0 skips the synthesis' is '0 — без синтеза'",
    ("cli.error.required", "not"): "'are required' is 'не заданы обязательные'",
    ("diag.e_rigid_truss", "not"): "'cannot move' is one word, 'неподвижны'",
    ("diag.e_underconstrained", "not"): "'add N inputs' is 'не хватает входных звеньев'",
    ("plot.fails_whole_cycle", "not"): "'(fails) anywhere' is 'ни в одном положении'",
    ("rule.non_negative", "not"): _ZERO_OR_POSITIVE,
    ("table.not_yaml", "not"): _NOT_VALID,
    ("table.yaml_unclosed", "before"): "'expected before line N' is 'до строки N ожидается' "
                                         "('до': 'up to')",
    ("cli.output.stdout_twice", "not"): "'or leave out --json' is 'или уберите --json'",
    ("sketch.warn_radian_all", "at most"): "'within 2π' is 'не больше 2π'",
    ("diag.e_underconstrained", "left"): "'left after' (remaining) is 'остаётся'",
    ("term.differs", "not"): "'differs' is 'не совпадает'",
    ("cli.output.lost", "upper"): "'nor anywhere else' is 'и больше некуда' ('больше': 'any more')",
    ("higher.not_closed", "upper"): _MORE,
    ("table.too_deep", "upper"): _MORE,
    ("structure.condition.degree", "upper"): "'form more' (pairs) is 'входят в большее число пар'",
    ("synth.report.lower", "lower"): _BOUND,
    ("synth.report.lower", "left"): _BOUND,
    ("synth.report.side_lower", "lower"): _BOUND,
    ("synth.report.side_lower", "left"): _BOUND,
    ("synth.report.upper", "upper"): _BOUND,
    ("synth.report.upper", "right"): _BOUND,
    ("synth.report.side_upper", "upper"): _BOUND,
    ("synth.report.side_upper", "right"): _BOUND,
    ("case.impact.energy", "before"): _UP_TO,
    ("cli.case.fourbar.psi1", "before"): _UP_TO,
    ("cli.case.impact.omega2", "before"): _UP_TO,
    ("cli.case.impact.omega4", "before"): _UP_TO,
    ("cli.synthesize.time_limit", "after"): "'after N seconds' is 'через N секунд'",
}


def _texts(lang: str) -> dict[str, str]:
    """Every entry of one catalogue: code -> its text(s), fields removed."""
    with (LOCALE / f"{lang}.po").open("rb") as stream:
        catalog = read_po(stream)
    out = {}
    for message in catalog:
        if not message.id:
            continue
        code = message.id[0] if isinstance(message.id, (tuple, list)) else message.id
        strings = (message.string if isinstance(message.string, (tuple, list))
                   else (message.string,))
        out[str(code)] = re.sub(r"\{[^{}]*\}", " ", " ".join(str(s) for s in strings))
    return out


def _mismatches(english: dict[str, str], russian: dict[str, str]) -> list[str]:
    """The entries where one language names a concept and the other does not."""
    found = []
    for concept, (en_pattern, ru_pattern) in CONCEPTS.items():
        en_re, ru_re = re.compile(en_pattern, re.IGNORECASE), re.compile(ru_pattern, re.IGNORECASE)
        for code, text in english.items():
            in_en, in_ru = bool(en_re.search(text)), bool(ru_re.search(russian.get(code, "")))
            if in_en != in_ru and (code, concept) not in ALLOWED:
                side = "English only" if in_en else "Russian only"
                found.append(f"{code} [{concept}, {side}]: {text!r} / {russian[code]!r}")
    return found


#: Opposite concepts: where an entry names both, it names them in the same order in both
#: languages (so "the lower bound must not exceed the upper" cannot become its converse).
OPPOSITES = (("lower", "upper"), ("min", "max"), ("inside", "outside"), ("before", "after"),
             ("left", "right"), ("parallel", "perpendicular"),
             ("clockwise", "counter-clockwise"), ("at least", "at most"))


def _first(pattern: str, text: str) -> int | None:
    found = re.search(pattern, text, re.IGNORECASE)
    return found.start() if found else None


def _order_mismatches(english: dict[str, str], russian: dict[str, str]) -> list[str]:
    """The entries that name two opposites in one order in English, the other in Russian."""
    found = []
    for one, other in OPPOSITES:
        for code, text in english.items():
            places = [(_first(CONCEPTS[c][0], text), _first(CONCEPTS[c][1], russian[code]))
                      for c in (one, other)]
            if all(en is not None and ru is not None for en, ru in places):
                (en_one, ru_one), (en_other, ru_other) = places
                if (en_one < en_other) != (ru_one < ru_other):  # type: ignore[operator]
                    found.append(f"{code} [{one} / {other}]: {text!r} / {russian[code]!r}")
    return found


def test_russian_keeps_negations_and_opposites() -> None:
    english, russian = _texts("en"), _texts("ru")
    mismatches = _mismatches(english, russian) + _order_mismatches(english, russian)
    assert not mismatches, "\n".join(mismatches)


def test_allowed_entries_are_still_needed() -> None:
    """An allowance that no longer excuses a difference is removed, not kept."""
    english, russian = _texts("en"), _texts("ru")
    stale = []
    for code, concept in ALLOWED:
        en_pattern, ru_pattern = CONCEPTS[concept]
        same = (bool(re.search(en_pattern, english[code], re.IGNORECASE))
                == bool(re.search(ru_pattern, russian[code], re.IGNORECASE)))
        if same:
            stale.append((code, concept))
    assert not stale, stale


@pytest.mark.parametrize(("code", "correct", "turned"), [
    ("force.reason.parallel_guides", "реакции не определены", "реакции определены"),
    ("reason.guides_parallel", "параллельны", "перпендикулярны"),
    ("case.fourbar.failure.zone_band", "внутри участка", "вне участка"),
    ("case.fourbar.failure.zone_band", "ниже", "выше"),
    ("case.tracker.sim_line", "мин. угол", "макс. угол"),
    ("case.fourbar.never_back", "после", "перед"),
    ("analyze.cw", "по часовой", "против часовой"),
    ("problem.bounds_order", "нижняя граница не должна превышать верхнюю",
     "верхняя граница не должна превышать нижнюю"),
    ("rule.at_least", "не меньше", "не больше"),
    ("higher.not_closed", "не вернулся", "вернулся"),
])
def test_a_sentence_turned_to_its_opposite_is_caught(code: str, correct: str,
                                                     turned: str) -> None:
    """One entry of the real catalogue turned to its opposite is reported, by its code."""
    english, russian = _texts("en"), _texts("ru")
    assert correct in russian[code]
    russian[code] = russian[code].replace(correct, turned, 1)
    reported = _mismatches(english, russian) + _order_mismatches(english, russian)
    assert [line for line in reported if line.startswith(f"{code} [")]
