"""Reports of the tracker case: text in English or Russian, and a dictionary for ``--json``.

The text gives, in this order: the task; Tabel 1 of the patent reproduced, printed value
beside computed value and their difference; the figure tables (figs. 4–16) the same way; the
design procedure Etapa I–VI for the task with the chosen design in millimetres; the
simulation that confirms it; the patent's inconsistencies; engineering notes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from synthesis.cases.tracker.design import (
    PATENT_TASK,
    Design,
    DesignTable,
    Violation,
    design_table,
)
from synthesis.cases.tracker.patent import CHOSEN, EXAMPLE, K2, SERIES
from synthesis.cases.tracker.reproduction import ANGLES, Comparison
from synthesis.cases.tracker.study import Study, Verification, worst
from synthesis.cases.tracker.synthesis_problem import SynthesisAnswer

__all__ = ["Lang", "inconsistencies", "notes", "summary", "to_dict", "violation_text"]

Lang = str  # a language of the catalogue (assur.text.languages())

_T: dict[str, tuple[str, str]] = {
    "title": ("Rhomboid orientation mechanism of a solar tracker driven by a linear actuator "
              "(patent application RO a 2010 00677)",
              "Ромбоидный механизм ориентации солнечного трекера с линейным приводом "
              "(заявка на патент RO a 2010 00677)"),
    "task": ("Design task", "Задание на проектирование"),
    "task_line": ("stroke a = {a:g}°, b_min.ad = {b:g}°, l1 = {l1:g} mm, actuator stroke "
                  "≤ {ls:g} mm, post clearance l_g ≥ {lg:g} mm; k2 = {k2}; k5 = {k5}",
                  "ход a = {a:g}°, b_min.ad = {b:g}°, l1 = {l1:g} мм, ход привода ≤ {ls:g} мм, "
                  "зазор до стойки l_g ≥ {lg:g} мм; k2 = {k2}; k5 = {k5}"),
    "tabel1": ("Tabel 1 of the patent reproduced (a = 210°, k5 = 2, l1 = 300 mm): "
               "printed / computed (computed − printed)",
               "Таблица 1 патента (a = 210°, k5 = 2, l1 = 300 мм): "
               "в патенте / расчёт (расчёт − патент)"),
    "figures": ("Tables under figs. 4–16 (a = 210°): printed / computed (difference)",
                "Таблицы под рис. 4–16 (a = 210°): в патенте / расчёт (разность)"),
    "quantity": ("quantity", "величина"),
    "source": ("source", "источник"),
    "nd": ("not derivable", "не выводится"),
    "worst": ("Largest differences where agreement is expected (tolerance): {items}",
              "Наибольшие разности там, где ожидается совпадение (допуск): {items}"),
    "kg_differs": ("k_g for k2 < 2.2 does not follow from the geometry: differences up to "
                   "{dk:.3f} (reported, not tuned)",
                   "k_g при k2 < 2.2 не следует из геометрии: разности до {dk:.3f} "
                   "(показаны как есть, без подгонки)"),
    "procedure": ("Design procedure (Etapa I–VI) for the task",
                  "Процедура проектирования (этапы I–VI) для задания"),
    "etapa1": ("Etapa I: b_min(a, k2) ≥ {b:g}° holds for k2 ≥ {k2min}",
               "Этап I: b_min(a, k2) ≥ {b:g}° выполняется при k2 ≥ {k2min}"),
    "etapa1_none": ("Etapa I: no tabulated k2 gives b_min ≥ {b:g}°",
                    "Этап I: ни одно значение k2 из таблицы не даёт b_min ≥ {b:g}°"),
    "etapa2_5": ("Etapa II–V: angles c, d; ratios k_d, k_i, k_s, k_g (Etapa IV: e and f are "
                 "not derivable from the text)",
                 "Этапы II–V: углы c, d; отношения k_d, k_i, k_s, k_g (этап IV: e и f по "
                 "тексту не выводятся)"),
    "verdict_ok": ("admissible", "допустим"),
    "etapa6": ("Etapa VI (rule: every requirement met, then the shortest extended actuator "
               "l_d, then the larger b_min)",
               "Этап VI (правило: все требования выполнены, затем наименьшая длина "
               "выдвинутого привода l_d, затем больший b_min)"),
    "chosen": ("Chosen design (table rows)", "Выбранный вариант (строки таблицы)"),
    "refined": ("Design on a continuous k2 (Etapa VI allows interpolation)",
                "Вариант при непрерывном k2 (этап VI допускает интерполяцию)"),
    "none": ("no design satisfies every requirement", "ни один вариант не выполняет всех "
                                                       "требований"),
    "patent_pick": ("The patent chose k2 = {k2:g}, k5 = {k5:g}: {same}",
                    "В патенте выбрано k2 = {k2:g}, k5 = {k5:g}: {same}"),
    "same": ("the same design", "тот же вариант"),
    "other": ("a different design", "другой вариант"),
    "sim": ("Simulation of the returned dimensions: the chain table solved group by group, "
            "{formula}, at {n} actuator lengths from l_i to l_d",
            "Моделирование полученных размеров: таблица цепи решена по группам, {formula}, "
            "положений привода от l_i до l_d: {n}"),
    "sim_line": ("stroke {s:.4f}° (closed form {a:.4f}°), min transmission at B {b:.4f}° "
                 "(closed form {bc:.4f}°), l_g at extension {g:.2f} mm (closed form "
                 "{gc:.2f} mm), least post distance over the stroke {gm:.2f} mm, assembles "
                 "everywhere: {ok}",
                 "ход {s:.4f}° (формула {a:.4f}°), мин. угол передачи в B {b:.4f}° "
                 "(формула {bc:.4f}°), l_g при выдвинутом приводе {g:.2f} мм (формула "
                 "{gc:.2f} мм), наименьшее расстояние до стойки за ход {gm:.2f} мм, "
                 "собирается везде: {ok}"),
    "sim_line2": ("min transmission at C (actuator to long rocker) {c:.2f}°; actuator lever "
                  "arm ds/dφ: least {r0:.1f} mm, {r1:.1f} mm retracted, {r2:.1f} mm extended",
                  "мин. угол передачи в C (привод — длинное коромысло) {c:.2f}°; плечо "
                  "привода ds/dφ: наименьшее {r0:.1f} мм, {r1:.1f} мм во втянутом, "
                  "{r2:.1f} мм в выдвинутом положении"),
    "transmission": ("b_min = {v:.2f}° is below the allowed {l:g}°",
                     "b_min = {v:.2f}° меньше допустимого {l:g}°"),
    "clearance": ("l_g = {v:.1f} mm is below the required {l:g} mm",
                  "l_g = {v:.1f} мм меньше требуемых {l:g} мм"),
    "stroke": ("l_s = {v:.1f} mm exceeds the actuator's stroke of {l:g} mm",
               "l_s = {v:.1f} мм больше хода привода {l:g} мм"),
    "synth": ("The same task as a B1–B5 synthesis problem",
              "Та же задача как задача синтеза B1–B5"),
    "synth_setup": ("varied: k2 in [{k2lo:g}, {k2hi:g}], k5 in [{k5lo:g}, {k5hi:g}], platform "
                    "start angle θ0 in [{tlo:g}°, {thi:g}°] (the platform is the input link: "
                    "{formula}); P1: assembly over the whole stroke; P2: b ≥ {b:g}°, "
                    "l_g ≥ {lg:g} mm, l_s ≤ {ls:g} mm; Q: the size l_d/l1",
                    "варьируются: k2 в [{k2lo:g}, {k2hi:g}], k5 в [{k5lo:g}, {k5hi:g}], "
                    "начальный угол платформы θ0 в [{tlo:g}°, {thi:g}°] (платформа — входное "
                    "звено: {formula}); P1: сборка на всём ходе; P2: b ≥ {b:g}°, "
                    "l_g ≥ {lg:g} мм, l_s ≤ {ls:g} мм; Q: размер l_d/l1"),
    "synth_run": ("search: {n} trials in {t:.2f} s (seed {seed}), stop: {stop}; "
                  "every condition met: {ok}",
                  "поиск: {n} испытаний за {t:.2f} с (seed {seed}), останов: {stop}; "
                  "все условия выполнены: {ok}"),
    "synth_found": ("found k2 = {k2:.4f}, k5 = {k5:.4f}, θ0 = {t0:.2f}°; transmission angle "
                    "at B {b1:.2f}° retracted, {b2:.2f}° extended",
                    "найдено k2 = {k2:.4f}, k5 = {k5:.4f}, θ0 = {t0:.2f}°; угол передачи в B "
                    "{b1:.2f}° во втянутом, {b2:.2f}° в выдвинутом положении"),
    "synth_check": ("actuator-driven chain simulated from l_i to l_d: stroke {s:.4f}°, "
                    "assembles everywhere: {ok}",
                    "моделирование цепи с приводом от l_i до l_d: ход {s:.4f}°, собирается "
                    "везде: {ok}"),
    "compare": ("Both answers side by side", "Оба ответа рядом"),
    "col_table": ("Etapa VI, rows", "этап VI, строки"),
    "col_refined": ("Etapa VI, continuous k2", "этап VI, непрерывный k2"),
    "col_synth": ("B1–B5 synthesis", "синтез B1–B5"),
    "b_ends": ("b at the ends, °", "b на концах, °"),
    "c_min": ("least angle at C, °", "наим. угол в C, °"),
    "synth_note": ("The patent's closed forms put b_min at both ends of the stroke (that is "
                   "what a = 2[180° − (c + d)] assumes); the search may place the stroke "
                   "anywhere and here shortens the extended actuator by {gain:.1f}% "
                   "({l0:.0f} → {l1:.0f} mm) with b_min.ad reached at one end only.",
                   "Формулы патента дают b_min на обоих концах хода (это и предполагает "
                   "a = 2[180° − (c + d)]); поиск может расположить ход где угодно и здесь "
                   "укорачивает выдвинутый привод на {gain:.1f}% ({l0:.0f} → {l1:.0f} мм), "
                   "достигая b_min.ad только на одном конце."),
    "synth_same": ("The search and the procedure agree within {gap:.1f}% on l_d.",
                   "Поиск и процедура согласуются по l_d с точностью {gap:.1f}%."),
    "yes": ("yes", "да"),
    "no": ("no", "нет"),
    "incons": ("Inconsistencies of the patent", "Несоответствия в патенте"),
    "notes": ("Engineering notes", "Инженерные замечания"),
    "lengths": ("lengths, mm", "размеры, мм"),
}


def _t(key: str, lang: Lang) -> str:
    return _T[key][0 if lang == "en" else 1]


def _fmt(value: float, quantity: str) -> str:
    if quantity in ANGLES or quantity in ("e", "f"):
        return f"{value:.2f}"
    if quantity.startswith("l"):
        return f"{value:.1f}"
    return f"{value:.3f}"


def _cell(row: Comparison, lang: Lang) -> str:
    printed = f"{row.printed:g}"
    if row.computed is None:
        return f"{printed} / — ({_t('nd', lang)})"
    mark = "" if row.status == "match" else (" !" if row.status == "MISMATCH" else " *")
    return (f"{printed} / {_fmt(row.computed, row.quantity)} "
            f"({row.difference:+.{2 if row.quantity in ANGLES else 3}f}){mark}")


def _table(rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return ["  " + "  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip()
            for r in rows]


def _tabel1(study: Study, lang: Lang) -> list[str]:
    columns = K2[1:]
    order = ["b_min", "c", "d", "e", "f", "k_d", "k_i", "k_s", "k_g",
             "l2", "l_d", "l_i", "l_s", "l_g"]
    rows = [[_t("quantity", lang), *(f"k2 = {k:g}" for k in columns)]]
    for quantity in order:
        cells = {c.k2: c for c in study.comparisons
                 if c.quantity == quantity and c.source == "Tabel 1"}
        rows.append([quantity, *(_cell(cells[k], lang) for k in columns)])
    return _table(rows)


def _figures(study: Study, lang: Lang) -> list[str]:
    rows = [[_t("quantity", lang), "k5", _t("source", lang), *(f"k2 = {k:g}" for k in K2)]]
    for series in SERIES:
        if series.source == "Tabel 1":
            continue
        cells = {c.k2: c for c in study.comparisons
                 if c.quantity == series.quantity and c.source == series.source
                 and c.k5 == series.k5}
        rows.append([series.quantity, "" if series.k5 is None else f"{series.k5:g}",
                     series.source, *(_cell(cells[k], lang) if k in cells else "" for k in K2)])
    return _table(rows)


def violation_text(violation: Violation, lang: Lang = "en") -> str:
    """One broken requirement as a sentence."""
    degrees = violation.requirement == "transmission"
    convert = math.degrees if degrees else float
    return _t(violation.requirement, lang).format(v=convert(violation.value),
                                                  l=convert(violation.limit))


def _table_designs(table: DesignTable) -> list[Design]:
    """The designs of the table's cells, k5 by k5, each over every k2."""
    return [table.design(i, j) for j in range(table.values.k5.shape[1])
            for i in range(table.values.k2.shape[0])]


