"""The mechanism you can play: a crank-angle slider and a play button in the coursework page.

:func:`play_data` samples an analysed cycle (every joint, slider block, guide and tracing
point, and the group that does not assemble where it fails) into plain numbers in mm and
degrees; :func:`play_section` embeds them as JSON in the page with an inline SVG and a small
script that draws the mechanism at the slider's angle. Nothing is fetched from the network.

The script reads ``#phi=<degrees>`` (or ``#l=<mm>`` for an actuator) from the page address
on load, sets the slider there and redraws through the slider's own ``input`` event, so a
browser can be sent to any position by the address alone; ``#play&phi=90`` shows the
mechanism alone, for a screen in a classroom.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from assur.kinematics.analysis import Motion, values
from assur.model import LinkId
from assur.plot.mechanism import failing_group, failure_text, working_space
from assur.text import render
from synthesis.app.coursework.page import Section, esc

__all__ = ["FRAMES", "play_data", "play_section"]

#: Positions embedded in the page (at most; fewer when the analysis has fewer).
FRAMES = 120
_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#bcbd22", "#17becf",
            "#e377c2")


def _xy(z: np.ndarray) -> list[list[float] | None]:
    """Points as ``[x, y]`` rounded to 0.001 mm, None where undefined."""
    return [[round(float(p.real), 3), round(float(p.imag), 3)] if np.isfinite(p) else None
            for p in z]


def _picked(x: Any, picks: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    return np.broadcast_to(np.asarray(values(x)), shape)[picks]


def play_data(motion: Motion, frames: int = FRAMES) -> dict[str, Any]:
    """The positions the page draws, as plain data (mm, degrees).

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
        length, mm), ``crank``, ``points`` (name → ``[x, y]`` or None per position: hinges
        by pair id, slider blocks ``"<pair>"`` of a prismatic pair, tracing points),
        ``pivots`` (hinges on the frame), ``slides`` (the slider blocks' points), ``links`` (``id``, ``points``, ``colour``),
        ``blocks`` (slider ``point`` and ``angle`` in degrees), ``guides`` (ends
        ``[x0, y0, x1, y1]`` or None per position), ``paths`` (names of moving points),
        ``fails`` (per position None or ``{"group", "hinges", "text_en", "text_ru"}``) and
        ``bounds`` ``[x0, x1, y0, y1]``.
    """
    model = motion.model
    shape = motion.q.shape
    picks = np.arange(0, shape[0], -(-shape[0] // frames))  # every k-th, evenly spaced
    crank = model.drive == "crank"
    points: dict[str, list[list[float] | None]] = {}
    pivots: list[str] = []
    links_of: dict[LinkId, list[str]] = {}
    for pid, (kind, joined, _) in model.pair_links.items():
        if kind == "R" and pid in motion.joints:
            points[str(pid)] = _xy(_picked(motion.joints[pid], picks, shape))
            if model.frame in joined:
                pivots.append(str(pid))
            for link in joined:
                links_of.setdefault(link, []).append(str(pid))
    blocks, guides, slides = [], [], []
    for pid, slider in motion.sliders.items():
        slides.append(str(pid))
        points[str(pid)] = _xy(_picked(slider.point, picks, shape))
        links_of.setdefault(slider.slider, []).append(str(pid))
        angle = _picked(slider.angle, picks, shape)
        blocks.append({"point": str(pid), "angle": [round(float(a), 2) if np.isfinite(a)
                                                    else None for a in np.degrees(angle)]})
        guides.append(_guide(slider, picks, shape, slider.carrier == model.frame))
    for traced in model.tracing:
        points[traced.name] = _xy(_picked(motion.tracing[traced.name], picks, shape))
        links_of.setdefault(traced.anchor.link, []).append(traced.name)
    links = [{"id": str(link), "points": names, "colour": _COLOURS[n % len(_COLOURS)]}
             for n, (link, names) in enumerate(sorted(links_of.items(), key=lambda kv: str(kv[0])))
             if link != model.frame]
    paths = [name for name, track in points.items()
             if len({tuple(p) for p in track if p is not None}) > 1]
    fails = []
    for index in picks:
        failure = failing_group(motion, int(index))
        fails.append(None if failure is None else {
            "group": failure.label, "hinges": _xy(np.array(failure.hinges, dtype=complex)),
            "text_en": failure_text(motion, failure, "en"),
            "text_ru": failure_text(motion, failure, "ru")})
    q = motion.q[picks]
    return {"q": [round(float(v), 3) for v in (np.degrees(q) if crank else q)],
            "crank": crank, "points": points, "pivots": pivots, "slides": slides, "links": links,
            "blocks": blocks, "guides": guides, "paths": paths, "fails": fails,
            "bounds": [round(v, 3) for v in working_space(motion)]}


def _guide(slider: Any, picks: np.ndarray, shape: tuple[int, ...], on_frame: bool
           ) -> dict[str, Any]:
    """The guide line over its slider's stroke at every kept position."""
    s = np.asarray(values(slider.s)).ravel()
    finite = s[np.isfinite(s)]
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 0.0)
    if not on_frame:
        lo, hi = min(lo, 0.0), max(hi, 0.0)
    margin = 0.15 * max(hi - lo, 1.0)
    base = _picked(slider.base, picks, shape)
    u = np.exp(1j * _picked(slider.angle, picks, shape))
    offset = float(np.asarray(slider.offset).ravel()[0])
    start = base + 1j * offset * u + (lo - margin) * u
    end = base + 1j * offset * u + (hi + margin) * u
    ends = [None if a is None or b is None else a + b for a, b in zip(_xy(start), _xy(end))]
    return {"frame": on_frame, "ends": ends}


