"""Search settings: every rule checked at construction, the same on the command line and in
a problem's ``search`` table; ``rng=``; an immutable result."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import yaml

from assur import AssurError
from synthesis import SearchSettings, SettingError
from synthesis.cli import main
from synthesis.criteria import Criteria
from synthesis.search import search
from synthesis.search_settings import setting_problem

PROBLEMS = Path(__file__).resolve().parents[2] / "input_tables" / "problems"


def _sphere(x: np.ndarray) -> Criteria:
    dev = x - 0.25
    zero = np.zeros(len(x))
    return Criteria(zero, zero, np.max(np.abs(dev), axis=1), dev, dev)


@pytest.mark.parametrize(("field", "value", "rule"), [
    ("batch", 0, "batch must be a power of two (1, 2, 4, …: designs per evaluation); got 0"),
    ("batch", 48, "batch must be a power of two"),
    ("shrink", 5.0, ("shrink (the half-width factor of each shrunk box) must be a number between "
                     "0 and 1, both excluded; got 5.0")),
    ("shrink", 0.0, "got 0.0"),
    ("time_limit", -1.0, "time_limit must be a positive number of seconds, or none; got -1.0"),
    ("budget_log2", -3, ("budget (log2 of the LPτ trials) must be a whole number from 0 to 24; "
                         "got -3")),
    ("budget_log2", 25, "got 25"),
    ("seed", -1, "seed must be a whole number ≥ 0; got -1"),
    ("seed", 1.5, "seed must be a whole number ≥ 0; got 1.5"),
    ("stall", 0, "stall (trials without improvement) must be a whole number ≥ 1, or none"),
    ("refine", "yes", "refine must be true or false; got 'yes'"),
    ("objective", "best", "objective must be 'lexicographic' or 'weighted'; got 'best'"),
    ("p2_weight", 0.0, "p2_weight (λ) must be a positive number; got 0.0"),
    ("shrink_passes", 11, "shrink_passes must be a whole number from 0 to 10; got 11"),
    ("refine_evaluations", 0, "refine_evaluations (evaluations per refinement start) must be"),
])
def test_every_setting_states_its_rule(field: str, value: object, rule: str) -> None:
    with pytest.raises(SettingError) as caught:
        SearchSettings(**{field: value})  # type: ignore[arg-type]
    assert rule in str(caught.value)
    assert isinstance(caught.value, ValueError) and isinstance(caught.value, AssurError)
    # the Russian catalogue states the same rule
    assert caught.value.text("ru") != str(caught.value)


def test_allowed_edges_are_accepted() -> None:
    s = SearchSettings(budget_log2=0, seed=0, batch=1, shrink=0.999, time_limit=1e-3,
                       stall=1, shrink_passes=10, refine_starts=1, refine_evaluations=1,
                       objective="weighted", p2_weight=1e-9)
    assert s.batch == 1 and setting_problem("batch", 1024) is None


def test_bounds_order_and_shape_are_checked() -> None:
    with pytest.raises(SettingError, match=r"a lower bound must not exceed its upper bound; "
                                           r"got lower\[1\] = 5 > upper\[1\] = 3"):
        search(_sphere, [0, 5], [1, 3], [0.5, 4])
    with pytest.raises(SettingError, match="must be vectors of one length"):
        search(_sphere, [0, 0], [1, 1, 1], [0.5, 0.5])
    with pytest.raises(SettingError, match="the bounds must be finite numbers"):
        search(_sphere, [0, -np.inf], [1, 1], [0.5, 0.5])
    # a fixed coordinate (lower = upper) is allowed
    r = search(_sphere, [0, 0.25], [1, 0.25], [0.5, 0.25], SearchSettings(budget_log2=3))
    assert np.all(r.trials[:, 1] == 0.25)


def _table_with(tmp_path: Path, search: dict[str, object]) -> Path:
    data = yaml.safe_load((PROBLEMS / "class3_fourbar_path.yaml").read_text(encoding="utf-8"))
    data["search"] = search
    path = tmp_path / "problem.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    return path


@pytest.mark.parametrize(("option", "key", "value", "rule"), [
    ("--budget", "budget", -3, ("budget (log2 of the LPτ trials) must be a whole number from 0 "
                                "to 24; got -3")),
    ("--time-limit", "time_limit", -1.0, ("time_limit must be a positive number of seconds, or "
                                          "none; got -1.0")),
    ("--shrink", "shrink_passes", 11, ("shrink_passes must be a whole number from 0 to 10; "
                                       "got 11")),
    ("--seed", "seed", -1, "seed must be a whole number ≥ 0; got -1"),
])
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_command_line_and_table_give_the_same_error(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str, key: str,
        value: object, rule: str, lang: str) -> None:
    good = _table_with(tmp_path, {"budget": 6})
    assert main(["synthesize", str(good), option, str(value), "--lang", lang, "--quiet"]) == 2
    named, _, from_option = capsys.readouterr().err.strip().partition(": ")
    assert named == option  # the command line names the option, then states the rule
    bad = _table_with(tmp_path, {key: value})
    assert main(["synthesize", str(bad), "--lang", lang, "--quiet"]) == 2
    from_table = capsys.readouterr().err
    assert f"search {key!r}: {from_option}" in from_table
    if lang == "en":
        assert from_option == rule
    assert "Traceback" not in from_option + from_table


def test_rng_accepts_a_seed_or_a_generator() -> None:
    settings = SearchSettings(budget_log2=6, seed=3, shrink_passes=1)
    by_seed = search(_sphere, [0, 0], [1, 1], [0.9, 0.9], settings)
    by_int = search(_sphere, [0, 0], [1, 1], [0.9, 0.9], SearchSettings(budget_log2=6,
                                                                        shrink_passes=1), rng=3)
    np.testing.assert_array_equal(by_seed.trials, by_int.trials)
    assert by_seed.seed == by_int.seed == 3
    # a Generator seeded like default_rng(3) draws the same first pass; it records no seed
    by_generator = search(_sphere, [0, 0], [1, 1], [0.9, 0.9], settings,
                          rng=np.random.default_rng(3))
    first = 1 + 2 ** 6
    np.testing.assert_array_equal(by_generator.trials[:first], by_seed.trials[:first])
    assert by_generator.seed is None
    with pytest.raises(SettingError, match="rng must be None, a whole number ≥ 0"):
        search(_sphere, [0, 0], [1, 1], [0.9, 0.9], settings, rng=-2)


def test_search_result_is_immutable() -> None:
    r = search(_sphere, [0, 0], [1, 1], [0.9, 0.9], SearchSettings(budget_log2=4))
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.stop = "time"  # type: ignore[misc]
    for array in (r.x, r.trials, r.criteria.q, r.trial_criteria.deviations):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 0.0
    assert isinstance(r.stage, tuple) and isinstance(r.history, tuple)
    assert r.history[0].trial == 0 and r.history[0].stage == "initial"
