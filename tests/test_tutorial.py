"""Every command of the tutorials (English and Russian) runs and prints what they show, so they
cannot go stale.

The commands are taken from the ```console blocks of ``docs/tutorial.md`` and
``docs/tutorial.ru.md`` (lines starting with ``$ ``; a trailing ``# exit N`` states the
expected exit code, 0 otherwise). The ```sh blocks hold only the installation steps, which
cannot run inside a test; the test makes sure nothing else hides there. Each tutorial runs
in its own process, the two in parallel, in a scratch folder laid out like the repository
(its input tables are links to the repository's); every file the commands write must land
in ``work/``, and the repository must be left as it was.

A ```text block shows output of the last ``$ `` command above it. Its lines must be printed by
that command (standard output, then standard error) in the same order, each run of shown lines
as consecutive lines of the output; a line ``…`` alone marks an elision (any number of lines),
and a block may show an excerpt (an elision is implied before its first and after its last
line). Trailing spaces do not count. When the program's wording changes, re-syncing is editing
the shown lines of the document: the test prints the command's whole output on a mismatch.
"""

from __future__ import annotations

import ast
import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from cli_runner import RUNNER

#: One command's outcome as the runner prints it: argv, code, stdout, stderr.
Result = dict[str, Any]
#: Each tutorial's working folder and the outcomes of its commands.
Runs = dict[str, tuple[Path, list[Result]]]

ROOT = Path(__file__).resolve().parent.parent
TUTORIALS = ("tutorial.md", "tutorial.ru.md")
SETUP = ("sudo apt-get install", "git clone", "cd assur", "python3 -m venv",
         ". .venv/bin/activate", "pip install")



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


def shown_outputs(text: str) -> list[tuple[int, list[str]]]:
    """Each ```text block with the index (among the ``$ `` commands) of the command it shows."""
    shown, count = [], 0
    for language, body in re.findall(r"^```(\w*)\n(.*?)^```", text,
                                     flags=re.MULTILINE | re.DOTALL):
        if language == "console":
            count += sum(line.startswith("$ ") for line in body.splitlines())
        elif language == "text":
            assert count, "an output block before any command"
            shown.append((count - 1, [line.rstrip() for line in body.splitlines()]))
    return shown


def printed(shown: list[str], output: list[str]) -> bool:
    """Whether ``output`` holds the ``shown`` lines in order, each run between elisions
    (``…`` alone on a line) as consecutive lines; a shown line ending in ``…`` stands for
    every line that starts with the rest (the last digits of a number that depends on the
    platform's floating point, the end of a long line).

    >>> printed(["b", "…", "d"], ["a", "b", "c", "d", "e"])
    True
    >>> printed(["b", "d"], ["a", "b", "c", "d"])
    False
    >>> printed(["d", "…", "b"], ["b", "d"])
    False
    >>> printed(["Q = 9.85…"], ["Q = 9.85471e-05"])
    True
    """
    runs: list[list[str]] = [[]]
    for line in shown:
        if line.strip() in ("…", "..."):
            runs.append([])
        else:
            runs[-1].append(line)
    start = 0
    for run in (run for run in runs if run):
        found = next((i for i in range(start, len(output) - len(run) + 1)
                      if all(_same(a, b) for a, b in zip(run, output[i:i + len(run)]))), None)
        if found is None:
            return False
        start = found + len(run)
    return True


def _same(shown: str, line: str) -> bool:
    """A shown line against a printed one: equal, or its prefix when it ends in ``…``."""
    if shown.endswith("…") and shown.strip() != "…":
        return line.startswith(shown[:-1])
    return shown == line


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
        process = subprocess.Popen([sys.executable, "-c", RUNNER], cwd=work, env=env,
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
def test_shown_outputs_are_what_the_commands_print(name: str, runs: Runs) -> None:
    text = (ROOT / "docs" / name).read_text(encoding="utf-8")
    _work, results = runs[name]
    shown = shown_outputs(text)
    assert len(shown) >= 5
    stale = []
    for index, lines in shown:
        result = results[index]
        output = [line.rstrip() for line in (result["stdout"] + result["stderr"]).splitlines()]
        if not printed(lines, output):
            stale.append(f"`assur {shlex.join(result['argv'])}` shows\n" + "\n".join(lines)
                         + "\n--- but prints:\n" + "\n".join(output))
    assert not stale, f"{name}: output shown is not what the command prints:\n\n" + (
        "\n\n".join(stale))


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


def test_readme_python_block_gives_the_values_it_shows(monkeypatch):
    """A line of the README's Python block whose comment is a Python value shows what the
    expression before the comment gives; the block runs as written."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    (block,) = blocks(text, "python")
    monkeypatch.chdir(ROOT)
    namespace: dict[str, object] = {}
    lines, checked = block.splitlines(), 0
    for statement in ast.parse(block).body:
        comment = lines[statement.end_lineno - 1].partition("#")[2].strip()
        try:
            shown = ast.literal_eval(comment)
        except (ValueError, SyntaxError):
            shown = None
        if shown is not None and isinstance(statement, ast.Expr):
            assert eval(compile(ast.Expression(statement.value), "README", "eval"),
                        namespace) == shown, ast.unparse(statement)
            checked += 1
        else:
            exec(compile(ast.Module([statement], []), "README", "exec"), namespace)  # noqa: S102 (the README's own code)
    assert checked >= 1
