"""Pictures of a mechanism: the kinematic scheme at one position, traced paths, animation.

:func:`draw_mechanism` draws, on a matplotlib axes, every link at one analysed position
through the one drawing of the links, :mod:`assur.plot.drawing` (binary links as bars,
links with three or more joints as shaded plates, hinges as small circles, frame pivots with
a hatched support, sliders as blocks on their guide lines, guides over the whole stroke),
link and joint labels, and the paths of the tracing points and of the moving joints over the
cycle. Where the mechanism does not assemble, what does assemble is
drawn and the group that fails is marked: its outer hinges circled in red and joined by a
dashed line, with the group, the reason and the interval of the cycle where it fails.
Joints that coincide share one label (``B=C``); paths that coincide are named in a note.
:func:`working_space` and :func:`coinciding` are those of :mod:`assur.plot.drawing`.
The title gives the crank angle φ from the sketch position (as the tables count it) and the
crank's direction from the x axis.

:func:`save_mechanism_picture` writes PNG, SVG, PDF or JPEG and :func:`save_animation` a GIF
or an MP4, by the file's ending, atomically. Only matplotlib's object API is used: figures
are :class:`matplotlib.figure.Figure` objects that pyplot never sees, so drawing here neither
switches the process's backend nor shows a window.
"""

from __future__ import annotations

import io
import math
import os
import textwrap
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from assur.io.files import atomic_write_bytes
from assur.kinematics.analysis import Motion, values
from assur.kinematics.dyads import DyadSolution, Reason, reason_text
from assur.plot.drawing import coinciding, draw_paths, draw_scheme, scheme, working_space
from assur.plot.formats import animation_format, figure_bytes, picture_format
from assur.text import render

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

__all__ = ["Failure", "coinciding", "draw_mechanism", "failing_group", "failure_text", "figure_for",
           "save_animation", "save_mechanism_picture", "working_space"]


