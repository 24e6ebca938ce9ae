"""Inputs other than one crank: a slider on a frame guide, a cylinder, several inputs with laws.

Three shipped mechanisms (and a crank with a cylinder), each checked against what the test
computes another way:

- positions against closed forms written here (circle intersections on the assembly branch
  of the sketch), to 1e-9 mm; the closed forms carry their derivatives (evaluated on jets,
  then checked against central differences of their own values), and the analysis's analogs
  agree with them;
- the driving efforts against one global Newton–Euler solve of all links at once, written
  here with the closed-form kinematics: three d'Alembert equations per moving link in every
  pair's reaction components and one unknown effort per input (a torque on a crank, a force
  along a slider's guide, a force along a cylinder's axis), to 1e-9 relative;
- the power balance, Σ effort·(its coordinate's rate) + Σ power of every load = 0, computed
  here from the test's kinematics and the analysis's efforts, to 1e-9 relative.

Bad input laws are refused with exit 2 naming the field.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

import assur
from assur.forces import ForceData, kinetostatics
from assur.kinematics import jets as J
from assur.kinematics.analysis import analyse
from assur.kinematics.build import load_with_forces
from assur.kinematics.jets import Jet
from assur.kinematics.reasons import Reason
from synthesis.cli import main

ROOT = Path(__file__).resolve().parents[2]
TABLES = ROOT / "input_tables"
MM = 1e-3


def _meet(p: Any, rp: float, q: Any, rq: float, sign: float) -> Any:
    """The point at distance rp from p and rq from q, on the side ``sign`` of p→q."""
    d = q - p
    dd = J.abs(d)
    a = (rp * rp - rq * rq + dd * dd) / (2.0 * dd)
    h = J.sqrt(rp * rp - a * a)
    return p + d / dd * (a + 1j * sign * h)


def _side(p: complex, q: complex, x: complex) -> float:
    return 1.0 if ((q - p).conjugate() * (x - p)).imag > 0 else -1.0


@dataclass
class Case:
    """A mechanism's closed form: the poses (a point fixed on each moving link and its angle)
    and the joints as functions of the input coordinates, the input laws of the cycle
    parameter, the sketched coordinates, and the drives in the order of the inputs."""

    table: str
    q: np.ndarray                                     # the analysed positions
    laws: Callable[[Any], list[Any]]                  # position → each input's coordinate
    sketched: list[float]                             # the coordinates at the sketch
    poses: Callable[[list[Any]], dict[Any, tuple[Any, Any]]]
    joints: Callable[[list[Any]], dict[str, Any]]
    drives: list[tuple[str, Any]]                     # ("torque", link) | ("slide", pair) | ("cylinder", pair)
    pairs: Callable[[list[Any]], dict[str, tuple[str, tuple[Any, Any], Any, Any]]]
    omega: float


def _sketch(name: str) -> dict[str, complex]:
    data = yaml.safe_load((TABLES / name).read_text(encoding="utf-8"))
    return {key: complex(*value["point"]) for key, value in data["geometry"].items()
            if isinstance(value, dict) and "point" in value}


def _slider_crank() -> Case:
    s = _sketch("slider_driven_slider_crank.yaml")
    a, b0, c0 = s["A"], s["B"], s["C"]
    r, rod = abs(b0 - a), abs(c0 - b0)
    sign = _side(a, c0, b0)

    def joints(x: list[Any]) -> dict[str, Any]:
        c = c0 + x[0]                                 # the guide is the x-axis
        return {"A": a + 0.0 * x[0], "B": _meet(a, r, c, rod, sign), "C": c}

    def poses(x: list[Any]) -> dict[Any, tuple[Any, Any]]:
        p = joints(x)
        return {1: (p["A"], J.arg(p["B"] - p["A"])), 2: (p["B"], J.arg(p["C"] - p["B"])),
                3: (p["C"], 0.0 * x[0])}

    def pairs(x: list[Any]) -> dict[str, tuple[str, tuple[Any, Any], Any, Any]]:
        p = joints(x)
        return {"A": ("R", (0, 1), p["A"], None), "B": ("R", (1, 2), p["B"], None),
                "C": ("R", (2, 3), p["C"], None), "D": ("P", (3, 0), p["C"], 1j + 0.0 * x[0])}

    return Case("slider_driven_slider_crank.yaml", np.linspace(-40.0, 20.0, 25),
                lambda q: [q], [0.0], poses, joints, [("slide", "D")], pairs, 80.0)


def _boom() -> Case:
    s = _sketch("hydraulic_boom_forces.yaml")
    a, b, c0 = s["A"], s["B"], s["C"]
    arm = abs(c0 - a)
    sign = _side(b, a, c0)

    def joints(x: list[Any]) -> dict[str, Any]:
        return {"A": a + 0.0 * x[0], "B": b + 0.0 * x[0], "C": _meet(b, x[0], a, arm, sign)}

    def poses(x: list[Any]) -> dict[Any, tuple[Any, Any]]:
        p = joints(x)
        axis = J.arg(p["C"] - p["B"])
        return {1: (p["A"], J.arg(p["C"] - p["A"])), 2: (p["B"], axis), 3: (p["C"], axis)}

    def pairs(x: list[Any]) -> dict[str, tuple[str, tuple[Any, Any], Any, Any]]:
        p = joints(x)
        u = (p["C"] - p["B"]) / J.abs(p["C"] - p["B"])
        return {"A": ("R", (0, 1), p["A"], None), "B": ("R", (0, 2), p["B"], None),
                "Pd": ("P", (2, 3), p["C"], 1j * u), "C": ("R", (3, 1), p["C"], None)}

    return Case("hydraulic_boom_forces.yaml", np.linspace(95.0, 135.0, 21), lambda q: [q],
                [abs(c0 - b)], poses, joints, [("cylinder", "Pd")], pairs, 40.0)


def _five_bar() -> Case:
    s = _sketch("five_bar_two_cranks.yaml")
    a, b0, c0, d0, e = s["A"], s["B"], s["C"], s["D"], s["E"]
    r1, r4, l2, l3 = abs(b0 - a), abs(d0 - e), abs(c0 - b0), abs(c0 - d0)
    sign = _side(b0, d0, c0)

    def joints(x: list[Any]) -> dict[str, Any]:
        b = a + (b0 - a) * J.expi(x[0])
        d = e + (d0 - e) * J.expi(x[1])
        return {"A": a + 0.0 * x[0], "B": b, "C": _meet(b, l2, d, l3, sign), "D": d,
                "E": e + 0.0 * x[0]}

    def poses(x: list[Any]) -> dict[Any, tuple[Any, Any]]:
        p = joints(x)
        return {1: (p["A"], J.arg(p["B"] - p["A"])), 2: (p["B"], J.arg(p["C"] - p["B"])),
                3: (p["D"], J.arg(p["C"] - p["D"])), 4: (p["E"], J.arg(p["D"] - p["E"]))}

    def pairs(x: list[Any]) -> dict[str, tuple[str, tuple[Any, Any], Any, Any]]:
        p = joints(x)
        return {k: ("R", links, p[k], None) for k, links in
                (("A", (0, 1)), ("B", (1, 2)), ("C", (2, 3)), ("D", (3, 4)), ("E", (4, 0)))}

    assert math.isclose(r1, 25) and math.isclose(r4, 25)
    return Case("five_bar_two_cranks.yaml", np.linspace(0, 2 * np.pi, 36, endpoint=False),
                lambda t: [t, math.pi / 2 + 2 * t], [0.0, 0.0], poses, joints,
                [("torque", 1), ("torque", 4)], pairs, 6.0)


def _crank_and_cylinder() -> Case:
    s = _sketch("crank_and_cylinder.yaml")
    a, b0, c0, e = s["A"], s["B"], s["C"], s["E"]
    coupler = abs(c0 - b0)
    sign = _side(b0, e, c0)

    def joints(x: list[Any]) -> dict[str, Any]:
        b = a + (b0 - a) * J.expi(x[0])
        return {"A": a + 0.0 * x[0], "B": b, "C": _meet(b, coupler, e, x[1], sign),
                "E": e + 0.0 * x[0]}

    def poses(x: list[Any]) -> dict[Any, tuple[Any, Any]]:
        p = joints(x)
        axis = J.arg(p["C"] - p["E"])
        return {1: (p["A"], J.arg(p["B"] - p["A"])), 2: (p["B"], J.arg(p["C"] - p["B"])),
                3: (p["E"], axis), 4: (p["C"], axis)}

    def pairs(x: list[Any]) -> dict[str, tuple[str, tuple[Any, Any], Any, Any]]:
        p = joints(x)
        u = (p["C"] - p["E"]) / J.abs(p["C"] - p["E"])
        return {"A": ("R", (0, 1), p["A"], None), "B": ("R", (1, 2), p["B"], None),
                "C": ("R", (2, 4), p["C"], None), "Pd": ("P", (3, 4), p["C"], 1j * u),
                "E": ("R", (3, 0), p["E"], None)}

    def laws(t: Any) -> list[Any]:                   # stroke [95, 125], one double stroke
        return [t, 95.0 + 30.0 * (1.0 - J.real(J.expi(t))) / 2.0]

    return Case("crank_and_cylinder.yaml", np.linspace(0, 2 * np.pi, 30, endpoint=False),
                laws, [0.0, abs(c0 - e)], poses, joints, [("torque", 1), ("cylinder", "Pd")],
                pairs, 3.0)


def _press() -> Case:
    s = _sketch("cylinder_press.yaml")
    a, b, c0, d0, e0 = s["A"], s["B"], s["C"], s["D"], s["E"]
    arm, rod = abs(c0 - a), abs(e0 - d0)
    sign = _side(b, a, c0)
    theta0 = cmath.phase(c0 - a)

    def joints(x: list[Any]) -> dict[str, Any]:
        c = _meet(b, x[0], a, arm, sign)
        d = a + (d0 - a) * J.expi(J.arg(c - a) - theta0)
        dx = e0.real - J.real(d)                      # the ram's guide: the line x = 140
        e = e0.real + 1j * (J.imag(d) - J.sqrt(rod * rod - dx * dx))   # below D, as drawn
        return {"A": a + 0.0 * x[0], "B": b + 0.0 * x[0], "C": c, "D": d, "E": e}

    def poses(x: list[Any]) -> dict[Any, tuple[Any, Any]]:
        p = joints(x)
        axis = J.arg(p["C"] - p["B"])
        return {1: (p["A"], J.arg(p["C"] - p["A"])), 2: (p["B"], axis), 3: (p["C"], axis),
                4: (p["D"], J.arg(p["E"] - p["D"])), 5: (p["E"], 0.0 * x[0])}

    def pairs(x: list[Any]) -> dict[str, tuple[str, tuple[Any, Any], Any, Any]]:
        p = joints(x)
        u = (p["C"] - p["B"]) / J.abs(p["C"] - p["B"])
        return {"A": ("R", (0, 1), p["A"], None), "B": ("R", (0, 2), p["B"], None),
                "Pd": ("P", (2, 3), p["C"], 1j * u), "C": ("R", (3, 1), p["C"], None),
                "D": ("R", (1, 4), p["D"], None), "E": ("R", (4, 5), p["E"], None),
                "F": ("P", (5, 0), p["E"], 1.0 + 0.0 * x[0])}

    assert e0.imag < d0.imag
    return Case("cylinder_press.yaml", np.linspace(150.0, 190.0, 21), lambda q: [q],
                [abs(c0 - b)], poses, joints, [("cylinder", "Pd")], pairs, 30.0)


CASES = {"slider": _slider_crank, "boom": _boom, "five_bar": _five_bar,
         "crank_and_cylinder": _crank_and_cylinder, "press": _press}


def _coordinates(case: Case, q: np.ndarray) -> list[Any]:
    return [x if isinstance(x, Jet) else Jet(x + 0.0 * q) for x in case.laws(Jet(q, 1.0, 0.0))]


@pytest.mark.parametrize("name", list(CASES))
def test_positions_and_analogs_follow_the_closed_forms(name: str) -> None:
    case = CASES[name]()
    model = assur.load_model(TABLES / case.table)
    motion = analyse(model, case.q, analogs=True)
    assert np.all(motion.exists)
    want = case.joints(_coordinates(case, case.q))
    for pid, point in want.items():
        got = J.as_jet(motion.joints[pid])
        assert np.max(np.abs(got.v - point.v)) <= 1e-9, pid
        scale = 1.0 + np.max(np.abs(point.d1)) + np.max(np.abs(point.d2))
        assert np.max(np.abs(got.d1 - point.d1)) <= 1e-9 * scale, pid
        assert np.max(np.abs(got.d2 - point.d2)) <= 1e-9 * scale, pid
        # the closed form's own derivatives against central differences of its values
        h = 1e-4
        ahead = case.joints(_coordinates(case, case.q + h))[pid].v
        behind = case.joints(_coordinates(case, case.q - h))[pid].v
        assert np.max(np.abs((ahead - behind) / (2 * h) - point.d1)) <= 1e-6 * scale, pid
        second = (ahead - 2 * point.v + behind) / (h * h)
        assert np.max(np.abs(second - point.d2)) <= 1e-4 * scale, pid


def _global(case: Case, data: ForceData, q: np.ndarray
            ) -> tuple[np.ndarray, list[Any], list[np.ndarray]]:
    """Every pair's reaction and one effort per input from one linear system per position;
    returns the efforts (positions × inputs), the inputs' coordinates (jets) and the power of
    every known load per unit speed of the position."""
    x = _coordinates(case, q)
    poses = case.poses(x)
    sketch = case.poses([Jet(np.array([v])) for v in case.sketched])
    pairs = case.pairs(x)
    links = sorted(poses)
    row = {link: 3 * k for k, link in enumerate(links)}
    column = {pid: 2 * k for k, pid in enumerate(pairs)}
    size = 3 * len(links)
    first_drive = 2 * len(pairs)
    assert first_drive + len(case.drives) == size
    n = q.size
    a = np.zeros((n, size, size))
    rhs = np.zeros((n, size))

    def put(link: Any, col: int, force: np.ndarray, point: np.ndarray,
            couple: np.ndarray | float = 0.0) -> None:
        if link not in row:
            return
        r = row[link]
        a[:, r, col] += force.real
        a[:, r + 1, col] += force.imag
        a[:, r + 2, col] += point.real * force.imag - point.imag * force.real + couple

    for pid, (kind, (first, second), point, normal) in pairs.items():
        c, k = column[pid], np.broadcast_to(point.v * MM, (n,))
        for link, sign in ((second, 1.0), (first, -1.0)):
            if kind == "R":
                put(link, c, sign * np.ones(n, complex), k)
                put(link, c + 1, sign * 1j * np.ones(n, complex), k)
            else:
                put(link, c, sign * np.broadcast_to(normal.v, (n,)), k)
                put(link, c + 1, np.zeros(n, complex), k, sign * np.ones(n))
    for index, (kind, what) in enumerate(case.drives):
        col = first_drive + index
        if kind == "torque":
            put(what, col, np.zeros(n, complex), np.zeros(n, complex), np.ones(n))
            continue
        _, (carrier, slider), point, normal = pairs[what]
        u = -1j * np.broadcast_to(normal.v, (n,))
        k = np.broadcast_to(point.v * MM, (n,))
        if kind == "slide":  # on the moving link along the guide's drawn direction
            put(carrier if slider == 0 else slider, col, u, k)
            continue
        put(slider, col, u, k)  # a cylinder pushes its rod out, along the carrier → rod axis
        put(carrier, col, -u, k)
    w2 = case.omega ** 2

    def fixed(link: Any, at: Any) -> Any:
        origin, angle = poses[link]
        origin0, angle0 = sketch[link]
        local = (at - origin0.v[0]) * cmath.exp(-1j * float(np.asarray(J.value(angle0))[0]))
        return (origin + local * J.expi(angle)) * MM

    powers: list[np.ndarray] = []

    def known(link: Any, force: np.ndarray, point: Any, torque: np.ndarray | float) -> None:
        r = row[link]
        rhs[:, r] -= force.real
        rhs[:, r + 1] -= force.imag
        rhs[:, r + 2] -= point.v.real * force.imag - point.v.imag * force.real + torque
        powers.append(J.dot(point.d1 + 0j, force + 0j) + torque * poses[link][1].d1)

    for link, mass in data.masses.items():
        assert mass.centre is not None
        centre = fixed(link, mass.centre)
        force = mass.mass * data.gravity - mass.mass * w2 * centre.d2
        known(link, force, centre, -mass.inertia * w2 * poses[link][1].d2)
    for load in data.loads:
        if load.torque is not None:
            assert isinstance(load.torque, float)
            known(load.link, np.zeros(n, complex), poses[load.link][0] * 0.0,
                  load.torque + np.zeros(n))
        else:
            assert isinstance(load.force, complex) and load.point is not None
            known(load.link, load.force + np.zeros(n, complex), fixed(load.link, load.point),
                  np.zeros(n))
    solution = np.linalg.solve(a, rhs[..., None])[..., 0]
    return solution[:, first_drive:], x, powers


@pytest.mark.parametrize("name", list(CASES))
def test_driving_efforts_equal_the_global_solve_and_balance_the_power(name: str) -> None:
    case = CASES[name]()
    model, data = load_with_forces(TABLES / case.table)
    assert data is not None
    result = kinetostatics(analyse(model, case.q, analogs=True), data, case.omega)
    efforts, coordinates, powers = _global(case, data, case.q)
    got = list(result.drivings.values())
    assert len(got) == len(case.drives)
    for index, values in enumerate(got):
        want = efforts[:, index]
        assert np.max(np.abs(values - want)) <= 1e-9 * np.max(np.abs(want)), index
    # power: each effort times its coordinate's rate (rad, or m for a slider or a cylinder)
    rates = [x.d1 * (1.0 if kind == "torque" else MM) for (kind, _), x in
             zip(case.drives, coordinates, strict=True)]
    terms = [*powers, *(values * rate for values, rate in zip(got, rates, strict=True))]
    total = np.sum(terms, axis=0)
    scale = np.sum(np.abs(terms), axis=0)
    assert np.max(np.abs(total) / scale) <= 1e-9
    assert np.max(np.abs(result.power_balance) / result.power_scale) <= 1e-9
    assert max(float(np.max(r.moment)) for r in result.residuals.values()) <= 1e-9


# ----------------------------------------------------------------- a stroke end reached


def _boom_with_law(table: list[list[float]], stroke: list[float]) -> dict[str, Any]:
    data: dict[str, Any] = yaml.safe_load((TABLES / "hydraulic_boom_forces.yaml").read_text(encoding="utf-8"))
    data["mechanism"]["inputs"] = [{"pair": "Pd", "stroke": stroke, "table": table}]
    return data


def test_a_cylinder_beyond_its_stroke_does_not_assemble_there() -> None:
    """The cylinder's length follows 110 + 30·sin t (tabulated every 5°), its stroke is
    [70, 130]: it passes 130 mm where sin t = 2/3, so the boom's group fails between
    t = asin(2/3) and 180° − asin(2/3), worst at 90°, 10 mm beyond the end."""
    table = [[t, 110 + 30 * math.sin(math.radians(t))] for t in range(0, 360, 5)]
    model = assur.build_model(assur.analyse_structure(
        assur.chain_from_dict(_boom_with_law(table, [70, 130]))))
    report = assur.check_existence(model, points=360)
    (group,) = report.groups
    (interval,) = group.intervals
    start = math.asin(2 / 3)
    assert interval.reason == Reason.STROKE_END
    assert abs(interval.start - start) <= 1e-4 and abs(interval.end - (math.pi - start)) <= 1e-4
    assert abs(interval.worst_at - math.pi / 2) <= 0.02
    assert interval.unit == "mm" and abs(interval.shortfall - 10.0) <= 1e-3
    beyond = analyse(model, np.array([math.pi / 2]))
    assert np.isnan(np.asarray(J.value(beyond.joints["C"]))).all()  # no pose beyond the end


def test_a_slider_beyond_its_stroke_is_reported_by_its_input_group() -> None:
    data = yaml.safe_load((TABLES / "slider_driven_slider_crank.yaml").read_text("utf-8"))
    data["mechanism"]["inputs"] = [{"pair": "D", "stroke": [-40, 20],
                                    "table": [[0, -30], [90, 30], [180, 0], [270, -20]]}]
    model = assur.build_model(assur.analyse_structure(assur.chain_from_dict(data)))
    report = assur.check_existence(model, points=72)
    slider = report.groups[0]
    assert slider.label == "L0(3)" and slider.intervals
    assert {i.reason for i in slider.intervals} == {Reason.STROKE_END}
    assert not report.groups[1].intervals  # the dyad is not blamed for the input's stroke


# ------------------------------------------------------------------------ bad input rows


@pytest.mark.parametrize("row, field", [
    ({"pair": "Pd", "stroke": [130, 90]}, "'stroke'"),
    ({"pair": "Pd", "stroke": [90]}, "'stroke'"),
    ({"pair": "Pd", "stroke": [90, 130], "ratio": 0}, "'ratio'"),
    ({"pair": "Pd", "stroke": [90, 130], "ratio": 1.5}, "'ratio'"),
    ({"pair": "Pd", "stroke": [90, 130], "phase": "late"}, "'phase'"),
    ({"pair": "Pd", "stroke": [90, 130], "table": [[0, 95], [0, 100]]}, "'table'"),
    ({"pair": "Pd", "stroke": [90, 130], "table": [[0, 95]]}, "'table'"),
    ({"pair": "Pd", "table": [[0, 95], [180, 120]]}, "'table'"),
    ({"pair": "Pd", "stroke": [90, 130], "speed": 2}, ": unknown key 'speed'"),
])
def test_a_bad_input_law_is_refused_naming_its_field(
        row: dict[str, Any], field: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    data = yaml.safe_load((TABLES / "hydraulic_boom_forces.yaml").read_text(encoding="utf-8"))
    data["mechanism"]["inputs"] = [row]
    path = tmp_path / "boom.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    for command in ("check", "analyze"):
        assert main([command, str(path)]) == 2
        err = capsys.readouterr().err
        assert f"mechanism.inputs[0]{field if field.startswith(':') else ' ' + field}" in err and "Traceback" not in err, err


@pytest.mark.parametrize("inputs, field", [
    ([{"link": 1, "stroke": [0, 10]}, {"link": 4}], "mechanism.inputs[0] 'stroke'"),
    ([{"link": 1}, {"link": 4, "table": [[0, 1], [90, 2]], "stroke": [0, 5]}],
     "mechanism.inputs[1] 'stroke'"),
])
def test_a_crank_refuses_a_stroke(inputs: list[dict[str, Any]], field: str, tmp_path: Path,
                                  capsys: pytest.CaptureFixture[str]) -> None:
    data = yaml.safe_load((TABLES / "five_bar_two_cranks.yaml").read_text(encoding="utf-8"))
    data["mechanism"]["inputs"] = inputs
    path = tmp_path / "five_bar.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    assert main(["analyze", str(path)]) == 2
    assert field in capsys.readouterr().err


def test_a_linear_input_with_a_law_needs_its_stroke(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    data = yaml.safe_load((TABLES / "crank_and_cylinder.yaml").read_text(encoding="utf-8"))
    data["mechanism"]["inputs"][1].pop("stroke")
    path = tmp_path / "cc.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    assert main(["analyze", str(path)]) == 2
    assert "mechanism.inputs[1] 'stroke'" in capsys.readouterr().err


# ------------------------------------------------------------ batches of designs, verdict


def test_a_batch_of_boom_designs_with_their_own_strokes() -> None:
    """``cycle_model``: D designs share the positions t while each has its stroke; each
    design's positions are the closed form's at its cylinder lengths, and its static driving
    force is that of the boom analysed alone at those lengths."""
    case = _boom()
    model, data = load_with_forces(TABLES / case.table)
    assert data is not None
    cycle = assur.cycle_model(model)
    s_max = np.array([110.0, 125.0, 135.0])
    designs = cycle.with_params({"L1(1,2).s_max": s_max[:, None]})
    t = assur.input_grid(designs, 12)
    batch = kinetostatics(analyse(designs, t, analogs=True), data, 0.0)
    for k, top in enumerate(s_max):
        lengths = 95.0 + (top - 95.0) * (1 - np.cos(t)) / 2
        alone = analyse(model, lengths, analogs=True)
        want = case.joints([Jet(lengths)])["C"].v
        got = np.asarray(J.value(analyse(designs, t).joints["C"]))[k]
        assert np.max(np.abs(got - want)) <= 1e-9
        expected = kinetostatics(alone, data, 0.0).driving
        assert np.max(np.abs(batch.driving[k] - expected)) <= 1e-9 * np.max(np.abs(expected))


@pytest.mark.parametrize("table, code, part", [
    ("slider_driven_slider_crank.yaml", "verdict.refused_drives", "verdict.drive_slider"),
    ("hydraulic_boom_forces.yaml", "verdict.refused_drives", "verdict.drive_actuator"),
    ("five_bar_two_cranks.yaml", "verdict.refused_inputs", None),
])
def test_the_verdict_says_what_the_course_program_refuses(table: str, code: str,
                                                          part: str | None) -> None:
    from assur.assessment import assess

    found = assess(assur.load_chain(TABLES / table), points=None)
    assert found.verdict == "outside program"
    messages = [f.message for f in found.findings if f.message.code == code]
    assert messages, [f.message.code for f in found.findings]
    if part is not None:
        assert part in repr(messages[0].data)


@pytest.mark.parametrize("name", ["five_bar", "crank_and_cylinder"])
def test_analogs_with_respect_to_each_input(name: str) -> None:
    """∂x/∂q_k of every joint against the closed form moved in q_k alone (the other inputs
    held at their values), per radian of a crank, per mm of a cylinder."""
    from assur.kinematics.analysis import input_analogs

    case = CASES[name]()
    model = assur.load_model(TABLES / case.table)
    values = [np.asarray(J.value(x)) + 0.0 * case.q for x in case.laws(case.q)]
    for k, label in enumerate(model.laws):
        moved = [Jet(v, float(i == k), 0.0) for i, v in enumerate(values)]
        want = case.joints(moved)
        got = input_analogs(model, label, case.q).joints
        for pid, point in want.items():
            scale = 1.0 + np.max(np.abs(point.d1)) + np.max(np.abs(point.d2))
            jet = J.as_jet(got[pid])
            assert np.max(np.abs(jet.v - point.v)) <= 1e-9, (label, pid)
            assert np.max(np.abs(jet.d1 - point.d1)) <= 1e-9 * scale, (label, pid)
            assert np.max(np.abs(jet.d2 - point.d2)) <= 1e-9 * scale, (label, pid)


def test_a_batch_finding_names_the_cycle_parameter_of_a_stroke_end() -> None:
    """The boom whose cylinder follows 110 + 30·sin t beyond its 130 mm end: the finding
    says where in t (asin(2/3) = 41.8°, 138.2°) and why."""
    from assur.assessment import assess

    table = [[t, 110 + 30 * math.sin(math.radians(t))] for t in range(0, 360, 5)]
    found = assess(assur.chain_from_dict(_boom_with_law(table, [70, 130])), points=72)
    assert found.verdict == "wrong"
    texts = [finding.text("en") for finding in found.findings]
    assert ("group L1(1,2) does not assemble for t = 41.8°…138.2°: a linear input (a slider, "
            "an actuator) is beyond an end of its stroke") in texts, texts


def test_an_actuator_of_a_triad_takes_no_law(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    data = yaml.safe_load((TABLES / "actuator_triad.yaml").read_text(encoding="utf-8"))
    data["mechanism"]["inputs"] = [{"pair": "S", "stroke": [85, 115],
                                    "table": [[0, 90], [180, 110]]}]
    path = tmp_path / "triad.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    assert main(["analyze", str(path)]) == 2
    assert "mechanism.inputs[0] 'pair'" in capsys.readouterr().err
    with pytest.raises(ValueError, match="along its length only"):
        assur.cycle_model(assur.load_model(TABLES / "actuator_triad.yaml"))
