"""The mechanism you can play: a crank-angle slider and a play button in the coursework page.

:func:`play_data` samples an analysed cycle into plain numbers in mm and degrees: the
primitives of :func:`assur.plot.drawing.scheme` (links, hinges on their supports, slider
blocks, hatched guides, tracing points, joint names), the traced paths, and the group that
does not assemble where it fails, so the page draws the links as the static pictures do;
:func:`play_section` embeds them as JSON in the page with an inline SVG and a small
script that draws the mechanism at the slider's angle. Nothing is fetched from the network.

The script reads ``#phi=<degrees>`` (or ``#l=<mm>`` for an actuator) from the page address
on load, sets the slider there and redraws through the slider's own ``input`` event, so a
browser can be sent to any position by the address alone; ``#play&phi=90`` shows the
mechanism alone, for a screen in a classroom.
"""

from __future__ import annotations

import json
from typing import Any, TypeVar

import numpy as np

from assur.kinematics.analysis import Motion
from assur.plot.drawing import Plate, paths, scheme, working_space
from assur.plot.mechanism import failing_group, failure_text
from assur.text import render
from assur.typing import ComplexArray
from synthesis.app.coursework.page import Section, esc

__all__ = ["FRAMES", "play_data", "play_section"]

#: Positions embedded in the page (at most; fewer when the analysis has fewer).
FRAMES = 120

XY = list[float] | None
T = TypeVar("T")


def _xy(z: ComplexArray, digits: int = 3) -> list[XY]:
    """Points as ``[x, y]`` rounded to ``digits`` decimals of a mm, None where undefined."""
    return [[round(float(p.real), digits), round(float(p.imag), digits)] if np.isfinite(p)
            else None for p in z]


def _shapes(z: ComplexArray, least: int) -> list[list[list[float]] | None]:
    """Polygons, one a position (rows of ``z``): their finite vertices as ``[x, y]``
    (0.01 mm), None where fewer than ``least`` are finite."""
    return [[p for p in _xy(row, 2) if p is not None] if np.isfinite(row).sum() >= least else None
            for row in z]


def _outlines(plate: Plate) -> list[list[str] | None]:
    """A link's outline at each position as the names of its points in drawing order, None
    where fewer than two exist."""
    finite = np.isfinite(plate.outline)
    return [[plate.members[i] for i, ok in zip(order.tolist(), keep.tolist()) if ok]
            if keep.sum() >= 2 else None for order, keep in zip(plate.order, finite)]


def _segments(z: ComplexArray) -> list[list[list[float]] | None]:
    """Strokes, one row of ends (shape (k, 2)) a position: ``[x0, y0, x1, y1]`` each, rounded
    to 0.01 mm; None where one is undefined."""
    ends = np.round(np.stack([z.real, z.imag], axis=-1), 2).reshape(z.shape[0], -1, 4)
    whole = [bool(row.all()) for row in np.isfinite(z).reshape(z.shape[0], -1)]
    return [row.tolist() if ok else None for row, ok in zip(ends, whole)]


def _held(seq: list[T]) -> list[T]:
    """A sequence over the positions, kept whole, or as its one value where every position
    has the same (a frame pivot's support, a frame guide): the page reads a sequence of one
    value as holding at every position."""
    return seq[:1] if all(item == seq[0] for item in seq) else seq


