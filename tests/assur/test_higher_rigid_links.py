"""Every link of a mechanism with a triad or a class IV group moves as a rigid body.

Checked from the analysis's output alone, over the whole cycle of every shipped table with a
higher group: each link's frame (origin, angle) carries every point of the link at a fixed
place in it. A revolute pair's point belongs to both its links; a prismatic pair's slider
point to its slider, the guide's base point and direction to its carrier, and the slider
point lies on the guide line (base + offset·n + s·u). The cylinder and the rod of a linear
actuator slide on each other and are left out. A joint, a slide or a frame written for
the wrong leash or coupler breaks one of these.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from assur.kinematics.analysis import analyse
from assur.kinematics.build import load_model
from assur.model import LinkId

TABLES = Path(__file__).resolve().parents[2] / "input_tables"
#: The shipped tables with a triad or a class IV group, each its whole cycle.
HIGHER = sorted(p.name for p in TABLES.glob("*.yaml")
                if "triad" in p.name or "class_iv" in p.name)


def _constant(values: np.ndarray, scale: float) -> float:
    """The largest departure of ``values`` (over the positions where finite) from its first
    finite value, relative to ``scale``."""
    finite = values[np.isfinite(values)]
    return float(np.abs(finite - finite[0]).max() / scale) if finite.size else 0.0


@pytest.mark.parametrize("table", HIGHER)
def test_every_link_is_rigid(table: str) -> None:
    """Points of a link in its frame, and guides on their carriers, stay where they are."""
    model = load_model(TABLES / table)
    motion = analyse(model, points=90)
    ok = np.asarray(motion.exists)
    assert ok.any()
    actuators = {link for group in model.groups for link in group.composite}
    frames = {link: (np.asarray(o)[ok], np.asarray(a)[ok]) for link, (o, a) in
              motion.frames.items()
              if np.ndim(np.asarray(o)) and np.ndim(np.asarray(a)) and link not in actuators}
    joints = {pid: np.asarray(z)[ok] for pid, z in motion.joints.items()}
    scale = max(float(np.nanmax(np.abs(z))) for z in joints.values())

    def local(link: LinkId, point: np.ndarray) -> np.ndarray:
        origin, angle = frames[link]
        return np.asarray((point - origin) * np.exp(-1j * angle))

    checked = 0
    for pid, (kind, links, _) in model.pair_links.items():
        if kind == "R" and pid in joints:
            for link in links:
                if link in frames:
                    assert _constant(local(link, joints[pid]), scale) < 1e-9, (table, pid, link)
                    checked += 1
    for pid, slider in motion.sliders.items():
        point, base = np.asarray(slider.point)[ok], np.asarray(slider.base)[ok]
        angle = np.asarray(slider.angle)[ok] * np.ones(point.shape)
        s = np.asarray(slider.s)[ok]
        along = np.exp(1j * angle)
        on_line = base + np.asarray(slider.offset) * 1j * along + s * along
        assert np.abs(point - on_line).max() / scale < 1e-9, (table, pid)
        if slider.slider in frames:
            assert _constant(local(slider.slider, point), scale) < 1e-9, (table, pid)
        if slider.carrier in frames:
            assert _constant(local(slider.carrier, base), scale) < 1e-9, (table, pid)
            turn = np.angle(np.exp(1j * (angle - frames[slider.carrier][1])))
            assert _constant(turn, 1.0) < 1e-9, (table, pid)
        checked += 1
    assert checked >= len(model.pair_links) - 2


@pytest.mark.parametrize("table", [t for t in HIGHER if "actuator" not in t])
def test_points_drawn_on_every_link_start_where_drawn(table: str, tmp_path: Path) -> None:
    """A point traced on every moving link (beside the mean of its drawn pairs) is at its
    drawn place at the sketch (φ = 0) and keeps its distances to the link's hinges."""
    data = yaml.safe_load((TABLES / table).read_text(encoding="utf-8"))
    geometry = data["geometry"]
    drawn: dict[str, complex] = {}
    hinges: dict[str, list[str]] = {}
    links = {link for pair in data["mechanism"]["pairs"] for link in pair["links"]} - {0}
    for link in sorted(links):
        pairs = [p for p in data["mechanism"]["pairs"] if link in p["links"]]
        points = [complex(*geometry[p["id"]]["point"]) for p in pairs]
        drawn[f"K{link}"] = sum(points) / len(points) + 7 + 3j
        hinges[f"K{link}"] = [p["id"] for p in pairs if p["type"] == "R"]
        geometry.setdefault("tracing", {})[f"K{link}"] = {
            "link": link, "point": [drawn[f"K{link}"].real, drawn[f"K{link}"].imag]}
    path = tmp_path / table
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    motion = analyse(load_model(path), points=90)
    ok = np.asarray(motion.exists)
    assert motion.q[0] == 0.0 and ok[0]
    for name, where in drawn.items():
        traced = np.asarray(motion.tracing[name])
        assert abs(traced[0] - where) < 1e-9 * abs(where), (table, name)
        for pid in hinges[name]:
            gap = np.abs(traced[ok] - np.asarray(motion.joints[pid])[ok])
            assert np.abs(gap - gap[0]).max() < 1e-9 * abs(where), (table, name, pid)
