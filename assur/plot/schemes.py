"""Structural schemes as pictures: the structural scheme and the formalised scheme.

Two drawings of ``method.md`` §1.4 steps 12–13:

* the **structural scheme** (структурная схема, fig. 1.26): links and kinematic pairs drawn
  as the course draws them — a revolute pair (В) as a small circle, a prismatic pair (П) as
  a slider block on its guide line, frame pairs on a hatched base, links with three pairs
  as shaded triangles, the input link with an arrow — and every Assur group outlined and
  labelled with its class, order and kind;
* the **formalised structural scheme** (формализованная структурная схема, fig. 1.27): the
  graph of groups in layering order, an arrow from the group that moves a link to the group
  attached to it.

The layout is automatic. When the chain table gives pair coordinates (``geometry:``) the
scheme uses them; otherwise the links are placed in columns by layering level (a layered
layout) and every pair sits between the two links it joins.

Every drawn pair and group carries a ``gid`` (``pair-<id>``, ``group-<name>``), so an SVG
file can be checked element by element.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.errors import StructureError
from assur.io.files import atomic_write_bytes
from assur.kinds import KINDS
from assur.model import Chain, LinkId, Pair, PairId, PairType, id_key, joint_key
from assur.plot.formats import PICTURE_FORMATS, PictureFormatError, figure_bytes, picture_format
from assur.structure.classification import roman as roman_numeral
from assur.structure.classification import subscript
from assur.structure.group_models import GroupModelRow, group_models_table
from assur.text import render

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.text import Annotation
    from matplotlib.transforms import Bbox

    from assur.structure.analysis import StructuralAnalysis
    from assur.structure.classification import AssurGroup

__all__ = [
    "PictureFormatError",
    "SchemeLayout",
    "draw_formalised_scheme",
    "draw_structural_scheme",
    "framed",
    "group_graph",
    "roman",
    "save_schemes",
    "scheme_bytes",
    "scheme_figure",
    "scheme_layout",
]

#: The smallest type size of a scheme, in points: a scheme is drawn at its print size (it fits
#: the width of an A4 page, see :data:`SCHEME_SIZE`), so every label reads at 9 pt or more.
LABEL_PT = 9.0
#: Figure sizes in inches (width within the 18 cm of an A4 page's text).
SCHEME_SIZE = {"structural": (7.0, 5.2), "formalised": (7.0, 3.4), "both": (7.0, 9.0)}
#: Where a label may go, as shifts (points) from the place it is drawn at, the first tried
#: first (:func:`separate_labels`).
_SHIFTS = ((0, 0), (20, 0), (-20, 0), (0, 24), (0, -24), (20, 24), (-20, 24), (20, -24),
           (-20, -24), (34, 0), (-34, 0), (0, 36), (0, -36))
#: The further places a point's name may go: a leader line joins it to its point.
_FAR = ((48, 0), (-48, 0), (0, 48), (0, -48), (48, 40), (-48, 40), (48, -40), (-48, -40),
        (70, 0), (-70, 0), (0, 64), (0, -64))
#: The labels :func:`separate_labels` moves, in the order they are placed.
_MOVABLE = ("label-link", "label-group", "label-pair", "label-point", "label-edge")
#: The colour of the points the course asks to mark (N, M, A_k, B_k).
_POINT_COLOUR = "#8b0000"

_GROUP_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b",
                  "#e377c2", "#7f7f7f", "#bcbd22")
def roman(value: Any) -> str:
    """A group or mechanism class as a Roman numeral (``2`` → ``"II"``; texts pass through).

    >>> roman(2), roman("III"), roman(None)
    ('II', 'III', '–')
    """
    if value is None:
        return "–"
    if isinstance(value, int) and not isinstance(value, bool) and value > 0:
        return roman_numeral(value)
    return str(value)


# ----------------------------------------------------------------------------- the groups


@dataclass(frozen=True)
class _Group:
    """What the drawings need of one group (the input group included)."""

    name: str
    links: tuple[LinkId, ...]
    level: int
    group_class: int
    order: int
    kind: int | None
    is_input: bool
    external: tuple[tuple[PairId, LinkId, LinkId], ...]
    signature: str = ""


def _groups(analysis: StructuralAnalysis, chain: Chain) -> list[_Group]:
    """Input groups and Assur groups of an analysis, in layering order."""
    result = [_as_group(group, is_input=True) for group in analysis.input_groups]
    result += [_as_group(group, is_input=False) for group in analysis.groups]
    seen: set[str] = set()
    unique = []
    for item in result:
        if item.name not in seen:
            seen.add(item.name)
            unique.append(item)
    return sorted(unique, key=lambda g: (g.level, not g.is_input))


def _as_group(group: AssurGroup, *, is_input: bool) -> _Group:
    return _Group(name=group.label, links=tuple(group.links), level=group.level,
                  group_class=group.group_class, order=group.order, kind=group.kind,
                  is_input=is_input or group.level == 0, external=tuple(group.external),
                  signature=group.name)


def _kind_text(group: _Group, lang: str) -> str:
    """The kind of a dyad with its pair string, or the signature of a larger group."""
    kind = group.kind
    if isinstance(kind, int) and not isinstance(kind, bool):
        code = KINDS[kind].pair_text(lang) if kind in KINDS else ""
        return f"{kind} ({code})" if code else str(kind)
    return group.signature or "–" if kind is None else str(kind)


def _group_caption(group: _Group, lang: str) -> str:
    if group.is_input:
        return f"{group.name}\n{render('scheme.input', lang)}"
    kind = _kind_text(group, lang)
    if group.kind is not None:
        kind = render("scheme.kind", lang, pairs=kind)
    return f"{group.name}\n" + render("scheme.group", lang, group_class=roman(group.group_class),
                                       order=group.order, kind=kind)


def group_graph(chain: Chain, analysis: StructuralAnalysis
                ) -> list[tuple[str, str, tuple[PairId, ...]]]:
    """Edges of the formalised structural scheme.

    Parameters
    ----------
    chain : Chain
    analysis : StructuralAnalysis
        The result of :func:`assur.structure.analysis.analyse_structure`.

    Returns
    -------
    list of (source group, target group, pairs)
        An edge for every group that attaches to a link of another moving group, with the
        external pairs that make the attachment. Attachments to the frame are not edges
        (every group stands on the frame; the drawing shows the frame separately).
    """
    groups = _groups(analysis, chain)
    owner = {link: group for group in groups for link in group.links}
    edges: dict[tuple[str, str], list[PairId]] = {}
    for group in groups:
        for pair_id, _group_link, known in group.external:
            parent = owner.get(known)
            if parent is None or parent.level >= group.level:
                continue
            source = parent.name
            edges.setdefault((source, group.name), []).append(pair_id)
    return [(a, b, tuple(pairs)) for (a, b), pairs in edges.items()]


# ----------------------------------------------------------------------------- the layout


@dataclass(frozen=True)
class SchemeLayout:
    """Where the structural scheme puts things.

    Attributes
    ----------
    pairs : dict
        Pair id → position (complex ``x + 1j*y``).
    directions : dict
        P pair id → unit direction of its guide line (complex).
    links : dict
        Moving link id → the point where its number is written (complex).
    from_geometry : bool
        True when the positions are the table's coordinates, False for the layered layout.
    """

    pairs: dict[PairId, complex]
    directions: dict[PairId, complex]
    links: dict[LinkId, complex]
    from_geometry: bool


def _from_geometry(chain: Chain) -> tuple[dict[PairId, complex], dict[PairId, complex]] | None:
    """Pair positions and unit guide directions from the chain's sketch, if it has one."""
    sketch = chain.geometry
    if sketch is None or any(joint_key(pair) not in sketch.points for pair in chain.pairs):
        return None
    positions = {pair.id: sketch.points[joint_key(pair)] for pair in chain.pairs}
    directions = {pair.id: sketch.directions[joint_key(pair)].unit for pair in chain.pairs
                  if pair.type is PairType.P and joint_key(pair) in sketch.directions}
    return positions, directions


