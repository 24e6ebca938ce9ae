"""Following the sketched assembly mode over the crank cycle (§1.6–§1.8).

The mode of the sketch is followed forward from φ = 0 by a predictor from the exact analogs
and a Newton corrector, with step control and a test that the corrector stays in the root's
own basin, so that it never moves to a neighbouring mode. Where the mode ends (two modes
merge at a change point) the backward pass from φ = 0 finds the other end; the angles in
between do not assemble. Every design has its own angle and step: the designs advance
together under masks, one crank step after another. The passes walk the turn in coarse
steps; the requested angles are then solved in one batch from the accepted states, with
the same corrector and tests, and the few that fail them are stepped to.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.higher import compiled
from assur.kinematics.higher.groups import (
    ClassIVDrawing,
    HigherGroup,
    K,
    Triad,
    cofactors,
    det_rows,
    expand,
    hadamard,
    plain,
    row_max,
    row_sums,
    stack_last,
    values,
)
from assur.kinematics.higher.modes import (
    ACCEPT,
    SETTLED,
    TAU,
    AssemblyModes,
    assembly_modes,
    coefficients,
    cramer,
    newton,
    roots,
    select_mode,
    weights,
)
from assur.kinematics.higher.roots import chord, derivatives
from assur.kinematics.higher.roots import separation as roots_apart
from assur.kinematics.higher.track import Chains, chains, grid
from assur.kinematics.jets import Jet
from assur.kinematics.reasons import Reason
from assur.text import Message

__all__ = ["HigherSolution", "Stroke", "analogs", "follow_mode"]

TWO_PI = 2.0 * np.pi
#: Largest crank step of the continuation (rad).
H_MAX = np.radians(8.0)
#: Below this step the mode ends (rad).
H_MIN = 1e-10
#: Newton iterations of the corrector and its convergence bound on the scaled step.
ITERATIONS = 4
CONVERGED = 1e-10
#: From this many positions on, Newton goes on after SETTLE iterations only where it has not
#: converged.
MANY = 256
SETTLE = 2
#: A mode that ends with a margin up to this ends at a change point.
CHANGE = 1e-4
#: After a full turn the joints are back at the sketch within this times L.
CLOSED = 1e-9
#: Step sizes h, h/2, …, h/2^(RUNGS−1) are tried at once while a walk has at most
#: RUNGS_BUDGET rows (one row: the Python cost of a step dominates, not its arithmetic).
RUNGS = 8
RUNGS_BUDGET = 64
#: Lays the accepted angles of the designs side by side on one line (> 2π).
OFFSET = 8.0
#: Newton iterations on the extended system of a change point, and the bound on its scaled
#: residuals |F|/L and |g| at which the point is accepted.
FOLD_ITERATIONS = 8
FOLD_RESIDUAL = 1e-12
#: Central-difference step of g's derivatives (rad for angles and φ, times L for lengths).
FOLD_DIFFERENCE = 1e-6
#: A change point is confirmed this far (pass parameter) before and after it: two real roots
#: of p near the merging pair before, none after (:func:`_meets`).
MEET = 1e-8
#: Newton iterations for the extremum of Φ between the merging pair, and the step (rad)
#: after which they stop: the iteration converges quadratically, so the next step would be
#: of the order of its square, below roundoff (the steps then only jitter by an ulp).
MEET_ITERATIONS = 6
MEET_SETTLED = 1e-9

#: A pass over at least this many positions (requested angles × designs) corrects by a
#: compiled kernel where the group has one: about 1.5 µs less per position, once numba and
#: the cached kernels are loaded (0.5–1 s, once per process), so not for fewer positions,
#: unless the kernels were loaded on purpose (:func:`~assur.kinematics.higher.compiled.load`).
KERNEL_POSITIONS = 50_000
#: Positions corrected at once on a grid (:func:`_correct_at`): few enough that the entries
#: of their Jacobians stay in a core's cache (on 360,000 positions at once the products of
#: the strided entries of the 3×3 matrices cost about four times as much).
BLOCK = 8192

#: "auto" follows up to this many designs of a triad by the path of the root (beyond, the
#: batched steps cost less: ``docs/higher_groups.md`` §3).
ROOTS_DESIGNS = 128

Inputs = Callable[[Any], K]
T = TypeVar("T")


def _part(v: Any, name: str) -> np.ndarray:
    return np.asarray(getattr(v, name)) if isinstance(v, Jet) else np.zeros(np.shape(v))


def _stacked(f: list[Any], name: str) -> np.ndarray:
    """The part ``name`` ("v", "d1", "d2") of the residuals ``f``, stacked on a last axis."""
    return stack_last([np.asarray(J.value(v)) if name == "v" else _part(v, name) for v in f])


def analogs(group: HigherGroup[K], k: K, x: np.ndarray, jac: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and acceleration analogs x′, x″ of the unknowns by implicit differentiation.

    Parameters
    ----------
    group : Triad or ClassIVCoupled
        The group.
    k : TriadInputs or ClassIVInputs
        Its inputs at the position as jets in the crank angle φ.
    x : ndarray, shape (..., n)
        A solution there.
    jac : ndarray, shape (..., n, n), optional
        The Jacobian at x, if already at hand.

    Returns
    -------
    x1, x2 : ndarray, shape (..., n)
        dx/dφ from J x′ = −∂F/∂φ, and d²x/dφ² from J x″ = −(d²F/dφ² with x″ = 0).

    Examples
    --------
    A class IV group whose hinge H_a moves along x at unit speed:

    >>> from assur.kinematics.higher.coupled import ClassIVCoupled
    >>> from assur.kinematics.higher.groups import ClassIVInputs
    >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
    >>> k = ClassIVInputs(Jet(-12.5-20j, 1.0, 0.0), 140.5+22j)
    >>> x1, x2 = analogs(g, k, np.zeros(2))
    >>> x1.shape
    (2,)
    """
    if jac is None:
        jac = group.jacobian(x, values(k))
    return _implicit(group, k, x, cofactors(jac))


