"""Text (English, Russian) and JSON reports of a run of the case."""

from __future__ import annotations

import math
from typing import Any

from assur import REASONS
from synthesis.cases.fourbar_velocity_ratio.check import CheckResult
from synthesis.cases.fourbar_velocity_ratio.conditions import Design, Request, condition_residuals
from synthesis.cases.fourbar_velocity_ratio.messages import Message
from synthesis.cases.fourbar_velocity_ratio.modern_solver import min_transmission_angle
from synthesis.cases.fourbar_velocity_ratio.study import Study

__all__ = ["message_dict", "no_solution_text", "summary", "to_dict"]

_TEXT: dict[str, dict[str, str]] = {
    "title": {"en": "Four-bar for a prescribed velocity ratio over a zone",
              "ru": "Шарнирный четырёхзвенник с заданным передаточным отношением на участке"},
    "form_paper": {"en": "paper's form: e, n*, δ, ψ′ given; c, r, θ2 and ψ″ found",
                   "ru": "постановка статьи: заданы e, n*, δ, ψ′; ищутся c, r, θ2 и ψ″"},
    "form_delta": {"en": "variant: e, n*, ψ′, ψ″ given; c, r, θ2 and δ found",
                   "ru": "вариант: заданы e, n*, ψ′, ψ″; ищутся c, r, θ2 и δ"},
    "form_crank": {"en": "variant: n*, δ, ψ′, ψ″ given; c, r, θ2 and e found",
                   "ru": "вариант: заданы n*, δ, ψ′, ψ″; ищутся c, r, θ2 и e"},
    "stroke_fwd": {"en": "forward stroke (n > 0)", "ru": "прямой ход (n > 0)"},
    "stroke_ret": {"en": "return stroke (n < 0)", "ru": "обратный ход (n < 0)"},
    "request": {"en": "Request", "ru": "Задание"},
    "frame": {"en": "lengths divided by the frame length S = 1",
              "ru": "длины отнесены к длине стойки S = 1"},
    "modern": {"en": "Modern solver (grid scan of the crank-rocker domain + root finding)",
               "ru": "Современный решатель (сетка по области кривошипно-коромысловых "
                     "механизмов + поиск корня)"},
    "paper": {"en": "Paper's scheme (nested false position, steps a–p)",
              "ru": "Схема статьи (вложенные методы ложного положения, шаги a–p)"},
    "designs": {"en": "{k} design(s), {s:.3f} s, {n} evaluations",
                "ru": "решений: {k}, {s:.3f} с, вычислений: {n}"},
    "design": {"en": "design {i}", "ru": "решение {i}"},
    "residual": {"en": "conditions (7),(8),(12),(13): largest |residual| = {v:.2e} "
                       "(relative to n*: {w:.1e})",
                 "ru": "условия (7),(8),(12),(13): наибольшая |невязка| = {v:.2e} "
                       "(относительно n*: {w:.1e})"},
    "mu": {"en": "smallest transmission angle {m:.2f}°",
           "ru": "наименьший угол передачи {m:.2f}°"},
    "check": {"en": "independent check ({k} positions, circle intersection)",
              "ru": "независимая проверка ({k} положений, пересечение окружностей)"},
    "passed": {"en": "CONFIRMED", "ru": "ПОДТВЕРЖДЕНО"},
    "failed": {"en": "NOT CONFIRMED", "ru": "НЕ ПОДТВЕРЖДЕНО"},
    "peak": {"en": "peak n = {p:.12g} at θ = {a:.6f}°; n(θ1) = {n1:.12g}, n(θ3) = {n3:.12g}; "
                   "lowest in the zone {z:.9g}",
             "ru": "максимум n = {p:.12g} при θ = {a:.6f}°; n(θ1) = {n1:.12g}, "
                   "n(θ3) = {n3:.12g}; наименьшее на участке {z:.9g}"},
    "kind": {"en": "{g}, assembles over the whole turn: {a} (least margin {m:.3g}); "
                   "smallest transmission angle {mu:.2f}° at θ = {at:.1f}°",
             "ru": "{g}, собирается на всём обороте: {a} (наименьший запас {m:.3g}); "
                   "наименьший угол передачи {mu:.2f}° при θ = {at:.1f}°"},
    "rejected": {"en": "roots of the conditions that are not the design asked for:",
                 "ru": "корни условий, не являющиеся искомым механизмом:"},
    "none": {"en": "no design: {r}", "ru": "решения нет: {r}"},
    "paper_root": {"en": "root reached: {s:.3f} s, {n} evaluations, false-position iterations "
                         "θ2/c/r = {i}",
                   "ru": "найден корень: {s:.3f} с, вычислений: {n}, итераций ложного "
                         "положения θ2/c/r = {i}"},
    "wrong_root": {"en": "WRONG ROOT: {d}", "ru": "НЕВЕРНЫЙ КОРЕНЬ: {d}"},
    "agrees": {"en": "agrees with modern design {k} to {d:.1e} (max of |Δc|, |Δr|, |Δθ2|)",
               "ru": "совпадает с решением {k} современного решателя с точностью {d:.1e} "
                     "(наибольшее из |Δc|, |Δr|, |Δθ2|)"},
    "verdict_ok": {"en": "Verdict: design found and confirmed by the independent check.",
                   "ru": "Итог: механизм найден и подтверждён независимой проверкой."},
    "verdict_bad": {"en": "Verdict: no confirmed design.",
                    "ru": "Итог: подтверждённого механизма нет."},
    "yes": {"en": "yes", "ru": "да"},
    "no": {"en": "no", "ru": "нет"},
}

