"""Block B5 pictures: output against target, the mechanism at the best design, convergence.

Matplotlib is imported lazily with the Agg backend; nothing is ever shown on screen.  Each
``plot_*`` function draws on a given ``Axes`` (or a new figure) and returns the ``Axes``;
:func:`save_plots` writes the three pictures of a synthesis run into a folder.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from assur import atomic_write_bytes, values
from synthesis.evaluate import Analysis
from synthesis.problem import Problem
from synthesis.search import SearchResult

__all__ = ["plot_convergence", "plot_mechanism", "plot_output", "save_plots"]

_LABELS = {
    "en": {"phi": "crank rotation φ, deg", "psi": "output angle ψ, deg",
           "n": "velocity ratio n = dψ/dφ",
           "S": "slider displacement S, mm", "x": "x, mm", "y": "y, mm",
           "dev": "deviation Δ_K", "target": "control points", "reproduced": "reproduced",
           "trial": "trial", "seconds": "wall time, s", "best": "best Q (feasible)",
           "zone": "tolerance zone", "mechanism": "mechanism at φ = 0", "path": "path of Ж"},
    "ru": {"phi": "угол поворота кривошипа φ, град", "psi": "угол выходного звена ψ, град",
           "n": "передаточное отношение n = dψ/dφ",
           "S": "перемещение ползуна S, мм", "x": "x, мм", "y": "y, мм",
           "dev": "отклонение Δ_K", "target": "контрольные точки",
           "reproduced": "воспроизводимая функция", "trial": "испытание",
           "seconds": "время, с", "best": "лучшее Q (допустимое)", "zone": "зона допуска",
           "mechanism": "механизм при φ = 0", "path": "траектория Ж"},
}


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_output(problem: Problem, analysis: Analysis, *, axes: Any = None,
                lang: str = "en") -> Any:
    """The reproduced output against the targets, with the deviations at the control points.

    Returns the main ``Axes``; the deviations are drawn on a twin axis (classes 1–2) or as
    segments from each required point to the reproduced one (classes 3–4).
    """
    plt = _pyplot()
    t = _LABELS[lang]
    ax = axes if axes is not None else plt.figure(figsize=(7, 5)).add_subplot()
    control = problem.control
    out = analysis.output_grid[0]
    if problem.task_class in (1, 2):
        scale = problem.output_scale
        phi = np.degrees(analysis.grid)
        ax.plot(phi, np.real(out) * scale, label=t["reproduced"])
        cphi = np.degrees(control.phi)
        if control.zone:
            middle = (control.lower + control.upper) / 2 * scale
            half = (control.upper - control.lower) / 2 * scale
            ax.errorbar(cphi, middle, yerr=half, fmt="none", capsize=4, color="tab:green",
                        label=t["zone"])
        else:
            ax.plot(cphi, control.value * scale, "o", label=t["target"])
        ax.set_xlabel(t["phi"])
        ax.set_ylabel(t["S"] if problem.task_class == 2
                      else t["n"] if problem.output.ratio else t["psi"])
        twin = ax.twinx()
        twin.bar(cphi, analysis.criteria.deviations[0], width=3.0, color="tab:red", alpha=0.5)
        twin.set_ylabel(t["dev"])
    else:
        ax.plot(out.real, out.imag, label=t["path"])
        ax.plot(control.point.real, control.point.imag, "o", label=t["target"])
        near = analysis.output_control[0]
        for p, q in zip(control.point, near):
            ax.plot([p.real, q.real], [p.imag, q.imag], color="tab:red")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(t["x"])
        ax.set_ylabel(t["y"])
    ax.legend(loc="best")
    ax.set_title(f"Q = {analysis.criteria.q[0]:.4g}")
    return ax


def plot_mechanism(problem: Problem, analysis: Analysis, *, axes: Any = None,
                   lang: str = "en") -> Any:
    """The mechanism at the start position φ = 0 (joints and links), with the output path."""
    plt = _pyplot()
    t = _LABELS[lang]
    ax = axes if axes is not None else plt.figure(figsize=(7, 6)).add_subplot()
    motion = analysis.motion
    model = motion.model
    at = 0

    def start(point: Any) -> complex:
        return complex(np.broadcast_to(values(point), (1, motion.q.size))[0, at])

    points: dict[Any, list[complex]] = {}
    for pid, (kind, links, _) in model.pair_links.items():
        if kind == "R" and pid in motion.joints:
            z = start(motion.joints[pid])
            for link in links:
                points.setdefault(link, []).append(z)
    for state in motion.sliders.values():
        z = start(state.point)
        points.setdefault(state.slider, []).append(z)
        points.setdefault(state.carrier, []).append(z)
    if problem.task_class in (3, 4):
        points.setdefault(problem.output.link, []).append(complex(analysis.output_grid[0, at]))
    for link, pts in points.items():
        if link == model.frame:
            ax.plot([p.real for p in pts], [p.imag for p in pts], "k^", markersize=9)
            continue
        pts = pts + pts[:1] if len(pts) > 2 else pts
        ax.plot([p.real for p in pts], [p.imag for p in pts], "o-", linewidth=2)
        centre = np.mean(pts)
        ax.annotate(str(link), (centre.real, centre.imag), fontsize=9)
    if problem.task_class in (3, 4):
        out = analysis.output_grid[0]
        ax.plot(out.real, out.imag, ":", label=t["path"])
        ax.plot(problem.control.point.real, problem.control.point.imag, "x", label=t["target"])
        ax.legend(loc="best")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(t["mechanism"])
    ax.set_xlabel(t["x"])
    ax.set_ylabel(t["y"])
    return ax


def plot_convergence(result: SearchResult, *, axes: Any = None, lang: str = "en") -> Any:
    """Best Q of the feasible designs against the trial number (log scale)."""
    plt = _pyplot()
    t = _LABELS[lang]
    ax = axes if axes is not None else plt.figure(figsize=(7, 4)).add_subplot()
    c = result.trial_criteria
    ok = (c.p1 == 0) & (c.p2 == 0) & np.isfinite(c.q)
    q = np.where(ok, c.q, np.inf)
    best = np.minimum.accumulate(q)
    shown = np.isfinite(best) & (best > 0)
    trials = np.arange(q.size)
    ax.semilogy(trials[shown], best[shown])
    for stage in ("shrink", "refine"):
        first = next((k for k, s in enumerate(result.stage) if s == stage), None)
        if first is not None:
            ax.axvline(first, color="grey", linestyle=":")
            ax.annotate(stage, (first, ax.get_ylim()[1]), fontsize=8, va="top")
    ax.set_xlabel(t["trial"])
    ax.set_ylabel(t["best"])
    return ax


def save_plots(folder: str | os.PathLike[str], problem: Problem, result: SearchResult,
               analysis: Analysis, *, lang: str = "en") -> list[Path]:
    """Write ``output.png``, ``mechanism.png`` and ``convergence.png`` into ``folder``."""
    plt = _pyplot()
    folder = Path(folder)
    written = []
    for name, draw in (("output", lambda ax: plot_output(problem, analysis, axes=ax, lang=lang)),
                       ("mechanism", lambda ax: plot_mechanism(problem, analysis, axes=ax,
                                                               lang=lang)),
                       ("convergence", lambda ax: plot_convergence(result, axes=ax,
                                                                   lang=lang))):
        fig = plt.figure(figsize=(7, 5))
        draw(fig.add_subplot())
        fig.tight_layout()
        import io

        buffer = io.BytesIO()
        fig.savefig(buffer, format="png", dpi=110)
        plt.close(fig)
        path = folder / f"{name}.png"
        atomic_write_bytes(path, buffer.getvalue())
        written.append(path)
    return written

