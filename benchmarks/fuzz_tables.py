"""Mutation fuzzer over every shipped table: no mutant may end in a traceback or a hang.

Each mutant is a shipped table of ``input_tables/`` (a mechanism table, a synthesis problem
or a built-in case's table) changed once: a key deleted or renamed with look-alike letters,
a value replaced (NaN, ±inf, 1e308, 5e-324, null, a list, a mapping, a decimal comma, a
Cyrillic look-alike), a list item duplicated, a value nested thousands deep, or the bytes cut,
flipped, duplicated, re-encoded in Windows-1251 or joined with random bytes.  The matching
command runs in-process (``synthesis.cli.main.main``) with small budgets and short grids; any
exit code other than 0, 1 or 2, any exception that escapes it, an exit 2 that does not name
the mutated file, or a run longer than the hang limit is a failure.  Now and then a table
goes to the wrong command.

``--focus new`` mutates only the newer features: the force sections (``masses:``,
``loads:``, ``gravity:``) and a problem's ``forces:``, the higher-group tables (triads,
class IV groups), and the options ``--omega``, ``--points``, ``--frames``, ``--at`` (and
``--scheduler`` with ``--scheduler-options``) given odd values on an unchanged table.

The hang limit is load-proof: at the start of every chunk of mutants the worker times a
known run (:data:`BASELINE`, the shipped torque-limited problem, budget 2) and a mutant hangs
when it runs longer than ``--hang-factor`` times that baseline (never less than
:data:`MIN_LIMIT`): a machine loaded by other jobs slows the baseline as much as the mutant.

Run (the counts by outcome are printed at the end; failures with their mutants are kept)::

    PYTHONPATH=. python benchmarks/fuzz_tables.py --mutants 10000 --workers 2
    PYTHONPATH=. python benchmarks/fuzz_tables.py --mutants 2000 --focus new --seed 7

The quick profile of the test suite (``tests/test_fuzz_tables.py``) runs the same engine.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import multiprocessing
import random
import shutil
import signal
import sys
import tempfile
import time
import traceback
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parent.parent
TABLES = ROOT / "input_tables"

#: Latin letters and the Cyrillic letters drawn the same.
LOOK_ALIKES = str.maketrans("aceopxyABCEHKMOPTX", "асеорхуАВСЕНКМОРТХ")
#: Values a mutation puts in place of a field's value.
ODD_VALUES: tuple[Any, ...] = (
    None, math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, 0, -1, 10 ** 12, 7, 2 ** 64,
    "", "x", "90,27", "1e999", True, [], [1, 2], [[1, 2], [3]], {}, {"a": 1}, "A",
)


#: Kinds whose solved tables take longer than the others: their time-limit factor.
SLOW = {"fourbar_velocity_ratio": 5.0}
#: Commands that do more than the baseline's kind of run: their time-limit factor (a report
#: analyses, draws and searches the whole coursework).
SLOW_COMMANDS = {"report": 5.0}
#: The known run timed at the start of every chunk: the unit of the hang limit.
BASELINE = ("problems/class1_fourbar_torque_limit.yaml", "problem")
#: The hang limit is never less than this (seconds): a very fast baseline still leaves time
#: for a mutant that imports a module on first use.
MIN_LIMIT = 10.0
#: The top-level sections of the newer features that ``--focus new`` mutates.
NEW_SECTIONS = ("masses", "loads", "gravity", "forces", "general")
#: Odd values of the command-line options ``--focus new`` gives.
ODD_OPTIONS: dict[str, tuple[str, ...]] = {
    "--omega": ("nan", "inf", "-inf", "1e300", "0", "-10", "ten", "1e-300", "5e-324", "10",
                "1e9", "1e10", ""),
    "--points": ("0", "1", "2", "-5", "100000000000", "100001", "1e3", "x", "12", "36"),
    "--frames": ("0", "-1", "1", "2", "3601", "1e9", "nan", "x"),
    "--at": ("inf", "-inf", "nan", "1e300", "-1e9", "720", "x", "45"),
    "--scheduler": ("tls://127.0.0.1:1", "tcp://127.0.0.1:abc", "tcp://:::", "local:0",
                    "local:100000", "local:-1", "ftp://x", "", "local:x", "tcp://127.0.0.1:1"),
}


@dataclass(frozen=True)
class Mutant:
    """One mutated table: where it came from, what was done, and its bytes."""

    origin: str
    operation: str
    data: bytes


# ------------------------------------------------------------------------ shipped tables


def shipped_tables() -> dict[str, str]:
    """Every shipped table (path relative to ``input_tables/``) → its kind."""
    out = {}
    for path in sorted(TABLES.rglob("*.yaml")):
        name = path.relative_to(TABLES).as_posix()
        if name.startswith("problems/"):
            out[name] = "problem"
        elif name.startswith("case_"):
            out[name] = name[len("case_"):-len(".yaml")]
        else:
            out[name] = "chain"
    return out


def command(kind: str, path: str, rng: random.Random) -> list[str]:
    """The command line that reads a table of ``kind`` (small budgets, short grids)."""
    if kind == "chain":
        if rng.random() < 0.5:
            return ["check", path, "--json"]
        return ["analyze", path, "--points", "12"]
    if kind == "problem":
        return ["synthesize", path, "--budget", "2", "--quiet", "--json", "--time-limit", "5"]
    if kind == "tracker":
        return ["case", "tracker", "--table", path, "--budget", "0", "--json"]
    if kind == "impact":
        return ["case", "impact", "--table", path, "--json"]
    return ["case", kind.replace("_", "-"), "--table", path, "--json", "--method", "modern"]


def newer_tables() -> dict[str, str]:
    """The shipped tables of the newer features: with force sections or a problem's
    ``forces:``, and the higher-group tables (triads, class IV groups)."""
    out = {}
    for name, kind in shipped_tables().items():
        text = (TABLES / name).read_text(encoding="utf-8")
        higher = "triad" in name or Path(name).name.startswith("class_iv_")
        forces = any(f"\n{key}:" in "\n" + text for key in ("masses", "loads", "forces"))
        if higher or forces:
            out[name] = kind
    return out


def option_command(kind: str, path: str, rng: random.Random, folder: Path,
                   scheduler: bool) -> list[str] | None:
    """A command on an unchanged table with one odd option value (None when ``kind`` takes
    none of the options)."""
    def odd(option: str) -> str:
        return rng.choice(ODD_OPTIONS[option])

    if kind == "chain":
        return rng.choice([
            ["analyze", path, "--points", odd("--points"), "--forces", "--omega", odd("--omega")],
            ["analyze", path, "--points", "12", "--forces", "--json", "--omega", odd("--omega")],
            ["analyze", path, "--points", "12", "--plot", str(folder / "fuzz.png"),
             "--at", odd("--at")],
            ["analyze", path, "--points", "12", "--animate", str(folder / "fuzz.gif"),
             "--frames", odd("--frames")],
            ["report", path, "--points", odd("--points"), "--budget", "2",
             "--out", str(folder / "fuzz.html"), "--quiet"],
        ])
    if kind == "problem" and scheduler:
        return ["synthesize", path, "--budget", "2", "--quiet", "--json", "--time-limit", "5",
                "--scheduler", odd("--scheduler")]
    return None


# ------------------------------------------------------------------------------ mutations


def tree_paths(node: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """Every path to a value inside parsed YAML."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield (*prefix, key)
            yield from tree_paths(value, (*prefix, key))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield (*prefix, index)
            yield from tree_paths(value, (*prefix, index))


