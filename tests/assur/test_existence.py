"""Existence intervals against a dense brute-force scan written independently in plain Python.

The scan reads the sketch of the failing course design with PyYAML, derives the dimensions
with ``math`` and checks the course's inequalities position by position (triangle inequality
for the RRR group, offset against hinge distance for the RPR group) — no code of the program
is used for the reference.
"""

from __future__ import annotations

import cmath
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import assur
import assur.kinematics.dyads

ROOT = Path(__file__).resolve().parents[2]
FAILS = ROOT / "input_tables" / "course_11_link_fails.yaml"
SCAN = 20000  # brute-force positions over one turn


def _p(sketch: dict, key: str) -> complex:
    x, y = sketch[key]["point"]
    return complex(x, y)


def _reference_scan(phi_shift_deg: float = 0.0, delta: float = 0.0) -> list[bool]:
    """True where the RPR group (6, 7) is the first group that cannot be assembled."""
    sketch = yaml.safe_load(FAILS.read_text())["geometry"]
    o, a0, c0, d = _p(sketch, "0-1"), _p(sketch, "1-2"), _p(sketch, "2-3"), _p(sketch, "3-0")
    n0, e7 = _p(sketch, "2-6"), _p(sketch, "7-0")
    l1, phi10 = abs(a0 - o), cmath.phase(a0 - o) + math.radians(phi_shift_deg)
    li, lj = abs(c0 - a0), abs(c0 - d)
    left = ((d - a0).conjugate() * (c0 - a0)).imag > 0  # C left of A→D in the sketch
    n_local = (n0 - a0) / (c0 - a0) * abs(c0 - a0)  # N in the coupler frame (axis A→C)
    axis = cmath.exp(1j * math.radians(sketch["6-7"]["direction"]))
    offset = abs((axis.conjugate() * (e7 - n0)).imag)
    out = []
    for k in range(SCAN):
        phi = 2 * math.pi * k / SCAN
        a = o + l1 * cmath.exp(1j * (phi10 + phi))
        dist = abs(d - a)
        assert abs(li - lj) < dist < li + lj  # the RRR group always assembles here
        cos_a = (li * li + dist * dist - lj * lj) / (2 * li * dist)
        turn = math.acos(cos_a) * (1 if left else -1)
        c = a + li * cmath.exp(1j * (cmath.phase(d - a) + turn))
        n = a + n_local * (c - a) / abs(c - a)
        rho = abs(n - e7)
        out.append(offset > (1 - delta) * rho)
    return out


def _intervals(mask: list[bool]) -> list[tuple[float, float]]:
    """Degrees (start, end) of the runs of True, joined across 360°."""
    n = len(mask)
    runs, start = [], None
    for k, value in enumerate(mask + [False]):
        if value and start is None:
            start = k
        elif not value and start is not None:
            runs.append([start, k - 1])
            start = None
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == n - 1:
        runs = [[runs[-1][0], runs[0][1]]] + runs[1:-1]
    step = 360.0 / n
    return [(a * step, b * step) for a, b in runs]


@pytest.fixture(scope="module")
def model() -> assur.KinematicModel:
    return assur.load_model(FAILS)


def _check(report: assur.ExistenceReport, reference: list[tuple[float, float]]) -> None:
    step = 360.0 / SCAN
    groups = {g.label: g for g in report.groups}
    assert [g.label for g in report.groups if g.intervals] == ["L3(6,7)"]
    found = [(math.degrees(i.start), math.degrees(i.end)) for i in groups["L3(6,7)"].intervals]
    assert len(found) == len(reference)
    for (a, b), (ra, rb) in zip(found, reference):
        assert abs((a - ra + 180) % 360 - 180) <= 1.01 * step
        assert abs((b - rb + 180) % 360 - 180) <= 1.01 * step
    interval = groups["L3(6,7)"].intervals[0]
    assert assur.kinematics.dyads.REASONS[interval.reason][0] == "guide offset larger than hinge distance"


def test_failing_interval_matches_the_brute_force_scan(model: assur.KinematicModel) -> None:
    report = assur.check_existence(model, points=360)
    reference = _intervals(_reference_scan())
    assert len(reference) == 1
    _check(report, reference)
    assert not report.all_exist
    # the worst violation: offset minus hinge distance, in mm, at the worst position
    interval = report.groups[2].intervals[0]
    assert interval.unit == "mm" and 4.0 < interval.shortfall < 5.0


