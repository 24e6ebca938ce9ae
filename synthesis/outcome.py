"""The outcome of a synthesis: blocks B2–B5 composed once.

:func:`synthesize` evaluates (B2, B3), searches (B4) and analyses the best design (B5) of
one problem read by :func:`synthesis.load_problem`.  Every front end that synthesises — the
``assur synthesize`` command, the coursework report, a script — calls it and renders its
:class:`SynthesisResult`; none composes the blocks itself.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any, TypeVar

from synthesis.distributed import executor_for
from synthesis.evaluate import Analysis, Evaluator
from synthesis.problem import Problem
from synthesis.report import summary
from synthesis.search import Executor, search
from synthesis.search_result import SearchResult
from synthesis.search_settings import SearchSettings

__all__ = ["SynthesisResult", "synthesize"]

T = TypeVar("T")
#: Most varied parameters :meth:`SynthesisResult.__repr__` lists one per line.
_REPR_PARAMETERS = 10


@dataclass(frozen=True, repr=False)
class SynthesisResult:
    """What the synthesis of one problem found (frozen; the numbers in table units).

    Attributes
    ----------
    problem : Problem
        The problem synthesised.
    search : SearchResult
        The search: the best design, every trial, the stop reason, the settings.
    analysis : Analysis
        The analysis of the best design alone (output, deviations, pressure angles, …);
        the criteria below are its criteria.
    """

    problem: Problem
    search: SearchResult
    analysis: Analysis

    @property
    def design(self) -> dict[str, float]:
        """The best design: varied parameter → value (mm, degrees)."""
        return self.problem.design(self.search.x)

    @property
    def q(self) -> float:
        """Q of the best design in the unit of the output (:attr:`unit`; NaN if undefined)."""
        return float(self.analysis.criteria.q[0]) * self.problem.output_scale

    @property
    def unit(self) -> str:
        """The unit of Q: 'deg', 'mm' or '1' (the dimensionless ratio n)."""
        return self.problem.output_unit

    @property
    def p1(self) -> float:
        """P1, the penalty of the obligatory conditions (0: the mechanism assembles)."""
        return float(self.analysis.criteria.p1[0])

    @property
    def p2(self) -> float:
        """P2, the penalty of the desirable conditions (NaN where P1 > 0)."""
        return float(self.analysis.criteria.p2[0])

    @property
    def feasible(self) -> bool:
        """Whether the best design meets P1 = P2 = 0 (:attr:`Criteria.feasible`)."""
        return bool(self.analysis.criteria.feasible[0])

    @property
    def favourable(self) -> bool:
        """Whether it is feasible and Q ≤ [Q] (False when the problem gives no [Q])."""
        return bool(self.analysis.criteria.favourable(self.problem.q_required)[0])

    @property
    def stop(self) -> str:
        """Why the search stopped (:data:`~synthesis.search_result.STOP_REASONS`)."""
        return self.search.stop

    @property
    def trials(self) -> int:
        """How many designs the search evaluated (the initial one included)."""
        return int(self.search.trials.shape[0])

    @property
    def interrupted(self) -> bool:
        """Whether the search was stopped by Ctrl-C (the best design so far is kept)."""
        return self.search.stop == "interrupted"

    def to_dict(self) -> dict[str, Any]:
        """Everything a report needs, as JSON-ready data: what ``assur synthesize --json``
        prints (:func:`synthesis.report.summary`; NaN and infinities become None)."""
        plain = _json_ready(summary(self.problem, self.search, self.analysis))
        assert isinstance(plain, dict)
        return plain

    def __repr__(self) -> str:
        names = list(self.design.items())
        shown = [f"        {name!r}: {value:.9g}," for name, value in names[:_REPR_PARAMETERS]]
        if len(names) > _REPR_PARAMETERS:
            shown.append(f"        … {len(names) - _REPR_PARAMETERS} more")
        head = (f"SynthesisResult(problem={self.problem.name!r}, "
                f"task_class={self.problem.task_class},")
        criteria = (f"    feasible={self.feasible}, favourable={self.favourable}, "
                    f"Q={self.q:.6g} {self.unit}, P1={self.p1:.6g}, P2={self.p2:.6g},")
        search = (f"    stop={self.stop!r} (in {self.search.stopped_in!r}), "
                  f"trials={self.trials}, seconds={self.search.elapsed:.3g},")
        return "\n".join([head, criteria, search, "    design={", *shown, "    })"])


def _json_ready(value: object) -> object:
    """A JSON-safe copy: NaN and infinities become None, tuples lists, keys strings."""
    if isinstance(value, Mapping):
        return {str(k): _json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _given(value: T | None, default: T) -> T:
    """An override, or the setting's value when the override is None."""
    return default if value is None else value