def _parent(tree: Any, path: tuple[Any, ...]) -> Any:
    for step in path[:-1]:
        tree = tree[step]
    return tree


def _odd_value(rng: random.Random, old: Any) -> Any:
    roll = rng.random()
    if roll < 0.15 and isinstance(old, str):
        return old.translate(LOOK_ALIKES)
    if roll < 0.3 and isinstance(old, (int, float)) and not isinstance(old, bool):
        return rng.choice([str(old), old * 1e300, old * 1e-300, -old, [old], {"v": old},
                           f"{old},5"])
    return rng.choice(ODD_VALUES)


def _tree_mutation(rng: random.Random, tree: Any,
                   within: tuple[str, ...] = ()) -> tuple[str, Any]:
    paths = list(tree_paths(tree))
    inside = [path for path in paths if path[0] in within]
    if inside:
        paths = inside
    if not paths:
        return "replace root", _odd_value(rng, tree)
    path = rng.choice(paths)
    parent = _parent(tree, path)
    key = path[-1]
    roll = rng.random()
    if roll < 0.2:
        del parent[key]
        return f"delete {path}", tree
    if roll < 0.3 and isinstance(parent, dict) and isinstance(key, str):
        parent[key.translate(LOOK_ALIKES) if rng.random() < 0.7 else key + "x"] = \
            parent.pop(key)
        return f"rename {path}", tree
    if roll < 0.4 and isinstance(parent, list):
        parent.insert(key, parent[key])
        return f"duplicate {path}", tree
    if roll < 0.45:
        value: Any = parent[key]
        for _ in range(rng.choice([50, 300])):
            value = [value]
        parent[key] = value
        return f"nest {path}", tree
    parent[key] = _odd_value(rng, parent[key])
    return f"replace {path} by {parent[key]!r:.40}", tree


