"""The whole tracker case for one design task: table, choice, simulation, reproduction.

:func:`run_study` builds the design table (Etapa I–V), chooses the design on the table's
rows and on a continuous ``k2`` (Etapa VI), and confirms every returned design by an
independent simulation of its dimensions (:mod:`~synthesis.cases.tracker.model`): the
platform stroke, the smallest transmission angle and the post clearance must come out of the
simulation as the closed forms promised.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from synthesis.cases.tracker.design import (
    Design,
    DesignTable,
    DesignTask,
    choose,
    design_table,
    refine,
)
from synthesis.cases.tracker.model import TrackerMotion, simulate
from synthesis.cases.tracker.reproduction import Comparison, reproduce, reproduce_mm
from synthesis.cases.tracker.synthesis_problem import SynthesisAnswer, has_room, solve

__all__ = ["Study", "Verification", "run_study", "verify", "worst"]


@dataclass(frozen=True)
class Verification:
    """A design's dimensions simulated over the actuator's stroke ``l_i … l_d``.

    Attributes
    ----------
    design : Design
    motion : TrackerMotion
        The chain-table model solved over the stroke by the mechanism-level analysis.
    stroke : float
        Simulated platform stroke, radians.
    b_min : float
        Smallest simulated transmission angle at B (coupler to short rocker), radians.
    c_min : float
        Smallest simulated transmission angle at C (actuator to long rocker), radians.
    clearance : float
        Simulated distance from the post to the actuator's axis at full extension.
    min_clearance : float
        Its smallest value over the stroke.
    lever_arm : tuple of float
        Smallest, retracted-end and extended-end lever arm ``ds/dφ`` of the actuator.
    assembles : bool
        Both dyads assemble at every position.
    """

    design: Design
    motion: TrackerMotion
    stroke: float
    b_min: float
    c_min: float
    clearance: float
    min_clearance: float
    lever_arm: tuple[float, float, float]
    assembles: bool

    @property
    def errors(self) -> dict[str, float]:
        """Simulated minus closed-form: stroke and b_min (degrees), l_g (mm)."""
        return {"stroke": math.degrees(self.stroke - self.design.a),
                "b_min": math.degrees(self.b_min - self.design.b_min),
                "l_g": self.clearance - self.design.l_g}


def verify(design: Design, *, positions: int = 721) -> Verification:
    """Simulate a design's dimensions and measure what the closed forms promise.

    Parameters
    ----------
    design : Design
    positions : int
        Actuator lengths evenly spread over ``[l_i, l_d]``.

    Returns
    -------
    Verification
    """
    motion = simulate(design.l1, design.l2, design.l5, design.l_i, design.l_d,
                      positions=positions)
    folded = motion.transmission
    arm = motion.lever_arm
    return Verification(
        design=design, motion=motion, stroke=motion.stroke,
        b_min=float(folded[0].min()), c_min=float(folded[1].min()),
        clearance=float(abs(motion.post_distance[-1])), min_clearance=motion.min_clearance,
        lever_arm=(float(arm.min()), float(arm[0]), float(arm[-1])),
        assembles=bool(motion.exists.all()))


@dataclass(frozen=True)
class Study:
    """Everything the tracker case reports for one design task.

    Attributes
    ----------
    task : DesignTask
    table : DesignTable
        Etapa I–V on the task's grid.
    chosen : Verification or None
        Etapa VI on the table's rows (None if no row is admissible).
    refined : Verification or None
        Etapa VI on a continuous ``k2`` (the smallest admissible design over every ``k5``).
    comparisons : list of Comparison
        The patent's printed values beside the computed ones (ratios, angles, then mm).
    synthesis : SynthesisAnswer or None
        The same task as a B1–B5 synthesis problem (None when not run).
    """

    task: DesignTask
    table: DesignTable
    chosen: Verification | None
    refined: Verification | None
    comparisons: list[Comparison]
    synthesis: SynthesisAnswer | None = None


def _smallest(designs: list[Design]) -> Design | None:
    return min(designs, key=lambda d: (d.k_d, -d.b_min)) if designs else None


def run_study(task: DesignTask, *, positions: int = 721, budget_log2: int | None = 10,
              seed: int = 0, progress: bool = False) -> Study:
    """Run the design procedure, the checks and the B1–B5 synthesis for one task.

    Parameters
    ----------
    task : DesignTask
    positions : int
        Positions of each verifying simulation.
    budget_log2 : int or None
        LPτ budget of the synthesis (``2**budget_log2`` trials in the first pass); None skips
        the synthesis (so does a stroke within 2° of a full turn).
    seed : int
        Seed of the synthesis.
    progress : bool
        Print the synthesis's progress on standard error.

    Returns
    -------
    Study
    """
    table = design_table(task)
    chosen = choose(table)
    refined = _smallest([d for d in (refine(task, k5) for k5 in task.k5) if d is not None])
    return Study(
        task=task, table=table,
        chosen=None if chosen is None else verify(chosen, positions=positions),
        refined=None if refined is None else verify(refined, positions=positions),
        comparisons=reproduce() + reproduce_mm(),
        synthesis=None if budget_log2 is None or not has_room(task) else solve(
            task, budget_log2=budget_log2, seed=seed, progress=progress))


def worst(comparisons: list[Comparison], quantity: str) -> float:
    """Largest |difference| of one quantity among the rows expected to match."""
    return max((c.deviation for c in comparisons
                if c.quantity == quantity and c.tolerance is not None), default=np.nan)