def _slider_positions(chain: Chain, positions: dict[PairId, complex],
                      directions: dict[PairId, complex]) -> dict[PairId, complex]:
    """Move each slider pair from the given point of its slide line to the slider itself.

    A table gives a prismatic pair as any point of the slide line and its direction. The
    slider block is drawn where the slider link is: at the foot of the perpendicular from
    the slider link's hinges to the line, or, for a slider with no hinge, where its two
    slide lines cross.
    """
    moved = dict(positions)
    for pair in chain.pairs:
        if pair.type is not PairType.P or pair.id not in directions:
            continue
        carrier = pair.guide if pair.guide is not None else pair.links[0]
        slider = pair.other(carrier)
        base, along = positions[pair.id], directions[pair.id]
        hinges = [positions[p.id] for p in chain.pairs_of(slider) if p.type is PairType.R]
        if hinges:
            centre = complex(np.mean(hinges))
            moved[pair.id] = base + along * ((np.conj(along) * (centre - base)).real)
            continue
        for other in chain.pairs_of(slider):
            if other.id == pair.id or other.type is not PairType.P or other.id not in directions:
                continue
            base2, along2 = positions[other.id], directions[other.id]
            det = (np.conj(along) * along2).imag
            if abs(det) > 1e-9:  # base + t·along = base2 + u·along2
                t = (np.conj(base2 - base) * along2).imag / det
                moved[pair.id] = base + t * along
                break
    return moved


def _link_levels(chain: Chain, groups: Sequence[_Group]) -> dict[LinkId, int]:
    levels = {link: group.level for group in groups for link in group.links}
    for link in chain.moving_links:  # links outside any group: one column past the last
        levels.setdefault(link, 1 + max(levels.values(), default=0))
    return levels