def _byte_mutation(rng: random.Random, data: bytes) -> tuple[str, bytes]:
    roll = rng.random()
    at = rng.randrange(len(data) + 1)
    if roll < 0.2:
        return f"truncate at {at}", data[:at]
    if roll < 0.35:
        noise = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 16)))
        return f"insert {len(noise)} random bytes at {at}", data[:at] + noise + data[at:]
    if roll < 0.5:
        lines = data.splitlines(keepends=True)
        index = rng.randrange(len(lines))
        return f"duplicate line {index + 1}", b"".join(lines[:index + 1] + lines[index:])
    if roll < 0.6:
        text = data.decode("utf-8")
        return "Windows-1251", text.encode("cp1251", errors="replace")
    if roll < 0.7:
        depth = rng.choice([100, 1000, 20000])
        return f"nest {depth} deep at {at}", data[:at] + b"[" * depth + b"]" * depth + data[at:]
    if roll < 0.8:
        text = data.decode("utf-8")
        return "look-alike letters", text.translate(LOOK_ALIKES).encode("utf-8")
    if roll < 0.9 and at < len(data):
        flipped = bytes([data[at] ^ (1 << rng.randrange(8))])
        return f"flip a bit at {at}", data[:at] + flipped + data[at + 1:]
    return f"decimal comma at {at}", data.replace(b".", b",", 1) if rng.random() < 0.5 \
        else data[:at] + b",27" + data[at:]


def mutate(rng: random.Random, origin: str, data: bytes,
           within: tuple[str, ...] = ()) -> Mutant:
    """One mutant of a shipped table's bytes: a change of its parsed tree (of the sections
    ``within`` when the table has them) or of its bytes."""
    if rng.random() < (0.9 if within else 0.65):
        tree = yaml.safe_load(data)
        operation, tree = _tree_mutation(rng, tree, within)
        try:
            text = yaml.safe_dump(tree, allow_unicode=True, sort_keys=False)
        except RecursionError:  # pragma: no cover - the dumper's own limit
            text = "[" * 5000 + "]" * 5000
        return Mutant(origin, operation, text.encode("utf-8"))
    operation, changed = _byte_mutation(rng, data)
    return Mutant(origin, operation, changed)


# ------------------------------------------------------------------------------ running


class Hang(BaseException):
    """Raised in the run when its time is up (not an ``Exception``: nothing may catch it)."""


def _alarm(signum: int, frame: Any) -> None:
    raise Hang


