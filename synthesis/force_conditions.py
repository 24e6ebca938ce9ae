"""Force limits as desirable conditions of the synthesis (block B2 → P2, ``docs/forces.md`` §9).

A problem table may hold a ``forces:`` table: the masses and loads of the links, the input
speed, and limits on the largest driving torque and on the largest reaction in named pairs::

    forces:
      omega: 10                      # rad/s of the crank
      gravity: [0, -9.81]            # m/s², optional
      masses: {2: {mass: 0.5, centre: {l: 60, beta: 0}, inertia: 6.0e-4}}
      loads: [{link: 3, torque: -15}]
      limits: {driving_torque: 12, reactions: {"2-3": 400}}     # N·m, N

The points of a design being synthesised are not sketch points: a centre of mass or the point
of a force is given in the link's own frame, as polar ``{l: mm, beta: degrees}`` (or as
``[x, y]`` mm in that frame), like the attachment points N and M of the identification
table. The penalty of a design (the designs of a batch at once, over the analysis grid)::

    P2_F = max(0, max_φ |M_d| − [M_d]) / [M_d] + Σ_pairs max(0, max_φ |R| − [R]) / [R]

with |R| = √(x² + y²) for a revolute pair and |normal| for a prismatic one; a position where
the forces are not solved counts 1 for each limit. P2_F is 0 iff every limit holds at every
grid position; it joins P2 (``criteria.desirable_penalty``) for the designs with P1 = 0 only.

Examples
--------
>>> import numpy as np
>>> excess(np.array([[3.0, -5.0], [1.0, np.nan]]), 4.0).tolist()
[0.25, 1.0]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import numpy.typing as npt

from assur.forces.model import ForceData
from assur.forces.solver import kinetostatics
from assur.forces.table import read_sections
from assur.io.reader import MISSING, Node, describe, normalise_id
from assur.kinematics.analysis import analyse
from assur.kinematics.model import KinematicModel
from assur.model import PairId
from assur.text import Message

__all__ = ["ForceConditions", "excess", "force_penalties", "read_force_conditions"]

FloatArray = npt.NDArray[np.float64]

_KEYS = ("omega", "gravity", "masses", "loads", "limits")
_LIMITS = ("driving_torque", "reactions")


@dataclass(frozen=True)
class ForceConditions:
    """The ``forces:`` table of a problem.

    Attributes
    ----------
    data : ForceData
        Masses and loads, points in the links' own frames (``local``).
    omega : float
        Crank speed, rad/s (0: static).
    driving_torque : float or None
        [M_d], N·m.
    reactions : mapping
        Pair id → [R], N.
    """

    data: ForceData
    omega: float
    driving_torque: float | None
    reactions: Mapping[PairId, float]


def read_force_conditions(top: Node, model: KinematicModel | None) -> ForceConditions | None:
    """The ``forces:`` table of a problem file, or None when there is none.

    Parameters
    ----------
    top : Node
        The top of the problem table; problems are recorded with its reader.
    model : KinematicModel or None
        The initial design (its moving links and pairs); None when the mechanism could not
        be built (then the table is not read: the mechanism's problems come first).

    Returns
    -------
    ForceConditions or None
        None also when a problem was recorded.

    Examples
    --------
    >>> from synthesis.problem_table import read_problem
    >>> problem = read_problem("input_tables/problems/class1_fourbar_torque_limit.yaml")
    >>> problem.forces.driving_torque, problem.forces.omega
    (8.0, 10.0)
    """
    node = top.child("forces", allowed=_KEYS, required=False)
    if node is None or model is None:
        return None
    reader = node.reader
    before = len(reader.issues)
    omega = node.get("omega", kind="number",
                     check=lambda v: None if v >= 0 else Message("rule.non_negative"))
    local = Node(reader, node.location, _localised(node.mapping), None)
    data = read_sections(local, tuple(model.links), model.drive != "crank")
    if data is None and not (node.has("masses") or node.has("loads")):
        reader.problem(node.location, "force.condition.no_loads")
    limits = node.child("limits", allowed=_LIMITS)
    torque, reactions = _limits(limits, model) if limits is not None else (None, {})
    if limits is not None and torque is None and not reactions:
        reader.problem(limits.location, "force.condition.no_limits")
    if len(reader.issues) > before or data is None or omega is MISSING:
        return None
    return ForceConditions(replace(data, local=True), float(omega), torque, reactions)


def _localised(mapping: Mapping[str, Any]) -> dict[str, Any]:
    """The table with every ``{l, beta}`` point written as [x, y] in the link's frame."""
    out = dict(mapping)
    masses = out.get("masses")
    if isinstance(masses, dict):
        out["masses"] = {link: _with_point(row, "centre") for link, row in masses.items()}
    loads = out.get("loads")
    if isinstance(loads, list):
        out["loads"] = [_with_point(row, "point") for row in loads]
    return out


def _with_point(row: Any, key: str) -> Any:
    if not isinstance(row, dict):
        return row
    value = row.get(key)
    if (isinstance(value, dict) and set(value) == {"l", "beta"}
            and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                    for v in value.values())):
        z = value["l"] * complex(math.cos(math.radians(value["beta"])),
                                 math.sin(math.radians(value["beta"])))
        return {**row, key: [z.real, z.imag]}
    return row


