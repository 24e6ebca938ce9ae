"""The compiled corrector of the class IV group against the corrector written with numpy.

For every form of ``test_higher_coupled.py`` (hinged couplers, blocks turning with a or c,
a PP coupler, sliding external pairs) and a coupler that is a linear actuator, on random
designs: predictors scattered about the drawn pose at a crank angle near the drawing's,
corrected both ways (:func:`continuation._correct` with and without its ``kernel``): the unknowns, the Jacobian, the margin and the acceptance agree to roundoff.
Independently, every accepted position satisfies the loop equations
(:meth:`ClassIVCoupled.residual`, straight from the joints rather than from the fitted
matrices the kernel contracts).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_higher_coupled import COUPLED, SHARED, random_designs

from assur.kinematics.higher import compiled, continuation
from assur.kinematics.higher.coupled import ClassIVCoupled
from assur.kinematics.higher.groups import ClassIVInputs, plain

D = 60
FORMS = SHARED + COUPLED


def _both(group: ClassIVCoupled, k: ClassIVInputs, guess: np.ndarray, sign: np.ndarray
          ) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """The corrector compiled, and written with numpy."""
    assert compiled.supports(group)
    return (continuation._correct(group, k, guess, sign, kernel=True),
            continuation._correct(group, k, guess, sign))


def _residual(group: ClassIVCoupled, k: ClassIVInputs, x: np.ndarray) -> np.ndarray:
    """max |g_j| at x over L."""
    with np.errstate(all="ignore"):
        f = np.stack(np.broadcast_arrays(*map(plain, group.residual(x, k))), axis=-1)
    return np.asarray(np.abs(f).max(axis=-1) / np.asarray(group.size))


def _check(group: ClassIVCoupled, k: ClassIVInputs, guess: np.ndarray, sign: np.ndarray
           ) -> None:
    """Both correctors alike: accepted at the same positions; the unknowns, the Jacobian and
    the margin to roundoff wherever the numpy corrector's Newton's method reached a root (a
    diverging one wanders where roundoff decides); the accepted positions on a root."""
    (x, jac, margin, ok), (x0, jac0, margin0, ok0) = _both(group, k, guess, sign)
    assert x.shape == x0.shape and jac.shape == jac0.shape and ok.shape == ok0.shape
    assert (ok == ok0).all()
    assert 0.3 < ok.mean() < 1.0  # both outcomes met
    root = _residual(group, k, x0) <= 1e-9
    assert root.mean() > 0.6
    assert np.abs(x - x0)[root].max() <= 1e-12
    big = np.abs(jac0).max(axis=(-2, -1), keepdims=True)
    assert (np.abs(jac - jac0) <= 1e-12 * big)[root].all()
    assert (np.abs(margin - margin0) <= 1e-12 * np.abs(margin0))[root].all()
    assert (_residual(group, k, x)[ok] <= 1e-9).all()


def _predictors(seed: int, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Predictors up to 0.1 rad from the drawn pose (some too far for the separation
    bound or Newton's four steps), and the sign of det J asked for: mostly +1."""
    rng = np.random.default_rng(seed)
    guess = rng.uniform(-0.1, 0.1, shape + (2,)) * rng.uniform(0.0, 1.0, shape + (1,)) ** 2
    return guess, np.where(rng.uniform(size=shape) < 0.1, -1.0, 1.0)


@pytest.mark.parametrize("form", FORMS)
def test_compiled_corrector_agrees_with_numpy(form: str) -> None:
    seed = 300 + FORMS.index(form)
    designs = random_designs(form, seed, D)
    group = designs.group
    k = designs.inputs(np.full(D, 0.01))
    x, sign = _predictors(seed, (3, D))
    _, jac, _, _ = continuation._correct(group, k, np.zeros((D, 2)), np.ones(D))
    # the drawn pose's own mode: det J of its sign
    drawn = np.sign(np.linalg.det(jac))
    _check(group, k, x, sign * drawn)


def test_compiled_corrector_with_an_actuated_coupler() -> None:
    designs = random_designs("RR RR/RR", 99, D)
    group = designs.group
    drawn = designs.inputs(np.full(D, 0.01))
    length = np.abs(np.asarray(group.c) - group.d) * 1.002
    k = ClassIVInputs(drawn.h_a, drawn.h_c, l_b=length)
    x, sign = _predictors(99, (D,))
    _, jac, _, _ = continuation._correct(group, k, np.zeros((D, 2)), np.ones(D))
    _check(group, k, x, sign * np.sign(np.linalg.det(jac)))
