"""Record, and compare, the JSON answers of the command line on every shipped input.

A restructuring must not change what the program answers. This script runs ``assur check``,
``assur analyze``, ``assur synthesize`` (seeded), ``assur batch`` and ``assur case …`` with
``--json`` on every table, problem and case that the project ships, and stores each answer
as a file. Run it once on the old tree and once on the new one, then compare:

    python benchmarks/snapshot_outputs.py record OUT_DIR [--tree PATH]
    python benchmarks/snapshot_outputs.py compare OLD_DIR NEW_DIR [--rtol 1e-9]

``--tree`` runs the program found at PATH (a checkout) instead of this one. Numbers are
compared with a relative tolerance (run times, which differ from run to run, are left out);
every other value must be equal. The comparison prints one line per input and a summary.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]

#: Keys whose values are timings or other run-dependent figures.
VOLATILE = {"elapsed", "elapsed_s", "time", "seconds", "time_s", "wall", "rate"}


def jobs(root: Path) -> list[tuple[str, list[str]]]:
    """(name, command-line arguments) of every shipped input."""
    out: list[tuple[str, list[str]]] = []
    for path in sorted((root / "input_tables").glob("*.yaml")):
        rel = path.relative_to(root).as_posix()
        if path.name.startswith("case_"):
            continue
        out.append((f"check:{rel}", ["check", rel, "--json"]))
        out.append((f"analyze:{rel}", ["analyze", rel, "--json", "--points", "72"]))
    for path in sorted((root / "input_tables" / "problems").glob("*.yaml")):
        rel = path.relative_to(root).as_posix()
        out.append((f"synthesize:{rel}", ["synthesize", rel, "--json", "--seed", "1"]))
    out.append(("batch:docs/tutorial_class", ["batch", "docs/tutorial_class", "--json"]))
    out.append(("case:fourbar-velocity-ratio",
                ["case", "fourbar-velocity-ratio", "--table",
                 "input_tables/case_fourbar_velocity_ratio.yaml", "--json"]))
    out.append(("case:tracker", ["case", "tracker", "--table",
                                 "input_tables/case_tracker.yaml", "--json"]))
    out.append(("case:impact", ["case", "impact", "--table",
                                "input_tables/case_impact.yaml", "--json"]))
    return out


def record(out_dir: Path, tree: Path) -> None:
    """Run every job with the program of ``tree`` and store exit code, stdout and stderr."""
    out_dir.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, PYTHONPATH=str(tree), MPLBACKEND="Agg")
    for name, args in jobs(ROOT):
        proc = subprocess.run([sys.executable, "-m", "synthesis", *args], cwd=ROOT, env=env,
                              capture_output=True, text=True, timeout=600, check=False)
        try:
            answer: Any = json.loads(proc.stdout)
        except json.JSONDecodeError:
            answer = {"stdout": proc.stdout}
        record_ = {"exit": proc.returncode, "answer": answer,
                   "stderr": proc.stderr if proc.returncode else ""}
        (out_dir / (name.replace("/", "__").replace(":", "--") + ".json")).write_text(
            json.dumps(record_, indent=1, sort_keys=True, ensure_ascii=False), encoding="utf-8")
        print(f"{proc.returncode}  {name}", flush=True)


def differences(a: Any, b: Any, rtol: float, where: str = "") -> list[str]:
    """Every place where two JSON values differ beyond ``rtol`` (numbers) or at all."""
    if isinstance(a, dict) and isinstance(b, dict):
        found: list[str] = []
        for key in sorted(set(a) | set(b), key=str):
            if key in VOLATILE:
                continue
            if key not in a or key not in b:
                found.append(f"{where}/{key}: only in {'new' if key in b else 'old'}")
                continue
            found += differences(a[key], b[key], rtol, f"{where}/{key}")
        return found
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items, now {len(b)}"]
        return [d for x, y in zip(a, b) for d in differences(x, y, rtol, where + "[]")][:20]
    numbers = (int, float)
    if (isinstance(a, numbers) and isinstance(b, numbers) and not isinstance(a, bool)
            and not isinstance(b, bool)):
        if math.isclose(a, b, rel_tol=rtol, abs_tol=1e-12):
            return []
        return [f"{where}: {a!r} → {b!r}"]
    return [] if a == b else [f"{where}: {str(a)[:80]!r} → {str(b)[:80]!r}"]


def compare(old: Path, new: Path, rtol: float) -> int:
    """Print the differences of two recordings; the number of inputs that differ."""
    names = sorted({p.name for p in old.glob("*.json")} | {p.name for p in new.glob("*.json")})
    changed = 0
    for name in names:
        a, b = old / name, new / name
        if not a.exists():
            print(f"new input  {name}")
            continue
        if not b.exists():
            print(f"MISSING now  {name}")
            changed += 1
            continue
        diff = differences(json.loads(a.read_text("utf-8")), json.loads(b.read_text("utf-8")),
                           rtol)
        print(f"{'same' if not diff else 'DIFFERS'}  {name}")
        for line in diff[:10]:
            print(f"    {line}")
        changed += bool(diff)
    old_names = [name for name in names if (old / name).exists()]
    print(f"{len(old_names)} inputs compared, {len(old_names) - changed} same, {changed} differ "
          f"(relative tolerance {rtol:g})")
    return changed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="what", required=True)
    rec = sub.add_parser("record")
    rec.add_argument("out", type=Path)
    rec.add_argument("--tree", type=Path, default=ROOT)
    cmp_ = sub.add_parser("compare")
    cmp_.add_argument("old", type=Path)
    cmp_.add_argument("new", type=Path)
    cmp_.add_argument("--rtol", type=float, default=1e-9)
    args = parser.parse_args(argv)
    if args.what == "record":
        record(args.out, args.tree.resolve())
        return 0
    return 1 if compare(args.old, args.new, args.rtol) else 0


if __name__ == "__main__":
    sys.exit(main())