def play_data(motion: Motion, frames: int = FRAMES) -> dict[str, Any]:
    """The positions the page draws, as plain data (mm, degrees).

    The geometry is that of :func:`assur.plot.drawing.scheme`, the one drawing of a
    mechanism's links that the static pictures draw too: the page only paints it.

    Parameters
    ----------
    motion : Motion
        One design over the cycle.
    frames : int
        At most this many positions are kept: every k-th of the analysis, the fewest k
        that fits (360 positions → every third, 3° apart).

    Returns
    -------
    dict
        ``q`` (the input: crank angle φ from the sketched position, degrees, or actuator
        length, mm), ``crank``, ``r`` (the radius of a hinge, mm), ``points`` (name →
        ``[x, y]`` or None per position: hinges and slider blocks by pair id, tracing
        points), ``hinges`` (``name`` and ``support``, the triangle under a frame pivot per
        position, or None), ``tracers`` (names), ``links`` (``id``, ``colour``, ``outline``
        per position as names of ``points`` in drawing order, ``label`` where its number is
        written), ``blocks`` (``name``, ``shape`` about its point along the x axis,
        ``angle`` of its guide in degrees per position), ``guides`` (``ground``, ``ends``
        ``[x0, y0, x1, y1]`` and ``hatch`` strokes per position), ``labels`` (name → the
        label written beside that point per position: coinciding joints share one),
        ``paths`` (``name``, ``tracing`` and its ``points``), ``fails`` (per position None
        or ``{"group", "hinges", "text_en", "text_ru"}``) and ``bounds``
        ``[x0, x1, y0, y1]``; a polygon or stroke is None where it is not drawn. A sequence
        of the primitives (not of ``points``) that has the same value at every position
        holds that one value.
    """
    size = motion.q.size
    picks = np.arange(0, size, -(-size // frames))  # every k-th, evenly spaced
    crank = motion.model.periodic
    drawn = scheme(motion, picks)
    traced, _ = paths(motion, picks)
    fails = []
    for index in picks:
        failure = failing_group(motion, int(index))
        fails.append(None if failure is None else {
            "group": failure.label, "hinges": _xy(np.array(failure.hinges, dtype=complex)),
            "text_en": failure_text(motion, failure, "en"),
            "text_ru": failure_text(motion, failure, "ru")})
    q = motion.q[picks]
    return {
        "q": [round(float(v), 3) for v in (np.degrees(q) if crank else q)], "crank": crank,
        "r": round(drawn.r, 4),
        "points": {**{h.name: _xy(h.at) for h in drawn.hinges},
                   **{b.name: _xy(b.at) for b in drawn.blocks},
                   **{t.name: _xy(t.at) for t in drawn.tracers}},
        "hinges": [{"name": h.name, "support": None if h.support is None
                    else _held(_shapes(h.support, 4))} for h in drawn.hinges],
        "tracers": [t.name for t in drawn.tracers],
        "links": [{"id": p.link, "colour": p.colour, "outline": _held(_outlines(p)),
                   "label": _held(_xy(p.label, 2))} for p in drawn.plates],
        "blocks": [{"name": b.name, "shape": _xy(b.shape[:4]),
                    "angle": _held([round(float(a), 2) if np.isfinite(a) else None
                                    for a in np.degrees(b.angle)])} for b in drawn.blocks],
        "guides": [{"ground": g.ground,
                    "ends": _held([None if e is None else e[0] + e[1]
                                   for e in _shapes(g.ends, 2)]),
                    "hatch": _held(_segments(g.hatch)) if g.ground else None}
                   for g in drawn.guides],
        "labels": {name: _held(list(text)) for name, text in drawn.labels.items()},
        "paths": [{"name": p.name, "tracing": p.tracing, "points": _xy(p.curve, 2)}
                  for p in traced],
        "fails": fails, "bounds": [round(v, 3) for v in working_space(motion)]}


_SCRIPT = """
(function () {
  var box = document.getElementById('play-box');
  var data = JSON.parse(document.getElementById('play-data').textContent);
  var lang = box.getAttribute('data-lang');
  var svg = box.querySelector('svg'), slider = box.querySelector('input[type=range]');
  var button = box.querySelector('button'), shown = box.querySelector('output');
  var note = box.querySelector('.play-note'), NS = 'http://www.w3.org/2000/svg';
  var b = data.bounds, r = data.r;
  svg.setAttribute('viewBox', [b[0], -b[3], b[1] - b[0], b[3] - b[2]].join(' '));
  function make(tag, attrs, parent) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) { e.setAttribute(k, attrs[k]); }
    (parent || svg).appendChild(e);
    return e;
  }
  // the SVG's y points down: every y of the data is negated
  function pts(ps) { return ps.map(function (p) { return p[0] + ',' + (-p[1]); }).join(' '); }
  function strokes(ss) {
    return ss.map(function (e) { return 'M' + e[0] + ',' + (-e[1]) + 'L' + e[2] + ',' + (-e[3]); })
      .join('');
  }
  function of(seq, k) { return seq.length === 1 ? seq[0] : seq[k]; }  // one value: held
  function show(e, on) { e.setAttribute('display', on ? 'inline' : 'none'); return on; }
  data.paths.forEach(function (path) {
    make('polyline', {points: pts(path.points.filter(function (p) { return p; })),
                      fill: 'none', stroke: path.tracing ? '#d62728' : '#999',
                      'stroke-width': path.tracing ? r / 3 : r / 5, 'class': 'path',
                      'stroke-dasharray': path.tracing ? 'none' : r / 2 + ' ' + r / 2});
  });
  var guides = data.guides.map(function (g) {
    return {line: make('line', {stroke: '#595959', 'stroke-width': g.ground ? r / 2 : r / 3}),
            hatch: make('path', {stroke: '#808080', 'stroke-width': r / 8, fill: 'none'})};
  });
  var links = data.links.map(function (link) {
    return {shape: make('polygon', {fill: link.colour, 'fill-opacity': 0.25, stroke: link.colour,
                                    'stroke-width': r * 0.7, 'stroke-linejoin': 'round',
                                    'stroke-linecap': 'round', id: 'link-' + link.id}),
            label: make('text', {fill: link.colour, 'font-size': 2.4 * r, 'font-weight': 'bold'})};
  });
  links.forEach(function (l, n) { l.label.textContent = data.links[n].id; });
  var blocks = data.blocks.map(function (block) {
    return make('polygon', {fill: 'white', stroke: 'black', 'stroke-width': r / 4,
                            points: pts(block.shape), 'class': 'block'});
  });
  var supports = data.hinges.map(function (h) {
    return h.support ? make('polygon', {fill: '#ccc', stroke: 'black', 'stroke-width': r / 6})
                     : null;
  });
  var joints = {};
  function joint(name, cls, attrs) {
    var g = make('g', {'class': cls});
    attrs.id = 'joint-' + name; attrs['data-name'] = name;
    joints[name] = {g: g, c: make('circle', attrs, g)};
  }
  data.hinges.forEach(function (h) {
    joint(h.name, 'joint', {r: r, fill: 'white', stroke: 'black', 'stroke-width': r / 4});
  });
  data.tracers.forEach(function (name) { joint(name, 'tracer', {r: r / 2, fill: '#d62728'}); });
  var labels = Object.keys(data.labels).map(function () {
    return make('text', {'font-size': 1.7 * r, fill: '#333'});
  });
  var failLine = make('polyline', {fill: 'none', stroke: '#d62728', 'stroke-width': r / 3,
                                   'stroke-dasharray': r + ' ' + r / 2, id: 'fail-line'});
  var failRings = make('g', {id: 'fail-rings'});
  function draw(k) {
    data.guides.forEach(function (g, n) {
      var e = of(g.ends, k), line = guides[n].line, hatch = guides[n].hatch;
      if (show(line, e)) {
        line.setAttribute('x1', e[0]); line.setAttribute('y1', -e[1]);
        line.setAttribute('x2', e[2]); line.setAttribute('y2', -e[3]);
      }
      var h = g.hatch && of(g.hatch, k);
      if (show(hatch, e && h)) { hatch.setAttribute('d', strokes(h)); }
    });
    data.links.forEach(function (link, n) {
      var o = of(link.outline, k), at = of(link.label, k);
      if (show(links[n].shape, o)) {
        links[n].shape.setAttribute('points', pts(o.map(function (name) {
          return data.points[name][k]; })));
      }
      if (show(links[n].label, at)) {
        links[n].label.setAttribute('x', at[0]); links[n].label.setAttribute('y', -at[1]);
      }
    });
    data.blocks.forEach(function (block, n) {
      var p = data.points[block.name][k], a = of(block.angle, k);
      if (show(blocks[n], p && a !== null)) {
        blocks[n].setAttribute('transform', 'translate(' + p[0] + ',' + (-p[1]) + ') rotate(' + (-a) + ')');
      }
    });
    data.hinges.forEach(function (h, n) {
      var o = h.support && of(h.support, k);
      if (supports[n] && show(supports[n], o)) { supports[n].setAttribute('points', pts(o)); }
    });
    Object.keys(joints).forEach(function (name) {
      var p = data.points[name][k], j = joints[name];
      if (show(j.g, p)) {
        j.g.setAttribute('transform', 'translate(' + p[0] + ',' + (-p[1]) + ')');
        j.c.setAttribute('data-x', p[0]);
        j.c.setAttribute('data-y', p[1]);
      } else {
        j.c.removeAttribute('data-x');
        j.c.removeAttribute('data-y');
      }
    });
    Object.keys(data.labels).forEach(function (name, n) {
      var at = data.points[name][k], text = of(data.labels[name], k);
      if (show(labels[n], at && text)) {
        labels[n].textContent = text;
        labels[n].setAttribute('x', at[0] + 1.2 * r);
        labels[n].setAttribute('y', -(at[1] - 2.2 * r));
      }
    });
    var fail = data.fails[k];
    while (failRings.firstChild) { failRings.removeChild(failRings.firstChild); }
    failLine.setAttribute('points', fail ? pts(fail.hinges) : '');
    if (fail) {
      fail.hinges.forEach(function (p) {
        make('circle', {cx: p[0], cy: -p[1], r: 2 * r, fill: 'none', stroke: '#d62728',
                        'stroke-width': r / 2.5, 'class': 'fail-ring'}, failRings);
      });
    }
    note.textContent = fail ? fail['text_' + lang] : '';
    svg.setAttribute('data-index', k);
    shown.textContent = (data.crank ? '\\u03c6 = ' : 'l = ') + data.q[k].toFixed(1) + (data.crank ? '\\u00b0' : ' mm');
  }
  slider.max = data.q.length - 1;
  slider.addEventListener('input', function () { draw(+slider.value); });
  var timer = null;
  button.addEventListener('click', function () {
    if (timer) { clearInterval(timer); timer = null; button.textContent = button.getAttribute('data-play'); return; }
    button.textContent = button.getAttribute('data-pause');
    timer = setInterval(function () {
      slider.value = (+slider.value + 1) % data.q.length;
      slider.dispatchEvent(new Event('input'));
    }, 60);
  });
  function nearest(target) {
    var best = 0;
    data.q.forEach(function (v, k) {
      var d = data.crank ? Math.abs(((v - target) % 360 + 540) % 360 - 180) : Math.abs(v - target);
      var e = data.crank ? Math.abs(((data.q[best] - target) % 360 + 540) % 360 - 180) : Math.abs(data.q[best] - target);
      if (d < e) { best = k; }
    });
    return best;
  }
  var asked = /[#&](?:phi|l)=(-?[0-9.]+)/.exec(location.hash);
  slider.value = asked ? nearest(parseFloat(asked[1])) : 0;
  slider.dispatchEvent(new Event('input'));
  if (/^#play/.test(location.hash)) { document.body.classList.add('play-only'); }
})();
"""


def play_section(motion: Motion, lang: str) -> Section:
    """The section with the playable mechanism.

    Parameters
    ----------
    motion : Motion
        One design over the cycle.
    lang : str
        Language of the captions.

    Returns
    -------
    Section
        Element ids: ``play-box`` (the box), ``play-data`` (the JSON), ``joint-<pair>`` (a hinge's
        circle, with ``data-x``, ``data-y`` in mm), ``fail-rings`` and ``fail-line`` (the
        group that fails), and the svg's ``data-index`` (the shown position).
    """
    data = json.dumps(play_data(motion), ensure_ascii=False, separators=(",", ":"))
    data = data.replace("</", "<\\/")  # nothing in the JSON may close the script element
    title = render("coursework.play_title", lang)
    body = (f'<div class="play" id="play-box" data-lang="{esc(lang)}">'
            '<div class="play-controls">'
            f'<button type="button" data-play="{esc(render("coursework.play", lang))}" '
            f'data-pause="{esc(render("coursework.pause", lang))}">'
            f'{esc(render("coursework.play", lang))}</button> '
            f'<input type="range" min="0" max="0" step="1" value="0" '
            f'aria-label="{esc(render("coursework.play_slider", lang))}"> <output></output>'
            "</div>"
            '<svg xmlns="http://www.w3.org/2000/svg" preserveAspectRatio="xMidYMid meet" '
            'role="img"></svg>'
            f'<p class="play-note bad"></p>'
            f'<p class="note">{esc(render("coursework.play_hint", lang))}</p></div>'
            f'<script type="application/json" id="play-data">{data}</script>'
            f"<script>{_SCRIPT}</script>")
    return Section("play", title, body)