def synthesize(problem: Problem, settings: SearchSettings | None = None, *,
               budget: int | None = None, seed: int | None = None,
               refine: bool | None = None, shrink: int | None = None,
               restarts: int | None = None, time_limit: float | None = None,
               scheduler: str | Executor | None = None,
               progress: bool | None = None) -> SynthesisResult:
    """Search for the best design of a problem and analyse it.

    Parameters
    ----------
    problem : Problem
        As read by :func:`synthesis.load_problem`.
    settings : SearchSettings, optional
        Default: the problem's own (:attr:`Problem.settings`: its ``search`` table, [Q],
        the objective).  The keywords below override single fields of it.
    budget : int, optional
        log2 of the LPτ trials of a round (``--budget``; 0 to 24).
    seed : int, optional
        Seed of the scrambled LPτ sequence (a whole number ≥ 0): same seed, same result.
    refine : bool, optional
        Whether to refine locally from the best trials.
    shrink : int, optional
        Number of shrinking passes per round (0 to 10).
    restarts : int, optional
        Rounds after the first one (0 to 64), made while no favourable design is found.
    time_limit : float, optional
        Wall-time limit of the search, seconds.
    scheduler : str or Executor, optional
        Where the LPτ blocks are evaluated: None, in this process; a ``--scheduler`` spec
        (a number of local workers, or a scheduler's address; :mod:`synthesis.distributed`),
        or an executor already connected.  The result does not depend on it.
    progress : bool, optional
        Print progress lines on standard error (default: as the settings say).

    Returns
    -------
    SynthesisResult
        Never raises for an infeasible outcome: ``result.feasible`` says whether a design
        meets every condition.

    Raises
    ------
    SettingError
        When an override breaks the rule of its setting (the message states the rule).
    TableError
        When the problem gives an allowable pressure angle to a group that has none.
    DistributedError
        When ``scheduler`` names a cluster that cannot be used.

    Examples
    --------
    >>> from synthesis import load_problem, synthesize
    >>> problem = load_problem("input_tables/problems/class3_fourbar_path.yaml")
    >>> result = synthesize(problem, budget=6, seed=1, refine=False, shrink=0, restarts=0)
    >>> result.trials == 1 + 2 ** 6, result.stop, result.unit
    (True, 'budget', 'mm')
    >>> result.to_dict()["Q"] == result.q, result.to_dict()["feasible"] == result.feasible
    (True, True)
    >>> print(repr(result).splitlines()[0])
    SynthesisResult(problem='four-bar coupler path', task_class=3,
    """
    base = settings if settings is not None else problem.settings
    settings = replace(
        base, budget_log2=_given(budget, base.budget_log2), seed=_given(seed, base.seed),
        refine=_given(refine, base.refine), shrink_passes=_given(shrink, base.shrink_passes),
        restarts=_given(restarts, base.restarts),
        time_limit=_given(time_limit, base.time_limit), progress=_given(progress, base.progress))
    evaluator = Evaluator(problem)
    if scheduler is None:  # the batches are analysed in this process
        evaluator.prepare(settings.round_trials)
    if scheduler is None or isinstance(scheduler, str):
        with executor_for(scheduler) as executor:
            result = search(evaluator, problem.lower, problem.upper, problem.initial,
                            settings, executor=executor)
    else:
        result = search(evaluator, problem.lower, problem.upper, problem.initial, settings,
                        executor=scheduler)
    return SynthesisResult(problem, result, evaluator.analyse(result.x[None, :]))
