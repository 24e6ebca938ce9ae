"""A linear actuator inside a triad (a bar leash) and inside a class IV group (a coupler).

The shipped example ``input_tables/actuator_triad.yaml`` (cylinder 2 and rod 3 as the leash
A–C of the triad with the base 4, then an RRR dyad) and a class IV group whose coupler b is
the actuator (all its internal pairs hinges, or d a block in a slot of a), over their
strokes:

- positions against a solve written here: the triad's joints C, D, F (six coordinates) from
  the six distance equations (three leash lengths, the actuator's equal to q, and the three
  sides of the base), by Newton's method stepping along the stroke from the sketch in
  0.25 mm steps, each step polished from the previous position;
- every closure: the distances on every link constant, the actuator's hinges q apart, the
  slider's coordinate s = q;
- analogs against central differences in q;
- the end of the drawn mode below the stroke against a dense scan of the four-bar that the
  base and the two rockers make (the mode ends where q = |C − A| is extremal along it), and
  the existence interval of :func:`check_existence` there;
- the force analysis against the global solve of all links (``test_forces_global``);
- the refusal of an actuator that is a ternary link of its group (the triad's base, a of a
  class IV group), or a class IV coupler with a prismatic pair at an end, naming the group
  and the members.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from test_forces_global import _global, agrees
from test_forces_higher import _loads

import assur
from assur.forces import kinetostatics
from assur.kinematics import jets as J
from assur.kinematics.analysis import analyse, sketch_input, values
from assur.kinematics.build import load_with_forces
from assur.kinematics.higher.kind import HigherGroupSolution
from synthesis.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "input_tables" / "actuator_triad.yaml"
SKETCH = {"A": 0j, "B": 120 + 0j, "C": 60 + 80j, "D": 110 + 90j, "E": 200 + 30j,
          "F": 150 + 120j}

#: The class IV group of test vector V2 with its coupler b (C–D) a cylinder 2 and a rod 3.
CLASS_IV: dict[str, Any] = {
    "mechanism": {
        "name": "class IV group with an actuator coupler",
        "links": [{"id": k, "name": n} for k, n in
                  ((0, "frame"), (1, "a"), (2, "cylinder"), (3, "rod"), (4, "c"), (5, "d"))],
        "pairs": [{"id": "H", "type": "R", "links": [0, 1]},
                  {"id": "C", "type": "R", "links": [1, 2]},
                  {"id": "S", "type": "P", "links": [2, 3], "guide": 2},
                  {"id": "D", "type": "R", "links": [3, 4]},
                  {"id": "K", "type": "R", "links": [0, 4]},
                  {"id": "E", "type": "R", "links": [4, 5]},
                  {"id": "F", "type": "R", "links": [5, 1]}],
        "inputs": [{"pair": "S"}]},
    "geometry": {"H": {"point": [-12.5, -20]}, "C": {"point": [57, 66]},
                 "S": {"point": [57, 66], "direction": [58, 1]},
                 "D": {"point": [115, 67]}, "K": {"point": [140.5, 22]},
                 "E": {"point": [87, 118]}, "F": {"point": [25.5, 98.5]},
                 "input": {"stroke": [54, 76]}}}

#: The same with link 5 (d) a block in a slot of link 1 (a) at F, drawn at 40°: d turns with
#: a, so the group has a prismatic internal pair beside the actuator coupler.
BLOCK_D: dict[str, Any] = dict(CLASS_IV, mechanism=dict(CLASS_IV["mechanism"], pairs=[
    dict(p, type="P", guide=1) if p["id"] == "F" else p
    for p in CLASS_IV["mechanism"]["pairs"]]),
    geometry=dict(CLASS_IV["geometry"], F={"point": [25.5, 98.5], "direction": 40}))
CLASS_IV_TABLES = {"class IV": CLASS_IV, "class IV, block d": BLOCK_D}


def _write(tmp_path: Path, name: str, table: dict[str, Any]) -> Path:
    path = tmp_path / name
    path.write_text(yaml.safe_dump(table, allow_unicode=True, sort_keys=False),
                    encoding="utf-8")
    return path


def _stepped(q: np.ndarray) -> dict[str, np.ndarray]:
    """C, D, F of the example's triad at the lengths q (increasing, through 100 mm) by
    Newton's method on the six distance equations, stepping from the sketch."""
    s = SKETCH
    fixed = {"C": ("A", None), "D": ("B", abs(s["D"] - s["B"])),
             "F": ("E", abs(s["F"] - s["E"]))}
    sides = [("C", "D"), ("D", "F"), ("C", "F")]

    def residual(x: np.ndarray, length: float) -> np.ndarray:
        p = {"C": complex(x[0], x[1]), "D": complex(x[2], x[3]), "F": complex(x[4], x[5])}
        out = [abs(p[k] - s[a]) - (length if r is None else r) for k, (a, r) in fixed.items()]
        out += [abs(p[a] - p[b]) - abs(s[a] - s[b]) for a, b in sides]
        return np.array(out)

    def newton(x: np.ndarray, length: float) -> np.ndarray:
        for _ in range(30):
            f = residual(x, length)
            jac = np.empty((6, 6))
            for k in range(6):
                dx = np.zeros(6)
                dx[k] = 1e-7
                jac[:, k] = (residual(x + dx, length) - residual(x - dx, length)) / 2e-7
            step = np.linalg.solve(jac, f)
            x = x - step
            if np.max(np.abs(step)) < 1e-13:
                break
        return x

    start = np.array([c for k in ("C", "D", "F") for c in (s[k].real, s[k].imag)])
    out: dict[float, np.ndarray] = {}
    for direction in (1.0, -1.0):
        x, length = start, 100.0
        for target in sorted((t for t in q if (t - 100.0) * direction >= 0),
                             key=lambda t: abs(t - 100.0)):
            while abs(target - length) > 1e-12:
                length = length + direction * min(0.25, abs(target - length))
                x = newton(x, length)
            out[float(target)] = x
    rows = np.array([out[float(t)] for t in q])
    return {k: rows[:, 2 * i] + 1j * rows[:, 2 * i + 1] for i, k in enumerate(("C", "D", "F"))}


