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
4. optional local refinement from the best few distinct trials with
   :func:`scipy.optimize.least_squares` (bounded trust-region, Jacobian by one batched
   forward-difference call) on the residuals of the best design; a refined design is kept
   only if it is better by the ranking rule.

Stop rules: (a) a favourable mechanism (P1 = P2 = 0 and Q ≤ [Q]); (b) no improvement of
the best in the last ``stall`` trials; (c) the trial budget or the time limit is used up.
Ctrl-C stops the search cleanly; the best design found so far is returned.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import optimize
from scipy.stats import qmc

from synthesis.criteria import Criteria, Objective, merit

__all__ = ["STOP_REASONS", "SearchResult", "SearchSettings", "search", "settings_for"]

FloatArray = npt.NDArray[np.float64]
Evaluator = Callable[[FloatArray], Criteria]

STOP_REASONS = {
    "favourable": "a favourable mechanism was found (P1 = P2 = 0, Q within the required accuracy)",
    "stall": "no progress in the last trials",
    "budget": "the trial budget is used up",
    "time": "the time limit is used up",
    "interrupted": "the search was interrupted (Ctrl-C); the best design so far is kept",
}


@dataclass(frozen=True)
class SearchSettings:
    """Options of the search.

    Parameters
    ----------
    budget_log2 : int
        The passive pass draws up to 2**budget_log2 LPτ trials.
    seed : int
        Seed of the scrambled Sobol' sequence (same seed, same trials, same result).
    batch : int
        Designs evaluated per call of the evaluator (a power of two).
    stall : int or None
        Stop after this many trials without improvement (None: never).
    time_limit : float or None
        Wall-time limit in seconds for the whole search (None: none).
    q_required : float or None
        The required accuracy [Q]; a feasible design with Q ≤ [Q] stops the search.
    objective : {'lexicographic', 'weighted'}
        How P1, P2 and Q are combined (see :func:`synthesis.criteria.merit`).
    p2_weight : float
        λ of the weighted objective.
    shrink_passes : int
        Number of passive passes in boxes shrunk around the best design.
    shrink : float
        Half-width factor of each shrunk box relative to the previous one.
    refine : bool
        Whether to refine locally from the best trials.
    refine_starts : int
        Number of distinct best trials the refinement starts from.
    refine_evaluations : int
        Limit of residual evaluations per refinement start.
    progress : bool
        Print progress lines on standard error.
    """

    budget_log2: int = 12
    seed: int = 0
    batch: int = 256
    stall: int | None = None
    time_limit: float | None = None
    q_required: float | None = None
    objective: Objective = "lexicographic"
    p2_weight: float = 1.0
    shrink_passes: int = 0
    shrink: float = 0.25
    refine: bool = False
    refine_starts: int = 3
    refine_evaluations: int = 200
    progress: bool = False


@dataclass
class SearchResult:
    """What the search found.

    Attributes
    ----------
    x : ndarray, shape (q,)
        The best design (varied parameters).
    criteria : Criteria
        Its criteria (arrays of length 1).
    trials : ndarray, shape (T, q)
        Every evaluated design, in order (trial 0 = initial values).
    trial_criteria : Criteria
        Their criteria.
    stage : list of str
        Where each trial came from: 'initial', 'lptau', 'shrink', 'refine'.
    history : list of dict
        One entry per improvement of the best: trial number, seconds, P1, P2, Q, merit.
    stop : str
        Key of :data:`STOP_REASONS`.
    elapsed : float
        Wall time of the search, seconds.
    """

    x: FloatArray
    criteria: Criteria
    trials: FloatArray
    trial_criteria: Criteria
    stage: list[str]
    history: list[dict[str, float]]
    stop: str
    elapsed: float
    settings: SearchSettings = field(repr=False, default_factory=SearchSettings)

    @property
    def feasible(self) -> bool:
        """Whether the best design meets every obligatory and desirable condition."""
        return bool(self.criteria.p1[0] == 0 and self.criteria.p2[0] == 0)

    @property
    def message(self) -> str:
        """The stop reason as a sentence."""
        return STOP_REASONS[self.stop]


