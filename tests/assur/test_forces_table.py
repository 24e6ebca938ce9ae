"""The ``masses:``, ``loads:`` and ``gravity:`` sections: values read, every problem at once."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from force_tables import TABLES, load

import assur
import assur.io.reader
from assur.errors import Issue
from assur.forces import ForceData, Load, Mass, Tabulated, read_forces

COURSE = assur.load_chain(TABLES / "course_11_link.yaml")
BOOM = assur.load_chain(TABLES / "hydraulic_boom.yaml")


def _read(sections: dict[str, Any], chain: assur.Chain = COURSE
          ) -> tuple[ForceData | None, list[Issue]]:
    reader = assur.io.reader.TableReader.from_data(sections, "t.yaml")
    return read_forces(reader.root(), chain), reader.issues


def test_a_shipped_table_is_read_into_typed_values() -> None:
    _, data = load("course_11_link_forces.yaml")
    assert data.masses[2] == Mass(0.7, 84.6567 + 66.8433j, 1.1433e-3)
    assert data.gravity == -9.81j
    (resistance,) = data.loads
    assert resistance.link == 11 and resistance.point == 250 + 154.47j
    assert isinstance(resistance.force, Tabulated)
    assert resistance.force.nodes == (0, 69, 71, 220, 222, 360)
    # periodic and linear: 70° lies half-way between -500 N and +500 N
    values = resistance.force.at(np.radians([70.0, 30.0, 390.0, 221.0]), periodic=True)
    np.testing.assert_allclose(values, [0j, -500j, -500j, 0j], atol=1e-12)


def test_constants_torques_and_gravity() -> None:
    data, issues = _read({"masses": {"3": {"mass": 0.5, "centre": [1, 2]}},
                          "loads": [{"link": 3, "torque": -20},
                                    {"link": "9", "force": [-500, 0], "point": [198.6, 230]},
                                    {"link": 6, "torque": {"phi": [0, 360], "value": [4, 4]}}],
                          "gravity": [0, -9.81]})
    assert issues == []
    assert data == ForceData({3: Mass(0.5, 1 + 2j, 0.0)},
                             (Load(3, torque=-20.0), Load(9, force=-500 + 0j, point=198.6 + 230j),
                              Load(6, torque=Tabulated((0.0, 360.0), (4.0, 4.0)))), -9.81j)


def test_without_masses_and_loads_there_is_no_force_analysis() -> None:
    assert _read({"gravity": [0, -9.81]}) == (None, [])
    assert _read({}) == (None, [])


def test_an_actuator_table_runs_over_the_length() -> None:
    data, issues = _read({"loads": [{"link": 1, "torque": {"length": [300, 400],
                                                              "value": [0, 10]}}]}, BOOM)
    assert issues == [] and data is not None
    torque = data.loads[0].torque
    assert isinstance(torque, Tabulated)
    assert torque.at(np.array([250.0, 350.0, 450.0]), periodic=False).tolist() \
        == [0.0, 5.0, 10.0]
    _, issues = _read({"loads": [{"link": 1, "torque": {"phi": [0, 360], "value": [0, 0]}}]},
                      BOOM)
    assert [i.location for i in issues] == ["loads[0] 'torque'", "loads[0] 'torque' 'length'"]


BAD = {
    "masses": {
        0: {"mass": 1.0, "centre": [0, 0]},
        2: {"mas": 1.0, "centre": [0, 0]},
        3: {"mass": -0.5, "centre": [0, 0], "inertia": -1},
        4: {"mass": 0.5},
        5: "heavy",
        6: {"mass": 0.2, "centre": [1, "a"]},
    },
    "loads": [
        {"link": 99, "torque": 1},
        {"link": 3, "torque": 1, "force": [1, 0], "point": [0, 0]},
        {"link": 3},
        {"link": 3, "force": [1, 0]},
        {"link": 3, "torque": 2, "point": [0, 0]},
        {"link": 3, "torque": {"phi": [0, 180, 360], "value": [1, 2]}},
        {"link": 3, "torque": {"phi": [0, 180, 90], "value": [1, 2, 3]}},
        {"link": 3, "torque": {"phi": [-10, 180], "value": [1, 2]}},
        {"link": 3, "torque": {"phi": [0, 180, 360], "value": [1, 2, 3]}},
        {"link": 3, "torque": {"phi": [0], "value": [1]}},
        {"link": 3, "force": {"phi": [0, 90], "x": [0, "a"], "y": [1, 1]}, "point": [0, 0]},
        {"link": 3, "torque": "much"},
    ],
    "gravity": [0],
}

#: Every problem of BAD: (location, catalogue code or None for the reader's own sentences).
PROBLEMS = [
    ("masses.0", "force.link.not_moving"),
    ("masses.2", None),                          # unknown key 'mas'; did you mean 'mass'?
    ("masses.3 'mass'", "table.rule_broken"),
    ("masses.3 'inertia'", "table.rule_broken"),
    ("masses.4", "force.mass.centre_missing"),
    ("masses.5", "force.mass.expected"),
    ("masses.6 'centre'[1]", "table.wrong_kind"),
    ("loads[0] 'link'", "force.link.not_moving"),
    ("loads[1]", "force.load.force_or_torque"),
    ("loads[2]", "force.load.force_or_torque"),
    ("loads[3]", "force.load.point_missing"),
    ("loads[4] 'point'", "force.load.point_with_torque"),
    ("loads[5] 'torque'", "force.table.lengths"),
    ("loads[6] 'torque' 'phi'", "force.table.not_increasing"),
    ("loads[7] 'torque' 'phi'", "force.table.outside"),
    ("loads[8] 'torque' 'phi'", "force.table.ends"),
    ("loads[9] 'torque' 'phi'", "force.table.too_short"),
    ("loads[10] 'force' 'x'[1]", "table.wrong_kind"),
    ("loads[11] 'torque'", "force.table.expected"),
    ("'gravity'", "force.vector.expected"),
]


def test_every_problem_is_reported_at_once() -> None:
    data, issues = _read(BAD)
    assert data is None
    assert [issue.location for issue in issues] == [location for location, _ in PROBLEMS]
    for issue, (_, code) in zip(issues, PROBLEMS):
        if code is not None:
            assert issue.message.code == code


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_every_problem_reads_as_a_sentence(lang: str) -> None:
    _, issues = _read(BAD)
    for issue in issues:
        text = issue.text(lang)
        assert "force." not in text and "(found=" not in text, text
    assert "did you mean 'mass'" in issues[1].text("en")
    assert issues[2].text("en") == "masses.3 'mass': must be positive and at most 1e+06; found -0.5"


def test_the_chain_reader_carries_the_sections_and_lists_their_problems_with_the_rest() -> None:
    import yaml

    table = yaml.safe_load((TABLES / "four_bar_gravity.yaml").read_text())
    chain = assur.chain_from_dict(table, "four_bar_gravity.yaml")
    assert chain.forces is not None and chain.forces.gravity == -9.81j
    assert assur.chain_from_dict({k: v for k, v in table.items()
                                  if k not in ("masses", "loads", "gravity")}).forces is None
    table["mechanism"]["pairs"][0]["type"] = "Q"              # a problem of the chain
    table["masses"][2]["inertia"] = -1                         # one of the masses
    table["gravty"] = table.pop("gravity")                     # a misspelt section
    with pytest.raises(assur.TableError) as caught:
        assur.chain_from_dict(table, "t.yaml")
    text = caught.value.text("en")
    assert "unknown key 'gravty'; did you mean 'gravity'?" in text
    assert "masses.2 'inertia': must be zero or positive and at most 1e+06; found -1" in text
    assert "mechanism.pairs[0] (id 'A') 'type'" in text
