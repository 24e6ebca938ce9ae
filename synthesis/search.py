"""Block B4: passive LPτ (Sobol') search with optional shrinking passes and local refinement.

The search knows nothing about mechanisms: it calls an evaluator that maps a batch of
designs ``X`` (shape ``(D, q)``, one row per design, one column per varied parameter) to
their :class:`~synthesis.criteria.Criteria`.  Designs are ranked by the scalar
:func:`~synthesis.criteria.merit`, which under the default lexicographic objective is the
same as comparing (P1, P2, Q) in that order.

Steps (``method.md`` §6):

1. trial 0 = the initial values x⁰ of the problem;
2. passive pass: scrambled, seeded Sobol' (LPτ) points ``q_t`` in the unit cube, drawn so
   that the number drawn is always a power of two (the balance property of the sequence),
   scaled to the box ``x = x⁻ + q ⊙ (x⁺ − x⁻)``;
3. optional shrinking passes: the same passive pass in a box shrunk around the best design
   (half-width × ``shrink``), clipped to the bounds;
4. optional local refinement with :func:`scipy.optimize.least_squares` (bounded
   trust-region, Jacobian by one batched forward-difference call) from the best few
   distinct designs, each followed by the minimax polish of where it ended (SLSQP, the
   desirable conditions held as inequality constraints); a refined design is kept only
   if it is better by the ranking rule, so never one that breaks a condition the best
   design keeps;
5. optional restarts, while no favourable design is found: steps 2–3 again (a round) with
   a fresh LPτ sequence over the whole box, the shrinking centred on the new round's own
   best; after the last round step 4 again, from the best designs of the rounds (best
   first, skipping the starts already refined), so that the starts lie in the basins
   different rounds found.

Every round's best and every refinement's end is kept (:attr:`SearchResult.optima`): how
many distinct local optima the search met, the evidence a report gives when [Q] was not
reached.

Stop rules: (a) a favourable mechanism (P1 = P2 = 0 and Q ≤ [Q]); (b) no improvement of
the round's best in its last ``stall`` trials ends the round (the search when it is the
last); (c) the budget or the time limit is used up: the budget counts every evaluated design,
the refinement's included (:attr:`SearchSettings.evaluations`, twice the trials the passive
passes plan), so that a target the search cannot reach does not make the refinement run on.  Every step returns how it ended
(a stop reason, or None when it ran to its end); a stop rule that fires inside a local
optimiser freezes its functions at a rejected value, without evaluating another design,
so that the optimiser ends within a few cheap steps.
Ctrl-C stops the search cleanly; the best design found so far is returned.

The options are :class:`~synthesis.search_settings.SearchSettings`, the outcome a
:class:`~synthesis.search_result.SearchResult`; this module is the engine.
"""

from __future__ import annotations

import itertools
import sys
import time
from collections.abc import Callable, Iterable, Iterator
from contextvars import ContextVar
from typing import Protocol

import numpy as np
import numpy.typing as npt
from scipy import optimize
from scipy.stats import qmc

from assur.text import Message
from assur.typing import FloatArray
from synthesis.criteria import Criteria, margin_penalty, merit
from synthesis.search_result import Improvement, Optimum, SearchResult
from synthesis.search_settings import SearchSettings, SettingError, whole

__all__ = ["LISTENER", "Executor", "search"]

Evaluator = Callable[[FloatArray], Criteria]
#: A source of randomness in the sense of SPEC 7: a seed, a Generator, or None (the settings' seed).
RNG = int | np.random.Generator | None

#: Who follows a search while it runs: ``listener(trials, planned, best, seconds)`` after every
#: evaluated batch, where ``planned`` counts the trials of the passive passes and ``best`` is
#: the best design's criteria (None before the first).  Set by a front end for the length of
#: a run (the command line's progress bar, :mod:`synthesis.app.progress`); when it is unset,
#: ``SearchSettings.progress`` prints plain lines instead.
LISTENER: ContextVar[Callable[[int, int, Criteria | None, float], None] | None] = ContextVar(
    "search_listener", default=None)


