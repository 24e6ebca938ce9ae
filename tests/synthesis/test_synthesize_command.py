"""``assur synthesize`` on the shipped problems; the result file re-analysed independently."""

from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

import assur
import assur.kinematics.analysis
from assur.kinematics.analysis import analyse
from synthesis import load_problem
from synthesis.cli import main
from synthesis.cli.commands import synthesize
from synthesis.evaluate import Evaluator

PROBLEMS = sorted((Path(__file__).resolve().parents[2] / "input_tables" / "problems")
                  .glob("*.yaml"))


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    parser = argparse.ArgumentParser()
    synthesize.add_args(parser)
    code = synthesize.run(parser.parse_args(argv))
    return code, capsys.readouterr().out


def _reanalyse(problem: dict[str, Any], result: Path, design: dict[str, float]) -> float:
    """Q of the result file's mechanism, from the public kinematics alone (``design``: the
    found parameters as the report gives them, for a class-5 segment's varied angle)."""
    model = assur.load_model(result)
    if model.drive in ("actuator", "slider"):  # its stroke over the cycle t, as synthesised
        model = assur.cycle_model(model)
    general, control, output = problem["general"], problem["control_points"], problem["output"]
    task = general["task_class"]
    if task == 5:
        return _reanalyse_guidance(problem, model, design)
    if task == 3:
        phi = 2 * np.pi * np.arange(4000) / 4000
    else:
        phi = np.radians([row["phi"] for row in control])
    motion = analyse(model, np.concatenate([[0.0], phi]))
    assert motion.exists.all()
    weights = np.array([row.get("E", 1.0) for row in control])
    if task == 1 and general.get("output") == "ratio":
        # n = dψ/dφ by a fourth-order central difference of the positions (no analogs)
        h = 1e-3
        stencil = phi[:, None] + h * np.array([-2.0, -1.0, 1.0, 2.0])
        angle = assur.kinematics.analysis.unwrap(assur.kinematics.analysis.values(analyse(model, stencil.ravel()).link_angle(
            output["link"])).reshape(stencil.shape))
        n = (angle[:, 0] - 8 * angle[:, 1] + 8 * angle[:, 2] - angle[:, 3]) / (12 * h)
        lo = np.array([row["n_lo"] for row in control])
        hi = np.array([row["n_hi"] for row in control])
        return float(np.max(weights * np.maximum(0.0, np.maximum(lo - n, n - hi))))
    if task == 1:
        angle = assur.kinematics.analysis.values(motion.link_angle(output["link"]))
        psi = np.degrees(np.angle(np.exp(1j * (angle[1:] - angle[0]))))
        if "psi" in control[0]:
            dev = psi - np.array([row["psi"] for row in control])
        else:
            lo = np.array([row["psi_lo"] for row in control])
            hi = np.array([row["psi_hi"] for row in control])
            dev = np.maximum(0.0, np.maximum(lo - psi, psi - hi))
        return float(np.max(weights * np.abs(dev)))  # degrees, as the report gives Q
    if task == 2:
        pair = next(pid for pid, state in motion.sliders.items()
                    if state.slider == output["link"] and state.carrier == model.frame)
        s = assur.kinematics.analysis.values(motion.sliders[pair].s)
        return float(np.max(weights * np.abs(s[1:] - s[0] - [row["S"] for row in control])))
    targets = np.array([row["x"] + 1j * row["y"] for row in control])
    point = (assur.kinematics.analysis.values(motion.tracing[output["point"]])
             if output["point"] in motion.tracing else _tracing_point(model, motion,
                                                                       output["link"]))
    if task == 4:
        return float(np.max(weights * np.abs(point[1:] - targets)))
    # class 3: nearest grid point, then the polygon of a 400 times finer grid around it
    m = np.argmin(np.abs(point[1:][None, :] - targets[:, None]), axis=1)
    fine = phi[m][:, None] + np.linspace(-1, 1, 801)[None, :] * (phi[1] - phi[0])
    motion = analyse(model, fine.ravel())
    curve = _tracing_point(model, motion, output["link"]).reshape(fine.shape)
    seg = np.diff(curve, axis=1)
    rel = targets[:, None] - curve[:, :-1]
    t = np.clip((np.conj(seg) * rel).real / np.abs(seg) ** 2, 0, 1)
    return float(np.max(weights * np.min(np.abs(rel - t * seg), axis=1)))


