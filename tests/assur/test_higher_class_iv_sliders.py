"""The class IV group with prismatic external pairs on seeded random designs.

Three forms: c slides on a guide of the frame (``RP``: a hinged to a crank), a slides on a
guide carried by the crank (``PR``: c hinged to the frame), both slide (``PP``: a on a guide
carried by a link in circular translation, c on a frame guide). Each check compares with a
computation made another way: the mode count with the general fallback's sweep of the full
pose system (``tests/assur/higher_fallback.py``), rigidity and the guides with distances
and cross products of the joints, the analogs with central differences, the followed mode and
its interval with a walk through all modes on a fine grid, the reactions with the global
solve of all links.

``ASSUR_HIGHER_FULL=1`` runs the full profile (1,000 designs per form for the counts).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from higher_checks import check_analogs_against_central_differences, check_class_iv_rigid
from higher_fallback import Joint, Motion, PoseSystem, sweep_modes
from test_higher_properties import walk_through

import assur
from assur.kinematics import jets as J
from assur.kinematics.analysis import analyse
from assur.kinematics.higher import ClassIVCoupled, ClassIVInputs, assembly_modes, follow_mode
from assur.kinematics.higher.groups import expand
from assur.kinematics.higher.kind import HigherGroupSolution

FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
COUNTED, RIGID, WALKED = (1000, 40, 12) if FULL else (40, 6, 3)
FORMS = ["RP", "PR", "PP"]
TWO_PI = 2 * np.pi


def _polar(rng: np.random.Generator, d: int, low: float, high: float) -> np.ndarray:
    return np.asarray(rng.uniform(low, high, d) * np.exp(2j * np.pi * rng.uniform(size=d)))


@dataclass
class Designs:
    """Random drawn class IV groups of one form and how their known links move.

    a's external pair H_a: a hinge on a crank pin (RP); a guide carried by the crank (PR); a
    guide carried by a link in circular translation (PP). c's: a guide on the frame (RP, PP)
    or a hinge on the frame (PR).
    """

    form: str
    group: ClassIVCoupled
    pin: np.ndarray  # H_a⁰, on the crank (pivot at the origin) or on the translating link
    radius: np.ndarray  # the translating link's circle (PP)

    def carrier(self, phi: Any) -> tuple[Any, Any]:
        """Shift and turn of the link that carries H_a: z⁰ ↦ shift + turn·z⁰."""
        if self.form == "PP":
            return self.radius * (J.expi(phi) - 1.0), 1.0 + 0.0 * self.radius
        return 0.0 * self.pin, J.expi(phi)

    def inputs(self, phi: Any) -> ClassIVInputs:
        shift, turn = self.carrier(phi)
        g = self.group
        h_a = shift + turn * self.pin
        u_a = None if g.u_a is None else g.u_a * turn
        return ClassIVInputs(h_a, g.h_c, u_a, g.u_c)

    def grid(self, phi: np.ndarray) -> ClassIVInputs:
        """The inputs on the (design, angle) grid."""
        wide = Designs(self.form, expand(self.group), self.pin[:, None], self.radius[:, None])
        return wide.inputs(np.asarray(phi)[None, :])

    def pose_system(self) -> PoseSystem:
        """The full pose system: a = 0, b = 1, c = 2, d = 3; H_a on "k", H_c on "frame"."""
        g = self.group
        ends = [Joint("P", link, body, h, u) if u is not None else Joint("R", link, body, h)
                for link, body, h, u in ((0, "k", g.h_a, g.u_a), (2, "frame", g.h_c, g.u_c))]
        return PoseSystem((ends[0], Joint("R", 0, 1, g.c), Joint("R", 1, 2, g.d),
                           Joint("R", 2, 3, g.e), Joint("R", 3, 0, g.f), ends[1]))

    def known(self, phi: float) -> dict[str, Motion]:
        shift, turn = self.carrier(phi)
        return {"k": Motion(np.asarray(shift), np.asarray(turn)), "frame": Motion(0.0, 1.0)}


def random_designs(form: str, seed: int, d: int) -> Designs:
    """Drawn assembled: C, F 40–70 from H_a; D, E 30–60 from H_c (90–110 from the origin)."""
    rng = np.random.default_rng(seed)
    h_a = _polar(rng, d, 8, 15)
    c, f = h_a + _polar(rng, d, 40, 70), h_a + _polar(rng, d, 40, 70)
    h_c = _polar(rng, d, 90, 110)
    dd, e = h_c + _polar(rng, d, 30, 60), h_c + _polar(rng, d, 30, 60)
    u_a, u_c = (np.exp(2j * np.pi * rng.uniform(size=d)) for _ in range(2))
    group = ClassIVCoupled(h_a, c, f, h_c, dd, e, u_a if form[0] == "P" else None,
                    u_c if form[1] == "P" else None)
    return Designs(form, group, h_a, rng.uniform(8, 15, d))


def _col(v: Any) -> np.ndarray:
    return np.asarray(v)[:, None]


# --- mode counts against the fallback ---------------------------------------------------------


@pytest.mark.parametrize("form", FORMS)
def test_mode_count_agrees_with_the_fallback_sweep(form: str) -> None:
    """At a crank angle of 37°, the closed form's real modes and the sweep's agree in number
    and in their joints on designs away from a birth or merge of modes."""
    designs = random_designs(form, 70 + FORMS.index(form), COUNTED)
    phi = np.radians(37.0)
    modes = assembly_modes(designs.group, designs.inputs(np.full(COUNTED, phi)))
    found = sweep_modes(designs.pose_system(), designs.known(phi), samples=1440)
    size = np.abs(np.log(np.abs(modes.roots)))
    near = ((size > 1e-6) & (size < 1e-3)).any(axis=1)
    thin = (np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=1)
    keep = ~near & ~thin
    assert keep.mean() >= 0.97
    assert (modes.count[keep] == found.count[keep]).all()
    bound = 2 if form == "PP" else 6
    assert set(modes.count.tolist()) <= set(range(0, bound + 1, 2))
    assert modes.count.max() >= (2 if form == "PP" else 4)
    # every closed-form mode's joints C, D, E, F are those of one of the sweep's modes
    mine = np.stack([modes.joints[name] for name in ("C", "D", "E", "F")], axis=-1)
    theirs = found.points[..., [1, 2, 3, 4]]
    apart = np.abs(mine[:, :, None, :] - theirs[:, None, :, :]).max(axis=-1)
    nearest = np.nan_to_num(apart, nan=np.inf).min(axis=-1)
    real = ~np.isnan(mine[..., 0]) & keep[:, None]
    assert (nearest[real] <= 1e-7 * _col(designs.group.size).repeat(mine.shape[1], 1)[real]).all()


# --- rigidity and the guides over full cycles -------------------------------------------------


@pytest.mark.parametrize("form", FORMS)
def test_links_stay_rigid_and_on_their_guides_over_the_cycle(form: str) -> None:
    designs = random_designs(form, 80 + FORMS.index(form), RIGID)
    g = designs.group
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    solution = follow_mode(g, designs.inputs, phi)
    ok = check_class_iv_rigid(solution, g)
    j = solution.joints
    size = np.broadcast_to(_col(g.size), ok.shape)[ok]
    k = designs.grid(phi)
    for side, name, drawn, h0 in (("a", "C", g.c, g.h_a), ("c", "D", g.d, g.h_c)):
        here = j["Ha" if side == "a" else "Hc"]
        guide = k.u_a if side == "a" else k.u_c
        known = k.h_a if side == "a" else k.h_c
        if guide is None:  # a hinge: the link's point there is the known hinge
            assert (np.abs(here - known)[ok] <= 1e-9 * size).all()
            continue
        # on the guide line, and turned as the guide's link: (X − H)/(X⁰ − H⁰) = u/u⁰
        line = np.abs((np.conj(guide) * (here - known)).imag)
        turn = np.abs((j[name] - here) / _col(np.asarray(drawn) - h0)
                      - guide / _col(g.u_a if side == "a" else g.u_c))
        assert (line[ok] <= 1e-9 * size).all() and (turn[ok] <= 1e-9).all()


# --- analogs against central differences ------------------------------------------------------


@pytest.mark.parametrize("form", FORMS)
def test_analogs_against_central_differences(form: str) -> None:
    """Every joint's and link rotation's analogs against central differences (1e-5 rad) of the
    positions and of the velocity analogs, at four crank angles."""
    designs = random_designs(form, 90 + FORMS.index(form), 8)
    check_analogs_against_central_differences(designs.group, designs.inputs, 8)


# --- the followed mode and its interval against a walk through all modes ----------------------


@pytest.mark.parametrize("form", ["RP", "PP"])
def test_no_mode_switch_and_the_interval_against_a_walk_through_all_modes(form: str) -> None:
    """On a 0.2° grid, every mode at every angle; the walk from the drawn pose steps to the
    nearest mode and ends where none is within 0.1. The continuation's positions (2° apart)
    equal the walk's, and its ends lie within one walk step of the walk's."""
    designs = random_designs(form, 100 + FORMS.index(form), WALKED)
    g = designs.group
    fine = 1800
    grid = np.linspace(0, TWO_PI, fine, endpoint=False)
    walk, forward, backward = walk_through(g, assembly_modes(expand(g), designs.grid(grid)).x)
    ends = np.stack([forward, backward], axis=-1)
    coarse = np.arange(0, fine, 10)
    phi = grid[coarse]
    solution = follow_mode(g, designs.inputs, phi)
    tolerance = 2 * TWO_PI / fine
    ahead = np.where(np.isnan(solution.ends[:, 0]), TWO_PI, solution.ends[:, 0])
    assert (np.abs(ahead - ends[:, 0]) <= tolerance).all()
    back = ~np.isnan(solution.ends[:, 1])
    assert (np.abs(solution.ends[back, 1] - ends[back, 1]) <= tolerance).all()
    walked = walk[:, coarse]
    away = (np.abs(phi - ends[:, :1]) > tolerance) & (np.abs(phi - ends[:, 1:]) > tolerance)
    assert (solution.exists == ~np.isnan(walked[..., 0]))[away].all()
    both = solution.exists & ~np.isnan(walked[..., 0])
    scale = np.where(g.lengths, 1.0 / _col(g.size), 1.0)[:, None, :]
    gap = np.abs(solution.x - walked) * scale
    assert both.any() and np.nanmax(np.where(both[..., None], gap, np.nan)) <= 1e-7


# --- the example table, the sketch rule, the force analysis -----------------------------------


TABLES = Path(assur.__file__).parents[1] / "input_tables"


def test_the_example_table_through_the_analysis() -> None:
    """``class_iv_slider.yaml``: its modes at the sketch are those of the fallback on the pose
    system written from the table's drawn points, and over the cycle link 4 slides on G with
    the frame's orientation while every link keeps its drawn distances."""
    model = assur.load_model(TABLES / "class_iv_slider.yaml")
    phi = np.radians(np.arange(0.0, 360.0, 10.0))
    motion = analyse(model, phi)
    assert np.all(motion.exists)
    drawn = {"B": -12.5 - 20j, "C": 57 + 66j, "D": 115 + 67j, "E": 87 + 118j,
             "F": 25.5 + 98.5j, "G": 140.5 + 22j}
    u = np.exp(1j * np.radians(150.0))
    system = PoseSystem((Joint("R", 0, "crank", drawn["B"]), Joint("R", 0, 1, drawn["C"]),
                         Joint("R", 1, 2, drawn["D"]), Joint("R", 2, 3, drawn["E"]),
                         Joint("R", 3, 0, drawn["F"]), Joint("P", 2, "frame", drawn["G"], u)))
    found = sweep_modes(system, {"crank": Motion(0.0, 1.0), "frame": Motion(0.0, 1.0)})
    group = motion.solutions["IV(2,3,4,5)"]
    assert isinstance(group, HigherGroupSolution)
    listed = group.modes()
    assert int(found.count) == len(listed) == 2
    for mode in listed:
        here = np.array([mode.joints[p] for p in "CDEF"])
        assert np.min(np.abs(found.points[:, 1:5] - here).max(axis=-1)) <= 1e-9 * 200
    j = {name: np.asarray(z) for name, z in motion.joints.items()}
    for a, b in (("B", "C"), ("B", "F"), ("C", "F"), ("D", "E"), ("D", "G"), ("E", "G"),
                 ("C", "D"), ("F", "E")):
        assert np.abs(np.abs(j[a] - j[b]) - abs(drawn[a] - drawn[b])).max() <= 1e-9 * 200
    assert np.abs(((j["G"] - drawn["G"]) * np.conj(u)).imag).max() <= 1e-9 * 200
    assert np.abs((j["D"] - j["G"]) / (drawn["D"] - drawn["G"]) - 1.0).max() <= 1e-12