class Executor(Protocol):
    """Where the blocks of a passive pass are evaluated (default: in this process, in turn).

    ``map(evaluate, blocks)`` yields ``evaluate(block)`` for every block, in the order of
    ``blocks``, drawing the blocks lazily; the search stops iterating when a stop rule fires.
    :class:`synthesis.distributed.DaskExecutor` evaluates them on a Dask cluster.
    """

    def map(self, evaluate: Evaluator, blocks: Iterable[FloatArray], /) -> Iterator[Criteria]:
        """``evaluate(block)`` for each block, in order."""
        ...


#: The minimax polish stops when Q gains less than this fraction of [Q] (of Q at its start
#: when the problem gives no [Q]) ...
POLISH_GAIN = 1e-3
POLISH_GAIN_RELATIVE = 1e-6
#: ... over this many SLSQP iterations.
POLISH_PATIENCE = 3
#: Relative clearance inside the limit at which the polish holds a desirable condition.
_CLEARANCE = 1e-7


class _Search:
    """State of one search run (the public entry point is :func:`search`)."""

    def __init__(self, evaluate: Evaluator, lower: FloatArray, upper: FloatArray,
                 settings: SearchSettings, rng: RNG, executor: Executor | None = None) -> None:
        self.evaluate = evaluate
        self.map: Callable[[Evaluator, Iterable[FloatArray]], Iterator[Criteria]] = (
            map if executor is None else executor.map)
        self.lower = lower
        self.upper = upper
        self.settings = settings
        self.seed = settings.seed if rng is None else None if isinstance(
            rng, np.random.Generator) else int(rng)
        self.generator = rng if isinstance(rng, np.random.Generator) else None
        self.start = time.perf_counter()
        self.blocks: list[FloatArray] = []
        self.block_criteria: list[Criteria] = []
        self.stage: list[str] = []
        self.history: list[Improvement] = []
        self.count = 0
        self.best_merit = np.inf
        self.best_x: FloatArray | None = None
        self.best_criteria: Criteria | None = None
        self.last_improvement = 0
        self.last_print = -np.inf
        # the current round (the first pass or a restart) and refinement start
        self.round = 0
        self.round_merit = np.inf
        self.round_x: FloatArray | None = None
        self.round_criteria: Criteria | None = None
        self.local_merit = np.inf
        self.local: tuple[FloatArray, Criteria] | None = None
        self.optima: list[Optimum] = []
        self.refined: list[FloatArray] = []   # the starts of the refinement so far
        #: The stop rule that fired ('favourable', 'time'), None while none has.
        self.stop: str | None = None

    # ------------------------------------------------------------------ bookkeeping
    def elapsed(self) -> float:
        return time.perf_counter() - self.start

    def rank(self, criteria: Criteria) -> FloatArray:
        s = self.settings
        q_ref = s.q_required if s.q_required else 1.0
        return merit(criteria, objective=s.objective, q_ref=q_ref, p2_weight=s.p2_weight)

    def record(self, x: FloatArray, stage: str, *,
               criteria: Criteria | None = None) -> Criteria:
        """Evaluate a batch (unless its criteria are given), keep it, update the best, apply
        the stop rules that end the search (:attr:`stop`)."""
        if criteria is None:
            criteria = self.evaluate(x)
        self.blocks.append(np.array(x, dtype=float))
        self.block_criteria.append(criteria)
        self.stage.extend([stage] * len(x))
        m = self.rank(criteria)
        k = int(np.argmin(m))
        if m[k] < self.local_merit:
            self.local_merit = float(m[k])
            self.local = (np.array(x[k], dtype=float), criteria.take([k]))
        if m[k] < self.round_merit:
            self.round_merit = float(m[k])
            self.round_x = np.array(x[k], dtype=float)
            self.round_criteria = criteria.take([k])
            self.last_improvement = self.count + k
        if m[k] < self.best_merit:
            self.best_merit = float(m[k])
            self.best_x = np.array(x[k], dtype=float)
            self.best_criteria = criteria.take([k])
            self.history.append(Improvement(
                self.count + k, self.elapsed(), float(criteria.p1[k]), float(criteria.p2[k]),
                float(criteria.q[k]), self.best_merit, stage))
        self.count += len(x)
        self.report()
        time_limit = self.settings.time_limit
        if self.best_criteria is not None \
                and self.best_criteria.favourable(self.settings.q_required)[0]:
            self.stop = "favourable"
        elif time_limit is not None and self.elapsed() >= time_limit:
            self.stop = "time"
        elif self.count >= self.settings.evaluations:
            self.stop = "budget"
        return criteria

    def halt(self) -> str | None:
        """Why a passive pass ends here: the search's stop rule, 'stall' when the round's
        best has not improved in its last ``stall`` trials, or None (go on)."""
        stall = self.settings.stall
        if self.stop is None and stall is not None and self.count - self.last_improvement > stall:
            return "stall"
        return self.stop

    def report(self, final: bool = False) -> None:
        listener = LISTENER.get()
        if listener is not None:
            listener(self.count, self.settings.planned, self.best_criteria, self.elapsed())
            return
        if not self.settings.progress:
            return
        now = self.elapsed()
        if not final and now - self.last_print < 0.5:
            return
        self.last_print = now
        c = self.best_criteria
        best = (f"P1={c.p1[0]:.4g} P2={c.p2[0]:.4g} Q={c.q[0]:.6g}" if c is not None else "-")
        print(f"  trials {self.count:7d}  {now:7.2f} s  best {best}", file=sys.stderr, flush=True)

    # ----------------------------------------------------------------------- passes
    def stream(self, number: int) -> np.random.Generator:
        """The generator that scrambles pass ``number`` of the current round (0 = its
        passive pass over the whole box).

        With a seed s, pass k of the first round draws from ``default_rng(s + k)`` and pass
        k of restart r from ``default_rng([s, r, k])``; with a Generator, the first pass
        draws from it and every later pass from its next spawned child.
        """
        if self.generator is None:
            assert self.seed is not None
            if self.round == 0:
                return np.random.default_rng(self.seed + number)
            return np.random.default_rng([self.seed, self.round, number])
        first = self.round == 0 and number == 0
        return self.generator if first else self.generator.spawn(1)[0]

    def passive(self, lower: FloatArray, upper: FloatArray, n_total: int, number: int,
                stage: str) -> str | None:
        """One passive pass of ``n_total`` Sobol' points scaled to [lower, upper]; returns
        why it ended early (:meth:`halt`), None when it drew every point."""
        q = lower.size
        if q == 0:
            return None
        engine = qmc.Sobol(d=q, scramble=True, rng=self.stream(number))
        batch = max(1, min(self.settings.batch, n_total))

        def blocks() -> Iterator[FloatArray]:
            drawn = 0
            while drawn < n_total:
                # draw so that the running total stays a power of two
                n = batch if drawn == 0 else min(drawn, n_total - drawn)
                unit = engine.random(n)
                for part in range(0, n, batch):
                    yield lower + unit[part:part + batch] * (upper - lower)
                drawn += n

        # the executor may evaluate blocks ahead; they are recorded in the order drawn
        mine, theirs = itertools.tee(blocks())
        for x, criteria in zip(mine, self.map(self.evaluate, theirs)):
            self.record(x, stage, criteria=criteria)
            ended = self.halt()
            if ended is not None:
                return ended
        return None

    def shrink_passes(self) -> str | None:
        """The shrinking passes around the round's best; returns why they ended early."""
        s = self.settings
        half = (self.upper - self.lower) / 2.0
        for k in range(s.shrink_passes):
            half = half * s.shrink
            centre = self.round_x
            assert centre is not None  # trial 0 is always recorded first
            lower = np.maximum(centre - half, self.lower)
            upper = np.minimum(centre + half, self.upper)
            ended = self.passive(lower, upper, 2 ** max(s.budget_log2 - 2, 4), 1 + k, "shrink")
            if ended is not None:
                return ended
        return None

    def refine(self) -> None:
        """Bounded least-squares refinement from the best few distinct designs, each followed
        by the minimax polish of where it ended (the basin with the best Σ Δ_K² is not always
        the one with the best Q).

        The starts are the best designs of the rounds (best first), then the best trials,
        skipping designs within 1e-3 of the box of a start already taken (now or by an
        earlier refinement): with restarts every start lies in the basin a different round
        found.
        """
        s = self.settings
        trials = np.concatenate(self.blocks)
        crit = _concat(self.block_criteria)
        order = np.argsort(self.rank(crit), kind="stable")
        rounds = sorted((o for o in self.optima if o.stage == "round" and o.p1 == 0),
                        key=lambda o: o.merit)
        candidates = [o.x for o in rounds] + [trials[k] for k in order if crit.p1[k] == 0]
        span = self.upper - self.lower
        span = np.where(span > 0, span, 1.0)   # a fixed parameter never tells designs apart
        starts: list[FloatArray] = []
        for x in candidates:
            if all(np.max(np.abs(x - x0) / span) > 1e-3
                   for x0 in starts + self.refined):
                starts.append(x)
            if len(starts) >= s.refine_starts:
                break
        self.refined += starts
        for x0 in starts:
            self.local_merit, self.local = np.inf, None
            self.refine_from(x0)
            if self.local is not None and s.polish and self.stop is None:
                self.minimax_from(self.local[0])
            if self.stop is not None:
                return
            self.keep_optimum("refine", self.local)

    def refine_from(self, x0: FloatArray) -> None:
        """Bounded least squares of the residuals from x0 (trust-region reflective).

        Once a stop rule fires, the residuals stay at a rejected value and the Jacobian at
        zero, without evaluating a design: the optimiser ends within a few cheap steps.
        """
        span = self.upper - self.lower
        lo, hi = self.lower, self.upper
        varied = span > 0
        x0 = np.clip(x0, lo, hi)
        base = self.record(x0[None, :], "refine")
        if self.stop is not None or base.p1[0] > 0 \
                or not np.all(np.isfinite(base.residuals[0])):
            return
        p2_start = base.p2[0]
        worst: FloatArray = 10.0 * (np.abs(base.residuals[0]) + 1e-12)
        cache: dict[bytes, FloatArray] = {}

        def residuals(x: FloatArray) -> FloatArray:
            x = np.clip(x, lo, hi)
            key = x.tobytes()
            if self.stop is not None:
                return cache.get(key, worst)
            if key not in cache:
                c = self.record(x[None, :], "refine")
                # a step may not break the chain nor worsen the desirable conditions
                ok = (c.p1[0] == 0 and c.p2[0] <= p2_start
                      and np.all(np.isfinite(c.residuals[0])))
                cache[key] = c.residuals[0] if ok else worst
            return cache[key]

        def jacobian(x: FloatArray) -> FloatArray:
            if self.stop is not None:
                return np.zeros((worst.size, x.size))
            x = np.clip(x, lo, hi)
            step = 1e-7 * np.maximum(np.abs(x), span)
            step = np.where(x + step > hi, -step, step)
            step = np.where(varied, step, 1.0)   # a fixed parameter stays put: column 0
            shifted = x[None, :] + np.diag(np.where(varied, step, 0.0))
            c = self.record(shifted, "refine")
            r0 = residuals(x)
            r = np.where(np.isfinite(c.residuals), c.residuals, r0[None, :])
            jac: FloatArray = ((r - r0[None, :]) / step[:, None]).T
            return jac

        # a fixed parameter gets the next float above it as its upper bound (lower < upper
        # for least squares; 1e-12 added to 2e6 would leave it equal)
        optimize.least_squares(residuals, x0, jac=jacobian,
                               bounds=(lo, np.where(varied, hi, np.nextafter(hi, np.inf))),
                               x_scale=np.where(varied, span, 1.0), method="trf",
                               max_nfev=self.settings.refine_evaluations, xtol=1e-15,
                               ftol=1e-15, gtol=1e-15)

    def minimax_from(self, x0: FloatArray) -> None:
        """Minimise Q itself near x0: min t subject to −t ≤ Δ_K(x) ≤ t (SLSQP).

        Least squares minimises Σ Δ_K², which is not Q = max |Δ_K| when the target cannot be
        met exactly; this epigraph form moves to the Chebyshev (minimax) design.  Under the
        lexicographic objective the desirable conditions that have a margin
        (:attr:`~synthesis.criteria.Criteria.margins`) are inequality constraints: one that
        holds at x0 is kept at m ≤ −10⁻⁷ (a hair inside, so the end is feasible), one that
        does not may not worsen; so the polish slides along the boundary of the allowed
        region instead of stopping where it first touches it.  A step that breaks the chain
        or worsens the rest of P2 is rejected.  Variables are scaled to the unit box; the
        Jacobians come from one batched forward-difference call.  The polish ends when Q
        gains less than :data:`POLISH_GAIN` of [Q] (:data:`POLISH_GAIN_RELATIVE` of Q at x0
        without [Q]) in :data:`POLISH_PATIENCE` iterations, or when a stop rule fires: from
        then on its functions stay at a rejected value and their Jacobians at zero, without
        evaluating a design, and SLSQP ends within a few cheap steps.
        """
        lo, span = self.lower, self.upper - self.lower
        base = self.record(x0[None, :], "refine")
        q0 = float(base.q[0])
        if self.stop is not None or base.p1[0] > 0 or not np.isfinite(q0) or q0 == 0.0:
            return
        held = self.settings.objective == "lexicographic"
        m0 = base.margins[0] if held else np.zeros(0)
        limit = np.where(m0 <= 0.0, -_CLEARANCE, m0)
        rest0 = _rest(base, held)
        fallback = (np.full(base.deviations.shape[1], 10.0 * q0), limit + 1.0)
        cache: dict[bytes, tuple[FloatArray, FloatArray]] = {}
        q_req = self.settings.q_required
        watch = _Gain(POLISH_GAIN * q_req if q_req else POLISH_GAIN_RELATIVE * q0,
                      POLISH_PATIENCE)

        def design(u: FloatArray) -> FloatArray:
            return lo + np.clip(u, 0.0, 1.0) * span

        def values(c: Criteria) -> list[tuple[FloatArray, FloatArray]]:
            """Deviations and held margins of each design of c (the fallback if rejected)."""
            rest = _rest(c, held)
            margins = c.margins if held else np.zeros((len(c), 0))
            return [(c.deviations[k], margins[k])
                    if c.p1[k] == 0 and rest[k] <= rest0 + 1e-12 * (1.0 + rest0)
                    and np.all(np.isfinite(c.deviations[k])) and np.all(np.isfinite(margins[k]))
                    else fallback for k in range(len(c))]

        def at(u: FloatArray) -> tuple[FloatArray, FloatArray]:
            key = np.clip(u, 0.0, 1.0).tobytes()
            if watch.settled or self.stop is not None:
                return cache.get(key, fallback)
            if key not in cache:
                cache[key] = values(self.record(design(u)[None, :], "refine"))[0]
            return cache[key]

        def jacobians(u: FloatArray) -> tuple[FloatArray, FloatArray]:
            if watch.settled or self.stop is not None:
                return np.zeros((fallback[0].size, u.size)), np.zeros((limit.size, u.size))
            u = np.clip(u, 0.0, 1.0)
            step = np.where(u + 1e-7 > 1.0, -1e-7, 1e-7)
            shifted = values(self.record(design(u[None, :] + np.diag(step)), "refine"))
            d0, m_at = at(u)
            d = np.array([item[0] for item in shifted])
            m = np.array([item[1] for item in shifted]).reshape(len(step), m_at.size)
            return ((d - d0[None, :]) / step[:, None]).T, ((m - m_at[None, :]) / step[:, None]).T

        def constraints(z: FloatArray) -> FloatArray:
            d, m = at(z[:-1])
            return np.concatenate([z[-1] - d, z[-1] + d, limit - m])

        def constraints_jac(z: FloatArray) -> FloatArray:
            jd, jm = jacobians(z[:-1])
            ones = np.ones((jd.shape[0], 1))
            return np.vstack([np.hstack([-jd, ones]), np.hstack([jd, ones]),
                              np.hstack([-jm, np.zeros((jm.shape[0], 1))])])

        q = span.size
        objective_grad = np.zeros(q + 1)
        objective_grad[-1] = 1.0
        optimize.minimize(lambda z: z[-1], np.append((x0 - lo) / np.where(span > 0, span, 1.0), q0),
                          jac=lambda z: objective_grad, method="SLSQP",
                          bounds=[(0.0, 1.0)] * q + [(0.0, None)],
                          constraints=[{"type": "ineq", "fun": constraints,
                                        "jac": constraints_jac}],
                          callback=lambda z: watch(float(z[-1])),
                          options={"maxiter": 60, "ftol": watch.gain})

    # -------------------------------------------------------------------------- run
    def keep_optimum(self, stage: str, found: tuple[FloatArray, Criteria] | None) -> None:
        """Note a local optimum (the end of a refinement start or the best of a round)."""
        if found is None:
            return
        x, c = found
        self.optima.append(Optimum(self.round, stage, x, float(c.p1[0]), float(c.p2[0]),
                                   float(c.q[0]), float(self.rank(c)[0])))

    def run_round(self) -> str:
        """One round: the passive pass over the whole box and the shrinking passes around
        the round's best; returns how it ended: 'budget', 'stall', or the search's stop
        rule ('favourable', 'time').  The round's best is kept even when Ctrl-C ends it."""
        s = self.settings
        try:
            ended = self.passive(self.lower, self.upper, 2 ** s.budget_log2, 0, "lptau")
            if ended is None and s.shrink_passes:
                ended = self.shrink_passes()
        finally:
            if self.round_x is not None and self.round_criteria is not None:
                self.keep_optimum("round", (self.round_x, self.round_criteria))
        return ended or "budget"

    def next_round(self) -> None:
        """Forget the round's best: a restart searches the whole box afresh."""
        self.round += 1
        self.round_merit, self.round_x, self.round_criteria = np.inf, None, None
        self.last_improvement = self.count

    def run(self, initial: FloatArray) -> SearchResult:
        try:
            stop = self.steps(initial)
        except KeyboardInterrupt:
            stop = "interrupted"
        self.report(final=True)
        s = self.settings
        assert self.best_x is not None and self.best_criteria is not None
        return SearchResult(
            x=self.best_x, criteria=self.best_criteria, trials=np.concatenate(self.blocks),
            trial_criteria=_concat(self.block_criteria), stage=tuple(self.stage),
            history=tuple(self.history), stop=stop, elapsed=self.elapsed(), settings=s,
            seed=self.seed, optima=tuple(self.optima), stopped_in=self.stage[-1])

    def steps(self, initial: FloatArray) -> str:
        """The initial design, the rounds and the refinements; returns the stop reason."""
        s = self.settings
        self.record(initial[None, :], "initial")
        stop = "budget"
        for number in range(s.restarts + 1):
            if self.stop is not None:
                return self.stop
            if number:
                self.next_round()
            stop = self.run_round()
            if s.refine and number == 0 and self.stop is None:
                # a task with an exact answer usually ends here, before any restart
                self.refine()
        if s.refine and s.restarts and self.stop is None:
            self.refine()
        return self.stop or stop


