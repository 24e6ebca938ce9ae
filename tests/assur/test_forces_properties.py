"""Properties of the force analysis: the toggle as data, scaling with ω², linearity in the
loads, rotation of the whole problem, the listing of a pair."""

from __future__ import annotations

import cmath
import copy
import math

import numpy as np
import pytest
import yaml
from force_tables import TABLES, load

import assur
import assur.kinematics.analysis
from assur.forces import ForceData, ForceReason, Load, Mass, Tabulated, kinetostatics
from assur.kinematics.analysis import analyse


def _four_bar(c: complex, b: complex = 20j) -> assur.KinematicModel:
    data = {"mechanism": {"pairs": [{"id": "A", "type": "R", "links": [0, 1]},
                                    {"id": "B", "type": "R", "links": [1, 2]},
                                    {"id": "C", "type": "R", "links": [2, 3]},
                                    {"id": "D", "type": "R", "links": [3, 0]}],
                          "inputs": [1]},
            "geometry": {"A": {"point": [0, 0]}, "B": {"point": [b.real, b.imag]},
                         "C": {"point": [c.real, c.imag]}, "D": {"point": [100, 0]}}}
    return assur.build_model(assur.analyse_structure(assur.chain_from_dict(data)))


def _change_point() -> assur.KinematicModel:
    """Crank 20, frame 100, coupler 70, rocker 50: 20 + 100 = 70 + 50, so coupler and rocker
    stretch into one line once a turn, at the crank angle 180° (90° from the sketch)."""
    b, d = 20j, 100 + 0j
    distance = abs(d - b)
    along = (70**2 - 50**2 + distance**2) / (2 * distance)
    c = b + (d - b) / distance * complex(along, math.sqrt(70**2 - along**2))
    return _four_bar(c)


LOADS = ForceData({2: Mass(0.5, 40 + 40j, 1e-3), 3: Mass(0.4, 90 + 20j, 5e-4)},
                  (Load(3, torque=-15.0),), -9.81j)


def test_the_toggle_is_null_with_its_reason_and_finite_elsewhere() -> None:
    model = _change_point()
    q = np.radians(np.arange(360.0))
    result = kinetostatics(analyse(model, q, analogs=True), LOADS, 0.0)
    toggle = np.zeros(360, bool)
    toggle[90] = True
    assert np.array_equal(result.reason != 0, toggle)
    assert result.reason[90] == ForceReason.TOGGLE and result.singular[90] == "L1(2,3)"
    assert np.isnan(result.driving[90]) and np.all(np.isfinite(result.driving[~toggle]))
    for reaction in result.reactions.values():
        assert np.isnan(reaction.x[90]) and np.all(np.isfinite(reaction.x[~toggle]))
    assert result.message(90).text("en") == ("group L1(2,3) is at a toggle here: its "
                                             "reactions are indeterminate")
    assert result.message(89) is None and result.ill_conditioned[90]


def test_reactions_grow_like_the_inverse_determinant_next_to_the_toggle() -> None:
    model = _change_point()
    q = math.pi / 2 + np.array([-1e-2, -1e-3, -1e-4, -1e-5, 1e-5, 1e-4, 1e-3, 1e-2])
    motion = analyse(model, q, analogs=True)
    result = kinetostatics(motion, LOADS, 0.0)
    b, c, d = (assur.kinematics.analysis.values(motion.joints[p]) for p in "BCD")
    determinant = np.abs(((b - c).conjugate() * (d - c)).imag) / (abs(b - c) * abs(d - c))
    bounded = np.hypot(result.reactions["C"].x, result.reactions["C"].y) * determinant
    assert np.all(np.isfinite(bounded)) and bounded.max() < 3 * bounded.min()
    assert np.hypot(result.reactions["C"].x, result.reactions["C"].y).max() > 1e5


def test_inertia_reactions_scale_with_the_square_of_the_speed() -> None:
    model, data = load("course_11_link_forces.yaml")
    inertia_only = ForceData(data.masses)
    motion = analyse(model, points=72, analogs=True)
    slow, fast = (kinetostatics(motion, inertia_only, w) for w in (10.0, 25.0))
    np.testing.assert_allclose(fast.driving, 6.25 * slow.driving, rtol=1e-12, atol=1e-12)
    for pid, reaction in slow.reactions.items():
        np.testing.assert_allclose(fast.reactions[pid].x, 6.25 * reaction.x, rtol=1e-11,
                                   atol=1e-9)


def test_reactions_are_linear_in_the_loads() -> None:
    model, data = load("course_11_link_forces.yaml")
    motion = analyse(model, points=36, analogs=True)
    whole = kinetostatics(motion, data, 10.0)
    inertia = kinetostatics(motion, ForceData(data.masses), 10.0)
    loads = kinetostatics(motion, ForceData(loads=data.loads), 10.0)
    weight = kinetostatics(motion, ForceData(data.masses, (), -9.81j), 0.0)
    total = inertia.driving + loads.driving + weight.driving
    np.testing.assert_allclose(whole.driving, total, rtol=1e-11, atol=1e-11)


