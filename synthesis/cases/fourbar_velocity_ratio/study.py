"""One run of the case: solve a request by the chosen methods and check every design."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from synthesis.cases.fourbar_velocity_ratio.check import CheckResult, check_design
from synthesis.cases.fourbar_velocity_ratio.conditions import Design, Request
from synthesis.cases.fourbar_velocity_ratio.modern_solver import ModernResult, solve_modern
from synthesis.cases.fourbar_velocity_ratio.paper_solver import PaperResult, solve_paper

__all__ = ["METHODS", "Study", "paper_check_tolerance", "run_study"]

METHODS = ("modern", "paper", "both")


def paper_check_tolerance(tol: float, delta: float) -> float:
    """Relative tolerance of the check for a design of the paper's scheme run with ``tol``
    on F1–F3: its conditions hold only to about that accuracy, but the check must still
    resolve the band, so the tolerance never exceeds δ/10."""
    return min(100.0 * tol, 0.1 * delta)


@dataclass
class Study:
    """The request, the solvers' results and the checks of their designs."""

    request: Request
    method: str
    modern: ModernResult | None = None
    paper: PaperResult | None = None
    modern_checks: list[CheckResult] = field(default_factory=list)
    paper_check: CheckResult | None = None
    paper_match: int | None = None
    paper_distance: float = math.nan

    @property
    def best(self) -> Design | None:
        """The design to show: the modern solver's best one, else the paper's good root."""
        if self.modern is not None and self.modern.design is not None:
            return self.modern.design
        if self.paper is not None and self.paper.ok:
            return self.paper.design
        return None

    @property
    def best_check(self) -> CheckResult | None:
        """The check of :attr:`best`."""
        if self.modern is not None and self.modern.design is not None:
            return self.modern_checks[0]
        return self.paper_check if self.best is not None else None

    @property
    def passed(self) -> bool:
        """A design was found and the independent check confirms it."""
        check = self.best_check
        return check is not None and check.passed


def _distance(a: Design, b: Design) -> float:
    return float(max(abs(a.c - b.c), abs(a.r - b.r),
                     abs(math.remainder(a.theta2 - b.theta2, 2 * math.pi))))


def run_study(request: Request, method: str = "modern", *, paper_tol: float = 1e-6) -> Study:
    """Solve the request by ``method`` (``modern``, ``paper`` or ``both``) and check the designs.

    Raises
    ------
    NoSolution
        When the request is impossible on its face.
    """
    request.check()
    study = Study(request, method)
    if method in ("modern", "both"):
        study.modern = solve_modern(request)
        study.modern_checks = [check_design(d) for d in study.modern.designs]
    if method in ("paper", "both"):
        study.paper = solve_paper(request, tol=paper_tol)
        if study.paper.design is not None:
            tolerance = paper_check_tolerance(paper_tol, study.paper.design.delta)
            study.paper_check = check_design(study.paper.design, value_tol=tolerance,
                                             angle_tol=tolerance)
    if study.paper is not None and study.paper.design is not None and study.modern is not None:
        pool = study.modern.designs
        if pool:
            gaps = np.array([_distance(study.paper.design, d) for d in pool])
            study.paper_match = int(np.argmin(gaps))
            study.paper_distance = float(gaps[study.paper_match])
    return study
