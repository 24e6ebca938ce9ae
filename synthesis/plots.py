"""Block B5 pictures: output against target, the mechanism at the best design, convergence.

Only matplotlib's object API is used: each ``plot_*`` function draws on the given ``Axes``
(or on a new :class:`matplotlib.figure.Figure` that pyplot never sees) and returns the
``Axes``, so drawing neither switches the process's backend nor shows a window;
:func:`save_plots` writes the three pictures of a synthesis run into a folder.
"""

from __future__ import annotations

import io
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from assur.io.files import atomic_write_bytes
from assur.plot.drawing import draw_scheme, scheme
from assur.text import render
from synthesis.evaluate import Analysis
from synthesis.problem import Problem
from synthesis.search_result import SearchResult

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["plot_convergence", "plot_mechanism", "plot_output", "save_plots"]


def _axes(axes: Axes | None, size: tuple[float, float]) -> Axes:
    """The caller's axes, or the axes of a new figure of ``size`` inches."""
    if axes is not None:
        return axes
    from matplotlib.figure import Figure

    return Figure(figsize=size).add_subplot()


def plot_output(problem: Problem, analysis: Analysis, *, axes: Axes | None = None,
                lang: str = "en") -> Axes:
    """The reproduced output against the targets, with the deviations at the control points.

    Parameters
    ----------
    problem : Problem
        The synthesis problem (its task class, control points and output).
    analysis : Analysis
        One design analysed over the grid (the first row is drawn).
    axes : matplotlib.axes.Axes, optional
        Where to draw; the axes of a new figure when None. Drawing on the caller's axes
        changes nothing else: no backend switch, no new pyplot figure.
    lang : str
        Language of the labels.

    Returns
    -------
    matplotlib.axes.Axes
        The main axes; the deviations are drawn on a twin axis (classes 1–2) or as segments
        from each required point to the reproduced one (classes 3–4).

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> from synthesis.evaluate import Evaluator
    >>> from synthesis.problem_table import load_problem
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables" / "problems"
    >>> problem = load_problem(tables / "class1_fourbar_rocker.yaml")
    >>> analysis = Evaluator(problem).analyse(problem.initial[None, :])
    >>> plot_output(problem, analysis).get_ylabel()
    'output angle ψ, deg'
    """
    ax = _axes(axes, (7, 5))
    control = problem.control
    out = analysis.output_grid[0]
    if problem.task_class in (1, 2):
        scale = problem.output_scale
        phi = np.degrees(analysis.grid)
        ax.plot(phi, np.real(out) * scale, label=render("plot.reproduced", lang))
        cphi = np.degrees(control.phi)
        if control.lower is not None and control.upper is not None:  # a tolerance zone
            middle = (control.lower + control.upper) / 2 * scale
            half = (control.upper - control.lower) / 2 * scale
            ax.errorbar(cphi, middle, yerr=half, fmt="none", capsize=4, color="tab:green",
                        label=render("plot.tolerance_zone", lang))
        else:
            ax.plot(cphi, control.value * scale, "o", label=render("plot.control_points", lang))
        ax.set_xlabel(render("plot.crank_rotation_deg", lang))
        ax.set_ylabel(render("plot.slider_displacement_mm", lang) if problem.task_class == 2
                      else render("plot.velocity_ratio", lang) if problem.output.ratio
                      else render("plot.output_angle_deg", lang))
        twin = ax.twinx()
        twin.bar(cphi, analysis.criteria.deviations[0] * scale, width=3.0, color="tab:red", alpha=0.5)
        twin.set_ylabel(render("plot.deviation", lang))
    else:
        ax.plot(out.real, out.imag, label=render("plot.path_of_tracing_point", lang))
        ax.plot(control.point.real, control.point.imag, "o",
                label=render("plot.control_points", lang))
        near = analysis.output_control[0]
        for p, q in zip(control.point, near):
            ax.plot([p.real, q.real], [p.imag, q.imag], color="tab:red")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(render("plot.x_mm", lang))
        ax.set_ylabel(render("plot.y_mm", lang))
    ax.legend(loc="best")
    ax.set_title(f"Q = {analysis.criteria.q[0] * problem.output_scale:.4g}")
    return ax