def test_triad_positions_equal_a_stepped_newton_solve_and_every_link_closes() -> None:
    model = assur.load_model(EXAMPLE)
    assert model.drive == "actuator" and model.groups[0].driven == "leash1"
    q = np.linspace(85.0, 115.0, 31)
    motion = analyse(model, q)
    assert motion.exists.all()
    expected = _stepped(q)
    j = {pid: values(z) for pid, z in motion.joints.items()}
    for name, z in expected.items():
        assert np.max(np.abs(j[name] - z)) <= 1e-9 * 250
    assert np.max(np.abs(np.abs(j["C"] - j["A"]) - q)) <= 1e-9
    for a, b in (("B", "D"), ("E", "F"), ("C", "D"), ("D", "F"), ("C", "F"), ("D", "G"),
                 ("G", "J"), ("J", "H")):
        drawn = abs(SKETCH.get(a, j[a][15]) - SKETCH.get(b, j[b][15]))
        assert np.max(np.abs(np.abs(j[a] - j[b]) - drawn)) <= 1e-9, (a, b)
    slider = motion.sliders["S"]
    assert slider.carrier == 2 and slider.slider == 3
    assert np.max(np.abs(values(slider.s) - q)) == 0.0
    # both members of the actuator turn with the leash A–C, along its axis
    for member in (2, 3):
        axis = np.exp(1j * values(motion.frames[member][1]))
        assert np.max(np.abs(axis - (j["C"] - j["A"]) / q)) <= 1e-12


