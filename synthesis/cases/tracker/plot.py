"""Pictures of the tracker case: the design charts and the mechanism at both stroke ends.

matplotlib is imported only when a picture is drawn, and only its object API is used (no
pyplot, nothing is shown); files are written atomically.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from assur.text import render
from synthesis.cases.figures import write_figure
from synthesis.cases.tracker.geometry import proportions, stroke
from synthesis.cases.tracker.model import TrackerMotion
from synthesis.cases.tracker.patent import EXAMPLE, SERIES
from synthesis.cases.tracker.study import Study

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["chart_figure", "mechanism_figure", "plot_mechanism", "save_plots"]

_CHART_K5 = (1.8, 2.0, 2.2)


def _label(key: str, lang: str, **data: float) -> str:
    return render(f"case.tracker.plot.{key}", lang, **data)


def _printed(quantity: str, k5: float | None) -> tuple[list[float], list[float]]:
    matching = [series for series in SERIES if series.quantity == quantity
                and (k5 is None or series.k5 == k5)]
    drawn = [series for series in matching if series.source != "Tabel 1"]
    if quantity in ("d", "k_d") and not any(series.values for series in drawn):
        drawn = matching
    points = [(k2, value) for series in drawn for k2, value in series.values.items()]
    return [p[0] for p in points], [p[1] for p in points]


def chart_figure(study: Study, lang: str = "en") -> Figure:
    """The design charts: the stroke against b_min, and every quantity against k2.

    Curves for several ``k5`` (the task's and the patent's 1.8, 2, 2.2); where the task's
    stroke is the patent's 210°, the printed values are drawn as markers.
    """
    from matplotlib.figure import Figure

    task = study.task
    fig = Figure(figsize=(14, 8.5))
    axes = fig.subplots(2, 3, gridspec_kw={"left": 0.05, "right": 0.99, "bottom": 0.06,
                                            "top": 0.96, "wspace": 0.22, "hspace": 0.28})
    k2 = np.linspace(min(task.k2) - 0.1, max(task.k2) + 0.1, 201)
    k5s = sorted(set(task.k5) | set(_CHART_K5))
    a_deg = math.degrees(task.stroke)
    patent = math.isclose(a_deg, EXAMPLE["stroke_deg"])

    ax = axes[0, 0]
    b = np.radians(np.linspace(5.0, 85.0, 321))
    for value in task.k2:
        ax.plot(np.degrees(b), np.degrees(stroke(b, value)), label=f"k2 = {value:g}")
    ax.axhline(a_deg, color="k", lw=0.8, ls="--")
    ax.axvline(math.degrees(task.min_transmission), color="r", lw=0.8, ls=":",
               label=f"b_min.ad ({_label('allowed', lang)})")
    table_b = np.degrees(study.table.values.b_min[:, 0])
    ax.plot(table_b, np.full_like(table_b, a_deg), "ko", ms=4)
    ax.set(title=_label("stroke", lang), xlabel=_label("b", lang), ylabel=_label("a", lang))
    ax.legend(fontsize=7)

    curves = {k5: proportions(task.stroke, k2, k5) for k5 in k5s}
    one = curves[k5s[0]]
    ax = axes[0, 1]
    ax.plot(k2, np.degrees(one.b_min), label="b_min")
    ax.axhline(math.degrees(task.min_transmission), color="r", lw=0.8, ls=":",
               label=_label("allowed", lang))
    if patent:
        ax.plot(*_printed("b_min", None), "kx", label=_label("patent", lang))
    ax.set(title=_label("bmin", lang), xlabel=_label("k2", lang), ylabel=_label("deg", lang))
    ax.legend(fontsize=7)

    ax = axes[0, 2]
    ax.plot(k2, np.degrees(one.c), label="c")
    ax.plot(k2, np.degrees(one.d), label="d")
    if patent:
        for quantity in ("c", "d"):
            ax.plot(*_printed(quantity, None), "kx")
    ax.set(title=_label("cd", lang), xlabel=_label("k2", lang), ylabel=_label("deg", lang))
    ax.legend(fontsize=7)

    panels = ((axes[1, 0], ("k_d", "k_i"), _label("kdi", lang)),
              (axes[1, 1], ("k_s",), _label("ks", lang)),
              (axes[1, 2], ("k_g",), _label("kg", lang)))
    for ax, quantities, title in panels:
        for index, k5 in enumerate(k5s):
            values = curves[k5]
            for quantity, style in zip(quantities, ("-", "--"), strict=False):
                ax.plot(k2, getattr(values, quantity), style, color=f"C{index}",
                        label=f"{quantity}, k5 = {k5:g}")
                if patent:
                    ax.plot(*_printed(quantity, k5), "x", color=f"C{index}",
                            label=_label("patent", lang) if index == 0 and style == "-" else None)
        ax.set(title=title, xlabel=_label("k2", lang), ylabel=_label("ratio", lang))
    axes[1, 1].axhline(task.actuator_stroke / task.l1, color="r", lw=0.8, ls=":",
                       label=_label("allowed", lang))
    axes[1, 2].axhline(task.min_clearance / task.l1, color="r", lw=0.8, ls=":",
                       label=_label("required", lang))
    for ax, _, _ in panels:
        ax.legend(fontsize=7)
    return fig


def plot_mechanism(motion: TrackerMotion, ax: Axes, *, title: str, body: float,
                   lang: str = "en", min_clearance: float | None = None) -> Axes:
    """Draw the mechanism at both ends of the stroke, with the actuator and the post.

    Parameters
    ----------
    motion : TrackerMotion
        The mechanism from the retracted to the extended actuator.
    ax : matplotlib Axes
    title : str
    body : float
        Length of the actuator's cylinder drawn from E (mm).
    lang : str
        A language of the catalogue.
    min_clearance : float, optional
        Draws the required clearance around the post as a dotted circle.

    Returns
    -------
    Axes
    """
    m = motion
    ax.plot(m.b.real, m.b.imag, color="0.7", lw=0.8)
    ax.plot(m.c.real, m.c.imag, color="0.7", lw=0.8)
    base = np.array([complex(m.d[0]), complex(m.a[0]), complex(m.e[0])])
    ax.plot(base.real, base.imag, color="k", lw=1.0)
    for index, colour, label in ((0, "tab:blue", _label("retracted", lang)),
                                 (-1, "tab:red", _label("extended", lang))):
        a, b, c, d, e = (complex(p[index]) for p in (m.a, m.b, m.c, m.d, m.e))
        ax.plot([a.real, b.real], [a.imag, b.imag], color=colour, lw=4, solid_capstyle="round",
                label=label)
        ax.plot([b.real, c.real, d.real], [b.imag, c.imag, d.imag], color=colour, lw=2)
        cylinder = e + (c - e) / abs(c - e) * min(abs(c - e), body)
        ax.plot([e.real, cylinder.real], [e.imag, cylinder.imag], color=colour, lw=6,
                alpha=0.45)
        ax.plot([e.real, c.real], [e.imag, c.imag], color=colour, lw=1.5, ls="--")
        ax.plot([a.real, b.real, c.real, d.real, e.real],
                [a.imag, b.imag, c.imag, d.imag, e.imag], "o", color=colour, ms=4)
    for name, point in (("A", m.a[0]), ("D", m.d[0]), ("E", m.e[0])):
        ax.annotate(name, (point.real, point.imag), textcoords="offset points", xytext=(4, -12))
    ax.plot([0.0], [0.0], "ks", ms=9)
    if min_clearance:
        angle = np.linspace(0.0, 2.0 * np.pi, 181)
        ax.plot(min_clearance * np.cos(angle), min_clearance * np.sin(angle), "k:", lw=0.8,
                label=_label("clear", lang, g=min_clearance))
    ax.set_aspect("equal")
    ax.set(title=title, xlabel=render("case.common.axis.x_mm", lang),
           ylabel=render("case.common.axis.y_mm", lang))
    ax.legend(fontsize=7, loc="lower left")
    return ax


def mechanism_figure(motion: TrackerMotion, *, title: str, body: float, lang: str = "en",
                     min_clearance: float | None = None) -> Figure:
    """A figure with :func:`plot_mechanism`."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 7))
    ax = fig.subplots(gridspec_kw={"left": 0.1, "right": 0.97, "bottom": 0.08, "top": 0.94})
    plot_mechanism(motion, ax, title=title, body=body, lang=lang, min_clearance=min_clearance)
    return fig