def plot_mechanism(problem: Problem, analysis: Analysis, *, axes: Axes | None = None,
                   lang: str = "en") -> Axes:
    """The mechanism at the start position φ = 0, with the output path.

    The links are drawn as in every picture of a mechanism (:mod:`assur.plot.drawing`); the
    output point of classes 3–4 rides on its link as a tracing point.

    Parameters
    ----------
    problem : Problem
        The synthesis problem (the output path and control points of classes 3–4).
    analysis : Analysis
        One design analysed over the grid (the first row is drawn).
    axes : matplotlib.axes.Axes, optional
        Where to draw; the axes of a new figure when None.
    lang : str
        Language of the labels.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> from synthesis.evaluate import Evaluator
    >>> from synthesis.problem_table import load_problem
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables" / "problems"
    >>> problem = load_problem(tables / "class1_fourbar_rocker.yaml")
    >>> analysis = Evaluator(problem).analyse(problem.initial[None, :])
    >>> plot_mechanism(problem, analysis, lang="ru").get_title()
    'механизм при φ = 0'
    """
    ax = _axes(axes, (7, 6))
    point = problem.output.point if problem.task_class in (3, 4) else None
    attached = ({point: (problem.output.link, analysis.output_grid[0])}
                if point is not None and point not in analysis.motion.tracing else None)
    draw_scheme(ax, scheme(analysis.motion, [0], attached=attached))
    if problem.task_class in (3, 4):
        out = analysis.output_grid[0]
        ax.plot(out.real, out.imag, ":", color="tab:red",
                label=render("plot.path_of_tracing_point", lang))
        ax.plot(problem.control.point.real, problem.control.point.imag, "x", color="tab:purple",
                label=render("plot.control_points", lang))
        ax.legend(loc="best")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(render("plot.mechanism_at_start", lang))
    ax.set_xlabel(render("plot.x_mm", lang))
    ax.set_ylabel(render("plot.y_mm", lang))
    return ax


def plot_convergence(result: SearchResult, *, axes: Axes | None = None, lang: str = "en") -> Axes:
    """Best Q of the feasible designs against the trial number (log scale).

    Parameters
    ----------
    result : SearchResult
        A finished search; the first trials of the shrink and refine stages are marked.
    axes : matplotlib.axes.Axes, optional
        Where to draw; the axes of a new figure when None.
    lang : str
        Language of the labels.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from synthesis.criteria import Criteria
    >>> from synthesis import SearchSettings
    >>> from synthesis.search import search
    >>> def evaluate(x):
    ...     dev = x - np.array([0.3, 0.7])
    ...     zero = np.zeros(len(x))
    ...     return Criteria(zero, zero, np.max(np.abs(dev), axis=1), dev, dev)
    >>> result = search(evaluate, [0, 0], [1, 1], [0.5, 0.5], SearchSettings(budget_log2=6))
    >>> ax = plot_convergence(result)
    >>> ax.get_yscale(), ax.get_xlabel()
    ('log', 'trial')
    """
    ax = _axes(axes, (7, 4))
    c = result.trial_criteria
    ok = (c.p1 == 0) & (c.p2 == 0) & np.isfinite(c.q)
    q = np.where(ok, c.q, np.inf)
    best = np.minimum.accumulate(q)
    shown = np.isfinite(best) & (best > 0)
    trials = np.arange(q.size)
    ax.semilogy(trials[shown], best[shown])
    for stage, name in (("shrink", render("plot.stage_shrink", lang)),
                        ("refine", render("plot.stage_refine", lang))):
        first = next((k for k, s in enumerate(result.stage) if s == stage), None)
        if first is not None:
            ax.axvline(first, color="grey", linestyle=":")
            ax.annotate(name, (first, ax.get_ylim()[1]), fontsize=8, va="top")
    ax.set_xlabel(render("plot.trial", lang))
    ax.set_ylabel(render("plot.best_q", lang))
    return ax


def save_plots(folder: str | os.PathLike[str], problem: Problem, result: SearchResult,
               analysis: Analysis, *, lang: str = "en") -> list[Path]:
    """Write ``output.png``, ``mechanism.png`` and ``convergence.png`` into ``folder``.

    Parameters
    ----------
    folder : str or path-like
        An existing folder; the files in it are replaced atomically.
    problem : Problem
    result : SearchResult
    analysis : Analysis
        The best design of ``result`` analysed over the grid.
    lang : str
        Language of the labels.

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    OSError
        When a file cannot be written.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> from synthesis.evaluate import Evaluator
    >>> from synthesis.problem_table import load_problem
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables" / "problems"
    >>> problem = load_problem(tables / "class1_fourbar_rocker.yaml")
    >>> from synthesis.search import search
    >>> from synthesis.search_settings import settings_for
    >>> evaluator = Evaluator(problem)
    >>> result = search(evaluator, problem.lower, problem.upper, problem.initial,
    ...                 settings_for(problem, budget_log2=4, refine=False))
    >>> analysis = evaluator.analyse(result.x[None, :])
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     [path.name for path in save_plots(folder, problem, result, analysis)]
    ['output.png', 'mechanism.png', 'convergence.png']
    """
    from matplotlib.figure import Figure

    folder = Path(folder)
    written = []
    drawers: tuple[tuple[str, Callable[[Axes], Axes]], ...] = (
        ("output", lambda ax: plot_output(problem, analysis, axes=ax, lang=lang)),
        ("mechanism", lambda ax: plot_mechanism(problem, analysis, axes=ax, lang=lang)),
        ("convergence", lambda ax: plot_convergence(result, axes=ax, lang=lang)))
    for name, draw in drawers:
        fig = Figure(figsize=(7, 5))
        draw(fig.add_subplot())
        fig.tight_layout()
        buffer = io.BytesIO()
        fig.savefig(buffer, format="png", dpi=110)
        path = folder / f"{name}.png"
        atomic_write_bytes(path, buffer.getvalue())
        written.append(path)
    return written
