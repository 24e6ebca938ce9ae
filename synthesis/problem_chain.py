"""The chain form of a synthesis problem: a mechanism given by its chain table and sketch.

A problem whose mechanism is a chain table with a ``geometry:`` sketch (``docs/synthesis.md``
§"Chain form") names its groups by their links as the labels do (``links: [2, 3, 4, 5]``
for ``III(2,3,4,5)``) and its varied parameters by the model's own columns, which the sketch
defines (``x_F``, ``y_F``: the drawn point of the pair F of a triad, mm; ``l_1``: the crank
length, mm; ``beta_G``: a guide direction, degrees; ``docs/higher_groups.md`` §9).  This
module holds what that form needs besides the reader: the key of a group, and the chain
table of a design, whose sketch is the design's own pose at the reference position (so
that ``assur analyze`` of the result solves exactly the design found).

Examples
--------
>>> from synthesis import load_problem
>>> problem = load_problem("input_tables/problems/class2_six_bar_triad.yaml")
>>> problem.names
('III(2,3,4,5).x_D', 'III(2,3,4,5).y_D', 'III(2,3,4,5).x_E', 'III(2,3,4,5).y_E')
>>> table = design_table(problem, problem.initial)
>>> table["geometry"]["D"]
{'point': [112, 7.5]}
"""

from __future__ import annotations

import cmath
import copy
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from assur.io.reader import normalise_id
from assur.kinematics.analysis import analyse, held
from assur.kinematics.laws import STROKE
from assur.kinematics.model import GroupModel, KinematicModel
from assur.model import LinkId

if TYPE_CHECKING:  # pragma: no cover
    from synthesis.problem import Problem

__all__ = ["design_table", "group_key", "is_chain_form", "table_number"]


def table_number(value: float) -> float | int:
    """A float written back to a table: whole numbers as int, others to 12 digits.

    Examples
    --------
    >>> table_number(40.0), table_number(0.1 + 0.2)
    (40, 0.3)
    """
    rounded = float(f"{value:.12g}")
    return int(rounded) if rounded.is_integer() and abs(rounded) < 1e15 else rounded


def is_chain_form(mechanism: Mapping[str, Any]) -> bool:
    """Whether a problem's mechanism is a chain table (``mechanism:`` is a mapping of pairs)
    rather than an identification table (whose ``mechanism:`` is at most a label)."""
    return isinstance(mechanism.get("mechanism"), Mapping)


def group_key(group: GroupModel) -> tuple[LinkId, ...]:
    """The links of a group as the problem tables name it: the links of its label.

    ``(i,)`` for L0, ``(i, j)`` for a dyad, every link of a triad or class IV group in the
    order of its label (``III(2,3,4,5)`` → ``(2, 3, 4, 5)``).
    """
    if group.layout is None:
        return (group.i,) if group.j is None else (group.i, group.j)
    inside = group.label[group.label.index("(") + 1:-1]
    return tuple(normalise_id(text) for text in inside.split(","))


def design_table(problem: Problem, x: npt.ArrayLike) -> dict[str, Any]:
    """The chain table of design x: the problem's chain with the design's pose as its sketch.

    The mechanism is solved at the reference position (φ = 0) with the design's parameters;
    every pair's point (a revolute joint; a point of the slide line and its direction for a
    prismatic pair) and every tracing point of the sketch is replaced by where the design
    puts it.  Rebuilt from this sketch, the model has the design's parameters and the drawn
    assembly modes are the design's.  Where a group of the design does not assemble at
    φ = 0, its joints keep the drawn points of the problem, moved to the varied coordinates
    ``x_<pair>``, ``y_<pair>`` where the design gives them.

    Parameters
    ----------
    problem : Problem
        A problem of the chain form (:func:`is_chain_form`).
    x : array_like, shape (q,)
        The varied parameters in table units.

    Returns
    -------
    dict
        ``mechanism`` and ``geometry`` as a chain table has them.
    """
    model = problem.model.with_params(problem.mechanism_design(x))
    # inputs that follow laws are drawn at their sketched coordinates, which the laws of
    # the result then move from as they move from the problem's sketch
    motion = analyse(held(model) if model.laws else model, np.zeros(1))
    table = copy.deepcopy(dict(problem.mechanism))
    geometry = table["geometry"]
    for key, entry in geometry.items():
        if not isinstance(entry, dict) or "point" not in entry:
            continue
        drawn = _drawn(model, str(key))
        point = _value(motion.joints.get(key))
        slider = motion.sliders.get(key)
        if slider is not None:
            point = _value(slider.base)
            angle = _value(slider.angle)
            if cmath.isfinite(angle):
                entry["direction"] = table_number(math.degrees(angle.real))
        if not cmath.isfinite(point) and drawn is not None:
            point = drawn
        if cmath.isfinite(point):
            entry["point"] = [table_number(point.real), table_number(point.imag)]
    for name, entry in (geometry.get("tracing") or {}).items():
        point = _value(motion.tracing.get(name))
        if isinstance(entry, dict) and cmath.isfinite(point):
            entry["point"] = [table_number(point.real), table_number(point.imag)]
    _write_strokes(table, model)
    return table


def _write_strokes(table: dict[str, Any], model: KinematicModel) -> None:
    """The design's stroke limits ``s_min``, ``s_max`` of each linear input, written into
    its row of ``mechanism.inputs`` (``stroke: [s_min, s_max]``, mm); the rows are in the
    order of the inputs, as the model's laws."""
    rows = (table.get("mechanism") or {}).get("inputs")
    if not isinstance(rows, list) or len(rows) != len(model.laws):
        return
    for row, law in zip(rows, model.laws.values()):
        if law.linear and law.limited and isinstance(row, dict):
            row["stroke"] = [table_number(float(np.ravel(model.params[f"{law.group}.{c}"])[0]))
                             for c in STROKE]


def _drawn(model: KinematicModel, pair: str) -> complex | None:
    """The drawn point ``x_<pair>``, ``y_<pair>`` of a higher group, if the model has one."""
    for group in model.groups:
        x, y = (model.params.get(group.column(f"{axis}_{pair}")) for axis in "xy")
        if group.layout is not None and x is not None and y is not None:
            return complex(float(np.ravel(x)[0]), float(np.ravel(y)[0]))
    return None


def _value(value: Any) -> complex:
    """The one position of a joint solved at φ = 0 (NaN when absent or not assembled)."""
    if value is None:
        return complex(math.nan, math.nan)
    return complex(np.ravel(np.asarray(getattr(value, "v", value)))[0])