def _concat(parts: list[Criteria]) -> Criteria:
    return Criteria(*(np.concatenate(arrays) for arrays in zip(*(p.arrays() for p in parts))))


def _rest(criteria: Criteria, held: bool) -> FloatArray:
    """P2 less the share of the conditions the refinement holds as constraints."""
    return criteria.p2 - margin_penalty(criteria.margins) if held else criteria.p2


class _Gain:
    """Follows the bound t on Q of a polish's iterations; :attr:`settled` once it has gained
    less than ``gain`` over the last ``patience`` iterations."""

    def __init__(self, gain: float, patience: int) -> None:
        self.gain = gain
        self.patience = patience
        self.seen: list[float] = []
        self.settled = False

    def __call__(self, t: float) -> None:
        self.seen.append(t)
        if len(self.seen) > self.patience and self.seen[-1 - self.patience] - t < self.gain:
            self.settled = True


def _bounds(lower: npt.ArrayLike, upper: npt.ArrayLike, initial: npt.ArrayLike
            ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The box and the start as float arrays of one length, lower ≤ upper, finite bounds."""
    arrays = tuple(np.atleast_1d(np.asarray(a, dtype=float)) for a in (lower, upper, initial))
    if any(a.ndim != 1 for a in arrays) or len({a.size for a in arrays}) != 1:
        raise SettingError(Message("search.bounds_shape", {
            "lower": arrays[0].shape, "upper": arrays[1].shape, "initial": arrays[2].shape}))
    lo, hi, x0 = arrays
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        raise SettingError(Message("search.bounds_finite", {"lower": lo.tolist(),
                                                            "upper": hi.tolist()}))
    wrong = np.flatnonzero(lo > hi)
    if wrong.size:
        k = int(wrong[0])
        raise SettingError(Message("search.bounds_order", {"k": k, "lower": float(lo[k]),
                                                           "upper": float(hi[k])}))
    return lo, hi, x0


def _check_rng(rng: object) -> RNG:
    if rng is None or isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, (int, np.integer)) and whole(rng) and rng >= 0:
        return int(rng)
    raise SettingError(Message("search.rng", {"found": rng}))


def search(evaluate: Evaluator, lower: npt.ArrayLike, upper: npt.ArrayLike,
           initial: npt.ArrayLike, settings: SearchSettings | None = None, *,
           rng: int | np.random.Generator | None = None,
           executor: Executor | None = None) -> SearchResult:
    """Search the box [lower, upper] for the best design.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(X) -> Criteria`` for a batch ``X`` of shape (D, q).
    lower, upper : array_like, shape (q,)
        Bounds of the varied parameters (finite, lower ≤ upper).
    initial : array_like, shape (q,)
        The initial design x⁰ (trial 0; it may lie outside the box).
    settings : SearchSettings, optional
    rng : int, numpy.random.Generator or None, optional
        Source of the scrambling of the LPτ sequence (SPEC 7): None uses
        ``settings.seed``; a whole number ≥ 0 is used as the seed instead; a Generator is
        drawn from directly (the shrinking passes from children it spawns), and the result
        then records no seed.
    executor : Executor, optional
        Evaluates the blocks of the passive passes (default: here, one after another);
        blocks are drawn and recorded in the same order whatever the executor, so the
        result does not depend on it.

    Returns
    -------
    SearchResult
        Never raises for an infeasible outcome: ``result.feasible`` says whether the best
        design meets P1 = P2 = 0.

    Raises
    ------
    SettingError
        When the bounds are not finite, of different lengths, or a lower bound exceeds its
        upper bound; when ``rng`` is neither None, a whole number ≥ 0 nor a Generator.

    Examples
    --------
    >>> import numpy as np
    >>> from synthesis.criteria import Criteria
    >>> def evaluate(x):
    ...     dev = x - np.array([0.3, 0.7])
    ...     zero = np.zeros(len(x))
    ...     return Criteria(zero, zero, np.max(np.abs(dev), axis=1), dev, dev)
    >>> r = search(evaluate, [0, 0], [1, 1], [0.5, 0.5], SearchSettings(budget_log2=8))
    >>> bool(r.criteria.q[0] < 0.05), r.stop
    (True, 'budget')
    >>> again = search(evaluate, [0, 0], [1, 1], [0.5, 0.5], SearchSettings(budget_log2=8),
    ...                rng=np.random.default_rng(0))
    >>> bool(np.all(again.x == r.x)), again.seed
    (True, None)
    """
    lo, hi, x0 = _bounds(lower, upper, initial)
    return _Search(evaluate, lo, hi, settings or SearchSettings(), _check_rng(rng),
                   executor).run(x0)
