"""Synthesise a problem: blocks B2–B5 composed once.

:func:`synthesize` evaluates (B2, B3), searches (B4) and summarises (B5) one problem read by
:func:`synthesis.problem.load_problem`.  Every front end that synthesises — the
``assur synthesize`` command, the coursework report — calls it and renders its
:class:`SynthesisOutcome`; none composes the blocks itself.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Any

import numpy as np

from synthesis.evaluate import Analysis, Evaluator
from synthesis.problem import Problem
from synthesis.report import summary
from synthesis.search import Executor, SearchResult, SearchSettings, search

__all__ = ["SynthesisOutcome", "synthesize"]


@dataclass(frozen=True)
class SynthesisOutcome:
    """What the synthesis of one problem found.

    Attributes
    ----------
    problem : Problem
        The problem synthesised.
    result : SearchResult
        The search: the best design, every trial, the stop reason.
    analysis : Analysis
        The analysis of the best design alone (output, deviations, pressure angles, …).
    summary : mapping
        Everything a report needs, as plain data (:func:`synthesis.report.summary`;
        read-only).
    """

    problem: Problem
    result: SearchResult
    analysis: Analysis
    summary: Mapping[str, Any]

    @property
    def feasible(self) -> bool:
        """Whether the best design meets P1 = P2 = 0."""
        return self.result.feasible

    @property
    def interrupted(self) -> bool:
        """Whether the search was stopped by Ctrl-C (the best design so far is kept)."""
        return self.result.stop == "interrupted"


def synthesize(problem: Problem, settings: SearchSettings | None = None, *,
               progress: bool | None = None,
               rng: int | np.random.Generator | None = None,
               executor: Executor | None = None) -> SynthesisOutcome:
    """Search for the best design of a problem and summarise it.

    Parameters
    ----------
    problem : Problem
        As read by :func:`synthesis.problem.load_problem`.
    settings : SearchSettings, optional
        Default: the problem's own (:attr:`Problem.settings`; see
        :func:`synthesis.search.settings_for` to override some of them).
    progress : bool, optional
        Print progress lines on standard error (default: as ``settings`` says).
    rng : int, numpy.random.Generator or None, optional
        Source of the LPτ scrambling (:func:`synthesis.search.search`); None uses the
        settings' seed.
    executor : Executor, optional
        Where the LPτ blocks are evaluated (default: in this process;
        :func:`synthesis.distributed.connect` gives one on a Dask cluster). The result does
        not depend on it.

    Returns
    -------
    SynthesisOutcome
        Never raises for an infeasible outcome: ``outcome.feasible`` says whether a design
        meets every condition.

    Raises
    ------
    TableError
        When the problem gives an allowable pressure angle to a group that has none.
    SettingError
        When ``rng`` is not a seed or a Generator.

    Examples
    --------
    >>> from synthesis.problem import load_problem
    >>> from synthesis.search import settings_for
    >>> problem = load_problem("input_tables/problems/class3_fourbar_path.yaml")
    >>> outcome = synthesize(problem, settings_for(problem, budget_log2=6, refine=False,
    ...                                            shrink_passes=0, restarts=0))
    >>> outcome.result.trials.shape[0] == 1 + 2 ** 6, outcome.summary["task_class"]
    (True, 3)
    """
    settings = settings if settings is not None else problem.settings
    if progress is not None:
        settings = replace(settings, progress=progress)
    evaluator = Evaluator(problem)
    result = search(evaluator, problem.lower, problem.upper, problem.initial, settings, rng=rng,
                    executor=executor)
    analysis = evaluator.analyse(result.x[None, :])
    return SynthesisOutcome(problem, result, analysis,
                            MappingProxyType(summary(problem, result, analysis)))