def _design_rows(study: Study, lang: Lang) -> list[str]:
    mm = "mm" if lang == "en" else "мм"
    head = ["k5", "k2", "b_min°", "c°", "d°", "k_d", "k_i", "k_s", "k_g", f"l_d {mm}",
            f"l_s {mm}", f"l_g {mm}", ""]
    rows = [head]
    for design in _table_designs(study.table):
        rows.append([f"{design.k5:g}", f"{design.k2:g}",
                     *(f"{math.degrees(x):.2f}" for x in (design.b_min, design.c, design.d)),
                     *(f"{x:.3f}" for x in (design.k_d, design.k_i, design.k_s, design.k_g)),
                     *(f"{x:.1f}" for x in (design.l_d, design.l_s, design.l_g)),
                     _t("verdict_ok", lang) if design.admissible
                     else "; ".join(violation_text(v, lang) for v in design.violations)])
    return _table(rows)


def _design_text(design: Design, lang: Lang) -> list[str]:
    angles = ", ".join(f"{name} = {math.degrees(getattr(design, name)):.2f}°"
                       for name in ("a", "b_min", "c", "d"))
    ratios = ", ".join(f"{name} = {getattr(design, name):.4f}"
                       for name in ("k2", "k5", "k_d", "k_i", "k_s", "k_g"))
    lengths = ", ".join(f"{name} = {value:.1f}" for name, value in design.lengths().items())
    return [f"  {ratios}", f"  {angles}",
            f"  {_t('lengths', lang)}: {lengths} (l3 = l2, l4 = l1)"]


