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

from assur.text import render
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

Lang = str


def _t(key: str, lang: Lang, **data: Any) -> str:
    return render(f"case.tracker.{key}", lang, **data)


def _yes_no(value: bool, lang: Lang) -> str:
    return render("case.common.yes" if value else "case.common.no", lang)


def _fmt(value: float, quantity: str) -> str:
    if quantity in ANGLES or quantity in ("e", "f"):
        return f"{value:.2f}"
    if quantity.startswith("l"):
        return f"{value:.1f}"
    return f"{value:.3f}"


def _cell(row: Comparison, lang: Lang) -> str:
    printed = f"{row.printed:g}"
    if row.computed is None:
        return f"{printed} / — ({_t('not_derivable', lang)})"
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
                     _source(series.source, lang),
                     *(_cell(cells[k], lang) if k in cells else "" for k in K2)])
    return _table(rows)


def _source(source: str, lang: Lang) -> str:
    """Where a printed series comes from (``"fig. 12"``) in ``lang``."""
    if source.startswith("fig. "):
        return _t("fig", lang, number=source.removeprefix("fig. "))
    return source


def violation_text(violation: Violation, lang: Lang = "en") -> str:
    """One broken requirement as a sentence."""
    degrees = violation.requirement == "transmission"
    convert = math.degrees if degrees else float
    return _t(f"violation.{violation.requirement}", lang, v=convert(violation.value),
              l=convert(violation.limit))


def _table_designs(table: DesignTable) -> list[Design]:
    """The designs of the table's cells, k5 by k5, each over every k2."""
    return [table.design(i, j) for j in range(table.values.k5.shape[1])
            for i in range(table.values.k2.shape[0])]


def _design_rows(study: Study, lang: Lang) -> list[str]:
    mm = render("case.common.unit.mm", lang)
    head = ["k5", "k2", "b_min°", "c°", "d°", "k_d", "k_i", "k_s", "k_g", f"l_d {mm}",
            f"l_s {mm}", f"l_g {mm}", ""]
    rows = [head]
    for design in _table_designs(study.table):
        rows.append([f"{design.k5:g}", f"{design.k2:g}",
                     *(f"{math.degrees(x):.2f}" for x in (design.b_min, design.c, design.d)),
                     *(f"{x:.3f}" for x in (design.k_d, design.k_i, design.k_s, design.k_g)),
                     *(f"{x:.1f}" for x in (design.l_d, design.l_s, design.l_g)),
                     _t("admissible", lang) if design.admissible
                     else "; ".join(violation_text(v, lang) for v in design.violations)])
    return _table(rows)


def _design_text(design: Design, lang: Lang) -> list[str]:
    angles = ", ".join(f"{name} = {math.degrees(getattr(design, name)):.2f}°"
                       for name in ("a", "b_min", "c", "d"))
    ratios = ", ".join(f"{name} = {getattr(design, name):.4f}"
                       for name in ("k2", "k5", "k_d", "k_i", "k_s", "k_g"))
    lengths = ", ".join(f"{name} = {value:.1f}" for name, value in design.lengths().items())
    return [f"  {ratios}", f"  {angles}",
            "  " + _t("lengths", lang, lengths=f"{lengths} (l3 = l2, l4 = l1)")]


def _verification_text(check: Verification, lang: Lang) -> list[str]:
    d = check.design
    return [
        "  " + _t(
            "sim_line", lang, s=math.degrees(check.stroke), a=math.degrees(d.a),
            b=math.degrees(check.b_min),
            bc=math.degrees(d.b_min), g=check.clearance, gc=d.l_g, gm=check.min_clearance,
            ok=_yes_no(check.assembles, lang)),
        "  " + _t("sim_line2", lang, c=math.degrees(check.c_min), r0=check.lever_arm[0],
                  r1=check.lever_arm[1], r2=check.lever_arm[2])]


