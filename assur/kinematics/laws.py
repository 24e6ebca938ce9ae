"""The laws of the inputs over the cycle: how each input's coordinate follows one parameter t.

A mechanism with several inputs (W > 1), or one input given a law, is analysed over one
common cycle parameter t ∈ [0, 2π) (``docs/kinematics.md`` §1.3). Each input's coordinate
is a law of t (:class:`InputLaw`):

- a crank turns ``phase + ratio·t`` from its sketched position (radians);
- a linear input (a slider on a frame guide: its displacement from the sketched position;
  an actuator: its length, mm) either runs its stroke harmonically,
  ``s_min + (s_max − s_min)·(1 − cos(ratio·t + phase))/2``, or follows a table over the
  cycle, interpolated by a periodic cubic spline.

The stroke limits ``s_min``, ``s_max`` are parameters of the group that holds the input
(mm), so a batch of designs may vary them; where an input's coordinate leaves them the
group does not assemble (:attr:`~assur.kinematics.reasons.Reason.STROKE_END`).

Examples
--------
>>> import numpy as np
>>> law = InputLaw("L0(1)", linear=False, phase=0.5, ratio=2)
>>> float(law.coordinate(np.float64(1.0), {}.get))
2.5
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.jets import Jet
from assur.typing import Value

__all__ = ["STROKE", "InputLaw", "stroke_margin"]

#: The parameter columns of a linear input's stroke limits, mm.
STROKE = ("s_min", "s_max")


@dataclass(frozen=True)
class InputLaw:
    """How one input's coordinate follows the cycle parameter t (radians).

    Attributes
    ----------
    group : str
        Label of the group holding the input (``"L0(1)"``, an actuator's dyad).
    linear : bool
        A slider or an actuator (mm) rather than a crank (radians).
    phase : float
        Radians: a crank's rotation at t = 0; the phase of a linear input's harmonic law.
    ratio : int
        Turns (double strokes) per cycle.
    table : tuple of (float, float)
        A linear input's law as rows (t in radians, coordinate in mm); empty for the
        harmonic law.
    limited : bool
        Whether the group's ``s_min``, ``s_max`` limit the coordinate.
    held : bool
        The input held at ``phase`` (its sketched coordinate), whatever t.
    moving : bool or None
        For analogs with respect to one input's coordinate (None: with respect to t): the
        coordinate's value follows t, its derivatives are 1, 0 (True, the input the
        analogs are taken for) or 0, 0 (False, every other input).
    """

    group: str
    linear: bool
    phase: float = 0.0
    ratio: int = 1
    table: tuple[tuple[float, float], ...] = ()
    limited: bool = False
    held: bool = False
    moving: bool | None = None

    def coordinate(self, t: Value, value: Callable[[str], Any]) -> Value:
        """The input's coordinate at the cycle parameter t (plain or a jet).

        Parameters
        ----------
        t : array_like or Jet
            Cycle parameter, radians.
        value : callable
            Parameter name → value (the model's :meth:`~assur.kinematics.model.
            KinematicModel.value`), for the stroke limits of the harmonic law.

        Returns
        -------
        array_like or Jet
            Radians of crank rotation, or mm.
        """
        if self.moving is not None and isinstance(t, Jet):
            plain = J.value(replace(self, moving=None).coordinate(t.v, value))
            return Jet(plain, float(self.moving), 0.0)
        if self.held:
            return self.phase + 0.0 * t
        if not self.linear:
            return self.phase + self.ratio * t
        if self.table:
            return self._spline_at(t)
        lo, hi = (value(f"{self.group}.{column}") for column in STROKE)
        cos = J.real(J.expi(self.ratio * t + self.phase))
        moved: Value = lo + (hi - lo) * (1.0 - cos) / 2.0
        return moved

    @cached_property
    def _spline(self) -> Any:
        from scipy.interpolate import CubicSpline  # only for a tabulated law

        ts = np.array([t for t, _ in self.table] + [self.table[0][0] + 2 * np.pi])
        vs = np.array([v for _, v in self.table] + [self.table[0][1]])
        return CubicSpline(ts, vs, bc_type="periodic")

    def _spline_at(self, t: Value) -> Value:
        spline, start = self._spline, self.table[0][0]
        base = np.asarray(J.value(t), dtype=float)
        wrapped = start + np.mod(base - start, 2 * np.pi)
        v = spline(wrapped)
        if not isinstance(t, Jet):
            return np.asarray(v)
        d1, d2 = spline(wrapped, 1), spline(wrapped, 2)
        return Jet(v, d1 * t.d1, d2 * t.d1 * t.d1 + d1 * t.d2)


def stroke_margin(q: Value, lo: Any, hi: Any) -> np.ndarray:
    """The normalised margin of a linear input to its stroke ends: min(q − lo, hi − q) over
    the stroke length (negative beyond an end; a stroke shorter than 1 mm counts as 1 mm).

    Examples
    --------
    >>> stroke_margin(np.array([10.0, 0.0, -5.0]), 0.0, 20.0).tolist()
    [0.5, 0.0, -0.25]
    """
    v = np.asarray(J.value(q), dtype=float)
    span = np.maximum(np.asarray(hi, dtype=float) - lo, 1.0)
    return np.asarray(np.minimum(v - lo, hi - v) / span)