def _verification_text(check: Verification, lang: Lang) -> list[str]:
    d = check.design
    return [
        "  " + _t("sim_line", lang).format(
            s=math.degrees(check.stroke), a=math.degrees(d.a), b=math.degrees(check.b_min),
            bc=math.degrees(d.b_min), g=check.clearance, gc=d.l_g, gm=check.min_clearance,
            ok=_t("yes" if check.assembles else "no", lang)),
        "  " + _t("sim_line2", lang).format(c=math.degrees(check.c_min), r0=check.lever_arm[0],
                                            r1=check.lever_arm[1], r2=check.lever_arm[2])]


def _synthesis_text(study: Study, lang: Lang) -> list[str]:
    answer = study.synthesis
    if answer is None:
        return []
    task = study.task
    lower, upper = _bounds(answer)
    out = ["", _t("synth", lang) + ":", "  " + _t("synth_setup", lang).format(
        k2lo=lower[0], k2hi=upper[0], k5lo=lower[1], k5hi=upper[1], tlo=lower[2],
        thi=upper[2], formula=answer.formula, b=math.degrees(task.min_transmission),
        lg=task.min_clearance, ls=task.actuator_stroke)]
    r = answer.result
    out.append("  " + _t("synth_run", lang).format(
        n=len(r.trials), t=r.elapsed, seed=r.settings.seed, stop=r.stop,
        ok=_t("yes" if answer.feasible else "no", lang)))
    b1, b2 = (math.degrees(v) for v in answer.ends)
    out.append("  " + _t("synth_found", lang).format(k2=answer.k2, k5=answer.k5,
                                                     t0=float(answer.x[2]), b1=b1, b2=b2))
    lengths = ", ".join(f"{k} = {v:.1f}" for k, v in answer.lengths().items())
    out.append(f"  {_t('lengths', lang)}: {lengths}")
    out.append("  " + _t("synth_check", lang).format(
        s=math.degrees(answer.check.stroke),
        ok=_t("yes" if bool(answer.check.exists.all()) else "no", lang)))
    out += ["", _t("compare", lang) + ":"]
    columns = [(_t("col_table", lang), study.chosen), (_t("col_refined", lang), study.refined)]
    rows = [["", *(name for name, _ in columns), _t("col_synth", lang)]]
    values = [_column(check) for _, check in columns] + [_synthesis_column(answer)]
    for key in ("k2", "k5", "l2", "l_d", "l_i", "l_s", "l_g", "b_ends", "c_min"):
        label = _t(key, lang) if key in ("b_ends", "c_min") else key
        rows.append([label, *(v.get(key, "—") for v in values)])
    out += _table(rows)
    if study.refined is not None and answer.feasible:
        l0, l1 = study.refined.design.l_d, answer.l_d
        gain = 100.0 * (l0 - l1) / l0
        out.append("  " + (_t("synth_note", lang).format(gain=gain, l0=l0, l1=l1)
                           if gain > 0.5 else _t("synth_same", lang).format(gap=abs(gain))))
    return out