def _layered_links(chain: Chain, groups: Sequence[_Group]) -> dict[LinkId, complex]:
    """Link nodes in columns by level; in a column, groups follow their parents' heights."""
    levels = _link_levels(chain, groups)
    members: dict[int, list[tuple[LinkId, ...]]] = {}
    grouped: set[LinkId] = set()
    for group in groups:
        members.setdefault(group.level, []).append(group.links)
        grouped.update(group.links)
    for link in sorted(set(chain.moving_links) - grouped, key=id_key):
        members.setdefault(levels[link], []).append((link,))
    nodes: dict[LinkId, complex] = {}
    neighbours: dict[LinkId, list[LinkId]] = {link: [] for link in chain.links}
    for pair in chain.pairs:
        a, b = pair.links
        neighbours[a].append(b)
        neighbours[b].append(a)
    for level in sorted(members):
        heights = {links: [nodes[n].imag for link in links for n in neighbours[link]
                           if n in nodes] for links in members[level]}
        column = sorted(members[level],
                        key=lambda links: float(np.mean(heights[links])) if heights[links]
                        else 0.0)
        y = 0.0
        for links in column:
            for k, link in enumerate(links):
                nodes[link] = complex(3.2 * level, y + 1.4) + _member_offset(k, len(links))
            y += 3.2 if len(links) > 1 else 2.2
    return nodes


def _member_offset(k: int, count: int) -> complex:
    """Where the k-th link of a group sits around the group's centre."""
    if count == 1:
        return 0j
    if count == 2:  # a dyad: link i up-left, link j down-right
        return complex(-0.45 + 0.9 * k, 0.7 - 1.4 * k)
    angle = math.pi / 2 + 2 * math.pi * k / count
    return 0.9 * complex(0.6 * math.cos(angle), math.sin(angle))


def _layered_pairs(chain: Chain, nodes: dict[LinkId, complex]) -> dict[PairId, complex]:
    """A pair between the two links it joins (a frame pair under its link), never two pairs
    on one spot: a pair that would land on another one moves aside along its normal."""
    positions: dict[PairId, complex] = {}
    for pair in chain.pairs:
        a, b = pair.links
        if chain.frame in (a, b):
            moving = b if a == chain.frame else a
            at, aside = nodes[moving] - 1.1j, 0.5 + 0j
        else:
            at, span = (nodes[a] + nodes[b]) / 2, nodes[b] - nodes[a]
            aside = 0.35j * span / abs(span) if abs(span) > 1e-9 else 0.35 + 0j
        step = 0
        while any(abs(at + _shift(step) * aside - q) < 0.2 for q in positions.values()):
            step += 1
        positions[pair.id] = at + _shift(step) * aside
    return positions


def _shift(step: int) -> int:
    """0, 1, −1, 2, −2, … : the k-th place to try beside a taken spot."""
    return (step + 1) // 2 * (1 if step % 2 else -1)


def _drawn(chain: Chain, analysis: StructuralAnalysis) -> Chain:
    """The chain a scheme shows: the replacing mechanism of a chain with higher pairs (its
    groups are the analysis's), else the chain itself."""
    return analysis.chain if analysis.original is not None else chain


def scheme_layout(chain: Chain, analysis: StructuralAnalysis) -> SchemeLayout:
    """Positions of pairs and links for the structural scheme.

    Parameters
    ----------
    chain : Chain
    analysis : StructuralAnalysis

    Returns
    -------
    SchemeLayout
        The table's coordinates when every pair has a ``geometry`` point, else a layered
        layout (links in columns by layering level, a pair between the links it joins).
    """
    groups = _groups(analysis, chain)
    geometric = _from_geometry(chain)
    if geometric is not None:
        positions, directions = geometric
        positions = _slider_positions(chain, positions, directions)
        links = {}
        for link in chain.moving_links:
            points = [positions[p.id] for p in chain.pairs_of(link)]
            links[link] = complex(np.mean(points)) if points else 0j
        from_geometry = True
    else:
        links = _layered_links(chain, groups)
        positions = _layered_pairs(chain, links)
        directions = {}
        from_geometry = False
    for pair in chain.pairs:
        if pair.type is PairType.P and pair.id not in directions:
            directions[pair.id] = _guide_direction(chain, pair, positions, links)
    return SchemeLayout(pairs=positions, directions=directions, links=links,
                        from_geometry=from_geometry)


def _guide_direction(chain: Chain, pair: Pair, positions: dict[PairId, complex],
                     links: dict[LinkId, complex]) -> complex:
    """Guide line of a P pair without coordinates: along the carrier towards the slider."""
    carrier = pair.guide if pair.guide is not None else pair.links[0]
    slider = pair.other(carrier)
    if carrier == chain.frame:
        return 1 + 0j
    delta = links.get(slider, 0j) - links.get(carrier, 0j)
    if abs(delta) < 1e-9:
        return 1 + 0j
    return delta / abs(delta)


