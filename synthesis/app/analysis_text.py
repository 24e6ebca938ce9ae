"""The text report of a kinematic analysis (``assur analyze``), in any catalogue language.

The existence verdict of every group (with the intervals where it cannot be assembled), the
ranges of the outputs, the largest pressure angles and the swing of every revolute joint.
"""

from __future__ import annotations

import math

import numpy as np

from assur import joint_rotations, pressure_angles
from assur.api import Analysis
from assur.kinematics.analysis import unwrap, values
from assur.kinematics.existence import CONDITIONS
from assur.kinematics.higher.kind import HigherGroupSolution
from assur.kinematics.laws import STROKE
from assur.kinematics.model import KinematicModel
from assur.kinematics.reasons import reason_text
from assur.records import moving_links
from assur.text import render

__all__ = ["analysis_text", "input_laws", "modes_lines", "position_text"]


def position_text(result: Analysis, value: float, lang: str = "en") -> str:
    """An input position as the report writes it: ``φ = 12.50°`` or ``l = 40.000 mm``
    (``мм`` in Russian)."""
    drive = result.model.drive
    if result.crank:
        return f"{'t' if drive == 'laws' else 'φ'} = {math.degrees(value):.2f}°"
    return f"{'s' if drive == 'slider' else 'l'} = {value:.3f} {render('analyze.unit_mm', lang)}"


def input_laws(model: KinematicModel, n: int, lang: str) -> list[str]:
    """The lines of the inputs of a cycle of laws: the cycle, then each input's law."""
    lines = [render("analyze.laws", lang, k=len(model.laws), n=n)]
    for label, law in model.laws.items():
        group = model.group(label)
        if not law.linear:
            lines.append("  " + render("analyze.law_crank", lang, group=label, link=group.i,
                                       phase=f"{math.degrees(law.phase):g}",
                                       ratio=f"{law.ratio:+d}"))
            continue
        lo, hi = (float(np.max(model.params[group.column(c)])) for c in STROKE)
        code = "analyze.law_table" if law.table else "analyze.law_harmonic"
        lines.append("  " + render(code, lang, group=label, lo=lo, hi=hi, rows=len(law.table),
                                   phase=f"{math.degrees(law.phase):g}", ratio=law.ratio))
    return lines


def analysis_text(result: Analysis, lang: str = "en") -> str:
    """The text report of one analysis.

    Parameters
    ----------
    result : Analysis
    lang : str
        A catalogue language.

    Returns
    -------
    str
        Several lines, without a final newline.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> import assur
    >>> result = assur.analyse(tables / "course_11_link.yaml", points=36)
    >>> analysis_text(result).splitlines()[0].split(" (")[0]
    'Kinematic analysis: DGTU example, fig. 1.25'
    """
    model, motion, report = result.model, result.motion, result.existence
    lines = [render("analyze.title", lang, name=model.name, source=model.source)]
    n = motion.q.size
    if model.drive == "laws":
        lines += input_laws(model, n, lang)
    elif model.drive == "slider":
        lines.append(render("analyze.slider_input", lang, link=model.groups[0].i,
                            lo=model.input_range[0], hi=model.input_range[1], n=n))
    elif result.crank:
        turning = (render("analyze.ccw", lang) if model.direction > 0
                   else render("analyze.cw", lang))
        lines.append(render("analyze.crank", lang, link=model.groups[0].i, n=n, dir=turning))
    else:
        lines.append(render("analyze.actuator", lang, lo=model.input_range[0],
                            hi=model.input_range[1], n=n))
    lines += ["", render("analyze.existence", lang)]
    units = {"mm": render("analyze.unit_mm", lang), "deg": "°"}
    verdicts = {"assembles": render("analyze.assembles", lang),
                "reached": render("analyze.reached", lang),
                "fails": render("analyze.fails", lang),
                "not evaluated": render("analyze.not_evaluated", lang)}
    for group in report.groups:
        reached = group.verdict == "assembles" and not group.evaluated.all()
        title = model.group(group.label).title(lang)
        lines.append(f"  {title:<20} {verdicts['reached' if reached else group.verdict]}; "
                     + render("analyze.margin", lang, m=group.min_margin, d=group.delta))
        lines.append(f"  {'':<20} {CONDITIONS[group.kind]}")
        for item in group.intervals:
            lines.append("    " + render("analyze.interval", lang,
                                         a=position_text(result, item.start, lang),
                                         b=position_text(result, item.end, lang),
                                         why=reason_text(item.reason, lang),
                                         v=item.shortfall, unit=units[item.unit],
                                         w=position_text(result, item.worst_at, lang)))
        skipped = int((~group.evaluated).sum())
        if skipped and group.evaluated.any():
            lines.append("    " + render("analyze.skipped", lang, n=skipped))
    broken = int((report.first >= 0).sum())
    lines.append(render("analyze.verdict_ok", lang) if broken == 0 else
                 render("analyze.verdict_bad", lang, n=broken, total=n))
    lines += modes_lines(result, lang)
    lines += ["", render("analyze.outputs", lang)]
    mm = render("analyze.unit_mm", lang)
    for link in moving_links(model):
        angle = np.degrees(unwrap(values(motion.link_angle(link))))
        lines.append(f"  {render('analyze.link', lang, link=link):<34} {_range(angle, '°')}")
    for pid, slider in motion.sliders.items():
        label = render("analyze.slider", lang, slider=slider.slider, carrier=slider.carrier,
                       pair=pid)
        lines.append(f"  {label:<34} {_range(values(slider.s), ' ' + mm)}")
    for name, point in motion.tracing.items():
        z = values(point)
        lines.append(f"  {render('analyze.trace', lang, name=name):<34} "
                     f"x {_range(z.real, ' ' + mm)}, y {_range(z.imag, ' ' + mm)}")
    lines += ["", *_pressure_lines(result, lang)]
    lines += ["", render("analyze.rotations", lang)]
    for turn in joint_rotations(motion):
        swing = (render("analyze.full", lang) if turn.full_turn
                 else f"{math.degrees(turn.swing):8.2f}°")
        lines.append(f"  {turn.pair!s:<8} {turn.links[0]}–{turn.links[1]:<4} "
                     f"{turn.group:<12} {swing}")
    return "\n".join(lines)


