"""Criteria Q, P1, P2 and their combination against values worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from synthesis import criteria as C


def test_value_deviations_and_q_by_hand() -> None:
    # two designs, three control points, weights 1, 2, 0.5
    out = np.array([[1.0, 2.0, 3.0], [1.5, 1.0, 5.0]])
    target = np.array([1.0, 2.5, 3.0])
    weights = np.array([1.0, 2.0, 0.5])
    dev = C.value_deviations(out, target, weights)
    # design 0: (0, 2·(−0.5), 0) ; design 1: (0.5, 2·(−1.5), 0.5·2)
    np.testing.assert_allclose(dev, [[0.0, -1.0, 0.0], [0.5, -3.0, 1.0]])
    np.testing.assert_allclose(C.criterion_q(dev), [1.0, 3.0])


def test_rms_form_by_hand() -> None:
    dev = np.array([[2.0, -1.0]])          # weighted: E = (2, 1) → unweighted δ = (1, −1)
    # sqrt((2·1 + 1·1) / 3) = 1
    assert C.criterion_rms(dev, np.array([2.0, 1.0]))[0] == pytest.approx(1.0)


def test_zone_deviation_is_zero_inside_and_the_overshoot_outside() -> None:
    out = np.array([[0.5, -0.2, 1.7]])
    lower = np.array([0.0, 0.0, 0.0])
    upper = np.array([1.0, 1.0, 1.5])
    np.testing.assert_allclose(C.zone_deviations(out, lower, upper, np.array([1.0, 3.0, 1.0])),
                               [[0.0, 0.6, 0.2]])


def test_nearest_point_on_a_square_path() -> None:
    square = np.array([[0, 1, 1 + 1j, 1j]], dtype=complex)
    targets = np.array([0.5 - 0.3j, 1.2 + 0.5j, 0.5 + 0.5j, -1 - 1j])
    index, point = C.nearest_on_path(square, targets)
    dist = C.path_deviations(point, targets, np.ones(4))
    # below the bottom edge, right of the right edge, the centre, beyond the corner 0
    np.testing.assert_allclose(dist[0], [0.3, 0.2, 0.5, math.sqrt(2)], atol=1e-12)
    np.testing.assert_allclose(point[0, :2], [0.5, 1 + 0.5j], atol=1e-12)
    np.testing.assert_allclose(index[0, :2], [0.5, 1.5], atol=1e-12)


def test_nearest_point_on_a_fine_circle() -> None:
    theta = np.linspace(0, 2 * np.pi, 2000, endpoint=False)
    circle = 2.0 * np.exp(1j * theta)[None, :]
    targets = np.array([3.0 * np.exp(0.3j), 0.5 * np.exp(-2j)])
    _, point = C.nearest_on_path(circle, targets)
    # distance to a circle of radius 2: | |P| − 2 |
    np.testing.assert_allclose(np.abs(point - targets)[0], [1.0, 1.5], atol=1e-5)


def test_timed_path_deviation_by_hand() -> None:
    points = np.array([[3 + 4j, 1j]])
    np.testing.assert_allclose(C.timed_path_deviations(points, np.array([0j, 1j]),
                                                       np.array([2.0, 1.0])), [[10.0, 0.0]])


def test_existence_penalty_by_hand() -> None:
    # N_Q = 4; position 0 exists; at 1 group 2 fails by v = 1; at 2 group 4 fails by v = 3
    first = np.array([[0, 2, 4]])
    violation = np.array([[0.0, 1.0, 3.0]])
    # (4 − 2) + 1/2 + (4 − 4) + 3/4 = 3.25
    assert C.existence_penalty(first, violation, 4)[0] == pytest.approx(3.25)
    assert C.existence_penalty(np.zeros((1, 3), int), violation, 4)[0] == 0.0


def test_existence_penalty_prefers_later_and_smaller_breaks() -> None:
    early = C.existence_penalty(np.array([[2]]), np.array([[0.01]]), 5)
    late = C.existence_penalty(np.array([[5]]), np.array([[10.0]]), 5)
    assert late[0] < early[0]


def test_desirable_penalties_by_hand() -> None:
    x = np.array([[-1.0, 0.5, 3.0]])
    # (0 − (−1))/2 + 0 + (3 − 2)/2 = 1
    assert C.bounds_penalty(x, [0, 0, 0], [2, 1, 2])[0] == pytest.approx(1.0)
    # (50 − 40)/40 = 0.25, the second group is within its limit
    alpha = np.radians([[50.0, 10.0]])
    assert C.pressure_penalty(alpha, np.radians([40.0, 45.0]))[0] == pytest.approx(0.25)
    assert C.rotation_penalty(np.radians([[100.0]]), np.radians([80.0]))[0] == \
        pytest.approx(0.25)
    # a point 3 mm beyond a box of diagonal 5 mm, another inside
    assert C.workspace_penalty(np.array([[3.0, 0.0]]), np.array([5.0, 7.0]))[0] == \
        pytest.approx(0.6)
    assert C.desirable_penalty(1.0, 0.25, 0.5, 0.6, weights=(1.0, 2.0, 4.0, 5.0)) == \
        pytest.approx(6.5)


def _criteria(p1: list[float], p2: list[float], q: list[float]) -> C.Criteria:
    n = len(p1)
    return C.Criteria(np.array(p1), np.array(p2), np.array(q), np.zeros((n, 1)),
                      np.zeros((n, 1)))


triples = st.tuples(st.sampled_from([0.0, 0.0, 1e-3, 0.5, 7.0, 1e6]),
                    st.sampled_from([0.0, 0.0, 1e-4, 0.3, 40.0]),
                    st.floats(0.0, 1e3, allow_nan=False))


@given(st.lists(triples, min_size=2, max_size=12))
def test_lexicographic_merit_orders_like_the_tuple(items: list[tuple[float, float, float]]
                                                   ) -> None:
    p1 = [a for a, _, _ in items]
    p2 = [b if a == 0 else math.nan for a, b, _ in items]
    q = [c if a == 0 else math.nan for a, _, c in items]
    m = C.merit(_criteria(p1, p2, q), q_ref=0.1)
    key = [(a, b if a == 0 else 0.0, c if a == 0 else 0.0) for a, b, c in items]
    for i in range(len(items)):
        for j in range(len(items)):
            if key[i] < key[j]:
                assert m[i] <= m[j]
            if key[i] == key[j]:
                assert m[i] == m[j]


def test_weighted_merit_trades_p2_for_q() -> None:
    c = _criteria([0.0, 0.0, 0.1], [0.0, 0.1, math.nan], [1.0, 0.5, math.nan])
    lex = C.merit(c)
    weighted = C.merit(c, objective="weighted", p2_weight=1.0)
    assert lex[0] < lex[1] < lex[2]           # P2 > 0 loses against any Q
    assert weighted[1] < weighted[0] < weighted[2]   # 0.5 + 0.1 < 1.0; P1 > 0 still last
