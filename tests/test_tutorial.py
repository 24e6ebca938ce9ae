"""Every command of the tutorials (English and Russian) runs, so they cannot go stale.

The commands are taken from the ```console blocks of ``docs/tutorial.md`` and
``docs/tutorial.ru.md`` (lines starting with ``$ ``; a trailing ``# exit N`` states the
expected exit code, 0 otherwise). The ```sh blocks hold only the installation steps, which
cannot run inside a test; the test makes sure nothing else hides there. Each tutorial runs
in its own process, the two in parallel, in a scratch folder laid out like the repository
(its input tables are links to the repository's); every file the commands write must land
in ``work/``, and the repository must be left as it was.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

#: One command's outcome as the runner prints it: argv, code, stdout, stderr.
Result = dict[str, Any]
#: Each tutorial's working folder and the outcomes of its commands.
Runs = dict[str, tuple[Path, list[Result]]]

ROOT = Path(__file__).resolve().parent.parent
TUTORIALS = ("tutorial.md", "tutorial.ru.md")
SETUP = ("sudo apt-get install", "git clone", "cd assur", "python3 -m venv",
         ". .venv/bin/activate", "pip install")

# Runs the commands of one tutorial in one process (no start-up cost per command) and
# prints, as JSON, the exit code and the output of each.
_RUNNER = r"""
import contextlib, io, json, sys
import matplotlib
matplotlib.use("Agg")
from synthesis.cli import main
results = []
for argv in json.load(sys.stdin):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    results.append({"argv": argv, "code": code, "stdout": out.getvalue(),
                    "stderr": err.getvalue()})
json.dump(results, sys.stdout)
"""


def blocks(text: str, language: str) -> list[str]:
    """The contents of the fenced blocks of one language."""
    return re.findall(rf"^```{language}\n(.*?)^```", text, flags=re.MULTILINE | re.DOTALL)


def commands(text: str) -> list[tuple[list[str], int]]:
    """The ``$ `` commands of the console blocks with their expected exit codes."""
    found = []
    for block in blocks(text, "console"):
        for line in block.splitlines():
            if not line.startswith("$ "):
                continue
            command, _, comment = line[2:].partition("#")
            code = re.fullmatch(r"\s*exit (\d+)\s*", comment)
            argv = shlex.split(command)
            assert argv[0] == "assur", f"only assur commands belong in console blocks: {line}"
            found.append((argv[1:], int(code.group(1)) if code else 0))
    return found


def _workspace(root: Path) -> Path:
    """A scratch folder laid out like the repository for the tutorial's paths."""
    root.mkdir()
    (root / "input_tables").symlink_to(ROOT / "input_tables")
    (root / "docs").mkdir()
    (root / "docs" / "tutorial_class").symlink_to(ROOT / "docs" / "tutorial_class")
    return root


def _files(root: Path) -> set[str]:
    """Every file under ``root`` (links to folders not followed), relative to it."""
    return {p.relative_to(root).as_posix() for p in root.rglob("*") if not p.is_dir()}


def _repository_state() -> tuple[set[str], ...]:
    """The files of the repository's folders that the tutorial reads or could write."""
    return tuple(_files(ROOT / folder) for folder in ("docs", "input_tables"))


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> Runs:
    before = _repository_state()
    base = tmp_path_factory.mktemp("tutorials")
    env = {**os.environ, "MPLBACKEND": "Agg"}
    started = {}
    for name in TUTORIALS:
        text = (ROOT / "docs" / name).read_text(encoding="utf-8")
        work = _workspace(base / name.replace(".", "_"))
        process = subprocess.Popen([sys.executable, "-c", _RUNNER], cwd=work, env=env,
                                   stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True)
        argvs = [argv for argv, _ in commands(text)]
        started[name] = (work, process, json.dumps(argvs))
    results = {}
    for name, (work, process, payload) in started.items():
        out, err = process.communicate(payload, timeout=600)
        assert process.returncode == 0, err
        results[name] = (work, json.loads(out))
    assert _repository_state() == before, "a tutorial command wrote into the repository"
    return results


@pytest.mark.slow
@pytest.mark.parametrize("name", TUTORIALS)
def test_every_file_written_goes_into_the_working_folder(name: str, runs: Runs) -> None:
    work, results = runs[name]
    written = _files(work) - {"input_tables", "docs/tutorial_class"}
    assert written and all(path.startswith("work/") for path in written), sorted(written)
    announced = {line.split(": ", 1)[1] for result in results
                 for line in result["stderr"].splitlines()
                 if line.startswith(("written: ", "записан: "))}
    assert announced == written  # one ``written: PATH`` line for every file, no other


@pytest.mark.parametrize("name", TUTORIALS)
def test_setup_blocks_hold_only_installation(name: str) -> None:
    text = (ROOT / "docs" / name).read_text(encoding="utf-8")
    lines = [line for block in blocks(text, "sh") for line in block.splitlines() if line]
    assert lines, "the installation steps are missing"
    for line in lines:
        assert line.startswith(SETUP), f"{name}: not an installation step: {line}"


@pytest.mark.slow
@pytest.mark.parametrize("name", TUTORIALS)
def test_every_command_runs(name: str, runs: Runs) -> None:
    text = (ROOT / "docs" / name).read_text(encoding="utf-8")
    expected = commands(text)
    assert len(expected) >= 12
    _work, results = runs[name]
    for (argv, code), result in zip(expected, results):
        assert result["argv"] == argv
        assert result["code"] == code, (argv, result["stderr"][-2000:])


@pytest.mark.slow
@pytest.mark.parametrize("name", TUTORIALS)
def test_pictures_exist_and_are_drawn_by_the_commands(name: str, runs: Runs) -> None:
    text = (ROOT / "docs" / name).read_text(encoding="utf-8")
    work, _results = runs[name]
    pictures = re.findall(r"!\[[^\]]*\]\((img/[^)]+)\)", text)
    assert len(pictures) >= 6
    for picture in pictures:
        assert (ROOT / "docs" / picture).is_file(), picture
        drawn = work / "work" / picture.removeprefix("img/")
        if not picture.endswith("course_report.png"):  # a browser screenshot of the report
            assert drawn.is_file(), f"no command draws {picture}"


@pytest.mark.slow
def test_russian_tutorial_prints_russian(runs: Runs) -> None:
    """Every command of the Russian tutorial answers in Russian (``--lang ru``)."""
    work, results = runs["tutorial.ru.md"]
    cyrillic = re.compile("[а-яё]", re.IGNORECASE)
    expected = {tuple(argv): code for argv, code in commands(
        (ROOT / "docs" / "tutorial.ru.md").read_text(encoding="utf-8"))}
    for result in results:
        argv = result["argv"]
        if "--help" in argv or expected[tuple(argv)] != 0:
            continue
        assert "--lang" in argv and argv[argv.index("--lang") + 1] == "ru", argv
        if argv[0] == "report":
            page = work / argv[argv.index("--out") + 1]
            assert '<html lang="ru">' in page.read_text(encoding="utf-8")
        else:
            assert cyrillic.search(result["stdout"]), argv
