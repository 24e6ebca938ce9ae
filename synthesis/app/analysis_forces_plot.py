"""The picture of a force analysis (``assur analyze --forces --plot F.png``).

The mechanism at one position on top; below it the driving torque over the cycle by groups
and by Zhukovsky's lever (the two curves coincide when the analysis is right), and the
magnitude of the reaction in every pair.

Examples
--------
>>> import synthesis
>>> from pathlib import Path
>>> table = Path(synthesis.__file__).parents[1] / "input_tables" / "four_bar_gravity.yaml"
>>> import assur
>>> result = assur.analyse(table, points=36, forces=True, omega=10.0)
>>> len(forces_figure(result, result.forces).axes)
3
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np

from assur.api import Analysis
from assur.forces.solver import ForceAnalysis
from assur.io.files import atomic_write_bytes
from assur.plot.formats import figure_bytes, picture_format
from assur.plot.mechanism import draw_mechanism, figure_for
from assur.text import render

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["draw_force_curves", "forces_figure", "save_forces_png"]

#: Height of each of the two curve panels, inches.
PANEL = 2.6


def forces_figure(result: Analysis, forces: ForceAnalysis, index: int = 0,
                  lang: str = "en") -> Figure:
    """The mechanism at position ``index`` above the drive and the reactions over the cycle.

    Parameters
    ----------
    result : Analysis
        One design (positions shaped ``(N,)``).
    forces : ForceAnalysis
        Its force analysis.
    index : int
        The position the mechanism is drawn at.
    lang : str
        Language of the titles and labels.

    Returns
    -------
    matplotlib.figure.Figure
        Not attached to pyplot.
    """
    fig, ax = figure_for(result.motion)
    draw_mechanism(result.motion, index, ax, lang=lang)
    width, height = fig.get_size_inches()
    total = height + 2 * PANEL + 0.6
    fig.set_size_inches(width, total)
    ax.set_position((0.1, (2 * PANEL + 0.6) / total, 0.85, (height - 0.5) / total))
    torque = fig.add_axes((0.1, (PANEL + 0.6) / total, 0.85, (PANEL - 0.7) / total))
    pairs = fig.add_axes((0.1, 0.45 / total, 0.85, (PANEL - 0.7) / total))
    draw_force_curves(torque, pairs, result, forces, lang)
    return fig


def draw_force_curves(torque: Axes, pairs: Axes, result: Analysis,
                      forces: ForceAnalysis, lang: str = "en") -> None:
    """The drive over the cycle (by groups and by the lever) on ``torque``, the magnitude of
    every reaction on ``pairs``.

    Parameters
    ----------
    torque, pairs : matplotlib.axes.Axes
        Where to draw.
    result : Analysis
        The kinematics (its positions and kind of input).
    forces : ForceAnalysis
        Of one design.
    lang : str
        Language of the titles and labels.
    """
    q = result.motion.q
    x = np.degrees(q) if result.crank else q
    drive = "force.plot.driving_torque" if result.crank else "force.plot.driving_force"
    torque.plot(x, forces.driving, lw=1.6, label=render("force.plot.groups", lang))
    torque.plot(x, forces.driving_lever, "--", lw=1.0, label=render("force.plot.lever", lang))
    torque.set_ylabel(render(drive, lang))
    torque.set_title(render("force.plot.title", lang, omega=f"{forces.omega:g}",
                            unit=render("force.report.rad_s" if result.crank
                                        else "force.report.mm_s", lang)), fontsize=10)
    torque.legend(fontsize=8)
    for pair, reaction in forces.reactions.items():
        pairs.plot(x, np.hypot(reaction.x, reaction.y), lw=1.0, label=str(pair))
    pairs.set_ylabel(render("force.plot.reactions", lang))
    pairs.set_xlabel(render("plot.crank_angle_deg" if result.crank
                            else "plot.actuator_length_mm", lang))
    pairs.legend(fontsize=7, ncol=min(6, max(1, len(forces.reactions))))
    for axes in (torque, pairs):
        axes.grid(True, lw=0.3, alpha=0.5)


def save_forces_png(result: Analysis, forces: ForceAnalysis,
                    path: str | os.PathLike[str], index: int = 0, *, lang: str = "en",
                    dpi: int = 110) -> None:
    """Write :func:`forces_figure` atomically, in the format of the file's ending (PNG, SVG,
    PDF or JPEG).

    Raises
    ------
    PictureFormatError
        For another ending.
    OSError
        When the file cannot be written.
    """
    fmt = picture_format(path)
    atomic_write_bytes(path, figure_bytes(forces_figure(result, forces, index, lang), fmt, dpi=dpi))
