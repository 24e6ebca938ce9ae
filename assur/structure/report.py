"""Text report of a structural analysis, in English or Russian, in the course's own terms.

>>> from assur.io.chain_table import chain_from_dict
>>> from assur.structure.analysis import analyse_structure
>>> chain = chain_from_dict({"mechanism": {"pairs": [
...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
...     {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
...     "inputs": [1]}}, source="four_bar.yaml")
>>> print(structure_report(analyse_structure(chain), lang="ru").splitlines()[-1])
Метод ДГТУ применим: да
"""

from __future__ import annotations

from collections.abc import Sequence

from assur.structure.classification import AssurGroup, roman
from assur.structure.identification import COLUMNS, IdentificationRow, Mismatch
from assur.structure.analysis import StructuralAnalysis

__all__ = ["group_description", "structure_report"]

_RU_ORDER_WORD = {2: "двухповодковая", 3: "трёхповодковая"}

_T = {
    "title": ("Structural analysis of {name} ({source})",
              "Структурный анализ механизма {name} ({source})"),
    "counts": ("moving links n = {n}, lower pairs p5 = {p5}, higher pairs p4 = {p4}",
               "число подвижных звеньев n = {n}, низших пар (5 класса) p5 = {p5}, "
               "высших пар (4 класса) p4 = {p4}"),
    "mobility": ("mobility W = 3n − 2p5 − p4 = 3·{n} − 2·{p5} − {p4} = {W}",
                 "степень подвижности W = 3n − 2p5 − p4 = 3·{n} − 2·{p5} − {p4} = {W}"),
    "star": ("corrected for loops of prismatic pairs: W* = {W_star}",
             "с учётом контуров из поступательных пар: W* = {W_star}"),
    "inputs": ("inputs ({m}): {items}", "входные звенья ({m}): {items}"),
    "groups": ("Groups in layering order:", "Группы в порядке наслоения:"),
    "none": ("  (none)", "  (нет)"),
    "formula": ("Structure formula: {formula}", "Формула строения: {formula}"),
    "class": ("Mechanism class: {cls}", "Класс механизма: {cls}"),
    "leftover": ("Links in no group: {links}", "Звенья, не вошедшие в группы: {links}"),
    "issues": ("Findings:", "Замечания:"),
    "rank": ("Rank test at the given pose: rank J = {rank} of {rows} rows, W_geom = {W_geom}, "
             "redundant constraints q_geom = {q_geom}",
             "Проверка ранга в заданном положении: ранг J = {rank} при {rows} строках, "
             "W_geom = {W_geom}, избыточных связей q_geom = {q_geom}"),
    "table": ("Structure-identification table (method table 1.4; – is a dash):",
              "Таблица идентификации структуры (табл. 1.4; – прочерк):"),
    "check_ok": ("The given identification table agrees with the analysis ({k} rows).",
                 "Заданная таблица идентификации совпадает с результатом анализа ({k} строк)."),
    "check_bad": ("The given identification table differs from the analysis ({k} mismatch(es)):",
                  "Заданная таблица идентификации расходится с анализом (расхождений: {k}):"),
    "yes": ("DGTU method applicable: yes", "Метод ДГТУ применим: да"),
    "no": ("DGTU method applicable: no", "Метод ДГТУ применим: нет"),
}


def _t(key: str, lang: str, **values: object) -> str:
    english, russian = _T[key]
    return (russian if lang == "ru" else english).format(**values)


def _pairs(group: AssurGroup, lang: str) -> tuple[str, str]:
    word = "к звену" if lang == "ru" else "to link"
    ext = ", ".join(f"{p} ({g} {word} {k})" for p, g, k in group.external)
    return ext, ", ".join(map(str, group.internal))


def _pair_text(group: AssurGroup, lang: str) -> str:
    kind = group.group_kind
    return kind.pair_text(lang) if kind is not None else group.name


def group_description(group: AssurGroup, lang: str = "en") -> str:
    """One line describing a group in the course's terms."""
    ru = lang == "ru"
    if group.group_class == 1:
        return (f"начальный механизм (механизм I класса): стойка {group.i_minus_1} и входное "
                f"звено {group.i}, ведущая пара {group.pair_i}" if ru else
                f"input group (class I mechanism): frame {group.i_minus_1} and input link "
                f"{group.i}, driven pair {group.pair_i}")
    ext, internal = _pairs(group, lang)
    if group.name == "PPP":
        head = (f"уровень {group.level}: не группа Ассура (ППП: контур из поступательных пар)"
                if ru else f"level {group.level}: not an Assur group (PPP: a loop of prismatic "
                           f"pairs)")
    elif group.is_dyad:
        head = (f"уровень {group.level}: группа Ассура {group.group_class} класса "
                f"{group.order} порядка {group.kind} вида ({_pair_text(group, lang)}); "
                f"i = {group.i}, j = {group.j}" if ru else
                f"level {group.level}: Assur group of class {group.group_class}, order "
                f"{group.order}, kind {group.kind} ({group.name}); i = {group.i}, j = {group.j}")
    else:
        word = _RU_ORDER_WORD.get(group.order, "") if group.group_class == 3 else ""
        head = (f"уровень {group.level}: группа Ассура {group.group_class} класса "
                f"{group.order} порядка{' (' + word + ')' if word else ''}, {group.name}" if ru
                else f"level {group.level}: Assur group of class {group.group_class}, order "
                     f"{group.order}, {group.name}")
    one = len(group.internal) == 1
    tail = (f"; внешние пары {ext}; внутренн{'яя пара' if one else 'ие пары'} {internal or '—'}"
            if ru else f"; external pairs {ext}; internal pair{'' if one else 's'} "
                       f"{internal or '—'}")
    if group.composite:
        members = ", ".join(map(str, group.composite))
        tail += (f"; звенья {members} с ведущей парой привода считаются одним звеном" if ru else
                 f"; links {members} with the driven actuator pair count as one link")
    return head + tail


