"""The force section of the coursework report (``docs/forces.md``).

Present when the table has a ``masses:`` or ``loads:`` section and a kinematic model: the
input speed is the table's ``general: {omega: W}`` (rad/s of the crank, mm/s of an
actuator), the static analysis (ω = 0) when it gives none. The section holds the extreme
driving torque and where, the table of the largest reaction in every pair, the two checks
(Zhukovsky's lever and the Newton–Euler residuals) and the curves over the cycle.
"""

from __future__ import annotations

import math

from assur.api import Analysis
from assur.assessment import Assessment
from assur.forces.solver import kinetostatics
from assur.kinematics.analysis import analyse
from assur.text import render
from synthesis.app.analysis_forces import summarise
from synthesis.app.analysis_forces_plot import draw_force_curves
from synthesis.app.analysis_forces_render import summary_lines
from synthesis.app.analysis_text import position_text
from synthesis.app.coursework.page import Section, esc, figure, table

__all__ = ["forces_sections"]


def forces_sections(found: Assessment, lang: str, points: int) -> list[Section]:
    """The force section of a report, or none when the table has no force data.

    Parameters
    ----------
    found : Assessment
        The assessed table (its chain carries the force data, its model the dimensions).
    lang : str
        A catalogue language.
    points : int
        Positions over the cycle.

    Returns
    -------
    list of Section
        Empty, or the one section.

    Examples
    --------
    >>> from synthesis.app.assess import assess
    >>> import synthesis
    >>> from pathlib import Path
    >>> table = Path(synthesis.__file__).parents[1] / "input_tables" / "four_bar_gravity.yaml"
    >>> [section.ident for section in forces_sections(assess(table, points=12), "en", 12)]
    ['forces']
    """
    data = found.chain.forces
    if data is None or found.model is None or found.existence is None:
        return []
    from matplotlib.figure import Figure

    omega = found.chain.general.omega or 0.0  # (none stated: the static analysis)
    motion = analyse(found.model, points=points, analogs=True)
    forces = kinetostatics(motion, data, omega)
    result = Analysis(found.model, motion, found.existence,
                      found.chain.general.pressure_angles(found.model), omega, forces)
    summary = summarise(forces, motion.q)
    lines = summary_lines(result, forces, summary, lang)
    at = render("force.report.at_column", lang)
    header = (render("force.report.pair_column", lang), render("force.report.links_column", lang),
              render("force.report.max_r_column", lang), at,
              render("force.report.max_m_column", lang), at)
    rows = [(peak.pair, f"{peak.links[0]} → {peak.links[1]}", _fixed(peak.force.value),
             _where(result, peak.force.at, lang),
             None if peak.moment is None else _fixed(peak.moment.value, 4),
             None if peak.moment is None else _where(result, peak.moment.at, lang))
            for peak in summary.pairs]
    fig = Figure(figsize=(7.0, 5.6))
    torque, pairs = fig.subplots(2, 1, sharex=True)
    draw_force_curves(torque, pairs, result, forces, lang)
    fig.tight_layout()
    title = render("force.report.section", lang)
    body = (f'<p id="forces-omega">{esc(lines[0])}</p>'
            f'<p id="forces-drive">{esc(lines[1].strip())}</p>'
            + table(header, rows, numeric=(2, 4), table_id="forces-reactions")
            + "".join(f"<p>{esc(line.strip())}</p>" for line in lines[3 + len(rows):])
            + figure(fig, title, ident="forces-plot"))
    return [Section("forces", title, body)]


def _fixed(value: float, digits: int = 3) -> str:
    return f"{value:.{digits}f}" if math.isfinite(value) else "–"


def _where(result: Analysis, at: float, lang: str) -> str:
    return position_text(result, at, lang) if math.isfinite(at) else "–"
