"""``assur analyze``: the JSON output checked from the JSON alone, reports, files, bad input."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "input_tables" / "course_11_link.yaml"
TABLE = ROOT / "input_tables" / "course_11_link_table.yaml"
FAILS = ROOT / "input_tables" / "course_11_link_fails.yaml"


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(["analyze", *map(str, argv)])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def example_json() -> dict:
    """The JSON of the course example at 360 positions (computed once)."""
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main(["analyze", str(EXAMPLE), "--json", "--points", "360"]) == 0
    return json.loads(buffer.getvalue())


def _points(entry: dict) -> np.ndarray:
    x = np.array(entry["x"], dtype=float)
    y = np.array(entry["y"], dtype=float)
    return x + 1j * y


def test_every_group_assembles_over_the_whole_turn(example_json: dict) -> None:
    data = example_json
    assert len(data["input"]["values"]) == 360
    assert data["all_exist"] is True
    dyads = [g for g in data["groups"] if g["kind"] != 0]
    assert [g["kind"] for g in dyads] == [1, 4, 3, 2, 5]  # layering order of the course
    for group in dyads:
        assert all(group["existence"]["exists"]), group["label"]
        assert group["existence"]["intervals"] == []
        assert min(group["existence"]["margin"]) > 0.1


def test_lengths_are_constant_on_every_link_recomputed_from_json(example_json: dict) -> None:
    """Every pair of revolute joints on one link keeps its distance (rigid links)."""
    data = example_json
    joints = {pid: _points(j) for pid, j in data["joints"].items()}
    links_of = {pid: j["links"] for pid, j in data["joints"].items()}
    on_link: dict[str, list[str]] = {}
    for pid, links in links_of.items():
        for link in links:
            on_link.setdefault(str(link), []).append(pid)
    for name, point in data["tracing"].items():
        joints[f"trace {name}"] = _points(point)
        on_link.setdefault(str(point["link"]), []).append(f"trace {name}")
    checked = 0
    for link, pids in on_link.items():
        for a in range(len(pids)):
            for b in range(a + 1, len(pids)):
                d = np.abs(joints[pids[a]] - joints[pids[b]])
                scale = max(float(d.max()), 1.0)
                assert np.ptp(d) <= 1e-9 * scale, (link, pids[a], pids[b])
                checked += 1
    assert checked >= 10


def test_link_angles_follow_their_joints_recomputed_from_json(example_json: dict) -> None:
    """A link's angle minus the direction between two of its joints is constant."""
    data = example_json
    joints = {pid: _points(j) for pid, j in data["joints"].items()}
    for link, entry in data["links"].items():
        angle = np.radians(np.array(entry["angle_deg"]["value"], dtype=float))
        pids = [pid for pid, j in data["joints"].items() if int(link) in j["links"]]
        if len(pids) < 2:
            continue
        direction = np.angle(joints[pids[1]] - joints[pids[0]])
        diff = np.angle(np.exp(1j * (angle - direction)))
        assert np.ptp(np.unwrap(diff)) < 1e-9, link


def test_guides_check_out_recomputed_from_json(example_json: dict) -> None:
    """Each slider point lies on its guide line at a constant offset, at coordinate s; the
    guide base moves with its carrier and the guide turns with it."""
    data = example_json
    joints = {pid: _points(j) for pid, j in data["joints"].items()}
    links = data["links"]
    for pid, slider in data["sliders"].items():
        point, base = _points(slider["point"]), _points(slider["base"])
        theta = np.radians(np.array(slider["angle_deg"], dtype=float))
        u = np.exp(1j * theta)
        rel = np.conj(u) * (point - base)
        scale = max(float(np.abs(point - base).max()), 1.0)
        s = np.array(slider["s"]["value"], dtype=float)
        assert np.abs(rel.real - s).max() <= 1e-9 * scale, pid
        assert np.abs(rel.imag - slider["offset"]).max() <= 1e-9 * scale, pid
        carrier = str(slider["carrier"])
        if carrier == "0":
            assert np.ptp(base.real) + np.ptp(base.imag) <= 1e-9 * scale
            assert np.ptp(theta) <= 1e-12
            continue
        carrier_angle = np.radians(np.array(links[carrier]["angle_deg"]["value"], dtype=float))
        assert np.ptp(np.unwrap(theta - carrier_angle)) < 1e-9, pid
        for jid, j in data["joints"].items():
            if slider["carrier"] in j["links"]:
                d = np.abs(joints[jid] - base)
                assert np.ptp(d) <= 1e-9 * max(float(d.max()), 1.0), (pid, jid)


