"""One drawing of a mechanism's links: the static picture, the picture of a synthesised design
and the playable report draw the same links, blocks, hinges and guides at a position.

The expectation is built here from the motion alone — a link is drawn through its hinges, the
blocks of the sliders it carries and its tracing points; a block sits on its slider's point
along the guide's direction; a guide passes through its slider's point — and each front end's
output (matplotlib artists, the report's JSON) is read back into the same terms.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Polygon

from assur.kinematics.analysis import Motion, analyse, values
from assur.kinematics.build import load_model
from assur.model import LinkId
from assur.plot.mechanism import draw_mechanism
from assur.typing import Value
from synthesis import load_problem
from synthesis.app.coursework.play import play_data
from synthesis.evaluate import Evaluator
from synthesis.plots import plot_mechanism

ROOT = Path(__file__).resolve().parent.parent
TABLES = ROOT / "input_tables"

TOL = 2e-3  # mm: the report rounds points to 0.001 mm
GUIDE_TOL = 1e-2  # mm: and the ends of guides to 0.01 mm
Links = list[list[complex]]
Blocks = list[tuple[complex, float]]
Guides = list[tuple[complex, complex]]


def _covers(a: list[complex], b: list[complex]) -> bool:
    """Every point of ``a`` is within TOL of a point of ``b``, and back."""
    return (all(min(abs(p - q) for q in b) < TOL for p in a)
            and all(min(abs(p - q) for q in a) < TOL for p in b))


def same_links(drawn: Links, expected: Links) -> bool:
    """The same links: each drawn one covers the points of one expected, one to one."""
    left = list(expected)
    for points in drawn:
        match = next((i for i, other in enumerate(left) if _covers(points, other)), None)
        if match is None:
            return False
        left.pop(match)
    return not left


def same_points(drawn: list[complex], expected: list[complex]) -> bool:
    return len(drawn) == len(expected) and _covers(drawn, expected)


def _at(x: Value, k: int, n: int) -> complex:
    z = np.asarray(values(x), dtype=np.complex128).reshape(-1)
    return complex(z[0] if z.size == 1 else z[k])


def expected_links(motion: Motion, k: int, extra: dict[LinkId, complex] | None = None
                   ) -> Links:
    """Every moving link with two or more points at position ``k``, as the set of its points."""
    model, n = motion.model, motion.q.size
    points: dict[LinkId, list[complex]] = {}
    for pid, (kind, links, _) in model.pair_links.items():
        if kind == "R" and pid in motion.joints:
            for link in links:
                points.setdefault(link, []).append(_at(motion.joints[pid], k, n))
    for slider in motion.sliders.values():
        points.setdefault(slider.slider, []).append(_at(slider.point, k, n))
    for traced in model.tracing:
        points.setdefault(traced.anchor.link, []).append(_at(motion.tracing[traced.name], k, n))
    for link, z in (extra or {}).items():
        points.setdefault(link, []).append(z)
    return [[z for z in zs if np.isfinite(z)] for link, zs in points.items()
            if link != model.frame and sum(np.isfinite(z) for z in zs) >= 2]


def expected_hinges(motion: Motion, k: int) -> list[complex]:
    n = motion.q.size
    return [_at(z, k, n) for pid, z in motion.joints.items()
            if motion.model.pair_links[pid][0] == "R" and np.isfinite(_at(z, k, n))]


def expected_blocks(motion: Motion, k: int) -> Blocks:
    """Slider point and the guide's direction (rad, modulo π), where both exist."""
    n = motion.q.size
    blocks = [(_at(s.point, k, n), float(_at(s.angle, k, n).real) % np.pi)
              for s in motion.sliders.values()]
    return [(z, a) for z, a in blocks if np.isfinite(z) and np.isfinite(a)]


def _is_outline(vertices: list[complex]) -> bool:
    """A simple polygon: its vertices go round their centre in one direction."""
    z = np.array(vertices)
    if z.size < 3:
        return True
    turns = np.diff(np.unwrap(np.angle(z - z.mean())))
    return bool(np.all(turns > 0) or np.all(turns < 0))


def matplotlib_drawing(ax: Axes) -> tuple[Links, list[complex], Blocks, Guides, bool]:
    """Links (bars of width 3, plate outlines of width 2.5), hinges (circles), blocks (white
    rectangles: centre → direction of the long side) and guide lines (width 2.2 or 1.4)."""
    links: Links = []
    guides: Guides = []
    simple = True
    for line in ax.lines:
        xy = np.asarray(line.get_xydata())
        z = xy[:, 0] + 1j * xy[:, 1]
        if line.get_linewidth() in (3.0, 2.5):
            vertices = list(z[:-1]) if line.get_linewidth() == 2.5 else list(z)
            links.append(vertices)
            simple &= _is_outline(vertices)
        elif line.get_linewidth() in (2.2, 1.4):
            guides.append((complex(z[0]), complex(z[-1])))
    hinges = [complex(*c.center) for c in ax.patches if isinstance(c, Circle)]
    blocks: Blocks = []
    for patch in ax.patches:
        if isinstance(patch, Polygon) and patch.get_facecolor()[:3] == (1.0, 1.0, 1.0):
            xy = patch.get_xy()
            z = xy[:4, 0] + 1j * xy[:4, 1]
            long = z[1] - z[0] if abs(z[1] - z[0]) > abs(z[2] - z[1]) else z[2] - z[1]
            blocks.append((complex(z.mean()), float(np.angle(long)) % np.pi))
    return links, hinges, blocks, guides, simple


def _defined(z: complex | None) -> complex:
    """A vertex of an outline: the point must exist."""
    assert z is not None
    return z


