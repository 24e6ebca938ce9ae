"""One drawing of a mechanism's links: the kinematic scheme as typed primitives.

:func:`scheme` turns an analysed motion at chosen positions into the primitives that every
picture of the mechanism is made of, each with its geometry at every chosen position (mm,
points as ``x + 1j * y``, NaN where the point does not exist):

* :class:`Plate` — a moving link: a bar between its two points, or a shaded plate around
  three or more, with its number;
* :class:`Hinge` — a revolute pair, on a hatched support (:attr:`Hinge.support`) when it
  joins a link to the frame;
* :class:`Block` — the slider block of a prismatic pair, along its guide;
* :class:`Guide` — a guide line over the stroke of its slider, hatched on the frame side
  when the guide is the frame's;
* :class:`Tracer` — a tracing point (or an output point of a synthesis problem);
* labels — a joint's name, merged with the names of joints that coincide (``B=C``).

:func:`paths` gives the traced paths of the tracing points and the moving joints, with the
paths that coincide named once. :func:`draw_scheme` renders a scheme at one position on a
matplotlib axes: the static picture (:func:`assur.plot.mechanism.draw_mechanism`) and the
picture of a synthesised design draw through it, and the playable coursework page serialises
the same primitives for the browser, so the three show the same links.

Examples
--------
>>> from pathlib import Path
>>> import assur
>>> table = Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml"
>>> drawn = scheme(assur.analyse(table, points=36).motion, [0, 9])
>>> [(plate.link, plate.outline.shape) for plate in drawn.plates]
[('1', (2, 2)), ('2', (2, 2)), ('3', (2, 2))]
>>> [(hinge.name, hinge.support is not None) for hinge in drawn.hinges]
[('A', True), ('B', False), ('C', False), ('D', True)]
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import numpy.typing as npt

from assur.kinematics.analysis import Motion, SliderState, values
from assur.model import LinkId
from assur.text import render
from assur.typing import BoolArray, ComplexArray, FloatArray, IntArray, Value

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["COLOURS", "Block", "Guide", "Hinge", "Path", "Plate", "Scheme", "Tracer",
           "coinciding", "draw_paths", "draw_scheme", "paths", "scheme", "track",
           "working_space"]

#: Colours of the links, in the order of their numbers (matplotlib's ten-colour cycle).
COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#bcbd22", "#17becf",
           "#e377c2")
#: A slider block about its point along the x axis, and a support under a hinge, in radii.
_BLOCK = np.array([-2.2 - 1.1j, 2.2 - 1.1j, 2.2 + 1.1j, -2.2 + 1.1j, -2.2 - 1.1j],
                  dtype=np.complex128)
_SUPPORT = np.array([0, -1.92 - 1.92j, 1.92 - 1.92j, 0], dtype=np.complex128)
_TICKS = 8  # hatching strokes along a frame guide


class Plate(NamedTuple):
    """A moving link.

    Attributes
    ----------
    link : str
        The link's number.
    colour : str
        Its colour, ``#rrggbb``.
    members : tuple of str
        Names of its points: hinges and slider blocks by pair id, tracing points.
    order : ndarray of int, shape (P, m)
        At each position, its members (indices into ``members``) in drawing order: around
        their centre for three or more, the missing ones (NaN) last.
    outline : ndarray of complex, shape (P, m)
        Its points in that order: a bar for two finite points, a plate for more.
    label : ndarray of complex, shape (P,)
        Where its number is written (NaN where it has no point).
    """

    link: str
    colour: str
    members: tuple[str, ...]
    order: IntArray
    outline: ComplexArray
    label: ComplexArray


class Hinge(NamedTuple):
    """A revolute pair.

    Attributes
    ----------
    name : str
        The pair's id.
    at : ndarray of complex, shape (P,)
    support : ndarray of complex, shape (P, 4), or None
        The triangle of the frame's support under a hinge on the frame; None otherwise.
    """

    name: str
    at: ComplexArray
    support: ComplexArray | None


class Block(NamedTuple):
    """The slider block of a prismatic pair.

    Attributes
    ----------
    name : str
        The pair's id.
    at : ndarray of complex, shape (P,)
        The slider's point on the guide.
    angle : ndarray of float, shape (P,)
        The guide's direction, rad.
    shape : ndarray of complex, shape (5,)
        The closed rectangle of the block about its point, along the x axis.
    """

    name: str
    at: ComplexArray
    angle: FloatArray
    shape: ComplexArray

    @property
    def outline(self) -> ComplexArray:
        """The closed rectangle at each position, shape (P, 5)."""
        turned: ComplexArray = self.at[:, None] + self.shape * np.exp(1j * self.angle)[:, None]
        return turned


class Guide(NamedTuple):
    """A guide line over the stroke of its slider, with a margin.

    Attributes
    ----------
    name : str
        The prismatic pair's id.
    ground : bool
        The guide is the frame's (drawn thicker and hatched).
    ends : ndarray of complex, shape (P, 2)
    hatch : ndarray of complex, shape (P, k, 2)
        Ends of the hatching strokes (k = 0 for a guide on a moving link).
    """

    name: str
    ground: bool
    ends: ComplexArray
    hatch: ComplexArray


class Tracer(NamedTuple):
    """A tracing point (a point of a link whose path is drawn).

    Attributes
    ----------
    name : str
    at : ndarray of complex, shape (P,)
    """

    name: str
    at: ComplexArray


class Scheme(NamedTuple):
    """The primitives of a mechanism at chosen positions.

    Attributes
    ----------
    r : float
        The radius of a hinge, mm (1.2 % of the working space); every size is a multiple.
    plates, hinges, blocks, guides, tracers : tuple
        In drawing order.
    labels : dict
        Hinge or tracing point name → the label written beside it at each position: the
        names of the points within 1.5 radii of it joined by ``=`` (``B=C``), empty where it
        is merged into an earlier point's label or the point does not exist.
    """

    r: float
    plates: tuple[Plate, ...]
    hinges: tuple[Hinge, ...]
    blocks: tuple[Block, ...]
    guides: tuple[Guide, ...]
    tracers: tuple[Tracer, ...]
    labels: dict[str, tuple[str, ...]]


class Path(NamedTuple):
    """A traced path.

    Attributes
    ----------
    name : str
        The tracing point's name or the joint's id.
    tracing : bool
        A tracing point's path (a joint's otherwise).
    curve : ndarray of complex, shape (P,)
    """

    name: str
    tracing: bool
    curve: ComplexArray


def track(x: Value, size: int) -> ComplexArray:
    """A point (or value) of a motion at every position of its cycle, shape ``(size,)``.

    A constant (a frame pivot) is repeated; a single design's ``(1, size)`` is flattened.
    """
    z = np.asarray(values(x), dtype=np.complex128).reshape(-1)
    return np.broadcast_to(z, (size,)) if z.size == 1 else z


def working_space(motion: Motion) -> tuple[float, float, float, float]:
    """Limits ``(x0, x1, y0, y1)`` of every joint, slider base and tracing point over the
    cycle, with a margin of 8 % (mm)."""
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


def _span(motion: Motion) -> float:
    x0, x1, y0, y1 = working_space(motion)
    return max(x1 - x0, y1 - y0)


def _order(z: ComplexArray) -> IntArray:
    """The drawing order of a link's points ``z`` (P, m): two as they are, more sorted
    around their centre; the missing ones last."""
    finite = np.isfinite(z)
    if z.shape[1] < 3:
        return np.argsort(~finite, axis=1, kind="stable")
    angle = np.where(finite, np.angle(z - _centre(z)[:, None]), np.inf)
    return np.argsort(angle, axis=1, kind="stable")


def _centre(z: ComplexArray) -> ComplexArray:
    """The mean of the finite points of each row, NaN for a row with none."""
    finite = np.isfinite(z)
    count = finite.sum(axis=1)
    total: ComplexArray = np.where(finite, z, 0).sum(axis=1)
    with np.errstate(invalid="ignore"):
        return total / np.where(count > 0, count, np.nan)


def _free(at: ComplexArray, placed: list[ComplexArray], step: complex, gap: float
          ) -> ComplexArray:
    """``at`` moved by ``step`` until it is at least ``gap`` from every placed point."""
    while True:
        near = np.zeros(at.shape, dtype=bool)
        for other in placed:
            near |= np.abs(at - other) < gap
        if not near.any():
            return at
        at = np.where(near, at + step, at)


def _labels(named: list[tuple[str, ComplexArray]], radius: float
            ) -> dict[str, tuple[str, ...]]:
    """Names of points that lie within ``radius`` of an earlier point's merged into its label."""
    head = np.full((len(named), named[0][1].size) if named else (0, 0), -1)
    for i, (_, z) in enumerate(named):
        for j in range(i):
            near = (head[i] < 0) & (head[j] == j) & (np.abs(z - named[j][1]) <= radius)
            head[i] = np.where(near, j, head[i])
        head[i] = np.where((head[i] < 0) & np.isfinite(z), i, head[i])
    texts = np.full(head.shape, "", dtype=object)
    for i, (name, _) in enumerate(named):
        for j in range(i + 1):
            texts[j] = np.where(head[i] == j, np.where(texts[j] == "", name,
                                                       texts[j] + "=" + name), texts[j])
    return {name: tuple(str(t) for t in texts[i]) for i, (name, _) in enumerate(named)}


