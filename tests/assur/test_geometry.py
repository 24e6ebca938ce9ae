"""The kinematic model: parameters derived from a sketch and read from identification rows."""

from __future__ import annotations

import cmath
import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import assur
from assur.kinematics.analysis import analyse

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "input_tables" / "course_11_link.yaml"
TABLE = ROOT / "input_tables" / "course_11_link_table.yaml"
DATA = yaml.safe_load(EXAMPLE.read_text())
TABLE_DATA = yaml.safe_load(TABLE.read_text())


def _model(data: dict, source: str = "sketch.yaml") -> assur.KinematicModel:
    return assur.build_model(assur.analyse_structure(assur.chain_from_dict(data, source)))


def _p(key: str) -> complex:
    return complex(*DATA["geometry"][key]["point"])


def _cross(a: complex, b: complex) -> float:
    return a.real * b.imag - a.imag * b.real


def test_sketch_gives_lengths_attachments_guides_and_variants() -> None:
    model = assur.load_model(EXAMPLE)
    p = model.params
    o, a, c, d, n = _p("0-1"), _p("1-2"), _p("2-3"), _p("3-0"), _p("2-6")
    assert p["L0(1).l_1"] == pytest.approx(abs(a - o))
    assert p["L0(1).phi_1_0"] == pytest.approx(math.degrees(math.atan2(a.imag, a.real)))
    assert p["L1(2,3).l_i"] == pytest.approx(abs(c - a))
    assert p["L1(2,3).l_j"] == pytest.approx(abs(c - d))
    assert p["L1(2,3).x_Hj"] == 150 and p["L1(2,3).y_Hj"] == 0
    # N on the coupler: distance from its hinge A and angle from the axis A→C
    assert p["L1(2,3).l_N"] == pytest.approx(abs(n - a))
    turn = math.degrees(math.atan2(_cross(c - a, n - a), ((c - a).conjugate() * (n - a)).real))
    assert p["L1(2,3).beta_N"] == pytest.approx(turn)
    # guide of slider 4 on the rocker: relative to the rocker axis D→C, through the pivot
    rocker = math.degrees(math.atan2((c - d).imag, (c - d).real))
    assert p["L4(4,5).beta_i"] == pytest.approx(DATA["geometry"]["3-4"]["direction"] - rocker)
    assert p["L4(4,5).x_Ak"] == pytest.approx(0, abs=1e-12)
    # kulisa: offset of the block pivot from the axis through the coupler hinge
    axis = cmath.exp(1j * math.radians(DATA["geometry"]["6-7"]["direction"]))
    assert p["L3(6,7).d"] == pytest.approx(_cross(axis, _p("7-0") - n))
    assert p["L5(11,10).gamma"] == pytest.approx(60.0)
    sigma = {g.label: g.sigma for g in model.groups}
    assert sigma["L1(2,3)"] == (1 if _cross(d - a, c - a) > 0 else -1) == 1
    assert sigma["L2(9,8)"] == -1  # C behind the foot of H_j along the guide direction 180°
    assert all(p[f"{g.label}.delta"] == 0.0 for g in model.groups if g.kind)
    assert [t.name for t in model.tracing] == ["K"]


def test_identification_rows_give_the_same_parameters_as_the_sketch() -> None:
    sketch, table = assur.load_model(EXAMPLE), assur.load_model(TABLE)
    for name, value in table.params.items():
        if name not in sketch.params:  # a column of an absent attachment: zero in the table
            assert value == 0.0, name
            continue
        diff = sketch.params[name] - value
        if name.split(".")[1].startswith(("beta", "phi", "gamma")):
            diff = (diff + 180.0) % 360.0 - 180.0  # angles in degrees, modulo a turn
        assert abs(diff) < 0.02, name
    rows = {row["group"]: row for row in table.parameter_table()}
    assert rows["L1(2,3)"]["x_Hi"] == "A" and rows["L1(2,3)"]["x_Hj"] == 150.0
    assert rows["L2(9,8)"]["x_Hj"] == "A"
    assert [g.sigma for g in table.groups] == [1, 1, 1, 1, -1, 1]


def test_a_synthesis_range_in_a_mechanism_table_is_sent_to_the_problem_table() -> None:
    data = copy.deepcopy(TABLE_DATA)
    data["structure_identification"][0]["params"]["l_1"] = [40, 30, 50]
    with pytest.raises(assur.TableError) as caught:
        _model(data)
    (issue,) = caught.value.issues
    assert "'l_1'" in issue.location
    assert "synthesis problem" in issue.text("en") and "[40, 30, 50]" in issue.text("en")
    assert "задачи синтеза" in issue.text("ru")


def test_direction_from_identification_rows() -> None:
    data = copy.deepcopy(TABLE_DATA)
    rows = data["structure_identification"]
    rows[0]["params"]["s"] = -1
    model = _model(data)
    assert model.direction == -1
    motion = analyse(model, np.radians([0.0, 90.0]))
    pin = motion.joints["0-1"] + 40 * np.exp(1j * np.radians([30.0, -60.0]))
    np.testing.assert_allclose(motion.solutions["L0(1)"].c, pin, atol=1e-12)


