"""The tracker's design task posed as a B1–B5 optimisation-synthesis problem.

B1, the varied parameters (``method.md`` §4): ``k2 = l2/l1`` and ``k5 = l5/l1`` over the
ranges of the task, and the start angle ``θ0`` of the platform — the crank angle
``phi_1_0`` of the input group when the platform is taken as the input link. ``l1`` is
given. The platform turns from ``θ0`` through the stroke ``a``; it may not pass the base
direction A→D, where the kite folds (B on D), so ``θ0`` lies in ``(−180°, 180° − a)``.

B2, the analysis: the chain table of :mod:`~synthesis.cases.tracker.model` with the platform
as the input link (the actuator becomes an RPR group, its length the distance E–C), every
candidate design at every position in one call of
:func:`assur.kinematics.analysis.analyse` (parameters as ``(D, 1)`` columns).

B3, the criteria (:mod:`synthesis.criteria`): P1 — the chain assembles over the whole stroke;
P2 — the desirable conditions, each a normalised excess: the transmission angle at B not
below ``b_min.ad`` (as the pressure angle ``90° − b`` not above ``90° − b_min.ad``), the post
clearance not below its minimum, the actuator stroke ``l_d − l_i`` within the actuator's;
Q — the size, the longest actuator length over ``l1`` (``k_d``).

B4, the search: :func:`synthesis.search.search` (seeded LPτ passes, shrinking passes).

Unlike the patent's procedure, which places the stroke symmetrically (the transmission angle
is ``b_min`` at both ends, the premise of ``a = 2[180° − (c + d)]``), the search is free to
place it anywhere; :func:`solve` reports where it went.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import numpy.typing as npt

from assur import KinematicModel, Motion, analyse_structure, build_model
from assur.io.sketch import with_sketch
from assur.kinematics.analysis import analyse, values
from assur.model import Drive
from assur.typing import FloatArray
from synthesis.cases.tracker.design import DesignTask
from synthesis.cases.tracker.model import TrackerMotion, chain, simulate, sketch
from synthesis.criteria import Criteria, bounds_penalty, existence_penalty, pressure_penalty
from synthesis.search import search
from synthesis.search_result import SearchResult
from synthesis.search_settings import SearchSettings

__all__ = ["NAMES", "Evaluator", "SynthesisAnswer", "bounds", "has_room", "solve"]


NAMES: tuple[str, ...] = ("k2", "k5", "theta0_deg")
"""The varied parameters, in the order of the design vector x."""

_EDGE_DEG = 1.0  # keep the stroke this far from the folded position (B on D)


def has_room(task: DesignTask) -> bool:
    """Whether the stroke leaves room for the platform's start angle (see :func:`bounds`)."""
    return math.degrees(task.stroke) < 360.0 - 2.0 * _EDGE_DEG


def bounds(task: DesignTask) -> tuple[FloatArray, FloatArray]:
    """B1: lower and upper bounds of ``x = (k2, k5, θ0 in degrees)``.

    ``k5`` is fixed (lower = upper) when the task gives a single value.

    Raises
    ------
    ValueError
        When the stroke leaves no room for ``θ0`` (``a`` within 2° of a full turn).
    """
    a = math.degrees(task.stroke)
    lo, hi = -180.0 + _EDGE_DEG, 180.0 - a - _EDGE_DEG
    if not has_room(task):
        raise ValueError(f"a stroke of {a:g}° leaves no room for the platform's start angle")
    return (np.array([min(task.k2), min(task.k5), lo]),
            np.array([max(task.k2), max(task.k5), hi]))


@dataclass(frozen=True)
class _Measures:
    """What B2 measures on each design (arrays of shape (D,))."""

    p1: FloatArray
    b_min: FloatArray
    l_i: FloatArray
    l_d: FloatArray
    clearance: FloatArray