def run_command(argv: list[str], timeout: float, named: str | None = None
                ) -> tuple[str, str]:
    """Run ``assur ARGV`` in-process; returns (outcome, detail).

    The outcome is ``exit 0``/``exit 1``/``exit 2`` (allowed), ``exit N`` for another code,
    ``traceback`` (the exception's traceback in the detail), ``hang``, ``blames a file of
    the program`` (a refusal naming one of the program's own files instead of the user's),
    or ``exit 2 naming no file`` (a refusal that names neither ``named``, the mutated file,
    nor an option: the user cannot tell what to fix).
    """
    from synthesis.cli.main import main

    out = io.StringIO()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
            code = main(argv)
    except SystemExit as exc:  # argparse refuses an option
        code = exc.code if isinstance(exc.code, int) else 2
    except Hang:
        return "hang", out.getvalue()[-2000:]
    except BaseException:  # noqa: BLE001 - every escape is a finding
        return "traceback", traceback.format_exc()
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    text = out.getvalue()
    if code == 2 and any(str(ROOT / package) in text for package in ("assur", "synthesis")):
        return "blames a file of the program", text[-2000:]
    if code == 2 and named is not None and not _names(text, named, argv):
        return "exit 2 naming no file", text[-2000:]
    return f"exit {code}", text[-2000:]


def _names(text: str, named: str, argv: list[str]) -> bool:
    """Whether a refusal names the file (or a file it names, such as a problem's mechanism
    table, a path given in an option) or one of the options given."""
    words = [named, Path(named).name, *(a for a in argv[1:] if a.startswith("--")),
             *(a for a in argv if "/" in a)]
    return any(word and word in text for word in words) or "usage:" in text


def baseline(folder: Path) -> float:
    """Seconds of the known run :data:`BASELINE` on this machine, now (the unit of the hang
    limit; timed again at the start of every chunk, so that it follows the machine's load)."""
    name, kind = BASELINE
    start = time.perf_counter()
    run_command(command(kind, str(folder / name), random.Random(0)), timeout=3600.0)
    return time.perf_counter() - start


def hang_limit(folder: Path, factor: float) -> float:
    """The hang limit: ``factor`` times the :func:`baseline`, at least :data:`MIN_LIMIT`."""
    return max(MIN_LIMIT, factor * baseline(folder))


def copy_tables(folder: Path) -> None:
    """The shipped tables into ``folder`` (problems find their mechanism tables there)."""
    shutil.copytree(TABLES, folder, dirs_exist_ok=True)


def warm_up(folder: Path) -> None:
    """Run every command once on a shipped table, so that the modules each one imports on
    first use are loaded before the time of a mutant is measured (an import cut short by the
    time limit would leave a half-imported module behind)."""
    rng = random.Random(0)
    done: set[str] = set()
    for name, kind in shipped_tables().items():
        if kind not in done:
            done.add(kind)
            run_command(command(kind, str(folder / name), rng), timeout=3600.0)


def fuzz(n: int, seed: int, timeout: float, folder: Path,
         report: Callable[[int, str, Mutant, list[str], str], None] | None = None,
         skip: frozenset[str] = frozenset(), focus: str = "all",
         scheduler: bool = False) -> Counter[str]:
    """Run ``n`` mutants drawn from ``seed``; returns the count of each outcome.

    Every mutant is written to ``folder`` beside the copies of the shipped tables (so that a
    problem still finds its mechanism table) and read by its command; a wrong command is
    given one time in ten.  ``timeout`` is the hang limit in seconds (:func:`hang_limit`).
    ``report(index, outcome, mutant, argv, detail)`` is called for every outcome that is not
    an allowed exit code.  Tables of the kinds in ``skip`` are not mutated (the quick profile
    leaves out the slowest case).  ``focus='new'`` mutates the newer features only (the
    module's description); ``scheduler`` adds odd ``--scheduler`` values to them.
    """
    if not (folder / "four_bar.yaml").exists():
        copy_tables(folder)
    chosen = newer_tables() if focus == "new" else shipped_tables()
    tables = {name: kind for name, kind in chosen.items() if kind not in skip}
    originals = {name: (TABLES / name).read_bytes() for name in tables}
    names = sorted(tables)
    kinds = sorted(set(tables.values()))
    within = NEW_SECTIONS if focus == "new" else ()
    rng = random.Random(seed)
    counts: Counter[str] = Counter()
    for index in range(n):
        origin = rng.choice(names)
        kind = tables[origin]
        argv = (option_command(kind, str(folder / origin), rng, folder, scheduler)
                if focus == "new" and rng.random() < 0.3 else None)
        if argv is None:
            mutant = mutate(rng, origin, originals[origin], within)
            target = folder / Path(origin).parent / f"mutant_{seed}_{index}.yaml"
            target.write_bytes(mutant.data)
            kind = kind if rng.random() < 0.9 else rng.choice(kinds)
            argv = command(kind, str(target), rng)
        else:
            mutant, target = Mutant(origin, "options " + " ".join(argv[2:]), originals[origin]), \
                folder / origin
        limit = timeout * SLOW.get(kind, 1.0) * SLOW_COMMANDS.get(argv[0], 1.0)
        outcome, detail = run_command(argv, limit, str(target))
        if target.name.startswith("mutant_"):
            target.unlink()
        for written in ("fuzz.png", "fuzz.gif", "fuzz.html"):
            (folder / written).unlink(missing_ok=True)
        counts[outcome] += 1
        if outcome not in ("exit 0", "exit 1", "exit 2") and report is not None:
            report(index, outcome, mutant, argv, detail)
    return counts


