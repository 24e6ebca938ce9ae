"""Masses that follow the design and limits on prismatic pairs' couples (``docs/forces.md`` §9).

The masses of a batch are checked against masses built by hand, design by design: the
distance between the two named hinges taken from that design's own joints at the sketched
position (φ = 0), mass ρ·l, centre the midpoint as a sketch point, inertia m·l²/12; a slider
or block its mass at its hinge. The fixed-mass force analysis of each design alone must give
what the batch gives.
"""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from assur.forces.solver import ForceAnalysis, kinetostatics
from assur.kinematics.analysis import analyse, values
from assur.kinematics.model import KinematicModel
from assur.model import ForceData, LinkId, Load, Mass
from synthesis import load_problem, problem_from_dict, synthesize
from synthesis.cli import main
from synthesis.evaluate import Evaluator
from synthesis.force_conditions import force_penalties
from synthesis.problem import Problem

PROBLEMS = Path(__file__).resolve().parents[2] / "input_tables" / "problems"
ELEVEN = PROBLEMS / "class2_course_11_link.yaml"
FOUR_BAR = PROBLEMS / "class1_fourbar_inertia_limit.yaml"
OMEGA, RHO = 10.0, 0.005

#: link → the two hinges whose distance is its length (the ternary links 2 and 8 name them)
BARS = {1: ("0-1", "1-2"), 2: ("1-2", "2-6"), 3: ("2-3", "3-0"), 6: ("2-6", "6-8"),
        8: ("6-8", "8-10")}
#: slider or block → its one hinge, its mass, kg, and moment of inertia, kg·m²
BLOCKS = {4: ("4-5", 0.3, 0.0), 7: ("7-0", 0.4, 2e-4), 9: ("8-9", 0.5, 0.0),
          10: ("8-10", 0.6, 1e-3)}
#: a resistance on slider 11 at the origin of its frame (it has no hinge), N
RESISTANCE = -500j
COUPLES = {"10-11": 80.0, "6-7": 0.02}


def _eleven_link() -> Problem:
    data = yaml.safe_load(ELEVEN.read_text(encoding="utf-8"))
    data["mechanism"] = str(ELEVEN.parent / data["mechanism"])
    masses: dict[int, Any] = {
        link: {"per_mm": RHO, "centre": "middle", "inertia": "rod", "between": list(pairs)}
        for link, pairs in BARS.items()}
    masses.update({link: {"mass": mass, "inertia": inertia}
                   for link, (_, mass, inertia) in BLOCKS.items()})
    data["forces"] = {"omega": OMEGA, "gravity": [0, -9.81], "masses": masses,
                      "loads": [{"link": 11, "force": [0, -500], "point": [0, 0]}],
                      "limits": {"couples": COUPLES}}
    return problem_from_dict(data, str(ELEVEN))


def _by_hand(model: KinematicModel) -> ForceData:
    """Fixed masses of one design, as sketch points, from its joints at φ = 0."""
    sketch = analyse(model, np.zeros(1), analogs=True)
    joint = {pair: complex(np.asarray(values(z)).ravel()[0])
             for pair, z in sketch.joints.items()}
    masses: dict[LinkId, Mass] = {}
    for link, (a, b) in BARS.items():
        length = abs(joint[b] - joint[a])
        mass = RHO * length
        masses[link] = Mass(mass, (joint[a] + joint[b]) / 2, mass * (length * 1e-3) ** 2 / 12)
    for link, (hinge, mass, inertia) in BLOCKS.items():
        masses[link] = Mass(mass, joint[hinge], inertia)
    origin = complex(np.asarray(values(sketch.frames[11][0])).ravel()[0])
    return ForceData(masses, (Load(11, force=RESISTANCE, point=origin),), -9.81j)


def _feasible_batch(problem: Problem, n: int, seed: int) -> tuple[Evaluator, np.ndarray]:
    evaluator = Evaluator(problem)
    rng = np.random.default_rng(seed)
    x = problem.lower + rng.random((n, problem.lower.size)) * (problem.upper - problem.lower)
    feasible = evaluator(x).p1 == 0
    assert feasible.sum() >= 3
    return evaluator, x[feasible]


