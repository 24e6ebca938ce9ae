"""Every real assembly mode of a triad or a class IV group at one position (§1.4, §1.5).

The eliminant Φ(θ) is a trigonometric polynomial of degree m; its coefficients come from the
group in closed form (:meth:`~assur.kinematics.higher.groups.HigherGroup.coefficients`); the
roots of p(E) = E^m·Φ are the eigenvalues of its companion matrix, batched over designs. Roots
on the unit circle give the candidates, each completed, polished by Newton's method on the
reduced equations where the completion does not already satisfy them, then deduplicated on
the joint positions.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from assur.kinematics.higher.groups import (
    HigherGroup,
    K,
    cofactors,
    det_rows,
    expand,
    hadamard,
    plain,
    row_max,
    row_offsets,
    row_sums,
    stack_last,
)

__all__ = ["AssemblyModes", "assembly_modes", "coefficients", "cramer", "newton", "select_mode"]

#: Roots with |ln|E|| up to this are candidates for real modes.
TAU = 1e-6
#: A polished candidate is a mode when max|F| ≤ ACCEPT·L.
ACCEPT = 1e-9
#: Two modes are one when no joint differs by more than SAME·L.
SAME = 1e-7
#: Candidates recovered with max|F| ≤ SETTLED·L need no Newton step; else the Newton steps
#: stop once every step is below this (lengths over L plus angles): Newton converges
#: quadratically there, so the next step would be below roundoff.
SETTLED = 1e-12
#: The complex NaN of a missing point.
NAN = complex(np.nan, np.nan)


def coefficients(group: HigherGroup[K], k: K) -> np.ndarray:
    """Coefficients p_0 … p_2m of p(E) = Σ φ_{n−m} Eⁿ, shape (..., 2m + 1).

    Parameters
    ----------
    group : HigherGroup
        The group (drawn values of shape () or (D,)).
    k : TriadInputs or ClassIVInputs
        Its inputs at one position, plain arrays.

    Returns
    -------
    ndarray, complex
        The coefficients in increasing powers of E (p_{2m−n} = conj p_n: Φ is real on the
        unit circle).

    Examples
    --------
    >>> from assur.kinematics.higher.coupled import ClassIVCoupled
    >>> from assur.kinematics.higher.groups import ClassIVInputs
    >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
    >>> p = coefficients(g, ClassIVInputs(-12.5-20j, 140.5+22j))
    >>> p.shape, bool(np.allclose(p, np.conj(p[::-1])))
    ((7,), True)
    """
    return group.coefficients(k)


def roots(coef: np.ndarray) -> np.ndarray:
    """All roots of the polynomials (increasing powers), NaN where a coefficient is not finite.

    A vanishing leading coefficient (two coincident hinges) sends its roots to a large
    modulus, far off the unit circle, instead of failing.
    """
    n = coef.shape[-1] - 1
    size = np.abs(coef).max(axis=-1, keepdims=True)
    good = np.isfinite(coef).all(axis=-1) & (size[..., 0] > 0)
    safe = np.where(good[..., None], coef, 1.0)
    lead = safe[..., -1:]
    floor = 1e-14 * np.where(good[..., None], size, 1.0)
    lead = np.where(np.abs(lead) < floor, floor, lead)
    companion = np.zeros(coef.shape[:-1] + (n, n), dtype=complex)
    companion[..., 0, :] = -safe[..., -2::-1] / lead
    companion[..., np.arange(1, n), np.arange(n - 1)] = 1.0
    found = np.linalg.eigvals(companion)
    return np.where(good[..., None], found, np.nan)


def solve(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with jac·x = rhs (stacked 2×2 or 3×3) by Cramer's rule; NaN if singular, no error."""
    return cramer(*cofactors(jac), rhs)


