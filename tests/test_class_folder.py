"""A class folder of student tables, each with one documented mistake: ``assur check``,
``assur batch`` and ``assur report`` give every table the same verdict, the same count and
the same first finding, and the batch row names the mistake.

Each table in ``tests/class_folder/`` starts with a header written when the mistake was
made: ``# mistake:`` what was changed, ``# verdict:`` the verdict the mistake calls for,
``# names:`` words of the catalogue message that names the mistake (empty for the correct
table).
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
from pathlib import Path
from typing import Any

import pytest

from synthesis.cli import main

FOLDER = Path(__file__).resolve().parent / "class_folder"
TABLES = sorted(FOLDER.glob("*.yaml"))


def _header(path: Path) -> dict[str, str]:
    """The documented mistake: the ``# key: value`` lines before the table."""
    found = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.startswith("# "):
            break
        key, _, value = line[2:].partition(":")
        found[key.strip()] = value.strip()
    return found


@pytest.fixture(scope="module")
def batch_rows(tmp_path_factory: pytest.TempPathFactory) -> dict[str, dict[str, Any]]:
    """The rows of ``assur batch --json`` on the folder, checked against its CSV."""
    out = tmp_path_factory.mktemp("batch") / "rows.csv"
    capture = io.StringIO()
    with contextlib.redirect_stdout(capture):
        assert main(["batch", str(FOLDER), "--json", "--csv", str(out), "--jobs", "1",
                     "--quiet"]) == 0
    rows = {row["file"]: row for row in json.loads(capture.getvalue())}
    with out.open(encoding="utf-8-sig", newline="") as handle:
        for record in csv.DictReader(handle):
            row = rows[record["file"]]
            assert (record["verdict"], record["problem"], int(record["problems"])) == (
                row["verdict"], row["problem"], row["problems"])
    return rows


def test_the_folder_holds_twenty_documented_mistakes() -> None:
    assert len(TABLES) >= 20
    for path in TABLES:
        header = _header(path)
        assert header.get("mistake") and header.get("verdict"), path.name


def _run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(args)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


@pytest.mark.slow
@pytest.mark.parametrize("path", TABLES, ids=[p.stem for p in TABLES])
def test_check_batch_and_report_agree(path: Path, batch_rows: dict[str, dict[str, Any]],
                                      capsys: pytest.CaptureFixture[str],
                                      tmp_path: Path) -> None:
    header = _header(path)
    row = batch_rows[path.name]
    assert row["verdict"] == header["verdict"]
    assert header["names"].lower() in row["problem"].lower()
    assert len(row["problem"]) <= 160 and str(FOLDER) not in row["problem"]
    check = _run(["check", str(path), "--json"], capsys)
    report = _run(["report", str(path), "--json", "--out", str(tmp_path / "r.html")], capsys)
    if row["verdict"] == "unreadable":  # no assessment: both refuse the file with its reason
        first = row["problem"].rstrip("…").split(":")[0]
        for code, _out, err in (check, report):
            assert code == 2 and first in err
        return
    assert check[0] == 0 and report[0] == 0
    found = json.loads(check[1])
    facts = json.loads(report[1])
    for record in (found, facts):
        assert (record["verdict"], record["problems"]) == (row["verdict"], row["problems"])
    assert found["findings"] == facts["findings"]
    if row["verdict"] == "correct":
        assert row["problem"] == "" and found["findings"] == []
        return
    first = found["findings"][0]
    text = f"{first['where']}: {first['message']}" if first["where"] else first["message"]
    assert row["problem"].rstrip("…") == text[:len(row["problem"].rstrip("…"))]


@pytest.mark.slow
def test_a_synthesis_problem_has_no_unverified_variants(capsys: pytest.CaptureFixture[str],
                                                        tmp_path: Path) -> None:
    """A problem's assembly variants are its givens, not a student's answers: the check of
    its initial design and the report of its designed mechanism do not call them unverified
    (the problem table has no sketch, so a student's table like it would be)."""
    problem = FOLDER.parent.parent / "input_tables" / "problems" / "class1_fourbar_rocker.yaml"
    assert "geometry" not in problem.read_text(encoding="utf-8")
    code, out, _ = _run(["check", str(problem), "--json"], capsys)
    assert code == 0 and json.loads(out)["verdict"] == "correct"
    code, out, _ = _run(["report", str(problem), "--json", "--out", str(tmp_path / "r.html")],
                        capsys)
    assert code == 0 and json.loads(out)["verdict"] == "correct"