_KINDS = {"crank-rocker": "кривошипно-коромысловый", "double-crank": "двухкривошипный",
          "double-rocker": "двухкоромысловый", "rocker-crank": "коромыслово-кривошипный",
          "change-point": "переходный (s + l = p + q)", "non-Grashof": "не удовлетворяет Грасгофу"}

_FAILURES = {
    "grashof": {"en": "not a crank-rocker: {kind}", "ru": "не кривошипно-коромысловый: {kind}"},
    "assembly": {"en": "does not assemble at θ = {theta_deg:.2f}°: {why}",
                 "ru": "не собирается при θ = {theta_deg:.2f}°: {why}"},
    "peak_value": {"en": "peak {found:.12g}, wanted {wanted:.12g}",
                   "ru": "максимум {found:.12g}, требуется {wanted:.12g}"},
    "peak_angle": {"en": "peak at {found_deg:.6f}°, wanted at θ2 = {wanted_deg:.6f}°",
                   "ru": "максимум при {found_deg:.6f}°, требуется при θ2 = {wanted_deg:.6f}°"},
    "end_theta1": {"en": "n(θ1) = {found:.12g}, wanted {wanted:.12g}",
                   "ru": "n(θ1) = {found:.12g}, требуется {wanted:.12g}"},
    "end_theta3": {"en": "n(θ3) = {found:.12g}, wanted {wanted:.12g}",
                   "ru": "n(θ3) = {found:.12g}, требуется {wanted:.12g}"},
    "zone_band": {"en": "the ratio falls to {found:.9g} inside the zone, below n_end = "
                        "{wanted:.9g}",
                  "ru": "отношение падает до {found:.9g} внутри участка, ниже n_end = "
                        "{wanted:.9g}"},
}


def _t(key: str, lang: str, **values: Any) -> str:
    return _TEXT[key][lang].format(**values)


def _request_lines(request: Request, lang: str) -> list[str]:
    parts = [f"n* = {request.n_star:g}", f"ψ′ = {math.degrees(request.psi1):g}°"]
    if request.e is not None:
        parts.insert(0, f"e = {request.e:g}")
    if request.delta is not None:
        parts.append(f"δ = {request.delta:g} (n_end = {request.n_star * (1 - request.delta):g})")
    if request.psi2 is not None:
        parts.append(f"ψ″ = {math.degrees(request.psi2):g}°")
    stroke = "stroke_fwd" if request.n_star > 0 else "stroke_ret"
    head = (f"{_t('request', lang)} ({_t('form_' + request.form, lang)}; {_t(stroke, lang)}; "
            f"{_t('frame', lang)}):")
    return [head, "  " + ", ".join(parts)]


def _design_lines(design: Design, lang: str) -> list[str]:
    v = design.as_dict()
    residuals = condition_residuals(design)
    worst = max(abs(residuals[k]) for k in ("n(θ2) − n*", "dn/dθ(θ2)", "n(θ1) − n_end",
                                            "n(θ3) − n_end"))
    angles = (f"θ1 = {v['theta1_deg']:.8f}°, θ2 = {v['theta2_deg']:.8f}°, "
              f"θ3 = {v['theta3_deg']:.8f}°, ψ″ = {v['psi2_deg']:.8f}°, δ = {v['delta']:.12g}")
    return [f"e = {v['e']:.12g}, c = {v['c']:.12g}, r = {v['r']:.12g}", angles,
            _t("residual", lang, v=worst, w=worst / abs(design.n_star)),
            _t("mu", lang, m=math.degrees(min_transmission_angle(design)))]


def _check_lines(check: CheckResult, lang: str) -> list[str]:
    head = f"{_t('check', lang, k=check.samples)}: " + _t("passed" if check.passed else "failed",
                                                           lang)
    lines = [head]
    if math.isfinite(check.peak):
        lines.append("  " + _t("peak", lang, p=check.peak, a=math.degrees(check.peak_angle),
                               n1=check.ratio_theta1, n3=check.ratio_theta3, z=check.zone_low))
    kind = check.grashof if lang == "en" else _KINDS.get(check.grashof, check.grashof)
    if math.isfinite(check.min_transmission):
        lines.append("  " + _t("kind", lang, g=kind, a=_t("yes" if check.assembles else "no", lang),
                               m=check.worst_margin, mu=math.degrees(check.min_transmission),
                               at=math.degrees(check.min_transmission_angle)))
    for code, values in check.failures:
        shown = dict(values)
        if code == "grashof" and lang == "ru":
            shown["kind"] = _KINDS.get(str(shown["kind"]), shown["kind"])
        if code == "assembly":
            shown["why"] = REASONS[int(shown["reason_code"])][0 if lang == "en" else 1]
        lines.append("  ✗ " + _FAILURES[code][lang].format(**shown))
    return lines