def _at(x: Any, index: int) -> Any:
    return np.asarray(values(x)).reshape(-1)[index]


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
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=36)
    >>> fig, ax = assur.plot.mechanism.figure_for(motion)
    >>> ax.get_aspect(), float(fig.get_figwidth())
    (1.0, 7.0)
    """
    from matplotlib.figure import Figure

    x0, x1, y0, y1 = working_space(motion)
    aspect = (y1 - y0) / max(x1 - x0, 1e-12)
    fig = Figure(figsize=(size, max(3.0, min(size * aspect, 2 * size)) + 0.4))
    ax = fig.add_subplot()
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    return fig, ax


class Failure(NamedTuple):
    """The group that does not assemble at a drawn position.

    Attributes
    ----------
    label : str
        The group's label, e.g. ``"L3(6,7)"``.
    reason : int
        A :class:`~assur.kinematics.dyads.Reason` code.
    hinges : tuple of complex
        The group's outer hinges that exist at the position (where it is attached).
    runs : tuple of (int, int)
        First and last index of every run of positions where this group fails.
    """

    label: str
    reason: int
    hinges: tuple[complex, ...]
    runs: tuple[tuple[int, int], ...]


def _along(x: Any, shape: tuple[int, ...]) -> np.ndarray:
    return np.broadcast_to(np.asarray(x), shape)


def failing_group(motion: Motion, index: int) -> Failure | None:
    """The first group, in layering order, that does not assemble at a position.

    Later groups are not evaluated where an earlier one fails (their reason is
    ``UNDEFINED_INPUT``), so the group found is the one to blame.

    Parameters
    ----------
    motion : Motion
        One design.
    index : int
        The position.

    Returns
    -------
    Failure or None
        None where the whole mechanism assembles.

    Examples
    --------
    >>> from pathlib import Path
    >>> import numpy as np, assur
    >>> table = Path(assur.__file__).parents[1] / "input_tables" / "course_11_link_fails.yaml"
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(assur.load_model(table), np.radians(np.arange(0, 360, 10.0)))
    >>> failure = failing_group(motion, 4)
    >>> failure.label, [(10 * a, 10 * b) for a, b in failure.runs]
    ('L3(6,7)', [(30, 70)])
    """
    shape = motion.q.shape
    for label, solution in motion.solutions.items():
        reasons = _along(solution.reason, shape)
        if int(reasons[index]) in (Reason.ASSEMBLES, Reason.UNDEFINED_INPUT):
            continue
        fails = (reasons != Reason.ASSEMBLES) & (reasons != Reason.UNDEFINED_INPUT)
        edges = np.diff(np.r_[0, fails.astype(np.int8), 0])
        runs = tuple(zip(np.flatnonzero(edges == 1).tolist(),
                         (np.flatnonzero(edges == -1) - 1).tolist()))
        group = motion.model.group(label)
        hinges = tuple(complex(_at(motion.joints[pid], index))
                       for role, pid in group.pairs.items()
                       if role in ("H_i", "H_j") and pid in motion.joints)
        return Failure(label, int(reasons[index]), tuple(z for z in hinges if np.isfinite(z)),
                       runs)
    return None


def failure_text(motion: Motion, failure: Failure, lang: str) -> str:
    """Which group does not assemble, over which part of the cycle, and why."""
    n = motion.q.size
    if failure.runs == ((0, n - 1),):
        where = render("plot.fails_whole_cycle", lang)
    else:
        crank = motion.model.periodic
        q = np.degrees(motion.q) if crank else motion.q
        unit = "°" if crank else " mm"
        ranges = "; ".join(f"{q[a]:.1f}{unit}" if a == b else f"{q[a]:.1f}…{q[b]:.1f}{unit}"
                           for a, b in failure.runs)
        where = render("plot.fails_at" if crank else "plot.fails_at_length", lang,
                       ranges=ranges)
    return render("plot.group_fails", lang, group=failure.label, where=where,
                  reason=reason_text(failure.reason, lang))


def _title(motion: Motion, index: int, failure: Failure | None, lang: str, wrap: int) -> str:
    model = motion.model
    q = float(motion.q[index])
    if model.drive == "crank":
        crank = motion.solutions[model.groups[0].label]
        assert isinstance(crank, DyadSolution)  # the input group
        arm = _at(crank.c, index) - _at(crank.origin_i, index)
        absolute = math.degrees(float(np.angle(arm))) % 360.0
        position = render("plot.crank_angle", lang, angle=math.degrees(q), absolute=absolute)
    elif model.drive == "laws":
        position = render("plot.cycle_t", lang, angle=math.degrees(q))
    else:
        position = render("plot.slider_s" if model.drive == "slider" else "plot.actuator_length",
                          lang, length=q)
    lines = [model.name, position]
    if failure is not None:
        lines.append(failure_text(motion, failure, lang))
    return "\n".join(textwrap.fill(line, wrap) for line in lines)


def _mark_failure(ax: Axes, failure: Failure, r: float, lang: str) -> None:
    """Red rings on the hinges of the group that does not assemble, joined by a dashed line."""
    if not failure.hinges:
        return
    z = np.array(failure.hinges)
    ax.plot(z.real, z.imag, "--", color="tab:red", lw=1.2, zorder=7)
    ax.plot(z.real, z.imag, "o", mfc="none", mec="tab:red", mew=2.0, ms=13, zorder=7,
            gid=f"fails-{failure.label}")
    ax.annotate(render("plot.group_fails_mark", lang, group=failure.label),
                (z[0].real, z[0].imag), xytext=(10, -18), textcoords="offset points",
                color="tab:red", fontsize=8, weight="bold", zorder=8,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85})


def draw_mechanism(motion: Motion, index: int = 0, ax: Axes | None = None, *,
                   paths: bool = True, labels: bool = True, lang: str = "en",
                   wrap: int = 90) -> Axes:
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
    wrap : int
        Longest line of the title, characters (longer lines are wrapped).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on. Its title gives the crank angle φ from the sketch position and the
        crank's direction from the x axis (or the actuator length), and, where the mechanism
        does not assemble, the group that fails, the interval and the reason.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=36)
    >>> ax = assur.draw_mechanism(motion, 9)
    >>> print(ax.get_title())
    four-bar (crank-rocker)
    crank angle φ = 90.0° from the sketched position (crank at 150.3° from the x axis)
    """
    if ax is None:
        _, ax = figure_for(motion)
    drawn = scheme(motion, [index])
    if paths:
        draw_paths(ax, motion, lang)
    draw_scheme(ax, drawn, labels=labels)
    failure = failing_group(motion, index)
    if failure is not None:
        _mark_failure(ax, failure, drawn.r, lang)
    ax.set_title(_title(motion, index, failure, lang, wrap), fontsize=10)
    ax.set_xlabel(render("plot.x_mm", lang))
    ax.set_ylabel(render("plot.y_mm", lang))
    ax.grid(True, lw=0.3, alpha=0.5)
    return ax