class _Stop(Exception):
    """Raised inside the search loop when a stop rule fires."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class _Search:
    """State of one search run (the public entry point is :func:`search`)."""

    def __init__(self, evaluate: Evaluator, lower: FloatArray, upper: FloatArray,
                 settings: SearchSettings) -> None:
        self.evaluate = evaluate
        self.lower = lower
        self.upper = upper
        self.settings = settings
        self.start = time.perf_counter()
        self.blocks: list[FloatArray] = []
        self.block_criteria: list[Criteria] = []
        self.stage: list[str] = []
        self.history: list[dict[str, float]] = []
        self.count = 0
        self.best_merit = np.inf
        self.best_x: FloatArray | None = None
        self.best_criteria: Criteria | None = None
        self.last_improvement = 0
        self.last_print = -np.inf

    # ------------------------------------------------------------------ bookkeeping
    def elapsed(self) -> float:
        return time.perf_counter() - self.start

    def rank(self, criteria: Criteria) -> FloatArray:
        s = self.settings
        q_ref = s.q_required if s.q_required else 1.0
        return merit(criteria, objective=s.objective, q_ref=q_ref, p2_weight=s.p2_weight)

    def record(self, x: FloatArray, stage: str, *, check_stall: bool = True) -> Criteria:
        """Evaluate a batch, keep it, update the best, apply the stop rules."""
        criteria = self.evaluate(x)
        self.blocks.append(np.array(x, dtype=float))
        self.block_criteria.append(criteria)
        self.stage.extend([stage] * len(x))
        m = self.rank(criteria)
        k = int(np.argmin(m))
        if m[k] < self.best_merit:
            self.best_merit = float(m[k])
            self.best_x = np.array(x[k], dtype=float)
            self.best_criteria = criteria.take([k])
            self.last_improvement = self.count + k
            self.history.append({
                "trial": float(self.count + k), "seconds": self.elapsed(),
                "p1": float(criteria.p1[k]), "p2": float(criteria.p2[k]),
                "q": float(criteria.q[k]), "merit": self.best_merit, "stage": stage})
        self.count += len(x)
        self.report()
        s = self.settings
        if self.favourable():
            raise _Stop("favourable")
        if s.time_limit is not None and self.elapsed() >= s.time_limit:
            raise _Stop("time")
        if check_stall and s.stall is not None and self.count - self.last_improvement > s.stall:
            raise _Stop("stall")
        return criteria

    def favourable(self) -> bool:
        c = self.best_criteria
        q_req = self.settings.q_required
        return (c is not None and q_req is not None and c.p1[0] == 0 and c.p2[0] == 0
                and bool(c.q[0] <= q_req))

    def report(self, final: bool = False) -> None:
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
    def passive(self, lower: FloatArray, upper: FloatArray, n_total: int, seed: int,
                stage: str) -> None:
        """One passive pass of ``n_total`` Sobol' points scaled to [lower, upper]."""
        q = lower.size
        if q == 0:
            return
        engine = qmc.Sobol(d=q, scramble=True, rng=np.random.default_rng(seed))
        batch = max(1, min(self.settings.batch, n_total))
        drawn = 0
        while drawn < n_total:
            # draw so that the running total stays a power of two
            n = batch if drawn == 0 else min(drawn, n_total - drawn)
            unit = engine.random(n)
            for part in range(0, n, batch):
                self.record(lower + unit[part:part + batch] * (upper - lower), stage)
            drawn += n

    def shrink_passes(self) -> None:
        s = self.settings
        half = (self.upper - self.lower) / 2.0
        for k in range(s.shrink_passes):
            half = half * s.shrink
            centre = self.best_x
            lower = np.maximum(centre - half, self.lower)
            upper = np.minimum(centre + half, self.upper)
            self.passive(lower, upper, 2 ** max(s.budget_log2 - 2, 4), s.seed + 1 + k, "shrink")

    def refine(self) -> None:
        """Bounded least-squares refinement from the best few distinct trials."""
        s = self.settings
        trials = np.concatenate(self.blocks)
        crit = _concat(self.block_criteria)
        order = np.argsort(self.rank(crit), kind="stable")
        starts: list[FloatArray] = []
        for k in order:
            if crit.p1[k] > 0:
                break
            if all(np.max(np.abs(trials[k] - x0) / (self.upper - self.lower)) > 1e-3
                   for x0 in starts):
                starts.append(trials[k])
            if len(starts) >= s.refine_starts:
                break
        for x0 in starts:
            self.refine_from(x0)
        if self.best_x is not None and self.best_criteria is not None \
                and self.best_criteria.p1[0] == 0:
            self.minimax_from(self.best_x)

    def refine_from(self, x0: FloatArray) -> None:
        span = self.upper - self.lower
        lo, hi = self.lower, self.upper
        varied = span > 0
        x0 = np.clip(x0, lo, hi)
        base = self.record(x0[None, :], "refine", check_stall=False)
        if base.p1[0] > 0 or not np.all(np.isfinite(base.residuals[0])):
            return
        p2_start = base.p2[0]
        worst = 10.0 * (np.abs(base.residuals[0]) + 1e-12)
        cache: dict[bytes, FloatArray] = {}

        def residuals(x: FloatArray) -> FloatArray:
            x = np.clip(x, lo, hi)
            key = x.tobytes()
            if key not in cache:
                c = self.record(x[None, :], "refine", check_stall=False)
                # a step may not break the chain nor worsen the desirable conditions
                ok = (c.p1[0] == 0 and c.p2[0] <= p2_start
                      and np.all(np.isfinite(c.residuals[0])))
                cache[key] = c.residuals[0] if ok else worst
            return cache[key]

        def jacobian(x: FloatArray) -> FloatArray:
            x = np.clip(x, lo, hi)
            step = 1e-7 * np.maximum(np.abs(x), span)
            step = np.where(x + step > hi, -step, step)
            shifted = x[None, :] + np.diag(step)
            c = self.record(shifted, "refine", check_stall=False)
            r0 = residuals(x)
            r = np.where(np.isfinite(c.residuals), c.residuals, r0[None, :])
            return ((r - r0[None, :]) / step[:, None]).T

        optimize.least_squares(residuals, x0, jac=jacobian, bounds=(lo, hi + ~varied * 1e-12),
                               x_scale=np.where(varied, span, 1.0), method="trf",
                               max_nfev=self.settings.refine_evaluations, xtol=1e-15,
                               ftol=1e-15, gtol=1e-15)

    def minimax_from(self, x0: FloatArray) -> None:
        """Minimise Q itself near x0: min t subject to −t ≤ Δ_K(x) ≤ t (SLSQP).

        Least squares minimises Σ Δ_K², which is not Q = max |Δ_K| when the target cannot be
        met exactly; this epigraph form moves to the Chebyshev (minimax) design.  Variables
        are scaled to the unit box; the Jacobian of Δ comes from one batched
        forward-difference call.
        """
        lo, span = self.lower, self.upper - self.lower
        base = self.record(x0[None, :], "refine", check_stall=False)
        q0 = float(base.q[0])
        if base.p1[0] > 0 or not np.isfinite(q0) or q0 == 0.0:
            return
        p2_start = base.p2[0]
        fallback = np.full(base.deviations.shape[1], 10.0 * q0)
        cache: dict[bytes, FloatArray] = {}

        def design(u: FloatArray) -> FloatArray:
            return lo + np.clip(u, 0.0, 1.0) * span

        def deviations(u: FloatArray) -> FloatArray:
            key = np.clip(u, 0.0, 1.0).tobytes()
            if key not in cache:
                c = self.record(design(u)[None, :], "refine", check_stall=False)
                ok = (c.p1[0] == 0 and c.p2[0] <= p2_start
                      and np.all(np.isfinite(c.deviations[0])))
                cache[key] = c.deviations[0] if ok else fallback
            return cache[key]

        def jacobian(u: FloatArray) -> FloatArray:
            u = np.clip(u, 0.0, 1.0)
            step = np.where(u + 1e-7 > 1.0, -1e-7, 1e-7)
            c = self.record(design(u[None, :] + np.diag(step)), "refine", check_stall=False)
            d0 = deviations(u)
            d = np.where(np.isfinite(c.deviations), c.deviations, d0[None, :])
            return ((d - d0[None, :]) / step[:, None]).T

        def constraints(z: FloatArray) -> FloatArray:
            d = deviations(z[:-1])
            return np.concatenate([z[-1] - d, z[-1] + d])

        def constraints_jac(z: FloatArray) -> FloatArray:
            jac = jacobian(z[:-1])
            ones = np.ones((jac.shape[0], 1))
            return np.vstack([np.hstack([-jac, ones]), np.hstack([jac, ones])])

        q = span.size
        objective_grad = np.zeros(q + 1)
        objective_grad[-1] = 1.0
        optimize.minimize(lambda z: z[-1], np.append((x0 - lo) / span, q0),
                          jac=lambda z: objective_grad, method="SLSQP",
                          bounds=[(0.0, 1.0)] * q + [(0.0, None)],
                          constraints=[{"type": "ineq", "fun": constraints,
                                        "jac": constraints_jac}],
                          options={"maxiter": 60, "ftol": 1e-15})

    # -------------------------------------------------------------------------- run
    def run(self, initial: FloatArray) -> SearchResult:
        s = self.settings
        stop = "budget"
        try:
            self.record(initial[None, :], "initial")
            self.passive(self.lower, self.upper, 2 ** s.budget_log2, s.seed, "lptau")
            if s.shrink_passes:
                self.shrink_passes()
            if s.refine:
                self.refine()
        except _Stop as signal:
            stop = signal.reason
        except KeyboardInterrupt:
            stop = "interrupted"
        self.report(final=True)
        assert self.best_x is not None and self.best_criteria is not None
        return SearchResult(
            x=self.best_x, criteria=self.best_criteria, trials=np.concatenate(self.blocks),
            trial_criteria=_concat(self.block_criteria), stage=self.stage,
            history=self.history, stop=stop, elapsed=self.elapsed(), settings=s)


