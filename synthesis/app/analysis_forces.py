"""A force analysis condensed for the reports (``assur analyze --forces --omega W``).

:func:`assur.analyse` runs the kinetostatics (``docs/forces.md``) with the table's
``masses:``, ``loads:`` and ``gravity:`` sections; :func:`summarise` condenses the result for
the text report and the coursework report: the extreme driving torque and where,
the largest reaction in every pair, and the two checks (power balance and Newton–Euler).

Examples
--------
>>> from pathlib import Path
>>> import synthesis
>>> import assur
>>> table = Path(synthesis.__file__).parents[1] / "input_tables" / "four_bar_gravity.yaml"
>>> result = assur.analyse(table, points=36, forces=True, omega=10.0)
>>> forces = result.forces
>>> forces.drive, forces.driving.shape
('driving_torque', (36,))
>>> summary = summarise(forces, result.motion.q)
>>> summary.solved, summary.balance_relative < 1e-12
(36, True)
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from assur.forces.groups import ForceReason
from assur.forces.solver import ForceAnalysis
from assur.kinds import KINDS
from assur.model import LinkId, PairId

__all__ = ["Extreme", "ForceSummary", "InputEffort", "PairPeak", "summarise"]


@dataclass(frozen=True, slots=True)
class InputEffort:
    """One input's driving effort over the positions: the label of its group, its kind
    (``'driving_torque'``, N·m, or ``'driving_force'``, N), its extremes and mean."""

    label: str
    kind: str
    low: Extreme
    high: Extreme
    mean: float


@dataclass(frozen=True, slots=True)
class Extreme:
    """A largest (or smallest) value over the positions and the input coordinate there
    (radians of crank rotation, or mm of actuator length); NaN when nothing was solved."""

    value: float
    at: float


@dataclass(frozen=True, slots=True)
class PairPeak:
    """The largest reaction in one pair: |R| (N), and for a prismatic pair the largest
    |moment| about its slider point (N·m)."""

    pair: PairId
    links: tuple[LinkId, LinkId]
    force: Extreme
    moment: Extreme | None


@dataclass(frozen=True, slots=True)
class ForceSummary:
    """What the reports say of a force analysis.

    Attributes
    ----------
    low, high : Extreme
        The smallest and largest driving torque (N·m) or force (N).
    mean : float
        The mean of the drive over the solved positions.
    pairs : tuple of PairPeak
    balance : float
        The largest |power balance| (driving torque − the lever's), N·m or N.
    balance_relative : float
        The largest |power balance| relative to the sum of the magnitudes of the powers.
    residual_force, residual_moment : float
        The largest relative Newton–Euler residual of any link.
    unsolved : dict
        Reason → the first position where it holds (positions not solved).
    solved, total : int
        Positions solved, and all positions.
    inputs : tuple of InputEffort
        Each input's driving effort, when there are several inputs or the input is a slider
        (empty otherwise: ``low``, ``high``, ``mean`` say it).
    """

    low: Extreme
    high: Extreme
    mean: float
    pairs: tuple[PairPeak, ...]
    balance: float
    balance_relative: float
    residual_force: float
    residual_moment: float
    unsolved: dict[ForceReason, tuple[float, str | None]]
    solved: int
    total: int
    inputs: tuple[InputEffort, ...] = ()


def summarise(forces: ForceAnalysis, q: np.ndarray) -> ForceSummary:
    """Condense a force analysis of one design (positions ``q``) for the reports.

    Parameters
    ----------
    forces : ForceAnalysis
        Of one design: arrays shaped ``(N,)``.
    q : ndarray
        The input coordinate at the positions.

    Returns
    -------
    ForceSummary
    """
    driving = np.asarray(forces.driving, dtype=float)
    with np.errstate(all="ignore"):
        relative = np.abs(forces.power_balance) / forces.power_scale
        residuals = list(forces.residuals.values())
    pairs = tuple(PairPeak(r.pair, r.links, _largest(np.hypot(r.x, r.y), q),
                           None if r.moment is None else _largest(np.abs(r.moment), q))
                  for r in forces.reactions.values())
    unsolved: dict[ForceReason, tuple[float, str | None]] = {}
    for index in np.flatnonzero(forces.reason):
        reason = ForceReason(int(forces.reason[index]))
        unsolved.setdefault(reason, (float(q[index]), forces.singular[index]))
    inputs: tuple[InputEffort, ...] = ()
    slider = forces.drive == "driving_force" and next(iter(forces.drivings)).startswith(
        KINDS[0].code)  # a force on an input group: a slider on a frame guide
    if len(forces.drivings) > 1 or slider:
        inputs = tuple(_effort(label, forces.drive_kinds[label], values, q)
                       for label, values in forces.drivings.items())
    return ForceSummary(
        low=_extreme(driving, q, np.nanargmin), high=_extreme(driving, q, np.nanargmax),
        mean=_mean(driving),
        pairs=pairs, balance=_peak(np.abs(forces.power_balance)),
        balance_relative=_peak(np.where(forces.power_scale > 0, relative, 0.0)),
        residual_force=_peak(np.concatenate([r.force.ravel() for r in residuals])),
        residual_moment=_peak(np.concatenate([r.moment.ravel() for r in residuals])),
        unsolved=unsolved, solved=int(np.count_nonzero(forces.reason == 0)),
        total=int(forces.reason.size), inputs=inputs)


def _effort(label: str, kind: str, values: np.ndarray, q: np.ndarray) -> InputEffort:
    data = np.asarray(values, dtype=float)
    return InputEffort(label, kind, _extreme(data, q, np.nanargmin),
                       _extreme(data, q, np.nanargmax), _mean(data))


def _mean(data: np.ndarray) -> float:
    return float(np.nanmean(data)) if np.isfinite(data).any() else float("nan")


def _extreme(data: np.ndarray, q: np.ndarray, pick: Callable[[np.ndarray], Any]) -> Extreme:
    if not np.isfinite(data).any():
        return Extreme(float("nan"), float("nan"))
    index = int(pick(data))
    return Extreme(float(data[index]), float(q[index]))


def _largest(data: np.ndarray, q: np.ndarray) -> Extreme:
    return _extreme(np.asarray(data, dtype=float), q, np.nanargmax)


def _peak(data: np.ndarray) -> float:
    data = np.asarray(data, dtype=float)
    return float(np.nanmax(data)) if np.isfinite(data).any() else float("nan")
