"""Time ``assur batch`` on a class of 1,000 tables (target: under a minute on 2 cores).

The folder mixes what a teacher gets: the course's 11-link mechanism with its identification
table (with and without a student's slip), four-bars with a sketch (some of which do not
assemble over the whole cycle), chains with the wrong number of inputs, and broken files.

    python benchmarks/bench_batch.py [--tables 1000] [--jobs N]
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np
import yaml

from synthesis.app.batch import run_batch

ROOT = Path(__file__).resolve().parent.parent


def _four_bar(rng: np.random.Generator) -> dict:
    crank, coupler, rocker, frame = rng.uniform(20, 40), rng.uniform(60, 110), \
        rng.uniform(50, 100), 100.0
    b, d = complex(crank, 0), complex(frame, 0)
    dist = abs(d - b)
    x = (coupler ** 2 - rocker ** 2 + dist ** 2) / (2 * dist)
    h = math.sqrt(max(coupler ** 2 - x ** 2, 0.0))
    c = b + (d - b) / dist * (x + 1j * h)
    return {"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
        {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
        "inputs": [1]},
        "geometry": {"A": {"point": [0.0, 0.0]}, "B": {"point": [b.real, 0.0]},
                     "C": {"point": [float(c.real), float(c.imag)]},
                     "D": {"point": [frame, 0.0]}}}


def make_class(folder: Path, count: int, seed: int = 0) -> None:
    """Write ``count`` tables of mixed kinds into ``folder``."""
    rng = np.random.default_rng(seed)
    course = yaml.safe_load((ROOT / "input_tables" / "course_11_link_table.yaml").read_text(
        encoding="utf-8"))
    chain = (ROOT / "input_tables" / "course_11_link.yaml").read_text(encoding="utf-8")
    for k in range(count):
        path = folder / f"student_{k:04d}.yaml"
        kind = k % 10
        if kind in (0, 1, 2):
            path.write_text(chain, encoding="utf-8")
            continue
        if kind in (3, 4):
            data = yaml.safe_load(yaml.safe_dump(course))
            if kind == 4:  # a slip in the successor column
                data["structure_identification"][1]["i_plus_1"] = 7
        elif kind in (5, 6, 7):
            data = _four_bar(rng)
        elif kind == 8:
            data = {"mechanism": {"pairs": [{"id": i, "type": "R", "links": ab} for i, ab in
                                            enumerate(([0, 1], [1, 2], [2, 3], [3, 4], [4, 0]))],
                                  "inputs": [1]}}
        else:
            path.write_text("mechanism: {pairs: [\n", encoding="utf-8")
            continue
        path.write_text(yaml.safe_dump(data), encoding="utf-8")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tables", type=int, default=1000)
    parser.add_argument("--jobs", type=int, default=None)
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="assur-class-"))
    try:
        make_class(folder, args.tables)
        start = time.perf_counter()
        rows = run_batch(folder, jobs=args.jobs)
        elapsed = time.perf_counter() - start
    finally:
        shutil.rmtree(folder)
    jobs = args.jobs or os.cpu_count()
    verdicts = Counter(r.verdict for r in rows)
    existence = Counter(r.existence for r in rows)
    print(f"{len(rows)} tables in {elapsed:.1f} s on {jobs} process(es): "
          f"{len(rows) / elapsed:.0f} tables/s")
    print(f"verdicts: {dict(verdicts)}; existence: {dict(existence)}")


if __name__ == "__main__":
    main()
