"""One slip, one message: every shipped table with ONE typical mistake, and the messages each gets.

Each mutant is a table of ``input_tables/`` changed in one place by one of the mistakes a
student makes:

* ``lookalike-key`` / ``lookalike-value``: a Latin letter of a key or of a text value typed
  as the Cyrillic letter drawn the same;
* ``decimal-comma``: a number written with a comma (``90,27``), in the file's own text;
* ``misspelt-key``: two neighbouring letters of a key swapped;
* ``wrong-type``: a number given as a word, a list as a number, a mapping as a list;
* ``out-of-range``: a group kind ``L`` or an assembly ``variant`` of 7, a pair type ``Q``,
  another number of 1e12;
* ``missing-row``: one row of a list of rows deleted;
* ``swapped-columns``: the values of two neighbouring fields of a row swapped;
* ``wrong-command``: the unchanged table given to the command of another kind of table.

The matching command runs in-process and the findings it prints (the ``  - `` lines of a
refusal or of the identification check) are counted, less those the unchanged table gets.
A mistake that gets more than one finding is listed with them: one slip should get one
message, and a finding that only follows from an earlier one is noise.

Run (``--sites`` mutants per table and mistake; the list of cascades, then the counts)::

    PYTHONPATH=. python benchmarks/one_slip.py --sites 4
"""

from __future__ import annotations

import argparse
import contextlib
import io
import random
import re
import sys
import tempfile
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml  # type: ignore[import-untyped]

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_tables import (
    LOOK_ALIKES,
    TABLES,
    command,
    copy_tables,
    shipped_tables,
    tree_paths,
)

#: A number in a line of YAML (outside its comment), with its fraction if it has one.
_NUMBER = re.compile(r"(?<![\w.#-])(\d+)\.(\d+)(?![\w.])")
#: Fields whose value is a small number of a fixed range: the value that is out of it.
_RANGED = {"L": 7, "variant": 7, "type": "Q"}


@dataclass(frozen=True)
class Slip:
    """One table with one mistake: its origin, the mistake, where, and the mutated text."""

    origin: str
    mistake: str
    where: str
    text: str


def _at(tree: Any, path: tuple[Any, ...]) -> Any:
    for step in path:
        tree = tree[step]
    return tree


def _lookalike(text: str) -> str | None:
    """``text`` with its first letter that has a Cyrillic look-alike replaced (None if none)."""
    for index, letter in enumerate(text):
        other = letter.translate(LOOK_ALIKES)
        if other != letter:
            return text[:index] + other + text[index + 1:]
    return None


def _misspelt(text: str) -> str | None:
    """``text`` with two neighbouring distinct letters in its middle swapped."""
    for index in range(1, len(text) - 2):
        a, b = text[index], text[index + 1]
        if a != b and a.isalpha() and b.isalpha():
            return text[:index] + b + a + text[index + 2:]
    return None


def _renamed(parent: dict[Any, Any], old: Any, new: Any) -> None:
    """Rename a key of ``parent`` in place, keeping its position."""
    items = list(parent.items())
    parent.clear()
    parent.update({(new if key == old else key): value for key, value in items})


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


#: One change of a parsed table: (what: rename, set, swap or pop; the path; its argument).
Edit = tuple[str, tuple[Any, ...], Any]


def _tree_slips(tree: Any) -> Iterator[tuple[str, str, Edit]]:
    """Every one-place mistake of a parsed table: (mistake, where, the change)."""
    for path in tree_paths(tree):
        parent, key = _at(tree, path[:-1]), path[-1]
        value = parent[key]
        where = ".".join(map(str, path))
        if isinstance(parent, dict) and isinstance(key, str):
            look, typo = _lookalike(key), _misspelt(key)
            if look:
                yield "lookalike-key", where, ("rename", path, look)
            if typo:
                yield "misspelt-key", where, ("rename", path, typo)
            if key in _RANGED and not isinstance(value, (list, dict)):
                yield "out-of-range", where, ("set", path, _RANGED[key])
            keys = list(parent)
            position = keys.index(key)
            if position + 1 < len(keys) and isinstance(_at(tree, path[:-2]) if len(path) > 1
                                                       else None, list):
                other = keys[position + 1]
                yield "swapped-columns", f"{where}<->{other}", ("swap", path, other)
        look = _lookalike(value) if isinstance(value, str) else None
        if look:
            yield "lookalike-value", where, ("set", path, look)
        if _is_number(value):
            yield "wrong-type", where, ("set", path, "ten")
            if not (isinstance(key, str) and key in _RANGED):
                yield "out-of-range", where, ("set", path, 10 ** 12)
        elif isinstance(value, list) and value:
            yield "wrong-type", where, ("set", path, 5)
            if isinstance(value[0], dict):
                for index in range(len(value)):
                    yield "missing-row", f"{where}[{index}]", ("pop", path, index)
        elif isinstance(value, dict) and value:
            yield "wrong-type", where, ("set", path, [1, 2])


def _apply(tree: Any, edit: Edit) -> None:
    """Make one change of :func:`_tree_slips` in ``tree``."""
    what, path, argument = edit
    parent, key = _at(tree, path[:-1]), path[-1]
    if what == "rename":
        _renamed(parent, key, argument)
    elif what == "set":
        parent[key] = argument
    elif what == "swap":
        parent[key], parent[argument] = parent[argument], parent[key]
    else:
        parent[key].pop(argument)


