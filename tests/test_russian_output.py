"""Russian means Russian: every command, run with ``--lang ru`` on every shipped table, prints
no English word except what the user wrote.

The commands: ``check``, ``analyze`` (with ``--forces`` where the table has masses or
loads), ``report`` (the text of the page), ``synthesize`` (each problem of
``input_tables/problems``, a small search), ``batch`` (the folder of the shipped tables and
the tutorial's class folder) and the three built-in cases. They run in one process (no
start-up cost per command), with few positions over the cycle: the words do not depend on
their number.

A word is a run of two or more Latin letters. Allowed, and why:

- **the user's own text**: every key and value of the table file (of every table of the
  folder, for ``batch``), except the link names, which the shipped tables give in both
  languages (``name: {en: crank, ru: кривошип}``);
- **file names and paths** (a token with ``/`` or a file ending): what the user typed or
  where a file went;
- **quoted text** (``'general: allowable'``, ``'--omega W'``, ``'assur check'``): a field,
  an option or a command quoted as the user types it; and «…», a quotation of a published
  source (the header «Ns» of the impact paper's table, a patent's number);
- **options** (``--forces``): typed as written;
- **symbols and codes**: a token with a digit or an underscore (``l_i``, ``H_iH_j``,
  ``W_geom``, ``b_min.ad``, ``p5``, ``L1``; the finding codes ``E_OVERCONSTRAINED`` that a
  program filters on), the Roman numerals of group classes (``II``, ``III``, ``IV``), the functions of
  the formulas (``sin``, ``cos``, ``det``), and the column names of the identification table
  (``seq``, ``variant``, ``out_code``), which are the field names the student writes in
  the table file.
"""

from __future__ import annotations

import html
import json
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from cli_runner import RUNNER

ROOT = Path(__file__).resolve().parent.parent
TABLES = ROOT / "input_tables"
#: Positions over the cycle for analyze and report (the words do not depend on them).
POINTS = "24"
WORD = re.compile(r"(?<![\w'])[A-Za-z]{2,}(?![\w])")
SYMBOLS = frozenset({"II", "III", "IV", "VI", "sin", "cos", "det", "seq", "variant"})



def commands(work: Path) -> list[tuple[list[str], Path | None]]:
    """Each command with the table (or the folder of tables) it reads; None for a case."""
    found: list[tuple[list[str], Path | None]] = []
    for table in sorted(TABLES.glob("*.yaml")):
        if table.name.startswith("case_"):
            continue
        text = table.read_text(encoding="utf-8")
        found += [(["check", str(table)], table),
                  (["analyze", str(table), "--points", POINTS], table),
                  (["report", str(table), "--points", POINTS, "--quiet",
                    "--out", str(work / f"{table.stem}.html")], table)]
        if re.search(r"^(masses|loads):", text, flags=re.MULTILINE):
            found.append((["analyze", str(table), "--points", POINTS, "--forces",
                           "--omega", "10"], table))
    for problem in sorted((TABLES / "problems").glob("*.yaml")):
        found.append((["synthesize", str(problem), "--budget", "3", "--quiet",
                       "--out", str(work / f"{problem.stem}.result.yaml")], problem))
    found += [(["batch", str(TABLES), "--csv", str(work / "tables.csv")], TABLES),
              (["batch", str(ROOT / "docs" / "tutorial_class")], ROOT / "docs" / "tutorial_class"),
              (["case", "fourbar-velocity-ratio"], None),
              (["case", "tracker", "--budget", "0"], None),
              (["case", "impact"], None)]
    return [([argv[0], *argv[1:], "--lang", "ru"], table) for argv, table in found]


def _strings(data: Any, skip: bool = False) -> list[str]:
    """Every key and text value of a table, the link names left out."""
    if isinstance(data, dict):
        return [item for key, value in data.items() for item in (
            [str(key)] + ([] if skip and key == "name" else _strings(value, key == "links")))]
    if isinstance(data, list):
        return [item for value in data for item in _strings(value, skip)]
    return [str(data)] if isinstance(data, str) else []


def _page_text(path: Path) -> str:
    """The words a reader sees on a report page (no style, script or embedded pictures)."""
    page = path.read_text(encoding="utf-8")
    page = re.sub(r"<(style|script)\b.*?</\1>", " ", page, flags=re.DOTALL)
    page = re.sub(r"<[^>]+>", " ", page)
    return html.unescape(page)