def scheme(motion: Motion, picks: Sequence[int] | npt.NDArray[np.intp], *,
           attached: Mapping[str, tuple[LinkId, ComplexArray]] | None = None) -> Scheme:
    """The primitives of the mechanism at chosen positions.

    Parameters
    ----------
    motion : Motion
        One design over the cycle.
    picks : sequence of int
        The positions, indices into the cycle.
    attached : mapping, optional
        More points drawn as tracing points: name → (the link that carries it, the point at
        every position of the cycle), e.g. the output point of a synthesis problem.

    Returns
    -------
    Scheme
        Every array shaped ``(len(picks), ...)``; sizes in multiples of ``r``.
    """
    model = motion.model
    n = motion.q.size
    picks = np.asarray(picks, dtype=np.intp)
    r = 0.012 * _span(motion)

    def at(x: Value) -> ComplexArray:
        return track(x, n)[picks]

    points_of: dict[LinkId, list[tuple[str, ComplexArray]]] = {}
    hinges = []
    for pid, (kind, links, _) in model.pair_links.items():
        if kind == "R" and pid in motion.joints:
            z = at(motion.joints[pid])
            hinges.append(Hinge(str(pid), z, z[:, None] + r * _SUPPORT
                                if model.frame in links else None))
            for link in links:
                points_of.setdefault(link, []).append((str(pid), z))
    blocks, guides = [], []
    for pid, slider in motion.sliders.items():
        z, angle = at(slider.point), at(slider.angle).real
        points_of.setdefault(slider.slider, []).append((str(pid), z))
        blocks.append(Block(str(pid), z, angle, _BLOCK * r))
        guides.append(_guide(str(pid), slider, picks, n, r, slider.carrier == model.frame))
    carried = [(traced.anchor.link, traced.name, motion.tracing[traced.name])
               for traced in model.tracing]
    carried += [(link, name, point) for name, (link, point) in (attached or {}).items()]
    tracers = []
    for link, name, point in carried:
        tracers.append(Tracer(name, at(point)))
        points_of.setdefault(link, []).append((name, tracers[-1].at))
    plates: list[Plate] = []
    placed: list[ComplexArray] = []
    for k, (link, pts) in enumerate(sorted(points_of.items(), key=lambda kv: str(kv[0]))):
        if link == model.frame:
            continue
        z = np.stack([point for _, point in pts], axis=1)
        order = _order(z)
        label = _free(_centre(z) + 1.8 * r * (1 + 1j), placed, 2.2j * r, 2.0 * r)
        placed.append(label)
        plates.append(Plate(str(link), COLOURS[k % len(COLOURS)], tuple(n for n, _ in pts),
                            order, np.take_along_axis(z, order, axis=1), label))
    named = [(h.name, h.at) for h in hinges] + [(t.name, t.at) for t in tracers]
    return Scheme(r, tuple(plates), tuple(hinges), tuple(blocks), tuple(guides), tuple(tracers),
                  _labels(named, 1.5 * r))