def _batch_forces(problem: Problem, evaluator: Evaluator, x: np.ndarray) -> ForceAnalysis:
    assert problem.forces is not None
    motion = analyse(evaluator.model(x), evaluator.grid, analogs=True)
    return kinetostatics(motion, problem.forces.data_of(motion), problem.forces.omega)


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def test_masses_per_mm_are_the_fixed_masses_of_each_design() -> None:
    problem = _eleven_link()
    evaluator, x = _feasible_batch(problem, 8, 3)
    batch = _batch_forces(problem, evaluator, x)
    for d in range(3):
        model = evaluator.model(x[d:d + 1])
        one = kinetostatics(analyse(model, evaluator.grid, analogs=True),
                            _by_hand(model), OMEGA)
        assert _relative(batch.driving[d], one.driving.ravel()) < 1e-12
        for pair in ("0-1", "2-6", "6-7", "10-11"):
            got, want = batch.reactions[pair], one.reactions[pair]
            assert _relative(got.x[d] + 1j * got.y[d], (want.x + 1j * want.y).ravel()) < 1e-12
        got_m, want_m = batch.reactions["10-11"].moment, one.reactions["10-11"].moment
        assert got_m is not None and want_m is not None
        assert _relative(got_m[d], want_m.ravel()) < 1e-12


def test_a_couple_limit_is_the_excess_of_the_largest_couple() -> None:
    problem = _eleven_link()
    evaluator, x = _feasible_batch(problem, 8, 4)
    assert problem.forces is not None
    got = force_penalties(problem.forces, evaluator.model, x, np.ones(len(x), bool),
                          evaluator.grid)
    want = np.zeros(len(x))
    for d in range(len(x)):
        model = evaluator.model(x[d:d + 1])
        one = kinetostatics(analyse(model, evaluator.grid, analogs=True),
                            _by_hand(model), OMEGA)
        for pair, limit in COUPLES.items():
            couple = one.reactions[pair].moment
            assert couple is not None and np.isfinite(couple).all()
            want[d] += max(0.0, float(np.max(np.abs(couple))) - limit) / limit
    np.testing.assert_allclose(got, want, rtol=1e-10)
    assert (got > 0).any() and (got == 0).any()      # binding for some designs only


def _respecting(problem: Problem, x: np.ndarray) -> float:
    """The largest |driving torque| of one four-bar design, masses built by hand."""
    evaluator = Evaluator(problem)
    model = evaluator.model(np.atleast_2d(x))
    joint = {pair: complex(np.asarray(values(z)).ravel()[0]) for pair, z in
             analyse(model, np.zeros(1)).joints.items()}
    masses: dict[LinkId, Mass] = {}
    for link, (a, b) in {1: ("0-1", "1-2"), 2: ("1-2", "2-3"), 3: ("2-3", "3-0")}.items():
        length = abs(joint[b] - joint[a])
        mass = 0.02 * length
        masses[link] = Mass(mass, (joint[a] + joint[b]) / 2, mass * (length * 1e-3) ** 2 / 12)
    forces = kinetostatics(analyse(model, evaluator.grid, analogs=True),
                           ForceData(masses, (Load(3, torque=-15.0),)), 30.0)
    return float(np.max(np.abs(forces.driving)))


