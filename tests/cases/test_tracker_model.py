"""Tracker case: the kinematic model on the group solvers against the closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from assur import REASONS, Reason
from synthesis.cases.tracker.design import PATENT_TASK, design_at
from synthesis.cases.tracker.model import actuator_positions, simulate
from synthesis.cases.tracker.study import verify


@pytest.fixture(scope="module")
def patent_design():
    return verify(design_at(PATENT_TASK, 2.2, 2.0), positions=401)


def test_every_link_keeps_its_length(patent_design):
    m, d = patent_design.motion, patent_design.design
    assert m.exists.all()
    assert np.allclose(np.abs(m.b - m.a), d.l1, atol=1e-9)
    assert np.allclose(np.abs(m.c - m.b), d.l2, atol=1e-9)
    assert np.allclose(np.abs(m.c - m.d), d.l2, atol=1e-9)
    assert np.allclose(np.abs(m.c - m.e), m.s, atol=1e-9)
    assert np.allclose(np.abs(m.e - m.d), d.l5, atol=1e-12)


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
    assert patent_design.clearance == pytest.approx(patent_design.design.l_g, abs=1e-9)
    assert patent_design.min_clearance == pytest.approx(patent_design.design.l_g, abs=1e-6)


def test_lever_arm_equals_the_finite_difference_of_the_platform_angle(patent_design):
    m = patent_design.motion
    numeric = np.gradient(m.s, m.platform)
    assert np.allclose(m.lever_arm[1:-1], numeric[1:-1], rtol=2e-3)


def test_failed_assembly_is_data_not_nan_silence():
    s = np.array([100.0, 400.0, 5000.0])           # the last one cannot reach C
    m = simulate(300.0, 660.0, 600.0, s)
    assert m.exists.tolist() == [True, True, False]
    assert np.isnan(m.c[-1]) and m.margin[-1] < 0.0
    assert REASONS[int(m.reason[-1])][0] == REASONS[Reason.FOLDED][0]  # |EC| − |DC| > |DE|
    assert m.reason[:2].tolist() == [0, 0]


def test_designs_are_simulated_at_once_by_broadcasting():
    l1 = np.array([[300.0], [250.0]])
    s = actuator_positions(np.array([350.0, 300.0]), np.array([1200.0, 1000.0]), 11)
    m = simulate(l1, 2.0 * l1, 2.0 * l1, s)
    assert m.b.shape == (2, 11) and m.stroke.shape == (2,)


@given(st.floats(120.0, 300.0), st.floats(1.2, 3.0), st.floats(1.3, 3.0))
def test_any_stroke_and_proportions_are_confirmed_by_simulation(a_deg, k2, k5):
    task = PATENT_TASK.__class__(stroke=math.radians(a_deg), min_transmission=0.0, l1=100.0,
                                 actuator_stroke=1e6, min_clearance=0.0)
    check = verify(design_at(task, k2, k5), positions=201)
    assert check.assembles
    assert check.errors["stroke"] == pytest.approx(0.0, abs=1e-7)
    assert check.errors["b_min"] == pytest.approx(0.0, abs=1e-7)
    assert check.errors["l_g"] == pytest.approx(0.0, abs=1e-7)