def _bounds(answer: SynthesisAnswer) -> tuple[list[float], list[float]]:
    from synthesis.cases.tracker.synthesis_problem import bounds

    lower, upper = bounds(answer.task)
    return [float(v) for v in lower], [float(v) for v in upper]


def _column(check: Verification | None) -> dict[str, str]:
    if check is None:
        return {}
    d = check.design
    ends = check.motion.transmission[0]
    out = {"k2": f"{d.k2:.4f}", "k5": f"{d.k5:.4f}"}
    out.update({k: f"{v:.1f}" for k, v in d.lengths().items() if k != "l1" and k != "l5"})
    out["b_ends"] = f"{math.degrees(ends[0]):.2f} / {math.degrees(ends[-1]):.2f}"
    out["c_min"] = f"{math.degrees(check.c_min):.2f}"
    return out


def _synthesis_column(answer: SynthesisAnswer) -> dict[str, str]:
    out = {"k2": f"{answer.k2:.4f}", "k5": f"{answer.k5:.4f}"}
    out.update({k: f"{v:.1f}" for k, v in answer.lengths().items() if k not in ("l1", "l5")})
    b1, b2 = (math.degrees(v) for v in answer.ends)
    out["b_ends"] = f"{b1:.2f} / {b2:.2f}"
    out["c_min"] = f"{math.degrees(float(answer.check.transmission[1].min())):.2f}"
    return out