# ----------------------------------------------------------------------------- drawing


def _scale(layout: SchemeLayout) -> float:
    points = np.array(list(layout.pairs.values()) or [0j])
    span = max(float(np.ptp(points.real)), float(np.ptp(points.imag)), 1e-9)
    return span / 45.0 if layout.from_geometry else 0.14


def _ground(ax: Axes, at: complex, size: float, direction: complex = 1 + 0j) -> None:
    """A hatched base (frame) under a point, along ``direction``."""
    along = direction / abs(direction)
    down = -1j * along
    if down.imag > 0:
        down = -down
    base = at + down * size * 1.1
    a, b = base - along * size * 1.6, base + along * size * 1.6
    ax.plot([a.real, b.real], [a.imag, b.imag], color="black", lw=1.2, zorder=2)
    for t in np.linspace(-1.4, 1.4, 6):
        p = base + along * size * t
        q = p + (down - along) * size * 0.5
        ax.plot([p.real, q.real], [p.imag, q.imag], color="black", lw=0.7, zorder=2)
    ax.plot([at.real, base.real], [at.imag, base.imag], color="black", lw=1.2, zorder=2)


def _draw_revolute(ax: Axes, pair: Pair, at: complex, size: float, chain: Chain) -> None:
    from matplotlib.patches import Circle

    if chain.frame in pair.links:
        _ground(ax, at, size * 1.6)
    circle = Circle((at.real, at.imag), size * 0.55, facecolor="white", edgecolor="black",
                    lw=1.3, zorder=6)
    circle.set_gid(f"pair-{pair.id}")
    ax.add_patch(circle)


def _draw_prismatic(ax: Axes, pair: Pair, at: complex, size: float, chain: Chain,
                    direction: complex) -> None:
    from matplotlib.patches import Polygon

    along = direction / abs(direction)
    across = 1j * along
    a, b = at - along * size * 3.2, at + along * size * 3.2
    carrier = pair.guide if pair.guide is not None else pair.links[0]
    ax.plot([a.real, b.real], [a.imag, b.imag], color="black", lw=1.6, zorder=3)
    if carrier == chain.frame:
        _ground(ax, at - across * size * 0.4 if across.imag > 0 else at + across * size * 0.4,
                size * 1.6, along)
    corners = [at + along * size * sx + across * size * sy * 0.6
               for sx, sy in ((-1.1, -1), (1.1, -1), (1.1, 1), (-1.1, 1))]
    block = Polygon([(c.real, c.imag) for c in corners], closed=True, facecolor="white",
                    edgecolor="black", lw=1.3, zorder=6)
    block.set_gid(f"pair-{pair.id}")
    ax.add_patch(block)


def _draw_link(ax: Axes, link: LinkId, points: list[complex], colour: str, size: float,
               is_input: bool) -> None:
    from matplotlib.patches import Polygon

    if len(points) >= 3:
        hull = _convex(points)
        poly = Polygon([(p.real, p.imag) for p in hull], closed=True, facecolor=colour,
                       alpha=0.18, edgecolor=colour, lw=2.2, zorder=4)
        poly.set_gid(f"link-{link}")
        ax.add_patch(poly)
    centre = complex(np.mean(points)) if points else 0j
    for p in points:
        line = ax.plot([centre.real, p.real] if len(points) >= 3 else [points[0].real, p.real],
                       [centre.imag, p.imag] if len(points) >= 3 else [points[0].imag, p.imag],
                       color=colour, lw=2.4, zorder=4, solid_capstyle="round")
        line[0].set_gid(f"link-{link}")
    if is_input and len(points) >= 2:
        from matplotlib.patches import FancyArrowPatch

        arrow = FancyArrowPatch((points[0].real + size * 2.2, points[0].imag),
                                (points[0].real, points[0].imag + size * 2.2),
                                connectionstyle="arc3,rad=0.5", arrowstyle="-|>",
                                mutation_scale=10, color="black", lw=1.0, zorder=7)
        ax.add_patch(arrow)


def _convex(points: Iterable[complex]) -> list[complex]:
    """Convex hull (monotone chain) of a few points; collinear input returns its ends."""
    unique = sorted({(round(p.real, 12), round(p.imag, 12)) for p in points})
    if len(unique) <= 2:
        return [complex(*u) for u in unique]

    def turn(o: tuple[float, float], a: tuple[float, float], b: tuple[float, float]) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[tuple[float, float]] = []
    for p in unique:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list[tuple[float, float]] = []
    for p in reversed(unique):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return [complex(*u) for u in lower[:-1] + upper[:-1]]


def _outline(points: list[complex], pad: float) -> list[complex]:
    """A rounded outline around points: the hull of small circles about each point."""
    ring = np.exp(1j * np.linspace(0, 2 * np.pi, 24, endpoint=False))
    cloud = [p + pad * r for p in points for r in ring]
    return _convex(cloud)


