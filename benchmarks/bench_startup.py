"""Start-up time: ``assur check`` of a small table and ``import assur``, against another tree.

Each command runs in a fresh interpreter (a subprocess) as a user runs it; the two trees run
alternately, so a load on the machine falls on both alike.  Compiled byte code is kept as an
installed program keeps it (``pip`` compiles on install), in a cache folder outside the trees
(``PYTHONPYCACHEPREFIX``), after one warm-up run of each.  Prints the median and the
quartiles of the wall time of each, the median CPU time (user + system, less sensitive to a
busy machine than the wall time), and the modules of scipy, matplotlib, networkx and tqdm
that ``assur check`` loaded.

    python benchmarks/bench_startup.py [--runs 15] [--base /path/to/old/tree]
"""

from __future__ import annotations

import argparse
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
#: The command of ``assur check`` as the console script runs it.
CHECK = ("import sys; from synthesis.cli import main; sys.argv[1:] = ['check', %r]; "
         "code = main(); import sys; "
         "print(sorted({m.split('.')[0] for m in sys.modules} & "
         "{'scipy', 'matplotlib', 'networkx', 'tqdm'}), file=sys.stderr); sys.exit(code)")
IMPORT = "import assur"


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--base", type=Path, default=Path("/work/base"),
                        help="the tree to compare with (default /work/base)")
    args = parser.parse_args()
    trees = {"this tree": ROOT, "base": args.base}
    cases = {"assur check " + TABLE: CHECK % TABLE, "python -c 'import assur'": IMPORT,
             "python -c 'pass' (the interpreter alone, for scale)": "pass"}
    for label, code in cases.items():
        times: dict[str, list[float]] = {name: [] for name in trees}
        cpus: dict[str, list[float]] = {name: [] for name in trees}
        loaded = {}
        for tree in trees.values():
            _once(tree, code)  # warm-up: compile the byte code once
        for _ in range(args.runs):
            for name, tree in trees.items():
                seconds, cpu, modules = _once(tree, code)
                times[name].append(seconds)
                cpus[name].append(cpu)
                loaded[name] = modules
        print(label)
        for name in trees:
            q1, median, q3 = statistics.quantiles(times[name], n=4)
            print(f"  {name:10s} wall median {median:6.3f} s (quartiles {q1:.3f}–{q3:.3f} s), "
                  f"CPU median {statistics.median(cpus[name]):.3f} s, {args.runs} runs  "
                  f"{loaded[name]}")
        ratio = statistics.median(times["base"]) / statistics.median(times["this tree"])
        print(f"  base / this tree = {ratio:.2f}")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