def _kg_gap(study: Study) -> float:
    """Largest difference of the printed k_g from the geometry where no agreement is expected."""
    return max(c.deviation for c in study.comparisons
               if c.quantity == "k_g" and c.tolerance is None)


def inconsistencies(study: Study, lang: Lang = "en") -> list[str]:
    """The patent's inconsistencies, each as one sentence with the numbers that show it."""
    from synthesis.cases.tracker.geometry import proportions

    a = math.radians(EXAMPLE["stroke_deg"])
    at = proportions(a, np.array(K2), EXAMPLE["k5"])
    b22 = math.degrees(float(at.b_min[-1]))
    k_s22 = float(at.k_s[-1])
    kg_gap = _kg_gap(study)
    kg_printed = ", ".join(f"{at_k:g}" for at_k in
                           next(s for s in SERIES if s.source == "fig. 12").values.values())
    kg_computed = ", ".join(f"{x:.3f}" for x in at.k_g)
    l1, ls = EXAMPLE["l1_mm"], EXAMPLE["actuator_stroke_mm"]
    example = design_table(PATENT_TASK)
    kept = ", ".join(f"{k:g}" for k in example.values.k2[example.clearance_ok[:, 0], 0])
    if lang == "en":
        return [
            f"f for k2 = 2.2: {CHOSEN['f']:g}° in Etapa IV and Etapa VI, but 4.4° in Tabel 1 "
            "and under fig. 11 (f itself cannot be checked: it is not defined).",
            f"b_min for k2 = 2.2: {CHOSEN['b_min']:g}° in Etapa VI, but 31.8° in Tabel 1 and "
            f"fig. 4; the closed form gives {b22:.2f}°.",
            f"Actuator stroke: the example asks for an actuator with l_s = {ls:g} mm, and the "
            f"chosen design uses l_s = {CHOSEN['l_s']:g} mm (computed {k_s22 * l1:.1f} mm). "
            f"With l1 = {l1:g} mm fixed by the wind load both cannot hold: "
            f"{100 * k_s22 * l1 / ls:.0f}% of the stroke is used (using all of it would need "
            f"l1 = {ls / k_s22:.0f} mm).",
            f"k_g (figs. 12, 14, 16): printed {kg_printed} for k5 = 2; the distance from A to "
            f"the extended actuator's axis is {kg_computed}. The charts agree with the "
            f"geometry only at k2 = 2.2; below it they differ by up to {kg_gap:.3f} (not "
            f"tuned). With the computed values the example's clearance l_g ≥ "
            f"{EXAMPLE['min_clearance_mm']:g} mm holds for k2 = {kept} (the patent: 2.2).",
            "e and f (Etapa IV, figs. 10, 11) are drawn in fig. 1, which the text does not "
            "contain; they cannot be derived from the text and are not computed here (the "
            "printed e is not even monotonic in k2: 27, 40, 48, 33.5, 22).",
            "The captions of figs. 9, 13, 15 define k_s = k_d·k_i (a product); the numbers "
            "and Etapa III use the difference k_s = k_d − k_i.",
        ]
    return [
        f"f при k2 = 2.2: {CHOSEN['f']:g}° на этапах IV и VI, но 4.4° в таблице 1 и под "
        "рис. 11 (сам угол f проверить нельзя: он не определён).",
        f"b_min при k2 = 2.2: {CHOSEN['b_min']:g}° на этапе VI, но 31.8° в таблице 1 и на "
        f"рис. 4; формула даёт {b22:.2f}°.",
        f"Ход привода: в примере задан привод с ходом l_s = {ls:g} мм, а выбранный вариант "
        f"использует l_s = {CHOSEN['l_s']:g} мм (расчёт {k_s22 * l1:.1f} мм). При l1 = "
        f"{l1:g} мм, заданном ветровой нагрузкой, оба условия выполнить нельзя: используется "
        f"{100 * k_s22 * l1 / ls:.0f}% хода (полный ход потребовал бы l1 = "
        f"{ls / k_s22:.0f} мм).",
        f"k_g (рис. 12, 14, 16): в патенте {kg_printed} при k5 = 2; расстояние от A до оси "
        f"выдвинутого привода равно {kg_computed}. Графики согласуются с геометрией только при "
        f"k2 = 2.2; при меньших k2 разность достигает {kg_gap:.3f} (без подгонки). По "
        f"расчётным значениям зазор примера l_g ≥ {EXAMPLE['min_clearance_mm']:g} мм "
        f"выполняется при k2 = {kept} (в патенте: 2.2).",
        "e и f (этап IV, рис. 10, 11) показаны на рис. 1, которого в тексте нет; по тексту "
        "их вывести нельзя, и здесь они не вычисляются (напечатанный угол e даже не монотонен "
        "по k2: 27, 40, 48, 33.5, 22).",
        "В подписях к рис. 9, 13, 15 k_s = k_d·k_i (произведение); числа и этап III "
        "используют разность k_s = k_d − k_i.",
    ]


