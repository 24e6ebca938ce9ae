"""Tracker case: the design task as a B1–B5 synthesis problem, against a hand-derived
optimum and against the patent's procedure."""

from __future__ import annotations

import cmath
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from synthesis.cases.tracker.design import PATENT_TASK, refine
from synthesis.cases.tracker.synthesis_problem import Evaluator, bounds, has_room, solve


@pytest.fixture(scope="module")
def answer():
    return solve(PATENT_TASK, budget_log2=10, seed=0)


def _asymmetric_optimum(a_deg, b_deg, k5, clearance):
    """Smallest k2 with the retracted end at ADC = b_min.ad and the post clearance met.

    D at 0, A at 1, E at k5, l1 = 1. The platform AB is AD mirrored in AC, so it turns by
    twice the turn of AC: arg(C − 1) grows by a/2 over the stroke. C = 1 + t·e^{iγ} on the
    circle |C| = k2.
    """
    def extended(k2):
        gamma = cmath.phase(k2 * cmath.exp(1j * math.radians(b_deg)) - 1) + math.radians(a_deg) / 2
        t = -math.cos(gamma) + math.sqrt(math.cos(gamma) ** 2 + k2 * k2 - 1)
        return 1 + t * cmath.exp(1j * gamma)

    def gap(k2):
        c = extended(k2)
        return (k5 - 1) * c.imag / abs(c - k5) - clearance

    k2 = brentq(gap, 1.2, 3.0, xtol=1e-12)
    c = extended(k2)
    return k2, abs(c - k5), math.degrees(math.pi - cmath.phase(c))


def test_search_finds_the_hand_derived_asymmetric_optimum(answer):
    k2, k_d, far_end = _asymmetric_optimum(210.0, 25.0, 2.0, 85.0 / 300.0)
    assert far_end > 25.0                        # the extended end keeps b above the limit
    assert answer.feasible
    assert answer.k2 == pytest.approx(k2, abs=0.01)
    assert answer.l_d == pytest.approx(k_d * 300.0, rel=0.005)
    assert math.degrees(answer.ends[0]) == pytest.approx(25.0, abs=0.05)


def test_synthesis_answer_is_confirmed_by_the_actuator_driven_chain(answer):
    check = answer.check
    assert check.exists.all()
    assert check.stroke == pytest.approx(PATENT_TASK.stroke, abs=1e-7)
    assert np.degrees(check.transmission[0].min()) >= 25.0 - 1e-6
    assert check.min_clearance >= 85.0 - 1e-6
    assert answer.l_d - answer.l_i <= 1000.0


def test_synthesis_is_never_larger_than_the_symmetric_procedure(answer):
    assert answer.l_d <= refine(PATENT_TASK, 2.0).l_d


def test_same_seed_same_answer(answer):
    again = solve(PATENT_TASK, budget_log2=10, seed=0)
    assert np.array_equal(again.x, answer.x)


def test_evaluator_separates_obligatory_and_desirable_conditions():
    evaluate = Evaluator(PATENT_TASK, positions=61)
    x = np.array([[2.2, 2.0, -73.916],      # the patent's design, symmetric placement
                  [1.4, 2.0, -56.576]])     # k2 = 1.4 symmetric: b 22.74°, l_g 48.7 mm
    c = evaluate(x)
    assert c.p1.tolist() == [0.0, 0.0]      # both assemble over the whole stroke
    assert c.p2[0] == pytest.approx(0.0, abs=1e-9)
    assert c.q[0] == pytest.approx(4.0402, abs=1e-3)       # k_d of the patent's design
    # θ0 = 2c − 180° with c = 61.71° (fig. 5); P2 = pressure (90 − 22.74 − 65)/65
    # + clearance (85 − 48.7)/85 (Tabel of Etapa II–V for k2 = 1.4)
    assert c.p2[1] == pytest.approx((90 - 22.74 - 65) / 65 + (85 - 48.7) / 85, abs=0.005)


def test_stroke_near_a_full_turn_has_no_room_for_the_start_angle():
    task = replace(PATENT_TASK, stroke=math.radians(359.0))
    assert not has_room(task)
    with pytest.raises(ValueError, match="leaves no room"):
        bounds(task)


def test_a_batch_of_designs_equals_one_design_at_a_time():
    evaluate = Evaluator(replace(PATENT_TASK, k5=(1.8, 2.4)), positions=61)
    x = np.array([[2.2, 2.0, -73.9], [1.8, 2.3, -90.0], [1.5, 1.9, -60.0]])
    batch = evaluate(x)
    for k, row in enumerate(x):
        one = evaluate(row)
        assert one.p1[0] == batch.p1[k]
        assert one.p2[0] == pytest.approx(batch.p2[k], abs=1e-12)
        assert one.q[0] == pytest.approx(batch.q[k], abs=1e-12)