def _drawings(study: Study, lang: str) -> list[tuple[str, TrackerMotion, str, float]]:
    out = []
    for name, check in (("chosen", study.chosen), ("refined", study.refined)):
        if check is not None:
            d = check.design
            out.append((name, check.motion, _label("mech", lang, k2=d.k2, k5=d.k5, l1=d.l1,
                                                   a=math.degrees(check.stroke)), d.l_i))
    answer = study.synthesis
    if answer is not None:
        title = _label("mech", lang, k2=answer.k2, k5=answer.k5, l1=answer.task.l1,
                       a=math.degrees(answer.check.stroke)) + " (B1–B5)"
        out.append(("synthesis", answer.check, title, answer.l_i))
    return out


def save_plots(study: Study, directory: str | Path, lang: str = "en", *,
               dpi: int = 120) -> list[Path]:
    """Write the design charts and the designs' drawings as PNG files (``dpi`` dots/inch).

    Returns
    -------
    list of Path
        The files written: ``tracker_charts.png``, then ``tracker_chosen.png``,
        ``tracker_refined.png`` and ``tracker_synthesis.png`` for the designs there are.
    """
    directory = Path(directory)
    paths = [write_figure(chart_figure(study, lang), directory / "tracker_charts.png",
                           dpi=dpi)]
    for name, motion, title, body in _drawings(study, lang):
        paths.append(write_figure(mechanism_figure(motion, title=title, body=body, lang=lang,
                                                   min_clearance=study.task.min_clearance),
                                  directory / f"tracker_{name}.png", dpi=dpi))
    return paths