def modes_lines(result: Analysis, lang: str) -> list[str]:
    """Every real assembly mode at the sketch of each triad and class IV group, the drawn
    one marked, and what became of the drawn mode over the cycle.

    Parameters
    ----------
    result : Analysis
    lang : str

    Returns
    -------
    list of str
        The report's lines (none for a mechanism of dyads only).
    """
    lines: list[str] = []
    for label, sol in result.motion.solutions.items():
        if not isinstance(sol, HigherGroupSolution):
            continue
        lines += ["", render("higher.report.modes", lang, group=label)]
        lines += ["  " + note.text(lang) for note in sol.follow.notes()]
        for k, mode in enumerate(sol.modes(), start=1):
            joints = ", ".join(f"{pid} ({z.real:.4f}, {z.imag:.4f})"
                               for pid, z in mode.joints.items())
            mark = render("higher.report.drawn", lang) if mode.drawn else ""
            lines.append("  " + render("higher.report.mode", lang, k=k, mark=mark,
                                       angle=math.degrees(mode.angle), margin=mode.margin,
                                       sign=mode.det_sign, joints=joints))
    return lines


def _pressure_lines(result: Analysis, lang: str) -> list[str]:
    """The largest pressure angle of every L1/L2 group with a two-hinge rod."""
    angles = pressure_angles(result.motion)
    if not angles:
        return [render("analyze.no_pressure", lang)]
    lines = [render("analyze.pressure", lang)]
    for item in angles:
        at = int(np.nanargmax(item.alpha)) if np.isfinite(item.alpha).any() else 0
        allowed = result.allowed_pressure[item.label]
        over = math.degrees(item.maximum) > allowed
        lines.append("  " + render("analyze.alpha", lang, label=item.label, pair=item.pair,
                                   a=math.degrees(item.maximum),
                                   at=position_text(result, float(result.motion.q[at]), lang),
                                   allowed=allowed,
                                   verdict=render("analyze.alpha_over" if over
                                                  else "analyze.alpha_within", lang)))
    return lines


def _range(data: np.ndarray, unit: str) -> str:
    data = np.asarray(data, dtype=float)
    if not np.isfinite(data).any():
        return "—"
    lo, hi = float(np.nanmin(data)), float(np.nanmax(data))
    return f"{lo:9.3f} … {hi:9.3f}{unit} (Δ {hi - lo:.3f})"
