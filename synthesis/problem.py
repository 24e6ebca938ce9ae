"""Block B1: the synthesis problem table (the six input arrays of the course).

A problem file is YAML with these tables (``method.md`` §4; ``docs/synthesis.md`` shows a
complete example of each task class):

``general``
    ``control_points`` (N_z), ``direction`` (s: +1 counter-clockwise, −1 clockwise),
    ``groups`` (N_Q, L0 included), ``task_class`` (1–5), ``grid`` (positions of the
    analysis grid over a full crank turn), optional ``accuracy`` ([Q], stop rule a, in
    the unit of the output: degrees for ψ, mm for S and Ж, none for the ratio n),
    ``objective`` (``lexicographic`` | ``weighted``), ``p2_weight`` (λ of the weighted form),
    ``output`` (class 1 only: ``angle``, the output link's angle ψ, the default; or
    ``ratio``, its velocity ratio n = dψ/dφ, the first analog), ``criterion`` (``max``, the
    default, or ``rms``: how Q is built from the deviations).
``mechanism`` or ``structure_identification``
    The structure identification: a path (relative to the problem file) of an
    identification table, or its rows inline.  The rows' ``params:`` give the values of the
    parameters that the problem does not list.  Or the chain form: a path of a chain table
    with a ``geometry:`` sketch, or its ``mechanism:`` and ``geometry:`` sections inline; the
    groups are then named by the links of their labels and the columns are those the sketch
    defines (:mod:`synthesis.problem_chain`; the only form for triads and class IV groups).
``group_models``
    Table 1.5, the group-model identification array (optional): rows ``{links: [i, j],
    <column>: value, …}`` (``links: [1]`` for L0; or the columns ``i``, ``j``), each value
    a text (a pair or a point: ``"2-3"``), a number, null (the course's dash), or a list or
    a mapping of these; read into :class:`GroupModelRow` and checked against the groups of
    the mechanism.
``output``
    What the task controls: ``{link: L}`` (its angle ψ, class 1; its slider displacement S,
    class 2) or ``{link: L, point: N|M}`` (tracing point Ж, classes 3–4), with
    ``length`` (mm) and ``angle`` (degrees, a number or ``[initial, lower, upper]``) the
    guided segment of class 5 (:mod:`synthesis.guidance`).
``parameters``
    The varied-parameter tables 2.1–2.6, one row per group (``links: [i, j]``, or
    ``links: [1]`` for L0); each column of the group is ``[initial, lower, upper]``, a single
    number (a fixed value, lower = upper = initial), ``A`` (taken from earlier groups) or
    ``0`` (absent).  Lengths in mm (table units), angles in degrees.  A row replaces the
    same columns of the identification row with the same links.  The bounds are read here;
    the mechanism is handed to :mod:`assur` with plain numbers (the initial values), and
    the kinematic model checks every column (:func:`assur.build_model`).
``allowable``
    Tables 2.7–2.11: rows ``{links: [i, j], pressure_angle: deg, rotations: {joint: deg},
    workspace: {x: [min, max], y: [min, max]}, strokes: {P_i: [min, max]}}`` (the box
    applies to the group's revolute joints, mm; a stroke range to the slider coordinate of
    a prismatic pair, mm).
``control_points``
    Tables 2.12–2.15, columns by class: 1 ``K, phi, psi, E`` (or ``psi_lo, psi_hi`` for a
    zone; with ``output: ratio`` the columns ``n``, ``n_lo``, ``n_hi`` instead, plain
    numbers), 2 ``K, phi, S, E`` (or ``S_lo, S_hi``), 3 ``K, x, y, E``, 4 ``K, phi, x, y,
    E``, 5 ``K, [phi,] x, y, theta, E`` (φ, ψ, θ in degrees; E defaults to 1).
``law``
    Classes 1–4, instead of ``control_points``: ``phi: [first, last]`` and the output as
    formulas of φ (:mod:`synthesis.expressions`).
``search``
    Optional defaults of the search: ``budget`` (log2 of the LPτ trials), ``seed``,
    ``refine``, ``shrink_passes``, ``stall``, ``time_limit``, ``refine_evaluations``
    (evaluations per refinement start; an ill-conditioned task may need more than 200).

:func:`synthesis.problem_table.load_problem` (``synthesis.load_problem``) reads and checks
everything, the one reader, and raises one :class:`~assur.errors.TableError` listing every
problem (file, table, row, field).  This module holds what it returns: typed, frozen
objects.  Reading builds the
kinematic model of the initial design but runs no kinematic analysis; the one check that
needs an analysis (that a group with an allowable pressure angle has one) is made when the
problem is evaluated (:class:`~synthesis.evaluate.Evaluator`).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from assur import KinematicModel
from assur.errors import Issue
from assur.io.reader import normalise_id
from assur.model import DEFAULT_PRESSURE_ANGLE, LinkId, PairId, Student
from assur.typing import ComplexArray, FloatArray
from synthesis.criteria import Objective
from synthesis.problem_chain import design_table, is_chain_form, table_number
from synthesis.search_settings import SearchSettings

if TYPE_CHECKING:  # pragma: no cover
    from synthesis.force_conditions import ForceConditions

__all__ = [
    "CRITERIA",
    "DEFAULT_PRESSURE_ANGLE",
    "OUTPUT_QUANTITIES",
    "SEGMENT_ANGLE",
    "ControlPoints",
    "GroupKey",
    "GroupModelRow",
    "Output",
    "Parameter",
    "Problem",
    "output_slider",
    "row_key",
]

#: The links of a group as the tables name it: ``(i,)`` for L0, ``(i, j)`` for a dyad, the
#: links of the label for a triad or class IV group (``(2, 3, 4, 5)``).
GroupKey = tuple[LinkId, ...]

#: Class-1 outputs: the output link's angle ψ, or its velocity ratio n = dψ/dφ.
OUTPUT_QUANTITIES = ("angle", "ratio")
#: Name of the varied parameter of a class-5 task's segment angle (degrees in the tables),
#: a parameter of the problem rather than of the mechanism.
SEGMENT_ANGLE = "output.angle"
#: Ways to build Q from the deviations: their largest magnitude, or their root mean square.
CRITERIA = ("max", "rms")
#: Keys of the ``search`` table → fields of :class:`~synthesis.search.SearchSettings`.
SEARCH_FIELDS = {"budget": "budget_log2", "seed": "seed", "refine": "refine",
                 "shrink_passes": "shrink_passes", "stall": "stall",
                 "time_limit": "time_limit", "refine_evaluations": "refine_evaluations",
                 "restarts": "restarts"}


@dataclass(frozen=True)
class Parameter:
    """One varied column of a parameter table (table units: mm, degrees).

    Attributes
    ----------
    name : str
        Full name in the kinematic model, ``"<group label>.<column>"`` (``"L1(2,3).l_i"``).
    initial, lower, upper : float
        Initial value and bounds, lower < upper.
    links : tuple
        The links of its group as the tables name them (``(1,)``, ``(2, 3)``).
    """

    name: str
    initial: float
    lower: float
    upper: float
    links: GroupKey = ()

    @property
    def group(self) -> str:
        """Label of the group, e.g. ``'L1(2,3)'``."""
        return self.name.rsplit(".", 1)[0]

    @property
    def column(self) -> str:
        """Designation of the column, e.g. ``'l_i'``."""
        return self.name.rsplit(".", 1)[1]


#: A plain cell of table 1.5: a text (a pair, a point), a number, or None (the course's dash).
ModelScalar = str | int | float | None
#: A cell of table 1.5: a plain one, a list of them (the pairs of an attachment point), or a
#: mapping of them (a base point ``{link: 3, at: 3-0}``).
ModelValue = ModelScalar | list[ModelScalar] | dict[str, ModelScalar]


@dataclass(frozen=True)
class GroupModelRow:
    """One row of table 1.5 (the group-model identification array) as a problem gives it.

    Attributes
    ----------
    links : tuple
        The links of its group as the tables name them (``(1,)``, ``(2, 3)``).
    label : str
        The group's label in the mechanism (``'L1(2,3)'``).
    fields : mapping
        The row's other columns, in the order written, each a :data:`ModelValue`.
    location : str
        Where the row is (``group_models[1]``).
    """

    links: GroupKey
    label: str
    fields: Mapping[str, ModelValue]
    location: str

    def as_row(self) -> dict[str, object]:
        """The row as written: ``links`` and the other columns."""
        return {"links": list(self.links), **self.fields}


@dataclass(frozen=True)
class ControlPoints:
    """The control-point table of the task class (angles in radians).

    Attributes
    ----------
    phi : ndarray, shape (K,)
        Crank rotation from the start position (classes 1, 2, 4; NaN for class 3).
    value : ndarray, shape (K,)
        ψ_K (radians), n_K (the velocity ratio, dimensionless) or S_K (mm) (classes 1–2;
        NaN for a class-1 zone).
    point : ndarray of complex, shape (K,)
        Required points x_K + i·y_K (classes 3–4).
    weight : ndarray, shape (K,)
        Weights E_K.
    lower, upper : ndarray, shape (K,) or None
        Limits of a tolerance zone: class 1 (radians, or plain numbers for the ratio),
        class 2 (mm).
    angle : ndarray, shape (K,) or None
        Class 5: the required direction θ_K of the guided segment (radians).
    """

    phi: FloatArray
    value: FloatArray
    point: ComplexArray
    weight: FloatArray
    lower: FloatArray | None = None
    upper: FloatArray | None = None
    angle: FloatArray | None = None

    def __post_init__(self) -> None:
        for array in (self.phi, self.value, self.point, self.weight, self.lower, self.upper,
                      self.angle):
            if array is not None:
                array.setflags(write=False)

    @property
    def zone(self) -> bool:
        """Whether the task (class 1 or 2) is given as a tolerance zone."""
        return self.lower is not None

    @property
    def timed(self) -> bool:
        """Whether each control point belongs to a given crank angle φ_K (classes 1, 2, 4;
        class 5 when its rows give ``phi``)."""
        return bool(np.all(np.isfinite(self.phi))) and self.phi.size > 0


@dataclass(frozen=True)
class Output:
    """The controlled output: the angle or slider of ``link``, or a point on it.

    ``point`` is ``'N'``/``'M'`` (an attachment point) or the name of a tracing point;
    ``quantity`` (class 1) is ``'angle'`` (ψ) or ``'ratio'`` (n = dψ/dφ).  Class 5 guides
    a segment fixed on the link: it starts at ``point``, is ``length`` mm long and makes the
    angle ``angle`` (radians) with the axis of the link's local frame; a varied angle is the
    parameter :data:`SEGMENT_ANGLE` of the problem, and ``angle`` is then its initial value.
    """

    link: LinkId
    point: str | None = None
    quantity: str = "angle"
    length: float | None = None
    angle: float = 0.0

    @property
    def ratio(self) -> bool:
        """Whether the controlled output is the velocity ratio n = dψ/dφ."""
        return self.quantity == "ratio"


@dataclass(frozen=True)
class Problem:
    """A synthesis problem as read from its table.

    The design vector x of the search holds the varied parameters in the order of
    :attr:`parameters` (groups in layering order, columns in table order), in table units.

    Attributes
    ----------
    mechanism : mapping
        The identification table of the initial design as handed to :mod:`assur`: every
        column a plain number or ``'A'`` (:meth:`mechanism_table` writes a design into it);
        or, in the chain form, its ``mechanism`` and ``geometry`` sections as given.
    model : KinematicModel
        The kinematic model of the initial design.
    accuracy : float or None
        [Q] in the unit of the output as the table gives it: degrees for the angle ψ
        (class 1), mm (classes 2–4), a plain number for the ratio n.
        :attr:`settings` hands the search [Q] in the internal unit (radians for ψ).
    pressure_angles, rotations, workspace : mapping
        Group label → allowable pressure angle (radians), joint → allowable swing
        (radians), working-space box ``(x_min, x_max, y_min, y_max)`` (mm).
    strokes : mapping
        Group label → prismatic pair role → the allowed range ``(s_min, s_max)`` of its
        slider coordinate s (mm, as the kinematics measures it from the guide's base point).
    criterion : str
        How Q is built from the deviations: ``'max'`` (the course's, the default) or
        ``'rms'`` (:data:`CRITERIA`).
    search : mapping
        The values the ``search`` table gives (its own keys: ``budget``, ``seed``, …),
        each already checked by the rule of its setting.
    forces : ForceConditions or None
        The ``forces:`` table: masses, loads and limits on the driving torque and the
        reactions (:mod:`synthesis.force_conditions`).
    student : Student or None
        The ``student:`` section, read by the chain tables' reader
        (:func:`assur.io.chain_table.read_student`); None when the table has none.
    group_models : tuple of GroupModelRow
        Table 1.5 as the problem gives it (empty when it gives none).
    warnings : tuple of Issue
        What the table reader read but warns of (the course's Cyrillic «А», a cell that is
        a range of the program's and a fixed value of the course's alike).
    """

    source: str
    name: str
    task_class: int
    n_points: int
    direction: int
    n_groups: int
    grid: int
    accuracy: float | None
    objective: Objective
    p2_weight: float
    mechanism: Mapping[str, Any]
    model: KinematicModel
    parameters: tuple[Parameter, ...]
    control: ControlPoints
    output: Output
    pressure_angles: Mapping[str, float] = field(default_factory=dict)
    rotations: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    workspace: Mapping[str, tuple[float, float, float, float]] = field(default_factory=dict)
    strokes: Mapping[str, Mapping[str, tuple[float, float]]] = field(default_factory=dict)
    criterion: str = "max"
    group_models: tuple[GroupModelRow, ...] = ()
    search: Mapping[str, Any] = field(default_factory=dict)
    forces: ForceConditions | None = None
    student: Student | None = None
    warnings: tuple[Issue, ...] = ()

    @property
    def output_unit(self) -> str:
        """Unit of the controlled output, of Q and of [Q] wherever a user reads them
        (tables, reports, JSON): ``'deg'`` (ψ), ``'mm'`` (S, Ж) or ``'1'`` (the
        dimensionless ratio n).  Inside, ψ and its deviations are radians."""
        if self.task_class == 1:
            return "1" if self.output.ratio else "deg"
        return "mm"  # (class 5: the deviations of the segment's end points)

    @property
    def output_scale(self) -> float:
        """Table units per internal unit of the output (degrees per radian for ψ, else 1)."""
        return math.degrees(1.0) if self.output_unit == "deg" else 1.0

    @property
    def q_required(self) -> float | None:
        """[Q] in the internal unit of Q (radians for ψ), None when the problem gives none."""
        return None if self.accuracy is None else self.accuracy / self.output_scale

    @property
    def names(self) -> tuple[str, ...]:
        """Full names of the varied parameters (the coordinates of x)."""
        return tuple(p.name for p in self.parameters)

    @property
    def lower(self) -> FloatArray:
        """x⁻."""
        return np.array([p.lower for p in self.parameters])

    @property
    def upper(self) -> FloatArray:
        """x⁺."""
        return np.array([p.upper for p in self.parameters])

    @property
    def initial(self) -> FloatArray:
        """x⁰."""
        return np.array([p.initial for p in self.parameters])

    @property
    def settings(self) -> SearchSettings:
        """The search settings the problem asks for: its ``search`` table, [Q], the objective.

        Settings the table does not give keep the defaults of
        :class:`~synthesis.search_settings.SearchSettings` (a budget of 2**10 trials per
        round, seed 0, …).
        """
        given = {SEARCH_FIELDS[key]: value for key, value in self.search.items()}
        return SearchSettings(**given, q_required=self.q_required, objective=self.objective,
                              p2_weight=self.p2_weight)

    def design(self, x: npt.ArrayLike) -> dict[str, float]:
        """Name → value of the varied parameters of design x."""
        return {p.name: float(v) for p, v in zip(self.parameters, np.asarray(x, dtype=float))}

    def mechanism_design(self, x: npt.ArrayLike) -> dict[str, float]:
        """Name → value of the varied parameters of design x that belong to the mechanism
        (all but a class-5 segment angle, :data:`SEGMENT_ANGLE`)."""
        return {name: value for name, value in self.design(x).items() if name != SEGMENT_ANGLE}

    def mechanism_table(self, x: npt.ArrayLike) -> dict[str, Any]:
        """The mechanism table of design x: what the result file stores.

        The identification form gets every varied column as a plain number; the chain form
        gets the design's pose at the reference position as its sketch
        (:func:`synthesis.problem_chain.design_table`).  ``assur analyze`` reads it back.
        """
        if is_chain_form(self.mechanism):
            return design_table(self, x)
        table = copy.deepcopy(dict(self.mechanism))
        rows = {row_key(row): row for row in table.get("structure_identification", [])}
        for p, value in zip(self.parameters, np.asarray(x, dtype=float)):
            if p.name != SEGMENT_ANGLE:
                rows[p.links]["params"][p.column] = table_number(float(value))
        return table


def output_slider(model: KinematicModel, link: LinkId) -> PairId | None:
    """The prismatic pair whose slider coordinate S is the output of task class 2.

    A pair of ``link`` that ``link`` does not carry (the link slides in it), on a guide of the
    frame if there is one; None when the link has no such pair.
    """
    pairs = model.pair_links
    options = [pid for pid, (kind, links, carrier) in pairs.items()
               if kind == "P" and link in links and carrier != link]
    options.sort(key=lambda pid: pairs[pid][2] != model.frame)
    return options[0] if options else None


def row_key(row: Mapping[str, Any]) -> GroupKey:
    """The links of an identification row: ``(i,)`` for L0, ``(i, j)`` for a dyad."""
    if row.get("L") == 0 or row.get("j") is None:
        return (normalise_id(row.get("i")),)
    return (normalise_id(row.get("i")), normalise_id(row.get("j")))