_SCRIPT = """
(function () {
  var box = document.getElementById('play-box');
  var data = JSON.parse(document.getElementById('play-data').textContent);
  var lang = box.getAttribute('data-lang');
  var svg = box.querySelector('svg'), slider = box.querySelector('input[type=range]');
  var button = box.querySelector('button'), shown = box.querySelector('output');
  var note = box.querySelector('.play-note'), NS = 'http://www.w3.org/2000/svg';
  var b = data.bounds, span = Math.max(b[1] - b[0], b[3] - b[2]), r = 0.012 * span;
  svg.setAttribute('viewBox', [b[0], -b[3], b[1] - b[0], b[3] - b[2]].join(' '));
  function make(tag, attrs, parent) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) { e.setAttribute(k, attrs[k]); }
    (parent || svg).appendChild(e);
    return e;
  }
  function at(name, k) { var p = data.points[name][k]; return p ? [p[0], -p[1]] : null; }
  data.paths.forEach(function (name) {
    var d = data.points[name].map(function (p) { return p ? p[0] + ',' + (-p[1]) : null; })
      .filter(function (p) { return p; }).join(' ');
    make('polyline', {points: d, fill: 'none', stroke: '#999', 'stroke-width': r / 5,
                      'stroke-dasharray': r / 2 + ' ' + r / 2, 'class': 'path'});
  });
  var guides = data.guides.map(function (g) {
    return make('line', {stroke: '#555', 'stroke-width': g.frame ? r / 2 : r / 3});
  });
  var links = data.links.map(function (link) {
    return make('polygon', {fill: link.colour, 'fill-opacity': 0.2, stroke: link.colour,
                            'stroke-width': r * 0.7, 'stroke-linejoin': 'round',
                            id: 'link-' + link.id});
  });
  var labels = data.links.map(function (link) {
    var t = make('text', {fill: link.colour, 'font-size': 2.4 * r, 'font-weight': 'bold'});
    t.textContent = link.id;
    return t;
  });
  var blocks = data.blocks.map(function () {
    return make('rect', {width: 4.4 * r, height: 2.2 * r, x: -2.2 * r, y: -1.1 * r,
                         fill: 'white', stroke: 'black', 'stroke-width': r / 4});
  });
  var joints = {};
  Object.keys(data.points).forEach(function (name) {
    var pivot = data.pivots.indexOf(name) >= 0, slide = data.slides.indexOf(name) >= 0;
    var g = make('g', {'class': slide ? 'slide' : 'joint'});
    if (pivot) {
      make('polygon', {points: [0, 0, -1.9 * r, 1.9 * r, 1.9 * r, 1.9 * r].join(' '),
                       fill: '#ccc', stroke: 'black', 'stroke-width': r / 6}, g);
    }
    var c = make('circle', {r: slide ? r / 3 : r, fill: slide ? 'black' : 'white',
                            stroke: 'black', 'stroke-width': r / 4, id: 'joint-' + name,
                            'data-name': name}, g);
    var t = make('text', {'font-size': 1.7 * r, fill: '#333', x: 1.2 * r, y: 2.6 * r}, g);
    joints[name] = {g: g, c: c, t: t};
  });
  var failLine = make('polyline', {fill: 'none', stroke: '#d62728', 'stroke-width': r / 3,
                                   'stroke-dasharray': r + ' ' + r / 2, id: 'fail-line'});
  var failRings = make('g', {id: 'fail-rings'});
  function draw(k) {
    var named = [];  // labels of coinciding joints merged: "B=C"
    Object.keys(joints).forEach(function (name) {
      var p = at(name, k), j = joints[name], near = null;
      if (p) {
        named.forEach(function (other) {
          if (!near && Math.hypot(other.p[0] - p[0], other.p[1] - p[1]) <= 1.5 * r) { near = other; }
        });
      }
      if (near) { near.names.push(name); j.t.textContent = ''; }
      else if (p) { named.push({p: p, names: [name], t: j.t}); }
      j.g.setAttribute('display', p ? 'inline' : 'none');
      if (p) {
        j.g.setAttribute('transform', 'translate(' + p[0] + ',' + p[1] + ')');
        j.c.setAttribute('data-x', data.points[name][k][0]);
        j.c.setAttribute('data-y', data.points[name][k][1]);
      } else {
        j.c.removeAttribute('data-x');
        j.c.removeAttribute('data-y');
      }
    });
    named.forEach(function (item) { item.t.textContent = item.names.join('='); });
    var placed = [];
    data.links.forEach(function (link, n) {
      var ps = link.points.map(function (name) { return at(name, k); })
        .filter(function (p) { return p; });
      if (ps.length > 2) {
        var cx = 0, cy = 0;
        ps.forEach(function (p) { cx += p[0] / ps.length; cy += p[1] / ps.length; });
        ps.sort(function (p, q) {
          return Math.atan2(p[1] - cy, p[0] - cx) - Math.atan2(q[1] - cy, q[0] - cx);
        });
      }
      links[n].setAttribute('points', ps.map(function (p) { return p.join(','); }).join(' '));
      links[n].setAttribute('display', ps.length > 1 ? 'inline' : 'none');
      labels[n].setAttribute('display', ps.length > 0 ? 'inline' : 'none');
      if (ps.length) {
        var mx = 0, my = 0;
        ps.forEach(function (p) { mx += p[0] / ps.length; my += p[1] / ps.length; });
        mx += 1.8 * r; my -= 1.8 * r;
        while (placed.some(function (q) { return Math.hypot(q[0] - mx, q[1] - my) < 2 * r; })) {
          my -= 2.2 * r;  // another link's number is there: move up
        }
        placed.push([mx, my]);
        labels[n].setAttribute('x', mx);
        labels[n].setAttribute('y', my);
      }
    });
    data.blocks.forEach(function (block, n) {
      var p = at(block.point, k), a = block.angle[k];
      blocks[n].setAttribute('display', p && a !== null ? 'inline' : 'none');
      if (p && a !== null) {
        blocks[n].setAttribute('transform', 'translate(' + p[0] + ',' + p[1] + ') rotate(' + (-a) + ')');
      }
    });
    data.guides.forEach(function (g, n) {
      var e = g.ends[k];
      guides[n].setAttribute('display', e ? 'inline' : 'none');
      if (e) {
        guides[n].setAttribute('x1', e[0]); guides[n].setAttribute('y1', -e[1]);
        guides[n].setAttribute('x2', e[2]); guides[n].setAttribute('y2', -e[3]);
      }
    });
    var fail = data.fails[k];
    while (failRings.firstChild) { failRings.removeChild(failRings.firstChild); }
    failLine.setAttribute('points', fail ? fail.hinges.map(function (p) {
      return p[0] + ',' + (-p[1]); }).join(' ') : '');
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
