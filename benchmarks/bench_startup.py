"""Start-up time: ``assur check`` of each small table of dyads against the import floor.

Each command runs in a fresh interpreter (a subprocess) as a user runs it.  The commands
take turns within every round — each table in this tree and, with ``--base``, in another
tree, then the floor — so a load on the machine falls on all of them alike.  Compiled byte
code is kept as an installed program keeps it (``pip`` compiles on install), in a cache
folder outside the trees (``PYTHONPYCACHEPREFIX``), after one warm-up run of each; the
warm-up also compiles the text catalogue into the user's cache, as the first run of an
installed program does.

The floor is what ``assur check`` cannot do without: the interpreter with ``numpy`` (the rank
test, the kinematic model) and ``yaml`` (the table) imported.  It is measured in the same
rounds, so the time *above the floor* — what the program itself spends on its own imports
and its work — is a difference of two medians taken under the same load.  Prints, for each
table and tree, the median and quartiles of the wall time and the median CPU time (user +
system, less sensitive to a busy machine than the wall time); then the time above the floor;
then the modules that ``assur check`` loaded.

    python benchmarks/bench_startup.py [--runs 11] [--base OTHER_TREE] [--tables a.yaml ...]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: The shipped tables of cranks and dyads (the structure's speed path; the hydraulic boom,
#: driven by an actuator between moving links, and the triads take the general path).
TABLES = ("four_bar", "four_bar_gravity", "slider_crank", "slider_crank_press", "scotch_yoke",
          "slotted_lever", "tangent", "whitworth", "watt_ii", "stephenson",
          "five_bar_two_inputs", "course_11_link", "course_11_link_table", "course_11_link_fails")
#: Packages whose presence after ``assur check`` is reported (none of them is needed).
WATCHED = ("networkx", "scipy", "matplotlib", "tqdm", "dask", "babel", "importlib.metadata",
           "assur.forces", "assur.kinematics.higher", "assur.kinematics.existence", "assur.plot")
#: ``assur check`` as the console script runs it; prints the modules it loaded on stderr.
CHECK = ("import sys; from synthesis.cli import main; sys.argv[1:] = ['check', %r]; "
         "code = main(); import json; "
         "print(json.dumps(sorted(sys.modules)), file=sys.stderr); sys.exit(code)")
FLOOR = "import numpy, yaml"
CACHE = Path(tempfile.gettempdir()) / "assur-bench-startup"


def _cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def _once(tree: Path, code: str) -> tuple[float, float, str]:
    """Wall and CPU seconds of ``python -c code`` with ``tree`` first on the path."""
    env = dict(os.environ, PYTHONPATH=str(tree),
               PYTHONPYCACHEPREFIX=str(CACHE / str(tree).strip("/").replace("/", "_")))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    start, cpu = time.perf_counter(), _cpu()
    done = subprocess.run([sys.executable, "-c", code], cwd=tree, env=env,
                          capture_output=True, text=True, check=False)
    seconds, cpu = time.perf_counter() - start, _cpu() - cpu
    if done.returncode != 0:
        raise SystemExit(f"{tree}: {code!r} failed:\n{done.stderr}")
    return seconds, cpu, done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ""


def _loaded(modules: list[str]) -> str:
    """The watched packages among ``modules`` and the count of the program's own modules."""
    found = [name for name in WATCHED
             if any(m == name or m.startswith(name + ".") for m in modules)]
    own = sum(m.split(".")[0] in ("assur", "synthesis") for m in modules)
    return (f"{len(modules)} modules, {own} of assur/synthesis; "
            f"of {', '.join(WATCHED)}: {', '.join(found) or 'none'}")


def _summary(times: list[float], cpus: list[float]) -> str:
    q1, median, q3 = statistics.quantiles(times, n=4)
    return (f"wall median {median:6.3f} s (quartiles {q1:.3f}–{q3:.3f} s), "
            f"CPU median {statistics.median(cpus):.3f} s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=11, help="rounds (default 11)")
    parser.add_argument("--base", type=Path, default=None,
                        help="another tree of the program to time in the same rounds")
    parser.add_argument("--tables", nargs="+", default=None, metavar="NAME",
                        help="tables of input_tables/ to check (default: every table of dyads)")
    parser.add_argument("--modules", type=Path, default=None,
                        help="write the modules that check loaded in each tree (JSON) here")
    args = parser.parse_args()
    trees = {"this tree": ROOT, **({"base": args.base.resolve()} if args.base else {})}
    tables = [f"input_tables/{name.removesuffix('.yaml')}.yaml" for name in args.tables or TABLES]
    commands = {(table, name): (tree, CHECK % table)
                for table in tables for name, tree in trees.items()}
    commands["floor", ""] = ROOT, FLOOR
    wall: dict[tuple[str, str], list[float]] = {key: [] for key in commands}
    cpu: dict[tuple[str, str], list[float]] = {key: [] for key in commands}
    loaded: dict[str, list[str]] = {}
    for tree, code in commands.values():
        _once(tree, code)  # warm-up: compile the byte code (and the catalogue) once
    for _ in range(args.runs):
        for key, (tree, code) in commands.items():
            seconds, used, printed = _once(tree, code)
            wall[key].append(seconds)
            cpu[key].append(used)
            if key[0] == tables[0]:
                loaded[key[1]] = json.loads(printed)
    floor = statistics.median(wall["floor", ""])
    print(f"{args.runs} rounds; floor: python -c '{FLOOR}' "
          f"{_summary(wall['floor', ''], cpu['floor', ''])}")
    for table in tables:
        print(f"assur check {table}")
        for name in trees:
            print(f"  {name:10s} {_summary(wall[table, name], cpu[table, name])}")
    print("above the floor (wall median of check − wall median of the floor)")
    print(f"  {'table':28s}" + "".join(f"{name:>12s}" for name in trees))
    for table in tables:
        print(f"  {Path(table).stem:28s}" + "".join(
            f"{statistics.median(wall[table, name]) - floor:10.3f} s" for name in trees))
    print(f"modules loaded by assur check {tables[0]}")
    for name in trees:
        print(f"  {name:10s} {_loaded(loaded[name])}")
    if args.modules is not None:
        args.modules.write_text(json.dumps(loaded, indent=1), encoding="utf-8")


if __name__ == "__main__":
    main()
