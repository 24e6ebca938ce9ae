"""Existence of every dyad kind against an exact decision, over 10⁵ random designs per kind.

The designs and the exact decision are those of ``tests/assur/test_dyads_exact.py``
(lengths log-uniform over 1e-3 … 1e6 mm, the group anywhere from 1e-3 to 1e6 mm from the
origin, half of the designs as near a limit of existence as their coordinates allow; L1–L3
decided in exact integer arithmetic, L4–L5 by the exact angle reduced by π to 50 digits).
This script prints, per kind, how many designs assemble, how many the solver misjudges
outside the round-off band, how many lie in the band (read as toggles) and the largest
closure residual of the assembled ones relative to the group's size.

Run::

    PYTHONPATH=. python benchmarks/existence_exact.py
"""

from __future__ import annotations

import importlib.util
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def _exact_module():
    spec = importlib.util.spec_from_file_location(
        "test_dyads_exact", ROOT / "tests" / "assur" / "test_dyads_exact.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def closure(exact, kind: str) -> float:
    """The largest closure residual over the assembled designs, relative to the group's
    size plus the rounding of coordinates far from the origin (as the test allows it)."""
    data = exact.designs(kind)
    sol = exact.SOLVERS[kind](*data["args"])
    ok = sol.exists
    args, c = data["args"], sol.c
    if kind == "RRR":
        h_i, h_j, l_i, l_j, _ = args
        residuals = [np.abs(c - h_i) - l_i, np.abs(c - h_j) - l_j]
    elif kind == "RRP":
        h_j, a, theta, e, l_j, _ = args
        u = np.exp(1j * theta)
        residuals = [np.abs(c - h_j) - l_j, ((c - a) * np.conj(u)).imag - e]
    elif kind == "RPR":
        h_i, h_j, h, _ = args
        frame = (sol.s_i + 1j * h) * np.exp(1j * sol.angle_i)
        residuals = [np.abs(frame - (h_j - h_i))]
    elif kind == "PRP":
        a, theta_i, e_i, b, theta_j, e_j = args
        residuals = [np.abs(c - (a + (sol.s_i + 1j * e_i) * np.exp(1j * theta_i))),
                     np.abs(c - (b + (sol.s_j + 1j * e_j) * np.exp(1j * theta_j)))]
    else:
        h_j, gamma, a, theta_s, e = args
        residuals = [np.abs(c - (h_j + sol.s_j * np.exp(1j * (theta_s + gamma)))),
                     np.abs(c - (a + (sol.s_i + 1j * e) * np.exp(1j * theta_s)))]
    scale = data["size"]
    if kind in ("PRP", "RPP"):
        scale = scale + np.abs(sol.s_i) + np.abs(sol.s_j)
    scale = scale + 8 * exact.EPS * (data["places"] + np.abs(c)) / exact.CLOSURE
    return float(max(np.max(np.abs(r[ok]) / scale[ok]) for r in residuals))


def main() -> int:
    """Print the table; exit 1 if a design is misjudged or a closure exceeds 1e-9."""
    exact = _exact_module()
    kinds = {"RRR": "L1", "RRP": "L2", "RPR": "L3", "PRP": "L4", "RPP": "L5"}
    print(f"{exact.DESIGNS} designs per kind, lengths 1e-3 … 1e6 mm")
    print("kind       assemble  misjudged  in band  band read as failing  "
          "at band edge  worst closure / size")
    bad = 0
    for kind, label in kinds.items():
        begin = time.perf_counter()
        wrong, band, toggles_failed, edge = exact.misjudged(kind)
        assembled = int(np.sum(exact.SOLVERS[kind](*exact.designs(kind)["args"]).exists))
        worst = closure(exact, kind)
        bad += wrong + toggles_failed + (worst > exact.CLOSURE)
        print(f"{label} {kind}  {assembled:9d}  {wrong:9d}  {band:7d}  {toggles_failed:20d}  "
              f"{edge:12d}  {worst:20.2e}   ({time.perf_counter() - begin:.1f} s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