def notes(study: Study, lang: Lang = "en") -> list[str]:
    """Engineering observations on the chosen design that the patent does not discuss."""
    check = study.chosen or study.refined
    if check is None:
        return []
    d = check.design
    c_min = math.degrees(check.c_min)
    if lang == "en":
        items = [f"The patent checks the transmission angle at B only. At C the angle between "
                 f"the actuator and the long rocker falls to {c_min:.1f}°, and at full "
                 f"extension the actuator's lever arm about the platform is "
                 f"{check.lever_arm[2]:.0f} mm (up to {max(check.motion.lever_arm):.0f} mm "
                 "elsewhere in the stroke): the actuator force needed for a given platform "
                 "torque is largest there."]
        if d.l_i < d.l_s:
            items.append(f"The retracted hinge-to-hinge length l_i = {d.l_i:.0f} mm is shorter "
                         f"than the stroke l_s = {d.l_s:.0f} mm: a clevis-mounted single-stage "
                         "actuator cannot do this; the actuator must be trunnion-mounted with "
                         "its body behind E, or telescopic.")
        return items
    items = [f"В патенте проверяется только угол передачи в B. В C угол между приводом и "
             f"длинным коромыслом падает до {c_min:.1f}°, а плечо привода относительно оси "
             f"платформы в выдвинутом положении равно {check.lever_arm[2]:.0f} мм (до "
             f"{max(check.motion.lever_arm):.0f} мм на остальном ходе): усилие привода для "
             "заданного момента на платформе там наибольшее."]
    if d.l_i < d.l_s:
        items.append(f"Длина втянутого привода между шарнирами l_i = {d.l_i:.0f} мм меньше хода "
                     f"l_s = {d.l_s:.0f} мм: одноступенчатый привод с проушинами так не может; "
                     "нужен привод на цапфах с корпусом за шарниром E или телескопический.")
    return items


