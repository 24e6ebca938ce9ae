"""Pictures of the kinematic part of the coursework report (matplotlib, no pyplot state).

* :func:`existence_figure` — the existence margin of every group over the cycle, the
  tolerance δ and the intervals where a group does not assemble;
* :func:`mechanism_figure` — the mechanism at four positions of the cycle, with the paths
  of its joints (drawn by :func:`assur.plot.mechanism.draw_mechanism`);
* :func:`kinematic_figures` — the diagrams of the link angles ψ and the slider
  displacements S over the crank angle, with their first and second analogs
  (dψ/dφ, d²ψ/dφ², dS/dφ, d²S/dφ²), and the pressure angles of the L1/L2 groups.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from assur import ExistenceReport, Jet, KinematicModel, Motion
from assur.text import render
from assur.typing import FloatArray, Value

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["existence_figure", "kinematic_figures", "mechanism_figure"]


def _parts(x: Value, shape: tuple[int, ...]) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Value, first and second analog of a jet (a plain array has zero analogs)."""
    v, d1, d2 = (x.v, x.d1, x.d2) if isinstance(x, Jet) else (x, 0.0, 0.0)
    value, first, second = (np.broadcast_to(np.asarray(part, dtype=float), shape)
                            for part in (v, d1, d2))
    return value, first, second


#: Width of a diagram, inches: the text width of an A4 page, so that it prints at its size.
WIDTH = 7.0
#: Type size of legends and axis labels, points (≥ 9 on paper, the figure not scaled down).
TYPE_PT = 9.0


def _new_figure(size: tuple[float, float]) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=size, layout="constrained")


def _legend_outside(ax: Axes) -> None:
    """The legend to the right of the axes, off the curves."""
    ax.legend(fontsize=TYPE_PT, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              frameon=False)


def _styles(curves: dict[str, np.ndarray], lang: str) -> dict[str, tuple[str, str]]:
    """Legend label and line style of each curve: a curve that coincides with an earlier one
    is dashed and its label says so ("same curve as …"), instead of vanishing under it."""
    from assur.plot.mechanism import coinciding

    span = max((float(np.nanmax(np.abs(v))) for v in curves.values() if np.isfinite(v).any()),
               default=1.0)
    same = coinciding(curves, 1e-6 * max(span, 1.0))
    return {name: (render("plot.same_curve", lang, label=name, other=same[name]), "--")
            if name in same else (name, "-") for name in curves}


def _axis(model: KinematicModel, q: np.ndarray, lang: str) -> tuple[np.ndarray, str]:
    if model.periodic:
        return np.degrees(q), render("plot.cycle_t_deg" if model.drive == "laws"
                                     else "plot.crank_angle_deg", lang)
    return q, render("plot.slider_s_mm" if model.drive == "slider"
                     else "plot.actuator_length_mm", lang)


def existence_figure(report: ExistenceReport, model: KinematicModel, *,
                     lang: str = "en") -> Figure:
    """The existence margins of the groups over the cycle.

    Parameters
    ----------
    report : ExistenceReport
        From :func:`assur.kinematics.existence.check_existence`.
    model : KinematicModel
    lang : str
        Language of the labels.

    Returns
    -------
    matplotlib.figure.Figure
        Not attached to pyplot.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> fig = existence_figure(assur.check_existence(model, points=36), model)
    >>> fig.axes[0].get_title()
    'Existence of the groups over the cycle'
    """
    fig = _new_figure((WIDTH, 3.4))
    ax = fig.add_subplot()
    x, xlabel = _axis(model, report.q, lang)
    margins = {model.group(group.label).title(lang): group.margin for group in report.groups}
    styles = _styles(margins, lang)
    for group, (label, ls) in zip(report.groups, styles.values(), strict=True):
        line = ax.plot(x, group.margin, lw=1.5, label=label, ls=ls)[0]
        if np.isfinite(group.delta) and group.delta > 0:
            ax.axhline(group.delta, color=line.get_color(), lw=0.7, ls=":")
        if group.fails.any():
            ax.fill_between(x, 0, 1, where=group.fails, transform=ax.get_xaxis_transform(),
                            color=line.get_color(), alpha=0.15, lw=0)
    ax.axhline(0.0, color="black", lw=0.8)
    if not report.all_exist:
        ax.plot([], [], color="grey", alpha=0.3, lw=6, label=render("plot.does_not_assemble", lang))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(render("plot.existence_margin", lang))
    ax.set_title(render("plot.existence", lang), fontsize=11)
    ax.grid(alpha=0.3)
    if model.periodic:
        ax.set_xticks(np.arange(0, 361, 45))
        ax.set_xlim(0, 360)
    _legend_outside(ax)
    return fig


def _analog_axes(fig: Figure, xlabel: str, ylabels: tuple[str, str, str]) -> list[Axes]:
    axes = fig.subplots(3, 1, sharex=True)
    for ax, label in zip(axes, ylabels):
        ax.set_ylabel(label, fontsize=TYPE_PT)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(xlabel)
    return list(axes)


def _draw_analogs(axes: list[Axes], x: np.ndarray,
                  curves: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]], lang: str) -> None:
    """Value and analogs of each curve, styled by :func:`_styles`."""
    first = {name: parts[0] for name, parts in curves.items()}
    styles = _styles(first, lang)
    for name, parts in curves.items():
        label, ls = styles[name]
        axes[0].plot(x, first[name], label=label, lw=1.3, ls=ls)
        axes[1].plot(x, np.broadcast_to(parts[1], x.shape), lw=1.3, ls=ls)
        axes[2].plot(x, np.broadcast_to(parts[2], x.shape), lw=1.3, ls=ls)


