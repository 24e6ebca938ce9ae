"""Text and JSON reports of the impact case; the text in any language of the catalogue."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from assur.text import render
from synthesis.cases.impact.data import PAPER_IMPULSE_UNIT, TABLE_1_COLUMNS
from synthesis.cases.impact.position import REASONS
from synthesis.cases.impact.study import ImpactStudy

__all__ = ["report_json", "report_text"]

Lang = str

#: The sentences of the source's slips, in the order the report numbers them.
_SLIPS = ("slip.unit", "slip.r2", "slip.alpha", "slip.inertia", "slip.equations", "slip.angles")
#: The rocker's lever in the restitution law: exact, and as (7)–(8) print it.
_EXACT_LEVER = "r4·sin(ψ − θ4)"
_PRINTED_LEVER = "ρ·sin(ψ − θ4 + α)"
_ROCKER_VELOCITY = "ρ·θ4'·sin(ψ − θ4 − α) = r4·θ4'·sin(ψ − θ4)"
#: Catalogue codes of the units named in :data:`TABLE_1_COLUMNS` and the report.
_UNITS = {"mm": "case.common.unit.mm", "kg": "case.impact.unit.kg",
          "kgmm2": "case.impact.unit.kg_mm2", "rad/s": "case.impact.unit.rad_s",
          "1e-4 N·s": "case.impact.unit.impulse", "rigid rate": "case.impact.unit.rigid_rate"}

_COLUMN_LABEL = {"omega2": "θ2'+", "omega3": "θ3'+", "F": "F", "r_A": "r_A", "r_O2": "r_O2"}
_MODEL_LABEL = {"TM": "[2]", "P": "P"}


def _t(key: str, lang: Lang, **data: Any) -> str:
    return render(f"case.impact.{key}", lang, **data)


def report_text(study: ImpactStudy, lang: Lang = "en") -> str:
    """The full text report: data, position, both models, Table 1 check, energy, slips."""
    lines = [_t("title", lang), "", *_data_lines(study, lang), "", *_position_lines(study, lang),
             "", *_model_lines(study, lang), ""]
    if study.table is not None:
        lines += [*_table_lines(study, lang), ""]
    else:
        lines += [_t("no_table", lang), ""]
    lines += [*_energy_lines(study, lang), "", _t("slips", lang)]
    lines += [f"  {number}. {_t(key, lang, velocity=_ROCKER_VELOCITY)}"
              for number, key in enumerate(_SLIPS, start=1)]
    return "\n".join(lines) + "\n"


def _u(name: str, lang: Lang) -> str:
    return render(_UNITS[name], lang)


def _data_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    d = study.data
    mm, kg, kgmm2, rads = (_u(name, lang) for name in ("mm", "kg", "kgmm2", "rad/s"))
    lever = (_t("lever_paper", lang) if study.lever == "paper"
             else _t("lever_exact", lang, formula=_EXACT_LEVER))
    return [
        _t("data", lang),
        (f"  r1 = {d.r1 * 1e3:g} {mm}, r2 = {d.r2 * 1e3:g} {mm}, r3 = {d.r3 * 1e3:g} {mm}, "
         f"r4 = {d.r4 * 1e3:g} {mm}; m2 = {d.m2:g} {kg}, m3 = {d.m3:g} {kg}, m4 = {d.m4:g} {kg}"),
        (f"  I_O2 = {d.inertia_o2 * 1e6:g}, I3 = {d.inertia3 * 1e6:g}, "
         f"I4 = {d.inertia4 * 1e6:g}, I_O4 = {d.inertia_o4 * 1e6:g} {kgmm2}; "
         f"ξ = {d.clearance * 1e3:g} {mm}"),
        (f"  θ2 = {math.degrees(d.theta2):g}°, θ2' = {d.omega2:g} {rads}, k = {d.k:g}, "
         f"μ = {d.mu:g}; {_t('lever', lang, lever=lever)}"),
    ]


def _position_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    p = study.position
    rads = _u("rad/s", lang)
    rows: dict[str, list[str]] = {}
    for index, omega4 in enumerate(p.omega4):
        if not p.exists[index]:
            text = render(REASONS[int(p.reason[index])], lang)
        else:
            deg = {name: math.degrees(float(getattr(p, name)[index]))
                   for name in ("theta3", "theta4_rigid", "theta4", "psi")}
            text = (f"θ3 = {deg['theta3']:.4f}°, θ4 = {deg['theta4_rigid']:.4f}° "
                    f"({_t('rigid', lang)}), {deg['theta4']:.4f}° ({_t('bearing', lang)}), "
                    f"ψ = {deg['psi']:.4f}°, ψ − θ4 = {(deg['psi'] - deg['theta4']) % 360:.4f}°;"
                    f" θ3' = {p.omega3[index]:.4f} {rads}, θ4' ({_u('rigid rate', lang)}) = "
                    f"{p.omega4_rigid[index]:.4f} {rads}")
        rows.setdefault(text, []).append(f"{omega4:g}")
    lines = [_t("position", lang, sigma=study.data.sigma)]
    for text, omega4 in rows.items():
        lines += [f"  θ4' = {', '.join(omega4)} {rads}:", f"    {text}"]
    return lines


def _model_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    heads = ("θ4'", _t("model", lang), "θ2'+", "θ3'+", "θ4'+", "F", "f", "r_A", "r_O2", "M_drive")
    lines = [_t("models", lang), "  " + "".join(f"{h:>10}" for h in heads)]
    unit = PAPER_IMPULSE_UNIT
    for index, omega4 in enumerate(study.position.omega4):
        if not study.position.exists[index]:
            continue
        for model in ("TM", "P"):
            r = study.results[model]
            values = (r.omega2[index], r.omega3[index], r.omega4[index], r.normal[index] / unit,
                      r.friction[index] / unit, abs(r.r_a[index]) / unit,
                      abs(r.r_o2[index]) / unit, r.drive[index] / unit)
            lines.append(f"  {omega4:>10g}{_MODEL_LABEL[model]:>10}"
                         + "".join(f"{round(v, 2) + 0.0:>10.2f}" for v in values))
    lines.append("  " + _t("drive", lang))
    return lines


def _table_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    table = study.table
    assert table is not None
    omega4 = study.position.omega4
    lines = [_t("table", lang)]
    head = _t("column", lang)
    lines.append(f"  {head:<14}" + "".join(f"{f'θ4={w:g}':>32}" for w in omega4))
    for key in table.printed:
        column, model = key
        label = f"{_COLUMN_LABEL[column]} {_MODEL_LABEL[model]}"
        cells = "".join(
            f"{table.printed[key][i]:>10.1f}{table.computed[key][i]:>11.2f}"
            f"{100 * table.relative[key][i]:>+10.3f}%" for i in range(len(omega4)))
        lines.append(f"  {label:<14}{cells}")
    units = ", ".join(f"{_COLUMN_LABEL[c]} {_u(u, lang)}" for c, u in TABLE_1_COLUMNS.items())
    lines.append("  " + _t("table_units", lang, units=units))
    lines.append(_t("worst", lang))
    for key, worst in table.worst().items():
        label = f"{_COLUMN_LABEL[key[0]]} {_MODEL_LABEL[key[1]]}"
        lines.append(f"  {label:<14}{100 * worst:>8.3f} %")
    overall = max(table.worst().values())
    lines.append("  " + _t("all_within", lang, worst=100 * overall))
    return lines


def _energy_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    lines = [_t("energy", lang)]
    for index, omega4 in enumerate(study.position.omega4):
        if not study.position.exists[index]:
            continue
        for model in ("TM", "P"):
            e = study.energy[model]
            values = (e.before[index] * 1e3, e.drive_work[index] * 1e3, e.after[index] * 1e3,
                      e.loss[index] * 1e3)
            lines.append(f"  θ4' = {omega4:>6g} {_MODEL_LABEL[model]:>4}"
                         + "".join(f"{v:>12.4f}" for v in values)
                         + f"{100 * e.relative_loss[index]:>12.5f}")
            if not study.results[model].full_slip[index]:
                lines.append("    " + _t("friction_bad", lang, model=_MODEL_LABEL[model],
                                           w4=omega4))
    s = study.slip
    exists = study.position.exists
    if exists.any():
        lines += ["", _t("slip_head", lang), "  " + _t(
            "slip_body", lang, printed=_PRINTED_LEVER, exact_lever=_EXACT_LEVER,
            alpha=math.degrees(float(np.max(np.abs(s.alpha[exists])))),
            lever=float(np.max(np.abs(s.lever_error[exists]))),
            tm=float(np.max(s.energy_error["TM"][exists])),
            p=float(np.max(s.energy_error["P"][exists])),
            exact=float(max(np.max(np.abs(v[exists])) for v in s.exact_energy_error.values())),
            kp=float(np.max(s.restitution["P"][exists])))]
    return lines


def _floats(array: Any) -> list[float | None]:
    return [None if not np.isfinite(v) else float(v) for v in np.ravel(array)]


def report_json(study: ImpactStudy) -> dict[str, Any]:
    """The report as plain data (SI units; Table 1 columns in the paper's units)."""
    d, p = study.data, study.position
    out: dict[str, Any] = {
        "case": "impact",
        "lever": study.lever,
        "data": {"r1": d.r1, "r2": d.r2, "r3": d.r3, "r4": d.r4, "m2": d.m2, "m3": d.m3,
                 "m4": d.m4, "inertia_o2": d.inertia_o2, "inertia3": d.inertia3,
                 "inertia4": d.inertia4, "inertia_o4": d.inertia_o4, "clearance": d.clearance,
                 "omega2": d.omega2, "theta2_deg": math.degrees(d.theta2),
                 "omega4": list(d.omega4), "k": d.k, "mu": d.mu, "sigma": d.sigma},
        "position": {
            "exists": [bool(v) for v in p.exists],
            "reason": [render(REASONS[int(v)]) for v in p.reason],
            **{f"{name}_deg": _floats(np.degrees(getattr(p, name)))
               for name in ("theta3", "theta4_rigid", "theta4", "psi")},
            "omega3": _floats(p.omega3), "omega4_rigid": _floats(p.omega4_rigid),
        },
        "models": {},
        "alpha_slip": {
            "alpha_deg": _floats(np.degrees(study.slip.alpha)),
            "lever_error": _floats(study.slip.lever_error),
            "energy_error": {k: _floats(v) for k, v in study.slip.energy_error.items()},
            "restitution": {k: _floats(v) for k, v in study.slip.restitution.items()},
        },
    }
    for model, r in study.results.items():
        e = study.energy[model]
        out["models"][model] = {
            "omega2": _floats(r.omega2), "omega3": _floats(r.omega3), "omega4": _floats(r.omega4),
            "F": _floats(r.normal), "f": _floats(r.friction),
            "r_A": _floats(np.abs(r.r_a)), "r_O2": _floats(np.abs(r.r_o2)),
            "drive": _floats(r.drive), "full_slip": [bool(v) for v in r.full_slip],
            "paper_units": {k: _floats(v) for k, v in r.paper_units().items()},
            "energy": {"before": _floats(e.before), "after": _floats(e.after),
                       "drive_work": _floats(e.drive_work), "loss": _floats(e.loss)},
        }
    if study.table is not None:
        out["table_1"] = {
            f"{column} {model}": {"paper": _floats(study.table.printed[column, model]),
                                  "computed": _floats(study.table.computed[column, model]),
                                  "relative": _floats(study.table.relative[column, model])}
            for column, model in study.table.printed}
        out["worst_relative_error"] = {f"{c} {m}": w for (c, m), w in study.table.worst().items()}
    return out
