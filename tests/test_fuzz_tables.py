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


def test_the_runner_tells_a_traceback_and_a_hang(monkeypatch) -> None:
    cli = importlib.import_module("synthesis.cli.main")

    def crash(argv):
        return {}["missing"]

    monkeypatch.setattr(cli, "main", crash)
    outcome, detail = fuzz_tables.run_command(["check", "x"], 5)
    assert outcome == "traceback" and "KeyError" in detail

    def loop(argv):
        while True:
            time.sleep(0.01)

    monkeypatch.setattr(cli, "main", loop)
    assert fuzz_tables.run_command(["check", "x"], 0.2)[0] == "hang"


def test_mutants_of_the_shipped_tables_end_cleanly(tmp_path) -> None:
    """A fixed set of mutants (seeded), each with a time limit."""
    failures: list[str] = []

    def report(index, outcome, mutant, argv, detail):
        failures.append(f"{outcome}: {mutant.origin} {mutant.operation} {argv}\n{detail}")

    fuzz_tables.copy_tables(tmp_path)
    counts = fuzz_tables.fuzz(MUTANTS, 0, TIMEOUT, tmp_path, report, SKIP)
    assert not failures, "\n\n".join(failures)
    assert sum(counts.values()) == MUTANTS


@pytest.mark.parametrize("seed", range(3))
def test_a_mutation_changes_the_table(seed) -> None:
    rng = random.Random(seed)
    tables = fuzz_tables.shipped_tables()
    for name in sorted(tables)[:6]:
        original = (fuzz_tables.TABLES / name).read_bytes()
        mutant = fuzz_tables.mutate(rng, name, original)
        assert mutant.data != original or "truncate" in mutant.operation
