"""The corrector of the continuation compiled: Newton's method and the acceptance tests.

At many positions (the requested angles of many designs, the rungs of a step) the corrector
of the continuation (:func:`~assur.kinematics.higher.continuation._correct`) spends its
time in numpy's calls on short arrays and in one pass over memory per operation, some two
hundred of them per Newton step. Here each position is corrected from start to finish by
compiled scalar code (numba): Newton's method on the group's loop equations with Cramer's
rule, each position stopping once its own step is settled, then its Jacobian, the sign of
its determinant, the margin and the separation bound of the root, each with the operations
of the group's own methods.

:func:`supports` and :func:`has_analogs` tell which groups have kernels without loading
numba; the kernels' modules import it, and :func:`correct`, :func:`analogs` and
:func:`predict` import them when first called. The continuation calls them on a pass over a
large grid (``continuation.KERNEL_POSITIONS``), or on every pass once :func:`load` has been
called: a program that will analyse many positions in this process (a search) loads them
first, and a single smaller analysis never loads numba. The compiled code is cached on disk
after the first run.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from assur.kinematics.higher.coupled import ClassIVCoupled
from assur.kinematics.higher.groups import ClassIVInputs, HigherGroup, Triad, TriadInputs

__all__ = ["analogs", "correct", "engaged", "has_analogs", "load", "predict", "supports"]

#: Whether :func:`load` was called in this process.
_ENGAGED = [False]


def load() -> None:
    """Load numba and the kernels now (compiling them on the first run after installation),
    and correct every later pass of the continuation by them, however few its positions.

    Loading costs about half a second once per process; once loaded, the compiled
    corrector follows even one design 2–4 times faster than numpy's (``docs/higher_groups.md``
    §7). Call it before many analyses of mechanisms with higher groups, as the search does
    for a large budget.
    """
    from assur.kinematics.higher.compiled import coupled, triad  # noqa: F401

    _ENGAGED[0] = True


def engaged() -> bool:
    """Whether :func:`load` was called in this process (every pass then uses the kernels)."""
    return _ENGAGED[0]


def supports(group: HigherGroup[Any]) -> bool:
    """Whether a kernel corrects this group: a class IV group of any form, a triad without a
    P–P leash."""
    return isinstance(group, ClassIVCoupled) or has_analogs(group)


def has_analogs(group: HigherGroup[Any]) -> bool:
    """Whether a kernel gives this group's analogs: a triad without a P–P leash."""
    return isinstance(group, Triad) and not group.pinned


def correct(group: HigherGroup[Any], k: Any, guess: np.ndarray,
            sign: np.ndarray, iterations: int, converged: float, mask: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The corrector and the acceptance tests (a)–(c) of §1.6 at every position of ``guess``
    for a group that :func:`supports` accepts.

    Parameters
    ----------
    group : HigherGroup
        The group; drawn values numbers or one per design (the positions' last axis).
    k : TriadInputs or ClassIVInputs
        Its inputs at the positions, plain arrays.
    guess : ndarray, shape (..., n)
        The predictor.
    sign : ndarray
        The sign of det J of the mode followed, per design.
    iterations, converged : int, float
        Newton's steps at most, and the scaled step at which a position stops.
    mask : ndarray of bool, optional
        The positions to correct (all if None); the others are NaN and fail.

    Returns
    -------
    x, jac, margin, ok : ndarray
        The corrected unknowns (..., n), their Jacobian (..., n, n), the margin (...), and
        where Newton's method converged, det J has the sign ``sign`` and the correction is
        at most a quarter of the separation bound.
    """
    if isinstance(group, ClassIVCoupled):
        from assur.kinematics.higher.compiled.coupled import correct_coupled

        assert isinstance(k, ClassIVInputs)
        return correct_coupled(group, k, guess, sign, iterations, converged, mask)
    from assur.kinematics.higher.compiled.triad import correct_triad

    assert isinstance(group, Triad) and isinstance(k, TriadInputs)
    return correct_triad(group, k, guess, sign, iterations, converged, mask)


def analogs(group: HigherGroup[Any], k: Any, x: np.ndarray, jac: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
    """The analogs x′, x″ at every position of ``x`` for a group that :func:`has_analogs`
    accepts (:func:`~assur.kinematics.higher.continuation.analogs`: the same implicit
    differentiation; ``k`` the inputs as jets in the crank angle)."""
    from assur.kinematics.higher.compiled.triad import analogs_triad

    assert isinstance(group, Triad) and isinstance(k, TriadInputs)
    return analogs_triad(group, k, x, jac)


def predict(t: np.ndarray, x: np.ndarray, x1: np.ndarray, x2: np.ndarray, nearest: np.ndarray,
            targets: np.ndarray, s: float) -> np.ndarray:
    """The predictor x + s·h·x′ + ½h²·x″, h = target − t, of every target (..., shape of
    ``nearest``) from the state ``nearest`` of the states t (S,), x, x′, x″ (S, n); the
    continuation's predictor from the accepted states, in one compiled pass."""
    from assur.kinematics.higher.compiled._jit import predict as kernel

    out = np.empty(nearest.shape + x.shape[-1:])
    kernel(t, x, x1, x2, np.ascontiguousarray(nearest).reshape(-1),
           np.ascontiguousarray(targets, dtype=float).reshape(-1), s,
           out.reshape(-1, x.shape[-1]))
    return out