def _link_label_place(points: list[complex], node: complex) -> tuple[complex, complex]:
    """Where a link's number goes: beside the middle of a bar, inside a plate.

    Returns the anchor point and the offset in points (complex).
    """
    if len(points) == 2 and abs(points[1] - points[0]) > 0:
        along = (points[1] - points[0]) / abs(points[1] - points[0])
        normal = 1j * along if (1j * along).imag >= 0 else -1j * along
        return (points[0] + points[1]) / 2, 9 * normal
    if len(points) >= 3:
        return complex(np.mean(points)), 0j
    return (points[0] if points else node), complex(6, 6)


def _models(analysis: StructuralAnalysis) -> list[GroupModelRow]:
    """Table 1.5 of the mechanism; empty when it is not made of the course's groups."""
    try:
        return group_models_table(analysis)
    except StructureError:
        return []


def scheme_points(chain: Chain, analysis: StructuralAnalysis
                  ) -> list[tuple[str, PairId | None, PairId]]:
    """The points the course asks to mark on the schemes (step 15 of its procedure): the
    attachment points N_k, M_k of every group and the base points A_k, B_k of its guides.

    Returns
    -------
    list of (name, pair, where)
        The name (``N₂``; ``M₂~`` for a point that slides: a later link runs on a guide of
        the link), the pair it names (None for a base point), and the pair whose place in
        the drawing it is marked at: the hinge, the guide, or the hinge a base point is put
        at.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/slider_crank.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> scheme_points(analysis.chain, analysis)
    [('N₁', 'B', 'B'), ('A₂', None, 'D')]
    """
    del chain  # the analysis holds it; the signature is that of the drawings
    found: list[tuple[str, PairId | None, PairId]] = []
    for row in _models(analysis):
        sub = subscript(row.k)
        for letter, point in (("N", row.N), ("M", row.M)):
            if point is None:
                continue
            found += [(f"{letter}{sub}", pair, pair) for pair in point.hinges]
            found += [(f"{letter}{sub}~", pair, pair) for pair in point.guides]
        for base in (row.A, row.B):
            if base is not None:
                found.append((f"{base.letter}{sub}", None,
                              base.at if base.at is not None else base.pair))
    return found


def _base_place(chain: Chain, layout: SchemeLayout, pair: PairId) -> complex:
    """Where a base point is drawn: a hinge's place, or the point of the guide's line the
    sketch gives (where the student put the base), else the pair's place."""
    sketch = chain.geometry
    key = joint_key(chain.pair(pair))
    if chain.pair(pair).type is PairType.P and sketch is not None and key in sketch.points:
        return sketch.points[key]
    return layout.pairs[pair]


def _draw_points(ax: Axes, chain: Chain, analysis: StructuralAnalysis,
                 layout: SchemeLayout) -> None:
    """Mark N_k, M_k, A_k and B_k on the structural scheme."""
    for name, named, where in scheme_points(chain, analysis):
        at = layout.pairs[where] if named is not None else _base_place(chain, layout, where)
        if named is None:
            ax.plot([at.real], [at.imag], marker="x", ms=5, mew=1.2, color=_POINT_COLOUR,
                    zorder=7)
        ax.annotate(name, (at.real, at.imag), xytext=(6, 6), textcoords="offset points",
                    fontsize=LABEL_PT, fontstyle="italic", fontweight="bold",
                    color=_POINT_COLOUR, zorder=8, gid="label-point",
                    bbox={"boxstyle": "round,pad=0.05", "fc": "white", "ec": "none",
                          "alpha": 0.8})


def _draw_leaders(labels: Iterable[Annotation]) -> None:
    """A thin line from each point's name, where :func:`separate_labels` put it, to its
    point (none when the name sits next to it)."""
    from matplotlib.lines import Line2D

    for label in labels:
        if label.get_gid() != "label-point" or label.axes is None:
            continue
        ax = label.axes
        box = label.get_window_extent()
        x, y = ax.transData.transform(label.xy)
        near = (min(max(x, box.x0), box.x1), min(max(y, box.y0), box.y1))
        if math.dist((x, y), near) < 6.0 * ax.figure.dpi / 72.0:
            continue
        (x0, y0), (x1, y1) = ax.transData.inverted().transform([(x, y), near])
        ax.add_line(Line2D([x0, x1], [y0, y1], color=_POINT_COLOUR, lw=0.6, zorder=7,
                           gid="leader"))


