"""Text and JSON reports of the impact case, in English and Russian."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from synthesis.cases.impact.data import PAPER_IMPULSE_UNIT, TABLE_1_COLUMNS
from synthesis.cases.impact.position import REASONS
from synthesis.cases.impact.study import ImpactStudy

__all__ = ["report_json", "report_text"]

Lang = str  # a language of the catalogue (assur.text.languages())

_TEXT: dict[str, dict[str, str]] = {
    "title": {
        "en": "Impact in a four-bar with a clearance in the bearing B "
              "(Vjaters, Viba, Grasmanis)",
        "ru": "Удар в четырёхзвеннике с зазором в шарнире B (Вятерс, Виба, Грасманис)",
    },
    "data": {"en": "Data", "ru": "Исходные данные"},
    "position": {"en": "Position at the instant of impact",
                 "ru": "Положение механизма в момент удара"},
    "assembly": {"en": "assembly σ", "ru": "сборка σ"},
    "rigid": {"en": "rigid closure", "ru": "жёсткое замыкание"},
    "bearing": {"en": "bearing centre", "ru": "центр втулки"},
    "lever": {"en": "restitution lever of the rocker", "ru": "плечо коромысла в законе удара"},
    "lever_paper": {"en": "as printed in (7)–(8)", "ru": "как напечатано в (7)–(8)"},
    "lever_exact": {"en": "exact, r4·sin(ψ − θ4)", "ru": "точное, r4·sin(ψ − θ4)"},
    "models": {
        "en": "Both models ([2] Townsend–Mansour: crank speed held; P: the source's, every "
              "velocity may jump); impulses in 1e-4 N·s",
        "ru": "Обе модели ([2] Таунсенд–Мансур: скорость кривошипа сохраняется; P: модель "
              "статьи, скачком меняются все скорости); импульсы в 1e-4 Н·с",
    },
    "table": {
        "en": "Table 1 of the source beside the computed one (relative difference)",
        "ru": "Таблица 1 статьи и расчёт (относительное расхождение)",
    },
    "worst": {"en": "Worst relative error per column", "ru": "Наибольшая погрешность по столбцам"},
    "no_table": {
        "en": "The data differ from the source's: no comparison with Table 1.",
        "ru": "Данные отличаются от данных статьи: сравнение с таблицей 1 не проводится.",
    },
    "energy": {"en": "Kinetic energy, mJ", "ru": "Кинетическая энергия, мДж"},
    "energy_head": {
        "en": "before, drive work, after, lost, lost %",
        "ru": "до, работа привода, после, потеря, потеря %",
    },
    "slip_head": {"en": "The α-sign slip of (7)–(8)", "ru": "Ошибка знака α в (7)–(8)"},
    "slip_body": {
        "en": "α = {alpha:.4f}° (8); the printed lever ρ·sin(ψ − θ4 + α) differs from the exact "
              "r4·sin(ψ − θ4) by {lever:.2e}. With k = 1, μ = 0 the kinetic energy then grows "
              "by {tm:.2e} ([2]) and {p:.2e} (P) of itself instead of being conserved (exact "
              "lever: {exact:.1e}); the effective restitution coefficient is {kp:.6f}.",
        "ru": "α = {alpha:.4f}° (8); напечатанное плечо ρ·sin(ψ − θ4 + α) отличается от точного "
              "r4·sin(ψ − θ4) на {lever:.2e}. При k = 1, μ = 0 кинетическая энергия растёт на "
              "{tm:.2e} ([2]) и {p:.2e} (P) вместо сохранения (точное плечо: {exact:.1e}); "
              "фактический коэффициент восстановления {kp:.6f}.",
    },
    "friction_bad": {
        "en": "Full slip is not consistent for {model} at θ4' = {w4:g} rad/s: the slip reverses "
              "during the impact (the pin would stick); the energy balance there is not "
              "physical.",
        "ru": "Полное скольжение не согласовано для {model} при θ4' = {w4:g} рад/с: "
              "скольжение меняет знак во время удара (палец бы застрял); энергетический баланс "
              "там нефизичен.",
    },
    "slips": {"en": "Slips of the source", "ru": "Неточности статьи"},
}

_SLIPS: dict[str, list[str]] = {
    "en": [
        ("Unit of the impulses: the heads of Table 1 say \"Ns\", the values are in 1e-4 N·s "
         "(F = 726.4 means 0.07264 N·s; a coupler of 18 g at about 10 m/s carries 0.17 N·s)."),
        "Equation (7) prints \"r_2θ\" for r2 in v_B3n.",
        ("Equations (7)–(8): α is the angle between the rocker and the radius ρ to the pin "
         "centre; the rocker's normal velocity there is ρ·θ4'·sin(ψ − θ4 − α) = "
         "r4·θ4'·sin(ψ − θ4), the source prints + α (effect quantified above)."),
        ("I_O4 is never stated: the data give I4 = 10 kg·mm² (about the centre); Table 1 is "
         "reproduced with I_O4 = I4 + m4·(r4/2)² = 38.8 kg·mm²."),
        ("For [2] the source speaks of \"3 equations\" in four unknowns θ3'+, θ4'+, F, f; the "
         "fourth is f = μF."),
        ("θ3, θ4 and ψ are not printed; they follow from the rigid closure at θ2 = 150° (open "
         "assembly) with the bearing centre ξ behind the pin on the rocker's circle."),
    ],
    "ru": [
        ("Единица импульсов: в заголовках таблицы 1 «Ns», значения же в 1e-4 Н·с "
         "(F = 726,4 означает 0,07264 Н·с; шатун массой 18 г при скорости около 10 м/с имеет "
         "импульс 0,17 Н·с)."),
        "В формуле (7) напечатано «r_2θ» вместо r2 в v_B3n.",
        ("Формулы (7)–(8): α — угол между коромыслом и радиусом ρ к центру пальца; нормальная "
         "скорость точки коромысла там ρ·θ4'·sin(ψ − θ4 − α) = r4·θ4'·sin(ψ − θ4), в статье "
         "+ α (влияние оценено выше)."),
        ("I_O4 в статье не указан: дан I4 = 10 кг·мм² (относительно центра масс); таблица 1 "
         "воспроизводится при I_O4 = I4 + m4·(r4/2)² = 38,8 кг·мм²."),
        ("Для [2] статья говорит о «3 уравнениях» с четырьмя неизвестными θ3'+, θ4'+, F, f; "
         "четвёртое — f = μF."),
        ("θ3, θ4 и ψ не напечатаны; они следуют из жёсткого замыкания при θ2 = 150° (открытая "
         "сборка), центр втулки — на окружности коромысла на ξ позади пальца."),
    ],
}

_UNITS: dict[str, dict[str, str]] = {
    "mm": {"en": "mm", "ru": "мм"},
    "kg": {"en": "kg", "ru": "кг"},
    "kgmm2": {"en": "kg·mm²", "ru": "кг·мм²"},
    "rad/s": {"en": "rad/s", "ru": "рад/с"},
    "1e-4 N·s": {"en": "1e-4 N·s", "ru": "1e-4 Н·с"},
    "model": {"en": "model", "ru": "модель"},
    "rigid rate": {"en": "rigid", "ru": "жёстк."},
}

_COLUMN_LABEL = {"omega2": "θ2'+", "omega3": "θ3'+", "F": "F", "r_A": "r_A", "r_O2": "r_O2"}
_MODEL_LABEL = {"TM": "[2]", "P": "P"}


def _t(key: str, lang: Lang) -> str:
    return _TEXT[key][lang]


def report_text(study: ImpactStudy, lang: Lang = "en") -> str:
    """The full text report: data, position, both models, Table 1 check, energy, slips."""
    lines = [_t("title", lang), "", *_data_lines(study, lang), "", *_position_lines(study, lang),
             "", *_model_lines(study, lang), ""]
    if study.table is not None:
        lines += [*_table_lines(study, lang), ""]
    else:
        lines += [_t("no_table", lang), ""]
    lines += [*_energy_lines(study, lang), "", _t("slips", lang)]
    lines += [f"  {number}. {text}" for number, text in enumerate(_SLIPS[lang], start=1)]
    return "\n".join(lines) + "\n"


def _u(name: str, lang: Lang) -> str:
    return _UNITS[name][lang]


def _data_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    d = study.data
    mm, kg, kgmm2, rads = (_u(name, lang) for name in ("mm", "kg", "kgmm2", "rad/s"))
    lever = _t("lever_paper" if study.lever == "paper" else "lever_exact", lang)
    return [
        _t("data", lang),
        (f"  r1 = {d.r1 * 1e3:g} {mm}, r2 = {d.r2 * 1e3:g} {mm}, r3 = {d.r3 * 1e3:g} {mm}, "
         f"r4 = {d.r4 * 1e3:g} {mm}; m2 = {d.m2:g} {kg}, m3 = {d.m3:g} {kg}, m4 = {d.m4:g} {kg}"),
        (f"  I_O2 = {d.inertia_o2 * 1e6:g}, I3 = {d.inertia3 * 1e6:g}, "
         f"I4 = {d.inertia4 * 1e6:g}, I_O4 = {d.inertia_o4 * 1e6:g} {kgmm2}; "
         f"ξ = {d.clearance * 1e3:g} {mm}"),
        (f"  θ2 = {math.degrees(d.theta2):g}°, θ2' = {d.omega2:g} {rads}, k = {d.k:g}, "
         f"μ = {d.mu:g}; {_t('lever', lang)}: {lever}"),
    ]


def _position_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    p = study.position
    rads = _u("rad/s", lang)
    rows: dict[str, list[str]] = {}
    for index, omega4 in enumerate(p.omega4):
        if not p.exists[index]:
            text = REASONS[int(p.reason[index])][0 if lang == "en" else 1]
        else:
            deg = {name: math.degrees(float(getattr(p, name)[index]))
                   for name in ("theta3", "theta4_rigid", "theta4", "psi")}
            text = (f"θ3 = {deg['theta3']:.4f}°, θ4 = {deg['theta4_rigid']:.4f}° "
                    f"({_t('rigid', lang)}), {deg['theta4']:.4f}° ({_t('bearing', lang)}), "
                    f"ψ = {deg['psi']:.4f}°, ψ − θ4 = {(deg['psi'] - deg['theta4']) % 360:.4f}°;"
                    f" θ3' = {p.omega3[index]:.4f} {rads}, θ4' ({_u('rigid rate', lang)}) = "
                    f"{p.omega4_rigid[index]:.4f} {rads}")
        rows.setdefault(text, []).append(f"{omega4:g}")
    lines = [f"{_t('position', lang)} ({_t('assembly', lang)} = {study.data.sigma:+d})"]
    for text, omega4 in rows.items():
        lines += [f"  θ4' = {', '.join(omega4)} {rads}:", f"    {text}"]
    return lines


def _model_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    heads = ("θ4'", _u("model", lang), "θ2'+", "θ3'+", "θ4'+", "F", "f", "r_A", "r_O2", "M_drive")
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
    lines.append("  M_drive: " + ("angular impulse of the drive, 1e-4 N·m·s" if lang == "en"
                                  else "импульс момента привода, 1e-4 Н·м·с"))
    return lines


def _table_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    table = study.table
    assert table is not None
    omega4 = study.position.omega4
    lines = [_t("table", lang)]
    head = "column" if lang == "en" else "столбец"
    lines.append(f"  {head:<14}" + "".join(f"{f'θ4={w:g}':>32}" for w in omega4))
    for key in table.printed:
        column, model = key
        label = f"{_COLUMN_LABEL[column]} {_MODEL_LABEL[model]}"
        cells = "".join(
            f"{table.printed[key][i]:>10.1f}{table.computed[key][i]:>11.2f}"
            f"{100 * table.relative[key][i]:>+10.3f}%" for i in range(len(omega4)))
        lines.append(f"  {label:<14}{cells}")
    units = ", ".join(f"{_COLUMN_LABEL[c]} {_u(u, lang)}" for c, u in TABLE_1_COLUMNS.items())
    lines.append("  " + ("(paper, computed, difference; units: " if lang == "en"
                         else "(статья, расчёт, расхождение; единицы: ") + units + ")")
    lines.append(_t("worst", lang))
    for key, worst in table.worst().items():
        label = f"{_COLUMN_LABEL[key[0]]} {_MODEL_LABEL[key[1]]}"
        lines.append(f"  {label:<14}{100 * worst:>8.3f} %")
    overall = max(table.worst().values())
    lines.append(("  all entries within " if lang == "en" else "  все значения в пределах ")
                 + f"{100 * overall:.3f} %")
    return lines


def _energy_lines(study: ImpactStudy, lang: Lang) -> list[str]:
    lines = [f"{_t('energy', lang)} ({_t('energy_head', lang)})"]
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
                lines.append("    " + _t("friction_bad", lang).format(
                    model=_MODEL_LABEL[model], w4=omega4))
    s = study.slip
    exists = study.position.exists
    if exists.any():
        lines += ["", _t("slip_head", lang), "  " + _t("slip_body", lang).format(
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
            "reason": [REASONS[int(v)][0] for v in p.reason],
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
