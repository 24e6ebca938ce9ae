"""The force analysis of triads and class IV groups against one global solve of all links.

Random designs of a crank driving a triad of each leash combination (RR, RP, PR leashes,
internal pair first) and of the class IV group of ``input_tables/class_iv_group.yaml`` with
its dimensions varied, with random masses, centres, moments of inertia, forces, torques and
gravity. The reference is the independent global Newton–Euler solve of
``test_forces_global`` (all moving links at once, every pair's reaction and the driving
torque as unknowns, the centres' accelerations built from the joints). The group-by-group
result agrees with it to 1e-9 relative, and the power balance and every link's residual hold
at every assembled position.
"""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from force_tables import TABLES
from test_forces_global import _global, agrees

import assur
from assur.forces import ForceData, Load, Mass, kinetostatics
from assur.forces.linear import _condensed_solve, _solve, equilibrium_linear
from assur.kinematics.analysis import analyse
from assur.kinematics.higher.kind import Layout
from synthesis.cli.main import main

MM = 1e-3
OMEGA = 12.0
PHI = np.linspace(0.0, 2 * np.pi, 24, endpoint=False)
SEEDS = range(2)
TRIADS = ["RR-RR-RR", "RR-RR-RP", "RR-RR-PR", "RR-RP-RP", "RR-RP-PR", "RR-PR-PR"]


def _triad(kind: str, rng: np.random.Generator) -> assur.KinematicModel:
    """A crank 1 (O–B) driving a triad: base 4 with the internal pairs C, D, F; leash 2
    (B–C, RR or PR), leash 3 (D to E on the frame) and leash 5 (F to G on the frame) of the kinds
    ``kind`` names (RR: two hinges; RP: a block hinged to the base sliding on the frame; PR:
    a leash sliding on a guide of the base, hinged to the frame)."""
    turn = rng.uniform(0, 2 * math.pi)
    b = [rng.uniform(20, 45) * math.cos(turn), rng.uniform(20, 45) * math.sin(turn)]
    c = [rng.uniform(70, 100), rng.uniform(0, 60)]
    d = [c[0] + rng.uniform(20, 50), c[1] + rng.uniform(-40, -10)]
    f = [c[0] + rng.uniform(20, 50), c[1] + rng.uniform(10, 40)]
    e = [d[0] + rng.uniform(-40, 40), d[1] + rng.uniform(-60, -20)]
    g = [f[0] + rng.uniform(-40, 40), f[1] + rng.uniform(20, 60)]
    pairs: list[dict[str, Any]] = [{"id": "O", "type": "R", "links": [0, 1]},
                                   {"id": "B", "type": "R", "links": [1, 2]},
                                   {"id": "C", "type": "R", "links": [2, 4]}]
    geometry: dict[str, Any] = {"O": {"point": [0, 0]}, "B": {"point": b}, "C": {"point": c},
                                "input": {"rotation": str(rng.choice(["ccw", "cw"]))}}
    for inner, outer, link, p, q, leash in (("D", "E", 3, d, e, kind[3:5]),
                                            ("F", "G", 5, f, g, kind[6:8])):
        angle = float(rng.uniform(-180, 180))
        internal: dict[str, Any] = {"id": inner, "type": "R", "links": [link, 4]}
        external: dict[str, Any] = {"id": outer, "type": "R", "links": [link, 0]}
        geometry[inner], geometry[outer] = {"point": p}, {"point": q}
        if leash == "RP":
            external.update(type="P", guide=0)
            geometry[outer]["direction"] = angle
        elif leash == "PR":
            internal.update(type="P", guide=4)
            geometry[inner]["direction"] = angle
        pairs += [internal, external]
    if kind[:2] == "PR":   # leash 2 slides on a guide of the base through C
        pairs[2].update(type="P", guide=4)
        geometry["C"]["direction"] = float(rng.uniform(-180, 180))
    for pair in pairs[1:]:   # either listing order: the reactions are of the first on the second
        if rng.uniform() < 0.5:
            pair["links"] = pair["links"][::-1]
    data = {"mechanism": {"pairs": pairs, "inputs": [1]}, "geometry": geometry}
    return assur.build_model(assur.analyse_structure(assur.chain_from_dict(data)))


def _class_iv(rng: np.random.Generator) -> assur.KinematicModel:
    """The class IV group of ``input_tables`` with every joint moved by up to ±4 mm."""
    model = assur.load_model(TABLES / "class_iv_group.yaml")
    varied = {name: value + rng.uniform(-4, 4) for name, value in model.params.items()
              if name.startswith("IV(") and (".x_" in name or ".y_" in name or ".l_" in name)}
    return model.with_params(varied)


