"""Pictures of a mechanism: the kinematic scheme at one position, traced paths, animation.

:func:`draw_mechanism` draws, on a matplotlib axes, every link at one analysed position
(binary links as bars, links with three or more joints as shaded plates), hinges as small
circles, frame pivots with a hatched support, sliders as blocks on their guide lines, guides
over the whole stroke, link and joint labels, and the paths of the tracing points and of the
moving joints over the cycle. :func:`save_mechanism_png` and :func:`save_animation_gif` write
files atomically. Only matplotlib's object API is used: figures are
:class:`matplotlib.figure.Figure` objects that pyplot never sees, so drawing here neither
switches the process's backend nor shows a window.
"""

from __future__ import annotations

import io
import math
import os
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.io.files import atomic_write_bytes
from assur.kinematics.analysis import Motion, values
from assur.model import LinkId
from assur.text import render

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle

__all__ = ["draw_mechanism", "figure_for", "save_animation_gif", "save_mechanism_png"]


def _at(x: Any, index: int) -> Any:
    return np.asarray(values(x)).reshape(-1)[index]


def _bounds(motion: Motion) -> tuple[float, float, float, float]:
    points = [np.asarray(values(z)).ravel() for z in motion.joints.values()]
    points += [np.asarray(values(z)).ravel() for z in motion.tracing.values()]
    points += [np.asarray(values(s.base)).ravel() for s in motion.sliders.values()]
    allz = np.concatenate(points)
    allz = allz[np.isfinite(allz)]
    if allz.size == 0:
        return -1.0, 1.0, -1.0, 1.0
    x0, x1 = float(allz.real.min()), float(allz.real.max())
    y0, y1 = float(allz.imag.min()), float(allz.imag.max())
    pad = 0.08 * max(x1 - x0, y1 - y0, 1e-9)
    return x0 - pad, x1 + pad, y0 - pad, y1 + pad


def figure_for(motion: Motion, size: float = 7.0) -> tuple[Figure, Axes]:
    """A new figure with one axes sized and scaled to the mechanism's working space.

    Parameters
    ----------
    motion : Motion
        The analysed mechanism; every joint, slider base and tracing point over the cycle
        fits in the axes' limits (with a margin of 8 %).
    size : float
        Width of the figure, inches; the height follows the working space's aspect.

    Returns
    -------
    figure : matplotlib.figure.Figure
        Not attached to pyplot: nothing is shown, and the figure is freed with its last
        reference.
    axes : matplotlib.axes.Axes
        With equal aspect and the limits of the working space.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> motion = assur.analyse(model, points=36)
    >>> fig, ax = assur.plot.mechanism.figure_for(motion)
    >>> ax.get_aspect(), float(fig.get_figwidth())
    (1.0, 7.0)
    """
    from matplotlib.figure import Figure

    x0, x1, y0, y1 = _bounds(motion)
    aspect = (y1 - y0) / max(x1 - x0, 1e-12)
    fig = Figure(figsize=(size, max(3.0, min(size * aspect, 2 * size)) + 0.4))
    ax = fig.add_subplot()
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    return fig, ax