class Evaluator:
    """B2 and B3: the criteria of a batch of designs ``X`` of shape ``(D, 3)``.

    Parameters
    ----------
    task : DesignTask
    positions : int
        Platform positions over the stroke.
    """

    def __init__(self, task: DesignTask, *, positions: int = 181) -> None:
        self.task = task
        self.lower, self.upper = bounds(task)
        self.q = np.linspace(0.0, task.stroke, positions)
        l1, k2 = task.l1, float(np.mean(task.k2))
        geometry = sketch(l1, k2 * l1, 2.0 * l1, l1, 2.0 * l1)
        del geometry["input"]
        analysis = analyse_structure(with_sketch(replace(chain(), inputs=(Drive(link=1),)),
                                                 geometry))
        self.formula = analysis.formula
        self.model: KinematicModel = build_model(analysis)
        self._joints: dict[Any, Any] = {}
        for pair in analysis.chain.pairs:
            if pair.type.value == "R":
                self._joints.setdefault(pair.origin, pair.id)
        self._names = self._parameter_names(self.model)

    @staticmethod
    def _parameter_names(model: KinematicModel) -> dict[str, list[str]]:
        """The model's parameters that carry l2, the position of E, and θ0."""
        names: dict[str, list[str]] = {"l2": [], "e": [], "theta0": []}
        for group in model.groups:
            if group.kind == 0:
                names["theta0"].append(group.column("phi_1_0"))
            elif group.kind == 1:
                names["l2"] += [group.column(c) for c in ("l_i", "l_j", "l_N")
                                if group.column(c) in model.params]
            elif group.kind == 3:
                names["e"].append(group.column("x_Hi"))
        return names

    def designs(self, x: npt.ArrayLike) -> KinematicModel:
        """The model with the designs' parameters as ``(D, 1)`` columns."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        l1 = self.task.l1
        column = {"l2": x[:, :1] * l1, "e": (x[:, 1:2] - 1.0) * l1, "theta0": x[:, 2:3]}
        return self.model.with_params({name: column[key] for key, group in self._names.items()
                                        for name in group})

    def measure(self, x: npt.ArrayLike) -> _Measures:
        """Analyse the designs over the stroke and measure what the criteria need."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        model = self.designs(x)
        motion = analyse(model, self.q)
        shape = (x.shape[0], self.q.size)
        a, b, c, e = (np.broadcast_to(values(motion.joints[self._joints[name]]), shape)
                      for name in "ABCE")
        with np.errstate(invalid="ignore", divide="ignore"):
            angle_b = np.abs(np.angle((a - b) / (c - b)))
            folded = np.minimum(angle_b, np.pi - angle_b)
            s = np.abs(c - e)
            post = np.abs(np.imag(np.conj(c - e) * (a - e))) / s
        return _Measures(p1=self._existence(motion, model, shape),
                         b_min=np.min(folded, axis=1), l_i=np.min(s, axis=1),
                         l_d=np.max(s, axis=1), clearance=np.min(post, axis=1))

    @staticmethod
    def _existence(motion: Motion, model: KinematicModel, shape: tuple[int, int]) -> FloatArray:
        first = np.zeros(shape, dtype=int)
        violation = np.zeros(shape)
        for ordinal, group in enumerate(model.groups, start=1):
            solution = motion.solutions[group.label]
            fails = (first == 0) & ~np.broadcast_to(solution.exists, shape)
            first = np.where(fails, ordinal, first)
            violation = np.where(fails, -np.broadcast_to(solution.margin, shape), violation)
        return existence_penalty(first, violation, len(model.groups))

    def __call__(self, x: npt.ArrayLike) -> Criteria:
        """B3: P1, P2 and Q (the size ``l_d/l1``) of the designs."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        m = self.measure(x)
        task = self.task
        feasible = m.p1 == 0
        alpha = 90.0 - np.degrees(m.b_min)
        varied = self.upper > self.lower
        p2 = (bounds_penalty(x[:, varied], self.lower[varied], self.upper[varied])
              + pressure_penalty(alpha[:, None],
                                 np.array([90.0 - math.degrees(task.min_transmission)]))
              + np.maximum(0.0, task.min_clearance - m.clearance) / max(task.min_clearance, 1.0)
              + np.maximum(0.0, m.l_d - m.l_i - task.actuator_stroke) / task.actuator_stroke)
        size = m.l_d / task.l1
        q = np.where(feasible, size, np.nan)
        p2 = np.where(feasible, np.nan_to_num(p2, nan=np.inf), np.nan)
        return Criteria(m.p1, p2, q, q[:, None], q[:, None])


@dataclass(frozen=True)
class SynthesisAnswer:
    """B5: the design the search found, in the patent's terms, checked by simulation.

    Attributes
    ----------
    task : DesignTask
    x : ndarray
        ``(k2, k5, θ0 in degrees)``.
    feasible : bool
        P1 = P2 = 0 (every condition met).
    l_i, l_d : float
        Actuator length at the two ends of the stroke, mm.
    check : TrackerMotion
        The actuator-driven chain simulated from ``l_i`` to ``l_d``.
    result : SearchResult
        The search's record (trials, stop reason, time).
    formula : str
        Structure formula of the synthesis model (platform as the input link).
    """

    task: DesignTask
    x: FloatArray
    feasible: bool
    l_i: float
    l_d: float
    check: TrackerMotion
    result: SearchResult
    formula: str

    @property
    def k2(self) -> float:
        """``l2/l1``."""
        return float(self.x[0])

    @property
    def k5(self) -> float:
        """``l5/l1``."""
        return float(self.x[1])

    @property
    def ends(self) -> tuple[float, float]:
        """Transmission angle at B at the retracted and the extended end, radians."""
        folded = self.check.transmission[0]
        return float(folded[0]), float(folded[-1])

    def lengths(self) -> dict[str, float]:
        """The design in millimetres, by the patent's names."""
        l1 = self.task.l1
        return {"l1": l1, "l2": self.k2 * l1, "l5": self.k5 * l1, "l_d": self.l_d,
                "l_i": self.l_i, "l_s": self.l_d - self.l_i,
                "l_g": float(abs(self.check.post_distance[-1]))}


def solve(task: DesignTask, *, budget_log2: int = 10, seed: int = 0, positions: int = 181,
          shrink_passes: int = 3, progress: bool = False) -> SynthesisAnswer:
    """Run B1–B5 for a design task.

    Parameters
    ----------
    task : DesignTask
    budget_log2 : int
        The first passive pass draws ``2**budget_log2`` LPτ trials.
    seed : int
        Seed of the scrambled sequence (same seed, same answer).
    positions : int
        Platform positions per analysis.
    shrink_passes : int
        Passive passes in boxes shrunk around the best design.
    progress : bool
        Print the search's progress on standard error.

    Returns
    -------
    SynthesisAnswer
    """
    evaluate = Evaluator(task, positions=positions)
    lower, upper = evaluate.lower, evaluate.upper
    settings = SearchSettings(budget_log2=budget_log2, seed=seed, shrink_passes=shrink_passes,
                              progress=progress)
    result = search(evaluate, lower, upper, (lower + upper) / 2.0, settings)
    m = evaluate.measure(result.x)
    l_i, l_d = float(m.l_i[0]), float(m.l_d[0])
    x = result.x
    check = simulate(task.l1, x[0] * task.l1, x[1] * task.l1, l_i, l_d, positions=positions)
    return SynthesisAnswer(task=task, x=x, feasible=result.feasible, l_i=l_i, l_d=l_d,
                           check=check, result=result, formula=evaluate.formula)