def _limits(node: Node, model: KinematicModel
            ) -> tuple[float | None, dict[PairId, float]]:
    def positive(value: float) -> Message | None:
        return None if value > 0 else Message("rule.positive")

    torque = node.get("driving_torque", kind="number", required=False, default=None,
                      check=positive)
    reactions: dict[PairId, float] = {}
    table = node.child("reactions", required=False)
    if table is not None:
        for raw, value in table.mapping.items():
            pair = normalise_id(raw)
            where = f"{table.location} {raw!r}"
            if pair not in model.pair_links:
                node.reader.problem(where, "force.condition.unknown_pair", found=describe(raw),
                                    known=", ".join(map(str, model.pair_links)))
            elif (not isinstance(value, (int, float)) or isinstance(value, bool)
                  or not value > 0):
                node.reader.problem(where, "force.condition.limit", found=describe(value))
            else:
                reactions[pair] = float(value)
    return (None if torque in (MISSING, None) else float(torque)), reactions


def force_penalties(conditions: ForceConditions | None,
                    model_of: Callable[[FloatArray], KinematicModel], x: FloatArray,
                    feasible: npt.NDArray[np.bool_], grid: FloatArray) -> FloatArray:
    """P2_F of a batch of designs, shape (D,); 0 for the designs with P1 > 0.

    Parameters
    ----------
    conditions : ForceConditions or None
        The problem's force limits (None: no penalty).
    model_of : callable
        Designs (D', q) → their kinematic model (``Evaluator.model``).
    x : ndarray, shape (D, q)
        The designs.
    feasible : ndarray of bool, shape (D,)
        P1 = 0: only these are analysed.
    grid : ndarray, shape (N,)
        Crank rotations of the analysis grid, radians.

    Returns
    -------
    ndarray, shape (D,)
    """
    out = np.zeros(np.shape(x)[0])
    if conditions is None or not feasible.any():
        return out
    motion = analyse(model_of(x[feasible]), grid, analogs=True)
    forces = kinetostatics(motion, conditions.data, conditions.omega)
    shape = (int(feasible.sum()), grid.size)
    total = np.zeros(shape[0])
    if conditions.driving_torque is not None:
        total += excess(np.broadcast_to(forces.driving, shape), conditions.driving_torque)
    for pair, limit in conditions.reactions.items():
        r = forces.reactions[pair]
        size = np.abs(r.normal) if r.normal is not None else np.hypot(r.x, r.y)
        total += excess(np.broadcast_to(size, shape), limit)
    out[feasible] = total
    return out


def excess(values: FloatArray, limit: float) -> FloatArray:
    """``max(0, max_φ |v| − limit) / limit`` per design (rows), plus 1 where a position
    is not solved (NaN).

    Parameters
    ----------
    values : ndarray, shape (D, N)
    limit : float
        > 0.

    Returns
    -------
    ndarray, shape (D,)
    """
    values = np.asarray(values, dtype=float)
    solved = np.isfinite(values)
    peak = np.max(np.where(solved, np.abs(values), 0.0), axis=-1)
    return np.maximum(0.0, peak - limit) / limit + (~solved.all(axis=-1))