def _check_analogs(model: assur.KinematicModel, q: np.ndarray, h: float = 1e-4) -> None:
    """Joints, link angles and the slider's s against central differences of step h."""
    exact = analyse(model, q, analogs=True)
    up, down = analyse(model, q + h), analyse(model, q - h)
    for pid, jet in exact.joints.items():
        z = J.as_jet(jet)
        hi, lo = values(up.joints[pid]), values(down.joints[pid])
        d1, d2 = (hi - lo) / (2 * h), (hi - 2 * z.v + lo) / (h * h)
        assert np.max(np.abs(z.d1 - d1)) <= 1e-6 * (1 + np.max(np.abs(d1))), pid
        assert np.max(np.abs(z.d2 - d2)) <= 1e-3 * (1 + np.max(np.abs(d2))), pid
    for link, (_, angle) in exact.frames.items():
        if link == model.frame:
            continue
        d1 = (values(up.frames[link][1]) - values(down.frames[link][1])) / (2 * h)
        assert np.max(np.abs(J.as_jet(angle).d1 - d1)) <= 1e-7, link
    assert np.max(np.abs(J.as_jet(exact.sliders["S"].s).d1 - 1.0)) == 0.0


def test_triad_analogs_equal_central_differences_in_the_length() -> None:
    model = assur.load_model(EXAMPLE)
    _check_analogs(model, np.linspace(86.0, 114.0, 8))


@pytest.mark.parametrize("which", list(CLASS_IV_TABLES))
def test_class_iv_coupler_positions_close_and_analogs_equal_differences(which: str,
                                                                      tmp_path: Path) -> None:
    table = CLASS_IV_TABLES[which]
    model = assur.load_model(_write(tmp_path, "civ.yaml", table))
    group = model.groups[0]
    assert group.kind == "IV" and group.driven == "b" and group.composite == (2, 3)
    assert float(sketch_input(model)) == pytest.approx(abs(57 + 66j - (115 + 67j)), abs=1e-12)
    q = np.linspace(54.0, 76.0, 12)
    motion = analyse(model, q)
    assert motion.exists.all()
    j = {pid: values(z) for pid, z in motion.joints.items()}
    g = table["geometry"]
    drawn = {k: complex(*g[k]["point"]) for k in ("H", "C", "D", "K", "E", "F")}
    assert np.max(np.abs(np.abs(j["D"] - j["C"]) - q)) <= 1e-9
    if which == "class IV":
        pairs = (("H", "C"), ("H", "F"), ("C", "F"), ("K", "D"), ("K", "E"), ("D", "E"),
                 ("F", "E"))
    else:  # F slides: d's point there (the slider's point) and a's (its base) differ
        block = motion.sliders["F"]
        j["F"], j["Fa"] = values(block.point), values(block.base)
        turn_a = (j["C"] - j["H"]) / (drawn["C"] - drawn["H"])
        turn_d = (j["F"] - j["E"]) / (drawn["F"] - drawn["E"])
        guide = turn_a * np.exp(1j * np.radians(40.0))
        assert np.max(np.abs(turn_d - turn_a)) <= 1e-9          # d turns with a
        assert np.max(np.abs((np.conj(guide) * (j["F"] - j["Fa"])).imag)) <= 1e-9
        pairs = (("H", "C"), ("H", "Fa"), ("C", "Fa"), ("K", "D"), ("K", "E"), ("D", "E"),
                 ("F", "E"))
        drawn["Fa"] = drawn["F"]
    for a, b in pairs:
        assert np.max(np.abs(np.abs(j[a] - j[b]) - abs(drawn[a] - drawn[b]))) <= 1e-9, (a, b)
    _check_analogs(model, np.linspace(55.0, 75.0, 5))


