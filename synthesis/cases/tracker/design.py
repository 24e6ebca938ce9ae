"""The patent's design procedure (Etapa I–VI) as a program.

For a platform stroke ``a``, the smallest allowed transmission angle ``b_min.ad``, the short
rocker ``l1`` (set by the wind load), the stroke of the available actuator and the clearance
needed between the actuator and the platform's post, the procedure

I.   computes ``b_min(a, k2)`` for the discrete ``k2`` and keeps ``b_min ≥ b_min.ad``
     (the smallest such ``k2`` is ``k2_min``);
II.  computes the angles ``c`` and ``d``;
III. computes the actuator ratios ``k_d``, ``k_i``, ``k_s`` for every ``k5``;
IV.  would read the angles ``e`` and ``f`` — the text never defines them, so they are
     reported as not derivable;
V.   computes the post clearance ``k_g``;
VI.  chooses the design: among the rows that satisfy every requirement
     (``b_min ≥ b_min.ad``, ``l_g ≥`` the clearance, ``l_s ≤`` the actuator's stroke) the
     one of the smallest size — the shortest extended actuator ``l_d``, which sets the
     envelope of the mechanism — and, among equals, the larger ``b_min``.

Etapa VI also allows designs interpolated between the table's rows; :func:`refine` finds the
smallest such design for the chosen ``k5`` on a continuous ``k2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from scipy.optimize import brentq

from assur.typing import BoolArray, FloatArray
from synthesis.cases.tracker.geometry import Proportions, check_ratios, proportions
from synthesis.cases.tracker.patent import EXAMPLE, K2

__all__ = [
    "PATENT_TASK",
    "Design",
    "DesignTable",
    "DesignTask",
    "Violation",
    "choose",
    "design_at",
    "design_table",
    "refine",
]


_REFINE_POINTS = 2001
_SLACK = 1e-9  # a requirement met to this margin (rad or mm) counts as met (roots of refine)


@dataclass(frozen=True)
class DesignTask:
    """What the designer gives (the patent's "Se cunosc").

    Parameters
    ----------
    stroke : float
        Platform stroke ``a``, radians, in (0, 2π).
    min_transmission : float
        Smallest allowed transmission angle ``b_min.ad``, radians.
    l1 : float
        Short rocker (= base) length, mm.
    actuator_stroke : float
        Stroke of the available actuator, mm: the design's ``l_s`` may not exceed it.
    min_clearance : float
        Smallest allowed distance ``l_g`` from the post to the extended actuator's axis, mm.
    k2, k5 : tuple of float
        The discrete proportions ``l2/l1`` and ``l5/l1`` to tabulate (each > 1).
    """

    stroke: float
    min_transmission: float
    l1: float
    actuator_stroke: float
    min_clearance: float
    k2: tuple[float, ...] = K2
    k5: tuple[float, ...] = (2.0,)

    def __post_init__(self) -> None:
        problems = []
        if not 0.0 < self.stroke < 2.0 * math.pi:
            problems.append(f"the stroke must lie strictly between 0° and 360°; got "
                            f"{math.degrees(self.stroke):g}°")
        if not 0.0 <= self.min_transmission < 0.5 * math.pi:
            problems.append(f"the smallest allowed transmission angle must lie in [0°, 90°); "
                            f"got {math.degrees(self.min_transmission):g}°")
        for name in ("l1", "actuator_stroke"):
            if not getattr(self, name) > 0.0:
                problems.append(f"{name} must be positive; got {getattr(self, name)!r}")
        if not self.min_clearance >= 0.0:
            problems.append(f"min_clearance must not be negative; got {self.min_clearance!r}")
        for name in ("k2", "k5"):
            values = getattr(self, name)
            if not values or any(not v > 1.0 for v in values):
                problems.append(f"{name} needs at least one value, each greater than 1; "
                                f"got {list(values)!r}")
        if problems:
            raise ValueError("; ".join(problems))


PATENT_TASK = DesignTask(
    stroke=math.radians(EXAMPLE["stroke_deg"]),
    min_transmission=math.radians(EXAMPLE["min_transmission_deg"]),
    l1=EXAMPLE["l1_mm"], actuator_stroke=EXAMPLE["actuator_stroke_mm"],
    min_clearance=EXAMPLE["min_clearance_mm"], k2=K2, k5=(EXAMPLE["k5"],))
"""The worked example of the patent: a = 210°, b_min.ad = 25°, l1 = 300 mm, a 1000 mm
actuator, l_g ≥ 85 mm, k2 = 1.4 … 2.2, k5 = 2."""


@dataclass(frozen=True)
class Violation:
    """A requirement a design breaks.

    Attributes
    ----------
    requirement : {'transmission', 'clearance', 'stroke'}
        ``b_min ≥ b_min.ad``, ``l_g ≥`` the clearance, or ``l_s ≤`` the actuator's stroke.
    value, limit : float
        The design's value and the task's limit (radians for the transmission angle, mm
        otherwise).
    """

    requirement: Literal["transmission", "clearance", "stroke"]
    value: float
    limit: float


@dataclass(frozen=True)
class Design:
    """One design: proportions, angles (radians) and lengths (mm).

    Attributes
    ----------
    k2, k5 : float
        ``l2/l1`` and ``l5/l1``.
    a, b_min, c, d : float
        Stroke, smallest transmission angle and the patent's angles ``c``, ``d``.
    k_d, k_i, k_s, k_g : float
        Actuator extended, retracted and stroke, post clearance, over ``l1``.
    l1, l2, l5, l_d, l_i, l_s, l_g : float
        The same in millimetres (``l3 = l2``, ``l4 = l1``).
    violations : tuple of Violation
        The requirements the design breaks (empty for an admissible design).
    """

    k2: float
    k5: float
    a: float
    b_min: float
    c: float
    d: float
    k_d: float
    k_i: float
    k_s: float
    k_g: float
    l1: float
    violations: tuple[Violation, ...] = field(default=())

    @property
    def l2(self) -> float:
        """Coupler and long rocker, mm."""
        return self.k2 * self.l1

    @property
    def l5(self) -> float:
        """Distance from the long rocker's base hinge D to the actuator's base hinge E, mm."""
        return self.k5 * self.l1

    @property
    def l_d(self) -> float:
        """Actuator length (hinge to hinge) fully extended, mm."""
        return self.k_d * self.l1

    @property
    def l_i(self) -> float:
        """Actuator length fully retracted, mm."""
        return self.k_i * self.l1

    @property
    def l_s(self) -> float:
        """Actuator stroke used, mm."""
        return self.k_s * self.l1

    @property
    def l_g(self) -> float:
        """Distance from the post to the extended actuator's axis, mm."""
        return self.k_g * self.l1

    @property
    def admissible(self) -> bool:
        """Whether every requirement of the task holds."""
        return not self.violations

    def lengths(self) -> dict[str, float]:
        """Every length in mm, by the patent's names."""
        return {name: float(getattr(self, name))
                for name in ("l1", "l2", "l5", "l_d", "l_i", "l_s", "l_g")}


@dataclass(frozen=True)
class DesignTable:
    """The design table of Etapa I–V over the grid ``k2 × k5`` (arrays of shape (K2, K5)).

    Attributes
    ----------
    task : DesignTask
    values : Proportions
        Every closed-form quantity on the grid.
    transmission_ok, clearance_ok, stroke_ok : ndarray of bool
        ``b_min ≥ b_min.ad``; ``l_g ≥`` the clearance; ``l_s ≤`` the actuator's stroke.
    """

    task: DesignTask
    values: Proportions
    transmission_ok: BoolArray
    clearance_ok: BoolArray
    stroke_ok: BoolArray

    @property
    def admissible(self) -> BoolArray:
        """Rows that satisfy every requirement."""
        return self.transmission_ok & self.clearance_ok & self.stroke_ok

    @property
    def k2_min(self) -> float | None:
        """Etapa I: the smallest tabulated ``k2`` with ``b_min ≥ b_min.ad`` (None if none)."""
        kept = self.transmission_ok[:, 0]
        return float(self.values.k2[kept, 0].min()) if kept.any() else None

    def design(self, row: int, column: int) -> Design:
        """The design of one cell of the table."""
        return _design(self.task, self.values, (row, column))


def _violations(task: DesignTask, values: Proportions) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Margins (≥ 0 when met) of the three requirements, arrays like ``values.k2``."""
    return (values.b_min - task.min_transmission,
            values.k_g * task.l1 - task.min_clearance,
            task.actuator_stroke - values.k_s * task.l1)


def _design(task: DesignTask, values: Proportions, index: tuple[int, ...]) -> Design:
    transmission, clearance, stroke = (float(m[index]) for m in _violations(task, values))
    broken = []
    if transmission < -_SLACK:
        broken.append(Violation("transmission", float(values.b_min[index]),
                                task.min_transmission))
    if clearance < -_SLACK:
        broken.append(Violation("clearance", float(values.k_g[index]) * task.l1,
                                task.min_clearance))
    if stroke < -_SLACK:
        broken.append(Violation("stroke", float(values.k_s[index]) * task.l1,
                                task.actuator_stroke))
    return Design(**{name: float(getattr(values, name)[index]) for name in (
        "k2", "k5", "a", "b_min", "c", "d", "k_d", "k_i", "k_s", "k_g")},
        l1=task.l1, violations=tuple(broken))


def design_table(task: DesignTask) -> DesignTable:
    """Etapa I–V: every quantity for every tabulated ``(k2, k5)`` and the requirements met.

    Parameters
    ----------
    task : DesignTask

    Returns
    -------
    DesignTable
    """
    values = proportions(task.stroke, np.array(task.k2)[:, None], np.array(task.k5)[None, :])
    transmission, clearance, stroke = _violations(task, values)
    return DesignTable(task=task, values=values, transmission_ok=transmission >= 0.0,
                       clearance_ok=clearance >= 0.0, stroke_ok=stroke >= 0.0)


def design_at(task: DesignTask, k2: float, k5: float) -> Design:
    """The design for one pair of proportions (not necessarily on the task's grid)."""
    check_ratios(k2, k5)
    return _design(task, proportions(task.stroke, k2, k5), ())


def _smallest(l_d: FloatArray, b_min: FloatArray, admissible: BoolArray) -> tuple[int, ...]:
    """Index of the admissible cell with the shortest ``l_d`` (then the largest ``b_min``)."""
    order = np.lexsort((-b_min[admissible], l_d[admissible]))
    return tuple(int(i[order[0]]) for i in np.nonzero(admissible))


def choose(table: DesignTable) -> Design | None:
    """Etapa VI on the table's rows: the admissible design of the smallest size.

    Returns
    -------
    Design or None
        None when no row satisfies every requirement.
    """
    if not table.admissible.any():
        return None
    return table.design(*_smallest(table.values.k_d, table.values.b_min, table.admissible))


def refine(task: DesignTask, k5: float) -> Design | None:
    """The smallest admissible design for one ``k5`` on a continuous ``k2``.

    ``k2`` runs over the task's range ``[min(k2), max(k2)]`` (Etapa VI: designs interpolated
    between the rows). The admissible design with the shortest extended actuator is found on
    a fine grid; when it lies on the border of the admissible set, the border is located by
    Brent's method on the requirement that fails just below it.

    Returns
    -------
    Design or None
        None when no ``k2`` in the range satisfies every requirement.
    """
    k2 = np.linspace(min(task.k2), max(task.k2), _REFINE_POINTS)
    values = proportions(task.stroke, k2, k5)
    margins = _violations(task, values)
    admissible = np.logical_and.reduce([m >= 0.0 for m in margins])
    if not admissible.any():
        return None
    (best,) = _smallest(values.k_d, values.b_min, admissible)
    if best == 0 or admissible[best - 1]:
        return design_at(task, float(k2[best]), k5)
    roots = []
    for which, margin in enumerate(margins):
        if margin[best - 1] < 0.0:
            def gap(x: float, which: int = which) -> float:
                return float(_violations(task, proportions(task.stroke, x, k5))[which])
            roots.append(brentq(gap, k2[best - 1], k2[best], xtol=1e-12))
    return design_at(task, max(roots), k5)