def _synthesis_text(study: Study, lang: Lang) -> list[str]:
    answer = study.synthesis
    if answer is None:
        return []
    task = study.task
    lower, upper = _bounds(answer)
    out = ["", _t("synth", lang), "  " + _t(
        "synth_setup", lang, k2lo=lower[0], k2hi=upper[0], k5lo=lower[1], k5hi=upper[1],
        tlo=lower[2],
        thi=upper[2], formula=answer.formula, b=math.degrees(task.min_transmission),
        lg=task.min_clearance, ls=task.actuator_stroke)]
    r = answer.result
    out.append("  " + _t("synth_run", lang, n=len(r.trials), t=r.elapsed, seed=r.settings.seed,
                         stop=r.stop, ok=_yes_no(answer.feasible, lang)))
    b1, b2 = (math.degrees(v) for v in answer.ends)
    out.append("  " + _t("synth_found", lang, k2=answer.k2, k5=answer.k5,
                         t0=float(answer.x[2]), b1=b1, b2=b2))
    lengths = ", ".join(f"{k} = {v:.1f}" for k, v in answer.lengths().items())
    out.append("  " + _t("lengths", lang, lengths=lengths))
    out.append("  " + _t("synth_check", lang, s=math.degrees(answer.check.stroke),
                         ok=_yes_no(bool(answer.check.exists.all()), lang)))
    out += ["", _t("compare", lang)]
    columns = [(_t("column.table", lang), study.chosen),
               (_t("column.refined", lang), study.refined)]
    rows = [["", *(name for name, _ in columns), _t("column.synthesis", lang)]]
    values = [_column(check) for _, check in columns] + [_synthesis_column(answer)]
    for key in ("k2", "k5", "l2", "l_d", "l_i", "l_s", "l_g", "b_ends", "c_min"):
        label = _t(f"row.{key}", lang) if key in ("b_ends", "c_min") else key
        rows.append([label, *(v.get(key, "—") for v in values)])
    out += _table(rows)
    if study.refined is not None and answer.feasible:
        l0, l1 = study.refined.design.l_d, answer.l_d
        gain = 100.0 * (l0 - l1) / l0
        out.append("  " + (_t("synth_note", lang, gain=gain, l0=l0, l1=l1)
                           if gain > 0.5 else _t("synth_same", lang, gap=abs(gain))))
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
    return [
        _t("incons.f", lang, f=CHOSEN["f"]),
        _t("incons.b_min", lang, b_min=CHOSEN["b_min"], b22=b22),
        _t("incons.stroke", lang, ls=ls, chosen=CHOSEN["l_s"], computed=k_s22 * l1, l1=l1,
           used=100 * k_s22 * l1 / ls, needed=ls / k_s22),
        _t("incons.k_g", lang, printed=kg_printed, computed=kg_computed, gap=kg_gap,
           clearance=EXAMPLE["min_clearance_mm"], kept=kept),
        _t("incons.e_f", lang),
        _t("incons.k_s", lang),
    ]


def notes(study: Study, lang: Lang = "en") -> list[str]:
    """Engineering observations on the chosen design that the patent does not discuss."""
    check = study.chosen or study.refined
    if check is None:
        return []
    d = check.design
    c_min = math.degrees(check.c_min)
    items = [_t("note.at_c", lang, c_min=c_min, arm=check.lever_arm[2],
                most=max(check.motion.lever_arm))]
    if d.l_i < d.l_s:
        items.append(_t("note.retracted", lang, l_i=d.l_i, l_s=d.l_s))
    return items


def summary(study: Study, lang: Lang = "en") -> str:
    """The case's text report.

    Parameters
    ----------
    study : Study
    lang : str
        A language of the catalogue (:func:`assur.text.languages`).

    Returns
    -------
    str
    """
    task = study.task
    out = [_t("title", lang), "", _t("task", lang), "  " + _t(
        "task_line", lang, a=math.degrees(task.stroke), b=math.degrees(task.min_transmission),
        l1=task.l1,
        ls=task.actuator_stroke, lg=task.min_clearance, k2=", ".join(f"{k:g}" for k in task.k2),
        k5=", ".join(f"{k:g}" for k in task.k5)), ""]
    out += [_t("tabel1", lang), *_tabel1(study, lang), ""]
    out += [_t("figures", lang), *_figures(study, lang)]
    tolerances = {c.quantity: c.tolerance for c in study.comparisons
                  if c.tolerance is not None and c.quantity in ("b_min", "c", "d", "k_d", "k_i",
                                                                "k_s", "k_g")}
    out.append("  " + _t("worst", lang, items=", ".join(
        f"{q} {worst(study.comparisons, q):.3f} ({tol:g})" for q, tol in tolerances.items())))
    out += ["  " + _t("kg_differs", lang, dk=_kg_gap(study)), ""]
    out += [_t("procedure", lang)]
    k2min = study.table.k2_min
    out.append("  " + (_t("etapa1", lang, b=math.degrees(task.min_transmission),
                          k2min=k2min) if k2min is not None
                       else _t("etapa1_none", lang, b=math.degrees(task.min_transmission))))
    out += ["  " + _t("etapa2_5", lang), *_design_rows(study, lang)]
    out += ["  " + _t("etapa6", lang)]
    for key, check in (("chosen", study.chosen), ("refined", study.refined)):
        out.append("  " + _t(key, lang))
        if check is None:
            out.append(f"  {_t('none', lang)}")
            continue
        out += _design_text(check.design, lang)
        out += ["  " + _t("sim", lang, n=check.motion.s.shape[-1],
                          formula=check.motion.formula),
                *_verification_text(check, lang)]
    if study.chosen is not None and _is_patent_task(study):
        same = math.isclose(study.chosen.design.k2, CHOSEN["k2"]) and \
            math.isclose(study.chosen.design.k5, CHOSEN["k5"])
        out.append("  " + _t(
            "patent_pick", lang, k2=CHOSEN["k2"], k5=CHOSEN["k5"],
            same=_t("same" if same else "other", lang)))
    out += _synthesis_text(study, lang)
    out += ["", _t("inconsistencies", lang)]
    out += [f"  {i}. {text}" for i, text in enumerate(inconsistencies(study, lang), 1)]
    extra = notes(study, lang)
    if extra:
        out += ["", _t("notes", lang), *(f"  - {text}" for text in extra)]
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