def save_mechanism_picture(motion: Motion, path: str | os.PathLike[str], index: int = 0, *,
                           lang: str = "en", dpi: int = 120) -> None:
    """Draw the mechanism at one position with its paths and write the picture atomically,
    in the format of the file's ending (PNG, SVG, PDF or JPEG).

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
        Dots per inch (PNG, JPEG).

    Raises
    ------
    PictureFormatError
        For another ending (nothing is drawn).
    OSError
        When the file cannot be written.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=36)
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "four_bar.pdf")
    ...     save_mechanism_picture(motion, path, index=3)
    ...     path.read_bytes()[:5]
    b'%PDF-'
    """
    fmt = picture_format(path)
    fig, ax = figure_for(motion)
    draw_mechanism(motion, index, ax, lang=lang)
    atomic_write_bytes(path, figure_bytes(fig, fmt, dpi=dpi))


def _frames(motion: Motion, frames: int, lang: str, dpi: int) -> Iterator[FigureCanvasAgg]:
    """The figure redrawn at evenly chosen positions of the cycle (one figure, reused), on its
    raster canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    n = motion.q.size
    picks = np.unique(np.linspace(0, n - 1, min(frames, n)).round().astype(int))
    fig, ax = figure_for(motion, size=6.0)
    canvas = FigureCanvasAgg(fig)
    fig.set_dpi(dpi)
    limits = ax.get_xlim(), ax.get_ylim()
    for index in picks:
        ax.clear()
        ax.set_xlim(*limits[0])
        ax.set_ylim(*limits[1])
        ax.set_aspect("equal")
        draw_mechanism(motion, int(index), ax, lang=lang)
        yield canvas


def save_animation(motion: Motion, path: str | os.PathLike[str], *, frames: int = 72,
                   duration_ms: int = 60, lang: str = "en", dpi: int = 80) -> None:
    """Animate a whole cycle and write a looping GIF, or an MP4, atomically.

    Parameters
    ----------
    motion : Motion
        The analysed mechanism.
    path : str or path-like
        The file to write (replaced atomically when it exists); ``.gif``, or ``.mp4`` where
        matplotlib finds an ffmpeg writer (:func:`assur.plot.formats.animation_formats`).
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
    PictureFormatError
        For another ending, or ``.mp4`` without ffmpeg (nothing is drawn).
    OSError
        When the file cannot be written.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> model = assur.load_model(Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml")
    >>> from assur.kinematics.analysis import analyse
    >>> motion = analyse(model, points=36)
    >>> import tempfile, pathlib
    >>> from PIL import Image
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder, "four_bar.gif")
    ...     save_animation(motion, path, frames=4, dpi=40)
    ...     with Image.open(path) as gif:
    ...         gif.n_frames
    4
    """
    fmt = animation_format(path)
    if fmt == "mp4":
        _write_mp4(motion, path, frames, duration_ms, lang, dpi)
        return
    from PIL import Image

    images = []
    for canvas in _frames(motion, frames, lang, dpi):
        canvas.draw()
        rgba = np.asarray(canvas.buffer_rgba())
        images.append(Image.fromarray(rgba[..., :3].copy()).convert(
            "P", palette=Image.Palette.ADAPTIVE))
    buffer = io.BytesIO()
    images[0].save(buffer, format="GIF", save_all=True, append_images=images[1:],
                   duration=duration_ms, loop=0)
    atomic_write_bytes(path, buffer.getvalue())


def _write_mp4(motion: Motion, path: str | os.PathLike[str], frames: int, duration_ms: int,
               lang: str, dpi: int) -> None:
    """The animation through matplotlib's ffmpeg writer, into a scratch file first."""
    import tempfile
    from pathlib import Path

    from matplotlib.animation import FFMpegWriter

    writer = FFMpegWriter(fps=max(1, round(1000 / duration_ms)))
    with tempfile.TemporaryDirectory() as folder:
        scratch = Path(folder, "animation.mp4")
        drawn = _frames(motion, frames, lang, dpi)
        first = next(drawn)
        with writer.saving(first.figure, str(scratch), dpi):
            writer.grab_frame()
            for _canvas in drawn:
                writer.grab_frame()
        atomic_write_bytes(path, scratch.read_bytes())
