"""A mechanism with higher pairs beside its replacing mechanism, at the sketched position.

The left panel draws the mechanism as given: each link through its lower pairs (a revolute
pair as a small circle, a prismatic pair as a block on its guide line, a pair on the frame
on a hatched base), and the profiles of the higher pairs — circles (rollers, eccentric
discs), knife edges, flat faces, tabulated cam profiles, and for a gear mesh the pitch
circles, the base circles and the line of action. The right panel is the structural scheme
of the replacing mechanism (:func:`assur.plot.schemes.draw_structural_scheme`), whose
replacing links stand where the left panel draws them dashed: between the centres of
curvature of the profiles at the contact.

Every drawn profile carries a ``gid`` (``profile-<pair id>-<k>``), every replacing link
``replacing-<link>``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from assur.model import Chain, CircleProfile, LineProfile, LinkId, PairType, Profile, joint_key
from assur.plot.schemes import draw_structural_scheme, framed, separate_labels
from assur.profiles import gear_contact, polar_points
from assur.text import render

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from assur.structure.analysis import StructuralAnalysis

__all__ = ["draw_higher_mechanism", "replacing_figure"]

#: Figure size in inches: two panels side by side (scaled to the page by the report).
SIZE = (10.0, 4.4)
_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b")


def replacing_figure(analysis: StructuralAnalysis, *, lang: str = "en") -> Figure:
    """The mechanism with its higher pairs (left) and the structural scheme of its
    replacing mechanism (right).

    Parameters
    ----------
    analysis : StructuralAnalysis
        The analysis of a chain with higher pairs and a sketch (``analysis.original``).
    lang : {"en", "ru"}

    Returns
    -------
    matplotlib Figure (not attached to pyplot)

    Raises
    ------
    ValueError
        For an analysis of a chain without higher pairs or without a sketch.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/cam_lever.yaml"
    >>> figure = replacing_figure(assur.analyse_structure(assur.load_chain(table)))
    >>> len(figure.axes)
    2
    """
    from matplotlib.figure import Figure

    original = analysis.original
    if original is None or original.geometry is None:
        raise ValueError("the analysis is not of a chain with higher pairs and a sketch")
    fig = Figure(figsize=SIZE, layout="constrained")
    left, right = fig.subplots(1, 2)
    draw_higher_mechanism(original, analysis, ax=left, lang=lang)
    draw_structural_scheme(analysis.chain, analysis, ax=right, lang=lang)
    right.set_title(render("scheme.replacing", lang), fontsize=12)
    separate_labels(fig)
    return fig


def draw_higher_mechanism(chain: Chain, analysis: StructuralAnalysis, *, ax: Axes,
                          lang: str = "en") -> Axes:
    """Draw a chain with higher pairs at its sketch, with its replacing links dashed.

    Parameters
    ----------
    chain : Chain
        The chain as given (with higher pairs and a sketch).
    analysis : StructuralAnalysis
        Its analysis (the replacing links come from ``analysis.replacements``).
    ax : matplotlib Axes
    lang : {"en", "ru"}

    Returns
    -------
    matplotlib Axes
    """
    sketch = chain.geometry
    assert sketch is not None
    colour = {link: _COLOURS[k % len(_COLOURS)] for k, link in enumerate(chain.moving_links)}
    size = _size(chain)
    anchors: dict[LinkId, list[complex]] = {link: [] for link in chain.links}
    for pair in chain.pairs:
        at = sketch.points.get(joint_key(pair))
        if at is None:
            continue
        for link in pair.links:
            anchors[link].append(at)
    for higher in chain.higher:
        for link, profile in zip(higher.links, sketch.profiles.get(higher.id, ()), strict=False):
            anchors[link].append(_anchor(profile))
    for link in chain.moving_links:
        points = list(dict.fromkeys(anchors[link]))
        if len(points) > 1:
            loop = [*points, points[0]] if len(points) > 2 else points
            ax.plot([p.real for p in loop], [p.imag for p in loop], color=colour[link],
                    lw=2.2, solid_capstyle="round", zorder=2, gid=f"link-{link}")
        if points:
            middle = sum(points) / len(points)
            ax.annotate(str(link), (middle.real, middle.imag), xytext=(6, 6),
                        textcoords="offset points", fontsize=10, fontweight="bold",
                        color=colour[link], zorder=8, gid="label-link")
    for higher in chain.higher:
        profiles = sketch.profiles.get(higher.id, ())
        for k, (link, profile) in enumerate(zip(higher.links, profiles, strict=False)):
            _profile(ax, profile, colour.get(link, "dimgray"), size, f"profile-{higher.id}-{k}")
        if higher.gear is not None and len(profiles) == 2:
            first, second = profiles
            assert isinstance(first, CircleProfile) and isinstance(second, CircleProfile)
            touch = gear_contact(higher.gear, (first.centre, second.centre))
            for centre, foot in zip((first.centre, second.centre), touch.centres, strict=True):
                assert foot is not None
                _circle(ax, centre, abs(foot - centre), "gray", ":", f"base-{higher.id}")
            feet = [p for p in touch.centres if p is not None]
            ax.plot([p.real for p in feet], [p.imag for p in feet], color="gray", lw=0.8,
                    zorder=1, gid=f"line-of-action-{higher.id}")
    for pair in chain.pairs:
        at = sketch.points.get(joint_key(pair))
        if at is None:
            continue
        on_frame = chain.frame in pair.links
        if pair.type is PairType.R:
            ax.plot([at.real], [at.imag], "o", ms=6, mfc="white", mec="black", zorder=6,
                    gid=f"pair-{pair.id}")
        else:
            direction = sketch.directions[joint_key(pair)].unit
            ends = [at - direction * size, at + direction * size]
            ax.plot([p.real for p in ends], [p.imag for p in ends], color="black", lw=1,
                    zorder=3, gid=f"guide-{pair.id}")
            ax.plot([at.real], [at.imag], "s", ms=9, mfc="white", mec="black", zorder=6,
                    gid=f"pair-{pair.id}")
        if on_frame:
            ax.plot([at.real], [at.imag - 0.15 * size], "^", ms=10, mfc="none",
                    mec="black", zorder=5)
        ax.annotate(str(pair.origin if pair.origin is not None else pair.id),
                    (at.real, at.imag), xytext=(-9, -12), textcoords="offset points",
                    fontsize=9, color="#444444", zorder=8, gid="label-pair")
    for item in analysis.replacements:
        dashed = [point for point in item.points if point is not None]
        if len(dashed) == 2 and dashed[0] != dashed[1]:
            ax.plot([p.real for p in dashed], [p.imag for p in dashed], "--", color="black",
                    lw=1.2, zorder=7, gid=f"replacing-{item.link}")
    return framed(ax, render("scheme.original", lang), 0.1)


def _size(chain: Chain) -> float:
    """A tenth of the sketch's extent: the size of the drawn marks."""
    sketch = chain.geometry
    assert sketch is not None
    points = list(sketch.points.values()) or [0j]
    extent = max(abs(p - q) for p in points for q in points)
    return max(extent, 1.0) / 10


