"""Options of the search (block B4), checked when they are made.

:class:`SearchSettings` holds every option of :func:`synthesis.search.search`; each field
has one rule (:func:`setting_problem`), which also checks the command-line options and the
``search:`` table of a problem, so that the three can never disagree.  A broken rule is a
:class:`SettingError` whose message states the rule and the value found.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from assur import AssurError
from assur.text import Message
from synthesis.criteria import Objective

if TYPE_CHECKING:
    from synthesis.problem import Problem

__all__ = ["MAX_BUDGET", "MAX_RESTARTS", "MAX_SHRINK_PASSES", "REFINE_SHARE", "SearchSettings",
           "SettingError",
           "setting_problem", "settings_for", "whole"]

#: Largest budget: 2**24 LPτ trials.
MAX_BUDGET = 24
#: Largest number of shrinking passes.
MAX_SHRINK_PASSES = 10
#: Largest number of restarts.
MAX_RESTARTS = 64
#: The refinement may evaluate this many times the designs the passive passes plan (and at
#: least ``refine_starts × refine_evaluations``): :attr:`SearchSettings.evaluations`.
REFINE_SHARE = 1.0
def whole(value: Any) -> bool:
    """Whether ``value`` is a whole number (an int, not a bool)."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def _real(value: Any) -> bool:
    return (isinstance(value, (int, float, np.integer, np.floating))
            and not isinstance(value, (bool, np.bool_)) and math.isfinite(value))


def _optional(test: Callable[[Any], bool]) -> Callable[[Any], bool]:
    return lambda value: value is None or test(value)


#: The rule of every setting: field of :class:`SearchSettings` → (catalogue code, test).
#: The same rules check the command-line options and the ``search:`` table of a problem.
_RULES: dict[str, tuple[str, Callable[[Any], bool]]] = {
    "budget_log2": ("search.budget", lambda v: whole(v) and 0 <= v <= MAX_BUDGET),
    "seed": ("search.seed", lambda v: whole(v) and v >= 0),
    "batch": ("search.batch", lambda v: whole(v) and v >= 1 and (v & (v - 1)) == 0),
    "stall": ("search.stall", _optional(lambda v: whole(v) and v >= 1)),
    "time_limit": ("search.time_limit", _optional(lambda v: _real(v) and v > 0)),
    "q_required": ("search.accuracy", _optional(lambda v: _real(v) and v > 0)),
    "objective": ("search.objective", lambda v: v in ("lexicographic", "weighted")),
    "p2_weight": ("search.p2_weight", lambda v: _real(v) and v > 0),
    "shrink_passes": ("search.shrink_passes",
                      lambda v: whole(v) and 0 <= v <= MAX_SHRINK_PASSES),
    "shrink": ("search.shrink", lambda v: _real(v) and 0 < v < 1),
    "refine": ("search.refine", lambda v: isinstance(v, (bool, np.bool_))),
    "refine_starts": ("search.refine_starts", lambda v: whole(v) and v >= 1),
    "restarts": ("search.restarts", lambda v: whole(v) and 0 <= v <= MAX_RESTARTS),
    "refine_evaluations": ("search.refine_evaluations", lambda v: whole(v) and v >= 1),
    "polish": ("search.polish", lambda v: isinstance(v, (bool, np.bool_))),
    "progress": ("search.progress", lambda v: isinstance(v, (bool, np.bool_))),
}


def setting_problem(name: str, value: Any) -> Message | None:
    """The broken rule of one search setting, or None when the value is allowed.

    Parameters
    ----------
    name : str
        A field of :class:`SearchSettings` (``'budget_log2'``, ``'batch'``, ``'shrink'``, …).
    value : object
        The value to check.

    Returns
    -------
    Message or None
        The catalogue message stating the rule and the value found.

    Examples
    --------
    >>> setting_problem("budget_log2", -3).text("en")
    'budget (log2 of the LPτ trials) must be a whole number from 0 to 24; got -3'
    >>> setting_problem("shrink", 0.25) is None
    True
    """
    code, test = _RULES[name]
    if test(value):
        return None
    return Message(code, {"found": value})


class SettingError(AssurError, ValueError):
    """A search setting breaks its rule (the message states the rule and the value).

    The command line reports it like a table problem, with exit code 2.
    """

    def __init__(self, message: Message) -> None:
        self.message = message
        super().__init__(message.text("en"))

    def text(self, lang: str = "en") -> str:
        """The sentence in ``lang``."""
        return self.message.text(lang)