def report_drawing(data: dict[str, Any], k: int
                   ) -> tuple[Links, list[complex], Blocks, Guides, bool]:
    """The same read from the report's JSON at its k-th position."""
    def of(seq: list[Any]) -> Any:
        return seq[0] if len(seq) == 1 else seq[k]

    points = {name: (None if track[k] is None else complex(*track[k]))
              for name, track in data["points"].items()}
    links: Links = []
    simple = True
    for link in data["links"]:
        names = of(link["outline"])
        if names is not None:
            vertices = [_defined(points[name]) for name in names]
            links.append(vertices)
            simple &= _is_outline(vertices)
    hinges = [z for h in data["hinges"] if (z := points[h["name"]]) is not None]
    blocks: Blocks = []
    for block in data["blocks"]:
        shape = np.array([complex(*p) for p in block["shape"]])
        angle = of(block["angle"])
        p = points[block["name"]]
        if p is not None and angle is not None:
            corners = p + shape * np.exp(1j * np.radians(angle))
            long = corners[1] - corners[0]
            blocks.append((complex(corners.mean()), float(np.angle(long)) % np.pi))
    guides = [(complex(*e[:2]), complex(*e[2:])) for g in data["guides"]
              if (e := of(g["ends"])) is not None]
    return links, hinges, blocks, guides, simple


def _on_a_guide(z: complex, guides: Guides) -> bool:
    """On the line of a drawn guide and within its ends."""
    return any(abs(((z - a) / (b - a)).imag) * abs(b - a) < GUIDE_TOL
               and 0 <= ((z - a) / (b - a)).real <= 1 for a, b in guides)


def _same_blocks(drawn: Blocks, expected: Blocks) -> None:
    """Each expected block drawn once: at its point, its long side along its guide."""
    def parallel(a: float, b: float) -> bool:
        turn = (a - b) % np.pi
        return min(turn, np.pi - turn) < 1e-3

    left = list(drawn)
    for point, angle in expected:
        match = next(i for i, (z, a) in enumerate(left)
                     if abs(z - point) < TOL and parallel(a, angle))
        left.pop(match)
    assert not left


@pytest.fixture(scope="module")
def sliders_motion() -> Motion:
    """A six-bar with a triad, a plate of three hinges and two sliders on frame guides."""
    model = load_model(TABLES / "six_bar_triad_sliders.yaml")
    return analyse(model, np.radians(np.arange(0.0, 360.0, 3.0)))


@pytest.mark.parametrize("table", ["six_bar_triad_sliders", "course_11_link", "course_11_link_fails",
                                   "whitworth"])
def test_the_static_picture_and_the_report_draw_the_same_links(table: str) -> None:
    motion = analyse(load_model(TABLES / f"{table}.yaml"), np.radians(np.arange(0.0, 360.0, 3.0)))
    data = play_data(motion)  # 120 positions: the report keeps every one of them
    for k in (0, 15, 70):
        links = expected_links(motion, k)
        hinges = expected_hinges(motion, k)
        blocks = expected_blocks(motion, k)
        fig = Figure()
        ax = draw_mechanism(motion, k, fig.add_subplot())
        for drawn in (matplotlib_drawing(ax), report_drawing(data, k)):
            assert same_links(drawn[0], links)
            assert same_points(drawn[1], hinges)
            _same_blocks(drawn[2], blocks)
            assert all(_on_a_guide(point, drawn[3]) for point, _ in blocks)
            assert drawn[4]  # plates drawn as simple polygons


def test_the_course_failure_leaves_out_the_later_groups() -> None:
    motion = analyse(load_model(TABLES / "course_11_link_fails.yaml"),
                     np.radians(np.arange(0.0, 360.0, 3.0)))
    k = 15  # φ = 45°: the kulisa group L3(6,7) does not assemble, nor anything after it
    links = expected_links(motion, k)
    assert len(links) < len(expected_links(motion, 0))
    fig = Figure()
    assert same_links(matplotlib_drawing(draw_mechanism(motion, k, fig.add_subplot()))[0], links)
    assert same_links(report_drawing(play_data(motion), k)[0], links)


@pytest.mark.parametrize("name", ["class2_six_bar_triad", "class3_fourbar_path"])
def test_the_synthesis_picture_draws_the_same_links(name: str) -> None:
    problem = load_problem(TABLES / "problems" / f"{name}.yaml")
    analysis = Evaluator(problem).analyse(problem.initial[None, :])
    motion = analysis.motion
    extra = ({problem.output.link: complex(analysis.output_grid[0, 0])}
             if problem.task_class in (3, 4) else None)
    fig = Figure()
    drawn = matplotlib_drawing(plot_mechanism(problem, analysis, axes=fig.add_subplot()))
    assert same_links(drawn[0], expected_links(motion, 0, extra))
    assert same_points(drawn[1], expected_hinges(motion, 0))
    _same_blocks(drawn[2], expected_blocks(motion, 0))
    assert drawn[4]


def test_the_report_merges_the_labels_of_coinciding_joints(tmp_path: Path) -> None:
    data = yaml.safe_load((TABLES / "four_bar.yaml").read_text("utf-8"))
    data["geometry"]["tracing"] = {"K": {"link": 2, "point": [110, 80]},  # K placed on C
                                   "L": {"link": 2, "point": [110.4, 80.3]}}  # 0.5 mm off
    table = tmp_path / "traced.yaml"
    table.write_text(yaml.safe_dump(data), encoding="utf-8")
    motion = analyse(load_model(table), points=24)
    labels = play_data(motion)["labels"]
    # within a hinge's radius (0.012 of the 110 mm span) at every position: one label at C
    assert labels == {"A": ["A"], "B": ["B"], "C": ["C=K=L"], "D": ["D"], "K": [""], "L": [""]}
