"""Triads and class IV groups through the model builder and the analysis (``assur analyze``).

The expectations come from elsewhere: the test vectors of ``higher_groups.md`` §6 (two
independent solvers), distances between the joints of each link in the drawing, a walk
through the full set of assembly modes on a crank grid 20 times finer than the analysis,
and central differences.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from test_higher_vectors import CASES

from assur.kinematics import jets as J
from assur.kinematics.analysis import Motion, analyse, values
from assur.kinematics.build import load_model
from assur.kinematics.existence import check_existence
from assur.kinematics.higher import Triad, TriadInputs, assembly_modes
from assur.kinematics.higher.kind import HigherGroupSolution
from assur.kinematics.jets import Jet
from assur.kinematics.model import KinematicModel

TABLES = Path(__file__).parents[2] / "input_tables"
DEG = np.pi / 180.0
#: The test vector of each example table and the pairs of its joints, in the vector's order.
EXAMPLES = {"eight_bar_triad": ("V1", "III(4,5,6,7)", ("E", "F", "H")),
            "class_iv_group": ("V2", "IV(2,3,4,5)", ("C", "D", "E", "F")),
            "six_bar_triad": ("V3", "III(2,3,4,5)", ("C", "D", "F"))}


@pytest.mark.parametrize("table", EXAMPLES)
def test_the_example_tables_give_the_test_vectors(table: str) -> None:
    """The drawn mode at the vector's angles and every mode at the sketch, to 1e-9 L."""
    case, label, pairs = EXAMPLES[table]
    group, _, _, modes, _, cycle = CASES[case]
    size = float(group.size)
    model = load_model(TABLES / f"{table}.yaml")
    angles = np.array([0.0, *sorted(cycle)])
    motion = analyse(model, angles * DEG)
    assert motion.exists.all()
    for column, angle in enumerate(angles[1:], start=1):
        for pid, point in zip(pairs, cycle[int(angle)], strict=True):
            assert abs(np.asarray(motion.joints[pid])[column] - complex(*point)) <= 1e-9 * size
    solution = motion.solutions[label]
    assert isinstance(solution, HigherGroupSolution)
    found = solution.modes()
    assert len(found) == len(modes) and [abs(m.angle) < 1e-9 for m in found] == \
        [m.drawn for m in found]
    for mode, (theta, *points) in zip(found, modes, strict=True):
        assert abs(mode.angle - theta * DEG) <= 1e-9
        for pid, point in zip(pairs, points, strict=True):
            assert abs(mode.joints[pid] - complex(*point)) <= 1e-9 * size


def _link_distances(model: KinematicModel, motion: Motion) -> list[np.ndarray]:
    """|Z_a − Z_b| over the positions for every two revolute joints on one moving link."""
    out = []
    for link in model.links:
        on = [pid for pid, (kind, links, _) in model.pair_links.items()
              if kind == "R" and link in links and pid in motion.joints]
        out += [np.abs(J.value(motion.joints[a]) - J.value(motion.joints[b]))
                for i, a in enumerate(on) for b in on[i + 1:]]
    return out


@pytest.mark.parametrize("table", ["eight_bar_triad", "class_iv_group", "six_bar_triad"])
def test_links_stay_rigid_over_the_cycle_of_random_designs(table: str) -> None:
    """Every distance on every link constant over a full cycle (≤ 1e-9 relative), for 8
    designs whose internal joints are moved at random (each picks its mode at the sketch)."""
    model = load_model(TABLES / f"{table}.yaml")
    rng = np.random.default_rng(7)
    moved = {name: value + rng.uniform(-4, 4, (8, 1)) for name, value in model.params.items()
             if name.startswith(("III", "IV")) and name.split(".")[1][:2] in ("x_", "y_")}
    designs = model.with_params(moved)
    motion = analyse(designs, np.arange(0, 360, 3.0) * DEG)
    ok = motion.exists
    assert ok.any(axis=1).all()
    for distance in _link_distances(designs, motion):
        first = np.nanmax(np.where(ok, distance, np.nan), axis=1, keepdims=True)
        spread = np.abs(distance - first)[ok]
        assert (spread <= 1e-9 * first.max()).all()


def test_analogs_through_the_analysis_against_central_differences() -> None:
    model = load_model(TABLES / "eight_bar_triad.yaml")
    centre, h = np.radians([20.0, 110.0, 250.0]), 1e-5
    jets = analyse(model, centre, analogs=True)
    ahead, behind = analyse(model, centre + h), analyse(model, centre - h)
    for pid in ("E", "F", "H", "D", "G"):
        fd = (values(ahead.joints[pid]) - values(behind.joints[pid])) / (2 * h)
        assert np.abs(fd - _d1(jets.joints[pid])).max() <= 1e-6 * 200
    for link in (4, 5, 6, 7):
        turn = values(ahead.link_angle(link)) - values(behind.link_angle(link))
        fd = np.angle(np.exp(1j * turn)) / (2 * h)
        assert np.abs(fd - _d1(jets.link_angle(link))).max() <= 1e-6


def _d1(x: object) -> np.ndarray:
    assert isinstance(x, Jet)
    return np.asarray(x.d1)


def _walk(group: Triad, inputs: Callable[[np.ndarray], TriadInputs], phi: np.ndarray
          ) -> np.ndarray:
    """Where the sketched mode, walked to the nearest of all modes at each angle (forward and
    backward from 0), is followed: a scan through the full root set."""
    modes = assembly_modes(group, inputs(phi)).x  # (angles, modes, 3)
    scale = np.array([1 / float(group.size), 1 / float(group.size), 1.0])
    alive = np.zeros(len(phi), dtype=bool)
    for order in (np.arange(len(phi)), np.r_[0, np.arange(len(phi) - 1, 0, -1)]):
        x = group.drawn()
        for m in order:
            gap = np.abs(modes[m] - x)
            gap[:, 2] = np.abs(np.angle(np.exp(1j * gap[:, 2])))
            apart = np.nan_to_num((gap * scale).sum(axis=1), nan=np.inf)
            if apart.min() > 0.05:
                break
            x = modes[m, apart.argmin()]
            alive[m] = True
    return alive


def test_existence_interval_against_a_dense_scan_through_all_modes() -> None:
    """``analyze``'s interval of the failing example: its ends within one step of a 0.05°
    scan through the full root set, reason 8; the verdict at every analysed position."""
    model = load_model(TABLES / "six_bar_triad_fails.yaml")
    report = check_existence(model, points=360)
    (group,) = report.groups
    (interval,) = group.intervals
    assert interval.reason == 8
    pin, c, d, f, e = -50 - 1.5j, 77.5 + 30.5j, 112 + 7.5j, 114 + 52j, 81 + 31j
    triad = Triad(("RR", "RR", "RP"), (c, d, f), (pin, e, f), (None, None, 1 + 0j))

    def inputs(phi: np.ndarray) -> TriadInputs:
        return TriadInputs((pin * np.exp(1j * phi), e + 0 * phi, f + 0 * phi),
                           (None, None, 1 + 0 * phi))

    step = 0.05
    phi = np.arange(0, 360, step) * DEG
    alive = _walk(triad, inputs, phi)
    lost = np.flatnonzero(~alive)
    start, end = phi[lost[0]], phi[lost[-1]]
    assert start - step * DEG <= interval.start <= start
    assert end <= interval.end <= end + step * DEG
    assert (group.fails == ~alive[::20]).all()