def _loads(model: assur.KinematicModel, rng: np.random.Generator) -> ForceData:
    """Random masses on every moving link, a force and a torque on each group link."""
    moving = sorted({link for _, links, _ in model.pair_links.values() for link in links}
                    - {model.frame})

    def near() -> complex:
        return complex(*rng.uniform(-60, 180, 2))

    masses = {link: Mass(float(rng.uniform(0.1, 2.0)), near(), float(rng.uniform(0, 5e-3)))
              for link in moving}
    loads = tuple(load for link in moving[1:] for load in (
        Load(link, force=complex(*rng.uniform(-400, 400, 2)), point=near()),
        Load(link, torque=float(rng.uniform(-10, 10)))))
    return ForceData(masses, loads, complex(*rng.uniform(-10, 10, 2)))


def _agrees(model: assur.KinematicModel, data: ForceData) -> int:
    """Compare with the global solve; the number of positions compared."""
    motion = analyse(model, PHI, analogs=True)
    result = kinetostatics(motion, data, OMEGA)
    with np.errstate(invalid="ignore"):  # NaN where the design does not assemble
        expected = _global(motion, data, OMEGA)
    solved = result.reason == 0
    assert np.array_equal(solved, np.asarray(motion.exists) & (result.reason == 0))
    assert np.all(np.isnan(result.driving[~solved]))
    if not solved.any():
        return 0
    agrees(motion, result, expected, solved, 1e-9)
    for residual in result.residuals.values():
        assert np.max(residual.force[solved]) <= 1e-9
        assert np.max(residual.moment[solved]) <= 1e-9
    return int(solved.sum())


@pytest.mark.parametrize("kind", [*TRIADS, "PR-RP-PR"])   # the last without a bar
def test_triad_reactions_equal_the_global_solve(kind: str) -> None:
    compared = 0
    for seed in SEEDS:
        rng = np.random.default_rng(seed)
        model = _triad(kind, rng)
        assert model.groups[-1].layout is not None
        assert sorted(model.groups[-1].layout.leashes) == sorted(kind.split("-"))
        compared += _agrees(model, _loads(model, rng))
    assert compared >= PHI.size / 2


def test_class_iv_reactions_equal_the_global_solve() -> None:
    compared = 0
    for seed in SEEDS:
        rng = np.random.default_rng(seed)
        model = _class_iv(rng)
        compared += _agrees(model, _loads(model, rng))
    assert compared > len(SEEDS) * PHI.size / 2


def test_designs_in_one_call_equal_each_design_alone() -> None:
    """(D, N) arrays: 40 triad designs at once keep the balances and equal the single runs."""
    rng = np.random.default_rng(3)
    model = _triad("RR-RR-RP", rng)
    data = _loads(model, rng)
    varied = {name: value * rng.uniform(0.97, 1.03, (40, 1))
              for name, value in model.params.items()
              if name.startswith("III(") and (".l_" in name or ".x_" in name)}
    result = kinetostatics(analyse(model.with_params(varied), PHI, analogs=True), data,
                           OMEGA)
    solved = result.reason == 0
    assert result.driving.shape == (40, PHI.size) and solved.sum() > 200
    assert np.all(np.abs(result.power_balance[solved]) <= 1e-9 * result.power_scale[solved])
    for k in (0, 39):
        single = model.with_params({name: value[k, 0] for name, value in varied.items()})
        alone = kinetostatics(analyse(single, PHI, analogs=True), data, OMEGA)
        np.testing.assert_allclose(result.driving[k], alone.driving, rtol=1e-12, atol=1e-12)
        for pid, reaction in alone.reactions.items():
            np.testing.assert_allclose(result.reactions[pid].x[k], reaction.x, rtol=1e-12,
                                       atol=1e-9)


class _Stub:
    """Loads of an RRR triad given by its joint points (m) and known loads."""

    def __init__(self, points: dict[str, np.ndarray]) -> None:
        self.points = points
        self.links = {"B": (1, 2), "C": (2, 4), "D": (3, 4), "E": (3, 0), "F": (5, 4),
                      "G": (5, 0)}

    def joint(self, pair: str) -> np.ndarray:
        return self.points[pair]

    def normal(self, pair: str) -> np.ndarray:
        raise AssertionError("no prismatic pair")

    def pair(self, pair: str) -> tuple[str, tuple[int, int]]:
        return "R", self.links[pair]

    def force(self, link: int) -> np.ndarray:
        return np.full(3, 10.0 + 5j * link)

    def moment(self, link: int, point: np.ndarray) -> np.ndarray:
        return 2.0 - (point.real * 5 * link - point.imag * 10.0)