def _guide(name: str, slider: SliderState, picks: npt.NDArray[np.intp], n: int, r: float,
           ground: bool) -> Guide:
    """The guide line over its slider's stroke (a guide on a moving link from its base point)."""
    s_all = np.asarray(values(slider.s)).real.ravel()
    finite = s_all[np.isfinite(s_all)]
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (np.nan, np.nan)
    if not ground:
        lo, hi = min(lo, 0.0), max(hi, 0.0)
    margin = 0.15 * max(hi - lo, 4 * r)
    u = np.exp(1j * track(slider.angle, n)[picks].real)
    offset = float(np.asarray(slider.offset).real.ravel()[0])
    line = track(slider.base, n)[picks] + 1j * offset * u
    ends = line[:, None] + np.array([lo - margin, hi + margin]) * u[:, None]
    if ground:
        along = ends[:, :1] + np.linspace(0, 1, _TICKS) * (ends[:, 1:] - ends[:, :1])
        tick = (-1j * u * 0.6 * r * (1 + 0.5j))[:, None]
        hatch = np.stack([along, along + tick], axis=2)
    else:
        hatch = np.zeros((picks.size, 0, 2), dtype=complex)
    return Guide(name, ground, ends, hatch)


def coinciding(curves: Mapping[str, npt.NDArray[np.generic]], tolerance: float
               ) -> dict[str, str]:
    """Which curves coincide with an earlier one over their whole length.

    Parameters
    ----------
    curves : mapping
        Name → values (real or complex) at the same positions; NaN where undefined.
    tolerance : float
        Largest difference still counted as the same value.

    Returns
    -------
    dict
        Name of a later curve → name of the first curve it coincides with (a curve with no
        finite value coincides with nothing).

    Examples
    --------
    >>> coinciding({"a": np.array([1.0, 2.0]), "b": np.array([1.0, 2.0 + 1e-12]),
    ...             "c": np.array([1.0, 3.0])}, 1e-9)
    {'b': 'a'}
    """
    same: dict[str, str] = {}
    seen: list[tuple[str, npt.NDArray[np.generic]]] = []
    for name, curve in curves.items():
        z = np.asarray(curve).ravel()
        finite = np.isfinite(z)
        if not finite.any():
            continue
        for first, other in seen:
            if (other.shape == z.shape and np.array_equal(finite, np.isfinite(other))
                    and np.max(np.abs(z[finite] - other[finite])) <= tolerance):
                same[name] = first
                break
        else:
            seen.append((name, z))
    return same