def test_masses_following_the_design_move_the_optimum_and_it_respects_the_limit() -> None:
    problem = load_problem(FOUR_BAR)
    assert problem.forces is not None and problem.forces.driving_torque == 10.0
    # the same masses frozen at the initial design's: as the table was before rules
    initial = analyse(problem.model, np.zeros(1), analogs=True)
    frozen = {rule.link: rule.of(initial) for rule in problem.forces.follow}
    fixed_masses: dict[LinkId, Mass] = {
        link: Mass(np.asarray(m.mass).item(), complex(np.asarray(m.centre).item()),
                   np.asarray(m.inertia).item()) for link, m in frozen.items()}
    fixed = dataclasses.replace(problem, forces=dataclasses.replace(
        problem.forces, follow=(),
        data=dataclasses.replace(problem.forces.data, masses=fixed_masses)))
    # 2^9 LPτ trials and their shrinking boxes, no early stop: each run ends at its best
    settings = dataclasses.replace(problem.settings, refine=False, q_required=1e-4,
                                   budget_log2=9)
    follow_run = synthesize(problem, settings, progress=False)
    fixed_run = synthesize(fixed, settings, progress=False)
    x_follow = np.asarray(follow_run.search.x).ravel()
    x_fixed = np.asarray(fixed_run.search.x).ravel()
    assert follow_run.feasible and follow_run.search.criteria.p2[0] == 0
    assert np.max(np.abs(x_follow - x_fixed)) > 5.0           # mm: another mechanism
    assert follow_run.q < 0.85 * fixed_run.q
    # re-analysed with masses built from its own hinges, the optimum holds [M_d] = 10 N·m
    assert _respecting(problem, x_follow) <= 10.0 * (1 + 1e-9)
    assert _respecting(problem, x_follow) > 9.95               # and the limit binds
    # the mechanism that reproduces ψ(φ) exactly (the optimum without the limit) needs more
    assert _respecting(problem, np.array([40.0, 120.0, 100.0])) > 13.0


def test_every_problem_of_design_masses_and_couples_is_reported_at_once(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data = yaml.safe_load(ELEVEN.read_text(encoding="utf-8"))
    data["mechanism"] = str(ELEVEN.parent / data["mechanism"])
    bad = copy.deepcopy(data)
    bad["forces"] = {
        "omega": 10,
        "masses": {
            1: {"per_m": 0.005, "centre": "middle"},                  # misspelt key
            2: {"per_mm": 0.005, "centre": "middle", "inertia": "rod"},  # ternary: which two?
            3: {"mass": 1.0},                                          # two hinges, no centre
            4: {"mass": 1.0, "per_mm": 0.01, "centre": [0, 0]},        # both
            6: {"per_mm": 0.005, "centre": "midle", "inertia": "rods"},
            8: {"per_mm": 0.005, "centre": "middle", "between": ["6-8", "1-2"]},
            9: {"per_mm": 0.005, "centre": "middle"},                  # a slider: one hinge
            11: {"mass": 0.5},                                         # no hinge at all
        },
        "limits": {"couples": {"2-3": 5, "6-7": 0, "99": 1}},
    }
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(bad, allow_unicode=True), encoding="utf-8")
    assert main(["synthesize", str(path)]) == 2
    err = capsys.readouterr().err
    for part in (
            "forces.masses.1: unknown key 'per_m'",
            ("forces.masses.2: 'per_mm' needs the distance between two hinges, and link 2 has "
            "more than two (1-2, 2-3, 2-6): name the two with 'between: [A, B]'"),
            "forces.masses.3: link 3 has a mass: give 'centre'",
            "forces.masses.4: give exactly one of 'mass' (kg) and 'per_mm'",
            "forces.masses.6 'centre': expected the centre of mass",
            "forces.masses.6 'inertia': expected a moment of inertia",
            ("forces.masses.8 'between': expected two different hinges (revolute pairs) of "
            "link 8: 8-9, 6-8, 8-10; found [6-8, 1-2]"),
            ("forces.masses.9: 'per_mm' needs the distance between two hinges (revolute pairs), "
            "and link 9 has fewer than two (8-9)"),
            "forces.masses.11: link 11 has a mass: give 'centre'",
            "forces.limits.couples '2-3': expected a prismatic pair (",
            "forces.limits.couples '99': expected a prismatic pair (",
            "forces.limits.couples '6-7': expected a limit in N·m greater than 0; found 0"):
        assert part in err, part
    assert "Traceback" not in err and "give a limit" not in err
    assert main(["synthesize", str(path), "--lang", "ru"]) == 2
    ru = capsys.readouterr().err
    assert "у звена 2 их больше двух (1-2, 2-3, 2-6)" in ru
    assert "ожидалась поступательная пара" in ru