def test_interval_ends_do_not_depend_on_the_grid(model: assur.KinematicModel) -> None:
    coarse = assur.check_existence(model, points=48).groups[2].intervals[0]
    fine = assur.check_existence(model, points=720).groups[2].intervals[0]
    assert abs(coarse.start - fine.start) < 1e-8 and abs(coarse.end - fine.end) < 1e-8


def test_interval_across_the_start_of_the_turn(model: assur.KinematicModel) -> None:
    shifted = model.with_params({"L0(1).phi_1_0": float(model.params["L0(1).phi_1_0"]) + 50.0})
    report = assur.check_existence(shifted, points=360)
    reference = _intervals(_reference_scan(phi_shift_deg=50.0))
    assert reference[0][0] > reference[0][1]  # the reference run wraps past 360°
    _check(report, reference)


def test_margin_delta_widens_the_interval(model: assur.KinematicModel) -> None:
    strict = model.with_params({"L3(6,7).delta": 0.05})
    report = assur.check_existence(strict, points=360)
    reference = _intervals(_reference_scan(delta=0.05))
    _check(report, reference)
    plain = assur.check_existence(model, points=360).groups[2].intervals[0]
    widened = report.groups[2].intervals[0]
    assert widened.start < plain.start and widened.end > plain.end


def test_later_groups_are_not_evaluated_where_an_earlier_one_fails(
        model: assur.KinematicModel) -> None:
    report = assur.check_existence(model, points=360)
    l3, l2, l5 = report.groups[2], report.groups[3], report.groups[4]
    assert l3.fails.sum() > 0
    assert not l2.evaluated[l3.fails].any() and not l5.evaluated[l3.fails].any()
    assert l2.evaluated[~l3.fails].all()
    assert l2.verdict == "assembles" and l5.verdict == "assembles"
    assert np.isnan(l2.margin[l3.fails]).all()
    assert (report.first[l3.fails] == 2).all() and (report.first[~l3.fails] == -1).all()


def _four_bar(crank: float) -> assur.KinematicModel:
    """A four-bar sketch: crank pivot (0, 0), rocker pivot (100, 0), coupler 80, rocker 60."""
    chain = assur.chain_from_dict({
        "mechanism": {"pairs": [
            {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
            {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
            "inputs": [1]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": [crank, 0]},
                     "D": {"point": [100, 0]}, "C": {"point": [100 - 36, 48]}}})
    return assur.build_model(assur.analyse_structure(chain))


def test_non_grashof_crank_fails_where_the_triangle_inequality_breaks() -> None:
    crank = 30.0  # 100 + 30 > 80 + 60: the coupler and rocker cannot reach at φ near 180°
    model = _four_bar(crank)
    li, lj = math.hypot(64 - crank, 48), 60.0
    report = assur.check_existence(model, points=360)
    (group,) = report.groups
    reference = []
    for k in range(SCAN):
        phi = 2 * math.pi * k / SCAN
        dist = abs(100 - crank * cmath.exp(1j * phi))
        reference.append(not abs(li - lj) <= dist <= li + lj)
    expected = _intervals(reference)
    assert len(group.intervals) == len(expected) == 1
    got = group.intervals[0]
    step = 360 / SCAN
    assert abs(math.degrees(got.start) - expected[0][0]) <= 1.01 * step
    assert abs(math.degrees(got.end) - expected[0][1]) <= 1.01 * step
    assert assur.kinematics.dyads.REASONS[got.reason][0].startswith("hinges too far apart")
    # shortfall in mm at the worst position (φ = 180°): d − (l_i + l_j)
    assert math.isclose(got.shortfall, 100 + crank - li - lj, rel_tol=1e-6)


def test_group_that_never_assembles_fails_over_the_whole_turn() -> None:
    model = _four_bar(30.0).with_params({"L1(2,3).l_j": 200.0})  # |l_i − l_j| > 130 ≥ d
    report = assur.check_existence(model, points=72)
    (group,) = report.groups
    (interval,) = group.intervals
    assert (interval.start, interval.end) == (0.0, 2 * math.pi)
    assert assur.kinematics.dyads.REASONS[interval.reason][0].startswith("hinges too close")
    assert group.fails.all() and not report.all_exist