def _concat(parts: list[Criteria]) -> Criteria:
    return Criteria(*(np.concatenate([getattr(p, name) for p in parts])
                      for name in ("p1", "p2", "q", "deviations", "residuals")))


def settings_for(problem: Any, **overrides: Any) -> SearchSettings:
    """Search settings of a problem: its ``search`` table, then the given overrides.

    Parameters
    ----------
    problem : Problem
        Supplies ``search`` (``budget``, ``seed``, ``refine``, ``shrink_passes``, ``stall``,
        ``time_limit``, ``refine_evaluations``), ``accuracy`` ([Q]), ``objective`` and
        ``p2_weight``.
    **overrides
        Fields of :class:`SearchSettings`; None leaves the problem's value.
    """
    table = dict(problem.search)
    values: dict[str, Any] = {
        "budget_log2": table.get("budget", 12), "seed": table.get("seed", 0),
        "refine": table.get("refine", False), "shrink_passes": table.get("shrink_passes", 0),
        "stall": table.get("stall"), "time_limit": table.get("time_limit"),
        "refine_evaluations": table.get("refine_evaluations", 200),
        "q_required": problem.accuracy, "objective": problem.objective,
        "p2_weight": problem.p2_weight}
    values.update({k: v for k, v in overrides.items() if v is not None})
    return SearchSettings(**values)


def search(evaluate: Evaluator, lower: npt.ArrayLike, upper: npt.ArrayLike,
           initial: npt.ArrayLike, settings: SearchSettings | None = None) -> SearchResult:
    """Search the box [lower, upper] for the best design.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(X) -> Criteria`` for a batch ``X`` of shape (D, q).
    lower, upper : array_like, shape (q,)
        Bounds of the varied parameters (lower < upper).
    initial : array_like, shape (q,)
        The initial design x⁰ (trial 0; it may lie outside the box).
    settings : SearchSettings, optional

    Returns
    -------
    SearchResult
        Never raises for an infeasible outcome: ``result.feasible`` says whether the best
        design meets P1 = P2 = 0.

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
    """
    lower = np.asarray(lower, dtype=float)
    upper = np.asarray(upper, dtype=float)
    initial = np.asarray(initial, dtype=float)
    return _Search(evaluate, lower, upper, settings or SearchSettings()).run(initial)
