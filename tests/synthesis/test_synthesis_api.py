"""The public API of synthesis: a plain script gives what ``assur synthesize --json`` prints."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from synthesis import SettingError, SynthesisResult, load_problem, synthesize

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "input_tables" / "problems" / "class4_fourbar_timed.yaml"
#: A short run: 2^6 LPτ trials, one round, the refinement (the problem's [Q] may stop it).
OPTIONS = {"budget": 6, "seed": 5, "restarts": 0, "shrink": 1}

SCRIPT = """
import json, sys
from synthesis import load_problem, synthesize
result = synthesize(load_problem(sys.argv[1]), budget=6, seed=5, restarts=0, shrink=1)
print(json.dumps({"design": result.design, "Q": result.q, "stop": result.stop,
                  "trials": result.trials, "feasible": result.feasible}))
"""


def _python(*argv: str) -> str:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, *argv], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=600, check=False)
    assert done.returncode in (0, 1), done.stderr
    return done.stdout


def test_a_plain_script_gives_the_design_and_q_of_the_command() -> None:
    script = json.loads(_python("-c", SCRIPT, str(PROBLEM)))
    printed = json.loads(_python("-m", "synthesis", "synthesize", str(PROBLEM), "--json",
                                 "--quiet", "--budget", "6", "--seed", "5", "--restarts", "0",
                                 "--shrink", "1"))
    assert script["design"] == printed["design"]       # every digit
    assert script["Q"] == printed["Q"]
    assert script["stop"] == printed["search"]["stop"]
    assert script["trials"] == printed["search"]["trials"]
    assert script["feasible"] == printed["feasible"]


@pytest.fixture(scope="module")
def result() -> SynthesisResult:
    return synthesize(load_problem(PROBLEM), **OPTIONS)  # type: ignore[arg-type]


def test_to_dict_is_plain_json_that_agrees_with_the_attributes(result: SynthesisResult) -> None:
    data = result.to_dict()
    assert json.loads(json.dumps(data, allow_nan=False)) == data
    assert data["design"] == result.design
    assert data["Q"] == result.q and data["P1"] == result.p1 and data["P2"] == result.p2
    assert data["feasible"] is result.feasible and data["favourable"] is result.favourable
    assert data["search"]["trials"] == result.trials == result.search.trials.shape[0]
    # Q is the largest weighted deviation at the control points, in mm
    deviations = [abs(row["deviation"]) for row in data["control_points"]]
    assert math.isclose(result.q, max(deviations), rel_tol=1e-12)


def test_the_result_is_frozen_and_its_repr_short(result: SynthesisResult) -> None:
    with pytest.raises(AttributeError):
        result.problem = result.problem  # type: ignore[misc]
    text = repr(result)
    assert len(text.splitlines()) <= 20
    for name, value in result.design.items():
        assert f"{name!r}: {value:.9g}," in text
    assert f"stop={result.stop!r}" in text and f"trials={result.trials}" in text


def test_an_override_breaking_its_rule_is_refused() -> None:
    with pytest.raises(SettingError, match="budget .* must be a whole number from 0 to 24; "
                                           "got -3"):
        synthesize(load_problem(PROBLEM), budget=-3)
