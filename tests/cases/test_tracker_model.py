"""Tracker case: the chain-table model against the closed forms and against a plain
simulation built directly on the RRR solver."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from assur import solve_rrr
from synthesis.cases.tracker.design import PATENT_TASK, design_at
from synthesis.cases.tracker.model import chain, mechanism_model, simulate, sketch
from synthesis.cases.tracker.study import verify


def _plain(l1, l2, l5, s):
    """C from the circles about E (radius s) and D (l2), B from the circles about A (l1) and
    C (l2) on the side of AC away from D; A at 0, D at −l1, E at l5 − l1."""
    a, d, e = 0j, -l1 + 0j, (l5 - l1) + 0j
    c = solve_rrr(e, d, s, l2, -1.0).c        # σ = −1: C left of D→E, i.e. above the base
    b = solve_rrr(a, c, l1, l2, -1.0).c       # σ = −1: B right of A→C, D is on the left
    return a, b, c, d, e


@pytest.fixture(scope="module")
def patent_design():
    return verify(design_at(PATENT_TASK, 2.2, 2.0), positions=401)


def test_structure_is_two_rrr_dyads_with_the_frozen_actuator():
    analysis, model = mechanism_model(300.0, 660.0, 600.0, 350.0, 1200.0)
    assert analysis.W == 1
    assert analysis.formula == "II₁(3,{5,6}) → II₁(1,2)"
    assert [g.composite for g in analysis.groups] == [(5, 6), None]
    assert model.drive == "actuator" and model.input_range == (350.0, 1200.0)


def test_sketch_pose_is_a_kite():
    g = sketch(300.0, 660.0, 600.0, 350.0, 1200.0)
    p = {k: complex(*v["point"]) for k, v in g.items() if "point" in v}
    assert abs(p["B"] - p["A"]) == pytest.approx(300.0)
    assert abs(p["C"] - p["B"]) == pytest.approx(660.0)
    assert abs(p["C"] - p["D"]) == pytest.approx(660.0)
    assert set(g) - {"input"} == {pair.origin for pair in chain().pairs}


def test_chain_model_equals_the_plain_simulation(patent_design):
    m, d = patent_design.motion, patent_design.design
    a, b, c, dd, e = _plain(d.l1, d.l2, d.l5, m.s)
    assert np.allclose(m.b, b, atol=1e-6) and np.allclose(m.c, c, atol=1e-6)
    assert np.allclose(m.d, dd) and np.allclose(m.e, e) and np.allclose(m.a, a)


def test_every_link_keeps_its_length(patent_design):
    m, d = patent_design.motion, patent_design.design
    assert m.exists.all()
    assert np.allclose(np.abs(m.b - m.a), d.l1, atol=1e-6)
    assert np.allclose(np.abs(m.c - m.b), d.l2, atol=1e-6)
    assert np.allclose(np.abs(m.c - m.d), d.l2, atol=1e-6)
    assert np.allclose(np.abs(m.c - m.e), m.s, atol=1e-6)


def test_kite_branch_keeps_b_equal_to_the_angle_adc(patent_design):
    m = patent_design.motion
    assert np.allclose(m.angle_b, m.angle_adc, atol=1e-9)
    assert np.all(np.abs(m.b - m.d) > 1.0)   # never the other assembly (B on D)


def test_simulated_stroke_and_smallest_transmission_equal_the_closed_form(patent_design):
    d = patent_design.design
    assert patent_design.stroke == pytest.approx(math.radians(210.0), abs=1e-9)
    assert patent_design.b_min == pytest.approx(d.b_min, abs=1e-9)
    # b_min is reached at both ends of the stroke: ADC = b_min retracted, 180° − b_min extended
    adc = patent_design.motion.angle_adc
    assert adc[0] == pytest.approx(d.b_min, abs=1e-9)
    assert adc[-1] == pytest.approx(math.pi - d.b_min, abs=1e-9)


def test_post_distance_at_extension_is_l_g(patent_design):
    assert patent_design.clearance == pytest.approx(patent_design.design.l_g, abs=1e-6)
    assert patent_design.min_clearance == pytest.approx(patent_design.design.l_g, abs=1e-6)


def test_lever_arm_equals_the_finite_difference_of_the_platform_angle(patent_design):
    m = patent_design.motion
    numeric = np.gradient(m.s, m.platform)
    assert np.allclose(m.lever_arm[1:-1], numeric[1:-1], rtol=2e-3)


def test_failed_assembly_is_data_not_silent_nan():
    m = simulate(300.0, 660.0, 600.0, 100.0, 5000.0, positions=5)   # |EC| beyond |DC|+|DE|
    assert m.exists.tolist() == [True, False, False, False, False]
    assert np.isnan(m.c[1:]).all() and np.all(m.margin[1:] < 0.0)


@settings(max_examples=25)
@given(st.floats(120.0, 300.0), st.floats(1.2, 3.0), st.floats(1.3, 3.0))
def test_any_stroke_and_proportions_are_confirmed_by_simulation(a_deg, k2, k5):
    task = PATENT_TASK.__class__(stroke=math.radians(a_deg), min_transmission=0.0, l1=100.0,
                                 actuator_stroke=1e6, min_clearance=0.0)
    check = verify(design_at(task, k2, k5), positions=201)
    assert check.assembles
    assert check.errors["stroke"] == pytest.approx(0.0, abs=1e-6)
    assert check.errors["b_min"] == pytest.approx(0.0, abs=1e-6)
    assert check.errors["l_g"] == pytest.approx(0.0, abs=1e-6)
