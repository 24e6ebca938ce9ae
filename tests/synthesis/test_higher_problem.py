"""A synthesis problem on a chain table with a triad, through ``assur synthesize``.

The shipped problem ``class2_six_bar_triad.yaml`` asks for the stroke of the block of the
six-bar ``six_bar_triad.yaml``. Its targets and every result are checked against a solver
written here: Newton continuation in 2° crank steps of the six pose equations of the
mechanism's joints C, D, F (five fixed distances and the guide line), with a
finite-difference Jacobian, from the drawn pose. It shares nothing with the program's triad
solver (no elimination, no modes, no analogs).

The default run searches with a small budget and checks that what the command reports and
writes is the design it found (its deviations, re-solved here from the result file's
sketch); ``ASSUR_HIGHER_FULL=1`` runs the problem's own search and checks that it reaches
the required accuracy.
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

import assur
from assur.kinematics.analysis import analyse, values
from synthesis import problem_from_dict
from synthesis.cli import main
from synthesis.cli.commands import synthesize
from synthesis.evaluate import Evaluator
from synthesis.problem_chain import group_key

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "input_tables" / "problems" / "class2_six_bar_triad.yaml"
FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
#: The design whose stroke the problem's targets are (the other points as drawn).
TRUE = {"D": 106 + 14j, "E": 88 + 24j}


def _points(geometry: dict[str, Any]) -> dict[str, complex]:
    return {key: complex(*entry["point"]) for key, entry in geometry.items()
            if isinstance(entry, dict) and "point" in entry}


def stroke(points: dict[str, complex], phi_deg: np.ndarray, step: float = 2.0) -> np.ndarray:
    """S(φ) of the block (F along the horizontal guide from φ = 0) by Newton continuation."""
    o, b0, c0, d0, e0, f0 = (points[k] for k in "OBCDEF")
    lengths = np.array([abs(c0 - b0), abs(d0 - e0), abs(c0 - d0), abs(c0 - f0), abs(d0 - f0)])

    def residual(z: np.ndarray, b: complex) -> np.ndarray:
        c, d, f = z[0] + 1j * z[1], z[2] + 1j * z[3], z[4] + 1j * z[5]
        return np.array([*np.abs([c - b, d - e0, c - d, c - f, d - f]) - lengths,
                         f.imag - f0.imag])

    z = np.array([c0.real, c0.imag, d0.real, d0.imag, f0.real, f0.imag])
    out: list[float] = []
    phi = 0.0
    for target in phi_deg:
        while phi < target - 1e-12 or not out and phi == 0.0 and target == 0.0:
            h = min(step, target - phi)
            phi += h
            b = o + (b0 - o) * np.exp(1j * np.radians(phi))
            for _ in range(30):
                jac = np.stack([(residual(z + e, b) - residual(z - e, b)) / 2e-7
                                for e in 1e-7 * np.eye(6)], axis=1)
                dz = np.linalg.solve(jac, -residual(z, b))
                z = z + dz
                if np.abs(dz).max() < 1e-12:
                    break
            if h == 0.0:
                break
        out.append(z[4] - f0.real)
    return np.array(out)


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, dict[str, Any]]:
    parser = argparse.ArgumentParser()
    synthesize.add_args(parser)
    code = synthesize.run(parser.parse_args(argv))
    return code, json.loads(capsys.readouterr().out)


def test_the_targets_are_the_stroke_of_the_stated_design() -> None:
    problem = yaml.safe_load(PROBLEM.read_text(encoding="utf-8"))
    chain = yaml.safe_load((PROBLEM.parent / problem["mechanism"]).read_text(encoding="utf-8"))
    points = {**_points(chain["geometry"]), **TRUE}
    rows = problem["control_points"]
    solved = stroke(points, np.array([row["phi"] for row in rows]))
    assert np.abs(solved - [row["S"] for row in rows]).max() < 1e-6


def _check_result(data: dict[str, Any], result: Path) -> np.ndarray:
    """The result file's sketch is the reported design, and its stroke, re-solved here, has
    the reported deviations; returns the deviations."""
    table = yaml.safe_load(result.read_text(encoding="utf-8"))
    points = _points(table["geometry"])
    design = data["design"]
    for pair in "DE":
        assert abs(points[pair] - complex(design[f"III(2,3,4,5).x_{pair}"],
                                          design[f"III(2,3,4,5).y_{pair}"])) < 1e-8
    rows = data["control_points"]
    solved = stroke(points, np.array([row["phi"] for row in rows]))
    deviation: np.ndarray = solved - [row["target"] for row in rows]
    assert np.abs(deviation - [row["deviation"] for row in rows]).max() < 1e-6
    assert np.abs(deviation).max() == pytest.approx(data["Q"], abs=1e-6)
    return deviation


def test_a_short_search_writes_the_design_it_reports(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]
                                                      ) -> None:
    out = tmp_path / "result.yaml"
    code, data = _run([str(PROBLEM), "--out", str(out), "--json", "--quiet", "--budget", "4",
                       "--shrink", "1", "--restarts", "0", "--no-refine"], capsys)
    assert code == 0 and data["P1"] == 0 and data["P2"] == 0
    initial = yaml.safe_load((PROBLEM.parent / "../six_bar_triad.yaml").read_text())
    start = stroke(_points(initial["geometry"]), np.array([r["phi"] for r in
                                                           data["control_points"]]))
    worst = np.abs(start - [row["target"] for row in data["control_points"]]).max()
    assert np.abs(_check_result(data, out)).max() < 0.5 * worst


@pytest.mark.skipif(not FULL, reason="the problem's own search (ASSUR_HIGHER_FULL=1)")
def test_the_problem_is_solved_to_its_accuracy(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "result.yaml"
    code, data = _run([str(PROBLEM), "--out", str(out), "--json", "--quiet"], capsys)
    assert code == 0 and data["feasible"]
    assert np.abs(_check_result(data, out)).max() <= data["accuracy"]


def _problems(tmp_path: Path, edit: dict[str, Any], capsys: pytest.CaptureFixture[str]
              ) -> tuple[int, str]:
    data = yaml.safe_load(PROBLEM.read_text(encoding="utf-8"))
    data["mechanism"] = str(PROBLEM.parent / data["mechanism"])
    data.update(edit)
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    code = main(["synthesize", str(path), "--quiet"])
    captured = capsys.readouterr()
    return code, captured.out + captured.err


def test_bad_cells_are_reported_together(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    code, text = _problems(tmp_path, {
        "general": {"control_points": 12, "direction": -1, "groups": 3, "task_class": 2},
        "parameters": [{"links": [2, 3, 4, 5], "x_Q": [1, 0, 2], "y_D": "A",
                        "x_E": [81, 90, 75]},
                       {"links": [2, 3], "l_i": [1, 0, 2]}]}, capsys)
    assert code == 2
    assert "Traceback" not in text
    for expected in (
            "bad.yaml",
            ("parameters[0] 'x_Q': the group III(2,3,4,5) has no column 'x_Q'; the columns "
             "its sketch defines are beta_G, delta, x_C, x_D"),
            ("parameters[0] 'y_D': expected a number or [initial, lower, upper] (mm, "
             "degrees); found 'A' (a text)"),
            "parameters[0] 'x_E': the lower bound must not exceed the upper bound",
            ("parameters[1] 'links': no group of the mechanism has links [2, 3]; the groups "
             "are [1], [2, 3, 4, 5]"),
            "general 'groups': the mechanism has 2 groups (the input-link group L0 included); found 3",
            "general 'direction': the sketch turns the crank with s = 1"):
        assert expected in text, (expected, text)


def test_an_actuator_inside_a_triad_is_refused(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    """A triad follows its actuator's length only (``docs/higher_groups.md``): it cannot
    run over a cycle of a law, so the problem is refused with the reason."""
    chain = str(PROBLEM.parent.parent / "actuator_triad.yaml")
    code, text = _problems(tmp_path, {"mechanism": chain, "parameters": []}, capsys)
    assert code == 2 and "Traceback" not in text
    assert (f"mechanism: the actuator of the mechanism of {chain} is a bar of the group "
            "III(2,3,4,5,6) (a triad or a class IV group), which follows its length only"
            ) in text, text


@pytest.mark.parametrize(("table", "ends", "output"), [
    ("hydraulic_boom.yaml", ("B", "C"), 1), ("hydraulic_boom_forces.yaml", ("B", "C"), 1)])
def test_a_cylinder_runs_its_varied_stroke_over_the_cycle(table: str, ends: tuple[str, str],
                                                          output: int) -> None:
    """A mechanism driven by a cylinder that is a dyad's bar is synthesised over the cycle
    t of its harmonic law: its stroke limits are the columns ``s_min``, ``s_max`` of the
    group that holds it, and each design's cylinder — the distance of its two hinges — is
    s_min at t = 0, their mean at 90°, s_max at 180°."""
    model = assur.load_model(PROBLEM.parent.parent / table)
    label = next(g.label for g in model.groups if g.driven is not None)
    lo, hi = model.input_range
    data = {"general": {"control_points": 1, "groups": len(model.groups), "task_class": 1},
            "mechanism": str(PROBLEM.parent.parent / table), "output": {"link": output},
            "parameters": [{"links": list(group_key(model.group(label))),
                            "s_min": [lo, lo - 10, lo + 5], "s_max": [hi, hi - 5, hi + 10]}],
            "control_points": [{"K": 0, "phi": 90, "psi": 0}]}
    problem = problem_from_dict(data, "cylinder.yaml")
    assert problem.model.drive == "laws"
    assert problem.names == (f"{label}.s_max", f"{label}.s_min")
    x = np.array([[hi, lo], [hi + 6, lo - 4]])
    motion = analyse(Evaluator(problem).model(x), np.radians([0.0, 90.0, 180.0]))
    length = np.abs(values(motion.joints[ends[1]]) - values(motion.joints[ends[0]]))
    hand = np.array([[lo, (lo + hi) / 2, hi], [lo - 4, (lo + hi + 2) / 2, hi + 6]])
    np.testing.assert_allclose(length, hand, rtol=1e-12)


def test_a_chain_without_its_sketch_is_named(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    chain = yaml.safe_load((PROBLEM.parent / "../six_bar_triad.yaml").read_text())
    code, text = _problems(tmp_path, {"mechanism": chain["mechanism"]}, capsys)
    assert code == 2 and "Traceback" not in text
    assert "geometry: a chain table needs its 'geometry' sketch" in text, text


def test_an_inline_chain_reads_as_the_named_file(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    from synthesis import load_problem, problem_from_dict

    chain = yaml.safe_load((PROBLEM.parent / "../six_bar_triad.yaml").read_text())
    data = yaml.safe_load(PROBLEM.read_text(encoding="utf-8"))
    data.update(chain)
    inline = problem_from_dict(data, "inline.yaml")
    named = load_problem(PROBLEM)
    assert inline.names == named.names
    assert inline.model.params == named.model.params


def test_a_fixed_cell_changes_the_sketch_it_names() -> None:
    """``x_C: 80`` (a plain number) moves the drawn hinge C of the initial design: the
    evaluator's stroke of the initial design is that of the sketch with C moved."""
    from synthesis import problem_from_dict
    from synthesis.evaluate import Evaluator

    data = yaml.safe_load(PROBLEM.read_text(encoding="utf-8"))
    data["parameters"][0]["x_C"] = 80
    problem = problem_from_dict(data, "fixed.yaml", base=PROBLEM.parent)
    analysis = Evaluator(problem).analyse(problem.initial[None, :])
    chain = yaml.safe_load((PROBLEM.parent / data["mechanism"]).read_text(encoding="utf-8"))
    points = {**_points(chain["geometry"]), "C": 80 + 30.5j}
    phi = np.array([row["phi"] for row in data["control_points"]])
    assert np.abs(analysis.output_control[0] - stroke(points, phi)).max() < 1e-8


@pytest.mark.parametrize(("budget", "loads"), [(4, False), (5, True)])
def test_a_search_large_enough_loads_the_compiled_corrector_first(
        budget: int, loads: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """A search whose passive pass analyses at least ``KERNEL_POSITIONS`` positions loads the
    kernels before its first batch (here the threshold set to 1,000 positions: 2**5 trials ×
    (36 grid + 12 control angles) = 1,536 reach it, 2**4 × 48 = 768 do not); a four-bar
    problem never does, whatever its budget."""
    import synthesis
    from assur.kinematics.higher import compiled, continuation

    loaded: list[int] = []
    monkeypatch.setattr(compiled, "load", lambda: loaded.append(1))
    monkeypatch.setattr(continuation, "KERNEL_POSITIONS", 1000)
    problem = synthesis.load_problem(PROBLEM)
    assert Evaluator(problem).positions.size == 36 + 12
    synthesis.synthesize(problem, budget=budget, shrink=0, restarts=0, refine=False)
    assert loaded == ([1] if loads else [])
    fourbar = synthesis.load_problem(ROOT / "input_tables" / "problems" / "class3_fourbar_path.yaml")
    assert not Evaluator(fourbar).prepare(2 ** 20)
    assert loaded == ([1] if loads else [])
