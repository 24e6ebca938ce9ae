"""Start-up time: ``assur check`` of a small table against the floor, in this tree and another.

Each command runs in a fresh interpreter (a subprocess) as a user runs it; the two trees run
alternately, so a load on the machine falls on both alike.  Compiled byte code is kept as an
installed program keeps it (``pip`` compiles on install), in a cache folder outside the trees
(``PYTHONPYCACHEPREFIX``), after one warm-up run of each; the warm-up also compiles the text
catalogue into the user's cache, as the first run of an installed program does.

The floor is what ``assur check`` cannot do without: the interpreter with ``numpy``, ``yaml``
and ``networkx`` imported (numpy for the rank test and the solvers, PyYAML to read the table,
networkx for the structural analysis).  It is measured in the same run, so the time *above the
floor* — what the program itself spends on imports and work — is a difference of two medians
taken under the same load.  Prints, for each command, the median and the quartiles of the wall
time, the median CPU time (user + system, less sensitive to a busy machine than the wall
time); then the modules ``assur check`` loaded in each tree.

    python benchmarks/bench_startup.py [--runs 15] [--base /path/to/old/tree]
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
TABLE = "input_tables/four_bar.yaml"
#: Packages whose presence after ``assur check`` is reported (none of them is needed).
WATCHED = ("scipy", "matplotlib", "tqdm", "dask", "babel", "importlib.metadata",
           "assur.forces", "assur.kinematics.higher", "assur.kinematics.existence", "assur.plot")
#: ``assur check`` as the console script runs it; prints the modules it loaded on stderr.
CHECK = ("import sys; from synthesis.cli import main; sys.argv[1:] = ['check', %r]; "
         "code = main(); import json; "
         "print(json.dumps(sorted(sys.modules)), file=sys.stderr); sys.exit(code)")
FLOOR = "import numpy, yaml, networkx"
CACHE = Path(tempfile.gettempdir()) / "assur-bench-startup"


def _cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def _once(tree: Path, code: str) -> tuple[float, float, str]:
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--base", type=Path, default=Path("/work/base"),
                        help="the tree to compare with (default /work/base)")
    parser.add_argument("--modules", type=Path, default=None,
                        help="write the modules that check loaded in each tree (JSON) here")
    args = parser.parse_args()
    trees = {"this tree": ROOT, "base": args.base}
    cases = {"check": ("assur check " + TABLE, CHECK % TABLE),
             "floor": ("floor: python -c '" + FLOOR + "'", FLOOR),
             "python": ("python -c 'pass' (the interpreter alone)", "pass")}
    medians: dict[tuple[str, str], float] = {}
    loaded: dict[str, list[str]] = {}
    for case, (label, code) in cases.items():
        times: dict[str, list[float]] = {name: [] for name in trees}
        cpus: dict[str, list[float]] = {name: [] for name in trees}
        for tree in trees.values():
            _once(tree, code)  # warm-up: compile the byte code (and the catalogue) once
        for _ in range(args.runs):
            for name, tree in trees.items():
                seconds, cpu, printed = _once(tree, code)
                times[name].append(seconds)
                cpus[name].append(cpu)
                if case == "check":
                    loaded[name] = json.loads(printed)
        print(label)
        for name in trees:
            q1, median, q3 = statistics.quantiles(times[name], n=4)
            medians[case, name] = median
            print(f"  {name:10s} wall median {median:6.3f} s (quartiles {q1:.3f}–{q3:.3f} s), "
                  f"CPU median {statistics.median(cpus[name]):.3f} s, {args.runs} runs")
        sys.stdout.flush()
    print("above the floor (check − floor, wall medians)")
    for name in trees:
        above = medians["check", name] - medians["floor", name]
        print(f"  {name:10s} {above:6.3f} s  (check {medians['check', name]:.3f} s, "
              f"floor {medians['floor', name]:.3f} s)")
    print("modules loaded by assur check")
    for name in trees:
        print(f"  {name:10s} {_loaded(loaded[name])}")
    if args.modules is not None:
        args.modules.write_text(json.dumps(loaded, indent=1), encoding="utf-8")


if __name__ == "__main__":
    main()
