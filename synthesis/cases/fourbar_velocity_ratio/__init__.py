"""Built-in case: a crank-rocker four-bar synthesised for a prescribed velocity ratio over a
zone of crank angles (the paper's conditions (7)–(20), two solvers and an independent check).

The public entry points are :func:`solve_modern`, :func:`solve_paper` and :func:`check_design`.
"""

from __future__ import annotations

from assur.text import Message
from synthesis.cases.fourbar_velocity_ratio.check import CheckResult, check_design
from synthesis.cases.fourbar_velocity_ratio.conditions import Design, NoSolution, Request
from synthesis.cases.fourbar_velocity_ratio.modern_solver import (
    ModernResult,
    attainable_zone,
    solve_modern,
)
from synthesis.cases.fourbar_velocity_ratio.paper_solver import PaperResult, solve_paper

__all__ = [
    "CheckResult",
    "Design",
    "Message",
    "ModernResult",
    "NoSolution",
    "PaperResult",
    "Request",
    "attainable_zone",
    "check_design",
    "solve_modern",
    "solve_paper",
]