def summary(study: Study, lang: Lang = "en") -> str:
    """The case's text report.

    Parameters
    ----------
    study : Study
    lang : {'en', 'ru'}

    Returns
    -------
    str
    """
    task = study.task
    out = [_t("title", lang), "", _t("task", lang) + ":", "  " + _t("task_line", lang).format(
        a=math.degrees(task.stroke), b=math.degrees(task.min_transmission), l1=task.l1,
        ls=task.actuator_stroke, lg=task.min_clearance, k2=", ".join(f"{k:g}" for k in task.k2),
        k5=", ".join(f"{k:g}" for k in task.k5)), ""]
    out += [_t("tabel1", lang) + ":", *_tabel1(study, lang), ""]
    out += [_t("figures", lang) + ":", *_figures(study, lang)]
    tolerances = {c.quantity: c.tolerance for c in study.comparisons
                  if c.tolerance is not None and c.quantity in ("b_min", "c", "d", "k_d", "k_i",
                                                                "k_s", "k_g")}
    out.append("  " + _t("worst", lang).format(items=", ".join(
        f"{q} {worst(study.comparisons, q):.3f} ({tol:g})" for q, tol in tolerances.items())))
    out += ["  " + _t("kg_differs", lang).format(dk=_kg_gap(study)), ""]
    out += [_t("procedure", lang) + ":"]
    k2min = study.table.k2_min
    out.append("  " + (_t("etapa1", lang).format(b=math.degrees(task.min_transmission),
                                                 k2min=f"{k2min:g}") if k2min is not None
                       else _t("etapa1_none", lang).format(b=math.degrees(task.min_transmission))))
    out += ["  " + _t("etapa2_5", lang) + ":", *_design_rows(study, lang)]
    out += ["  " + _t("etapa6", lang) + ":"]
    for key, check in (("chosen", study.chosen), ("refined", study.refined)):
        out.append(f"  {_t(key, lang)}:")
        if check is None:
            out.append(f"  {_t('none', lang)}")
            continue
        out += _design_text(check.design, lang)
        out += ["  " + _t("sim", lang).format(n=check.motion.s.shape[-1],
                                              formula=check.motion.formula) + ":",
                *_verification_text(check, lang)]
    if study.chosen is not None and _is_patent_task(study):
        same = math.isclose(study.chosen.design.k2, CHOSEN["k2"]) and \
            math.isclose(study.chosen.design.k5, CHOSEN["k5"])
        out.append("  " + _t("patent_pick", lang).format(
            k2=CHOSEN["k2"], k5=CHOSEN["k5"], same=_t("same" if same else "other", lang)))
    out += _synthesis_text(study, lang)
    out += ["", _t("incons", lang) + ":"]
    out += [f"  {i}. {text}" for i, text in enumerate(inconsistencies(study, lang), 1)]
    extra = notes(study, lang)
    if extra:
        out += ["", _t("notes", lang) + ":", *(f"  - {text}" for text in extra)]
    return "\n".join(out) + "\n"