def english_words(text: str, user: set[str]) -> list[str]:
    """The words of ``text`` outside the allow-list of the module docstring.

    >>> english_words("ползун 3: 85 мм, l_i ≤ 'general: allowable', III(base 4)", set())
    ['base']
    >>> english_words("записан: /tmp/w/four_bar.html; --forces; min запас", set())
    ['min']
    >>> english_words("b_min.ad = 25°, «Ns», 'assur case tracker --table FILE'", set())
    []
    """
    text = re.sub(r"'[^'\n]*'|«[^»\n]*»", " ", text)
    text = re.sub(r"\S*_\S*", " ", text)
    text = re.sub(r"\S*(/|\.(yaml|html|csv|png|svg|json)\b)\S*", " ", text)
    text = re.sub(r"--[\w-]+", " ", text)
    return [word for word in WORD.findall(text)
            if word not in user and word not in SYMBOLS]


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> list[tuple[dict[str, Any], Path | None, Path]]:
    work = tmp_path_factory.mktemp("ru")
    listed = commands(work)
    process = subprocess.run([sys.executable, "-c", RUNNER], cwd=work, text=True,
                             input=json.dumps([argv for argv, _ in listed]),
                             capture_output=True, env={**os.environ, "MPLBACKEND": "Agg"},
                             timeout=1200, check=False)
    assert process.returncode == 0, process.stderr[-3000:]
    return [({**result, "text": result["stdout"] + result["stderr"]}, table, work)
            for result, (_, table) in zip(json.loads(process.stdout), listed, strict=True)]


@pytest.mark.slow
def test_every_command_on_every_table_answers_in_russian(runs):
    found = []
    for result, table, _work in runs:
        argv = result["argv"]
        if result["code"] == 3:
            continue  # an internal error: test_no_command_fails_inside
        text = result["text"]
        if argv[0] == "report" and result["code"] == 0:
            text += _page_text(Path(argv[argv.index("--out") + 1]))
        user: set[str] = set()
        for path in [] if table is None else sorted(table.glob("*.yaml")) if table.is_dir() \
                else [table]:
            try:
                data = yaml.safe_load(path.read_text(encoding="utf-8"))
            except yaml.YAMLError:
                continue  # a broken table of the class folder: its words are its own
            user |= set(WORD.findall(" ".join(_strings(data))))
        words = english_words(text, user)
        if words:
            lines = [line.strip() for line in text.splitlines()
                     if any(re.search(rf"\b{w}\b", line) for w in words)]
            found.append(f"assur {' '.join(argv)}: {sorted(set(words))}\n    "
                         + "\n    ".join(lines[:4]))
    assert not found, "English in Russian output:\n" + "\n".join(found)


@pytest.mark.slow
def test_no_command_fails_inside(runs):
    failed = [(r["argv"], r["text"][-300:]) for r, _, _ in runs if r["code"] not in (0, 1, 2)]
    assert not failed, failed


@pytest.mark.slow
def test_every_command_ran(runs):
    names = {result["argv"][0] for result, _, _ in runs}
    assert names == {"check", "analyze", "report", "synthesize", "batch", "case"}
    assert any("--forces" in result["argv"] for result, _, _ in runs)


def test_link_names_in_both_languages_are_read_and_checked(tmp_path):
    from assur import TableError, load_chain

    table = tmp_path / "named.yaml"
    table.write_text(
        "mechanism:\n  links:\n    - {id: 0, name: {en: frame, ru: стойка}}\n"
        "    - {id: 1, name: {en: crank, ru: кривошип}}\n    - {id: 2, name: rod}\n"
        "    - 3\n  pairs:\n"
        "    - {id: A, type: R, links: [0, 1]}\n    - {id: B, type: R, links: [1, 2]}\n"
        "    - {id: C, type: R, links: [2, 3]}\n    - {id: D, type: R, links: [3, 0]}\n"
        "  inputs: [1]\n", encoding="utf-8")
    chain = load_chain(table)
    assert chain.link_names("ru") == {0: "стойка", 1: "кривошип", 2: "rod"}
    assert chain.link_names("en") == {0: "frame", 1: "crank", 2: "rod"}
    table.write_text(table.read_text(encoding="utf-8").replace("ru: кривошип", "rus: кривошип")
                     .replace("en: frame", "en: 5"), encoding="utf-8")
    with pytest.raises(TableError) as info:
        load_chain(table)
    text = str(info.value)
    assert "mechanism.links[1].name" in text and "did you mean 'ru'" in text
    assert "mechanism.links[0].name 'en'" in text and "expected a text" in text