def _four_bar_end(below: float) -> float:
    """The actuator length where the drawn mode ends below the sketch: the base 4 and the
    rockers 5 (B–D) and 6 (E–F) make a four-bar; along its motion (the rocker 5 turned
    through ψ, dense grid, the drawn branch) C traces its coupler curve, and the mode ends
    where q = |C − A| stops decreasing."""
    s = SKETCH
    r5, r6, df = abs(s["D"] - s["B"]), abs(s["F"] - s["E"]), abs(s["F"] - s["D"])
    psi0 = np.angle(s["D"] - s["B"])
    sign = np.sign(((np.conj(s["E"] - s["D"])) * (s["F"] - s["D"])).imag)

    def q_at(psi: np.ndarray) -> np.ndarray:
        d = s["B"] + r5 * np.exp(1j * (psi0 + psi))
        u = s["E"] - d
        a = (df ** 2 - r6 ** 2 + np.abs(u) ** 2) / (2 * np.abs(u))
        h = np.sqrt(df ** 2 - a ** 2)
        e = u / np.abs(u)
        f = np.where(sign > 0, d + e * (a + 1j * h), d + e * (a - 1j * h))
        c = d + (s["C"] - s["D"]) * (f - d) / (s["F"] - s["D"])
        return np.abs(c - s["A"])

    grid = np.radians(np.arange(0.0, 60.0, 1e-5))
    for way in (1.0, -1.0):
        with np.errstate(invalid="ignore"):  # NaN beyond a dead point of the four-bar
            q = q_at(way * grid)
        if q[1] < q[0]:
            lowest = int(np.argmax(~(np.diff(q) < 0)))
            assert lowest > 0 and np.isfinite(q[lowest + 1]) and q[lowest] < below
            return float(q[lowest])
    raise AssertionError("q does not decrease either way")  # pragma: no cover


def test_mode_end_below_the_stroke_against_a_dense_scan_and_existence() -> None:
    model = dataclasses.replace(assur.load_model(EXAMPLE), input_range=(70.0, 115.0))
    end = _four_bar_end(85.0)
    motion = analyse(model, np.linspace(70.0, 115.0, 46))
    sol = motion.solutions[model.groups[0].label]
    assert isinstance(sol, HigherGroupSolution) and sol.follow.periodic is False
    assert np.isnan(sol.follow.ends[0]) and sol.follow.end_reasons[1] == 8
    assert sol.follow.ends[1] == pytest.approx(end, abs=1e-6)
    q = motion.q
    assert np.array_equal(sol.exists, q > end)
    assert np.all(sol.reason[q < end] == 8) and np.all(sol.margin[q < end] < 0)
    report = assur.check_existence(model, motion.q, motion=motion)
    (interval,) = report.groups[0].intervals
    assert interval.start == 70.0 and interval.reason == 8
    assert interval.end == pytest.approx(end, abs=1e-6)
    notes = [note.text("en") for note in sol.follow.notes()]
    assert f"q = {end:.4f} mm" in notes[-1] and "merges" in notes[-1]


@pytest.mark.parametrize("which", ["triad", "triad table loads", *CLASS_IV_TABLES])
def test_actuator_force_equals_the_global_solve(which: str, tmp_path: Path) -> None:
    path = EXAMPLE if which.startswith("triad") else \
        _write(tmp_path, "civ.yaml", CLASS_IV_TABLES[which])
    model, table = load_with_forces(path)
    data = table if which == "triad table loads" and table is not None else \
        _loads(model, np.random.default_rng(3))
    low, high = model.input_range
    q = np.linspace(low, high, 9)
    motion = analyse(model, q, analogs=True)
    result = kinetostatics(motion, data, 20.0)
    assert result.drive == "driving_force"
    with np.errstate(invalid="ignore"):
        expected = _global(motion, data, 20.0, float(sketch_input(model)))
    solved = result.reason == 0
    assert solved.all()
    agrees(motion, result, expected, solved, 1e-9)
    for residual in result.residuals.values():
        assert np.max(residual.force) <= 1e-9 and np.max(residual.moment) <= 1e-9


