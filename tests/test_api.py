"""The public verbs ``assur.load``, ``assur.check`` and ``assur.analyse``.

A plain script run in its own process uses the verbs on the course's 11-link tables; its
records must be the very ones that ``assur check --json`` and ``assur analyze --json
[--forces --omega W]`` print (the commands are thin renderers of the same results), and the
numbers must hold as mechanics: every link keeps its length over the cycle, and the driving
torque balances the power of the loads.
"""

from __future__ import annotations

import doctest
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import assur
from assur.structure.identification import check_identification

ROOT = Path(__file__).resolve().parent.parent
COURSE = ROOT / "input_tables" / "course_11_link.yaml"
COURSE_FORCES = ROOT / "input_tables" / "course_11_link_forces.yaml"
OMEGA = "7.5"

SCRIPT = f"""
import json, sys
import assur

chain = assur.load({str(COURSE)!r})
print(json.dumps({{
    "check": assur.check(chain, points=None).to_dict(),
    "analyse": assur.analyse(chain, points=24).to_dict(),
    "forces": assur.analyse({str(COURSE_FORCES)!r}, points=24, forces=True,
                            omega={OMEGA}).to_dict(),
}}, ensure_ascii=False))
"""


def _run(*args: str) -> Any:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env,
                          cwd=ROOT, check=True, timeout=600)
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def api() -> Any:
    return _run("-c", SCRIPT)


def _command(*args: str) -> Any:
    return _run("-m", "synthesis", *args)


def test_check_of_the_api_is_check_json(api: Any) -> None:
    assert api["check"] == _command("check", str(COURSE), "--json")


def test_analyse_of_the_api_is_analyze_json(api: Any) -> None:
    assert api["analyse"] == _command("analyze", str(COURSE), "--points", "24", "--json")


def test_analyse_with_forces_is_analyze_json_with_forces(api: Any) -> None:
    printed = _command("analyze", str(COURSE_FORCES), "--points", "24", "--json", "--forces",
                       "--omega", OMEGA)
    assert api["forces"] == printed
    assert printed["forces"]["omega"] == float(OMEGA)


def test_the_records_hold_as_mechanics(api: Any) -> None:
    """Two joints of one link stay at the link's length; the power balance is round-off."""
    record = api["analyse"]
    pairs: dict[int | str, list[str]] = {}
    for name, joint in record["joints"].items():
        for link in joint["links"]:
            pairs.setdefault(link, []).append(name)
    checked = 0
    for link, names in pairs.items():
        if link == 0 or len(names) < 2:
            continue
        a, b = (record["joints"][n] for n in names[:2])
        length = np.hypot(np.subtract(a["x"], b["x"]), np.subtract(a["y"], b["y"]))
        assert np.ptp(length) < 1e-9 * length.max(), link
        checked += 1
    assert checked >= 5
    forces = api["forces"]["forces"]
    balance = np.abs(np.array(forces["power_balance"], dtype=float))
    torque = np.abs(np.array(forces["driving_torque"], dtype=float))
    assert balance.max() < 1e-9 * torque.max()


def test_every_result_prints_in_a_few_lines() -> None:
    chain = assur.load(COURSE_FORCES)
    found = assur.check(chain, points=36)
    result = assur.analyse(chain, points=360, forces=True, omega=10.0)
    for shown in (found, found.analysis, found.existence, result, result.motion,
                  result.forces):
        text = repr(shown)
        assert len(text.splitlines()) <= 20 and len(text) < 2000, type(shown).__name__
    assert repr(result.motion).startswith("Motion(")
    assert "360 positions" in repr(result.motion)


def test_a_chain_without_a_student_table_is_no_table_to_check() -> None:
    chain = assur.load(COURSE)
    analysis = assur.analyse_structure(chain)
    assert chain.identification is None
    assert check_identification(analysis, chain.identification) is None
    assert assur.check(chain, points=None).identification == "not given"
    rows = assur.identification_table(analysis)
    assert check_identification(analysis, rows) == []


def test_the_api_page_runs_as_written() -> None:
    """Every example of ``docs/api.md`` (doctests in its ``python`` blocks)."""
    failed, attempted = doctest.testfile(str(ROOT / "docs" / "api.md"), module_relative=False,
                                         optionflags=doctest.ELLIPSIS, encoding="utf-8")
    assert attempted >= 10 and failed == 0