def test_a_dead_position_and_a_missing_one_are_nan_with_a_zero_margin() -> None:
    """Three leash lines through one point (position 0), a NaN joint (position 1), a regular
    triad (position 2): no error, NaN and margin 0 at the first two; at the third every link
    balances with the reported transfers."""
    group = SimpleNamespace(label="III(2,3,4,5)", layout=Layout(
        links=(4, 2, 3, 5), names=("base", "leash1", "leash2", "leash3"),
        internal=("C", "D", "F"), external=("B", "E", "G")))
    # leashes along the x-axis, the y-axis and the diagonal: all through (0, 0)
    inner = {"C": [1.0, np.nan, 1.0], "D": [1j, 1j, 1.2j], "F": [1 + 1j, 1 + 1j, 0.9 + 1j]}
    outer = {"B": [2.0, 2.0, 2.0], "E": [2j, 2j, 2j], "G": [2 + 2j, 2 + 2j, 2 + 2j]}
    points = {pair: np.array(p) for pair, p in {**inner, **outer}.items()}
    loads = _Stub(points)
    solved = equilibrium_linear(group, loads)  # type: ignore[arg-type]
    assert solved.determinant[0] < 1e-12 and solved.determinant[1] == 0
    assert solved.determinant[2] > 1e-3
    for transfer in solved.transfers:
        assert np.all(np.isnan(transfer.force[:2])) and np.isfinite(transfer.force[2])
    for link in (2, 3, 4, 5):
        force = loads.force(link)[2]
        moment = loads.moment(link, np.array([0j]))[0]
        for transfer in solved.transfers:
            sign = (transfer.target == link) - (transfer.source == link)
            force += sign * transfer.force[2]
            moment += sign * (transfer.point[2].real * transfer.force[2].imag
                              - transfer.point[2].imag * transfer.force[2].real)
        assert abs(force) < 1e-12 * 50 and abs(moment) < 1e-12 * 50, link


def test_a_singular_matrix_in_a_batch_is_nan_and_the_others_are_solved() -> None:
    matrix = np.array([np.zeros((3, 3)), np.diag([1.0, 2.0, 4.0]), np.full((3, 3), np.nan)])
    x, rcond = _solve(matrix, np.ones((3, 3)))
    assert np.all(np.isnan(x[0])) and np.all(np.isnan(x[2]))
    assert x[1].tolist() == [1.0, 0.5, 0.25] and rcond.tolist() == [0.0, 0.25, 0.0]


def _structured(rng: np.random.Generator, positions: int) -> np.ndarray:
    """Random 12×12 systems (positions last) shaped like a triad's: pairs 3, 4, 5 external
    revolute pairs on links 0, 1, 2, entering only those links' rows, the identity in their
    force rows; every other entry random."""
    matrix = rng.normal(size=(12, 12, positions))
    for pair, link in ((3, 0), (4, 1), (5, 2)):
        columns = [2 * pair, 2 * pair + 1]
        matrix[:, columns] = 0.0
        matrix[3 * link:3 * link + 2, columns] = np.eye(2)[..., None]
        matrix[3 * link + 2, columns] = rng.normal(size=(2, positions))
    return matrix


def test_the_condensed_solve_is_the_whole_systems_solve() -> None:
    rng = np.random.default_rng(3)
    matrix, rhs = _structured(rng, 50), rng.normal(size=(12, 50))
    # the last system singular: a row of link 3 a combination of its other two
    matrix[9, :, -1] = 0.5 * matrix[10, :, -1] - 2.0 * matrix[11, :, -1]
    rhs[9, -1] = 0.5 * rhs[10, -1] - 2.0 * rhs[11, -1]
    whole = np.moveaxis(matrix, -1, 0)
    expected = np.linalg.solve(whole[:-1], np.moveaxis(rhs, -1, 0)[:-1, :, None])[..., 0]
    x, rcond = _condensed_solve(matrix.copy(), rhs.copy(), {3: 0, 4: 1, 5: 2})
    assert np.allclose(x[:-1], expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())
    assert np.all(np.isnan(x[-1])) and rcond[-1] <= 1e-14 and np.all(rcond[:-1] > 1e-6)
    # singular exactly where the whole is: the condensed determinant is the whole one's
    assert abs(np.linalg.det(whole[-1])) < 1e-12 and np.all(np.abs(np.linalg.det(whole[:-1])) > 1e-6)


def test_analyze_forces_on_the_six_bar_with_a_triad(capsys: pytest.CaptureFixture[str]
                                                     ) -> None:
    """The shipped example: the JSON's reactions and drive balance the power of its loads
    (the lever torque printed beside it), and the text report has the force section."""
    import json

    table = str(TABLES / "six_bar_triad_forces.yaml")
    assert main(["analyze", table, "--forces", "--omega", "10", "--points", "24",
                 "--json"]) == 0
    forces = json.loads(capsys.readouterr().out)["forces"]
    driving = np.array(forces["driving_torque"])
    assert set(forces["reactions"]) == {"O", "B", "C", "D", "E", "F", "G"}
    assert forces["reason"] == [None] * 24
    np.testing.assert_allclose(driving, forces["driving_torque_lever"], rtol=0,
                               atol=1e-9 * np.max(np.abs(driving)))
    assert main(["analyze", table, "--forces", "--omega", "10", "--lang", "ru"]) == 0
    assert "Силовой расчёт" in capsys.readouterr().out
