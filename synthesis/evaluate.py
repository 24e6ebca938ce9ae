"""Block B2: analysis of a batch of candidate designs and their criteria.

:class:`Evaluator` turns a batch of designs ``X`` (shape ``(D, q)``, the varied parameters
of :class:`~synthesis.problem.Problem` in table units) into the kinematic model with every
varied parameter replaced by a ``(D, 1)`` column, analyses all designs at all positions in
one call of the public kinematics (analysis grid + control angles, groups in layering
order), and computes the criteria of block B3 (:mod:`synthesis.criteria`).

Outputs (``method.md`` §4.5):

* class 1, ψ: the angle of the output link, unwrapped along the grid and measured from its
  value at φ = 0 (counter-clockwise positive); at a control angle φ_K the value is the grid
  value at the nearest grid angle plus the wrapped difference of the two raw angles;
* class 1 with ``output: ratio``, n: the velocity ratio n(φ) = dψ/dφ of the output link, its
  first analog, computed exactly by forward differentiation of the group solvers (jets) at
  the control angles only (see :meth:`Evaluator.ratio`);
* class 2, S: the slider coordinate of the output link on its guide, measured from its value
  at φ = 0;
* class 5, the guided segment AB (:mod:`synthesis.guidance`): A = Ж as for classes 3–4,
  θ = the angle of the output link's local frame plus the segment's angle γ on the link;
  without timing, each control pose is compared with the nearest pose of the cycle, found on
  the grid and refined by Newton steps in φ as for class 3 with
  ``f = |A(φ) − A_K|² + |B(φ) − B_K|²``;
* classes 3–4, Ж: a tracing point of the output link (its attachment point N/M, or a named
  tracing point).  For class 3 the nearest point of the path is found on the grid polygon
  and then refined by Newton steps in φ on the true path, using the exact first and second
  derivatives of the position w.r.t. φ (``analogs``):
  ``φ ← φ − f'/f''``, ``f = |Ж(φ) − P_K|²``, ``f' = 2·Re(conj(Ж − P)·Ж')``,
  ``f'' = 2·(|Ж'|² + Re(conj(Ж − P)·Ж''))``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

import assur
import assur.kinematics.analysis
from assur import KinematicModel, Motion, TableError
from assur.errors import Issue
from assur.kinematics.analysis import analyse
from assur.text import Message
from assur.typing import ComplexArray, FloatArray, Value
from synthesis import criteria as C
from synthesis import guidance as G
from synthesis.force_conditions import force_penalties
from synthesis.problem import SEGMENT_ANGLE, ControlPoints, Problem, output_slider

__all__ = ["Analysis", "Evaluator"]


_NEWTON_STEPS = 2


@dataclass(frozen=True)
class Analysis:
    """The analysed designs of one batch (for reports and plots).

    Attributes
    ----------
    motion : Motion
        Kinematics at the grid positions followed by the control angles.
    grid : ndarray, shape (N,)
        Crank rotation of the analysis grid (radians from the start position).
    output_grid : ndarray, shape (D, N)
        The controlled output over the grid (ψ rad, n, S mm, or Ж complex); the ratio n only
        when analysed with ``curve=True`` (NaN otherwise).
    output_control : ndarray, shape (D, K)
        The output at the control points (for class 3: the nearest path points).
    phi_control : ndarray, shape (D, K)
        Crank rotation of each control value (class 3: of the nearest path point).
    criteria : Criteria
    pressure : dict
        Group label → largest pressure angle over the grid, shape (D, 1), radians (groups
        with an allowable pressure angle).
    rotations : dict
        Group label → swing of each checked joint, shape (D, J), radians.
    workspace : dict
        Group label → largest excursion of each joint outside its box, shape (D, J), mm.
    strokes : dict
        Group label → largest excursion of the slider coordinate of each limited prismatic
        pair outside its range, shape (D, J), mm.
    """

    motion: Motion
    grid: FloatArray
    output_grid: npt.NDArray[Any]
    output_control: npt.NDArray[Any]
    phi_control: FloatArray
    criteria: C.Criteria
    pressure: dict[str, FloatArray]
    rotations: dict[str, FloatArray]
    workspace: dict[str, FloatArray]
    strokes: dict[str, FloatArray]


class Evaluator:
    """The criteria of batches of designs of one problem.

    Parameters
    ----------
    problem : Problem
    grid : int, optional
        Positions of the analysis grid (default: the problem's ``grid``).

    Raises
    ------
    TableError
        When the problem gives an allowable pressure angle to a group that has none (the
        check needs an analysis, so it is made here rather than when the table is read).
    Examples
    --------
    ``Evaluator(problem)(X)`` gives the :class:`~synthesis.criteria.Criteria` of the rows of
    X; ``Evaluator(problem).analyse(X)`` gives everything computed on the way.
    """

    def __init__(self, problem: Problem, *, grid: int | None = None) -> None:
        self.problem = problem
        n = grid or problem.grid
        self.grid = 2.0 * np.pi * np.arange(n) / n
        self.control_phi = problem.control.phi if problem.control.timed else np.zeros(0)
        self.positions = np.concatenate([self.grid, self.control_phi])
        model = problem.model
        self.output_link = problem.output.link
        self.label, self.side = model.links[self.output_link]
        self._slider_pair = (output_slider(model, self.output_link) if problem.task_class == 2
                             else None)
        self.lower = problem.lower
        self.upper = problem.upper
        self._check_pressure_angles()

    def prepare(self, trials: int) -> bool:
        """Load the compiled corrector of the higher groups before ``trials`` designs are
        evaluated in this process, where the mechanism has a triad or a class IV group and
        the trials' positions (the grid and the control angles of each) reach
        ``KERNEL_POSITIONS``, as many as one analysis that would load it itself. Loaded
        first (:func:`assur.kinematics.higher.compiled.load`, about 0.4 s once), it
        corrects the batches of the search too, each of them too small to pay for the
        loading alone. Returns whether it loaded.
        """
        if not any(group.kind in ("III", "IV") for group in self.problem.model.groups):
            return False
        from assur.kinematics.higher import compiled, continuation  # as the analysis would

        if trials * self.positions.size < continuation.KERNEL_POSITIONS:
            return False
        compiled.load()
        return True

    def _check_pressure_angles(self) -> None:
        """Pressure angles exist only for L1/L2 groups with a two-hinge rod
        (``method.md`` §2.7); which groups have one is known from an analysis."""
        wanted = self.problem.pressure_angles
        if not wanted:
            return
        motion = analyse(self.problem.model, np.zeros(1))
        computed = {item.label for item in assur.pressure_angles(motion)}
        issues = [Issue(f"allowable ({label}) 'pressure_angle'",
                        Message("problem.pressure_none", {"group": label}))
                  for label in wanted if label not in computed]
        if issues:
            raise TableError(self.problem.source, issues)

    # ------------------------------------------------------------------ model and motion
    def model(self, x: npt.ArrayLike) -> KinematicModel:
        """The kinematic model with the varied parameters of the designs X, shape (D, q)."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        return self.problem.model.with_params(
            {name: x[:, k:k + 1] for k, name in enumerate(self.problem.names)
             if name != SEGMENT_ANGLE})

    def segment_angle(self, x: npt.ArrayLike) -> FloatArray:
        """γ of the designs X (class 5), shape (D, 1), radians: the varied column
        :data:`~synthesis.problem.SEGMENT_ANGLE` (degrees) or the fixed angle."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        if SEGMENT_ANGLE in self.problem.names:
            k = self.problem.names.index(SEGMENT_ANGLE)
            angle: FloatArray = np.radians(x[:, k:k + 1])
            return angle
        return np.full((x.shape[0], 1), self.problem.output.angle)

    def _segment(self, motion: Motion, model: KinematicModel, gamma: FloatArray
                 ) -> list[Value]:
        """The end points A, B of the guided segment over the analysed positions."""
        length = self.problem.output.length
        assert length is not None  # (class 5 reads it)
        a = self._point(motion, model)
        theta = motion.link_angle(self.output_link) + gamma
        return [a, a + length * assur.kinematics.jets.expi(theta)]

    def _point(self, motion: Motion, model: KinematicModel) -> Value:
        """The tracing point Ж of the output link over the analysed positions."""
        name = self.problem.output.point
        if name in motion.tracing:
            return motion.tracing[name]
        origin, angle = motion.frames[self.output_link]
        length = model.value(f"{self.label}.l_{name}")
        beta = model.value(f"{self.label}.beta_{name}")
        point: Value = origin + length * assur.kinematics.jets.expi(angle + beta) if isinstance(
            angle, assur.Jet) else origin + length * np.exp(1j * (angle + beta))
        return point

    # ------------------------------------------------------------------------ criteria
    def __call__(self, x: npt.ArrayLike) -> C.Criteria:
        """Criteria of the designs X, shape (D, q)."""
        return self.analyse(x, curve=False).criteria

    def ratio(self, model: KinematicModel, phi: FloatArray) -> FloatArray:
        """Velocity ratio of the output link at crank rotations φ, shape (D, len(φ)).

        Parameters
        ----------
        model : KinematicModel
            The model of the designs (:meth:`model`).
        phi : ndarray, shape (M,)
            Crank rotations from the start position (radians).

        Returns
        -------
        ndarray, shape (D, M)
            n(φ); NaN where the chain does not assemble.

        Notes
        -----
        The ratio is the first analog of the output angle ψ with respect to the crank
        rotation φ (the input coordinate of the analysis, positive in the crank's direction
        s; ψ counter-clockwise positive)::

            n(φ) = dψ/dφ

        It is the ``d1`` part of the link angle when the analysis carries jets
        (``assur.kinematics.analysis.analyse(model, φ, analogs=True)``): every group solver is differentiated
        in forward mode, so n is exact to rounding, not a finite difference.  For a
        four-bar driven counter-clockwise (s = +1; crank l₁ at angle φ₁, coupler angle φ_i,
        rocker l_j at angle φ_j, each frame's axis pointing to the joint C) this is the
        classical ``n = l₁·sin(φ₁ − φ_i) / (l_j·sin(φ_j − φ_i))``.  Analogs cost about
        four times the positions alone, so the criteria evaluate them at the control
        angles only.
        """
        motion = analyse(model, phi, analogs=True)
        shape = np.broadcast_shapes(model.design_shape, np.shape(phi))
        angle = motion.link_angle(self.output_link)
        assert isinstance(angle, assur.Jet)  # analogs=True carries jets
        return np.atleast_2d(np.broadcast_to(angle.d1, shape))

    def analyse(self, x: npt.ArrayLike, *, curve: bool = True) -> Analysis:
        """Analyse the designs X over the grid and the control angles.

        Parameters
        ----------
        x : array_like, shape (D, q)
            Designs (varied parameters in table units).
        curve : bool
            Also the velocity ratio over the grid (class 1 with ``output: ratio``; the
            criteria need it only at the control angles, so the search leaves it out).
        """
        x = np.atleast_2d(np.asarray(x, dtype=float))
        d = x.shape[0]
        model = self.model(x)
        motion = analyse(model, self.positions)
        n = self.grid.size
        p1 = self._existence(motion, model, d)
        cls = self.problem.task_class
        control = self.problem.control
        out: npt.NDArray[Any]
        out_grid: npt.NDArray[Any]
        with np.errstate(invalid="ignore"):
            if cls == 1:
                if self.problem.output.ratio:
                    out = self.ratio(model, self.control_phi)
                    out_grid = (self.ratio(model, self.grid) if curve
                                else np.full((d, n), np.nan))
                else:
                    raw = _full(motion.link_angle(self.output_link), d, self.positions.size)
                    grid = assur.kinematics.analysis.unwrap(raw[:, :n])
                    out_grid = grid - grid[:, :1]
                    nearest = np.rint(self.control_phi / (2 * np.pi) * n).astype(int) % n
                    wrap = np.angle(np.exp(1j * (raw[:, n:] - raw[:, nearest])))
                    out = out_grid[:, nearest] + wrap
                phi_c = np.broadcast_to(self.control_phi, out.shape)
                dev, res = _scalar_deviations(out, control)
            elif cls == 2:
                assert self._slider_pair is not None
                s = _full(assur.kinematics.analysis.values(motion.sliders[self._slider_pair].s), d,
                          self.positions.size)
                out_grid = s[:, :n] - s[:, :1]
                out = s[:, n:] - s[:, :1]
                phi_c = np.broadcast_to(self.control_phi, out.shape)
                dev, res = _scalar_deviations(out, control)
            elif cls == 5:
                gamma = self.segment_angle(x)
                length = float(self.problem.output.length or 0.0)
                a, b = (_full(assur.kinematics.analysis.values(end), d, self.positions.size)
                        for end in self._segment(motion, model, gamma))
                out_grid = a[:, :n]
                assert control.angle is not None  # (class 5 reads it)
                if control.timed:
                    out, ends_b = a[:, n:], b[:, n:]
                    phi_c = np.broadcast_to(self.control_phi, out.shape)
                else:
                    targets = G.segment_ends(control.point, control.angle, length)
                    start = G.nearest_pose(a[:, :n], b[:, :n], *targets) * (2 * np.pi / n)
                    phi_c, (out, ends_b) = self._nearest(
                        model, start.astype(float), list(targets),
                        lambda m: self._segment(m, model, gamma), 2 * np.pi / n)
                theta = np.angle(ends_b - out)
                dev = G.segment_deviations(out, theta, control.point, control.angle, length,
                                           control.weight)
                res = G.segment_residuals(out, theta, control.point, control.angle, length,
                                          control.weight)
            else:
                path = _full(assur.kinematics.analysis.values(self._point(motion, model)), d, self.positions.size)
                out_grid = path[:, :n]
                if cls == 4:
                    out = path[:, n:]
                    phi_c = np.broadcast_to(self.control_phi, out.shape)
                else:
                    index, _ = C.nearest_on_path(out_grid, control.point)
                    phi_c, (out,) = self._nearest(model, index * (2 * np.pi / n),
                                                  [control.point],
                                                  lambda m: [self._point(m, model)])
                dev = C.timed_path_deviations(out, control.point, control.weight)
                gap = control.weight * (out - control.point)
                res = np.concatenate([gap.real, gap.imag], axis=1)
            pressure, rotation = self._desirable(motion, d, n)
            signed = self._workspace(motion, d, n)
            stroke_signed = self._strokes(motion, d, n)
        workspace = {label: np.maximum(v, 0.0) for label, v in signed.items()}
        strokes = {label: np.maximum(v, 0.0) for label, v in stroke_signed.items()}
        feasible = p1 == 0
        q = np.where(feasible, C.criterion(dev, control.weight, self.problem.criterion), np.nan)
        bounds = C.bounds_penalty(x, self.lower, self.upper)
        alpha_allowed = np.array([self.problem.pressure_angles[k] for k in pressure])
        p2_alpha = C.pressure_penalty(_stack(pressure, d), alpha_allowed)
        limits = np.array([lim for label in rotation
                           for lim in self.problem.rotations[label].values()])
        p2_rot = C.rotation_penalty(_stack(rotation, d), limits)
        scales = []
        for label, excess in workspace.items():
            x_min, x_max, y_min, y_max = self.problem.workspace[label]
            scales += [math.hypot(x_max - x_min, y_max - y_min)] * excess.shape[1]
        ranges = np.array([hi - lo for label in strokes
                           for lo, hi in self.problem.strokes[label].values()])
        p2_work = (C.workspace_penalty(_stack(workspace, d), np.array(scales))
                   + C.workspace_penalty(_stack(strokes, d), ranges))
        p2_force = force_penalties(self.problem.forces, self.model, x, feasible, self.grid)
        p2 = np.where(feasible, C.desirable_penalty(bounds, p2_alpha, p2_rot, p2_work)
                      + p2_force, np.nan)
        margins = np.concatenate([_stack(pressure, d) / alpha_allowed - 1.0,
                                  _stack(rotation, d) / limits - 1.0,
                                  _stack(signed, d) / np.array(scales),
                                  _stack(stroke_signed, d) / ranges], axis=1)
        dev, res, margins = (np.where(feasible[:, None], a, np.nan) for a in (dev, res, margins))
        return Analysis(motion, self.grid, out_grid, out, np.asarray(phi_c),
                        C.Criteria(p1, p2, q, dev, res, margins), pressure, rotation, workspace,
                        strokes)

    def _nearest(self, model: KinematicModel, phi: FloatArray, targets: list[ComplexArray],
                 points: Callable[[Motion], list[Value]], spacing: float = 0.0
                 ) -> tuple[FloatArray, list[npt.NDArray[Any]]]:
        """Newton refinement in φ of the positions nearest to required points.

        Class 3: one point, Ж, and its required points P_K; class 5: the two ends of the
        segment and their required places.  With P_j(φ) the points and T_j their targets::

            f = Σ_j |P_j(φ) − T_j|²,   f' = 2·Σ_j Re(conj(P_j − T_j)·P_j'),
            f'' = 2·Σ_j (|P_j'|² + Re(conj(P_j − T_j)·P_j''))

        The start (from the grid polygon, or a grid position for class 5) is within a grid
        step of the minimum; each step is clipped to ``max(0.05, spacing/2)`` rad, and the
        last points are the second-order Taylor step ``P + P'·Δ + P''·Δ²/2`` from the last
        analysed position.
        """
        limit = max(0.05, 0.5 * spacing)
        steps = _NEWTON_STEPS + (spacing > 0)
        found: list[npt.NDArray[Any]] = []
        for _ in range(steps):
            jets = points(analyse(model, phi, analogs=True))
            f1 = np.zeros(np.shape(phi))
            f2 = np.zeros(np.shape(phi))
            for jet, target in zip(jets, targets):
                assert isinstance(jet, assur.Jet), "a motion with analogs"
                gap = jet.v - target
                f1 = f1 + 2 * (np.conj(gap) * jet.d1).real
                f2 = f2 + 2 * (np.abs(jet.d1) ** 2 + (np.conj(gap) * jet.d2).real)
            step = np.where(f2 > 0, -f1 / np.where(f2 > 0, f2, 1.0), 0.0)
            step = np.clip(np.nan_to_num(step), -limit, limit)
            phi = phi + step
            found = [np.asarray(jet.v + jet.d1 * step + 0.5 * jet.d2 * step ** 2)
                     for jet in jets if isinstance(jet, assur.Jet)]
        return phi, found

    def _existence(self, motion: Motion, model: KinematicModel, d: int) -> FloatArray:
        """P1 over all analysed positions (``criteria.existence_penalty``)."""
        shape = (d, self.positions.size)
        first = np.zeros(shape, dtype=int)
        violation = np.zeros(shape)
        for group in model.groups:
            sol = motion.solutions[group.label]
            exists = np.broadcast_to(sol.exists, shape)
            new = (first == 0) & ~exists
            if not new.any():
                continue
            delta = np.asarray(model.params.get(group.column("delta"), 0.0), dtype=float)
            margin = np.broadcast_to(np.asarray(sol.margin, dtype=float), shape)
            v = np.broadcast_to(delta, (d, 1)) - margin if delta.ndim else delta - margin
            first = np.where(new, group.seq, first)
            violation = np.where(new, v, violation)
        return C.existence_penalty(first, violation, len(model.groups))

    def _desirable(self, motion: Motion, d: int, n: int
                   ) -> tuple[dict[str, FloatArray], dict[str, FloatArray]]:
        """Largest pressure angles (D, 1) and joint rotation ranges (D, J) over the grid."""
        pressure: dict[str, FloatArray] = {}
        rotation: dict[str, FloatArray] = {}
        size = self.positions.size
        if self.problem.pressure_angles:
            for item in assur.pressure_angles(motion):
                if item.label in self.problem.pressure_angles:
                    alpha = np.nan_to_num(_full(item.alpha, d, size)[:, :n], nan=0.0)
                    pressure[item.label] = np.max(alpha, axis=1)[:, None]
        if self.problem.rotations:
            swings = {}
            for joint in assur.joint_rotations(motion):
                theta = np.nan_to_num(_full(joint.theta, d, size)[:, :n])
                swings[joint.pair] = np.ptp(theta, axis=1)
            for label, limits in self.problem.rotations.items():
                group = motion.model.group(label)
                rotation[label] = np.stack([swings[group.pairs[role]] for role in limits],
                                           axis=1)
        return pressure, rotation

    def _strokes(self, motion: Motion, d: int, n: int) -> dict[str, FloatArray]:
        """Signed largest excursion of the slider coordinate s of each limited prismatic
        pair outside its range [s_min, s_max] over the grid, (D, J) mm: positive outside,
        minus the smallest clearance to an end where s stays inside."""
        out: dict[str, FloatArray] = {}
        size = self.positions.size
        for label, limits in self.problem.strokes.items():
            group = motion.model.group(label)
            columns = []
            for role, (low, high) in limits.items():
                s = _full(assur.kinematics.analysis.values(
                    motion.sliders[group.pairs[role]].s), d, size)[:, :n]
                excess = np.fmax.reduce(np.maximum(low - s, s - high), axis=1)
                columns.append(np.nan_to_num(excess))
            out[label] = np.stack(columns, axis=1)
        return out

    def _workspace(self, motion: Motion, d: int, n: int) -> dict[str, FloatArray]:
        """Signed largest excursion of each group's revolute joints outside its box, (D, J)
        mm: positive outside (as :func:`_outside`), minus the smallest clearance to a side
        where the joint stays inside."""
        out: dict[str, FloatArray] = {}
        size = self.positions.size
        for label, box in self.problem.workspace.items():
            group = motion.model.group(label)
            columns = []
            for role, pid in group.pairs.items():
                if role.startswith("P") or pid not in motion.joints:
                    continue
                z = _full(assur.kinematics.analysis.values(motion.joints[pid]), d, size)[:, :n]
                columns.append(_outside(z, box))
            out[label] = np.stack(columns, axis=1)
        return out


def _outside(z: npt.NDArray[Any], box: tuple[float, float, float, float]) -> FloatArray:
    """Signed largest excursion of points outside an axis-aligned box over the positions
    (axis 1), per design: the excursion summed over the coordinates where a point leaves
    the box, else minus the smallest clearance to a side (positions not analysed are skipped).
    """
    x_min, x_max, y_min, y_max = box
    ex = np.maximum(x_min - z.real, z.real - x_max)
    ey = np.maximum(y_min - z.imag, z.imag - y_max)
    out = np.fmax.reduce(np.maximum(ex, 0.0) + np.maximum(ey, 0.0), axis=1)
    inside = np.fmax.reduce(np.maximum(ex, ey), axis=1)
    return np.nan_to_num(np.where(out > 0, out, inside))


def _scalar_deviations(out: FloatArray, control: ControlPoints
                       ) -> tuple[FloatArray, FloatArray]:
    """Deviations and residuals of a scalar output (classes 1, 2): from the required values,
    or from the tolerance zone when the rows give one."""
    if control.lower is not None and control.upper is not None:  # a zone
        return (C.zone_deviations(out, control.lower, control.upper, control.weight),
                C.zone_residuals(out, control.lower, control.upper, control.weight))
    dev = C.value_deviations(out, control.value, control.weight)
    return dev, dev


def _full(value: Any, d: int, n: int) -> npt.NDArray[Any]:
    """A quantity broadcast to (D, N)."""
    return np.broadcast_to(np.asarray(value), (d, n))


def _stack(parts: dict[str, FloatArray], d: int) -> FloatArray:
    if not parts:
        return np.zeros((d, 0))
    return np.concatenate([np.broadcast_to(v, (d, v.shape[1])) for v in parts.values()], axis=1)