@dataclass(frozen=True)
class SearchSettings:
    """Options of the search, checked when they are made.

    Parameters
    ----------
    budget_log2 : int
        The passive pass draws up to 2**budget_log2 LPτ trials (0 to 24).
    seed : int
        Seed of the scrambled Sobol' sequence (a whole number ≥ 0; same seed, same trials,
        same result).
    batch : int
        Designs evaluated per call of the evaluator (a power of two, which keeps every
        partial draw of the sequence balanced).
    stall : int or None
        End a round (the first pass or a restart) after this many trials without
        improvement of its best (None: never); the search stops when the last round ends.
    time_limit : float or None
        Wall-time limit in seconds for the whole search (positive; None: none).
    q_required : float or None
        The required accuracy [Q] (positive); a feasible design with Q ≤ [Q] stops the search.
    objective : {'lexicographic', 'weighted'}
        How P1, P2 and Q are combined (see :func:`synthesis.criteria.merit`).
    p2_weight : float
        λ of the weighted objective (positive).
    shrink_passes : int
        Number of passive passes in boxes shrunk around the best design (0 to 10).
    shrink : float
        Half-width factor of each shrunk box relative to the previous one, in (0, 1).
    refine : bool
        Whether to refine locally from the best trials.
    refine_starts : int
        Number of distinct best trials the refinement starts from (≥ 1).
    refine_evaluations : int
        Limit of residual evaluations per refinement start (≥ 1).
    restarts : int
        Rounds after the first one (0 to 64), each made only while no favourable design is
        found: a passive pass of a fresh LPτ sequence over the whole box and its own
        shrinking passes.  The refinement runs after the first round and again after the
        last one, from the best designs of the rounds.
    polish : bool
        Whether each least-squares refinement is followed by the minimax polish (SLSQP on
        Q itself, the desirable conditions held as constraints); ``docs/synthesis.md``
        gives the benchmark figures with and without it.
    progress : bool
        Print progress lines on standard error.

    Raises
    ------
    SettingError
        For the first setting that breaks its rule; the message states the rule.

    Examples
    --------
    >>> SearchSettings(budget_log2=8, shrink=0.5).shrink
    0.5
    >>> SearchSettings(batch=0)
    Traceback (most recent call last):
    ...
    synthesis.search_settings.SettingError: batch must be a power of two (1, 2, 4, …: designs per \
evaluation); got 0
    """

    budget_log2: int = 10
    seed: int = 0
    batch: int = 256
    stall: int | None = None
    time_limit: float | None = None
    q_required: float | None = None
    objective: Objective = "lexicographic"
    p2_weight: float = 1.0
    shrink_passes: int = 3
    shrink: float = 0.25
    refine: bool = True
    refine_starts: int = 3
    refine_evaluations: int = 200
    restarts: int = 3
    polish: bool = True
    progress: bool = False

    def __post_init__(self) -> None:
        for name in _RULES:
            problem = setting_problem(name, getattr(self, name))
            if problem is not None:
                raise SettingError(problem)

    @property
    def planned(self) -> int:
        """The trials of the initial design and of the passive passes of every round (the
        first and the restarts; a favourable design may end them sooner).

        >>> SearchSettings(budget_log2=7, shrink_passes=3, restarts=3).planned
        897
        """
        return int(1 + (1 + self.restarts) * self.round_trials)

    @property
    def round_trials(self) -> int:
        """The trials of the passive passes of one round: 2**budget_log2 and, in each
        shrinking pass, a quarter of that (at least 16).

        >>> SearchSettings(budget_log2=7, shrink_passes=3).round_trials
        224
        """
        return int(2 ** self.budget_log2 + self.shrink_passes * 2 ** max(self.budget_log2 - 2, 4))

    @property
    def evaluations(self) -> int:
        """The most designs the whole search evaluates, refinement included: the passive
        passes' :attr:`planned` trials and, with the refinement, :data:`REFINE_SHARE` times
        as many again, at least ``refine_starts × refine_evaluations`` (every design its
        least squares, Jacobians and polish evaluate counts).  The search stops with the
        reason ``'budget'`` at the batch that reaches it (a Jacobian's batch of at most one
        design per varied parameter may end past it).

        >>> SearchSettings(budget_log2=7, shrink_passes=3, restarts=3).evaluations
        1794
        >>> SearchSettings(budget_log2=2, shrink_passes=0, restarts=0).evaluations
        605
        >>> SearchSettings(budget_log2=2, shrink_passes=0, restarts=0, refine=False).evaluations
        5
        """
        if not self.refine:
            return self.planned
        share = max(REFINE_SHARE * self.planned, self.refine_starts * self.refine_evaluations)
        return int(self.planned + share)


def settings_for(problem: Problem, **overrides: Any) -> SearchSettings:
    """Search settings of a problem: its ``search`` table, then the given overrides.

    Parameters
    ----------
    problem : Problem
        Supplies :attr:`~synthesis.problem.Problem.settings` (its ``search`` table,
        ``accuracy`` [Q], ``objective`` and ``p2_weight``).
    **overrides
        Fields of :class:`SearchSettings`; None leaves the problem's value.

    Returns
    -------
    SearchSettings

    Raises
    ------
    SettingError
        When an override breaks its rule (the same rule as in the problem table).
    """
    return replace(problem.settings, **{k: v for k, v in overrides.items() if v is not None})