def test_the_guide_carried_by_the_sliding_link_moves_no_joint(tmp_path: Path) -> None:
    """The example with its guide G carried by the sliding link 4 (a slot of 4 on a block of
    the frame) instead of the frame: a prismatic pair's equation is the same whichever link
    carries the guide, so every joint stays where it was; the slider is on link 4, its base
    point fixed on 4 and its point on the frame, and its s has the opposite sign."""
    from test_higher_slotted_triad import check_sliders

    text = (TABLES / "class_iv_slider.yaml").read_text(encoding="utf-8")
    assert text.count("guide: 0}") == 1
    path = tmp_path / "slotted.yaml"
    path.write_text(text.replace("guide: 0}", "guide: 4}"), encoding="utf-8")
    phi = np.radians(np.arange(0.0, 360.0, 10.0))
    drawn = analyse(assur.load_model(TABLES / "class_iv_slider.yaml"), phi)
    slotted = analyse(assur.load_model(path), phi)
    assert np.all(slotted.exists)
    for pid in "BCDEF":
        assert np.abs(np.asarray(slotted.joints[pid]) - drawn.joints[pid]).max() <= 1e-9 * 200
    assert check_sliders(slotted, {"G": 4}, 200.0) == 1
    assert np.abs(np.asarray(slotted.sliders["G"].s) + drawn.sliders["G"].s).max() <= 1e-9 * 200


def test_reactions_equal_the_global_solve() -> None:
    """The example with its drawn joints moved by up to ±4 mm, random masses and loads: the
    group's linear solve agrees with the global solve of all links (1e-9 relative)."""
    from test_forces_higher import _agrees, _loads

    compared = 0
    for seed in range(2):
        rng = np.random.default_rng(seed)
        model = assur.load_model(TABLES / "class_iv_slider.yaml")
        varied = {name: value + rng.uniform(-4, 4) for name, value in model.params.items()
                  if name.startswith("IV(") and (".x_" in name or ".y_" in name)}
        model = model.with_params(varied)
        compared += _agrees(model, _loads(model, rng))
    assert compared > 24
