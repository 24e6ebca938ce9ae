"""Every shipped mechanism table runs through ``assur check`` and ``assur analyze``.

A table meant to fail says so in a comment line ``# expected: check N, analyze M (why)``
among its leading comments; every other table must give exit code 0 to both commands. The
commands run in-process, as a user runs them.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from synthesis.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXPECTED = re.compile(r"^#\s*expected:\s*check (\d), analyze (\d)\b", re.IGNORECASE)

def _tables() -> list[Path]:
    return sorted(path for path in (ROOT / "input_tables").glob("*.yaml")
                  if not path.name.startswith("case_"))


def expected_codes(text: str) -> dict[str, int]:
    """The exit codes a table's leading comments promise (0 for both when they say nothing)."""
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        found = EXPECTED.match(line)
        if found:
            return {"check": int(found.group(1)), "analyze": int(found.group(2))}
    return {"check": 0, "analyze": 0}


def test_expected_comment_is_read() -> None:
    assert expected_codes("# a table\n# Expected: check 0, analyze 2 (two inputs)\nx: 1\n") \
        == {"check": 0, "analyze": 2}
    assert expected_codes("# a table\nx: 1\n# expected: check 2, analyze 2\n") \
        == {"check": 0, "analyze": 0}


@pytest.mark.parametrize("path", _tables(), ids=lambda path: path.name)
def test_every_table_runs(path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    want = expected_codes(path.read_text(encoding="utf-8"))
    rel = path.relative_to(ROOT).as_posix()
    commands = {"check": ["check", str(path), "--json"],
                "analyze": ["analyze", str(path), "--json", "--points", "24"]}
    for command, argv in commands.items():
        code = main(argv)
        out, err = capsys.readouterr()
        assert code == want[command], f"assur {command} {rel}: exit {code}\n{err}"
        if code == 0:
            assert json.loads(out), f"assur {command} {rel}: no JSON"
        else:
            assert err.strip() and "Traceback" not in err, f"assur {command} {rel}: {err!r}"