@pytest.mark.parametrize("turn", [30.0, 200.0])
def test_turning_the_whole_problem_turns_the_reactions(turn: float) -> None:
    model, data = load("course_11_link_forces.yaml")
    rotor = cmath.exp(1j * math.radians(turn))
    turned = assur.build_model(assur.analyse_structure(assur.chain_from_dict(
        _turned_course(rotor))))
    turned_data = ForceData(
        {k: Mass(m.mass, m.centre * rotor, m.inertia) for k, m in data.masses.items()},
        (Load(11, force=_turned_table(data.loads[0].force, rotor),
              point=data.loads[0].point * rotor),), data.gravity * rotor)
    q = np.radians(np.arange(0.0, 360.0, 15.0))
    base = kinetostatics(analyse(model, q, analogs=True), data, 10.0)
    moved = kinetostatics(analyse(turned, q, analogs=True), turned_data, 10.0)
    np.testing.assert_allclose(moved.driving, base.driving, rtol=1e-9, atol=1e-9)
    for pid, reaction in base.reactions.items():
        force = (reaction.x + 1j * reaction.y) * rotor
        other = moved.reactions[pid]
        np.testing.assert_allclose(other.x + 1j * other.y, force, rtol=1e-9, atol=1e-7)
        if reaction.normal is not None:
            np.testing.assert_allclose(other.normal, reaction.normal, rtol=1e-9, atol=1e-7)
            np.testing.assert_allclose(other.moment, reaction.moment, rtol=1e-9, atol=1e-9)


def _turned_course(rotor: complex) -> dict:
    data = yaml.safe_load((TABLES / "course_11_link.yaml").read_text(encoding="utf-8"))
    for key, entry in data["geometry"].items():
        if key in ("input", "tracing"):
            continue
        z = complex(*entry["point"]) * rotor
        entry["point"] = [z.real, z.imag]
        if "direction" in entry:
            entry["direction"] += math.degrees(cmath.phase(rotor))
    del data["geometry"]["tracing"]
    return data


def _turned_table(force: Tabulated, rotor: complex) -> Tabulated:
    return Tabulated(force.nodes, tuple(v * rotor for v in force.values))


def test_listing_a_pair_the_other_way_negates_its_reaction() -> None:
    model, data = load("slider_crank_press.yaml")
    links = dict(model.pair_links)
    kind, (a, b), guide = links["3-0"]
    swapped = copy.copy(model)
    object.__setattr__(swapped, "pair_links", {**links, "3-0": (kind, (b, a), guide)})
    q = np.radians([10.0, 100.0, 250.0])
    base = kinetostatics(analyse(model, q, analogs=True), data, 10.0)
    other = kinetostatics(analyse(swapped, q, analogs=True), data, 10.0)
    for part in ("x", "y", "normal", "moment"):
        np.testing.assert_array_equal(getattr(other.reactions["3-0"], part),
                                      -getattr(base.reactions["3-0"], part))
    np.testing.assert_array_equal(other.driving, base.driving)


def test_the_normal_force_acts_where_its_moment_about_k_is_the_couple() -> None:
    model, data = load("course_11_link_forces.yaml")
    result = kinetostatics(analyse(model, points=36, analogs=True), data, 10.0)
    for pid in ("10-11", "11-0", "6-7", "3-4"):
        reaction = result.reactions[pid]
        force = reaction.x + 1j * reaction.y
        arm = reaction.acting_point - reaction.point
        moment = (arm.conjugate() * force).imag
        np.testing.assert_allclose(moment, reaction.moment, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose((arm.conjugate() * force).real, 0.0, atol=1e-9)
    assert result.reactions["0-1"].acting_point is None


def test_each_dyad_kind_has_its_own_equilibrium() -> None:
    from assur.forces.solver import EQUILIBRIA
    from assur.kinds import KINDS

    solvers = {kind.code: EQUILIBRIA.get(kind.code) for kind in KINDS.values()}
    assert solvers.pop("L0") is None            # the input group is solved by the drive
    assert all(callable(f) for f in solvers.values())
    assert len(set(solvers.values())) == len(solvers) == 5
    # every group of the 11-link example (one of each dyad kind) is solved by its entry
    model, data = load("course_11_link_forces.yaml")
    result = kinetostatics(analyse(model, np.radians([30.0]), analogs=True), data, 10.0)
    assert {g.kind for g in model.groups} == {0, 1, 2, 3, 4, 5}
    assert np.isfinite(result.driving).all() and result.reason.tolist() == [0]


def test_where_a_group_does_not_assemble_the_reason_says_so() -> None:
    model = assur.load_model(TABLES / "course_11_link_fails.yaml")
    motion = analyse(model, points=72, analogs=True)
    result = kinetostatics(motion, ForceData(loads=(Load(3, torque=-5.0),)), 5.0)
    apart = ~np.asarray(motion.exists)
    assert 0 < apart.sum() < 72
    assert (result.reason[apart] == ForceReason.NOT_ASSEMBLED).all()
    assert np.isnan(result.driving[apart]).all()
    assert (result.reason[~apart] == 0).all() and np.isfinite(result.driving[~apart]).all()