def _comma_slips(text: str) -> Iterator[tuple[str, str]]:
    """Every number with a decimal point of the text (outside comments) written with a comma."""
    offset = 0
    for number, line in enumerate(text.splitlines(keepends=True), start=1):
        code = line.split("#", 1)[0]
        for match in _NUMBER.finditer(code):
            at = offset + match.start()
            changed = text[:at] + f"{match[1]},{match[2]}" + text[offset + match.end():]
            yield f"line {number} {match[0]}", changed
        offset += len(line)


def slips(origin: str, text: str, sites: int, rng: random.Random) -> list[Slip]:
    """Up to ``sites`` mutants of each mistake for one table (drawn with ``rng``)."""
    by_mistake: dict[str, list[Slip]] = {}
    tree = yaml.safe_load(text)
    for mistake, where, edit in list(_tree_slips(tree)):
        copy = yaml.safe_load(text)
        _apply(copy, edit)
        by_mistake.setdefault(mistake, []).append(Slip(origin, mistake, where, yaml.safe_dump(
            copy, allow_unicode=True, sort_keys=False, default_flow_style=None)))
    for where, changed in _comma_slips(text):
        by_mistake.setdefault("decimal-comma", []).append(
            Slip(origin, "decimal-comma", where, changed))
    out: list[Slip] = []
    for found in by_mistake.values():
        out += found if len(found) <= sites else rng.sample(found, sites)
    return out


def findings(argv: list[str]) -> tuple[int, list[str]]:
    """Run ``assur ARGV`` in-process: its exit code and the findings it printed."""
    from synthesis.cli.main import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    if argv[0] not in ("check", "analyze") and code != 2:
        return code, []  # a run's own notes (hints of a search), not findings
    return code, [line[4:] for line in out.getvalue().splitlines() if line.startswith("  - ")]


def commands(kind: str, path: str) -> list[list[str]]:
    """The commands that read a table of ``kind``: ``check`` and ``analyze`` for a chain."""
    if kind == "chain":
        return [["check", path], ["analyze", path, "--points", "12"]]
    return [[arg for arg in command(kind, path, random.Random(0)) if arg != "--json"]]


def census(sites: int, seed: int, folder: Path, only: set[str] | None = None,
           report: Callable[[Slip, list[str], list[str]], None] | None = None) -> Counter[str]:
    """Run every slip; count by mistake the mutants with 0, 1 and more findings.

    ``report(slip, argv, extra)`` is called for every mutant with more than one new finding.
    """
    copy_tables(folder)
    rng = random.Random(seed)
    counts: Counter[str] = Counter()
    tables = shipped_tables()
    for origin, kind in sorted(tables.items()):
        if only and kind not in only:
            continue
        text = (TABLES / origin).read_text(encoding="utf-8")
        target = folder / Path(origin).parent / "slip.yaml"
        base = {tuple(argv[:1]): findings(argv)[1]
                for argv in commands(kind, str(folder / origin))}
        runs = [(slip, commands(kind, str(target))) for slip in slips(origin, text, sites, rng)]
        runs += [(Slip(origin, "wrong-command", other, text),
                  [[arg for arg in command(other, str(target), rng) if arg != "--json"]])
                 for other in sorted(set(tables.values()) - {kind})]
        for slip, argvs in runs:
            target.write_text(slip.text, encoding="utf-8")
            worst: list[str] = []
            for argv in argvs:
                extra = findings(argv)[1]
                for line in base.get(tuple(argv[:1]), []):  # what the unchanged table gets
                    if line in extra:
                        extra.remove(line)
                if len(extra) > len(worst):
                    worst, shown = extra, argv
            counts[f"{slip.mistake} {min(len(worst), 2)}"] += 1
            if len(worst) > 1 and report is not None:
                report(slip, shown, worst)
        target.unlink(missing_ok=True)
    return counts


def main(argv: list[str] | None = None) -> int:
    """Print every slip that gets more than one finding, then the counts by mistake."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sites", type=int, default=4, help="mutants per table and mistake")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--only", nargs="*", help="kinds of table (chain, problem, tracker, …)")
    args = parser.parse_args(argv)

    def report(slip: Slip, argv: list[str], extra: list[str]) -> None:
        print(f"{slip.origin}: {slip.mistake} at {slip.where} ({argv[0]}): {len(extra)}")
        for line in extra:
            print(f"    - {line[:200]}")

    with tempfile.TemporaryDirectory() as folder:
        counts = census(args.sites, args.seed, Path(folder), set(args.only or ()) or None,
                        report)
    mistakes = sorted({key.rsplit(" ", 1)[0] for key in counts})
    print(f"\n{'mistake':18s} {'0 findings':>10s} {'1':>5s} {'>1':>5s}")
    for mistake in mistakes:
        print(f"{mistake:18s} {counts[mistake + ' 0']:10d} {counts[mistake + ' 1']:5d} "
              f"{counts[mistake + ' 2']:5d}")
    total = sum(counts.values())
    many = sum(n for key, n in counts.items() if key.endswith(" 2"))
    print(f"{'all':18s} {total - many:>16d} {many:5d}   ({many} of {total} slips get >1)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