def _cell(value: object) -> str:
    if value is None:
        return "–"
    if isinstance(value, list):
        return ";".join(map(str, value))
    return str(value)


def _table(rows: Sequence[IdentificationRow]) -> list[str]:
    header = ["L", "seq", "i-1", "j-1", "i", "j", "i+1", "j+1", "variant", "out_code"]
    cells = [[_cell(getattr(row, key)) for key in COLUMNS] for row in rows]
    widths = [max(len(h), *(len(c[k]) for c in cells)) for k, h in enumerate(header)]
    lines = ["  " + "  ".join(h.rjust(w) for h, w in zip(header, widths, strict=True))]
    lines += ["  " + "  ".join(c.rjust(w) for c, w in zip(line, widths, strict=True))
              for line in cells]
    return lines


def structure_report(analysis: StructuralAnalysis, *, lang: str = "en",
                     table: Sequence[IdentificationRow] | None = None,
                     mismatches: Sequence[Mismatch] | None = None,
                     checked_rows: int = 0) -> str:
    """The text report of ``assur check``.

    Parameters
    ----------
    analysis : StructuralAnalysis
    lang : {'en', 'ru'}
    table : sequence of IdentificationRow, optional
        The identification table built from the analysis, printed when given.
    mismatches : sequence of Mismatch, optional
        The result of checking a user's table (None when no table was given).
    checked_rows : int
        Number of rows of the user's table.

    Returns
    -------
    str
        The report, lines joined by newlines.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> print(assur.structure_report(analysis).splitlines()[2].strip())
    mobility W = 3n − 2p5 − p4 = 3·3 − 2·4 − 0 = 1
    """
    a = analysis
    chain = a.chain
    items = []
    for drive in chain.inputs:
        if drive.link is not None:
            name = chain.link(drive.link).name
            items.append(str(drive.link) + (f" ({name})" if name else ""))
        elif drive.pair is not None:
            pair = chain.pair(drive.pair)
            items.append(f"{'пара' if lang == 'ru' else 'pair'} {pair.id} "
                         f"({pair.links[0]}–{pair.links[1]})")
    lines = [_t("title", lang, name=chain.name, source=chain.source),
             "  " + _t("counts", lang, n=a.n, p5=a.p5, p4=a.p4),
             "  " + _t("mobility", lang, n=a.n, p5=a.p5, p4=a.p4, W=a.W)]
    if a.W_star != a.W:
        lines.append("  " + _t("star", lang, W_star=a.W_star))
    lines.append("  " + _t("inputs", lang, m=a.m, items=", ".join(items) or "—"))
    lines += ["", _t("groups", lang)]
    groups = (*a.input_groups, *a.groups)
    width = max((len(g.label) for g in groups), default=0)
    lines += [f"  {g.label.ljust(width)}  {group_description(g, lang)}" for g in groups] or \
        [_t("none", lang)]
    lines += ["", _t("formula", lang, formula=a.formula or "—"),
              _t("class", lang, cls=roman(a.mechanism_class))]
    if a.leftover:
        lines.append(_t("leftover", lang, links=", ".join(map(str, a.leftover))))
    if a.rank is not None:
        lines.append(_t("rank", lang, **a.rank.to_dict()))
    if a.issues:
        lines += ["", _t("issues", lang)]
        lines += [f"  {d.code}: {d.text(lang)}" for d in a.issues]
    if table is not None:
        lines += ["", _t("table", lang), *_table(table)]
    if mismatches is not None:
        lines.append("")
        if mismatches:
            lines.append(_t("check_bad", lang, k=len(mismatches)))
            lines += [f"  - {m.message_ru if lang == 'ru' else m.message}" for m in mismatches]
        else:
            lines.append(_t("check_ok", lang, k=checked_rows))
    lines.append("")
    lines.append(_t("yes" if a.applicable else "no", lang))
    lines += [f"  - {text}" for text in (a.applicability_ru if lang == "ru" else a.applicability)]
    return "\n".join(lines)
