"""Class IV groups with prismatic internal pairs through the model builder and the analysis.

The examples ``class_iv_internal_slider.yaml`` (link 3 a block in the slot of link 2: an
R–P coupler), ``class_iv_internal_frame_guide.yaml`` (the same with link 4 sliding on a
frame guide) and ``class_iv_internal_two_blocks.yaml`` (two blocks in slots of link 2 and link
4 on a frame guide: both equations linear in its slide), the same tables with the guides carried by the other link of each sliding pair,
and random designs with the group's drawn points and guides moved. Each check compares with a
computation made another way: every point of every link keeps its coordinates in the link's
frame (rigid links, a hinge's one point on both links), a prismatic pair's two links turn
together and its point stays on the guide line with s the projection computed here, the
poses are modes of the full pose system of the group solved by the general fallback, the
analogs are central differences of the analysed positions, the reactions equal the global
solve of all links, the synthesis evaluator's batch equals each design alone and finds no
deviation at the design its target came from, and the forms that are not kinematically
determinate are refused with the reason.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from higher_checks import TABLES, refused
from higher_fallback import Joint, PoseSystem, sweep_modes
from higher_fallback import Motion as Known
from test_forces_higher import _agrees, _loads

from assur.io.chain_table import chain_from_dict
from assur.kinematics.analysis import Motion, analyse, values
from assur.kinematics.build import build_model, load_model
from assur.kinematics.existence import check_existence
from assur.kinematics.higher.kind import HigherGroupSolution
from assur.kinematics.model import KinematicModel
from synthesis.evaluate import Evaluator
from synthesis.problem import ControlPoints, Output, Parameter, Problem

LABEL = "IV(2,3,4,5)"
#: The examples and their prismatic pairs.
SLIDING = {"class_iv_internal_slider.yaml": ("C",),
           "class_iv_internal_frame_guide.yaml": ("C", "G"),
           "class_iv_internal_two_blocks.yaml": ("C", "F", "G")}
EXAMPLES = list(SLIDING)
PHI = np.radians(np.arange(0.0, 360.0, 10.0))
SCALE = 200.0
TOL = 1e-9 * SCALE


def _table(name: str, carried: dict[str, int] | None = None) -> dict[str, Any]:
    """A shipped example as a dict, the guide of each pair in ``carried`` moved to the link
    given."""
    table: dict[str, Any] = yaml.safe_load((TABLES / name).read_text(encoding="utf-8"))
    for pair in table["mechanism"]["pairs"]:
        if pair["id"] in (carried or {}):
            pair["guide"] = carried[pair["id"]]  # type: ignore[index]
    return table


def _model(table: dict[str, Any]) -> KinematicModel:
    from assur.structure.analysis import analyse_structure

    return build_model(analyse_structure(chain_from_dict(table)))


def _array(z: Any, shape: tuple[int, ...]) -> np.ndarray:
    return np.broadcast_to(np.asarray(values(z)), shape)


def _frame(motion: Motion, link: Any, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    if link == motion.model.frame:
        return np.zeros(shape, complex), np.zeros(shape)
    origin, angle = motion.frames[link]
    return _array(origin, shape), _array(angle, shape)


def check_pairs(motion: Motion, scale: float) -> int:
    """Every pair over the cycle; the number of sliders checked.

    Each point of a link (a hinge's point, a slider's point on its sliding link, its base on
    the carrier) keeps its coordinates in the link's frame, which makes the links rigid, the
    frames turn with them and a hinge one point of both its links. A prismatic pair's slider
    is on the carrier the table names, its two links turn together and its guide with the
    carrier, its point lies on the guide line through the base, and s is the projection of
    point − base on the guide. Checked against the first assembled position of each design.
    """
    ok = np.asarray(motion.exists)
    shape = ok.shape
    first = np.argmax(ok, axis=-1)[..., None]

    def start(z: np.ndarray) -> np.ndarray:
        return np.take_along_axis(z, first, axis=-1)
    on: dict[Any, list[np.ndarray]] = {}
    sliders = 0
    for pid, (kind, links, guide) in motion.model.pair_links.items():
        if kind == "R":
            for link in links:
                on.setdefault(link, []).append(_array(motion.joints[pid], shape))
            continue
        slider = motion.sliders[pid]
        assert slider.carrier == guide and {slider.carrier, slider.slider} == set(links)
        base, point = _array(slider.base, shape), _array(slider.point, shape)
        on.setdefault(slider.carrier, []).append(base)
        on.setdefault(slider.slider, []).append(point)
        angle = _array(slider.angle, shape)
        gap = (point - base) * np.exp(-1j * angle)
        assert np.abs(gap.imag)[ok].max() <= 1e-9 * scale, pid
        assert np.abs(gap.real - _array(slider.s, shape))[ok].max() <= 1e-9 * scale, pid
        carrier = _frame(motion, slider.carrier, shape)[1]
        for turn in (angle - carrier, _frame(motion, slider.slider, shape)[1] - carrier):
            apart = np.angle(np.exp(1j * (turn - start(turn))))
            assert np.abs(apart)[ok].max() <= 1e-12 * scale, pid
        sliders += 1
    for link, points in on.items():
        origin, angle = _frame(motion, link, shape)
        for z in points:
            local = (z - origin) * np.exp(-1j * angle)
            assert np.abs(local - start(local))[ok].max() <= 1e-9 * scale, link
    return sliders


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_examples_keep_every_pair_over_the_cycle(name: str) -> None:
    """The example assembles over the whole turn from its drawing, every pair holds, and
    moving each guide to the other link of its pair moves no hinge (only the sliders change
    sides)."""
    table = _table(name)
    motion = analyse(_model(table), PHI)
    assert np.asarray(motion.exists).all()
    assert check_pairs(motion, SCALE) == len(SLIDING[name])
    geometry = table["geometry"]
    for pid, (kind, _, _) in motion.model.pair_links.items():
        drawn = complex(*geometry[pid]["point"])
        at = ([motion.joints[pid]] if kind == "R"
              else [motion.sliders[pid].point, motion.sliders[pid].base])
        assert all(abs(complex(_array(z, PHI.shape)[0]) - drawn) <= TOL for z in at), pid
    swapped = {"C": 3, "F": 5, "G": 4}
    swapped = {pid: link for pid, link in swapped.items() if pid in SLIDING[name]}
    other = analyse(_model(_table(name, swapped)), PHI)
    assert check_pairs(other, SCALE) == len(swapped)
    for pid in sorted(set("BDEF") - set(swapped)):
        apart = _array(other.joints[pid], PHI.shape) - _array(motion.joints[pid], PHI.shape)
        assert np.abs(apart).max() <= TOL, pid
    for pid in swapped:
        mine, theirs = motion.sliders[pid], other.sliders[pid]
        assert np.abs(_array(theirs.s, PHI.shape) + _array(mine.s, PHI.shape)).max() <= TOL


@pytest.mark.parametrize("name", EXAMPLES)
def test_random_designs_keep_every_pair(name: str) -> None:
    """Eight designs in one analysis, the group's drawn points moved by up to ±4 mm and its
    guides turned by up to ±5°: every pair holds wherever a design assembles."""
    model = load_model(TABLES / name)
    rng = np.random.default_rng(15)
    moved = {key: value + rng.uniform(-5, 5, (8, 1)) if ".beta_" in key
             else value + rng.uniform(-4, 4, (8, 1))
             for key, value in model.params.items()
             if key.startswith(LABEL) and key.split(".")[1][:2] in ("x_", "y_", "be")}
    motion = analyse(model.with_params(moved), PHI)
    assert np.asarray(motion.exists).mean() > 0.5
    check_pairs(motion, SCALE)


def _pose_system(name: str) -> tuple[PoseSystem, list[str]]:
    """The group of an example as drawn, links a = 0, b = 1, c = 2, d = 3 (2, 3, 4, 5 of the
    table; 1 the crank, 0 the frame), each pair's guide on the link the table names; and
    the pair of each joint, in order."""
    table = _table(name)
    body: dict[int, int | str] = {1: "crank", 0: "frame", 2: 0, 3: 1, 4: 2, 5: 3}
    joints: list[Joint] = []
    order: list[str] = []
    for pair in table["mechanism"]["pairs"]:
        if pair["id"] == "O":
            continue
        point = complex(*table["geometry"][pair["id"]]["point"])
        first, second = (body[link] for link in pair["links"])
        if pair["type"] == "R":
            joints.append(Joint("R", first, second, point))
        else:
            if body[pair["guide"]] == first:
                first, second = second, first
            turn = math.radians(table["geometry"][pair["id"]]["direction"])
            joints.append(Joint("P", first, second, point, complex(math.cos(turn),
                                                                   math.sin(turn))))
        order.append(pair["id"])
    return PoseSystem(tuple(joints)), order


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_poses_are_modes_of_the_full_pose_system(name: str) -> None:
    """At every 15° the analysed joints are one of the modes the fallback finds by its sweep
    of the full pose system of the four links (1e-9 L), and at the sketch the report lists as
    many modes as the sweep finds, with the same joints."""
    system, order = _pose_system(name)
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    motion = analyse(load_model(TABLES / name), phi)
    found = sweep_modes(system, {"crank": Known(np.zeros(phi.size), np.exp(1j * phi)),
                                 "frame": Known(np.zeros(phi.size), np.ones(phi.size))})
    analysed = np.stack([_array(motion.joints[pid], phi.shape) if pid in motion.joints
                         else _array(motion.sliders[pid].point, phi.shape) for pid in order],
                        axis=-1)
    hinges = [k for k, pid in enumerate(order) if motion.model.pair_links[pid][0] == "R"]
    apart = np.abs(found.points[..., hinges] - analysed[:, None, hinges]).max(axis=-1)
    assert (np.nanmin(apart, axis=1) <= TOL).all()
    solution = motion.solutions[LABEL]
    assert isinstance(solution, HigherGroupSolution)
    listed = solution.modes()
    assert len(listed) == int(found.count[0]) >= 2
    for mode in listed:
        here = np.array([mode.joints[order[k]] for k in hinges if order[k] in mode.joints])
        columns = [k for k in hinges if order[k] in mode.joints]
        assert np.nanmin(np.abs(found.points[0][:, columns] - here).max(axis=-1)) <= TOL


@pytest.mark.parametrize("name", EXAMPLES)
def test_analogs_against_central_differences(name: str) -> None:
    """The exact analogs of every joint, slider and link angle against central differences
    of the analysed positions (step 1e-5 rad)."""
    centre, h = np.radians([20.0, 110.0, 250.0]), 1e-5
    jets = analyse(load_model(TABLES / name), np.concatenate([centre, centre + h, centre - h]),
                   analogs=True)

    def check(jet: Any, unit: float, angle: bool = False) -> None:
        _, plus, minus = np.reshape(np.asarray(values(jet)), (3, -1))
        step = plus - minus
        fd = (np.angle(np.exp(1j * step)) if angle else step) / (2 * h)
        assert np.abs(fd - np.reshape(np.asarray(jet.d1), (3, -1))[0]).max() <= 1e-6 * unit

    for jet in jets.joints.values():
        check(jet, SCALE)
    for slider in jets.sliders.values():
        check(slider.s, SCALE)
        check(slider.point, SCALE)
    for link in (2, 3, 4, 5):
        check(jets.link_angle(link), 1.0, angle=True)


@pytest.mark.parametrize("name", EXAMPLES)
def test_reactions_equal_the_global_solve(name: str) -> None:
    """The group's linear solve of the reactions (random masses and loads, the drawn points
    moved by up to ±4 mm) against the global solve of all links (1e-9 relative)."""
    compared = 0
    for seed in range(2):
        rng = np.random.default_rng(1500 + seed)
        model = load_model(TABLES / name)
        varied = {key: value + rng.uniform(-4, 4) for key, value in model.params.items()
                  if key.startswith(LABEL) and key.split(".")[1][:2] in ("x_", "y_")}
        compared += _agrees(model.with_params(varied), _loads(model, rng))
    assert compared > 24


@pytest.mark.parametrize("name", EXAMPLES)
def test_existence_over_the_turn_and_with_a_tolerance(name: str) -> None:
    """No failure at 360 positions of the turn (the drawing is away from a change point);
    with δ set to the median margin the failing positions are exactly those where the
    analysed margin is below δ, and an interval starts between a failing and an assembling
    grid position."""
    model = load_model(TABLES / name)
    (group,) = check_existence(model, points=360).groups
    assert not group.fails.any() and not group.intervals
    if name != EXAMPLES[0]:
        return
    report = check_existence(model, points=72)
    (group,) = report.groups
    delta = float(np.median(group.margin))
    strict = model.with_params({f"{LABEL}.delta": delta})
    motion = analyse(strict, report.q)
    solution = motion.solutions[LABEL]
    below = np.asarray(solution.margin) < delta
    (group,) = check_existence(strict, report.q, motion=motion).groups
    assert 0 < below.sum() < below.size and np.array_equal(group.fails, below)
    step = report.q[1] - report.q[0]
    for interval in group.intervals:
        k = int(np.searchsorted(report.q, interval.start))
        assert report.q[k] - step <= interval.start <= report.q[k] and below[k % below.size]


def test_the_synthesis_evaluator_on_the_example() -> None:
    """The rotation of link 4 of the slotted-block example with D moved: the evaluator finds
    no deviation at that design and some at the table's own; its batch equals each design
    evaluated alone."""
    model = load_model(TABLES / EXAMPLES[0])
    names = (f"{LABEL}.x_D", f"{LABEL}.y_D")
    true = (model.params[names[0]] + 3.0, model.params[names[1]] - 2.0)
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    truth = analyse(model.with_params(dict(zip(names, true, strict=True))), phi)
    angle = np.unwrap(np.asarray(truth.link_angle(4)))
    control = ControlPoints(phi, angle - angle[0], np.full(phi.size, np.nan + 0j),
                            np.ones(phi.size))
    problem = Problem(source="<test>", name="slotted block", task_class=1, n_points=phi.size,
                      direction=1, n_groups=len(model.groups), grid=36, accuracy=None,
                      objective="lexicographic", p2_weight=1.0, mechanism={}, model=model,
                      parameters=tuple(Parameter(name, model.params[name],
                                                 model.params[name] - 8.0,
                                                 model.params[name] + 8.0) for name in names),
                      control=control, output=Output(4))
    evaluator = Evaluator(problem)
    x = np.array([true, [model.params[n] for n in names], [true[0] - 1.0, true[1] + 1.5]])
    batch = evaluator(x)
    assert float(batch.q[0]) <= 1e-9 < float(batch.q[1])
    for k in range(len(x)):
        alone = evaluator(x[k:k + 1])
        assert math.isclose(float(batch.q[k]), float(alone.q[0]), rel_tol=1e-9, abs_tol=1e-12)


@pytest.mark.parametrize(("table", "changes", "code", "data"), [
    (EXAMPLES[0], {"{id: D, type: R, links: [3, 4]}": "{id: D, type: P, links: [3, 4], guide: 4}",
                   "D: {point: [115, 67]}": "D: {point: [115, 67], direction: 51.057}"},
     "higher.sketch.class_iv_parallel", {"group": LABEL, "link": "3", "pairs": "C, D"}),
    (EXAMPLES[1], {"{id: D, type: R, links: [3, 4]}": "{id: D, type: P, links: [3, 4], guide: 4}",
                   "D: {point: [115, 67]}": "D: {point: [115, 67], direction: 0}",
                   "{id: B, type: R, links: [1, 2]}": "{id: B, type: P, links: [1, 2], guide: 1}",
                   "B: {point: [-12.5, -20]}": "B: {point: [-12.5, -20], direction: 80}"},
     "higher.sketch.class_iv_turns",
     {"group": LABEL, "link": "3", "a": "2", "c": "4", "pairs": "C, D"}),
])
def test_non_determinate_forms_are_refused_with_the_reason(
        tmp_path: Path, table: str, changes: dict[str, str], code: str,
        data: dict[str, str]) -> None:
    """A coupler sliding on a and on c with parallel guides (a free slide), and one beside
    two sliding external pairs (3n − 2p = 0, but the rotations of a and c are fixed twice):
    one problem naming the group, the coupler and the pairs."""
    assert refused(table, changes, tmp_path) == [(code, data)]
