"""Text (in any language of the catalogue) and JSON reports of a run of the case."""

from __future__ import annotations

import math
from typing import Any

from assur.kinematics.dyads import reason_text
from assur.text import Message, languages, render
from synthesis.cases.fourbar_velocity_ratio.check import CheckResult
from synthesis.cases.fourbar_velocity_ratio.conditions import Design, Request, condition_residuals
from synthesis.cases.fourbar_velocity_ratio.modern_solver import min_transmission_angle
from synthesis.cases.fourbar_velocity_ratio.study import Study

__all__ = ["message_dict", "no_solution_text", "summary", "to_dict"]

def _t(key: str, lang: str, **values: Any) -> str:
    return render(f"case.fourbar.report.{key}", lang, **values)


def _request_lines(request: Request, lang: str) -> list[str]:
    parts = [f"n* = {request.n_star:g}", f"ψ′ = {math.degrees(request.psi1):g}°"]
    if request.e is not None:
        parts.insert(0, f"e = {request.e:g}")
    if request.delta is not None:
        parts.append(f"δ = {request.delta:g} (n_end = {request.n_star * (1 - request.delta):g})")
    if request.psi2 is not None:
        parts.append(f"ψ″ = {math.degrees(request.psi2):g}°")
    stroke = "stroke_forward" if request.n_star > 0 else "stroke_return"
    head = _t("request", lang, form=_t("form_" + request.form, lang), stroke=_t(stroke, lang),
              frame=_t("frame", lang))
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
    lines = [_t("check", lang, k=check.samples,
                verdict=_t("passed" if check.passed else "failed", lang))]
    if math.isfinite(check.peak):
        lines.append("  " + _t("peak", lang, p=check.peak, a=math.degrees(check.peak_angle),
                               n1=check.ratio_theta1, n3=check.ratio_theta3, z=check.zone_low))
    if math.isfinite(check.min_transmission):
        lines.append("  " + _t("kind", lang, g=_grashof(check.grashof, lang),
                               a=render("case.common.yes" if check.assembles else "case.common.no",
                                        lang),
                               m=check.worst_margin, mu=math.degrees(check.min_transmission),
                               at=math.degrees(check.min_transmission_angle)))
    for code, values in check.failures:
        shown = dict(values)
        if code == "grashof":
            shown["kind"] = _grashof(str(shown["kind"]), lang)
        if code == "assembly":
            shown["why"] = reason_text(int(shown["reason_code"]), lang)
        lines.append("  ✗ " + render(f"case.fourbar.failure.{code}", lang, **shown))
    return lines


def _grashof(kind: str, lang: str) -> str:
    """The Grashof kind of a four-bar (``"crank-rocker"``, ``"non-Grashof"``) in ``lang``."""
    return render("case.fourbar.grashof." + kind.lower().replace("-", "_"), lang)


def summary(study: Study, lang: str = "en") -> str:
    """The report as text in ``lang`` (any language of :func:`assur.text.languages`)."""
    lines = [_t("title", lang), "", *_request_lines(study.request, lang), ""]
    if study.modern is not None:
        m = study.modern
        lines += [_t("modern", lang),
                  "  " + _t("designs", lang, k=len(m.designs), s=m.seconds, n=m.evaluations)]
        for i, (design, check) in enumerate(zip(m.designs, study.modern_checks), start=1):
            lines.append("  " + _t("design", lang, i=i))
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
        lines.append(_t("paper", lang))
        if p.design is None:
            if p.reason is not None:
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
    """A message for JSON: its code and its wording in every language."""
    if message is None:
        return None
    return {"code": message.code, **{lang: message.text(lang) for lang in languages()}}


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
