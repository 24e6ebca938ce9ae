"""Existence of every group over the input cycle: where it cannot be assembled, and why.

The check follows the course (``method.md`` §5.4): at each input position the groups are
taken in layering order; the first group that cannot be assembled is reported there, and the
groups after it are not evaluated at that position. :func:`check_existence` returns, per
group, the intervals of the input coordinate where it is the first failing group, the failing
condition (the inequality of ``method.md`` §2.1–2.5 and the solver's reason), the worst
violation (normalised margin against δ, and in millimetres or degrees), and the margin over
the positions where it was evaluated. Interval ends are refined by bisection between the grid
positions, so they are exact to ``tol`` and do not depend on the grid step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.kinds import HIGHER, KINDS
from assur.kinematics import jets as J
from assur.kinematics.analysis import GroupSolution, Motion, analyse
from assur.kinematics.laws import STROKE
from assur.kinematics.model import GroupModel, KinematicModel
from assur.kinematics.reasons import Reason, reason_text
from assur.kinematics.rules import ShortfallAt, rules_of

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.higher.kind import HigherGroupSolution

__all__ = [
    "CONDITIONS",
    "ExistenceReport",
    "FailureInterval",
    "GroupExistence",
    "check_existence",
    "checked_groups",
    "first_failure",
]

#: Existence inequality of each kind, as printed in reports (``method.md`` §2.1–2.5; the
#: triad and the class IV group by their codes, ``docs/higher_groups.md``).
CONDITIONS: dict[int | str, str] = {
    **{number: kind.condition for number, kind in KINDS.items()},
    **{code: kind.condition for code, kind in HIGHER.items()}}


@dataclass(frozen=True)
class FailureInterval:
    """An interval of the input coordinate where a group is the first that fails.

    Attributes
    ----------
    start, end : float
        Ends (input coordinate; radians of crank rotation or mm of actuator length), refined
        between grid positions. For a full-turn crank an interval may wrap past 2π (then
        ``end < start``).
    reason : int
        Solver reason code at the worst position (:class:`assur.kinematics.reasons.Reason`).
    worst_margin : float
        The smallest normalised margin inside the interval (to compare with δ).
    worst_at : float
        Where it occurs.
    shortfall : float
        The violation in the group's own terms at the worst position: millimetres for L1–L3
        (how much a length is too short or too long), degrees for L4–L5 (angle between the
        guides below the allowed one).
    unit : str
        ``'mm'`` or ``'deg'``.
    """

    start: float
    end: float
    reason: int
    worst_margin: float
    worst_at: float
    shortfall: float
    unit: str

    def to_dict(self, degrees: bool) -> dict[str, Any]:
        """JSON-ready record (crank positions in degrees when ``degrees``)."""
        conv = math.degrees if degrees else float
        return {"start": conv(self.start), "end": conv(self.end), "reason": int(self.reason),
                "condition": reason_text(self.reason), "worst_margin": self.worst_margin,
                "worst_at": conv(self.worst_at), "shortfall": self.shortfall,
                "unit": self.unit}


@dataclass(frozen=True)
class GroupExistence:
    """Existence of one group over the positions.

    Attributes
    ----------
    label, name : str
    kind : int or str
    delta : float
        The assigned tolerance δ.
    evaluated : ndarray of bool
        Positions where every earlier group assembles (the group is checked there).
    fails : ndarray of bool
        Positions where this group is the first that fails.
    margin : ndarray
        Normalised margin (NaN where not evaluated).
    intervals : list of FailureInterval
    """

    label: str
    name: str
    kind: int | str
    delta: float
    evaluated: np.ndarray
    fails: np.ndarray
    margin: np.ndarray
    intervals: list[FailureInterval] = field(default_factory=list)

    @property
    def assembles(self) -> bool:
        """True when the group assembles wherever it is evaluated."""
        return not bool(self.fails.any())

    @property
    def min_margin(self) -> float:
        """Smallest margin over the positions where the group was evaluated."""
        values = self.margin[self.evaluated]
        return float(np.nanmin(values)) if values.size and np.isfinite(values).any() \
            else math.nan

    @property
    def verdict(self) -> str:
        """``'assembles'``, ``'fails'`` or ``'not evaluated'`` (an earlier group always fails)."""
        if not self.evaluated.any():
            return "not evaluated"
        return "assembles" if self.assembles else "fails"


@dataclass(frozen=True)
class ExistenceReport:
    """Existence of the mechanism over the positions ``q``.

    Attributes
    ----------
    q : ndarray
    groups : tuple of GroupExistence
        Layering order (the input group is left out: it always assembles).
    first : ndarray of int
        Index into ``groups`` of the first failing group at each position; −1 where all
        assemble.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> report = assur.check_existence(model, points=36)
    >>> [group.label for group in report.groups], bool(report.groups[0].fails.any())
    (['L1(2,3)'], False)
    """

    q: np.ndarray
    groups: tuple[GroupExistence, ...]
    first: np.ndarray

    def __repr__(self) -> str:
        failing = [f"{g.label} (intervals: {len(g.intervals)})" for g in self.groups
                   if g.intervals]
        return (f"ExistenceReport({np.size(self.q)} positions, every group assembles: "
                f"{self.all_exist}; fails: {', '.join(failing) or 'none'})")

    @property
    def all_exist(self) -> bool:
        """True when every group assembles at every position."""
        return bool((self.first < 0).all())


def checked_groups(model: KinematicModel) -> list[GroupModel]:
    """The groups whose existence is checked, in layering order: every group but the input
    groups, and an input group whose linear input has stroke limits."""
    return [g for g in model.groups if not g.group_kind.is_input
            or (g.label in model.laws and model.laws[g.label].limited)]


def first_failure(motion: Motion) -> np.ndarray:
    """Index (into the dyads in layering order) of the first failing group; −1 if none.

    Works for any shape of positions and designs, e.g. ``(D, N)``.
    """
    dyads = checked_groups(motion.model)
    shape = np.shape(motion.q)
    first = np.full(np.broadcast_shapes(shape, *(np.shape(motion.solutions[g.label].exists)
                                                 for g in dyads)), -1, dtype=np.int32)
    for index, group in enumerate(dyads):
        fails = ~motion.solutions[group.label].exists
        first = np.where((first < 0) & fails, index, first)
    return first


def check_existence(model: KinematicModel, q: np.ndarray | None = None, *, points: int = 360,
                    motion: Motion | None = None, refine: bool = True,
                    tol: float = 1e-10) -> ExistenceReport:
    """Existence of every group over the input positions of one design.

    Parameters
    ----------
    model : KinematicModel
        One design (scalar parameters).
    q : array_like, optional
        Increasing input positions; default the model's grid with ``points`` positions.
    motion : Motion, optional
        An analysis already made at ``q`` (saves one solve).
    refine : bool
        Refine interval ends by bisection to ``tol`` (relative to the input range).

    Returns
    -------
    ExistenceReport

    Examples
    --------
    The sketched four-bar is a crank-rocker (Grashof: 40.3 + 100.6 ≤ 100 + 80.6), so its RRR
    group assembles over the whole turn:

    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> report = assur.check_existence(model, points=36)
    >>> [group.intervals for group in report.groups]
    [[]]
    """
    if motion is None:
        motion = analyse(model, q, points=points)
    q = motion.q
    if q.ndim != 1 or model.design_shape not in ((), (1,), (1, 1)):
        raise ValueError("check_existence works on one design over a 1-D grid of positions")
    dyads = checked_groups(model)
    first = first_failure(motion).reshape(q.shape)
    span = model.input_range[1] - model.input_range[0]
    periodic = model.periodic and q.size > 1 and \
        math.isclose(q[-1] + (q[1] - q[0]) - q[0], 2 * math.pi)
    groups = []
    for index, group in enumerate(dyads):
        sol = motion.solutions[group.label]
        evaluated = (first < 0) | (first >= index)
        fails = first == index
        margin = np.where(evaluated, np.broadcast_to(sol.margin, q.shape), np.nan)
        runs = _runs(fails, periodic)
        intervals = [_interval(model, motion, group, index, run, periodic, refine,
                               tol * max(abs(span), 1.0))
                     for run in runs]
        delta = float(np.max(model.params.get(group.column("delta"), 0.0)))
        groups.append(GroupExistence(group.label, group.name, group.kind, delta, evaluated,
                                     fails, margin, intervals))
    return ExistenceReport(q, tuple(groups), first)


def _runs(mask: np.ndarray, periodic: bool) -> list[tuple[int, int]]:
    """Index runs (first, last) of True values; a run may wrap around when periodic."""
    if not mask.any():
        return []
    n = mask.size
    padded = np.concatenate(([False], mask, [False]))
    edges = np.flatnonzero(np.diff(padded.astype(np.int8)))
    runs = [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2])]
    if periodic and len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == n - 1:
        runs = [(runs[-1][0], runs[0][1])] + runs[1:-1]
    return runs


def _interval(model: KinematicModel, motion: Motion, group: GroupModel, index: int,
              run: tuple[int, int], periodic: bool, refine: bool, tol: float
              ) -> FailureInterval:
    q = motion.q
    n = q.size
    first, last = run
    idx = np.arange(first, last + 1) if first <= last else np.r_[first:n, 0:last + 1]
    sol = motion.solutions[group.label]
    margin = np.broadcast_to(sol.margin, q.shape)[idx]
    worst = int(idx[int(np.nanargmin(np.where(np.isnan(margin), np.inf, margin)))]) \
        if np.isfinite(margin).any() else int(idx[0])
    reason = int(np.broadcast_to(sol.reason, q.shape)[worst])
    start, end = float(q[first]), float(q[last])
    step = float(q[1] - q[0]) if n > 1 else 0.0
    whole = idx.size == n  # fails everywhere: the interval is the whole range
    if whole:
        start, end = float(model.input_range[0]), float(model.input_range[1])
    if refine and n > 1 and not whole:
        if first > 0 or periodic:
            outside = float(q[first - 1]) if first > 0 else float(q[-1]) - n * step
            start = _boundary(model, group, index, sol, outside, start, tol)
            start = start % (2 * math.pi) if periodic else start
        if last < n - 1 or periodic:
            outside = float(q[last + 1]) if last < n - 1 else float(q[0]) + n * step
            end = _boundary(model, group, index, sol, outside, end, tol)
            end = end % (2 * math.pi) if periodic else end
    shortfall, unit = _shortfall(model, motion, group, worst)
    return FailureInterval(start, end, reason, float(np.broadcast_to(sol.margin, q.shape)[worst]),
                           float(q[worst]), shortfall, unit)


def _boundary(model: KinematicModel, group: GroupModel, index: int, sol: GroupSolution,
              good: float, bad: float, tol: float) -> float:
    """The end of a failure interval between ``good`` and ``bad``: bisection for a dyad; for
    a triad or class IV group the change point where its followed mode ended, if it lies
    there (no re-solving: each solve follows the mode from the sketch), else ``bad``; a
    higher group solved in closed form is bisected like a dyad."""
    if group.layout is not None:
        from assur.kinematics.higher.kind import HigherGroupSolution  # loaded with the group

        assert isinstance(sol, HigherGroupSolution)
        if sol.followed:
            return _change_point(sol, good, bad)
    return _bisect(model, group, index, good, bad, tol)


def _change_point(sol: HigherGroupSolution, good: float, bad: float) -> float:
    """Where the followed mode of a higher group ended between ``good`` and ``bad``, else
    ``bad``."""
    lo, hi = sorted((good, bad))
    for end in map(float, np.asarray(sol.follow.ends, dtype=float).ravel()):
        if not math.isfinite(end):
            continue
        turns = math.floor((hi - end) / (2 * math.pi)) if sol.follow.periodic else 0
        shifted = end + 2 * math.pi * turns
        if lo <= shifted <= hi:
            return float(shifted)
    return bad


def _bisect(model: KinematicModel, group: GroupModel, index: int, good: float, bad: float,
            tol: float) -> float:
    """The boundary between a position where group ``index`` is not the first failing one
    (``good``) and one where it is (``bad``)."""
    lo, hi = good, bad
    for _ in range(200):
        if abs(hi - lo) <= tol:
            break
        mid = 0.5 * (lo + hi)
        motion = analyse(model, np.array([mid]))
        if int(first_failure(motion).ravel()[0]) != index:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _shortfall(model: KinematicModel, motion: Motion, group: GroupModel, at: int
               ) -> tuple[float, str]:
    """The violated condition in the group's own terms at one position (the kind's rule)."""
    sol = motion.solutions[group.label]

    def hinge(role: str) -> complex:
        return complex(np.broadcast_to(J.value(motion.joints[group.pairs[role]]),
                                       motion.q.shape)[at])

    margin = float(np.broadcast_to(sol.margin, motion.q.shape)[at])
    if int(np.broadcast_to(sol.reason, motion.q.shape)[at]) == Reason.STROKE_END:
        lo, hi = (float(np.max(model.value(group.column(c)))) for c in STROKE)
        return -margin * max(hi - lo, 1.0), "mm"
    rule = rules_of(group.group_kind).shortfall
    assert rule is not None  # every kind but the input group has one
    return rule(group, ShortfallAt(
        q=float(motion.q[at]), margin=float(np.broadcast_to(sol.margin, motion.q.shape)[at]),
        delta=float(np.max(model.params.get(group.column("delta"), 0.0))), value=model.value,
        hinge=hinge))