def draw_structural_scheme(chain: Chain, analysis: StructuralAnalysis, *, ax: Axes | None = None,
                           lang: str = "en", layout: SchemeLayout | None = None) -> Axes:
    """Draw the structural scheme (fig. 1.26 of the course).

    Parameters
    ----------
    chain : Chain
    analysis : StructuralAnalysis
        The groups to outline and label.
    ax : matplotlib Axes, optional
        Where to draw; a new figure is made when omitted.
    lang : {"en", "ru"}
    layout : SchemeLayout, optional
        Positions to use (default :func:`scheme_layout`).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> from matplotlib.figure import Figure
    >>> ax = Figure().subplots()
    >>> assur.draw_structural_scheme(analysis.chain, analysis, ax=ax) is ax
    True
    """
    ax = ax if ax is not None else _new_axes(SCHEME_SIZE["structural"])
    chain = _drawn(chain, analysis)
    layout = layout or scheme_layout(chain, analysis)
    size = _scale(layout)
    groups = _groups(analysis, chain)
    colour_of: dict[LinkId, str] = {}
    input_links: set[LinkId] = set()
    for k, group in enumerate(groups):
        for link in group.links:
            colour_of[link] = "black" if group.is_input else _GROUP_COLOURS[k % len(
                _GROUP_COLOURS)]
            if group.is_input:
                input_links.add(link)
    for link in chain.moving_links:
        points = [layout.pairs[p.id] for p in chain.pairs_of(link)]
        _draw_link(ax, link, points, colour_of.get(link, "dimgray"), size, link in input_links)
        where, offset = _link_label_place(points, layout.links.get(link, 0j))
        ax.annotate(str(link), (where.real, where.imag), xytext=(offset.real, offset.imag),
                    textcoords="offset points", fontsize=11, fontweight="bold",
                    ha="center", va="center", color=colour_of.get(link, "dimgray"), zorder=8,
                    bbox={"boxstyle": "round,pad=0.12", "fc": "white", "ec": "none",
                          "alpha": 0.85}, gid="label-link")
    for pair in chain.pairs:
        at = layout.pairs[pair.id]
        if pair.type is PairType.R:
            _draw_revolute(ax, pair, at, size, chain)
        else:
            _draw_prismatic(ax, pair, at, size, chain, layout.directions[pair.id])
        ax.annotate(str(pair.origin if pair.origin is not None else pair.id),
                    (at.real, at.imag), xytext=(-9, -12), textcoords="offset points",
                    fontsize=LABEL_PT, color="#444444", zorder=8, gid="label-pair",
                    bbox={"boxstyle": "round,pad=0.05", "fc": "white", "ec": "none",
                          "alpha": 0.8})
    _draw_points(ax, chain, analysis, layout)
    _draw_group_outlines(ax, chain, groups, layout, size, lang)
    return framed(ax, render("scheme.structural", lang), 0.12)


def framed(ax: Axes, title: str, margin: float) -> Axes:
    """A drawn mechanism's axes to scale and fitted to what is drawn, with ``margin`` (a
    fraction of the span) around it, no axis lines, and ``title``."""
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.margins(margin)
    ax.set_axis_off()
    ax.set_title(title, fontsize=12)
    return ax