def paths(motion: Motion, picks: Sequence[int] | npt.NDArray[np.intp] | None = None
          ) -> tuple[list[Path], dict[str, str]]:
    """The paths of the tracing points and of the moving joints.

    Parameters
    ----------
    motion : Motion
        One design over the cycle.
    picks : sequence of int, optional
        The positions kept (every position when None).

    Returns
    -------
    paths : list of Path
        Tracing points first, then the joints that move; a path that coincides with an
        earlier one over the whole cycle is left out.
    same : dict
        Name of a path left out → the name of the path it coincides with.
    """
    n = motion.q.size
    kept = np.arange(n) if picks is None else np.asarray(picks, dtype=np.intp)
    scale = _span(motion)
    curves = {name: track(point, n) for name, point in motion.tracing.items()}
    for pid, point in motion.joints.items():
        z = track(point, n)
        finite = z[np.isfinite(z)]
        if finite.size and np.max(np.abs(finite - finite[0])) > 1e-9 * scale:
            curves[str(pid)] = z
    same = coinciding(curves, 1e-6 * scale)
    return ([Path(name, name in motion.tracing, z[kept]) for name, z in curves.items()
             if name not in same], same)


def draw_paths(ax: Axes, motion: Motion, lang: str) -> None:
    """Draw the paths of :func:`paths` (tracing points red, joints dotted grey), the paths
    that coincide named in a note."""
    drawn, same = paths(motion)
    for path in drawn:
        ax.plot(path.curve.real, path.curve.imag, "-" if path.tracing else ":",
                color="tab:red" if path.tracing else "0.6", lw=1.2 if path.tracing else 0.7,
                zorder=1)
    if same:
        groups: dict[str, list[str]] = {}
        for name, first in same.items():
            groups.setdefault(first, [first]).append(name)
        note = render("plot.same_path", lang,
                      names="; ".join(" = ".join(names) for names in groups.values()))
        ax.text(0.01, 0.01, note, transform=ax.transAxes, fontsize=7, color="0.3",
                va="bottom", ha="left", zorder=7)


