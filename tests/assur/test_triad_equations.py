"""A triad's Newton data from one evaluation of its constraint lines (``Triad.equations``)
against its residual and Jacobian evaluated apart: the same numbers, to the last bit, so that
the continuation's iterates do not depend on which way they were computed."""

from __future__ import annotations

import numpy as np
import pytest

from assur.kinematics.higher.groups import Leash, Triad, TriadInputs, plain

FORMS = [("RR", "RR", "RR"), ("RR", "RP", "RR"), ("RR", "PR", "RP"), ("RR", "RP", "RP"),
         ("RP", "RP", "PR"), ("PR", "RP", "PR"), ("RR", "RP", "PP")]


@pytest.mark.parametrize("leashes", FORMS)
def test_equations_are_the_residual_and_the_jacobian(leashes: tuple[str, str, str]) -> None:
    rng = np.random.default_rng(len("".join(leashes)) + sum(map(ord, "".join(leashes))))

    def points() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return tuple(rng.normal(0.0, 50.0, 6) + 1j * rng.normal(0.0, 50.0, 6)  # type: ignore[return-value]
                     for _ in range(3))

    base, external = points(), points()
    guide = tuple(None if kind == "RR" else np.exp(1j * rng.uniform(0.0, 6.0, 6))
                  for kind in leashes)
    triad = Triad(tuple(Leash(kind) for kind in leashes), base, external, guide)  # type: ignore[arg-type]
    moved = TriadInputs(tuple(a + rng.normal(0.0, 1.0, 6) for a in external),  # type: ignore[arg-type]
                        tuple(None if u is None else u * np.exp(0.1j) for u in guide))  # type: ignore[arg-type]
    x = triad.drawn() + rng.normal(0.0, 0.1, (4, 6, 3))
    f, jac = triad.equations(x, moved)
    residual = np.stack(np.broadcast_arrays(*map(plain, triad.residual(x, moved))), axis=-1)
    assert np.array_equal(f, residual)
    assert np.array_equal(jac, triad.jacobian(x, moved))
    assert np.abs(residual).max() > 1e-3  # off the solution: a test of the equations' values