def _refused(tmp_path: Path, table: dict[str, Any], capsys: pytest.CaptureFixture[str],
             lang: str) -> str:
    path = _write(tmp_path, "refused.yaml", table)
    assert main(["analyze", str(path), "--lang", lang]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return err


def test_an_actuator_that_is_a_ternary_link_is_refused(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]
                                                        ) -> None:
    # the triad's base is the cylinder 2 (hinges C, D) with its rod 3 (hinge F)
    base = {"mechanism": {
        "name": "actuator as the base",
        "pairs": [{"id": "S", "type": "P", "links": [2, 3], "guide": 2},
                  {"id": "C", "type": "R", "links": [2, 4]},
                  {"id": "D", "type": "R", "links": [2, 5]},
                  {"id": "F", "type": "R", "links": [3, 6]},
                  {"id": "A", "type": "R", "links": [4, 0]},
                  {"id": "B", "type": "R", "links": [5, 0]},
                  {"id": "E", "type": "R", "links": [6, 0]}],
        "inputs": [{"pair": "S"}]},
        "geometry": {"C": {"point": [60, 80]}, "D": {"point": [110, 90]},
                     "S": {"point": [60, 80], "direction": [90, 40]},
                     "F": {"point": [150, 120]}, "A": {"point": [0, 0]},
                     "B": {"point": [120, 0]}, "E": {"point": [200, 30]},
                     "input": {"stroke": [90, 110]}}}
    err = _refused(tmp_path, base, capsys, "en")
    assert "III(2,3,4,5,6)" in err and "links 2, 3" in err and "three pairs" in err
    err = _refused(tmp_path, base, capsys, "ru")
    assert "звенья 2, 3" in err and "тремя парами" in err
    # the class IV group's link a is the cylinder 1 (hinges H, C) with its rod 6 (hinge F)
    table = dict(CLASS_IV, mechanism=dict(CLASS_IV["mechanism"], pairs=[
        {"id": "H", "type": "R", "links": [0, 1]},
        {"id": "S", "type": "P", "links": [1, 6], "guide": 1},
        {"id": "C", "type": "R", "links": [1, 2]},
        {"id": "D", "type": "R", "links": [2, 4]},
        {"id": "K", "type": "R", "links": [0, 4]},
        {"id": "E", "type": "R", "links": [4, 5]},
        {"id": "F", "type": "R", "links": [5, 6]}], links=None))
    del table["mechanism"]["links"]
    table["geometry"] = dict(CLASS_IV["geometry"], S={"point": [-12.5, -20],
                                                      "direction": [38, 118.5]},
                             input={"stroke": [100, 130]})
    err = _refused(tmp_path, table, capsys, "en")
    assert "IV(" in err and "links 1, 6" in err and "three pairs" in err
    # the coupler b is the actuator, and its end C slides on link a: it has no length
    pairs = [dict(p, type="P", guide=1) if p["id"] == "C" else p
             for p in CLASS_IV["mechanism"]["pairs"]]
    table = dict(CLASS_IV, mechanism=dict(CLASS_IV["mechanism"], pairs=pairs))
    table["geometry"] = dict(CLASS_IV["geometry"], C={"point": [57, 66], "direction": 40})
    err = _refused(tmp_path, table, capsys, "en")
    assert "IV(" in err and "links 2, 3" in err and "prismatic pair at an end (C)" in err
    err = _refused(tmp_path, table, capsys, "ru")
    assert "звенья 2, 3" in err and "поступательной парой на конце (C)" in err


def test_example_reports_the_stroke_in_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["analyze", str(EXAMPLE), "--json", "--points", "7"]) == 0
    group = json.loads(capsys.readouterr().out)["groups"][0]
    assert group["mode"]["count_at_sketch"] == 2
    assert group["mode"]["ends_mm"] == [None, None]     # the mode ends below the stroke
    assert "ends_deg" not in group["mode"]


def test_designs_with_their_own_sketch_length_in_one_call_equal_each_alone() -> None:
    """Moving C changes the actuator's drawn length q₀, so each design starts its passes
    from its own length; together they equal each design solved alone."""
    model = assur.load_model(EXAMPLE)
    column = model.groups[0].column("x_C")
    xs = np.array([58.0, 60.0, 63.0])
    q = np.linspace(85.0, 115.0, 7)
    together = analyse(model.with_params({column: xs[:, None]}), q, analogs=True)
    for k, x in enumerate(xs):
        alone = analyse(model.with_params({column: x}), q, analogs=True)
        for pid, jet in alone.joints.items():
            z, both = J.as_jet(jet), J.as_jet(together.joints[pid])
            assert np.max(np.abs(both.v[k] - z.v)) <= 1e-12 * 250, pid
            assert np.max(np.abs(both.d1[k] - z.d1)) <= 1e-10, pid
