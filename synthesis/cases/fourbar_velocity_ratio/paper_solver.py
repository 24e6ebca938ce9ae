"""The paper's solver: three nested loops of the method of false position ("double false").

Steps a–p of the source, for the paper's form (e, n*, δ, ψ′ given):

* a. take r; the starting value is the bound r = e/|n*|;
* b. the coupler admits ``1 + e − r < c < 1 − e + r``; start at ``c = 1 − e + r − ε``;
* c–g. inner loop: for the current (c, r) step θ2 from its starting value until F1 (18), with
  φ2 from (10), changes sign, then apply false position until ``|F1| < tol``;
* h–j. middle loop: step c down (repeating c–g at each c) until F2 (19) changes sign, then false
  position on c until ``|F2| < tol``;
* k–o. outer loop: with θ1 from (14) and φ1 from (16), step r up (repeating b–j at each r)
  until F3 (20) changes sign, then false position on r until ``|F3| < tol``;
* p. the design is read off; ψ″ follows from (13).

The source leaves the start and the step of θ2 and the steps of c and r open; they are the
keyword arguments below (θ2 starts at a right angle of the crank to the frame, 90° on the
forward stroke and 270° on the return stroke, and is stepped alternately on both sides; each
later inner loop starts from the previous θ2). The scheme finds one root and cannot tell a
peak from a trough; the returned design is therefore classified like the modern solver's
roots.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from assur.text import Message
from synthesis.cases.fourbar_velocity_ratio.conditions import (
    Design,
    Request,
    design_defect,
    design_from_unknowns,
    paper_functions,
)
from synthesis.cases.fourbar_velocity_ratio.kinematics import coupler_bounds

__all__ = ["PaperResult", "solve_paper"]


class _NoRoot(Exception):
    """A loop of the scheme found no sign change or did not converge (``message`` says which)."""

    def __init__(self, message: Message) -> None:
        super().__init__(str(message))
        self.message = message


@dataclass
class PaperResult:
    """Outcome of :func:`solve_paper`.

    Attributes
    ----------
    design : Design or None
        The root reached by the scheme.
    defect : Message or None
        Why that root is not the design asked for (see
        :func:`~.conditions.design_defect`); None for a good design.
    reason : Message or None
        Why the scheme stopped without a root.
    evaluations : int
        Evaluations of the functions (18)–(20).
    iterations : dict
        False-position iterations of the inner (θ2), middle (c) and outer (r) loops.
    seconds : float
        Wall time.
    """

    request: Request
    design: Design | None = None
    defect: Message | None = None
    reason: Message | None = None
    evaluations: int = 0
    iterations: dict[str, int] = field(default_factory=lambda: {"theta2": 0, "c": 0, "r": 0})
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        """Whether the scheme returned the design asked for."""
        return self.design is not None and self.defect is None


def _false_position(function: Callable[[float], float], a: float, fa: float, b: float,
                    fb: float, tol: float, max_iter: int) -> tuple[float, int]:
    """Regula falsi on a bracket ``[a, b]`` until ``|f| < tol``; returns (root, iterations)."""
    for iteration in range(1, max_iter + 1):
        x = b - fb * (b - a) / (fb - fa)
        fx = function(x)
        if not math.isfinite(fx):
            raise _NoRoot(Message("case.fourbar.undefined_in_bracket"))
        if abs(fx) < tol:
            return x, iteration
        if math.copysign(1.0, fx) == math.copysign(1.0, fa):
            a, fa = x, fx
        else:
            b, fb = x, fx
    raise _NoRoot(Message("case.fourbar.no_convergence", {"tol": tol, "count": max_iter}))


def _scan(function: Callable[[float], float], values: list[float]
          ) -> tuple[float, float, float, float]:
    """Step through ``values`` until the function changes sign between two defined values."""
    previous: tuple[float, float] | None = None
    for x in values:
        fx = function(x)
        if not math.isfinite(fx):
            continue
        if previous is not None and math.copysign(1.0, fx) != math.copysign(1.0, previous[1]):
            return previous[0], previous[1], x, fx
        previous = (x, fx)
    raise _NoRoot(Message("case.fourbar.no_sign_change"))


class _Scheme:
    """State of the nested loops for one request."""

    def __init__(self, request: Request, tol: float, epsilon: float, theta_start: float | None,
                 theta_step: float, c_steps: int, r_step: float, r_steps: int,
                 max_iter: int) -> None:
        if request.e is None or request.delta is None:
            raise ValueError("the paper's method needs e and δ given (the 'paper' form)")
        self.request = request
        self.e, self.delta = request.e, request.delta
        self.tol, self.epsilon, self.max_iter = tol, epsilon, max_iter
        self.theta_step, self.c_steps = theta_step, c_steps
        self.r_step, self.r_steps = r_step, r_steps
        if theta_start is None:
            theta_start = math.pi / 2 if request.n_star > 0 else 3 * math.pi / 2
        self.theta2 = theta_start
        self.evaluations = 0
        self.iterations = {"theta2": 0, "c": 0, "r": 0}

    def functions(self, c: float, r: float, theta2: float) -> tuple[float, float, float]:
        self.evaluations += 1
        q = self.request
        with np.errstate(invalid="ignore"):
            f1, f2, f3 = (float(v) for v in paper_functions(self.e, q.n_star, self.delta,
                                                            q.psi1, c, r, theta2))
        return f1, f2, f3

    def inner(self, c: float, r: float) -> float:
        """Steps c–g: θ2 with F1 = 0 for the given c and r."""
        def f1(theta: float) -> float:
            return self.functions(c, r, theta)[0]

        start = self.theta2
        if abs(f1(start)) < self.tol:
            return start
        turns = int(math.pi / self.theta_step)
        for side in (1.0, -1.0):
            values = [start + side * k * self.theta_step for k in range(turns + 1)]
            try:
                a, fa, b, fb = _scan(f1, values)
            except _NoRoot:
                continue
            theta, count = _false_position(f1, a, fa, b, fb, self.tol, self.max_iter)
            self.iterations["theta2"] += count
            self.theta2 = theta
            return theta
        raise _NoRoot(Message("case.fourbar.f1_no_sign_change"))

    def middle(self, r: float) -> tuple[float, float]:
        """Steps b–j: c (and θ2) with F1 = F2 = 0 for the given r."""
        lo, hi = (float(v) for v in coupler_bounds(self.e, r))
        if not lo < hi:
            raise _NoRoot(Message("case.fourbar.empty_coupler_interval"))

        def f2(c: float) -> float:
            try:
                theta = self.inner(c, r)
            except _NoRoot:
                return math.nan
            return self.functions(c, r, theta)[1]

        start = hi - self.epsilon
        step = (start - lo) / self.c_steps
        a, fa, b, fb = _scan(f2, [start - k * step for k in range(self.c_steps)])
        c, count = _false_position(f2, a, fa, b, fb, self.tol, self.max_iter)
        self.iterations["c"] += count
        return c, self.inner(c, r)

    def outer(self) -> tuple[float, float, float]:
        """Steps a and k–o: r (and c, θ2) with F1 = F2 = F3 = 0."""
        def f3(r: float) -> float:
            try:
                c, theta = self.middle(r)
            except _NoRoot:
                return math.nan
            return self.functions(c, r, theta)[2]

        start = self.e / abs(self.request.n_star)
        a, fa, b, fb = _scan(f3, [start * (1.0 + k * self.r_step) for k in range(self.r_steps)])
        r, count = _false_position(f3, a, fa, b, fb, self.tol, self.max_iter)
        self.iterations["r"] += count
        c, theta = self.middle(r)
        return c, r, theta


def solve_paper(request: Request, *, tol: float = 1e-6, epsilon: float = 1e-3,
                theta_start: float | None = None, theta_step: float = math.radians(5.0),
                c_steps: int = 20,
                r_step: float = 0.05, r_steps: int = 60, max_iter: int = 200) -> PaperResult:
    """Run the paper's nested false-position scheme (steps a–p).

    Parameters
    ----------
    request : Request
        A request in the paper's form (e, n*, δ, ψ′ given).
    tol : float
        The error allowed on F1, F2, F3 (steps g, j, o).
    epsilon : float
        The ε of step b.
    theta_start : float, optional
        Starting value of θ2 (step c), radians; by default 90° on the forward stroke and 270°
        on the return stroke.
    theta_step : float
        Step of θ2 while looking for a sign change of F1 (radians).
    c_steps : int
        Number of steps over the coupler interval while looking for a sign change of F2.
    r_step, r_steps : float, int
        Relative step of r from e/|n*| and the number of steps while looking for a sign
        change of F3.
    max_iter : int
        Iteration limit of each false-position run.

    Returns
    -------
    PaperResult
        The root reached, whether it is the design asked for, or why the scheme stopped.

    Raises
    ------
    NoSolution
        When the request is impossible on its face.
    """
    request.check()
    result = PaperResult(request)
    if request.form != "paper":
        result.reason = Message("case.fourbar.paper_form_only")
        return result
    clock = time.perf_counter()
    scheme = _Scheme(request, tol, epsilon, theta_start, theta_step, c_steps, r_step, r_steps,
                     max_iter)
    try:
        c, r, theta2 = scheme.outer()
    except _NoRoot as exc:
        result.reason = Message("case.fourbar.stopped", {"why": exc.message})
    else:
        design = design_from_unknowns(request, [c, r, theta2 % (2 * math.pi)])
        result.design = design
        result.defect = (design_defect(design, accuracy=10.0 * tol) if math.isfinite(design.psi2)
                         else Message("case.fourbar.never_back"))
    result.evaluations = scheme.evaluations
    result.iterations = scheme.iterations
    result.seconds = time.perf_counter() - clock
    return result