def _implicit(group: HigherGroup[K], k: K, x: np.ndarray,
              jac: tuple[list[list[np.ndarray]], np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`analogs` from the cofactors and determinants ``jac`` of the Jacobian: ∂F/∂φ
    with x held (plain), then d²F/dφ² with x′ and x″ = 0, both solved with them."""
    held = [x[..., i] for i in range(group.n)]
    x1 = cramer(*jac, -_stacked(group.residual(held, k), "d1"))
    moving = [Jet(x[..., i], x1[..., i], 0.0) for i in range(group.n)]
    return x1, cramer(*jac, -_stacked(group.residual(moving, k), "d2"))


def separation(group: HigherGroup[K], k: K, x: np.ndarray) -> np.ndarray:
    """A lower bound on the distance from the root E* of x to every other root of p
    (:func:`~assur.kinematics.higher.roots.separation`; §1.6, test (c))."""
    return roots_apart(coefficients(group, k), x[..., group.eliminated])


def finite_inputs(k: Any) -> np.ndarray:
    """True where every input of the record is finite."""
    out: Any = True
    for f in dataclasses.fields(k):
        v = getattr(k, f.name)
        for item in v if isinstance(v, tuple) else (v,):
            if item is not None:
                out = out & np.isfinite(J.value(item))
    return np.asarray(out)


@dataclass(frozen=True, eq=False)
class _Point:
    """States of a pass: the pass parameter t (φ = s·t), the unknowns x and their analogs."""

    t: np.ndarray
    x: np.ndarray
    x1: np.ndarray
    x2: np.ndarray

    def at(self, index: Any) -> _Point:
        """The states at ``index`` (of the axes before the unknowns)."""
        return _Point(self.t[index], self.x[index], self.x1[index], self.x2[index])

    def where(self, mask: np.ndarray, other: _Point) -> _Point:
        """This state where ``mask``, ``other`` elsewhere."""
        wide = mask[..., None]
        return _Point(np.where(mask, self.t, other.t), np.where(wide, self.x, other.x),
                      np.where(wide, self.x1, other.x1), np.where(wide, self.x2, other.x2))


def _analogs(group: HigherGroup[K], k: K, x: np.ndarray, jac: np.ndarray, kernel: bool
             ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`analogs`, by the group's compiled kernel where ``kernel`` and it has one."""
    if kernel and compiled.has_analogs(group):
        return compiled.analogs(group, k, x, jac)
    return analogs(group, k, x, jac)


def _kernel(group: HigherGroup[K], positions: int) -> bool:
    """Whether a pass over ``positions`` positions corrects by the group's compiled kernel
    (:mod:`~assur.kinematics.higher.compiled`): where it has one and they are at least
    ``KERNEL_POSITIONS``, or the kernels were loaded on purpose (:func:`compiled.load`)."""
    return (positions >= KERNEL_POSITIONS or compiled.engaged()) and compiled.supports(group)


def _correct(group: HigherGroup[K], kv: K, guess: np.ndarray, sign: np.ndarray,
             kernel: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Newton from the predictor ``guess`` and the acceptance tests (a)–(c) of §1.6.

    Returns the corrected unknowns, their Jacobian and margin (the Hadamard ratio of the
    margin rows), and where they pass: Newton converged, det J has the sign ``sign``, and
    the correction is at most a quarter of the separation bound; by the group's compiled
    kernel where ``kernel`` (:func:`_kernel`).
    """
    if kernel:
        return compiled.correct(group, kv, guess, sign, ITERATIONS, CONVERGED)
    xn, step = _newton(group, kv, guess)
    with np.errstate(all="ignore"):
        jac, rows = group.lines(xn, kv)
        apart = (np.abs(xn - guess) * weights(group)).sum(axis=-1)
        ok = (step <= CONVERGED) & (np.sign(det_rows(jac)) == sign) \
            & (apart <= 0.25 * separation(group, kv, xn))
        return xn, jac, hadamard(rows), ok


def _newton(group: HigherGroup[K], kv: K, guess: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method from ``guess`` (:func:`~assur.kinematics.higher.modes.newton`,
    ``ITERATIONS`` steps to ``CONVERGED``). On many positions, after the first ``SETTLE``
    steps only those not yet converged go on (laid flat, :func:`_take`)."""
    if guess[..., 0].size < MANY:
        return newton(group, kv, guess, ITERATIONS, CONVERGED)
    x, step = newton(group, kv, guess, SETTLE, CONVERGED)
    more = step > CONVERGED
    small_group, small_k = _take(group, more), _take(kv, more)
    if not more.any() or small_group is None or small_k is None:
        return newton(group, kv, x, ITERATIONS - SETTLE, CONVERGED) if more.any() else (x, step)
    x[more], step[more] = newton(small_group, small_k, x[more], ITERATIONS - SETTLE, CONVERGED)
    return x, step


def _take(record: T, mask: np.ndarray, index: tuple[np.ndarray, ...] | None = None
          ) -> T | None:
    """The record (a group or its inputs) at the positions ``mask`` of a grid, laid flat:
    every array value (each part of a jet), broadcast to the grid after its own leading axes,
    is indexed on the grid's axes; scalars are kept. ``index`` (the grid indices of some of
    the positions ``mask``, as from ``np.nonzero``) takes those only. None where a value does
    not broadcast (the caller then works on the whole grid)."""
    at = (...,) + (np.nonzero(mask) if index is None else index)

    def take(v: Any) -> Any:
        if v is None or isinstance(v, str):
            return v
        if isinstance(v, tuple):
            return tuple(take(item) for item in v)
        if isinstance(v, Jet):
            return Jet(take(v.v), take(v.d1), take(v.d2))
        a = np.asarray(v)
        if a.ndim == 0:
            return v
        lead = a.shape[:max(0, a.ndim - mask.ndim)]
        return np.broadcast_to(a, lead + mask.shape)[at]

    try:
        out = dataclasses.replace(record, **{  # type: ignore[type-var]
            f.name: take(getattr(record, f.name))
            for f in dataclasses.fields(record) if f.init})  # type: ignore[arg-type]
    except ValueError:
        return None
    if isinstance(record, HigherGroup):  # L of the drawn points, taken rather than computed
        vars(out)["size"] = take(record.size)
    return out


def _correct_at(group: HigherGroup[K], kv: K, guess: np.ndarray, sign: np.ndarray,
                mask: np.ndarray, kernel: bool = False
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_correct` on an (N, D) grid of positions, computed only where ``mask`` holds,
    ``BLOCK`` positions at a time (by the compiled ``kernel``: all at once, in place). Returns the
    unknowns, the Jacobians, the margins (the Hadamard ratio of the margin rows) and where
    the tests pass; NaN and False elsewhere."""
    if kernel:
        return compiled.correct(group, kv, guess, sign, ITERATIONS, CONVERGED, mask)
    n = group.n
    x, jac = (np.full(mask.shape + tail, np.nan) for tail in ((n,), (n, n)))
    margin = np.full(mask.shape, np.nan)
    ok = np.zeros(mask.shape, dtype=bool)
    where = np.nonzero(mask)
    sign = np.broadcast_to(sign, mask.shape)
    for start in range(0, where[0].size, BLOCK):
        at = tuple(w[start:start + BLOCK] for w in where)
        small_group, small_k = _take(group, mask, at), _take(kv, mask, at)
        if small_group is None or small_k is None:
            x, jac, margin, ok = _correct(group, kv, guess, sign)
            return x, jac, np.where(mask, margin, np.nan), ok & mask
        x[at], jac[at], margin[at], ok[at] = _correct(small_group, small_k, guess[at], sign[at])
    return x, jac, margin, ok


def _lines_at(group: HigherGroup[K], kv: K, x: np.ndarray, mask: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """The Jacobian and margin rows (:meth:`HigherGroup.lines`) at the positions ``mask``
    of an (N, D) grid, laid flat."""
    small_group, small_k = _take(group, mask), _take(kv, mask)
    with np.errstate(all="ignore"):
        if small_group is None or small_k is None:
            jac, lines = group.lines(x, kv)
            return jac[mask], lines[mask]
        return small_group.lines(x[mask], small_k)


def _singularity(group: HigherGroup[K], x: np.ndarray, kv: Any) -> np.ndarray:
    """g = det J / Π‖J_k‖ with the columns of lengths times L: 0 exactly where J is singular,
    dimensionless, in [−1, 1]."""
    jac = group.jacobian(x, kv) / weights(group)[..., None, :]
    return np.asarray(det_rows(jac) / np.prod(np.linalg.norm(jac, axis=-1), axis=-1))


def _fold(group: HigherGroup[K], inputs: Inputs[K], s: float, start: _Point, active: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The change point nearest ``start`` by Newton's method on the extended system.

    The unknowns are (x, t) with φ = s·t; the equations F(x, φ) = 0 and g(x, φ) = 0
    (:func:`_singularity`). The Jacobian's rows: [J, s·∂F/∂φ] with ∂F/∂φ exact (the inputs
    as jets), and [∂g/∂x, ∂g/∂t] by central differences (step ``FOLD_DIFFERENCE``). Returns
    t, x and where the rows ``active`` converged: max|F| ≤ ``FOLD_RESIDUAL``·L and
    |g| ≤ ``FOLD_RESIDUAL``.
    """
    n = group.n
    width = FOLD_DIFFERENCE / weights(group)
    shift = np.eye(n).reshape((n,) + (1,) * (start.x.ndim - 1) + (n,)) * width
    eye = np.eye(n + 1)
    size = np.asarray(group.size)
    t, x = start.t, start.x
    with np.errstate(all="ignore"):
        for iteration in range(FOLD_ITERATIONS + 1):
            k = inputs(Jet(s * t, 1.0, 0.0))
            kv = values(k)
            f = group.residual([Jet(x[..., i], 0.0, 0.0) for i in range(n)], k)
            value = np.broadcast_to(_stacked(f, "v"), x.shape)
            g = _singularity(group, x, kv)
            done = (np.abs(value).max(axis=-1) <= FOLD_RESIDUAL * size) \
                & (np.abs(g) <= FOLD_RESIDUAL)
            if iteration == FOLD_ITERATIONS or (done | ~active).all():
                break
            gs = _singularity(group, np.concatenate([x + shift, x - shift]), kv)
            ts = np.stack([t + FOLD_DIFFERENCE, t - FOLD_DIFFERENCE])
            gt = _singularity(group, np.broadcast_to(x, (2,) + x.shape), values(inputs(s * ts)))
            system = np.zeros(x.shape[:-1] + (n + 1, n + 1))
            system[..., :n, :n] = group.jacobian(x, kv)
            system[..., :n, n] = s * np.broadcast_to(_stacked(f, "d1"), x.shape)
            system[..., n, :n] = np.moveaxis((gs[:n] - gs[n:]), 0, -1) / (2.0 * width)
            system[..., n, n] = (gt[0] - gt[1]) / (2.0 * FOLD_DIFFERENCE)
            rhs = -np.concatenate([value, g[..., None]], axis=-1)
            safe = active & ~done & np.isfinite(system).all(axis=(-2, -1)) \
                & np.isfinite(rhs).all(axis=-1)
            safe &= np.linalg.det(np.where(safe[..., None, None], system, eye)) != 0.0
            step = np.linalg.solve(np.where(safe[..., None, None], system, eye),
                                   np.where(safe[..., None], rhs, 0.0)[..., None])[..., 0]
            x = x + step[..., :n]
            t = t + step[..., n]
    return t, x, active & done


def _pick(a: np.ndarray, first: np.ndarray) -> np.ndarray:
    """``a`` at the rung ``first`` of its leading axis, for every row."""
    a = np.broadcast_to(a, a.shape[:1] + first.shape + a.shape[1 + first.ndim:])
    index = first.reshape((1,) + first.shape + (1,) * (a.ndim - 1 - first.ndim))
    return np.asarray(np.take_along_axis(a, index, axis=0)[0])


def _walk(group: HigherGroup[K], inputs: Inputs[K], s: float, start: _Point, goal: np.ndarray,
          active: np.ndarray, sign: np.ndarray, log: list[tuple[_Point, np.ndarray]] | None,
          state: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None,
          kernel: bool = False) -> tuple[_Point, np.ndarray, np.ndarray]:
    """Step every active row from ``start.t`` to its ``goal`` (arrays (R, D)) under step control.

    One step from t: the predictor from the analogs, the corrector and the acceptance tests
    (:func:`_correct`); an accepted step doubles h (to at most ``H_MAX``), a rejected one
    halves it, and below ``H_MIN`` the row stops. While the rows are few, the halvings
    h, h/2, h/4, … are tried at once and the largest accepted one is taken, which is where
    the one-at-a-time halving would arrive. Where a row's mode is ending (a step beyond its
    state rejected, the margin falling), the change point is solved for (:func:`_ending`)
    and the row stops there. The accepted states go to ``log`` (with the mask of the rows
    that moved). Returns the last accepted state of each row and, where a row stopped short,
    the pass parameter and the reason (inf and 0 elsewhere).

    Once at most a quarter of the rows still move, the walk goes on with those alone, laid
    flat (:func:`_take`), carrying over their step, margin and flags (``state``).
    """
    shape = goal.shape
    count = max(1, min(RUNGS, RUNGS_BUDGET // max(1, int(np.prod(shape)))))
    halves = 0.5 ** np.arange(count).reshape((count,) + (1,) * len(shape))
    here, h = start, np.full(shape, H_MAX)
    end, why = np.full(shape, np.inf), np.zeros(shape, dtype=np.int8)
    margin, falling, tried = np.full(shape, np.inf), np.zeros(shape, bool), np.zeros(shape, bool)
    if state is not None:
        h, margin, falling, tried = (np.array(np.broadcast_to(v, shape)) for v in state)
    done = ~active
    # rows whose mode may be ending wait, unmoved, for their change points to be solved
    # together: the nearest rejected step beyond each, and whether a smaller step was taken
    waiting, beyond, taken_before = (np.zeros(shape, bool), np.full(shape, np.nan),
                                     np.zeros(shape, bool))
    while not done.all():
        moving = ~done
        few = 4 * moving.sum() <= moving.size
        if waiting.any() and (few or not (moving & ~waiting).any()):
            fold, stop = _ending_at(group, inputs, s, here, beyond, goal, waiting)
            here = fold.where(stop, here)
            if log is not None:
                log.append((here, stop))
            end = np.where(stop, here.t, end)
            why = np.where(stop, Reason.MODE_ENDS, why).astype(np.int8)
            done = done | stop | _stuck(group, inputs, s, here, waiting & ~stop & ~taken_before
                                        & (h < H_MIN), end, why)
            waiting = np.zeros(shape, bool)
            continue
        small = _take(group, moving) if few else None
        if small is not None:
            part: list[tuple[_Point, np.ndarray]] | None = [] if log is not None else None
            last, stop, code = _walk(
                small, _local(inputs, moving), s, here.at(moving), goal[moving],
                np.ones(int(moving.sum()), dtype=bool), np.broadcast_to(sign, shape)[moving],
                part, (h[moving], margin[moving], falling[moving], tried[moving]), kernel)
            for point, mask in part or []:
                wide = np.zeros(shape, dtype=bool)
                wide[moving] = mask
                assert log is not None
                log.append((_widen(here, point, moving), wide))
            here = _widen(here, last, moving)
            end[moving], why[moving] = stop, code
            break
        moving &= ~waiting
        hs = np.where(moving, np.minimum(h, goal - here.t), 0.0)
        trial = hs * halves
        k = inputs(Jet(s * (here.t + trial), 1.0, 0.0))
        kv = values(k)
        guess = here.x + (s * trial)[..., None] * here.x1 \
            + 0.5 * (trial * trial)[..., None] * here.x2
        xn, jac, margins, ok = _correct(group, kv, guess, sign, kernel)
        ok &= moving & ((halves == 1.0) | (trial >= H_MIN))
        taken = np.asarray(ok.any(axis=0))
        first = np.argmax(ok, axis=0)
        with np.errstate(all="ignore"):
            n1, n2 = _analogs(group, k, xn, jac, kernel)
            now = _pick(margins, first)
        step = _pick(trial, first)
        hit = taken & (first == 0) & (hs >= goal - here.t)
        moved = _Point(np.where(hit, goal, here.t + step), _pick(xn, first), _pick(n1, first),
                       _pick(n2, first))
        here = moved.where(taken, here)
        h = np.where(moving, np.where(taken, np.minimum(2.0 * np.where(first == 0, h, step),
                                                        H_MAX), hs * 0.5 ** count), h)
        if log is not None:
            log.append((here, taken))
        falling = np.where(taken, now < margin, falling)
        margin = np.where(taken, now, margin)
        tried &= ~taken
        ending = moving & ~hit & (~taken | (first > 0)) & falling & ~tried
        tried |= ending
        waiting |= ending
        # the nearest rejected step beyond the new state
        beyond = np.where(ending, here.t + np.where(taken, _pick(trial, np.maximum(first - 1, 0)),
                                                    trial[-1]), beyond)
        taken_before = np.where(ending, taken, taken_before)
        done = done | hit | _stuck(group, inputs, s, here,
                                   moving & ~ending & ~taken & (h < H_MIN), end, why)
    return here, end, why


def _stuck(group: HigherGroup[K], inputs: Inputs[K], s: float, here: _Point,
           stuck: np.ndarray, end: np.ndarray, why: np.ndarray) -> np.ndarray:
    """Stop the rows ``stuck`` (a step below ``H_MIN`` rejected) at their states: the pass
    parameter into ``end`` and the reason into ``why`` (in place): an input not finite, the
    mode ending (margin at most ``CHANGE``) or not followed. Returns ``stuck``."""
    if stuck.any():
        kv = values(inputs(s * here.t))
        with np.errstate(all="ignore"):
            margin_here = group.margin(here.x, kv)
        code = np.where(~finite_inputs(kv), Reason.UNDEFINED_INPUT,
                        np.where(margin_here <= CHANGE, Reason.MODE_ENDS, Reason.NOT_FOLLOWED))
        end[stuck], why[stuck] = here.t[stuck], code[stuck]
    return stuck


def _local(inputs: Inputs[K], rows: np.ndarray) -> Inputs[K]:
    """``inputs`` of the ``rows`` of a grid laid flat: evaluated on the whole grid (at φ = 0
    off the rows) and taken at the rows (:func:`_take`)."""
    def spread(v: Any) -> Any:
        if np.ndim(v) == 0:
            return v
        wide = np.zeros(np.shape(v)[:-1] + rows.shape)
        wide[..., rows] = v
        return wide

    def local(t: Any) -> K:
        wide = Jet(spread(t.v), spread(t.d1), spread(t.d2)) if isinstance(t, Jet) else spread(t)
        taken = _take(inputs(wide), rows)
        assert taken is not None
        return taken

    return local


def _widen(base: _Point, part: _Point, rows: np.ndarray) -> _Point:
    """``base`` with the ``rows`` replaced by the flat states ``part``."""
    out = _Point(*(np.array(np.broadcast_to(getattr(base, name), getattr(base, name).shape))
                   for name in ("t", "x", "x1", "x2")))
    for name in ("t", "x", "x1", "x2"):
        getattr(out, name)[rows] = getattr(part, name)
    return out


def _ending_at(group: HigherGroup[K], inputs: Inputs[K], s: float, here: _Point,
               beyond: np.ndarray, goal: np.ndarray, rows: np.ndarray
               ) -> tuple[_Point, np.ndarray]:
    """:func:`_ending` computed on the ``rows`` only, laid flat (the inputs are evaluated on
    the whole grid, at φ = 0 off the rows, and taken at the rows)."""
    small = _take(group, rows)
    if small is None:
        return _ending(group, inputs, s, here, beyond, goal, rows)
    fold, stop = _ending(small, _local(inputs, rows), s, here.at(rows), beyond[rows], goal[rows],
                         np.ones(int(rows.sum()), dtype=bool))
    hold = np.zeros(rows.shape, dtype=bool)
    hold[rows] = stop
    return _widen(here, fold, rows), hold


def _ending(group: HigherGroup[K], inputs: Inputs[K], s: float, here: _Point, beyond: np.ndarray,
            goal: np.ndarray, rows: np.ndarray) -> tuple[_Point, np.ndarray]:
    """The change point where the mode of the ``rows`` ends, if it lies near ``beyond``.

    The change point (t*, x*) by :func:`_fold` from the accepted state is taken where
    Newton converged, here.t < t* < here.t + 2·(beyond − here.t) and t* < ``goal`` (the step
    to ``beyond`` was rejected, but near a change point its predictor fails before the mode
    ends; a goal before t* is reached by stepping), and x* is where the square-root form of a fold
    (x − x* ∝ √(t* − t)) puts it from the state and its analog, x* ≈ x + 2(t* − t)·s·x′,
    to half the distance |x* − x| (a change point of other modes is far from there).
    Returns the change points as states (analogs NaN: unbounded there) and where they hold.
    """
    t, x, ok = _fold(group, inputs, s, here, rows)
    w = weights(group)
    with np.errstate(all="ignore"):
        model = here.x + (2.0 * s * (t - here.t))[..., None] * here.x1
        apart = (np.abs(x - here.x) * w).sum(axis=-1)
        off = (np.abs(x - model) * w).sum(axis=-1)
        ok &= (t > here.t) & (t < 2.0 * beyond - here.t) & (t < goal) & (off <= 0.5 * apart)
    ok &= _meets(group, inputs, s, t, x, ok)
    blank = np.full(x.shape, np.nan)
    return _Point(t, x, blank, blank), ok


def _pair(group: HigherGroup[K], k: K, theta: np.ndarray) -> np.ndarray:
    """The sign of the local discriminant of the two roots of Φ near ``theta``.

    Φ(θ) = Σ φ_n e^{inθ} (n = −m … m, the coefficients of p) has an extremum θ_c between the
    two roots of a merging pair (:func:`_extremum`). Two real roots lie about θ_c where
    Φ(θ_c) and Φ″(θ_c) have opposite signs, none where they have the same: returns
    −sign(Φ(θ_c)·Φ″(θ_c)), +1 with the pair on the unit circle, −1 with it off.
    """
    return np.asarray(np.sign(_extremum(coefficients(group, k), theta)[1]))


def _meets(group: HigherGroup[K], inputs: Inputs[K], s: float, t: np.ndarray, x: np.ndarray,
           rows: np.ndarray) -> np.ndarray:
    """Where the change point (t, x) of the ``rows`` is one: two modes really meet there.

    Near a change point the merging pair of roots of p is real on the side the mode comes
    from and complex beyond it: the local discriminant (:func:`_pair`) is +1 at t − ``MEET``
    and −1 at t + ``MEET``. Two modes that only pass close to each other keep it +1 on both
    sides (the extended system of :func:`_fold` then converges halfway between them, where
    det J = 0 and the residual is small but the pose is on neither mode).
    """
    out = np.zeros(rows.shape, dtype=bool)
    if not rows.any():
        return out
    return np.asarray(rows & _crosses(group, inputs, s * (t - MEET), s * (t + MEET),
                                      x[..., group.eliminated]))


def _crosses(group: HigherGroup[K], inputs: Inputs[K], before: np.ndarray, after: np.ndarray,
             theta: np.ndarray) -> np.ndarray:
    """Where the local discriminant of the pair of roots near ``theta`` (:func:`_pair`) is +1
    at the crank angles ``before`` and −1 at ``after``: the pair real on one side, complex on
    the other (the inputs at both evaluated at once)."""
    sides = _pair(group, values(inputs(np.stack([before, after]))), theta)
    return np.asarray((sides[0] > 0) & (sides[1] < 0))


def _kept(v: Any, mask: np.ndarray, jets: bool) -> list[np.ndarray]:
    """The parts of a joint or rotation ``v`` (N, D) — its value, and with ``jets`` both
    analogs (zero for a value that is not a jet) — where ``mask`` holds (NaN elsewhere),
    transposed to (D, N)."""
    parts = (v.v, v.d1, v.d2) if isinstance(v, Jet) else (v, 0.0 * v, 0.0 * v) if jets else (v,)
    if mask.all():  # nothing to blank: the parts as they are, where they have the grid's shape
        return [np.asarray(part).T if np.shape(part) == mask.shape
                else np.broadcast_to(part, mask.shape).T.copy() for part in parts]
    return [np.where(mask, np.broadcast_to(part, mask.shape), np.nan).T for part in parts]


@dataclass(frozen=True, eq=False)
class _Pass:
    """The mode followed in one direction: results at the targets and where it ended.

    ``x`` (D, N, n) and ``margin`` (D, N) are NaN at targets not reached; ``out`` holds the
    joints ("p.") and rotations ("r.") as their value, or value and both analogs, (D, N).
    """

    x: np.ndarray
    out: dict[str, list[np.ndarray]]
    margin: np.ndarray
    end: np.ndarray
    why: np.ndarray

    @property
    def reached(self) -> np.ndarray:
        return np.asarray(~np.isnan(self.x[..., 0]))


def _anchors(log: list[tuple[_Point, np.ndarray]], targets: np.ndarray, offset: float
             ) -> tuple[_Point, np.ndarray, np.ndarray, np.ndarray]:
    """The accepted states of a pass, and per target and design (``targets`` (N, D)) the
    nearest and the preceding one.

    Returns the states laid flat (design after design, t increasing), the flat index of the
    nearest and of the preceding state (N, D), and where the target lies within the
    stretch the pass covered. ``offset`` exceeds every pass parameter: it lays the designs
    side by side on one line.
    """
    followed = log[0][1]
    moved = np.stack([mask for _, mask in log])
    moved[0] |= ~followed.any()  # no design is followed: keep the starts, reach nothing
    design, step = np.nonzero(moved.T)
    states = _Point(*(np.stack([getattr(p, f) for p, _ in log])[step, design]
                      for f in ("t", "x", "x1", "x2")))
    d = moved.shape[1]
    count = np.bincount(design, minlength=d)
    first = np.cumsum(count) - count
    # the designs side by side on one line: t < offset
    query = targets + offset * np.arange(d)
    # design after design the queries increase, and a sorted search is about twice as fast
    after = np.searchsorted(states.t + offset * design, np.ascontiguousarray(query.T),
                            side="right").T
    before = np.maximum(after - 1, 0)
    inside = (after > first) & (after < first + count) & followed
    on_last = (after > first) & (states.t[before] == targets) & followed
    nearest = np.where(inside & (states.t[np.minimum(after, len(design) - 1)] - targets
                                 < targets - states.t[before]), after, before)
    return states, nearest, before, inside | on_last


def _follow(group: HigherGroup[K], inputs: Inputs[K], x0: np.ndarray, targets: np.ndarray,
            s: float, done: np.ndarray, jets: bool, span: Any = TWO_PI) -> _Pass:
    """Follow x0 from φ = 0 through φ = s·t for the targets 0 ≤ t ≤ span (§1.6).

    The pass walks to ``span`` (2π for a crank; per design along a stroke) in coarse
    accepted steps (:func:`_walk`); then every target is solved at once from the nearest
    accepted state (predictor from its analogs, corrector, the same acceptance tests), and
    the few that fail are stepped to from the state before them. ``targets`` are (N,) for
    every design or (N, D), one column per design. ``jets`` asks for the analogs of the
    joints and rotations.
    """
    d = x0.shape[0]
    grid = np.broadcast_to(targets[:, None] if targets.ndim == 1 else targets,
                           (len(targets), d))
    goal = np.broadcast_to(np.asarray(span, dtype=float), (1, d)).copy()
    x = np.where(done[:, None], group.drawn(), x0)[None]
    k = inputs(Jet(np.zeros((1, d)), 1.0, 0.0))
    jac = group.jacobian(x, values(k))
    sign = np.sign(det_rows(jac))
    with np.errstate(all="ignore"):
        x1, x2 = analogs(group, k, x, jac)
    log = [(_Point(np.zeros((1, d)), x, x1, x2), ~done[None])]
    kernel = _kernel(group, grid.size)
    _, end, why = _walk(group, inputs, s, log[0][0], goal, ~done[None], sign, log, None, kernel)
    log = [(p.at(0), mask[0]) for p, mask in log]
    states, nearest, before, reach = _anchors(log, grid, max(OFFSET, float(goal.max()) + 1.0))
    angle = np.broadcast_to(s * grid, reach.shape)
    k = inputs(Jet(angle, 1.0, 0.0)) if jets else inputs(angle)
    kv = values(k)
    if kernel:
        guess = compiled.predict(states.t, states.x, states.x1, states.x2, nearest, grid, s)
    else:
        anchor = states.at(nearest)
        h = grid - anchor.t
        guess = anchor.x + (s * h)[..., None] * anchor.x1 + 0.5 * (h * h)[..., None] * anchor.x2
    # between the last accepted state and the change point where the pass ended (its
    # analogs NaN): x* + (x_b − x*)·√((t* − t)/(t* − t_b)), the square-root form of a fold
    after = np.minimum(before + 1, len(states.t) - 1)
    with np.errstate(all="ignore"):
        root = np.sqrt((states.t[after] - grid) / (states.t[after] - states.t[before]))
        ending = reach & (states.t[after] > states.t[before]) \
            & np.isnan(states.x1[after, 0]) & (root <= 1.0)
        if ending.any():
            tip, prior = states.x[after[ending]], states.x[before[ending]]
            guess[ending] = tip + (prior - tip) * root[ending][:, None]
    x, jac, margin, ok = _correct_at(group, kv, guess, sign[0], reach, kernel)
    retry = reach & ~ok
    if retry.any():
        rank = np.cumsum(retry, axis=0) - 1
        j, design = np.nonzero(retry)
        shape = (int(rank.max()) + 1, d)
        start = _Point(np.zeros(shape), np.zeros(shape + (group.n,)), np.zeros(shape + (group.n,)),
                       np.zeros(shape + (group.n,)))
        for name in ("t", "x", "x1", "x2"):
            getattr(start, name)[rank[j, design], design] = \
                getattr(states, name)[before[j, design]]
        aims, active = np.zeros(shape), np.zeros(shape, dtype=bool)
        aims[rank[j, design], design] = grid[j, design]
        active[rank[j, design], design] = True
        last, _, _ = _walk(group, inputs, s, start, aims, active, sign[0], None, None, kernel)
        ok[j, design] = last.t[rank[j, design], design] == aims[rank[j, design], design]
        x[j, design] = last.x[rank[j, design], design]
        fresh = np.zeros(reach.shape, dtype=bool)
        fresh[j, design] = True
        jac[fresh], rows = _lines_at(group, kv, x, fresh)
        with np.errstate(all="ignore"):
            margin[fresh] = hadamard(rows)
    reached = reach & ok
    x = np.where(reached[..., None], x, np.nan)
    if jets:
        with np.errstate(all="ignore"):
            x1, x2 = _analogs(group, k, x, jac, kernel)
        cols: Any = [Jet(x[..., i], x1[..., i], x2[..., i]) for i in range(group.n)]
    else:
        cols, k = x, kv
    with np.errstate(all="ignore"):
        found = {"p." + a: b for a, b in group.joints(cols, k).items()}
        found.update({"r." + a: b for a, b in group.rotations(cols, k).items()})
    out = {name: _kept(v, reached, jets) for name, v in found.items()}
    return _Pass(x=x.transpose(1, 0, 2), out=out, margin=np.where(reached, margin, np.nan).T,
                 end=end[0], why=why[0])


@dataclass(frozen=True, eq=False)
class HigherSolution:
    """The sketched mode of a triad or a class IV group over the requested crank angles.

    Attributes
    ----------
    joints : dict of str to ndarray or Jet, complex, shape (..., N)
        The internal joints (triad: P1, P2, P3; class IV: C, D, E, F); jets with the exact
        analogs when asked for. NaN where the group does not exist.
    rotations : dict of str to ndarray or Jet, shape (..., N)
        The rotation of each link from the sketch (triad: base, leash1–3; class IV: a, b, c,
        d). A point drawn at z⁰ on a link with origin O is at O + (z⁰ − O⁰)·e^{i·rotation}.
    x : ndarray, shape (..., N, n)
        The unknowns: (W_x, W_y, θ) with W = P₁ − A₁, or (θ_a, θ_c).
    margin : ndarray, shape (..., N)
        The Hadamard ratio of the constraint lines where the mode is followed; where it is not,
        −min|ln|E|| over the roots of p off the unit circle (0 at a change point). NaN where
        an input is undefined.
    exists : ndarray, bool, shape (..., N)
        The mode is followed there and ``margin >= delta``.
    reason : ndarray, int8, shape (..., N)
        0, 7 (an earlier group fails), 8 (:attr:`~assur.kinematics.reasons.Reason.MODE_ENDS`) or 9
        (:attr:`~assur.kinematics.reasons.Reason.NOT_FOLLOWED`).
    ends : ndarray, shape (..., 2)
        The crank angles φ_f, φ_b in (0, 2π) where the forward and the backward pass from the
        sketch stop; NaN where the mode assembles over the whole turn.
    end_reasons : ndarray, int8, shape (..., 2)
        Why each pass stopped (7, 8 or 9; 0 where it did not).
    closed : ndarray, bool
        False where a full turn without a change point does not bring the mode back to the
        sketch (a circuit of more than one turn).
    found : ndarray, bool
        The sketch picks a mode (§1.5).
    modes : AssemblyModes
        Every real mode at the sketch position.
    periodic : bool
        True for a crank (angles modulo 2π); False along an actuator's stroke, where the
        positions and ``ends`` are actuator lengths (mm), the analogs derivatives with
        respect to the length, and neither ``closed`` nor ``overlap`` apply.
    """

    joints: dict[str, Any]
    rotations: dict[str, Any]
    x: np.ndarray
    margin: np.ndarray
    exists: np.ndarray
    reason: np.ndarray
    ends: np.ndarray
    end_reasons: np.ndarray
    closed: np.ndarray
    found: np.ndarray
    modes: AssemblyModes
    periodic: bool = True

    @property
    def overlap(self) -> np.ndarray:
        """True where both passes end at change points and the backward end φ_b comes before
        the forward end φ_f: every angle has a position, but the crank cannot make a full turn,
        and the positions after φ_f are those reached turning backward from the sketch (another
        assembly at the same angles, so the motion jumps at φ_f)."""
        both = (self.end_reasons == Reason.MODE_ENDS).all(axis=-1) & self.periodic
        with np.errstate(invalid="ignore"):
            return np.asarray(both & (self.ends[..., 1] < self.ends[..., 0]))

    def notes(self, design: int = 0) -> list[Message]:
        """What a user is told about one design: the sketch, the ends, the return.

        Examples
        --------
        >>> from assur.kinematics.higher.coupled import ClassIVCoupled
        >>> from assur.kinematics.higher.groups import ClassIVInputs
        >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
        >>> sol = follow_mode(g, lambda phi: ClassIVInputs(-12.5-20j, 140.5+22j), [0.0])
        >>> [m.text() for m in sol.notes()]
        ['6 real assembly modes at the sketch']
        """
        index = (design,) if self.found.ndim else ()
        out = [Message("higher.modes.count", {"n": int(self.modes.count[index])})]
        if not self.found[index]:
            out.append(Message("higher.sketch.no_mode"))
        codes: dict[int, str] = {Reason.UNDEFINED_INPUT: "higher.end.input",
                 Reason.MODE_ENDS: "higher.end.change_point",
                 Reason.NOT_FOLLOWED: "higher.end.lost"}
        if not self.periodic:
            codes = {code: f"higher.sketch.actuator_end.{name.rsplit('.', 1)[1]}"
                     for code, name in codes.items()}
        for end, code in zip(self.ends[index], self.end_reasons[index], strict=True):
            if code and self.periodic:
                out.append(Message(codes[int(code)], {"angle": float(np.degrees(end))}))
            elif code:
                out.append(Message(codes[int(code)], {"length": float(end)}))
        if not self.closed[index]:
            out.append(Message("higher.not_closed"))
        if self.overlap[index]:
            forward, backward = np.degrees(self.ends[index])
            out.append(Message("higher.overlap", {"forward": float(forward),
                                                  "backward": float(backward)}))
        return out


def _gap(group: HigherGroup[K], k: K, rows: np.ndarray) -> np.ndarray:
    """The margin where a mode is gone, where the mask ``rows`` holds (NaN elsewhere).

    −min|ln|E|| over the roots of p off the unit circle. A class IV group with both external
    pairs sliding may have none (its modes go on, with unbounded slides, beyond the position
    where the guides are parallel): there −|sin| of the angle between the guides, 0 where the
    mode ends at the parallel position.
    """
    small_group, small_k = _take(group, rows), _take(k, rows)
    with np.errstate(all="ignore"):
        if small_group is None or small_k is None:
            coef = np.broadcast_to(coefficients(group, k), rows.shape + (2 * group.degree + 1,))
            coef = coef[rows]
        else:
            coef = coefficients(small_group, small_k)
    out = np.full(rows.shape, np.nan)
    with np.errstate(all="ignore"):
        size = np.abs(np.log(np.abs(roots(coef))))
        out[rows] = -np.where(size > TAU, size, np.inf).min(axis=-1)
        if isinstance(group, ClassIVDrawing) and all(group.slides):
            guides = -np.abs(np.sin(np.angle(np.asarray(k.u_c) / k.u_a)))
            out = np.where(rows & np.isneginf(out), guides, out)
    return out


def _spread(k: Any, d: int) -> Any:
    """The inputs record with every value broadcast to the D designs."""
    def spread(v: Any) -> Any:
        if isinstance(v, tuple):
            return tuple(spread(item) for item in v)
        return None if v is None else np.broadcast_to(v, (d,))

    return dataclasses.replace(k, **{f.name: spread(getattr(k, f.name))
                                     for f in dataclasses.fields(k)})


def _designs(group: HigherGroup[K], inputs: Inputs[K]) -> tuple[tuple[int, ...], K]:
    """The design shape, () for one design, (D,) for many; and the inputs (plain) at φ = 0
    of a single crank angle, which are those of the sketch when there is one design."""
    first = values(inputs(np.zeros(1)))
    shapes = [np.shape(group.size)]
    for f in dataclasses.fields(first):
        v = getattr(first, f.name)
        shapes += [np.shape(item) for item in (v if isinstance(v, tuple) else (v,))
                   if item is not None]
    shape = np.broadcast_shapes(*shapes)
    return (() if shape in ((), (1,)) and np.shape(group.size) == () else shape), first


@dataclass(frozen=True, eq=False)
class Stroke:
    """An actuator's stroke: the input is a length q (mm) over [low, high], drawn at start.

    Attributes
    ----------
    low, high : float
        The ends of the stroke.
    start : float or ndarray
        The actuator's length at the sketch, q₀ (shape () or (D,)).
    """

    low: float
    high: float
    start: Any


def follow_mode(group: HigherGroup[K], inputs: Inputs[K], phi: Any, *, analogs: bool = False,
                delta: float | np.ndarray = 0.0, stroke: Stroke | None = None,
                method: str = "auto") -> HigherSolution:
    """Positions of the sketched assembly mode over the crank cycle, for one or many designs.

    Parameters
    ----------
    group : Triad or ClassIVCoupled
        The group; drawn values of shape () or (D,).
    inputs : callable
        ``inputs(phi)`` → :class:`TriadInputs` or :class:`ClassIVInputs`: the external
        hinges and guides at the crank angles ``phi`` (shape (D,), each design at its own
        angle), for a plain array and for a :class:`Jet` in φ. The continuation calls it at
        every step.
    phi : array_like, shape (N,)
        Crank angles from the sketch (rad); reduced modulo 2π.
    analogs : bool
        Return the joints and rotations as jets with the exact analogs.
    delta : float or ndarray
        The assigned tolerance: the group exists where ``margin >= delta``.
    stroke : Stroke, optional
        The input is an actuator's length: ``phi`` and the argument of ``inputs`` are
        lengths q (mm), the mode is followed from the sketch's length q₀ up to the stroke's
        upper end and down to its lower end (:func:`_follow_stroke`).
    method : {"auto", "roots", "steps"}
        How a crank's turn is followed: "steps" by the continuation; "roots" by the path of
        the sketched root through every real root at every angle
        (:func:`~assur.kinematics.higher.track.chains`), taken for a design where each of
        its links passes the continuation's step test or is walked through by sub-steps,
        also where the mode ends (the change points located on the path), the other
        designs by steps;
        "auto" by roots for up to ``ROOTS_DESIGNS`` designs of a triad with a bar and no P–P
        leash (where the steps' cost is Python's, a few dozen steps for each design), by
        steps otherwise.

    Returns
    -------
    HigherSolution

    Notes
    -----
    The mode is picked at φ = 0 by :func:`select_mode` among all real modes and followed
    forward to 2π; if it ends at a change point it is followed backward from 0 to the other
    end (§1.6). Each step: the predictor x + h·x′ + ½h²·x″ from the exact analogs, at most
    4 Newton iterations, and acceptance only if Newton converged, det J keeps its sign and
    the correction is under a quarter of a lower bound on the distance to every other root
    of p; otherwise the step is halved. A step below 1e-10 rad ends the mode.

    Examples
    --------
    The class IV group of test vector V2 driven by a crank O–B:

    >>> from assur.kinematics.higher.coupled import ClassIVCoupled
    >>> from assur.kinematics.higher.groups import ClassIVInputs
    >>> from assur.kinematics.jets import expi
    >>> g = ClassIVCoupled(-12.5-20j, 57+66j, 25.5+98.5j, 140.5+22j, 115+67j, 87+118j)
    >>> crank = lambda phi: ClassIVInputs((-12.5-20j) * expi(phi), 140.5+22j)
    >>> sol = follow_mode(g, crank, np.radians([60.0, 150.0]))
    >>> np.round(sol.joints["C"], 6).tolist()
    [(56.068701+80.176725j), (77.60907+105.948616j)]
    """
    phi = np.asarray(phi, dtype=float).reshape(-1)
    if stroke is not None:
        scale, start = group.size, stroke.start
        actuator = inputs

        def inputs(t: Any) -> Any:
            return actuator(start + scale * t)

    if method not in ("auto", "roots", "steps"):
        raise ValueError(f"method: 'auto', 'roots' or 'steps', not {method!r}")
    shape, first = _designs(group, inputs)
    d = int(np.prod(shape))
    k0 = _spread(first if d == 1 else values(inputs(np.zeros(d))), d)
    modes = assembly_modes(group, k0)
    x0, found = select_mode(group, k0, modes)
    x0 = np.broadcast_to(x0, (d, group.n))
    found = np.broadcast_to(found, (d,))
    if stroke is not None:
        solution = _follow_stroke(group, inputs, phi, stroke, x0, (modes, found), analogs,
                                  delta)
        return _squeeze(solution) if shape == () else solution
    if method == "roots" or (method == "auto" and d <= ROOTS_DESIGNS and _tracked(group)):
        solution = _follow_tracked(group, inputs, phi, x0, found, modes, analogs, delta)
    else:
        solution = _step_follow(group, inputs, phi, x0, found, modes, analogs, delta)
    return _squeeze(solution) if shape == () else solution


def _step_follow(group: HigherGroup[K], inputs: Inputs[K], phi: np.ndarray, x0: np.ndarray,
                 found: np.ndarray, modes: AssemblyModes, analogs: bool,
                 delta: float | np.ndarray) -> HigherSolution:
    """The sketched mode x0 (D, n) followed step by step (:func:`_follow`), forward from the
    sketch and backward where the forward pass ends."""
    d = x0.shape[0]
    k0 = _spread(values(inputs(np.zeros(d))), d)
    wrapped = np.mod(phi, TWO_PI)
    order = np.argsort(wrapped, kind="stable")
    unsort = np.argsort(order)
    grid = wrapped[order]
    n = len(grid)
    ahead = _follow(group, inputs, x0, np.append(grid, TWO_PI), 1.0, ~found, analogs)
    around = ahead.reached[:, -1]
    size = np.broadcast_to(group.size, (d,))
    with np.errstate(all="ignore"):
        home = np.max([np.abs(ahead.out["p." + a][0][:, -1] - np.broadcast_to(plain(v), (d,)))
                       for a, v in group.joints(x0, k0).items()], axis=0)
    closed = ~around | (home <= CLOSED * size)
    back_targets = np.append(TWO_PI - grid[grid > 0][::-1], TWO_PI)
    # the backward pass, where the forward one did not go round
    behind = (_follow(group, inputs, x0, back_targets, -1.0, ~found | around, analogs)
              if (found & ~around).any() else None)
    back_index = np.full(n, -1)
    back_index[grid > 0] = np.arange(len(back_targets) - 1)[::-1]
    use_ahead = ahead.reached[:, :n]
    use_behind = ~use_ahead & (back_index >= 0) & (
        behind.reached[:, back_index] if behind is not None else False)
    reached = (use_ahead | use_behind)[:, unsort]

    sorted_already = bool((unsort == np.arange(n)).all())

    def merge(a: np.ndarray, b: np.ndarray | None) -> np.ndarray:
        """A result of both passes (NaN where a pass did not reach) at the requested angles."""
        merged = (np.where(use_ahead, a[..., :n], np.where(use_behind, b[..., back_index], np.nan))
                  if b is not None and use_behind.any() else a[..., :n])
        return merged if sorted_already else merged[..., unsort]

    back_why = behind.why if behind is not None else np.zeros(d, dtype=np.int8)
    x = np.stack([merge(ahead.x[..., i], None if behind is None else behind.x[..., i])
                  for i in range(group.n)], axis=-1)
    merged_ends = (ahead.why == Reason.MODE_ENDS) & (back_why == Reason.MODE_ENDS)
    margin, reason = _unreached(group, inputs, phi, reached,
                                merge(ahead.margin, None if behind is None else behind.margin),
                                found & merged_ends)
    with np.errstate(invalid="ignore"):
        exists = reached & (margin >= np.asarray(delta)[..., None])
    reason = np.where(reached & ~exists, Reason.MODE_ENDS, reason).astype(np.int8)

    below = (reached & ~exists).any()

    def final(name: str) -> Any:
        parts = [merge(a, None if behind is None else behind.out[name][i])
                 for i, a in enumerate(ahead.out[name])]
        if below:
            parts = [np.where(exists, part, np.nan) for part in parts]
        return Jet(*parts) if analogs else parts[0]

    ends = np.stack([np.where(ahead.why > 0, ahead.end, np.nan),
                     np.where(back_why > 0, TWO_PI - (behind.end if behind is not None else 0.0),
                              np.nan)], axis=-1)
    return HigherSolution(
        joints={a[2:]: final(a) for a in ahead.out if a.startswith("p.")},
        rotations={a[2:]: final(a) for a in ahead.out if a.startswith("r.")},
        x=np.where(exists[..., None], x, np.nan), margin=margin, exists=exists, reason=reason,
        ends=ends, end_reasons=np.stack([ahead.why, back_why], axis=-1), closed=closed,
        found=found, modes=modes)


def _tracked(group: HigherGroup[K]) -> bool:
    """Whether "auto" follows the group by the path of its root: a triad with a bar and no
    P–P leash (its eliminated angle fixes the pose). Not a class IV group: the sketched root
    of ``class_iv_group.yaml`` has a neighbour closer than the samples' spacing from φ = 0
    on and passes within about 1e-7 rad of it near φ = 45.3° (a near-double root of the
    eliminant); the walk of its links spends its trials before and the steps follow anyway,
    so there the roots only add their cost (measured 2–4 times slower)."""
    return isinstance(group, Triad) and not group.pinned and not group.barless


@dataclass(frozen=True, eq=False)
class _Root:
    """Roots of the eliminant on the path: θ, its analogs θ′ and θ″ in φ, its separation
    bound from every other root of p, the sign of Φ′ there, and the pose x (..., n) with
    its analog x′."""

    theta: np.ndarray
    t1: np.ndarray
    t2: np.ndarray
    apart: np.ndarray
    slope: np.ndarray
    x: np.ndarray
    x1: np.ndarray

    def at(self, index: Any) -> _Root:
        """The roots at ``index``."""
        return _Root(*(getattr(self, f.name)[index] for f in dataclasses.fields(self)))

    def where(self, mask: np.ndarray, other: _Root) -> _Root:
        """These roots where ``mask``, ``other`` elsewhere."""
        def pick(name: str) -> np.ndarray:
            mine = getattr(self, name)
            return np.asarray(np.where(mask.reshape(mask.shape + (1,) * (mine.ndim - mask.ndim)),
                                       mine, getattr(other, name)))

        return _Root(*(pick(f.name) for f in dataclasses.fields(self)))


def _link(h: np.ndarray, here: _Root, there: _Root) -> np.ndarray:
    """The continuation's step test on a link of the path from ``here`` to ``there``, h = φ
    there − φ here (either sign): the root's analogs predict the other root, θ + hθ′ + ½h²θ″,
    within a quarter of its separation bound, and the other root's analogs predict this one
    back within a quarter of this one's; both keep the sign of Φ′."""
    with np.errstate(invalid="ignore"):
        ahead = here.theta + h * here.t1 + 0.5 * h * h * here.t2
        back = there.theta - h * there.t1 + 0.5 * h * h * there.t2
        return np.asarray((chord(ahead, there.theta) <= 0.25 * there.apart)
                          & (chord(back, here.theta) <= 0.25 * here.apart)
                          & (there.slope == here.slope))


def _links(columns: np.ndarray, root: _Root) -> np.ndarray:
    """Where each link of the path between its columns (U + 1,) passes the step test
    (:func:`_link`), shape (U, D)."""
    h = np.diff(columns)[:, None]
    return _link(h, root.at(slice(None, -1)), root.at(slice(1, None)))


def _poses(group: HigherGroup[K], k: K, theta: np.ndarray, sign: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The poses at the roots θ of the eliminant (the inputs ``k`` as jets in φ), by the
    group's recovery and 2 Newton iterations on the reduced equations; their analogs x′, x″,
    margin rows, and where they are poses of the mode: the residual at most ``ACCEPT``·L and
    det J of the sketch's ``sign``.

    An iteration's step below ``SETTLED`` ends them, and the residual, Jacobian and margin
    rows are then those of the point it started from: the step moved the pose by less than
    ``SETTLED``·L, so they differ from the final point's by that relative amount, and one
    evaluation of the equations is saved."""
    kv = values(k)
    scale = weights(group)
    with np.errstate(all="ignore"):
        x = group.recover(np.exp(1j * theta), kv)
        for iteration in range(POSE_ITERATIONS + 1):
            f, jac, lines = group.assessed(x, kv)
            factors = cofactors(jac)
            if iteration == POSE_ITERATIONS:
                break
            dx = cramer(*factors, -f)
            x = x + dx
            if not (row_sums(np.abs(dx * scale)) > SETTLED).any():
                break
        x1, x2 = _implicit(group, k, x, factors)
        posed = (row_max(np.abs(f)) <= ACCEPT * np.asarray(group.size)) \
            & (np.sign(factors[1]) == sign)
    return x, x1, x2, lines, posed


def _extremum(coef: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The extremum θ_c of Φ nearest ``theta`` (Newton's method on Φ′, at most
    ``MEET_ITERATIONS`` steps, none once every step is at most ``MEET_SETTLED``) and the
    local discriminant there, −Φ(θ_c)·sign Φ″(θ_c): positive where a pair of real roots lies
    about θ_c, negative where it has left the unit circle (:func:`_pair`)."""
    with np.errstate(all="ignore"):
        for _ in range(MEET_ITERATIONS):
            _, slope, bend = derivatives(coef, theta)
            step = np.where(bend != 0.0, slope / bend, 0.0)
            theta = theta - step
            if not (np.abs(step) > MEET_SETTLED).any():
                break
        value, _, bend = derivatives(coef, theta)
    return theta, np.asarray(-value * np.sign(bend))


#: A link of the path that fails the step test is walked by sub-steps: at most this many
#: trials (a sub-step doubles after an accepted one and halves after a rejected one) ...
REFINE_TRIALS = 48
#: ... none below this (rad); and at most this many links per design are walked.
REFINE_MIN = 1e-10
REFINE_ROUNDS = 4
#: Newton iterations on Φ from a sub-step's predictor, and their convergence bound (rad).
ROOT_ITERATIONS = 8
#: Newton iterations on the reduced equations from a pose recovered at a root (:func:`_poses`).
POSE_ITERATIONS = 2
#: A change point on the path is located by regula falsi (Illinois) on the local
#: discriminant in φ to a bracket of this (rad), in at most ``LOCATE_ITERATIONS`` evaluations.
LOCATED = 1e-11
LOCATE_ITERATIONS = 60
#: A located change point is located again from a bracket about it rounded to this (rad).
GRAIN = 2.0 ** -30
#: What a walk of a link ends in: the far column's root, or a change point.
THROUGH, ENDS = 1, 2


@dataclass(frozen=True, eq=False)
class _Leg:
    """Walks along the path, one row each (R,): the group and inputs at the rows' designs
    (laid flat), the direction s = ±1, the path's columns (U + 1,) and its roots at them for
    each row (R, U + 1; NaN off the path), the column each walk starts from (R,) and its
    root, and the sign of det J of the sketch."""

    group: HigherGroup[Any]
    inputs: Inputs[Any]
    s: np.ndarray
    columns: np.ndarray
    path: np.ndarray
    start: np.ndarray
    here: _Root
    sign: np.ndarray

    def coef(self, phi: np.ndarray) -> np.ndarray:
        """The eliminants' coefficients at φ (R,)."""
        with np.errstate(all="ignore"):
            return coefficients(self.group, values(self.inputs(phi)))

    def root(self, phi: np.ndarray, guess: np.ndarray) -> tuple[_Root, np.ndarray, np.ndarray]:
        """The root of Φ at φ by Newton's method from ``guess``, with its analogs and
        separation bound, where it converged to a pose of the mode (:func:`_poses`), and
        the eliminants' coefficients there."""
        k = self.inputs(Jet(phi, 1.0, 0.0))
        coef = coefficients(self.group, values(k))
        theta, step = guess, np.full(guess.shape, np.inf)
        with np.errstate(all="ignore"):
            for _ in range(ROOT_ITERATIONS):
                value, slope, _ = derivatives(coef, theta)
                step = value / slope
                theta = theta - step
                if not (np.abs(step) > CONVERGED).any():
                    break
            x, x1, x2, _, posed = _poses(self.group, k, theta, self.sign)
            apart = roots_apart(coef, theta)
            slope = np.sign(derivatives(coef, theta)[1])
        e = self.group.eliminated
        return (_Root(theta, x1[..., e], x2[..., e], apart, slope, x, x1),
                posed & (np.abs(step) <= CONVERGED), coef)


    def fold(self, star: np.ndarray, top: np.ndarray, phi: np.ndarray, here: _Root
             ) -> np.ndarray:
        """Where the double root ``top`` at φ = ``star`` is a change point of the mode the
        state (φ, ``here``) is on: its pose x* (the group's recovery) satisfies the
        equations to ``ACCEPT``·L, and the square-root form of a fold puts it from the
        state, x* ≈ x + 2(φ* − φ)·x′, to half the distance |x* − x| (:func:`_ending`)."""
        kv = values(self.inputs(star))
        w = weights(self.group)
        with np.errstate(all="ignore"):
            x = expand(self.group).recover(np.exp(1j * top)[..., None], expand(kv))[..., 0, :]
            f = self.group.residuals(x, kv)
            model = here.x + (2.0 * (star - phi))[..., None] * here.x1
            off = (np.abs(_turned(self.group, x - model)) * w).sum(axis=-1)
            apart = (np.abs(_turned(self.group, x - here.x)) * w).sum(axis=-1)
            return np.asarray((np.abs(f).max(axis=-1) <= ACCEPT * np.asarray(self.group.size))
                              & (off <= 0.5 * apart))


def _turned(group: HigherGroup[K], dx: np.ndarray) -> np.ndarray:
    """Differences of unknowns (..., n) with those of angles taken in (−π, π]."""
    return np.asarray(np.where(np.asarray(group.lengths), dx, np.angle(np.exp(1j * dx))))


def _locate(leg: _Leg, low: tuple[np.ndarray, ...], high: tuple[np.ndarray, ...],
            rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The change point of the ``rows`` between the ends ``low`` = (φ_a, θ_a, D_a), where the
    local discriminant D at the extremum θ_a between the pair of roots is positive (the
    pair real), and ``high`` = (φ_b, θ_b, D_b) with D_b < 0: regula falsi with the Illinois
    rule on D(φ), the extremum followed from the bracket's ends. Returns φ* where the
    bracket or two successive points are within ``LOCATED``, and θ* (NaN where not
    located; the caller confirms the meeting at ``MEET`` on either side)."""
    a, theta_a, value_a = low
    b, theta_b, value_b = high
    kept = np.zeros(a.shape, dtype=np.int8)
    point, theta_p = np.full(a.shape, np.nan), np.full(a.shape, np.nan)
    settled = np.zeros(a.shape, dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(LOCATE_ITERATIONS):
            wide = rows & ~settled & (np.abs(b - a) > LOCATED)
            if not wide.any():
                break
            mid = (a * value_b - b * value_a) / (value_b - value_a)
            inside = (mid - a) * (mid - b) < 0.0
            mid = np.where(wide & inside, mid, np.where(wide, 0.5 * (a + b), a))
            frac = np.where(wide, (mid - a) / (b - a), 0.0)
            guess = theta_a + frac * np.angle(np.exp(1j * (theta_b - theta_a)))
            theta, value = _extremum(leg.coef(mid), guess)
            rows &= np.isfinite(value)
            settled |= wide & (np.abs(mid - point) <= LOCATED)
            point, theta_p = np.where(wide, mid, point), np.where(wide, theta, theta_p)
            real, gone = wide & (value > 0.0), wide & (value <= 0.0)
            value_b = np.where(real & (kept == 1), 0.5 * value_b, value_b)
            value_a = np.where(gone & (kept == -1), 0.5 * value_a, value_a)
            a, value_a, theta_a = (np.where(real, v, w) for v, w in
                                   ((mid, a), (value, value_a), (theta, theta_a)))
            b, value_b, theta_b = (np.where(gone, v, w) for v, w in
                                   ((mid, b), (value, value_b), (theta, theta_b)))
            kept = np.where(real, 1, np.where(gone, -1, kept)).astype(np.int8)
    narrow = rows & ~settled & (np.abs(b - a) <= LOCATED)
    return (np.where(rows & settled, point, np.where(narrow, 0.5 * (a + b), np.nan)),
            np.where(rows & settled, theta_p, np.where(narrow, theta_a, np.nan)))


def _canonical(leg: _Leg, star: np.ndarray, top: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The located change points φ* (θ* their double roots) located once more from a
    bracket of ±2·``GRAIN`` about φ* rounded to ``GRAIN``, the extremum from θ* rounded
    likewise: the end found does not depend on where the walk came from (the columns, so
    the requested angles), but where φ* lies within roundoff of half a grain."""
    with np.errstate(invalid="ignore"):
        centre, guess = np.round(star / GRAIN) * GRAIN, np.round(top / GRAIN) * GRAIN
        a, b = centre - 2.0 * GRAIN * leg.s, centre + 2.0 * GRAIN * leg.s
        theta, value = _extremum(leg.coef(np.stack([a, b])), guess)
        again, at = _locate(leg, (a, theta[0], value[0]), (b, theta[1], value[1]),
                            np.isfinite(star) & (value[0] > 0.0) & (value[1] < 0.0))
    return np.where(np.isfinite(again), again, star), np.where(np.isfinite(again), at, top)


def _walk_path(leg: _Leg) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[tuple[np.ndarray, ...]]]:
    """Each row walked by sub-steps from its start column along the path, column after
    column in its direction, until its root is the path's again.

    A sub-step takes the root by Newton's method on Φ from the predictor and accepts it
    where it is a pose of the mode and the link passes the step test (:func:`_link`). At a
    column the walk is through where its root is the path's (closer than half its
    separation bound); else it goes on to the next column. A rejected sub-step where the
    local discriminant (:func:`_extremum`, at the extremum next to the root) has changed
    sign from the state brackets a change point; the row waits there while the others walk
    on, and the change points of all the rows waiting are located together, once no row is
    walking (:func:`_locate` and :func:`_canonical`). A row then ends at its change point once
    the pose at the double root is where the square-root form of a fold puts it from the
    state (:meth:`_Leg.fold`; the sub-steps go on towards φ*, at most halfway each), and the
    pair really meets there: the local discriminant (:func:`_pair`) is +1 at ``MEET`` before
    φ* and −1 after.

    Returns the outcome (``THROUGH``, ``ENDS``, or 0: neither within ``REFINE_TRIALS``
    sub-steps above ``REFINE_MIN``), the last column reached (for ``THROUGH`` the one
    where the path is met again), φ* of the rows that end, and the roots the walk took at
    the columns it passed (row, column, θ).
    """
    s, columns = leg.s, leg.columns
    r = s.shape[0]
    rows = np.arange(r)
    at = leg.start.copy()
    phi, here = columns[at], leg.here
    coef = leg.coef(phi)
    status = np.zeros(r, dtype=np.int8)
    star, top = np.full(r, np.nan), np.full(r, np.nan)
    h = np.full(r, 0.5 * np.diff(columns).max())
    passed: list[tuple[np.ndarray, ...]] = []
    active = np.isfinite(here.theta)
    trials = np.zeros(r, dtype=int)
    waiting = np.zeros(r, dtype=bool)
    low = high = (phi, phi, phi)  # the brackets of the rows waiting (φ, θ, D at both ends)
    with np.errstate(all="ignore"):
        while True:
            aim = np.clip(at + s.astype(int), 0, columns.size - 1)
            active &= (aim != at) & ((trials < REFINE_TRIALS) | waiting)
            walking = active & ~waiting
            if not walking.any():
                if not (active & waiting).any():
                    break
                found, point = _canonical(leg, *_locate(leg, low, high, active & waiting))
                star, top = np.where(waiting, found, star), np.where(waiting, point, top)
                moved, waiting = waiting, np.zeros(r, dtype=bool)
            else:
                trials += walking
                goal, target = columns[aim], leg.path[rows, aim]
                rest = np.abs(goal - phi)
                near = np.isfinite(star)
                step = np.where(near, np.minimum(h, 0.5 * np.abs(star - phi)),
                                np.minimum(h, rest))
                hit = ~near & (step >= rest)
                trial = np.where(walking, np.where(hit, goal, phi + s * step), phi)
                dh = trial - phi
                new, posed, fresh = leg.root(trial,
                                             here.theta + dh * here.t1 + 0.5 * dh * dh * here.t2)
                ok = walking & posed & _link(dh, here, new)
                arrive = ok & hit
                through = arrive & (chord(new.theta, target) <= 0.5 * new.apart)
                status[through] = THROUGH
                on = arrive & ~through
                passed.append((rows[on], aim[on], new.theta[on]))
                at = np.where(arrive, aim, at)
                look = walking & ~ok & ~near
                if look.any():
                    theta_a, value_a = _extremum(coef, here.theta)
                    theta_b, value_b = _extremum(fresh, theta_a)
                    look &= (value_a > 0.0) & (value_b < 0.0)
                    low = tuple(np.where(look, v, w) for v, w in
                                zip((phi, theta_a, value_a), low, strict=True))
                    high = tuple(np.where(look, v, w) for v, w in
                                 zip((trial, theta_b, value_b), high, strict=True))
                    waiting |= look
                phi, here = np.where(ok, trial, phi), new.where(ok, here)
                coef = np.where(ok[:, None], fresh, coef)
                h = np.where(ok, np.where(step < h, h, 2.0 * h), np.where(walking, 0.5 * step, h))
                moved = walking & ~through
                active &= ~through
            into = active & moved & ~waiting & np.isfinite(star)
            if into.any():
                into &= leg.fold(star, top, phi, here)
                into &= _crosses(leg.group, leg.inputs, star - s * MEET, star + s * MEET, top)
                status[into] = ENDS
            active &= ~into & ((h >= REFINE_MIN) | waiting)
    return status, at, np.where(status == ENDS, star, np.nan), passed


def _refined(group: HigherGroup[K], inputs: Inputs[K], paths: Chains, root: _Root,
             cert: np.ndarray, sign: np.ndarray, todo: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The links of the path that fail the step test (``cert`` False, (U, D)) walked by
    sub-steps (:func:`_walk_path`), for the designs ``todo``: from the first failing link of
    the forward stretch (from column 0 on), and, once the forward stretch ends at a change
    point, from the last failing link of the backward stretch (from column U down), up to
    ``REFINE_ROUNDS`` walks each. The links a walk passes are certified.

    Returns the certified links, the change points (D, 2) where the forward and the
    backward stretch end (NaN where none is located), the links (D, 2) that hold them, and
    the path's roots (U + 1, D) with those the walks took at the columns they passed.
    """
    u, d = cert.shape
    cert = cert.copy()
    theta = paths.theta.copy()
    ends = np.full((d, 2), np.nan)
    at = np.full((d, 2), -1)
    designs = np.arange(d)
    link = np.arange(u)[:, None]
    for _ in range(REFINE_ROUNDS + 1):
        whole = cert.all(axis=0)
        first = np.argmin(cert, axis=0)
        last = u - 1 - np.argmin(cert[::-1], axis=0)
        ahead = todo & ~whole & np.isnan(ends[:, 0])
        behind = todo & ~whole & ~ahead & np.isnan(ends[:, 1]) & paths.backward[-1]
        rows = ahead | behind
        small = _take(group, rows) if rows.any() else None
        if small is None:
            break
        column = designs[rows]
        side = np.where(ahead[column], 0, 1)
        start = np.where(side == 0, first[column], last[column] + 1)
        leg = _Leg(small, _local(inputs, rows), np.where(side == 0, 1.0, -1.0), paths.columns,
                   theta[:, column].T, start, root.at((start, column)), sign[column])
        status, reached, star, passed = _walk_path(leg)
        for row, col, value in passed:
            # where the forward stretch reaches, its roots count
            mine = (side[row] == 0) | (col > at[column[row], 0])
            theta[col[mine], column[row][mine]] = value[mine]
        low = np.where(side == 0, start, reached)
        high = np.where(side == 0, reached, start)
        walked = (link >= low) & (link < high) & (status > 0)
        cert[:, column] |= walked
        ending = status == ENDS
        ends[column[ending], side[ending]] = star[ending]
        at[column[ending], side[ending]] = np.where(side == 0, reached, reached - 1)[ending]
        todo = todo.copy()
        todo[column[status == 0]] = False
    return cert, ends, at, theta


def _follow_tracked(group: HigherGroup[K], inputs: Inputs[K], phi: np.ndarray,
                    x0: np.ndarray, found: np.ndarray, modes: AssemblyModes,
                    jets: bool, delta: float | np.ndarray) -> HigherSolution:
    """The sketched mode along the path of its root over the grid of angles
    (:func:`~assur.kinematics.higher.track.chains`), as far as each link of that path passes
    the continuation's step test (:func:`_links`) or is walked through by sub-steps
    (:func:`_refined`). A design is taken where its path goes round the turn, or where its
    forward stretch (from φ = 0) and backward stretch (from 2π down) both end at located
    change points (the angles between not reached, reason 8); the other designs are
    followed step by step (:func:`_step_follow`). ``x0`` (D, n) is the sketched mode, one of
    ``modes`` (its sign of det J is read off them)."""
    d = x0.shape[0]
    e = group.eliminated
    columns = grid(np.mod(phi, TWO_PI))
    at = np.broadcast_to(np.append(columns, TWO_PI)[:, None], (columns.size + 1, d))
    k = inputs(Jet(at, 1.0, 0.0))
    kv = values(k)
    paths = chains(group, kv, columns, x0[:, e], found)
    if not paths.bracketed.any():  # see the walks below: every design goes to the steps
        return _step_follow(group, inputs, phi, x0, found, modes, jets, delta)
    # the sign of det J of the sketched mode: that of the mode x0 is (NaN where none is)
    mode = (modes.x.reshape(d, -1, group.n) == x0[:, None, :]).all(axis=-1)
    sign = np.where(mode.any(axis=-1),
                    np.where(mode, modes.det_sign.reshape(d, -1), 0.0).sum(axis=-1), np.nan)
    x, x1, x2, lines, posed = _poses(group, k, paths.theta, sign)
    root = _Root(paths.theta, x1[..., e], x2[..., e], paths.apart, paths.slope, x, x1)
    same = (paths.forward[:-1] & paths.forward[1:]) | (paths.backward[:-1] & paths.backward[1:])
    cert = _links(paths.columns, root) & posed[:-1] & posed[1:] & same
    # a sketched root in no bracket has no chain of the columns' roots to return to: a walk
    # would stop at every column to the end of its trials (and on a dense grid fall short of
    # an end 40° away, then leave the design to the steps all the same), so the steps follow
    cert, ends, ends_at, theta = _refined(group, inputs, paths, root, cert, sign,
                                          found & paths.bracketed & ~cert.all(axis=0))
    around = found & cert.all(axis=0) & np.isnan(ends).all(axis=-1)
    ended = found & np.isfinite(ends).all(axis=-1)
    column = np.searchsorted(paths.columns, np.mod(phi, TWO_PI))[:, None]
    # the poses at the requested columns where a walk took another root than the path's
    moved = np.zeros(theta.shape, dtype=bool)
    moved[column[:, 0]] = (np.isfinite(theta) & (theta != paths.theta))[column[:, 0]]
    small = _take(group, moved) if moved.any() else None
    if small is not None:
        redo = _poses(small, _local(inputs, moved)(Jet(at[moved], 1.0, 0.0)), theta[moved],
                      np.broadcast_to(sign, moved.shape)[moved])
        for whole, fresh in zip((x, x1, x2, lines), redo[:4], strict=True):
            whole[moved] = fresh
    reached = around | (ended & ((column <= ends_at[:, 0]) | (column > ends_at[:, 1])))
    good = around | ended
    # the inputs at the requested angles: those at their columns
    wanted = _take(k if jets else kv, np.ones(at.shape, dtype=bool),
                   tuple(np.broadcast_arrays(column, np.arange(d))))
    if wanted is None:
        wanted = inputs(Jet(np.broadcast_to(phi[:, None], (phi.size, d)), 1.0, 0.0))
    solution = _from_path(group, inputs, (phi, wanted if jets else values(wanted)),
                          x[column[:, 0]], (x1[column[:, 0]], x2[column[:, 0]]),
                          lines[column[:, 0]], reached, ends,
                          np.where(ended, True, paths.closed), found, modes, jets, delta)
    if good.all():
        return solution
    rows = np.flatnonzero(~good)
    small_group, small_inputs = _take(group, ~good), _local(inputs, ~good)
    if small_group is None or rows.size == d:
        return _step_follow(group, inputs, phi, x0, found, modes, jets, delta)
    part = _step_follow(small_group, small_inputs, phi, x0[rows], found[rows], modes, jets,
                        np.asarray(delta)[rows] if np.ndim(delta) else delta)
    return _splice(solution, part, rows)


def _splice(whole: HigherSolution, part: HigherSolution, rows: np.ndarray) -> HigherSolution:
    """``whole`` with its designs ``rows`` replaced by those of ``part`` (its modes kept)."""
    def put(a: Any, b: Any) -> Any:
        if isinstance(a, dict):
            return {name: put(a[name], b[name]) for name in a}
        if isinstance(a, Jet):
            return Jet(put(a.v, b.v), put(a.d1, b.d1), put(a.d2, b.d2))
        out = np.array(a)
        out[rows] = b
        return out

    return dataclasses.replace(whole, **{
        f.name: put(getattr(whole, f.name), getattr(part, f.name))
        for f in dataclasses.fields(whole) if f.name not in ("modes", "periodic")})


def _unreached(group: HigherGroup[K], inputs: Inputs[K], phi: np.ndarray,
               reached: np.ndarray, margin: np.ndarray, ended: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """The margin and reason (D, N) at the crank angles ``phi`` (N,) with the angles not
    ``reached`` (D, N) filled in: the gap's margin (:func:`_gap`) and ``MODE_ENDS`` for the
    designs whose passes both ``ended`` (D,) at change points, ``NOT_FOLLOWED`` for the
    others; NaN and ``UNDEFINED_INPUT`` where an input is undefined."""
    d = reached.shape[0]
    margin = margin.copy()
    reason = np.zeros(reached.shape, dtype=np.int8)
    columns = np.flatnonzero(~reached.all(axis=0))
    if columns.size:
        kv = values(inputs(np.broadcast_to(phi[columns, None], (columns.size, d))))
        defined = np.broadcast_to(finite_inputs(kv), (columns.size, d)).T
        gone = ~reached[:, columns]
        margin[:, columns] = np.where(gone, np.where(defined, _gap(group, kv, gone.T).T, np.nan),
                                      margin[:, columns])
        reason[:, columns] = np.where(
            gone, np.where(defined, np.where(ended[:, None], Reason.MODE_ENDS,
                                             Reason.NOT_FOLLOWED),
                           Reason.UNDEFINED_INPUT), 0)
    return margin, reason


def _from_path(group: HigherGroup[K], inputs: Inputs[K], at: tuple[np.ndarray, K],
               x: np.ndarray, analog: tuple[np.ndarray, np.ndarray], lines: np.ndarray,
               reached: np.ndarray, ends: np.ndarray, closed: np.ndarray, found: np.ndarray,
               modes: AssemblyModes, jets: bool, delta: float | np.ndarray) -> HigherSolution:
    """The solution at the requested angles ``at`` = (φ (N,), the inputs there, as jets with
    ``jets``) from the path's unknowns ``x`` and their ``analog`` (N, D, n) and margin rows
    ``lines``, where ``reached`` (N, D). The passes' ``ends`` (D, 2) are change points where
    both are given (reason 8 between them), none where neither is."""
    phi, k = at
    ended = np.isfinite(ends).all(axis=-1)
    with np.errstate(all="ignore"):
        margin = np.where(reached, hadamard(lines), np.nan)
    margin, reason = _unreached(group, inputs, phi, reached.T, margin.T, found & ended)
    with np.errstate(invalid="ignore"):
        exists = reached & (margin.T >= np.asarray(delta))
    reason = np.where(reached.T & ~exists.T, Reason.MODE_ENDS, reason).astype(np.int8)
    x = np.where(exists[..., None], x, np.nan)
    cols: Any = ([Jet(x[..., i], analog[0][..., i], analog[1][..., i]) for i in range(group.n)]
                 if jets else x)
    with np.errstate(all="ignore"):
        points, turns = group.joints(cols, k), group.rotations(cols, k)

    def final(v: Any) -> Any:
        parts = _kept(v, exists, jets)
        return Jet(*parts) if jets else parts[0]

    why = np.where(ended, Reason.MODE_ENDS, 0).astype(np.int8)
    return HigherSolution(
        joints={a: final(v) for a, v in points.items()},
        rotations={a: final(v) for a, v in turns.items()},
        x=x.transpose(1, 0, 2), margin=margin, exists=exists.T, reason=reason,
        ends=np.where(ended[:, None], ends, np.nan), end_reasons=np.stack([why, why], axis=-1),
        closed=closed, found=found, modes=modes)


def _follow_stroke(group: HigherGroup[K], inputs: Inputs[K], q: np.ndarray, stroke: Stroke,
                   x0: np.ndarray, sketch: tuple[AssemblyModes, np.ndarray], jets: bool,
                   delta: float | np.ndarray) -> HigherSolution:
    """The drawn mode along an actuator's stroke, one row per design.

    The pass parameter is t = (q − q₀)/L (L the group's size, so that the largest step is
    that of a crank, ``H_MAX``·L of length): the forward pass runs from q₀ up to the stroke's
    upper end, the backward pass down to its lower end (both further if a requested length
    lies beyond), each as a crank's pass (step control, tests (a)–(c), ends and reasons);
    a length above q₀ is reached by the forward pass only, one below by the backward pass
    only. ``inputs`` takes t; the analogs are returned with respect to q. There is no
    period: no return to the sketch and no overlap of the two passes.
    """
    modes, found = sketch
    d = x0.shape[0]
    scale = np.broadcast_to(group.size, (d,))
    start = np.broadcast_to(np.asarray(stroke.start, dtype=float), (d,))
    t = (q[:, None] - start) / scale
    up = np.maximum((stroke.high - start) / scale, t.max(axis=0, initial=0.0))
    down = np.maximum((start - stroke.low) / scale, (-t).max(axis=0, initial=0.0))
    ahead = _follow(group, inputs, x0, np.maximum(t, 0.0), 1.0, ~found, jets, up)
    behind = _follow(group, inputs, x0, np.maximum(-t, 0.0), -1.0, ~found, jets, down)
    above = (t >= 0.0).T
    use_ahead, use_behind = above & ahead.reached, ~above & behind.reached
    reached = use_ahead | use_behind

    def merge(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.where(use_ahead, a, np.where(use_behind, b, np.nan))

    x = np.stack([merge(ahead.x[..., i], behind.x[..., i]) for i in range(group.n)], axis=-1)
    margin = merge(ahead.margin, behind.margin)
    why = np.where(above, ahead.why[:, None], behind.why[:, None])
    reason = np.zeros(reached.shape, dtype=np.int8)
    columns = np.flatnonzero(~reached.all(axis=0))
    if columns.size:
        kv = values(inputs(t[columns]))
        defined = np.broadcast_to(finite_inputs(kv), (columns.size, d)).T
        gone = ~reached[:, columns]
        margin[:, columns] = np.where(gone, np.where(defined, _gap(group, kv, gone.T).T, np.nan),
                                      margin[:, columns])
        ends_here = found[:, None] & (why[:, columns] == Reason.MODE_ENDS)
        reason[:, columns] = np.where(
            gone, np.where(defined, np.where(ends_here, Reason.MODE_ENDS,
                                             Reason.NOT_FOLLOWED),
                           Reason.UNDEFINED_INPUT), 0)
    with np.errstate(invalid="ignore"):
        exists = reached & (margin >= np.asarray(delta)[..., None])
    reason = np.where(reached & ~exists, Reason.MODE_ENDS, reason).astype(np.int8)
    per = scale[:, None]

    def final(name: str) -> Any:
        parts = [np.where(exists, merge(a, b), np.nan) / per ** order
                 for order, (a, b) in enumerate(zip(ahead.out[name], behind.out[name],
                                                    strict=True))]
        return Jet(*parts) if jets else parts[0]

    ends = np.stack([np.where(ahead.why > 0, start + scale * ahead.end, np.nan),
                     np.where(behind.why > 0, start - scale * behind.end, np.nan)], axis=-1)
    return HigherSolution(
        joints={a[2:]: final(a) for a in ahead.out if a.startswith("p.")},
        rotations={a[2:]: final(a) for a in ahead.out if a.startswith("r.")},
        x=np.where(exists[..., None], x, np.nan), margin=margin, exists=exists, reason=reason,
        ends=ends, end_reasons=np.stack([ahead.why, behind.why], axis=-1),
        closed=np.ones(d, dtype=bool), found=found, modes=modes, periodic=False)


def _squeeze(solution: HigherSolution) -> HigherSolution:
    """The solution of a single design without its design axis."""
    def one(v: Any) -> Any:
        if isinstance(v, bool):
            return v
        if isinstance(v, Jet):
            return Jet(v.v[0], v.d1[0], v.d2[0])
        if isinstance(v, dict):
            return {a: one(b) for a, b in v.items()}
        if isinstance(v, AssemblyModes):
            return AssemblyModes(**{f.name: one(getattr(v, f.name))
                                    for f in dataclasses.fields(v)})
        return np.asarray(v)[0]

    return HigherSolution(**{f.name: one(getattr(solution, f.name))
                             for f in dataclasses.fields(solution)})
