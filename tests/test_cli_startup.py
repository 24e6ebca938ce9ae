"""What ``assur check`` loads and reads: no module it does not use (networkx only for a chain
that needs the general structural path), each table file once, the text catalogue compiled
once and then read from the cache.

The modules are read from ``sys.modules`` of a fresh interpreter after the command ran; the
files opened are counted by an audit hook (``open`` events of the interpreter), so a second
read is seen whatever function makes it.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

import pytest
from test_catalogue import fresh_catalogues  # noqa: F401 - a fixture

from assur import text
from assur.io.chain_table import chain_from_dict, load_chain
from synthesis import load_problem
from synthesis.app.assess import assess

ROOT = Path(__file__).resolve().parents[1]
TABLE = ROOT / "input_tables" / "four_bar.yaml"
PROBLEM = ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml"
#: Packages that ``assur check`` of a small table of dyads has no use for (it runs the
#: existence check over the cycle behind its verdict: the kinematic analysis, with the
#: solutions of every kind of group, is loaded).
UNUSED = ("networkx", "scipy", "matplotlib", "tqdm", "dask", "assur.forces", "numba")
#: Runs ``assur check`` and prints its output and the modules loaded (JSON) as its last line.
CHECK = ("import io, json, sys, contextlib\n"
         "from synthesis.cli import main\n"
         "with contextlib.redirect_stdout(io.StringIO()) as out:\n"
         "    code = main(['check', sys.argv[1]])\n"
         "print(json.dumps({'code': code, 'out': out.getvalue(), 'modules': sorted(sys.modules)}))\n")
#: A four-bar with a link hung on the coupler by one hinge: the general path finds it idle.
IDLE = """mechanism:
  pairs:
    - {id: A, type: R, links: [0, 1]}
    - {id: B, type: R, links: [1, 2]}
    - {id: C, type: R, links: [2, 3]}
    - {id: D, type: R, links: [3, 0]}
    - {id: E, type: R, links: [2, 4]}
  inputs: [1]
"""


def _run_check(cache: Path, table: Path = TABLE) -> tuple[int, str, set[str]]:
    env = dict(os.environ, PYTHONPATH=str(ROOT), XDG_CACHE_HOME=str(cache))
    done = subprocess.run([sys.executable, "-c", CHECK, str(table)], env=env, cwd=ROOT,
                          capture_output=True, text=True, check=True, timeout=120)
    found = json.loads(done.stdout.strip().splitlines()[-1])
    return found["code"], found["out"], set(found["modules"])


def _check_modules(cache: Path) -> tuple[int, set[str]]:
    code, _, modules = _run_check(cache)
    return code, modules


def _loaded(package: str, modules: set[str]) -> bool:
    return any(m == package or m.startswith(package + ".") for m in modules)


def test_check_loads_only_what_it_uses_and_the_catalogue_from_the_cache(tmp_path: Path) -> None:
    code, first = _check_modules(tmp_path)
    assert code == 0
    # the command did its work: the structure was analysed and the catalogue compiled
    assert {"assur.structure.analysis", "numpy", "yaml"} <= first
    assert _loaded("babel", first)
    assert sorted((tmp_path / "assur").glob("en-*.mo"))
    assert [name for name in UNUSED if _loaded(name, first)] == []
    # a second run reads the compiled catalogue with gettext alone
    code, second = _check_modules(tmp_path)
    assert code == 0 and not _loaded("babel", second)
    assert [name for name in UNUSED if _loaded(name, second)] == []


@pytest.mark.parametrize("name", ["slider_crank", "course_11_link_table"])
def test_check_of_a_table_of_dyads_loads_no_graph_library(name: str, tmp_path: Path) -> None:
    """A slider (a prismatic pair: no loop of them to look for) and an identification table."""
    code, out, modules = _run_check(tmp_path, ROOT / "input_tables" / f"{name}.yaml")
    assert code == 0 and "Structure formula: I(0,1) → II" in out
    assert [package for package in UNUSED if _loaded(package, modules)] == []


def test_check_of_an_open_chain_takes_the_general_path(tmp_path: Path) -> None:
    table = tmp_path / "idle.yaml"
    table.write_text(IDLE, encoding="utf-8")
    code, out, modules = _run_check(tmp_path, table)
    # W = 3·4 − 2·5 = 2 with one input; link 4 hangs on the one hinge E (a bridge)
    assert code == 0 and "W = 3n − 2p5 − p4 = 3·4 − 2·5 − 0 = 2" in out
    idle = [line for line in out.splitlines() if "W_IDLE_LINK" in line]
    assert len(idle) == 1 and "link 4 " in idle[0]
    assert "networkx" in modules


@pytest.mark.usefixtures("fresh_catalogues")
def test_an_edited_catalogue_is_compiled_again(tmp_path, monkeypatch) -> None:
    for lang in ("en", "ru"):
        shutil.copy(text.LOCALE / f"{lang}.po", tmp_path / f"{lang}.po")
    monkeypatch.setattr(text, "LOCALE", tmp_path)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    assert text.render("cli.interrupted", "en") == "interrupted"
    po = tmp_path / "en.po"
    po.write_text(po.read_text(encoding="utf-8").replace(
        'msgid "cli.interrupted"\nmsgstr "interrupted"',
        'msgid "cli.interrupted"\nmsgstr "stopped by the user"'), encoding="utf-8")
    text.catalogue.cache_clear()
    assert text.render("cli.interrupted", "en") == "stopped by the user"
    assert len(list((tmp_path / "cache" / "assur").glob("en-*.mo"))) == 2
    # a damaged copy in the cache is compiled again, not shown to the user
    for compiled in (tmp_path / "cache" / "assur").glob("en-*.mo"):
        compiled.write_bytes(b"not a catalogue")
    text.catalogue.cache_clear()
    assert text.render("cli.interrupted", "en") == "stopped by the user"


#: The files opened while an audit hook is watching (one hook per process, switched here).
_OPENED: list[list[str]] = []


def _audit(event: str, args: tuple) -> None:
    if event == "open" and _OPENED and isinstance(args[0], (str, os.PathLike)):
        _OPENED[-1].append(os.path.realpath(args[0]))


sys.addaudithook(_audit)


@contextmanager
def _opened() -> Iterator[list[str]]:
    _OPENED.append([])
    try:
        yield _OPENED[-1]
    finally:
        _OPENED.pop()


@pytest.mark.parametrize("path", [TABLE, PROBLEM], ids=["chain", "problem"])
def test_assess_reads_a_table_once(path: Path) -> None:
    with _opened() as files:
        found = assess(path, points=None)
    assert files.count(os.path.realpath(path)) == 1
    # the chain is the one that the table's own reader gives
    if path == PROBLEM:
        problem = load_problem(path)
        expected = chain_from_dict(problem.mechanism_table(problem.initial), source=str(path))
        # with the problem's table 1.5, which the assessment checks
        expected = replace(expected, group_models=tuple(
            row.as_row() for row in problem.group_models) or None)
    else:
        expected = load_chain(path)
    assert found.chain == expected


@pytest.mark.parametrize("path", [TABLE, PROBLEM], ids=["chain", "problem"])
def test_the_coursework_report_reads_its_table_once(path: Path) -> None:
    from synthesis.app.coursework.report import build_report

    with _opened() as files:
        report = build_report(path, points=12, budget=4)
    assert files.count(os.path.realpath(path)) == 1
    assert report.source == str(path)