def draw_mechanism(motion: Motion, index: int = 0, ax: Axes | None = None, *,
                   paths: bool = True, labels: bool = True, lang: str = "en") -> Axes:
    """Draw the mechanism at one analysed position.

    Parameters
    ----------
    motion : Motion
        One design (positions shaped ``(N,)``).
    index : int
        Which position.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure from :func:`figure_for` when None. Drawing on the
        caller's axes changes nothing else: no backend switch, no new pyplot figure.
    paths : bool
        Draw the traced paths of the tracing points and the moving joints.
    labels : bool
        Write link numbers and joint names.
    lang : str
        Language of the title and axis labels (a catalogue of :mod:`assur.text`).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on; its title gives the input position and says when the mechanism
        does not assemble there.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> motion = assur.analyse(model, points=36)
    >>> ax = assur.draw_mechanism(motion, 9)
    >>> ax.get_title()
    'four-bar (crank-rocker): crank angle φ = 90.0°'
    """
    if ax is None:
        _, ax = figure_for(motion)
    model = motion.model
    frame = model.frame
    span = _bounds(motion)
    scale = max(span[1] - span[0], span[3] - span[2])
    r = 0.012 * scale
    if paths:
        for name, point in motion.tracing.items():
            z = np.asarray(values(point)).ravel()
            ax.plot(z.real, z.imag, "-", color="tab:red", lw=1.2, zorder=1)
        for pid, point in motion.joints.items():
            z = np.asarray(values(point)).ravel()
            if np.nanmax(np.abs(z - z[np.isfinite(z)][0]), initial=0.0) > 1e-9 * scale:
                ax.plot(z.real, z.imag, ":", color="0.6", lw=0.7, zorder=1)
    # guides over the stroke of their sliders
    for pid, slider in motion.sliders.items():
        s_all = np.asarray(values(slider.s)).ravel()
        if not np.isfinite(s_all).any():
            continue
        lo, hi = float(np.nanmin(s_all)), float(np.nanmax(s_all))
        if slider.carrier != frame:  # a guide on a moving link starts at its base point
            lo, hi = min(lo, 0.0), max(hi, 0.0)
        margin = 0.15 * max(hi - lo, 4 * r)
        base = _at(slider.base, index)
        angle = _at(slider.angle, index)
        if not (np.isfinite(base) and np.isfinite(angle)):
            continue
        u = np.exp(1j * angle)
        line_base = base + 1j * float(np.asarray(slider.offset).ravel()[0]) * u
        ends = line_base + np.array([lo - margin, hi + margin]) * u
        ax.plot(ends.real, ends.imag, "-", color="0.35",
                lw=2.2 if slider.carrier == frame else 1.4, zorder=2)
        if slider.carrier == frame:
            normal = -1j * u * 0.6 * r
            ticks = np.linspace(0, 1, 8)
            for t in ticks:
                p = ends[0] + t * (ends[1] - ends[0])
                ax.plot([p.real, (p + normal + 0.5 * normal * 1j).real],
                        [p.imag, (p + normal + 0.5 * normal * 1j).imag], "-", color="0.5",
                        lw=0.6, zorder=2)
    # links: bars between their joints, plates for three or more
    points_of: dict[LinkId, list[complex]] = {}
    for pid, (kind, links, _) in model.pair_links.items():
        if kind == "R" and pid in motion.joints:
            z = _at(motion.joints[pid], index)
            for link in links:
                points_of.setdefault(link, []).append(z)
    for pid, slider in motion.sliders.items():
        points_of.setdefault(slider.slider, []).append(_at(slider.point, index))
    for traced in model.tracing:
        z = _at(motion.tracing[traced.name], index)
        points_of.setdefault(traced.anchor.link, []).append(z)
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:olive",
               "tab:cyan", "tab:pink"]
    for n, (link, pts) in enumerate(sorted(points_of.items(), key=lambda kv: str(kv[0]))):
        if link == frame:
            continue
        pts = [p for p in pts if np.isfinite(p)]
        if not pts:
            continue
        colour = colours[n % len(colours)]
        zs = np.array(pts)
        if len(pts) >= 3:
            centre = zs.mean()
            order = np.argsort(np.angle(zs - centre))
            poly = zs[order]
            ax.fill(poly.real, poly.imag, color=colour, alpha=0.25, zorder=3)
            ax.plot(np.r_[poly.real, poly.real[0]], np.r_[poly.imag, poly.imag[0]], "-",
                    color=colour, lw=2.5, zorder=3)
        elif len(pts) == 2:
            ax.plot(zs.real, zs.imag, "-", color=colour, lw=3, zorder=3, solid_capstyle="round")
        if labels:
            c = zs.mean() + 1.8 * r * (1 + 1j)
            ax.text(c.real, c.imag, str(link), color=colour, fontsize=9, weight="bold",
                    zorder=6)
    # slider blocks
    for pid, slider in motion.sliders.items():
        z, angle = _at(slider.point, index), _at(slider.angle, index)
        if not (np.isfinite(z) and np.isfinite(angle)):
            continue
        corners = np.array([-2 - 1j, 2 - 1j, 2 + 1j, -2 + 1j, -2 - 1j]) * 1.1 * r
        block = z + corners * np.exp(1j * angle)
        ax.fill(block.real, block.imag, color="white", ec="black", lw=1.2, zorder=4)
    # hinges
    for pid, (kind, links, _) in model.pair_links.items():
        if kind != "R" or pid not in motion.joints:
            continue
        z = _at(motion.joints[pid], index)
        if not np.isfinite(z):
            continue
        if frame in links:
            tri = z + r * np.array([0, -1.6 - 1.6j, 1.6 - 1.6j, 0]) * 1.2
            ax.fill(tri.real, tri.imag, color="0.8", ec="black", lw=0.8, zorder=4)
        ax.add_patch(_circle(z, r))
        if labels:
            ax.text(z.real + 1.2 * r, z.imag - 2.2 * r, str(pid), fontsize=7, color="0.2",
                    zorder=6)
    for name, point in motion.tracing.items():
        z = _at(point, index)
        if np.isfinite(z):
            ax.plot([z.real], [z.imag], "o", color="tab:red", ms=5, zorder=6)
            if labels:
                ax.text(z.real + r, z.imag + r, name, color="tab:red", fontsize=9, zorder=6)
    q = float(motion.q[index])
    title = (render("plot.crank_angle", lang, angle=math.degrees(q)) if model.drive == "crank"
             else render("plot.actuator_length", lang, length=q))
    if not bool(np.asarray(motion.exists).ravel()[index]):
        title += " — " + render("plot.does_not_assemble", lang)
    ax.set_title(f"{model.name}: {title}", fontsize=10)
    ax.set_xlabel(render("plot.x_mm", lang))
    ax.set_ylabel(render("plot.y_mm", lang))
    ax.grid(True, lw=0.3, alpha=0.5)
    return ax


