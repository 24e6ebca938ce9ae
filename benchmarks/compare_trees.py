"""Run the benchmarks of two checkouts side by side and print the ratios new/old.

A change must not slow the program down. This script runs each benchmark script of
``benchmarks/`` with the program of the OLD checkout and with that of the NEW one in turn
(old, new, old, new, …: the machine's drift falls on both alike), reads the figures each run
prints, and prints per figure the median over the rounds for both trees and the ratio
new/old, oriented so that > 1 means the new tree is faster:

    python benchmarks/compare_trees.py OLD_TREE NEW_TREE [--rounds 3] [--only fourbar ...]

Each tree runs its own copy of the benchmark scripts (a restructuring may move what a script
imports); the measurement itself must be the same in both copies.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Bench:
    """One benchmark script, its arguments, and how to read its figures."""

    script: str
    args: tuple[str, ...]
    pattern: str
    higher_is_better: bool

    def figures(self, output: str) -> dict[str, float]:
        found = {}
        for match in re.finditer(self.pattern, output, re.MULTILINE):
            name, value = match.group("name").strip(), match.group("value")
            found[re.sub(r"\s+", " ", name)] = float(value.replace(",", ""))
        return found


BENCHES = {
    "fourbar": Bench("bench_fourbar.py", ("--rounds", "5"),
                     r"^(?P<name>\([abd]\) [^\n]*?)\s{2,}(?P<value>[\d,]+)\s+[\d,]+$", True),
    "mechanism": Bench("bench_mechanism.py", ("--repeat", "3"),
                       r"^(?P<name>(?:11-link|1,000 designs)[^\n]*?)\s{2,}[\d,]+\s+[\d.]+\s+"
                       r"(?P<value>[\d,]+)\s+[\d.]+x$", True),
    "structure": Bench("bench_structure.py", ("--rounds", "5"),
                       r"^(?P<name>peeling loop|analyse_structure|identification_table)\s+"
                       r"(?P<value>[\d.]+) ms", False),
    "synthesis": Bench("bench_synthesis.py",
                       ("--quick", "--no-peer", "--out",
                        str(Path(tempfile.gettempdir()) / "bench_synthesis.png")),
                       r"^\s+(?P<name>\d+\s+(?:no|yes))\s+\S+\s+\d+\s+(?P<value>[\d.]+)$",
                       False),
    "batch": Bench("bench_batch.py", ("--tables", "300"),
                   r"^\d+ (?P<name>tables) in (?P<value>[\d.]+) s", False),
    "higher": Bench("bench_higher.py", ("--rounds", "1"),
                    r"^\s*(?P<name>[\d,]+)\s+(?P<value>[\d,]+)\s+[\d,]+\s+[\d,]+\s+[\d,]+"
                    r"\s+[\d,]+\s+[\d,]+$", True),
}


def run(bench: Bench, tree: Path) -> dict[str, float]:
    """One run of a benchmark with the program of ``tree``."""
    env = dict(os.environ, PYTHONPATH=str(tree), MPLBACKEND="Agg")
    script = tree / "benchmarks" / bench.script
    proc = subprocess.run([sys.executable, str(script), *bench.args], check=False, env=env,
                          capture_output=True, text=True, timeout=1800, cwd=tree)
    figures = bench.figures(proc.stdout)
    if proc.returncode or not figures:
        raise SystemExit(f"{bench.script} with {tree} failed:\n{proc.stdout}\n{proc.stderr}")
    return figures


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--only", nargs="+", choices=sorted(BENCHES), default=sorted(BENCHES))
    args = parser.parse_args(argv)
    print(f"{'benchmark / figure':58s} {'old':>12s} {'new':>12s} {'new/old speed':>14s}")
    for key in args.only:
        bench = BENCHES[key]
        runs: dict[str, list[dict[str, float]]] = {"old": [], "new": []}
        for _ in range(args.rounds):
            runs["old"].append(run(bench, args.old.resolve()))
            runs["new"].append(run(bench, args.new.resolve()))
        for name in runs["old"][0]:
            old = statistics.median(r[name] for r in runs["old"] if name in r)
            new = statistics.median(r[name] for r in runs["new"] if name in r)
            speed = new / old if bench.higher_is_better else old / new
            print(f"{key + ': ' + name:58.58s} {old:12,.4g} {new:12,.4g} {speed:14.3f}",
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