def _anchor(profile: Profile) -> complex:
    """The point of a profile that its link's outline runs to."""
    if isinstance(profile, CircleProfile):
        return profile.centre
    if isinstance(profile, LineProfile):
        return profile.point
    return profile.centre


def _circle(ax: Axes, centre: complex, radius: float, colour: str, style: str,
            gid: str) -> None:
    turn = np.exp(1j * np.linspace(0.0, 2 * np.pi, 181))
    curve = centre + radius * turn
    ax.plot(curve.real, curve.imag, style, color=colour, lw=1.4, zorder=4, gid=gid)


def _profile(ax: Axes, profile: Profile, colour: str, size: float, gid: str) -> None:
    """One profile: a circle (a knife edge as a wedge mark), a stretch of line, a table."""
    if isinstance(profile, CircleProfile):
        if profile.is_point:
            ax.plot([profile.centre.real], [profile.centre.imag], "v", ms=8, color=colour,
                    zorder=5, gid=gid)
        else:
            _circle(ax, profile.centre, profile.radius, colour, "--" if profile.concave
                    else "-", gid)
        return
    if isinstance(profile, LineProfile):
        unit = profile.direction.unit
        ends = [profile.point - 2 * size * unit, profile.point + 2 * size * unit]
        ax.plot([p.real for p in ends], [p.imag for p in ends], color=colour, lw=2.4,
                zorder=4, gid=gid)
        return
    curve = polar_points(profile, np.linspace(0.0, 2 * np.pi, 361))[0]
    ax.plot(curve.real, curve.imag, color=colour, lw=1.4, zorder=4, gid=gid)
