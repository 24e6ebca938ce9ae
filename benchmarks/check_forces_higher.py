"""The force analysis of triads and class IV groups against the global solve, on many designs.

The heavy version of ``tests/assur/test_forces_higher.py``: for every leash combination of
the triad and for the class IV group, ``--designs`` random designs (with random masses,
loads and gravity) over ``--points`` crank angles; prints the positions compared and the
largest relative differences from the global Newton–Euler solve of the test (forces over the
largest force, moments over the largest moment plus force × size), the largest relative
power balance and the largest link residual.

Run: ``python benchmarks/check_forces_higher.py [--designs 30] [--points 36]``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "assur"))

from test_forces_global import _global, worst  # type: ignore[import-not-found]
from test_forces_higher import OMEGA, TRIADS, _class_iv, _loads, _triad  # type: ignore[import-not-found]

import assur
from assur.forces import kinetostatics
from assur.kinematics.analysis import analyse


def _worst(model: assur.KinematicModel, phi: np.ndarray, seed: int
           ) -> tuple[int, float, float, float, float]:
    """Positions compared and the four largest relative errors of one design."""
    rng = np.random.default_rng(seed)
    data = _loads(model, rng)
    motion = analyse(model, phi, analogs=True)
    result = kinetostatics(motion, data, OMEGA)
    with np.errstate(invalid="ignore"):
        expected = _global(motion, data, OMEGA)
    solved = result.reason == 0
    if not solved.any():
        return (0, 0.0, 0.0, 0.0, 0.0)
    force, moment, balance = worst(motion, result, expected, solved)
    residual = max(max(np.max(r.force[solved]), np.max(r.moment[solved]))
                   for r in result.residuals.values())
    return int(solved.sum()), force, moment, balance, residual


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=30)
    parser.add_argument("--points", type=int, default=36)
    args = parser.parse_args()
    phi = np.linspace(0.0, 2 * np.pi, args.points, endpoint=False)
    print(f"{'group':<10}{'designs':>8}{'positions':>10}{'forces':>10}{'moments':>10}"
          f"{'balance':>10}{'residual':>10}")
    for kind in [*TRIADS, "IV"]:
        rows = []
        for seed in range(1000, 1000 + args.designs):
            rng = np.random.default_rng(seed)
            model = _class_iv(rng) if kind == "IV" else _triad(kind, rng)
            rows.append(_worst(model, phi, seed))
        table = np.array(rows)
        print(f"{kind:<10}{args.designs:>8}{int(table[:, 0].sum()):>10}"
              + "".join(f"{value:>10.1e}" for value in table[:, 1:].max(axis=0)))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
