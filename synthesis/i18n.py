"""Terms of the course in English and Russian, for the reports of the coursework workflow.

The Russian words are those of the DGTU course (группа Ассура, класс, порядок, вид,
формула строения, угол давления, …). Other modules that print their own reports keep their
own sentences; this table holds the shared vocabulary of the coursework report and the
batch check.

Examples
--------
>>> term("formula", "ru")
'формула строения'
>>> term("formula", "en")
'structure formula'
"""

from __future__ import annotations

__all__ = ["LANGUAGES", "TERMS", "check_lang", "heading", "in_language", "term"]

LANGUAGES = ("en", "ru")

TERMS: dict[str, tuple[str, str]] = {
    # the structure
    "mechanism": ("mechanism", "механизм"),
    "link": ("link", "звено"),
    "name": ("name", "название"),
    "links": ("links", "звенья"),
    "frame": ("frame", "стойка"),
    "pair": ("pair", "кинематическая пара"),
    "pairs": ("kinematic pairs", "кинематические пары"),
    "pair_count": ("pairs", "пар"),
    "pair_type": ("type", "вид пары"),
    "revolute": ("revolute (R)", "вращательная (В)"),
    "prismatic": ("prismatic (P)", "поступательная (П)"),
    "guide": ("guide on link", "направляющая на звене"),
    "inputs": ("input links", "входные звенья"),
    "n_moving": ("moving links n", "подвижных звеньев n"),
    "p5": ("lower pairs p5", "низших пар p5"),
    "p4": ("higher pairs p4", "высших пар p4"),
    "mobility": ("mobility (Chebyshev)", "степень подвижности (формула Чебышева)"),
    "group": ("group", "группа"),
    "assur_group": ("Assur group", "группа Ассура"),
    "input_group": ("input group", "начальный механизм"),
    "groups": ("Assur groups", "группы Ассура"),
    "class": ("class", "класс"),
    "order": ("order", "порядок"),
    "kind": ("kind", "вид"),
    "level": ("level", "уровень"),
    "external_pairs": ("external pairs", "внешние пары"),
    "internal_pairs": ("internal pairs", "внутренние пары"),
    "formula": ("structure formula", "формула строения"),
    "mechanism_class": ("class of the mechanism", "класс механизма"),
    "applicable": ("the course method applies", "метод курса применим"),
    "not_applicable": ("the course method does not apply", "метод курса не применим"),
    "diagnostics": ("findings", "замечания"),
    "identification": ("structure-identification table", "таблица идентификации структуры"),
    "student_table": ("the table given in the file", "таблица из файла"),
    "schemes": ("structural schemes", "структурные схемы"),
    "structural_scheme": ("structural scheme", "структурная схема"),
    "formalised_scheme": ("formalised structural scheme", "формализованная структурная схема"),
    # kinematics
    "existence": ("existence of the groups over the cycle",
                  "существование групп за цикл"),
    "crank_angle": ("crank angle", "угол поворота кривошипа"),
    "margin": ("existence margin", "запас существования"),
    "condition": ("existence condition", "условие существования"),
    "pressure_angle": ("pressure angle", "угол давления"),
    "kinematics": ("kinematic diagrams", "кинематические диаграммы"),
    "whole_cycle": ("assembles over the whole cycle", "собирается на всём цикле"),
    "fails": ("does not assemble", "не собирается"),
    "no_geometry": ("the table gives no dimensions, so there is no kinematic check",
                    "в таблице нет размеров, кинематическая проверка не выполнялась"),
    # synthesis
    "synthesis": ("synthesis", "синтез"),
    "objective": ("objective", "целевая функция"),
    "feasible": ("feasible", "допустимо"),
    "infeasible": ("infeasible", "недопустимо"),
    # verdicts and the batch
    "file": ("file", "файл"),
    "files": ("files", "файлов"),
    "verdict": ("verdict", "итог"),
    "ok": ("ok", "верно"),
    "problems": ("problems", "есть ошибки"),
    "error": ("unreadable", "файл не читается"),
    "first_problem": ("first problem", "первая ошибка"),
    "matches": ("matches the chain", "совпадает со схемой"),
    "differs": ("differs from the chain", "не совпадает со схемой"),
    "none_given": ("not given", "не задана"),
    "report": ("coursework report", "отчёт по курсовой работе"),
    "data": ("the data", "исходные данные"),
    "counts": ("counts and mobility", "подсчёт звеньев и пар, подвижность"),
    "not_available": ("not available", "нет данных"),
    "yes": ("yes", "да"),
    "no": ("no", "нет"),
}


def check_lang(lang: str) -> str:
    """Return ``lang`` if it is a supported language.

    Raises
    ------
    ValueError
        If ``lang`` is not ``"en"`` or ``"ru"``.
    """
    if lang not in LANGUAGES:
        raise ValueError(f"language must be one of {', '.join(LANGUAGES)}; got {lang!r}")
    return lang


def in_language(pair: tuple[str, str], lang: str) -> str:
    """The text of an ``(English, Russian)`` pair in ``lang``.

    Every bilingual table of the package (:data:`TERMS`, the sentences of the reports, the
    reasons for which a group does not assemble) holds such pairs.

    Raises
    ------
    ValueError
        If ``lang`` is not ``"en"`` or ``"ru"``.

    >>> in_language(("crank", "кривошип"), "ru")
    'кривошип'
    """
    english, russian = pair
    return russian if check_lang(lang) == "ru" else english


def term(key: str, lang: str = "en") -> str:
    """The course's word for ``key`` in ``lang`` (``"en"`` or ``"ru"``).

    Raises
    ------
    KeyError
        If the term is not in :data:`TERMS`.
    """
    return in_language(TERMS[key], lang)


def heading(key: str, lang: str = "en") -> str:
    """The term with its first letter capitalised (the rest kept: «Группы Ассура»).

    >>> heading("groups", "ru")
    'Группы Ассура'
    """
    text = term(key, lang)
    return text[:1].upper() + text[1:]