def _draw_group_outlines(ax: Axes, chain: Chain, groups: Sequence[_Group],
                         layout: SchemeLayout, size: float, lang: str) -> None:
    """Dashed outline around each Assur group's own pairs; captions go to a legend."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Polygon

    handles = []
    for k, group in enumerate(groups):
        if group.is_input:
            continue
        colour = _GROUP_COLOURS[k % len(_GROUP_COLOURS)]
        members = set(group.links)
        own = {pid for pid, _g, _known in group.external}
        points = [layout.pairs[p.id] for p in chain.pairs
                  if p.id in own or set(p.links) <= members]
        if not points:
            continue
        outline = _outline(points, size * 2.4)
        patch = Polygon([(p.real, p.imag) for p in outline], closed=True, fill=False,
                        edgecolor=colour, lw=1.1, ls="--", zorder=1)
        patch.set_gid(f"group-{group.name}")
        ax.add_patch(patch)
        top = max(outline, key=lambda p: p.imag)
        ax.annotate(group.name, (top.real, top.imag), xytext=(0, 2),
                    textcoords="offset points", ha="center", va="bottom", fontsize=LABEL_PT,
                    color=colour, zorder=9, gid="label-group",
                    bbox={"boxstyle": "round,pad=0.05", "fc": "white", "ec": "none",
                          "alpha": 0.8})
        handles.append(Line2D([], [], color=colour, ls="--", lw=1.1,
                              label=_group_caption(group, lang).replace("\n", ": ")))
    if handles:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.01),
                  fontsize=LABEL_PT, frameon=False,
                  ncol=1 if len(handles) > 3 else len(handles))


def draw_formalised_scheme(chain: Chain, analysis: StructuralAnalysis, *, ax: Axes | None = None,
                           lang: str = "en") -> Axes:
    """Draw the formalised structural scheme (fig. 1.27 of the course).

    Groups are boxes in columns by layering level, left to right; an arrow joins a group
    to every group attached to one of its links, labelled with the attaching pairs. The
    frame is a box of its own at the left, with thin arrows to every group standing on it.

    Parameters
    ----------
    chain : Chain
    analysis : StructuralAnalysis
    ax : matplotlib Axes, optional
    lang : {"en", "ru"}

    Returns
    -------
    matplotlib Axes
    """
    from matplotlib.patches import FancyArrowPatch, Rectangle

    ax = ax if ax is not None else _new_axes(SCHEME_SIZE["formalised"])
    chain = _drawn(chain, analysis)
    groups = _groups(analysis, chain)
    marks: dict[PairId, list[str]] = {}
    for name, named, _ in scheme_points(chain, analysis):
        if named is not None:
            marks.setdefault(named, []).append(name)
    bases = {frozenset(x for x in (row.i, row.j) if x is not None): ", ".join(base.text().replace(f"_{row.k}", subscript(row.k))
                                  for base in (row.A, row.B) if base is not None)
             for row in _models(analysis)}
    by_level: dict[int, list[_Group]] = {}
    for group in groups:
        by_level.setdefault(group.level, []).append(group)
    tallest = max((len(m) for m in by_level.values()), default=1)
    step = 1.5 if any(bases.values()) else 1.2  # a node with its base points is taller
    where: dict[str, complex] = {}
    for level, members in sorted(by_level.items()):
        for k, group in enumerate(members):
            where[group.name] = complex(2.4 * level, step * (tallest - len(members)) / 2
                                        + step * (len(members) - 1 - k) + 1.3)
    colour = {g.name: ("black" if g.is_input else _GROUP_COLOURS[k % len(_GROUP_COLOURS)])
              for k, g in enumerate(groups)}
    left, right = -1.1, 2.4 * max(by_level, default=0) + 1.1
    ax.add_patch(Rectangle((left, -0.25), right - left, 0.25, facecolor="#eeeeee",
                           edgecolor="black", hatch="///", lw=1.0, zorder=1))
    ax.text(left + 0.05, -0.5, render("scheme.frame", lang), ha="left", va="top",
            fontsize=LABEL_PT)
    for group in groups:
        at = where[group.name]
        label = group.name if group.is_input else (
            f"{group.name}\n{roman(group.group_class)}/{group.order}, "
            f"{_kind_text(group, lang)}")
        if bases.get(frozenset(group.links)):
            label += f"\n{bases[frozenset(group.links)]}"
        node = ax.text(at.real, at.imag, label, ha="center", va="center", fontsize=9,
                       bbox={"boxstyle": "round,pad=0.35", "fc": "white", "lw": 1.4,
                             "ec": colour[group.name]}, zorder=5)
        node.set_gid(f"node-{group.name}")
        if group.is_input or any(known == chain.frame for _p, _g, known in group.external):
            ax.plot([at.real, at.real], [0.0, at.imag - 0.3], color="#999999", lw=0.8,
                    zorder=2)
    for source, target, pairs in group_graph(chain, analysis):
        a, b = where[source], where[target]
        arrow = FancyArrowPatch((a.real, a.imag), (b.real, b.imag), arrowstyle="-|>",
                                mutation_scale=14, color="black", lw=1.4, shrinkA=30,
                                shrinkB=30, zorder=3)
        arrow.set_gid(f"edge-{source}-{target}")
        ax.add_patch(arrow)
        mid = (a + b) / 2
        text = ", ".join(str(pair) + (f" ({', '.join(marks[pair])})" if pair in marks else "")
                         for pair in pairs)
        ax.annotate(text, (mid.real, mid.imag + 0.08), xytext=(0, 0),
                    textcoords="offset points", ha="center", va="bottom", fontsize=LABEL_PT,
                    color="#444444", zorder=4, gid="label-edge")
    top = step * tallest + 0.6 + (step - 1.2)
    for level in sorted(by_level):
        ax.text(2.4 * level, top, render("scheme.level", lang, level=level), ha="center",
                fontsize=LABEL_PT, color="#666666")
    ax.set_xlim(left - 0.1, right + 0.1)
    ax.set_ylim(-0.9, top + 0.4)
    ax.set_axis_off()
    ax.set_title(render("scheme.formalised", lang), fontsize=12)
    return ax


def _new_axes(size: tuple[float, float]) -> Axes:
    from matplotlib.figure import Figure

    return Figure(figsize=size, layout="constrained").add_subplot()


def scheme_figure(chain: Chain, analysis: StructuralAnalysis, *, lang: str = "en",
                  which: str = "both") -> Figure:
    """A figure with the structural scheme, the formalised scheme, or both stacked.

    Parameters
    ----------
    chain : Chain
    analysis : StructuralAnalysis
    lang : {"en", "ru"}
    which : {"both", "structural", "formalised"}

    Returns
    -------
    matplotlib Figure (not attached to pyplot; nothing is shown)
    """
    from matplotlib.figure import Figure

    if which not in ("both", "structural", "formalised"):
        raise ValueError(f"which must be 'both', 'structural' or 'formalised'; got {which!r}")
    fig = Figure(figsize=SCHEME_SIZE[which], layout="constrained")
    if which == "both":
        top, bottom = fig.subplots(2, 1, height_ratios=[2.2, 1])
        draw_structural_scheme(chain, analysis, ax=top, lang=lang)
        draw_formalised_scheme(chain, analysis, ax=bottom, lang=lang)
    else:
        ax = fig.add_subplot()
        draw = draw_structural_scheme if which == "structural" else draw_formalised_scheme
        draw(chain, analysis, ax=ax, lang=lang)
    _draw_leaders(separate_labels(fig))
    return fig


def separate_labels(fig: Figure) -> list[Annotation]:
    """Move the labels of the schemes of ``fig`` (links, groups, pairs, the pairs on the
    arrows of the formalised scheme, in that order) apart: each goes to the first place of :data:`_SHIFTS` where it covers no label
    placed before it and no joint; a label that fits nowhere takes the place where it
    overlaps least.  The layout is fixed first, and kept, so the places found are the
    places drawn.

    Returns
    -------
    list of Annotation
        The labels moved, placed.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Annotation
    from matplotlib.transforms import Bbox

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw_without_rendering()
    fig.set_layout_engine("none")
    placed = []
    movable: list[Annotation] = []
    joint = 5.0 * fig.dpi / 72.0  # half the size of a joint's circle, in pixels
    for ax in fig.axes:
        labels = [t for t in ax.texts if isinstance(t, Annotation) and t.get_gid() in _MOVABLE]
        movable += sorted(labels, key=lambda t: _MOVABLE.index(str(t.get_gid())))
        placed += [t.get_window_extent(renderer) for t in ax.texts if t not in labels]
        placed += [Bbox.from_extents(x - joint, y - joint, x + joint, y + joint)
                   for x, y in (ax.transData.transform(t.xy) for t in labels
                                if t.get_gid() == "label-pair")]
    for label in movable:
        start = label.xyann
        best: tuple[float, tuple[float, float]] | None = None
        shifts = (*_SHIFTS, *_FAR) if label.get_gid() == "label-point" else _SHIFTS
        for dx, dy in shifts:
            label.xyann = (start[0] + dx, start[1] + dy)
            box = label.get_window_extent(renderer)  # the text and its leader line
            overlap = sum(_overlap(box, other) for other in placed)
            if best is None or overlap < best[0]:
                best = (overlap, label.xyann)
            if overlap == 0:
                break
        assert best is not None
        label.xyann = best[1]
        placed.append(label.get_window_extent(renderer))
    return movable


