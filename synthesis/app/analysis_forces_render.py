"""A force analysis as CSV columns and text (``assur analyze --forces``); its JSON is
:meth:`assur.forces.solver.ForceAnalysis.to_dict`.

Forces are in N (global axes, the force of a pair's first listed link on its second), torques
in N·m (counter-clockwise positive).

Examples
--------
>>> from pathlib import Path
>>> import synthesis
>>> import assur
>>> table = Path(synthesis.__file__).parents[1] / "input_tables" / "slider_crank_press.yaml"
>>> result = assur.analyse(table, points=36, forces=True, omega=10.0)
>>> forces = result.forces
>>> [name for name, _ in forces_columns(forces)][:5]
['driving_torque', 'driving_torque_lever', 'power_balance', 'R_0-1_x', 'R_0-1_y']
>>> forces_text(result, forces, "ru").splitlines()[0]
'Силовой расчёт (кинетостатика): ω = 10 рад/с, g = (0, −9.81) м/с²'
"""

from __future__ import annotations

import math

import numpy as np

from assur.api import Analysis
from assur.forces.solver import ForceAnalysis
from assur.text import render
from synthesis.app.analysis_forces import Extreme, ForceSummary, summarise
from synthesis.app.analysis_text import position_text

__all__ = ["forces_columns", "forces_text"]


def forces_columns(forces: ForceAnalysis) -> list[tuple[str, np.ndarray]]:
    """The CSV columns of a force analysis: the drive, its lever value, the power balance,
    then ``R_<pair>_x``, ``R_<pair>_y`` (and ``_normal``, ``_moment``) of every pair.
    """
    drive = forces.drive
    columns = [(drive, forces.driving), (f"{drive}_lever", forces.driving_lever),
               ("power_balance", forces.power_balance)]
    if len(forces.drivings) > 1:
        columns[1:1] = [(f"{forces.drive_kinds[label]}_{label}", values)
                        for label, values in list(forces.drivings.items())[1:]]
    for pair, r in forces.reactions.items():
        columns += [(f"R_{pair}_x", r.x), (f"R_{pair}_y", r.y)]
        if r.normal is not None and r.moment is not None:
            columns += [(f"R_{pair}_normal", r.normal), (f"R_{pair}_moment", r.moment)]
    return columns


def forces_text(result: Analysis, forces: ForceAnalysis, lang: str = "en") -> str:
    """The force section of the text report (``lang``: a catalogue language): the lines of
    :func:`summary_lines` joined, without a final newline; ``result`` is the kinematics the
    forces were computed at.
    """
    summary = summarise(forces, result.motion.q)
    return "\n".join(summary_lines(result, forces, summary, lang))


def summary_lines(result: Analysis, forces: ForceAnalysis, summary: ForceSummary,
                  lang: str) -> list[str]:
    """The lines of the force section (shared by the text and the coursework reports)."""

    def at(extreme: Extreme) -> str:
        return position_text(result, extreme.at, lang) if math.isfinite(extreme.at) else "—"

    crank = result.crank
    gravity = forces.gravity
    lines = [render("force.report.title", lang, omega=f"{forces.omega:g}",
                    unit=render("force.report.rad_s" if crank else "force.report.mm_s", lang),
                    g=(render("force.report.gravity", lang, gx=_signed(gravity.real),
                              gy=_signed(gravity.imag)) if gravity
                       else render("force.report.no_gravity", lang)))]
    if summary.inputs:
        for effort in summary.inputs:
            code = ("force.report.input_torque" if effort.kind == "driving_torque"
                    else "force.report.input_force")
            lines.append("  " + render(code, lang, group=effort.label, lo=effort.low.value,
                                       lo_at=at(effort.low), hi=effort.high.value,
                                       hi_at=at(effort.high), mean=effort.mean))
    else:
        lines.append("  " + render("force.report.torque" if crank else "force.report.force",
                                   lang, lo=summary.low.value, lo_at=at(summary.low),
                                   hi=summary.high.value, hi_at=at(summary.high),
                                   mean=summary.mean))
    lines.append("  " + render("force.report.reactions", lang))
    for peak in summary.pairs:
        text = render("force.report.pair", lang, pair=peak.pair, a=peak.links[0],
                      b=peak.links[1], r=peak.force.value, at=at(peak.force))
        if peak.moment is not None:
            text += render("force.report.pair_moment", lang, m=peak.moment.value,
                           at=at(peak.moment))
        lines.append("    " + text)
    lines.append("  " + render("force.report.lever", lang, d=summary.balance,
                               rel=summary.balance_relative))
    lines.append("  " + render("force.report.residual", lang, f=summary.residual_force,
                               m=summary.residual_moment))
    for reason, (q, group) in summary.unsolved.items():
        why = render(f"force.reason.{reason.name.lower()}", lang, group=group or "")
        lines.append("  " + render("force.report.unsolved", lang,
                                   n=int(np.count_nonzero(forces.reason == reason)),
                                   total=summary.total, at=position_text(result, q, lang),
                                   why=why))
    return lines


def _signed(value: float) -> str:
    """A number with a typographic minus: ``−9.81``."""
    return f"{value:g}".replace("-", "−")