_WARM: list[bool] = []  # whether this worker process has run every command once


#: One chunk of a run: mutants, seed, hang factor, folder for failures, focus, scheduler.
Job = tuple[int, int, float, str, str, bool]


def _worker(job: Job) -> tuple[Counter[str], list[dict[str, Any]], float]:
    n, seed, factor, keep, focus, scheduler = job
    failures: list[dict[str, Any]] = []

    def report(index: int, outcome: str, mutant: Mutant, argv: list[str], detail: str) -> None:
        name = Path(keep) / f"seed{seed}_{index}.yaml"
        name.write_bytes(mutant.data)
        failures.append({"outcome": outcome, "origin": mutant.origin, "operation":
                         mutant.operation, "argv": argv, "kept": str(name),
                         "detail": detail[-1500:]})
        with Path(keep, "failures.log").open("a", encoding="utf-8") as log:
            log.write(json.dumps(failures[-1], ensure_ascii=False) + "\n")

    with tempfile.TemporaryDirectory() as folder:
        copy_tables(Path(folder))
        if not _WARM:
            warm_up(Path(folder))
            _WARM.append(True)
        limit = hang_limit(Path(folder), factor)
        counts = fuzz(n, seed, limit, Path(folder), report, focus=focus, scheduler=scheduler)
    return counts, failures, limit


def main(argv: list[str] | None = None) -> int:
    """Run the fuzzer and print the counts by outcome; exit 1 if any mutant failed."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mutants", type=int, default=10_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--hang-factor", type=float, default=30.0,
                        help="a mutant hangs past this many times the baseline run")
    parser.add_argument("--focus", choices=("all", "new"), default="all",
                        help="'new': the force sections, higher groups and options only")
    parser.add_argument("--scheduler-options", action="store_true",
                        help="with --focus new: odd --scheduler values too")
    parser.add_argument("--keep", default="fuzz_failures", help="folder for failing mutants")
    args = parser.parse_args(argv)
    Path(args.keep).mkdir(exist_ok=True)
    chunk = 100
    jobs: list[Job] = [(min(chunk, args.mutants - start), args.seed * 1_000_003 + start // chunk,
                        args.hang_factor, args.keep, args.focus, args.scheduler_options)
                       for start in range(0, args.mutants, chunk)]
    counts: Counter[str] = Counter()
    failures: list[dict[str, Any]] = []
    begin = time.perf_counter()
    with multiprocessing.get_context("fork").Pool(args.workers) as pool:
        for done, (part, found, limit) in enumerate(pool.imap_unordered(_worker, jobs), start=1):
            counts.update(part)
            failures.extend(found)
            print(f"{done * chunk} mutants, {sum(part.values())} in this chunk (hang limit "
                  f"{limit:.1f} s): {dict(sorted(counts.items()))}", file=sys.stderr, flush=True)
    Path(args.keep, "failures.json").write_text(json.dumps(failures, indent=1,
                                                           ensure_ascii=False))
    print(f"{sum(counts.values())} mutants in {time.perf_counter() - begin:.0f} s")
    for outcome, count in sorted(counts.items()):
        print(f"  {outcome:10s} {count}")
    print(f"failures kept in {args.keep}/failures.json: {len(failures)}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