def _is_patent_task(study: Study) -> bool:
    task = study.task
    return (math.isclose(math.degrees(task.stroke), EXAMPLE["stroke_deg"])
            and math.isclose(task.l1, EXAMPLE["l1_mm"]))


def _design_dict(check: Verification | None) -> dict[str, Any] | None:
    if check is None:
        return None
    d = check.design
    deg: Callable[[float], float] = math.degrees
    return {
        "k2": d.k2, "k5": d.k5, "a_deg": deg(d.a), "b_min_deg": deg(d.b_min),
        "c_deg": deg(d.c), "d_deg": deg(d.d), "k_d": d.k_d, "k_i": d.k_i, "k_s": d.k_s,
        "k_g": d.k_g, "lengths_mm": d.lengths(),
        "violations": [violation_text(v) for v in d.violations],
        "simulation": {"structure": check.motion.formula, "stroke_deg": deg(check.stroke),
                       "b_min_deg": deg(check.b_min),
                       "c_min_deg": deg(check.c_min), "l_g_mm": check.clearance,
                       "min_post_distance_mm": check.min_clearance,
                       "lever_arm_mm": {"least": check.lever_arm[0],
                                        "retracted": check.lever_arm[1],
                                        "extended": check.lever_arm[2]},
                       "assembles": check.assembles, "errors": check.errors},
    }


def _synthesis_dict(answer: SynthesisAnswer | None) -> dict[str, Any] | None:
    if answer is None:
        return None
    r = answer.result
    b1, b2 = (math.degrees(v) for v in answer.ends)
    return {"structure": answer.formula, "k2": answer.k2, "k5": answer.k5,
            "theta0_deg": float(answer.x[2]), "feasible": answer.feasible,
            "lengths_mm": answer.lengths(), "b_retracted_deg": b1, "b_extended_deg": b2,
            "simulated_stroke_deg": math.degrees(answer.check.stroke),
            "trials": len(r.trials), "seconds": r.elapsed, "seed": r.settings.seed,
            "stop": r.stop}


def to_dict(study: Study) -> dict[str, Any]:
    """Everything of the report as plain data (for ``--json``)."""
    task = study.task
    table = study.table
    rows = [{"k2": d.k2, "k5": d.k5, "b_min_deg": math.degrees(d.b_min),
             "c_deg": math.degrees(d.c), "d_deg": math.degrees(d.d), "k_d": d.k_d,
             "k_i": d.k_i, "k_s": d.k_s, "k_g": d.k_g, "lengths_mm": d.lengths(),
             "admissible": d.admissible,
             "violations": [violation_text(v) for v in d.violations]}
            for d in _table_designs(table)]
    return {
        "case": "tracker",
        "task": {"stroke_deg": math.degrees(task.stroke),
                 "min_transmission_deg": math.degrees(task.min_transmission), "l1_mm": task.l1,
                 "actuator_stroke_mm": task.actuator_stroke,
                 "min_clearance_mm": task.min_clearance, "k2": list(task.k2),
                 "k5": list(task.k5)},
        "reproduction": [{"quantity": c.quantity, "k2": c.k2, "k5": c.k5, "source": c.source,
                          "printed": c.printed, "computed": c.computed,
                          "difference": c.difference, "tolerance": c.tolerance,
                          "status": c.status} for c in study.comparisons],
        "k2_min": table.k2_min,
        "design_table": rows,
        "chosen": _design_dict(study.chosen),
        "refined": _design_dict(study.refined),
        "synthesis": _synthesis_dict(study.synthesis),
        "inconsistencies": inconsistencies(study, "en"),
        "notes": notes(study, "en"),
    }