def _overlap(a: Bbox, b: Bbox) -> float:
    """The area two display boxes share (0 when apart)."""
    width = min(a.x1, b.x1) - max(a.x0, b.x0)
    height = min(a.y1, b.y1) - max(a.y0, b.y0)
    return float(max(width, 0.0) * max(height, 0.0))


def scheme_bytes(chain: Chain, analysis: StructuralAnalysis, fmt: str = "svg", *, lang: str = "en",
                 which: str = "both", dpi: int = 110) -> bytes:
    """The scheme picture as the bytes of a file in ``fmt`` (see :func:`scheme_figure`).

    ``fmt`` is a format of :data:`assur.plot.formats.PICTURE_FORMATS` (``"svg"``,
    ``"png"``, ``"pdf"``, ``"jpeg"``). SVG keeps its texts as text (searchable, selectable)
    and is reproducible: the same chain gives the same bytes.

    Raises
    ------
    PictureFormatError
        For another format.
    """
    if fmt not in PICTURE_FORMATS.values():
        picture_format(f"scheme.{fmt}")  # raises, naming the formats supported
    fig = scheme_figure(chain, analysis, lang=lang, which=which)
    return figure_bytes(fig, fmt, dpi=dpi, tight=False)


def save_schemes(chain: Chain, analysis: StructuralAnalysis, path: str | os.PathLike[str], *,
                 lang: str = "en", which: str = "both") -> Path:
    """Write the schemes to a picture file in the format of its ending, atomically.

    Parameters
    ----------
    chain : Chain
        The chain drawn.
    analysis : StructuralAnalysis
        Its structural analysis (groups and layering).
    path : str or os.PathLike
        Output file; its ending chooses the format (``.png``, ``.svg``, ``.pdf``, ``.jpg``).
    lang : str
        Language of the labels.
    which : {'both', 'structural', 'formalised'}
        Which schemes to draw.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    PictureFormatError
        If the ending is not one of :data:`assur.plot.formats.PICTURE_FORMATS` (nothing is
        drawn).

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = assur.save_schemes(analysis.chain, analysis, pathlib.Path(folder) / "schemes.pdf")
    ...     path.read_bytes()[:5]
    b'%PDF-'
    """
    path = Path(path)
    fmt = picture_format(path)
    atomic_write_bytes(path, scheme_bytes(chain, analysis, fmt, lang=lang, which=which))
    return path