def cramer(cof: list[list[np.ndarray]], det: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with J·x = rhs from the cofactors C[i][j] and determinants of J
    (:func:`~assur.kinematics.higher.groups.cofactors`): x_j = Σ_i C_ij·rhs_i / det J; NaN
    where J is singular, no error. Several right-hand sides share one factorisation.

    Examples
    --------
    >>> from assur.kinematics.higher.groups import cofactors
    >>> jac = np.array([[2.0, 1.0], [1.0, 3.0]])
    >>> cramer(*cofactors(jac), np.array([3.0, 4.0])).tolist()
    [1.0, 1.0]
    """
    n = len(cof)
    parts = [rhs[..., i] for i in range(n)]
    with np.errstate(all="ignore"):
        return stack_last([sum(cof[i][j] * parts[i] for i in range(n)) / det for j in range(n)])


def weights(group: HigherGroup[K]) -> np.ndarray:
    """Per-unknown scale of step norms: 1/L for a length, 1 for an angle."""
    length = np.asarray(group.lengths)
    return np.where(length, 1.0 / np.asarray(group.size)[..., None], 1.0)


def newton(group: HigherGroup[K], k: K, x: np.ndarray, iterations: int,
           tol: float = SETTLED) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on the reduced equations.

    Stops after ``iterations`` steps, or earlier once every step is at most ``tol`` (by
    default ``SETTLED``: a step below it leaves the next one below roundoff). Returns the
    iterate and the scaled size of the last step (lengths divided by L, plus angles).
    """
    scale = weights(group)
    step = np.full(x.shape[:-1], np.inf)
    with np.errstate(all="ignore"):
        for _ in range(iterations):
            f, jac = group.equations(x, k)
            dx = solve(jac, -f)
            x = x + dx
            step = row_sums(np.abs(dx * scale))
            if not (step > tol).any():
                break
    return x, step


@dataclass(frozen=True, eq=False)
class AssemblyModes:
    """The real assembly modes of a group at one position.

    Attributes
    ----------
    x : ndarray, shape (..., 2m, n)
        The unknowns of each mode ((W_x, W_y, θ) of a triad, (θ_a, θ_c) of a class IV
        group), sorted by the eliminated angle θ; NaN rows after the last mode.
    count : ndarray, int
        The number of real modes (0, 2, 4 or 6 away from change points).
    joints : dict of str to ndarray, shape (..., 2m)
        The internal joints of each mode.
    margin, det_sign : ndarray, shape (..., 2m)
        The margin (§1.7) and the sign of det J of each mode.
    roots : ndarray, complex, shape (..., 2m)
        Every root E of p, on the unit circle or not.
    """

    x: np.ndarray
    count: np.ndarray
    joints: dict[str, np.ndarray]
    margin: np.ndarray
    det_sign: np.ndarray
    roots: np.ndarray


def assembly_modes(group: HigherGroup[K], k: K) -> AssemblyModes:
    """Every real assembly mode at one position, for one design or many at once.

    Parameters
    ----------
    group : Triad or ClassIVCoupled
        The group; drawn values of shape () or (D,).
    k : TriadInputs or ClassIVInputs
        Its inputs (external hinges, guides) at the position, plain arrays.

    Returns
    -------
    AssemblyModes
        The modes, their joints, margins and det J signs. A position with undefined inputs
        has no mode (count 0).

    Examples
    --------
    The class IV group of test vector V2 has six modes at the sketch:

    >>> from assur.kinematics.higher.coupled import ClassIVCoupled
    >>> from assur.kinematics.higher.groups import ClassIVInputs
    >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
    >>> modes = assembly_modes(g, ClassIVInputs(-12.5-20j, 140.5+22j))
    >>> int(modes.count), np.round(np.degrees(modes.x[3]), 6).tolist()
    (6, [-28.133111, -9.366866])
    """
    found = roots(coefficients(group, k))
    wide, kk = expand(group), expand(k)
    size = np.asarray(group.size)[..., None]
    with np.errstate(all="ignore"):
        near = np.abs(np.log(np.abs(found))) <= TAU
        x = np.where(near[..., None], wide.recover(found / np.abs(found), kk), np.nan)
        f, jac, rows = wide.assessed(x, kk)
        worst = row_max(np.abs(f))
        if not (worst <= SETTLED * size)[near].all():
            x, _ = newton(wide, kk, x, 3)
            f, jac, rows = wide.assessed(x, kk)
            worst = row_max(np.abs(f))
        valid = near & (worst <= ACCEPT * size)
        names = list(wide.joints(x, kk).items())
        # the joints and the eliminated rotation (as a point at the distance L): a triad
        # whose leashes all slide on the base has the same joints in two modes
        turn = size * np.exp(1j * x[..., group.eliminated])
        stack = stack_last([plain(p) for _, p in names] + [turn])
        apart = np.abs(stack[..., :, None, :] - stack[..., None, :, :]).max(axis=-1)
        same = (apart <= SAME * size[..., None]) & valid[..., :, None]
        valid &= ~(same & _earlier(same.shape[-1])).any(axis=-2)
        theta = np.where(valid, x[..., group.eliminated], np.inf)
        # each mode's row in the order of θ, laid flat
        order = np.argsort(theta, axis=-1)
        order += row_offsets(order.shape)
        valid = valid.reshape(-1)[order]
        x, stack = _sorted(x, order, valid, np.nan), _sorted(stack, order, valid, NAN)
        jac, rows = _sorted(jac, order, valid, np.nan), _sorted(rows, order, valid, np.nan)
        margin = hadamard(rows)
    return AssemblyModes(x=x, count=valid.sum(axis=-1),
                         joints={name: stack[..., j] for j, (name, _) in enumerate(names)},
                         margin=margin, det_sign=np.sign(det_rows(jac)), roots=found)


def _sorted(a: np.ndarray, order: np.ndarray, valid: np.ndarray, empty: complex
            ) -> np.ndarray:
    """The rows of ``a`` (..., 2m, …) at the flat row indices ``order`` (..., 2m), ``empty``
    where not ``valid``."""
    lead = order.ndim
    out = np.broadcast_to(a, order.shape + a.shape[lead:]).reshape((-1,) + a.shape[lead:])[order]
    out[~valid] = empty
    return np.asarray(out)


@functools.cache
def _earlier(n: int) -> np.ndarray:
    """[i, j] True where i < j: mode i comes before mode j (n × n)."""
    return np.asarray(np.tril(np.ones((n, n), dtype=bool), -1).T)


def select_mode(group: HigherGroup[K], k: K, modes: AssemblyModes
                ) -> tuple[np.ndarray, np.ndarray]:
    """The mode of the sketch: the one nearest the drawn joints, with the drawn sign of det J.

    Parameters
    ----------
    group : Triad or ClassIVCoupled
        The group.
    k : TriadInputs or ClassIVInputs
        Its inputs at the sketch position (φ = 0).
    modes : AssemblyModes
        The modes there, from :func:`assembly_modes`.

    Returns
    -------
    x : ndarray, shape (..., n)
        The chosen mode (NaN where there is none).
    found : ndarray, bool
        False where no mode has the drawn sign, or the nearest is not at most half as far
        from the drawing as the second nearest (§1.5), or the chosen mode is a change point.

    Examples
    --------
    >>> from assur.kinematics.higher.coupled import ClassIVCoupled
    >>> from assur.kinematics.higher.groups import ClassIVInputs
    >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
    >>> k = ClassIVInputs(-12.5-20j, 140.5+22j)
    >>> x, found = select_mode(g, k, assembly_modes(g, k))
    >>> bool(found), bool(np.allclose(x, 0.0, atol=1e-12))
    (True, True)
    """
    drawn = group.sketch
    with np.errstate(all="ignore"):
        sq = sum(np.abs(modes.joints[name] - np.asarray(drawn[name])[..., None]) ** 2
                 for name in drawn)
        rms = np.sqrt(np.asarray(sq) / len(drawn))
        sign = np.sign(det_rows(group.jacobian(group.drawn(), k)))
        rms = np.where(np.isnan(rms), np.inf, rms)
        ranked = np.sort(rms, axis=-1)
        own = np.where(modes.det_sign == sign[..., None], rms, np.inf)
        # the nearest mode's row, laid flat
        best = np.argmin(own, axis=-1) + row_offsets(own.shape)[..., 0]
        nearest = own.reshape(-1)[best]
        x = modes.x.reshape(-1, modes.x.shape[-1])[best]
        margin = modes.margin.reshape(-1)[best]
        found = np.isfinite(nearest) & (nearest == ranked[..., 0]) \
            & (nearest <= 0.5 * ranked[..., 1]) & (margin >= 1e-6)
    return np.where(found[..., None], x, np.nan), found