def _circle(z: complex, r: float) -> Circle:
    from matplotlib.patches import Circle

    return Circle((z.real, z.imag), r, facecolor="white", edgecolor="black", lw=1.2, zorder=5)


def save_mechanism_png(motion: Motion, path: str | os.PathLike[str], index: int = 0, *,
                       lang: str = "en", dpi: int = 120) -> None:
    """Draw the mechanism at one position with its paths and write a PNG atomically.

    Parameters
    ----------
    motion : Motion
        The analysed mechanism.
    path : str or path-like
        The file to write (replaced atomically when it exists).
    index : int
        Which position.
    lang : str
        Language of the title and axis labels.
    dpi : int
        Dots per inch.

    Raises
    ------
    OSError
        When the file cannot be written.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> motion = assur.analyse(model, points=36)
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "four_bar.png")
    ...     assur.plot.mechanism.save_mechanism_png(motion, path, index=3)
    ...     path.read_bytes()[1:4]
    b'PNG'
    """
    fig, ax = figure_for(motion)
    draw_mechanism(motion, index, ax, lang=lang)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    atomic_write_bytes(path, buffer.getvalue())


def save_animation_gif(motion: Motion, path: str | os.PathLike[str], *, frames: int = 72,
                       duration_ms: int = 60, lang: str = "en", dpi: int = 80) -> None:
    """Animate a whole cycle and write a looping GIF atomically.

    Parameters
    ----------
    motion : Motion
        The analysed mechanism.
    path : str or path-like
        The file to write (replaced atomically when it exists).
    frames : int
        How many evenly chosen positions are shown (all of them when there are fewer).
    duration_ms : int
        How long each frame is shown, milliseconds.
    lang : str
        Language of the title and axis labels.
    dpi : int
        Dots per inch.

    Raises
    ------
    OSError
        When the file cannot be written.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> motion = assur.analyse(model, points=36)
    >>> import tempfile, pathlib
    >>> from PIL import Image
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "four_bar.gif")
    ...     assur.plot.mechanism.save_animation_gif(motion, path, frames=4, dpi=40)
    ...     with Image.open(path) as gif:
    ...         gif.n_frames
    4
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    n = motion.q.size
    picks = np.unique(np.linspace(0, n - 1, min(frames, n)).round().astype(int))
    fig, ax = figure_for(motion, size=6.0)
    canvas = FigureCanvasAgg(fig)
    limits = ax.get_xlim(), ax.get_ylim()
    images = []
    for index in picks:
        ax.clear()
        ax.set_xlim(*limits[0])
        ax.set_ylim(*limits[1])
        ax.set_aspect("equal")
        draw_mechanism(motion, int(index), ax, lang=lang)
        fig.set_dpi(dpi)
        canvas.draw()
        rgba = np.asarray(canvas.buffer_rgba())
        frame_rgb = Image.fromarray(rgba[..., :3].copy())
        images.append(frame_rgb.convert("P", palette=Image.Palette.ADAPTIVE))
    buffer = io.BytesIO()
    images[0].save(buffer, format="GIF", save_all=True, append_images=images[1:],
                   duration=duration_ms, loop=0)
    atomic_write_bytes(path, buffer.getvalue())
