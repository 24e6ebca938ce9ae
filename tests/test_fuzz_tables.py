"""Quick profile of the mutation fuzzer (``benchmarks/fuzz_tables.py``): mutants of every
shipped table run through their commands in-process; none may end in a traceback, a hang or
an exit code other than 0, 1 or 2.  The long run (10,000 mutants) is the benchmark script."""

from __future__ import annotations

import importlib
import importlib.util
import random
import sys
import time
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parent.parent
_SPEC = importlib.util.spec_from_file_location("fuzz_tables", ROOT / "benchmarks" /
                                               "fuzz_tables.py")
assert _SPEC is not None and _SPEC.loader is not None
fuzz_tables = importlib.util.module_from_spec(_SPEC)
sys.modules["fuzz_tables"] = fuzz_tables
_SPEC.loader.exec_module(fuzz_tables)

#: Mutants of the quick profile.
MUTANTS = 24
#: Time limit of one mutant (seconds); generous, as the first run of a command imports it.
TIMEOUT = 60.0
#: The case whose every solved table takes seconds is left to the long run.
SKIP = frozenset({"fourbar_velocity_ratio"})


def test_every_shipped_table_has_a_command() -> None:
    kinds = fuzz_tables.shipped_tables()
    assert {"chain", "problem", "tracker", "impact", "fourbar_velocity_ratio"} <= set(kinds.values())
    rng = random.Random(0)
    for name, kind in kinds.items():
        argv = fuzz_tables.command(kind, name, rng)
        assert name in argv


def test_the_runner_tells_a_traceback_and_a_hang(monkeypatch: pytest.MonkeyPatch) -> None:
    cli = importlib.import_module("synthesis.cli.main")

    def crash(argv: list[str]) -> int:
        missing: dict[str, int] = {}
        return missing["missing"]

    monkeypatch.setattr(cli, "main", crash)
    outcome, detail = fuzz_tables.run_command(["check", "x"], 5)
    assert outcome == "traceback" and "KeyError" in detail

    def loop(argv: list[str]) -> int:
        while True:
            time.sleep(0.01)

    monkeypatch.setattr(cli, "main", loop)
    assert fuzz_tables.run_command(["check", "x"], 0.2)[0] == "hang"


def test_mutants_of_the_shipped_tables_end_cleanly(tmp_path: Path) -> None:
    """A fixed set of mutants (seeded), each with a time limit."""
    failures: list[str] = []

    def report(index: int, outcome: str, mutant: Any, argv: list[str], detail: str) -> None:
        failures.append(f"{outcome}: {mutant.origin} {mutant.operation} {argv}\n{detail}")

    fuzz_tables.copy_tables(tmp_path)
    counts = fuzz_tables.fuzz(MUTANTS, 0, TIMEOUT, tmp_path, report, SKIP)
    assert not failures, "\n\n".join(failures)
    assert sum(counts.values()) == MUTANTS


def test_mutants_of_the_newer_features_end_cleanly(tmp_path: Path) -> None:
    """Mutants of the force sections, higher-group tables and force conditions, and odd
    option values, under the load-proof hang limit."""
    failures: list[str] = []

    def report(index: int, outcome: str, mutant: Any, argv: list[str], detail: str) -> None:
        failures.append(f"{outcome}: {mutant.origin} {mutant.operation} {argv}\n{detail}")

    fuzz_tables.copy_tables(tmp_path)
    limit = max(TIMEOUT, fuzz_tables.hang_limit(tmp_path, 30.0))
    counts = fuzz_tables.fuzz(MUTANTS, 1, limit, tmp_path, report, SKIP, focus="new")
    assert not failures, "\n\n".join(failures)
    assert sum(counts.values()) == MUTANTS


def test_the_newer_tables_are_the_force_and_higher_group_ones() -> None:
    tables = fuzz_tables.newer_tables()
    for name in ("four_bar_gravity.yaml", "six_bar_triad.yaml", "class_iv_group.yaml",
                 "problems/class1_fourbar_torque_limit.yaml"):
        assert name in tables
    assert "four_bar.yaml" not in tables and "problems/class1_fourbar_rocker.yaml" not in tables


def test_the_hang_limit_follows_the_baseline(monkeypatch: pytest.MonkeyPatch,
                                             tmp_path: Path) -> None:
    """A machine twice as slow (the known run takes twice as long) doubles the limit."""
    limits = []
    monkeypatch.setattr(fuzz_tables, "MIN_LIMIT", 0.0)
    for delay in (0.05, 0.1):
        def slow(argv: list[str], timeout: float, named: str | None = None,
                 seconds: float = delay) -> tuple[str, str]:
            time.sleep(seconds)
            return "exit 0", ""

        monkeypatch.setattr(fuzz_tables, "run_command", slow)
        limits.append(fuzz_tables.hang_limit(tmp_path, 100.0))
    assert limits[0] >= 5.0 and limits[1] >= 10.0
    assert limits[1] / limits[0] == pytest.approx(2.0, rel=0.4)


def test_a_refusal_that_names_no_file_is_a_finding(monkeypatch: pytest.MonkeyPatch) -> None:
    cli = importlib.import_module("synthesis.cli.main")

    def refuse(argv: list[str]) -> int:
        print("something is wrong")
        return 2

    monkeypatch.setattr(cli, "main", refuse)
    assert fuzz_tables.run_command(["check", "/tmp/x.yaml"], 5, "/tmp/x.yaml")[0] == \
        "exit 2 naming no file"

    def named(argv: list[str]) -> int:
        print("1 problem in /tmp/x.yaml: masses.2 'mass': must be positive")
        return 2

    monkeypatch.setattr(cli, "main", named)
    assert fuzz_tables.run_command(["check", "/tmp/x.yaml"], 5, "/tmp/x.yaml")[0] == "exit 2"


@pytest.mark.parametrize("seed", range(3))
def test_a_mutation_changes_the_table(seed: int) -> None:
    rng = random.Random(seed)
    tables = fuzz_tables.shipped_tables()
    for name in sorted(tables)[:6]:
        original = (fuzz_tables.TABLES / name).read_bytes()
        mutant = fuzz_tables.mutate(rng, name, original)
        assert mutant.data != original or "truncate" in mutant.operation