def _reanalyse_guidance(problem: dict[str, Any], model: Any, design: dict[str, float]) -> float:
    """Class 5: the segment from the output link's point N, ``length`` mm long at the link's
    frame angle plus its angle on the link; Δ_K the larger gap of its two ends.  Without
    timing, the nearest pose (the least |A − A_K|² + |B − B_K|²): a grid of 4000 crank
    angles, then twice a 400 times finer one around the best."""
    control, output = problem["control_points"], problem["output"]
    angle = output.get("angle", 0.0)
    gamma = math.radians(design["output.angle"] if isinstance(angle, list) else angle)
    length = output["length"]
    a_k = np.array([row["x"] + 1j * row["y"] for row in control])
    b_k = a_k + length * np.exp(1j * np.radians([row["theta"] for row in control]))
    weights = np.array([row.get("E", 1.0) for row in control])

    def gaps(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        motion = analyse(model, phi.ravel())
        a = _tracing_point(model, motion, output["link"]).reshape(phi.shape)
        theta = assur.kinematics.analysis.values(
            motion.link_angle(output["link"])).reshape(phi.shape) + gamma
        b = a + length * np.exp(1j * theta)
        return np.abs(a - a_k[:, None]), np.abs(b - b_k[:, None])

    if "phi" in control[0]:
        gap_a, gap_b = gaps(np.radians([[row["phi"]] for row in control]))
        return float(np.max(weights * np.maximum(gap_a, gap_b)[:, 0]))
    phi = np.broadcast_to(2 * np.pi * np.arange(4000) / 4000, (len(control), 4000))
    width = 2 * np.pi / 4000
    for _ in range(3):
        gap_a, gap_b = gaps(phi)
        best = np.argmin(gap_a ** 2 + gap_b ** 2, axis=1)
        rows = np.arange(len(control))
        dev = np.maximum(gap_a, gap_b)[rows, best]
        phi = phi[rows, best][:, None] + np.linspace(-1, 1, 801)[None, :] * width
        width /= 400
    return float(np.max(weights * dev))


def _tracing_point(model: Any, motion: Any, link: Any) -> np.ndarray:
    """Attachment point N of the output link: origin + l_N·exp(i(angle + beta_N))."""
    label, _ = model.links[link]
    origin, angle = (assur.kinematics.analysis.values(v) for v in motion.frames[link])
    point: np.ndarray = origin + model.value(f"{label}.l_N") * np.exp(
        1j * (angle + model.value(f"{label}.beta_N")))
    return point


@pytest.mark.slow
@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_shipped_problem_is_solved_and_confirmed(path: Path, tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "result.yaml"
    code, text = _run([str(path), "--out", str(out), "--json", "--quiet"], capsys)
    data = json.loads(text)
    problem = yaml.safe_load(path.read_text(encoding="utf-8"))
    assert code == 0
    assert data["P1"] == 0 and data["P2"] == 0
    assert data["Q"] <= problem["general"]["accuracy"]
    confirmed = _reanalyse(problem, out, data["design"])
    # the result file rounds the dimensions to 12 significant digits
    assert confirmed == pytest.approx(data["Q"], rel=1e-3, abs=1e-8)


def test_report_in_russian_and_pictures(tmp_path: Path,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    path = next(p for p in PROBLEMS if p.stem.startswith("class3"))
    code, text = _run([str(path), "--budget", "6", "--lang", "ru", "--quiet",
                       "--plot", str(tmp_path / "pictures")], capsys)
    assert code == 0
    assert "Найденные параметры" in text and "Критерии" in text
    for name in ("output", "mechanism", "convergence"):
        assert (tmp_path / "pictures" / f"{name}.png").read_bytes()[:4] == b"\x89PNG"


def test_json_result_file_reads_back(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = next(p for p in PROBLEMS if p.stem.startswith("class4"))
    out = tmp_path / "result.json"
    code, text = _run([str(path), "--out", str(out), "--json", "--quiet"], capsys)
    problem = yaml.safe_load(path.read_text(encoding="utf-8"))
    assert code == 0
    assert _reanalyse(problem, out, json.loads(text)["design"]) == pytest.approx(json.loads(text)["Q"], rel=1e-3, abs=1e-8)


def test_feasible_trials_table(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = next(p for p in PROBLEMS if p.stem.startswith("class1_fourbar_rocker"))
    table = tmp_path / "trials.csv"
    code, text = _run([str(path), "--budget", "7", "--json", "--quiet", "--trials", str(table)],
                      capsys)
    data = json.loads(text)
    rows = list(csv.reader(table.read_text(encoding="utf-8").splitlines()))
    assert code == 0
    assert rows[0] == ["trial", "stage", "Q", "L0(1).l_1", "L1(2,3).l_i", "L1(2,3).l_j"]
    assert len(rows) - 1 == data["trials_written"] > 0
    q = [float(r[2]) for r in rows[1:]]
    assert q == sorted(q)
    # every listed design is inside the box (passive trials) and its Q is re-computed equal
    problem = load_problem(path)
    x = np.array([[float(v) for v in r[3:]] for r in rows[1:4]])
    assert np.all((x >= problem.lower) & (x <= problem.upper))
    # Q of a class-1 angle task is given in degrees; the evaluator works in radians
    np.testing.assert_allclose(np.degrees(Evaluator(problem)(x).q), q[:3], rtol=1e-12)


def test_bad_problem_exits_with_2_and_names_the_field(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("general: {control_points: two, task_class: 6}\n", encoding="utf-8")
    assert main(["synthesize", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "general 'control_points': expected a whole number; found 'two' (a text)" in err
    assert "general 'task_class': expected one of 1, 2, 3, 4, 5; found 6" in err
    assert "Traceback" not in err


def test_result_keeps_the_allowable_angles_and_analyze_judges_by_them(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The rocker problem allows 60°; its solution reaches about 54° (above the default
    45°), so a judgement against 45° would say 'exceeded'."""
    path = next(p for p in PROBLEMS if p.stem == "class1_fourbar_rocker")
    out = tmp_path / "result.yaml"
    assert _run([str(path), "--out", str(out), "--quiet"], capsys)[0] == 0
    table = yaml.safe_load(out.read_text(encoding="utf-8"))
    problem = yaml.safe_load(path.read_text(encoding="utf-8"))
    assert table["general"]["allowable"] == problem["allowable"]
    # the largest pressure angle, from the public kinematics of the result
    motion = analyse(assur.load_model(out), points=360)
    alpha = max(np.degrees(p.maximum) for p in assur.pressure_angles(motion))
    assert 45 < alpha < 60
    assert main(["analyze", str(out)]) == 0
    text = capsys.readouterr().out
    assert f"max {alpha:.2f}°" in text and "[α] = 60°, within" in text
    assert main(["analyze", str(out), "--lang", "ru"]) == 0
    assert "[α] = 60°, не превышен" in capsys.readouterr().out


def test_a_run_short_of_the_accuracy_says_what_to_try(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = next(p for p in PROBLEMS if p.stem == "class1_fourbar_rocker")
    no_refine = tmp_path / "no_refine.yaml"
    raw = yaml.safe_load(path.read_text(encoding="utf-8"))
    raw["search"]["refine"] = False
    no_refine.write_text(yaml.safe_dump(raw, allow_unicode=True), encoding="utf-8")
    code, text = _run([str(no_refine), "--budget", "5", "--restarts", "0", "--shrink", "0",
                       "--quiet", "--json"], capsys)
    data = json.loads(text)
    assert code == 0 and data["feasible"] and not data["favourable"]
    advice = data["advice"]
    assert [t["what"] for t in advice["try"]] == ["budget", "refine", "restarts"]
    assert advice["try"][0]["value"] == 7 and advice["try"][2]["value"] == 3
    # one round, no refinement: one optimum, the best design itself
    assert advice["optima"] == 1 and advice["q_min"] == advice["q_max"] == data["Q"]
    code, text = _run([str(no_refine), "--budget", "5", "--quiet", "--lang", "ru"], capsys)
    assert "'--refine'" in text and "Что попробовать:" in text