def kinematic_figures(motion: Motion, *, lang: str = "en") -> list[tuple[str, Figure]]:
    """Kinematic diagrams of one design over the cycle.

    Parameters
    ----------
    motion : Motion
        From :func:`assur.kinematics.analysis.analyse` with ``analogs=True``.
    lang : str
        Language of the labels and captions.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        Captions and figures: link angles, slider displacements (each with both analogs)
        and pressure angles, where the mechanism has them.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=36, analogs=True)
    >>> [caption for caption, _ in kinematic_figures(motion, lang="ru")]
    ['Углы поворота звеньев ψ: аналог скорости, аналог ускорения', 'Углы давления']
    """
    from assur import pressure_angles
    from assur.kinematics.analysis import unwrap

    model = motion.model
    x, xlabel = _axis(model, motion.q, lang)
    figures: list[tuple[str, Figure]] = []
    analogs = f"{render('plot.first_analog', lang)}, {render('plot.second_analog', lang)}"
    crank = {g.i for g in model.groups if g.kind == 0}
    rotating = []
    for link, (_origin, angle) in motion.frames.items():
        if link in crank or link == model.frame:
            continue
        value, first, second = _parts(angle, x.shape)
        psi = unwrap(value)
        if np.isfinite(psi).any() and np.nanmax(psi) - np.nanmin(psi) > 1e-9:
            rotating.append((link, psi, first, second))
    if rotating:
        fig = _new_figure((WIDTH, 7.0))
        axes = _analog_axes(fig, xlabel, ("ψ, °", "dψ/dφ", "d²ψ/dφ²"))
        labels = {render("plot.link", lang, link=link): (np.degrees(psi), first, second)
                  for link, psi, first, second in rotating}
        _draw_analogs(axes, x, labels, lang)
        _legend_outside(axes[0])
        title = render("plot.link_angles", lang)
        axes[0].set_title(title, fontsize=11)
        figures.append((f"{title}: {analogs}", fig))
    sliders = []
    for pid, state in motion.sliders.items():
        value, first, second = _parts(state.s, x.shape)
        if np.isfinite(value).any() and np.nanmax(value) - np.nanmin(value) > 1e-9:
            sliders.append((pid, state.slider, value, first, second))
    if sliders:
        fig = _new_figure((WIDTH, 7.0))
        axes = _analog_axes(fig, xlabel, (render("plot.s_mm", lang), render("plot.ds_mm", lang),
                                          render("plot.d2s_mm", lang)))
        labels = {render("plot.slider_of_pair", lang, pair=pid, link=slider): (v, d1, d2)
                  for pid, slider, v, d1, d2 in sliders}
        _draw_analogs(axes, x, labels, lang)
        _legend_outside(axes[0])
        title = render("plot.slider_displacements", lang)
        axes[0].set_title(title, fontsize=11)
        figures.append((f"{title}: {analogs}", fig))
    angles = pressure_angles(motion)
    if angles:
        fig = _new_figure((WIDTH, 3.2))
        ax = fig.add_subplot()
        alphas = {render("plot.pressure_angle_of_pair", lang, group=item.label, pair=item.pair,
                         maximum=math.degrees(item.maximum)):
                  np.degrees(np.broadcast_to(item.alpha, x.shape)) for item in angles}
        for (label, ls), alpha in zip(_styles(alphas, lang).values(), alphas.values(),
                                      strict=True):
            ax.plot(x, alpha, lw=1.4, label=label, ls=ls)
        ax.set_xlabel(xlabel)
        title = render("plot.pressure_angles", lang)
        ax.set_ylabel(render("plot.pressure_angle_deg", lang))
        ax.set_title(title, fontsize=11)
        ax.grid(alpha=0.3)
        _legend_outside(ax)
        figures.append((title, fig))
    if model.periodic:
        for _caption, fig in figures:
            for ax in fig.axes:
                ax.set_xticks(np.arange(0, 361, 45))
                ax.set_xlim(0, 360)
    return figures


def mechanism_figure(motion: Motion, *, lang: str = "en", positions: int = 4) -> Figure:
    """The mechanism at ``positions`` evenly spaced positions of the cycle (2 per row).

    Parameters
    ----------
    motion : Motion
        One design over the cycle.
    lang : str
        Language of the titles and labels.
    positions : int
        How many positions are drawn.

    Returns
    -------
    matplotlib.figure.Figure
        Not attached to pyplot.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> fig = mechanism_figure(analyse(model, points=36), positions=2)
    >>> [ax.get_title().splitlines()[1] for ax in fig.axes]
    ['crank angle φ = 0.0° from the sketched', 'crank angle φ = 180.0° from the']
    """
    from assur.plot.mechanism import draw_mechanism, working_space

    n = motion.q.size
    picks = [round(k * n / positions) % n for k in range(positions)]
    rows = math.ceil(positions / 2)
    x0, x1, y0, y1 = working_space(motion)
    height = min(max(3.9 * (y1 - y0) / max(x1 - x0, 1e-12), 1.8), 5.5) + 1.4  # plot + title
    fig = _new_figure((WIDTH, height * rows))
    axes = fig.subplots(rows, 2, squeeze=False).ravel()
    for ax, index in zip(axes, picks):
        draw_mechanism(motion, index, ax, lang=lang, wrap=38)
        ax.title.set_fontsize(TYPE_PT)
        ax.tick_params(labelsize=TYPE_PT)
        ax.xaxis.label.set_fontsize(TYPE_PT)
        ax.yaxis.label.set_fontsize(TYPE_PT)
        ax.set_aspect("equal")
        ax.autoscale_view()
    for ax in axes[len(picks):]:
        ax.set_axis_off()
    return fig
