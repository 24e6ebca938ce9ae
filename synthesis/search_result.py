"""What a search found (block B4): the best design, every trial, how the search stopped.

:class:`SearchResult` is frozen and its arrays are read-only; :class:`Improvement` and
:class:`Optimum` are its records of the progress and of the local optima met.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from assur.text import Message
from assur.typing import FloatArray
from synthesis.criteria import Criteria
from synthesis.search_settings import SearchSettings

__all__ = ["STOP_REASONS", "Improvement", "Optimum", "SearchResult", "distinct_optima"]

#: Stop reason → catalogue code of its sentence.
STOP_REASONS = {reason: f"search.stop.{reason}"
                for reason in ("favourable", "stall", "budget", "time", "interrupted")}

@dataclass(frozen=True)
class Improvement:
    """One improvement of the best design during the search.

    Attributes
    ----------
    trial : int
        Number of the trial that improved the best (0 = the initial design).
    seconds : float
        Wall time since the start of the search.
    p1, p2, q : float
        The criteria of the new best design.
    merit : float
        Its scalar objective (:func:`synthesis.criteria.merit`).
    stage : str
        Where the trial came from: 'initial', 'lptau', 'shrink', 'refine'.
    """

    trial: int
    seconds: float
    p1: float
    p2: float
    q: float
    merit: float
    stage: str

    def as_dict(self) -> dict[str, float | str]:
        """Plain data for reports and JSON (the trial number as a float, as the criteria)."""
        return {"trial": float(self.trial), "seconds": self.seconds, "p1": self.p1,
                "p2": self.p2, "q": self.q, "merit": self.merit, "stage": self.stage}


@dataclass(frozen=True)
class Optimum:
    """The best design of one round (the first pass or a restart) or of one refinement start.

    Attributes
    ----------
    round : int
        0 for the first pass, r for the r-th restart.
    stage : str
        'round' (the best of the whole round) or 'refine' (the end of one refinement start).
    x : ndarray, shape (q,)
        The design.
    p1, p2, q, merit : float
        Its criteria and scalar objective.
    """

    round: int
    stage: str
    x: FloatArray
    p1: float
    p2: float
    q: float
    merit: float


def distinct_optima(optima: tuple[Optimum, ...], lower: FloatArray, upper: FloatArray,
                    *, tolerance: float = 1e-3) -> list[Optimum]:
    """The optima that differ from each other, best first.

    Two optima are the same when every varied parameter differs by at most ``tolerance``
    of its range (lower to upper); of such a cluster the better one is kept.

    Parameters
    ----------
    optima : tuple of Optimum
        :attr:`SearchResult.optima`.
    lower, upper : ndarray, shape (q,)
        The search box.
    tolerance : float
        Relative distance below which two designs count as one.

    Returns
    -------
    list of Optimum
    """
    span = np.where(upper > lower, upper - lower, 1.0)
    kept: list[Optimum] = []
    for item in sorted(optima, key=lambda o: o.merit):
        if all(np.max(np.abs(item.x - other.x) / span) > tolerance for other in kept):
            kept.append(item)
    return kept


@dataclass(frozen=True)
class SearchResult:
    """What the search found (immutable: its arrays are read-only).

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
    stage : tuple of str
        Where each trial came from: 'initial', 'lptau', 'shrink', 'refine'.
    history : tuple of Improvement
        One entry per improvement of the best.
    stop : str
        Key of :data:`STOP_REASONS`.
    elapsed : float
        Wall time of the search, seconds.
    settings : SearchSettings
        The settings of the run.
    seed : int or None
        The seed of the LPτ scrambling; None when the search drew from a Generator given
        as ``rng``.
    optima : tuple of Optimum
        The best design of every round and the end of every refinement start: the local
        optima the search met, the evidence a report gives when [Q] was not reached.
    stopped_in : str
        The stage of the last trial, where the stop reason took effect: 'initial',
        'lptau', 'shrink' or 'refine'.
    """

    x: FloatArray
    criteria: Criteria
    trials: FloatArray
    trial_criteria: Criteria
    stage: tuple[str, ...]
    history: tuple[Improvement, ...]
    stop: str
    elapsed: float
    settings: SearchSettings
    seed: int | None
    optima: tuple[Optimum, ...] = ()
    stopped_in: str = "initial"

    def __post_init__(self) -> None:
        for array in (self.x, self.trials, *self.criteria.arrays(),
                      *self.trial_criteria.arrays()):
            array.setflags(write=False)

    @property
    def feasible(self) -> bool:
        """Whether the best design meets every obligatory and desirable condition."""
        return bool(self.criteria.feasible[0])

    @property
    def message(self) -> str:
        """The stop reason as a sentence (English; :meth:`stop_message` in any language)."""
        return self.stop_message().text("en")

    def stop_message(self) -> Message:
        """The stop reason as a catalogue message."""
        return Message(STOP_REASONS[self.stop])