def test_crank_turns_at_the_input_angle_recomputed_from_json(example_json: dict) -> None:
    data = example_json
    phi = np.radians(np.array(data["input"]["values"], dtype=float))
    pivot, pin = _points(data["joints"]["0-1"]), _points(data["joints"]["1-2"])
    turn = np.unwrap(np.angle(pin - pivot)) - phi
    assert np.ptp(turn) < 1e-12
    assert math.isclose(float(np.abs(pin - pivot).mean()), 40.0, rel_tol=1e-3)


def test_velocity_analogs_in_json_match_differences_of_positions(example_json: dict) -> None:
    data = example_json
    phi = np.radians(np.array(data["input"]["values"], dtype=float))
    step = phi[1] - phi[0]
    for pid in ("2-3", "8-9", "8-10"):
        z = _points(data["joints"][pid])
        d1 = _points(data["joints"][pid]["d1"])
        central = (np.roll(z, -1) - np.roll(z, 1)) / (2 * step)
        scale = float(np.abs(d1).max())
        assert np.abs(central - d1).max() < 2e-3 * scale, pid


def test_failing_design_reports_group_interval_and_condition(capsys) -> None:
    code, out, _ = _run(capsys, FAILS, "--json", "--points", "360")
    assert code == 0
    data = json.loads(out)
    assert data["all_exist"] is False
    failing = [g for g in data["groups"] if g["kind"] != 0 and g["existence"]["intervals"]]
    assert [g["label"] for g in failing] == ["L3(6,7)"]
    (interval,) = failing[0]["existence"]["intervals"]
    assert interval["condition"] == "guide offset larger than hinge distance"
    assert 20.0 < interval["start"] < 23.0 and 71.0 < interval["end"] < 74.0
    later = [g for g in data["groups"] if g["label"] in ("L2(9,8)", "L5(11,10)")]
    for group in later:  # not evaluated where L3 fails
        evaluated = np.array(group["existence"]["evaluated"])
        assert not evaluated[np.array(failing[0]["existence"]["first_failing"])].any()


def test_text_summary_in_both_languages(capsys) -> None:
    code, out, _ = _run(capsys, FAILS, "--points", "120")
    assert code == 0
    assert "L3 RPR (6, 7)" in out and "CANNOT BE ASSEMBLED" in out
    assert "guide offset larger than hinge distance" in out
    code, out, _ = _run(capsys, FAILS, "--points", "120", "--lang", "ru")
    assert code == 0
    assert "НЕ СОБИРАЕТСЯ" in out and "смещение направляющей" in out


def test_identification_table_form_gives_the_same_summary_ranges(capsys) -> None:
    code, out_a, _ = _run(capsys, EXAMPLE, "--json", "--points", "36")
    code_b, out_b, _ = _run(capsys, TABLE, "--json", "--points", "36")
    assert code == code_b == 0
    a, b = json.loads(out_a), json.loads(out_b)
    for pid in a["joints"]:
        za, zb = _points(a["joints"][pid]), _points(b["joints"][pid])
        assert np.abs(za - zb).max() < 0.02, pid  # the sketch is rounded to 0.01 mm


def test_files_are_written(tmp_path: Path, capsys) -> None:
    csv_file, png, gif = tmp_path / "a.csv", tmp_path / "a.png", tmp_path / "a.gif"
    code, _, _ = _run(capsys, EXAMPLE, "--points", "24", "--csv", csv_file, "--plot", png,
                        "--at", "90", "--animate", gif, "--frames", "3", "--omega", "10")
    assert code == 0
    lines = csv_file.read_text().splitlines()
    assert len(lines) == 25
    header = lines[0].split(",")
    assert header[0] == "phi_deg" and "joint_2-3_x_vel" in header
    row = dict(zip(header, lines[7].split(",")))
    assert math.isclose(float(row["phi_deg"]), 90.0)
    # velocity = ω · analog
    assert math.isclose(float(row["joint_2-3_x_vel"]), 10 * float(row["joint_2-3_x_d1"]),
                        rel_tol=1e-12)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert gif.read_bytes()[:6] == b"GIF89a"


def test_bad_sketch_is_reported_with_every_problem(tmp_path: Path, capsys) -> None:
    text = EXAMPLE.read_text().replace('"2-3":   {point: [149.53, 100.0]}',
                                       '"2-3":   {pont: [149.53, 100.0]}')
    text = text.replace("direction: 150}", "direction: east}")
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    code, _, err = _run(capsys, bad)
    assert code == 2
    assert "Traceback" not in err
    assert "geometry '2-3'" in err and "did you mean 'point'" in err
    assert "geometry '10-11' 'direction'" in err and "'east'" in err