def summary(study: Study, lang: str = "en") -> str:
    """The report as text in English (``en``) or Russian (``ru``)."""
    lines = [_t("title", lang), "", *_request_lines(study.request, lang), ""]
    if study.modern is not None:
        m = study.modern
        lines += [_t("modern", lang) + ":",
                  "  " + _t("designs", lang, k=len(m.designs), s=m.seconds, n=m.evaluations)]
        for i, (design, check) in enumerate(zip(m.designs, study.modern_checks), start=1):
            lines.append(f"  {_t('design', lang, i=i)}:")
            lines += ["    " + s for s in _design_lines(design, lang)]
            lines += ["    " + s for s in _check_lines(check, lang)]
        if m.rejected:
            lines.append("  " + _t("rejected", lang))
            lines += [f"    c = {d.c:.8g}, r = {d.r:.8g}, θ2 = {math.degrees(d.theta2):.4f}°: "
                      f"{why.text(lang)}" for d, why in m.rejected]
        if m.reason:
            lines.append("  " + _t("none", lang, r=m.reason.text(lang)))
        lines.append("")
    if study.paper is not None:
        p = study.paper
        lines.append(_t("paper", lang) + ":")
        if p.design is None:
            lines.append("  " + p.reason.text(lang))
        else:
            iterations = "/".join(str(p.iterations[k]) for k in ("theta2", "c", "r"))
            lines.append("  " + _t("paper_root", lang, s=p.seconds, n=p.evaluations,
                                   i=iterations))
            lines += ["    " + s for s in _design_lines(p.design, lang)]
            if p.defect:
                lines.append("    " + _t("wrong_root", lang, d=p.defect.text(lang)))
            if study.paper_check is not None:
                lines += ["    " + s for s in _check_lines(study.paper_check, lang)]
            if study.paper_match is not None:
                lines.append("    " + _t("agrees", lang, k=study.paper_match + 1,
                                         d=study.paper_distance))
        lines.append("")
    lines.append(_t("verdict_ok" if study.passed else "verdict_bad", lang))
    return "\n".join(lines) + "\n"


def no_solution_text(reason: Message, lang: str = "en") -> str:
    """The answer to a request that no crank-rocker can meet."""
    return f"{_t('title', lang)}\n\n{_t('none', lang, r=reason.text(lang))}\n"


def message_dict(message: Message | None) -> dict[str, str] | None:
    """A message for JSON: its code and both wordings."""
    if message is None:
        return None
    return {"code": message.code, "en": message.text("en"), "ru": message.text("ru")}


def _request_dict(request: Request) -> dict[str, Any]:
    return {"form": request.form, "e": request.e, "n_star": request.n_star,
            "delta": request.delta, "psi1_deg": math.degrees(request.psi1),
            "psi2_deg": None if request.psi2 is None else math.degrees(request.psi2)}


def _design_dict(design: Design, check: CheckResult | None) -> dict[str, Any]:
    out: dict[str, Any] = dict(design.as_dict())
    out["residuals"] = condition_residuals(design)
    out["min_transmission_deg"] = math.degrees(min_transmission_angle(design))
    if check is not None:
        out["check"] = check.as_dict()
    return out


def to_dict(study: Study) -> dict[str, Any]:
    """The results as plain data for JSON."""
    out: dict[str, Any] = {"case": "fourbar-velocity-ratio", "request": _request_dict(
        study.request), "method": study.method, "passed": study.passed}
    if study.modern is not None:
        m = study.modern
        out["modern"] = {
            "designs": [_design_dict(d, c) for d, c in zip(m.designs, study.modern_checks)],
            "rejected": [{"design": d.as_dict(), "why": message_dict(why)}
                         for d, why in m.rejected],
            "reason": message_dict(m.reason), "evaluations": m.evaluations, "seconds": m.seconds}
    if study.paper is not None:
        p = study.paper
        out["paper"] = {
            "design": None if p.design is None else _design_dict(p.design, study.paper_check),
            "wrong_root": message_dict(p.defect), "reason": message_dict(p.reason),
            "evaluations": p.evaluations,
            "iterations": p.iterations, "seconds": p.seconds,
            "matches_modern_design": None if study.paper_match is None else study.paper_match + 1,
            "distance_to_modern": None if study.paper_match is None else study.paper_distance}
    return out