def test_every_problem_of_the_rows_is_reported_at_once() -> None:
    data = copy.deepcopy(TABLE_DATA)
    rows = data["structure_identification"]
    del rows[0]["params"]["l_1"]
    rows[1]["params"]["x_Hj"] = "A"      # the rocker pivot is on the frame: a number is needed
    rows[1]["params"]["lengt_i"] = 3     # unknown column
    rows[2]["params"]["l_j"] = [130, 140, 150]  # initial outside its bounds
    rows[3]["params"]["x_Hi"] = 12.5     # hinge on the moving coupler: must be 'A'
    with pytest.raises(assur.TableError) as info:
        _model(data, "rows.yaml")
    text = str(info.value)
    assert "5 problems in rows.yaml" in text
    assert "'l_1': this column is missing" in text
    assert "'x_Hj': the hinge lies on the frame: expected its coordinate (mm); found 'A'" in text
    assert "unknown column 'lengt_i'" in text
    assert "belongs in the parameters table of a synthesis problem" in text
    assert "'x_Hi': the hinge lies on moving link 2" in text


def test_every_problem_of_the_sketch_is_reported_at_once() -> None:
    data = copy.deepcopy(DATA)
    geometry = data["geometry"]
    del geometry["4-5"]
    del geometry["9-0"]["direction"]
    geometry["8-9"] = {"point": [1, "x"]}
    geometry["11-O"] = {"point": [0, 0]}
    geometry["margin"] = {"L1(2,3)": 1.5}
    with pytest.raises(assur.TableError) as info:
        _model(data, "sketch.yaml")
    text = str(info.value)
    assert "geometry '4-5': the R pair '4-5'" in text
    assert "geometry '9-0': the slider pair '9-0'" in text and "needs 'direction'" in text
    assert "geometry '8-9' 'point': expected two numbers" in text
    assert "geometry '11-O': unknown key; did you mean '11-0'?" in text
    assert "δ must lie in [0, 1)" in text


def test_margin_rotation_and_tracing_from_the_sketch() -> None:
    data = copy.deepcopy(DATA)
    data["geometry"]["margin"] = 0.05
    data["geometry"]["input"] = {"rotation": "cw"}
    model = _model(data)
    assert model.direction == -1
    assert all(model.params[f"{g.label}.delta"] == 0.05 for g in model.groups if g.kind)
    motion = analyse(model, np.array([0.0, 0.5]))
    # the tracing point is fixed on the coupler: its distances to the coupler's hinges hold
    k = motion.tracing["K"]
    for pid, sketched in (("1-2", _p("1-2")), ("2-3", _p("2-3")), ("2-6", _p("2-6"))):
        expected = abs(complex(100, 110) - sketched)
        np.testing.assert_allclose(np.abs(k - motion.joints[pid]), expected, rtol=1e-12)
    # clockwise: the crank turns by −φ from its sketched angle
    pin = motion.joints["1-2"] - motion.joints["0-1"]
    assert np.angle(pin[1] / pin[0]) == pytest.approx(-0.5)


def test_with_params_rejects_unknown_names_with_a_hint() -> None:
    model = assur.load_model(EXAMPLE)
    with pytest.raises(KeyError, match=r"did you mean 'L1\(2,3\).l_i'"):
        model.with_params({"L1(2,3).l_ii": 3.0})
    batch = model.with_params({"L1(2,3).l_i": np.array([[139.0], [141.0]])})
    assert batch.design_shape == (2, 1)
    assert model.design_shape == ()


def test_chain_that_does_not_split_into_groups_has_no_model() -> None:
    """A five-bar with one input keeps one degree of freedom: no kinematic model."""
    pairs = [{"id": k, "type": "R", "links": links} for k, links in
             (("A", [0, 1]), ("B", [1, 2]), ("C", [2, 3]), ("D", [3, 4]), ("E", [4, 0]))]
    geometry = {k: {"point": p} for k, p in
                (("A", [0, 0]), ("B", [10, 0]), ("C", [20, 10]), ("D", [30, 5]), ("E", [40, 0]))}
    with pytest.raises(assur.StructureError, match="does not split into Assur groups"):
        _model({"mechanism": {"pairs": pairs, "inputs": [1]}, "geometry": geometry})


@pytest.mark.parametrize(("cy", "sigma", "phi_i", "phi_j"),
                         [(48.0, 1, 36.8699, 126.8699), (-48.0, -1, -36.8699, -126.8699)])
def test_rrr_test_vectors_of_the_method_at_the_sketched_position(
        cy: float, sigma: int, phi_i: float, phi_j: float) -> None:
    """method.md §2.9: H_i = (0, 0), H_j = (100, 0), l_i = 80, l_j = 60."""
    pairs = [{"id": k, "type": "R", "links": links} for k, links in
             (("O", [0, 1]), ("Hi", [1, 2]), ("C", [2, 3]), ("Hj", [3, 0]))]
    geometry = {"O": {"point": [-20, 0]}, "Hi": {"point": [0, 0]}, "C": {"point": [64, cy]},
                "Hj": {"point": [100, 0]}}
    model = _model({"mechanism": {"pairs": pairs, "inputs": [1]}, "geometry": geometry})
    group = model.group("L1(2,3)")
    assert group.sigma == sigma
    assert model.params["L1(2,3).l_i"] == 80.0 and model.params["L1(2,3).l_j"] == 60.0
    motion = analyse(model, np.array([0.0, 2 * np.pi]))
    np.testing.assert_allclose(motion.joints["C"], complex(64, cy), atol=1e-12)
    np.testing.assert_allclose(np.degrees(motion.frames[2][1]), phi_i, atol=1e-4)
    np.testing.assert_allclose(np.degrees(motion.frames[3][1]), phi_j, atol=1e-4)
    (alpha,) = assur.pressure_angles(motion)
    np.testing.assert_allclose(alpha.alpha, 0.0, atol=1e-7)
