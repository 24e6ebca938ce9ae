"""Pictures of the assembly modes of the triads and class IV groups at the sketch.

:func:`draw_modes` draws, for every triad and class IV group of an analysed mechanism, each
of its real assembly modes at the sketch position in its own axes: the links solved before
the group as drawn, and the group's links through the joints of that mode (the drawn mode
marked in its title). :func:`save_modes_png` writes the picture atomically. Only matplotlib's
object API is used (no pyplot state, no backend switch).
"""

from __future__ import annotations

import io
import math
import os
from typing import TYPE_CHECKING

import numpy as np

from assur.io.files import atomic_write_bytes
from assur.kinematics.analysis import Motion, values
from assur.kinematics.higher.kind import HigherGroupSolution, SketchMode
from assur.model import LinkId, PairId
from assur.text import render

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["draw_modes", "save_modes_png"]


def _mode_panels(motion: Motion) -> list[tuple[str, int, SketchMode]]:
    """(group label, mode number, mode) of every mode of every higher group."""
    return [(label, k, mode) for label, sol in motion.solutions.items()
            if isinstance(sol, HigherGroupSolution)
            for k, mode in enumerate(sol.modes(), start=1)]


def _draw_panel(ax: Axes, motion: Motion, index: int, label: str, mode: SketchMode) -> None:
    """The links up to the group ``label`` at position ``index``, the group in ``mode``."""
    model = motion.model
    upto = [g.label for g in model.groups]
    solved = set(upto[:upto.index(label) + 1])
    points: dict[PairId, complex] = {pid: complex(np.asarray(values(z)).reshape(-1)[index])
                                     for pid, z in motion.joints.items()}
    points.update({pid: complex(np.asarray(values(s.point)).reshape(-1)[index])
                   for pid, s in motion.sliders.items()})
    points.update(mode.joints)
    links: dict[LinkId, list[complex]] = {}
    for pid, (ptype, pair_links, _) in model.pair_links.items():
        for link in pair_links:
            if pid in points and (link == model.frame or model.links.get(link, ("",))[0] in solved):
                links.setdefault(link, []).append(points[pid])
    for link, zs in links.items():
        if link == model.frame:
            ax.plot([z.real for z in zs], [z.imag for z in zs], "k^", ms=7)
            continue
        ring = zs + zs[:1] if len(zs) > 2 else zs
        ax.plot([z.real for z in ring], [z.imag for z in ring], "-",
                color="tab:red" if model.links[link][0] == label else "tab:blue", lw=2)
    for pid, z in points.items():
        if model.pair_links[pid][0] == "P":
            ax.plot([z.real], [z.imag], "s", mfc="white", mec="black", ms=8)
        else:
            ax.plot([z.real], [z.imag], "o", mfc="white", mec="black", ms=5)
    ax.set_aspect("equal")


def draw_modes(motion: Motion, index: int = 0, *, lang: str = "en") -> Figure:
    """Every real assembly mode at the sketch of every triad and class IV group.

    Parameters
    ----------
    motion : Motion
        One design, analysed so that ``index`` is the sketch position (φ = 0).
    index : int
        The position of the known links drawn with each mode.
    lang : str
        Language of the titles.

    Returns
    -------
    matplotlib.figure.Figure
        One axes per mode (the group's links in red); empty when the mechanism has no such
        group.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables"
    ...                          / "class_iv_group.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> fig = draw_modes(analyse(model, points=4))
    >>> len(fig.axes)
    6
    """
    from matplotlib.figure import Figure

    panels = _mode_panels(motion)
    cols = min(3, max(len(panels), 1))
    rows = max(math.ceil(len(panels) / cols), 1)
    fig = Figure(figsize=(4.2 * cols, 4.0 * rows))
    for n, (label, k, mode) in enumerate(panels, start=1):
        ax = fig.add_subplot(rows, cols, n)
        _draw_panel(ax, motion, index, label, mode)
        mark = render("higher.report.drawn", lang) if mode.drawn else ""
        ax.set_title(render("higher.plot.mode", lang, group=label, k=k, mark=mark,
                            angle=math.degrees(mode.angle)), fontsize=9)
    return fig


def save_modes_png(motion: Motion, path: str | os.PathLike[str], index: int = 0, *,
                   lang: str = "en", dpi: int = 110) -> None:
    """Draw :func:`draw_modes` and write a PNG atomically.

    Parameters
    ----------
    motion : Motion
        One design analysed with the sketch position at ``index``.
    path : str or path-like
        The file to write (replaced atomically when it exists).
    index : int
        The sketch position.
    lang : str
        Language of the titles.
    dpi : int
        Dots per inch.

    Raises
    ------
    OSError
        When the file cannot be written.
    """
    fig = draw_modes(motion, index, lang=lang)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    atomic_write_bytes(path, buffer.getvalue())