def _finite(z: ComplexArray) -> ComplexArray:
    keep: BoolArray = np.isfinite(z)
    return z[keep]


def draw_scheme(ax: Axes, drawn: Scheme, k: int = 0, *, labels: bool = True) -> None:
    """Draw a scheme at one of its positions on a matplotlib axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Where to draw (nothing else of it is changed).
    drawn : Scheme
        From :func:`scheme`.
    k : int
        Which of its positions (an index into its picks).
    labels : bool
        Write link numbers and joint names.
    """
    from matplotlib.patches import Circle

    r = drawn.r
    for guide in drawn.guides:
        ends = guide.ends[k]
        if not np.isfinite(ends).all():
            continue
        ax.plot(ends.real, ends.imag, "-", color="0.35", lw=2.2 if guide.ground else 1.4,
                zorder=2)
        for stroke in guide.hatch[k]:
            ax.plot(stroke.real, stroke.imag, "-", color="0.5", lw=0.6, zorder=2)
    for plate in drawn.plates:
        z = _finite(plate.outline[k])
        if z.size >= 3:
            ax.fill(z.real, z.imag, color=plate.colour, alpha=0.25, zorder=3)
            ax.plot(np.r_[z.real, z.real[0]], np.r_[z.imag, z.imag[0]], "-",
                    color=plate.colour, lw=2.5, zorder=3)
        elif z.size == 2:
            ax.plot(z.real, z.imag, "-", color=plate.colour, lw=3, zorder=3,
                    solid_capstyle="round")
        at = plate.label[k]
        if labels and np.isfinite(at):
            ax.text(at.real, at.imag, plate.link, color=plate.colour, fontsize=9,
                    weight="bold", zorder=6)
    for block in drawn.blocks:
        rectangle = block.outline[k]
        if np.isfinite(rectangle).all():
            ax.fill(rectangle.real, rectangle.imag, color="white", ec="black", lw=1.2, zorder=4)
    for hinge in drawn.hinges:
        z = hinge.at[k]
        if not np.isfinite(z):
            continue
        if hinge.support is not None:
            ax.fill(hinge.support[k].real, hinge.support[k].imag, color="0.8", ec="black",
                    lw=0.8, zorder=4)
        ax.add_patch(Circle((z.real, z.imag), r, facecolor="white", edgecolor="black", lw=1.2,
                            zorder=5))
    for tracer in drawn.tracers:
        z = tracer.at[k]
        if np.isfinite(z):
            ax.plot([z.real], [z.imag], "o", color="tab:red", ms=5, zorder=6)
    if labels:
        at = {hinge.name: hinge.at[k] for hinge in drawn.hinges}
        at.update((tracer.name, tracer.at[k]) for tracer in drawn.tracers)
        for name, texts in drawn.labels.items():
            z, text = at[name], texts[k]
            if text:
                ax.text(z.real + 1.2 * r, z.imag - 2.2 * r, text, fontsize=7, color="0.2",
                        zorder=6)
