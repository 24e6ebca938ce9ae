"""Block B1: the synthesis problem table (the six input arrays of the course).

A problem file is YAML with these tables (``method.md`` §4; ``docs/synthesis.md`` shows a
complete example of each task class):

``general``
    ``control_points`` (N_z), ``direction`` (s: +1 counter-clockwise, −1 clockwise),
    ``groups`` (N_Q, L0 included), ``task_class`` (1–4), ``grid`` (positions of the
    analysis grid over a full crank turn), optional ``accuracy`` ([Q], stop rule a),
    ``objective`` (``lexicographic`` | ``weighted``), ``p2_weight`` (λ of the weighted form),
    ``output`` (class 1 only: ``angle``, the output link's angle ψ, the default; or
    ``ratio``, its velocity ratio n = dψ/dφ, the first analog).
``mechanism`` or ``structure_identification``
    The structure identification: a path (relative to the problem file) of an
    identification table, or its rows inline.  The rows' ``params:`` give the values of the
    parameters that the problem does not list.
``group_models``
    Optional records of table 1.5, kept for the report.
``output``
    What the task controls: ``{link: L}`` (its angle ψ, class 1; its slider displacement S,
    class 2) or ``{link: L, point: N|M}`` (tracing point Ж, classes 3–4).
``parameters``
    The varied-parameter tables 2.1–2.6, one row per group (``links: [i, j]``, or
    ``links: [1]`` for L0); each column of the group is ``[initial, lower, upper]``, a single
    number (a fixed value, lower = upper = initial), ``A`` (taken from earlier groups) or
    ``0`` (absent).  Lengths in mm (table units), angles in degrees.  A row replaces the
    same columns of the identification row with the same links; the kinematic model then
    checks every column (:func:`assur.build_model`).
``allowable``
    Tables 2.7–2.11: rows ``{links: [i, j], pressure_angle: deg, rotations: {joint: deg},
    workspace: {x: [min, max], y: [min, max]}}`` (the box applies to the group's revolute
    joints, mm).
``control_points``
    Tables 2.12–2.15, columns by class: 1 ``K, phi, psi, E`` (or ``psi_lo, psi_hi`` for a
    zone; with ``output: ratio`` the columns ``n``, ``n_lo``, ``n_hi`` instead, plain
    numbers), 2 ``K, phi, S, E``, 3 ``K, x, y, E``, 4 ``K, phi, x, y, E`` (φ, ψ in degrees;
    E defaults to 1).
``search``
    Optional defaults of the search: ``budget`` (log2 of the LPτ trials), ``seed``,
    ``refine``, ``shrink_passes``, ``stall``, ``time_limit``, ``refine_evaluations``
    (evaluations per refinement start; an ill-conditioned task may need more than 200).

:func:`load_problem` reads and checks everything and raises one
:class:`~assur.errors.TableError` listing every problem (file, table, row, field).
"""

from __future__ import annotations

import copy
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

import assur
from assur import MISSING, Message, Node, TableError, TableReader, normalise_id

__all__ = [
    "ControlPoints",
    "DEFAULT_PRESSURE_ANGLE",
    "GroupKey",
    "OUTPUT_QUANTITIES",
    "Output",
    "Parameter",
    "Problem",
    "load_problem",
    "problem_from_dict",
]

GroupKey = tuple[Any, ...]

#: The program default of the allowable pressure angle [α], degrees (``method.md`` §2.7).
DEFAULT_PRESSURE_ANGLE = 45.0
FloatArray = npt.NDArray[np.float64]


_TOP = ("schema_version", "name", "general", "mechanism", "structure_identification",
        "frame", "group_models", "output", "parameters", "allowable", "control_points",
        "search")
_GENERAL = ("control_points", "direction", "groups", "task_class", "grid", "accuracy",
            "objective", "p2_weight", "output")
_SEARCH = ("budget", "seed", "refine", "shrink_passes", "stall", "time_limit",
           "refine_evaluations")
#: Class-1 outputs: the output link's angle ψ, or its velocity ratio n = dψ/dφ.
OUTPUT_QUANTITIES = ("angle", "ratio")
#: Control-point columns of the target value and of the zone limits, per class-1 output.
_VALUE_COLUMNS = {"angle": ("psi", "psi_lo", "psi_hi"), "ratio": ("n", "n_lo", "n_hi")}
_POINT_COLUMNS = {
    1: ("K", "phi", "psi", "psi_lo", "psi_hi", "E"),
    2: ("K", "phi", "S", "E"),
    3: ("K", "x", "y", "E"),
    4: ("K", "phi", "x", "y", "E"),
}
_CLASS_NAMES = {1: "rotating output ψ(φ)", 2: "slider output S(φ)",
                3: "tracing-point path without timing", 4: "tracing-point path with timing"}


@dataclass(frozen=True)
class Parameter:
    """One varied column of a parameter table (table units: mm, degrees).

    Attributes
    ----------
    name : str
        Full name in the kinematic model, ``"<group label>.<column>"`` (``"L1(2,3).l_i"``).
    initial, lower, upper : float
        Initial value and bounds, lower < upper.
    """

    name: str
    initial: float
    lower: float
    upper: float

    @property
    def group(self) -> str:
        """Label of the group, e.g. ``'L1(2,3)'``."""
        return self.name.rsplit(".", 1)[0]

    @property
    def column(self) -> str:
        """Designation of the column, e.g. ``'l_i'``."""
        return self.name.rsplit(".", 1)[1]


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
        Limits of a class-1 tolerance zone (radians, or plain numbers for the ratio).
    """

    phi: FloatArray
    value: FloatArray
    point: npt.NDArray[np.complex128]
    weight: FloatArray
    lower: FloatArray | None = None
    upper: FloatArray | None = None

    @property
    def zone(self) -> bool:
        """Whether the class-1 task is given as a tolerance zone."""
        return self.lower is not None


@dataclass(frozen=True)
class Output:
    """The controlled output: the angle or slider of ``link``, or a point on it.

    ``point`` is ``'N'``/``'M'`` (an attachment point) or the name of a tracing point;
    ``quantity`` (class 1) is ``'angle'`` (ψ) or ``'ratio'`` (n = dψ/dφ).
    """

    link: Any
    point: str | None = None
    quantity: str = "angle"

    @property
    def ratio(self) -> bool:
        """Whether the controlled output is the velocity ratio n = dψ/dφ."""
        return self.quantity == "ratio"


@dataclass(frozen=True)
class Problem:
    """A synthesis problem as read from its table.

    The design vector x of the search holds the varied parameters in the order of
    :attr:`parameters` (groups in layering order, columns in table order), in table units.
    """

    source: str
    name: str
    task_class: int
    n_points: int
    direction: int
    n_groups: int
    grid: int
    accuracy: float | None
    objective: str
    p2_weight: float
    mechanism: dict[str, Any]
    model: Any
    parameters: tuple[Parameter, ...]
    control: ControlPoints
    output: Output
    pressure_angles: dict[str, float] = field(default_factory=dict)
    rotations: dict[str, dict[str, float]] = field(default_factory=dict)
    workspace: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    group_models: tuple[Any, ...] = ()
    search: dict[str, Any] = field(default_factory=dict)

    @property
    def output_unit(self) -> str:
        """Internal unit of the controlled output: ``'rad'`` (ψ), ``'mm'`` (S, Ж) or ``'1'``
        (the dimensionless ratio n)."""
        if self.task_class == 1:
            return "1" if self.output.ratio else "rad"
        return "mm"

    @property
    def output_scale(self) -> float:
        """Table units per internal unit of the output (degrees per radian for ψ, else 1)."""
        return math.degrees(1.0) if self.output_unit == "rad" else 1.0

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

    def design(self, x: npt.ArrayLike) -> dict[str, float]:
        """Name → value of the varied parameters of design x."""
        return {p.name: float(v) for p, v in zip(self.parameters, np.asarray(x, dtype=float))}

    def mechanism_table(self, x: npt.ArrayLike) -> dict[str, Any]:
        """The identification table of design x, every varied column a plain number.

        This is what the result file stores; ``assur analyze`` reads it back.
        """
        table = copy.deepcopy(self.mechanism)
        labels = {group.label: ((group.i,) if group.j is None else (group.i, group.j))
                  for group in self.model.groups}
        values: dict[tuple[Any, ...], dict[str, float]] = {}
        for name, value in self.design(x).items():
            label, column = name.rsplit(".", 1)
            values.setdefault(labels[label], {})[column] = _clean(value)
        for row in table.get("structure_identification", []):
            params = row.get("params")
            if not isinstance(params, dict):
                continue
            for column, raw in list(params.items()):
                if isinstance(raw, list) and len(raw) == 3:
                    params[column] = _clean(float(raw[0]))
            params.update(values.get(_row_key(row), {}))
        return table


def _clean(value: float) -> float | int:
    """A float written back to a table: whole numbers as int, others to 12 digits."""
    rounded = float(f"{value:.12g}")
    return int(rounded) if rounded.is_integer() and abs(rounded) < 1e15 else rounded


def _row_key(row: dict[str, Any]) -> tuple[Any, ...]:
    if row.get("L") == 0 or row.get("j") is None:
        return (normalise_id(row.get("i")),)
    return (normalise_id(row.get("i")), normalise_id(row.get("j")))


# ---------------------------------------------------------------------------------- reading

def load_problem(path: str | os.PathLike[str]) -> Problem:
    """Read and check a problem file.

    Parameters
    ----------
    path : path-like
        The YAML problem table.

    Returns
    -------
    Problem

    Raises
    ------
    TableError
        Listing every problem of the file and of the identification table it refers to.
    """
    return _read(TableReader.from_path(path), Path(path).parent)


def problem_from_dict(data: Any, source: str = "<data>", base: str | os.PathLike[str] = ".",
                      ) -> Problem:
    """Build a problem from already parsed data (see :func:`load_problem`)."""
    return _read(TableReader.from_data(data, source), Path(base))


def _positive(v: Any) -> Message | None:
    return None if v > 0 else Message("rule.positive")


def _read(reader: TableReader, base: Path) -> Problem:
    top = reader.root(allowed=_TOP)
    name = top.get("name", kind="str", required=False, default=None)
    general = top.child("general", allowed=_GENERAL)
    g: dict[str, Any] = {}
    if general is not None:
        g["n_points"] = general.get("control_points", kind="int", check=_positive)
        g["direction"] = general.choice("direction", [1, -1], required=False, default=1)
        g["n_groups"] = general.get("groups", kind="int", check=_positive)
        g["task_class"] = general.choice("task_class", [1, 2, 3, 4])
        g["grid"] = general.get("grid", kind="int", required=False, default=360,
                                check=lambda v: None if v >= 8 else
                                Message("rule.at_least", {"low": 8}))
        g["accuracy"] = general.get("accuracy", kind="number", required=False, default=None,
                                    check=_positive)
        g["objective"] = general.choice("objective", ["lexicographic", "weighted"],
                                        required=False, default="lexicographic")
        g["p2_weight"] = general.get("p2_weight", kind="number", required=False, default=1.0,
                                     check=_positive)
        g["output"] = general.choice("output", OUTPUT_QUANTITIES, required=False,
                                     default="angle")
        if general.has("output") and g["task_class"] in (2, 3, 4):
            reader.add("general 'output'", f"only task class 1 chooses its output (angle or "
                                           f"ratio); task class {g['task_class']} controls "
                                           f"{_CLASS_NAMES[g['task_class']]}; remove 'output'")
    mechanism = _read_mechanism(reader, top, base)
    rows = mechanism.get("structure_identification") or []
    groups = {_row_key(row): row for row in rows if isinstance(row, dict)}
    if g.get("n_groups") not in (None, MISSING) and rows and g["n_groups"] != len(rows):
        reader.add("general 'groups'", f"the structure identification has {len(rows)} groups "
                                       f"(L0 included); found {g['n_groups']}")
    _merge_parameters(top, groups)
    if g.get("direction") in (1, -1):
        for row in rows:
            if isinstance(row, dict) and row.get("L") == 0 and isinstance(row.get("params"), dict):
                if row["params"].setdefault("s", g["direction"]) != g["direction"]:
                    reader.add("general 'direction'", f"the input group's params give s = "
                                                      f"{row['params']['s']!r}; found "
                                                      f"{g['direction']}")
    structure_ok = bool(rows) and not any(
        issue.location.startswith(("mechanism", "structure_identification", "parameters", "frame"))
        for issue in reader.issues)
    task_class = g.get("task_class", MISSING)
    quantity = g.get("output", "angle")
    output = _read_output(top, task_class, groups,
                          quantity if quantity in OUTPUT_QUANTITIES else "angle")
    control = _read_control(top, task_class, g.get("n_points", MISSING), quantity)
    pressure, rotations, boxes = _read_allowable(top, groups)
    models = tuple(top.get("group_models", kind="list", required=False, default=[]) or [])
    search = _read_search(top)
    model = _build_model(reader, mechanism) if structure_ok else None
    parameters: tuple[Parameter, ...] = ()
    pressure_angles: dict[str, float] = {}
    rotation_limits: dict[str, dict[str, float]] = {}
    if model is not None:
        labels = {(grp.i,) if grp.j is None else (grp.i, grp.j): grp.label
                  for grp in model.groups}
        parameters = tuple(Parameter(n, float(model.params[n]), lo, hi)
                           for n, (lo, hi) in model.bounds.items() if hi > lo)
        if not parameters:
            reader.add("parameters", "no parameter is varied; give at least one column as "
                                     "[initial, lower, upper] with lower < upper")
        pressure_angles = {labels[k]: v for k, v in pressure.items()}
        rotation_limits = {labels[k]: v for k, v in rotations.items()}
        _check_allowable(reader, model, pressure_angles, rotation_limits)
        if output.link not in (None, MISSING) and output.link not in model.links:
            reader.add("output 'link'", f"link {output.link!r} is not a moving link of the "
                                        f"mechanism")
    reader.raise_if_any()
    return Problem(
        source=reader.source, name=name or Path(reader.source).stem,
        task_class=task_class, n_points=g["n_points"], direction=g["direction"],
        n_groups=g["n_groups"], grid=g["grid"], accuracy=g["accuracy"],
        objective=g["objective"], p2_weight=float(g["p2_weight"]), mechanism=mechanism,
        model=model, parameters=parameters, control=control, output=output,
        pressure_angles=pressure_angles, rotations=rotation_limits,
        workspace={labels[k]: v for k, v in boxes.items()} if model is not None else {},
        group_models=models,
        search=search)


def _build_model(reader: TableReader, mechanism: dict[str, Any]) -> Any:
    """The kinematic model of the initial design, or None (its problems become issues)."""
    try:
        chain = assur.chain_from_dict(mechanism, source=reader.source)
        return assur.build_model(assur.analyse_structure(chain))
    except TableError as exc:
        reader.issues.extend(exc.issues)
    except assur.StructureError as exc:
        reader.add("structure_identification", str(exc))
    return None


def _read_mechanism(reader: TableReader, top: Node, base: Path) -> dict[str, Any]:
    """The identification table: from a file named by ``mechanism`` or given inline."""
    if top.has("mechanism") and top.has("structure_identification"):
        reader.add("mechanism", "give either 'mechanism' (a file) or "
                                "'structure_identification' (inline rows), not both")
        return {}
    if top.has("structure_identification"):
        rows = top.get("structure_identification", kind="list")
        frame = top.get("frame", kind="id", required=False, default=0)
        if rows is MISSING:
            return {}
        return {"frame": frame, "structure_identification": copy.deepcopy(rows)}
    path = top.get("mechanism", kind="str", required=False, default=None)
    if path is None:
        reader.add("mechanism", "this field is missing; expected the file of the structure "
                                "identification table, or 'structure_identification' rows")
        return {}
    if path is MISSING:
        return {}
    target = base / path
    try:
        inner = TableReader.from_path(target)
    except TableError as exc:
        for issue in exc.issues:
            reader.add("mechanism", f"{target}: {issue}")
        return {}
    data = inner.data
    if not isinstance(data, dict) or not isinstance(data.get("structure_identification"), list):
        reader.add("mechanism", f"{target} has no 'structure_identification' rows; a synthesis "
                                f"problem needs the identification form of the mechanism")
        return {}
    keep = ("frame", "structure_identification", "name", "mechanism")
    return {k: copy.deepcopy(v) for k, v in data.items() if k in keep}


def _group_of(row: Node, groups: dict[GroupKey, Any]) -> GroupKey | None:
    links = row.get("links", kind="list")
    if links is MISSING:
        return None
    key = tuple(normalise_id(v) for v in links)
    if groups and key not in groups:
        known = ", ".join(str(list(k)) for k in groups)
        row.reader.add(f"{row.location} 'links'", f"no group of the structure identification "
                                                  f"has links {list(key)}; the groups are "
                                                  f"{known}")
        return None
    return key


def _merge_parameters(top: Node, groups: dict[GroupKey, Any]) -> None:
    """Write the rows of ``parameters`` into the ``params`` of the identification rows.

    The columns are checked by the kinematic model (all columns of the kind, numbers,
    ``A``, or ``[initial, lower, upper]``); here only the form of the table.
    """
    seen: set[GroupKey] = set()
    for row in top.rows("parameters", None, required=False):
        key = _group_of(row, groups)
        if key is None or key not in groups:
            continue
        if key in seen:
            row.reader.add(f"{row.location} 'links'", f"group {list(key)} already has a "
                                                      f"parameter row")
        seen.add(key)
        target = groups[key]
        params = target.get("params")
        if not isinstance(params, dict):
            params = {}
            target["params"] = params
        for column, value in row.mapping.items():
            if column == "links":
                continue
            if isinstance(value, list) and len(value) == 3 and all(map(_is_number, value)) \
                    and value[1] > value[2]:
                row.reader.add(f"{row.location} {column!r}", f"the lower bound must not exceed "
                                                             f"the upper bound; found {value}")
            params[column] = value


def _read_output(top: Node, task_class: Any, groups: dict[GroupKey, Any],
                 quantity: str = "angle") -> Output:
    node = top.child("output", allowed=("link", "point"))
    if node is None:
        return Output(None, quantity=quantity)
    link = node.get("link", kind="id")
    point = node.get("point", kind="str", required=False, default=None)
    members = {k for key in groups for k in key}
    if link is not MISSING and members and link not in members:
        top.reader.add("output 'link'", f"link {link!r} is not a link of any group")
    if task_class in (3, 4) and point is None:
        top.reader.add("output 'point'", "a path task (class 3 or 4) needs the tracing point: "
                                         "'N' or 'M' of the link")
    elif task_class in (1, 2) and point is not None:
        top.reader.add("output 'point'", f"task class {task_class} controls the link itself; "
                                         f"remove 'point' or choose class 3 or 4")
    return Output(link, point, quantity)


def _read_control(top: Node, task_class: Any, n_points: Any, quantity: Any = "angle"
                  ) -> ControlPoints:
    """Tables 2.12–2.15.

    Class 1 reads ψ (degrees → radians) or, with ``output: ratio``, the dimensionless ratio n
    (columns ``n``, ``n_lo``, ``n_hi``); an invalid ``output`` (already reported) accepts the
    columns of both, so that it is reported once.
    """
    if task_class == 1 and quantity in _VALUE_COLUMNS:
        names = _VALUE_COLUMNS[quantity]
        columns: tuple[str, ...] = ("K", "phi", *names, "E")
    elif task_class == 1:
        names = _VALUE_COLUMNS["angle"]
        columns = ("K", "phi", *(c for v in _VALUE_COLUMNS.values() for c in v), "E")
    else:
        names = _VALUE_COLUMNS["angle"]
        columns = _POINT_COLUMNS.get(task_class, ("K", "phi", "psi", "psi_lo", "psi_hi", "S",
                                                  "x", "y", "E"))
    value_col, lo_col, hi_col = names
    convert = _num if quantity == "ratio" else _deg
    rows = list(top.rows("control_points", columns))
    k = len(rows)
    phi, value, lo, hi, weight = (np.full(k, np.nan) for _ in range(5))
    point = np.full(k, np.nan, dtype=complex)
    zone_rows = 0
    for n, row in enumerate(rows):
        number = row.get("K", kind="int", required=False, default=n)
        if number is not MISSING and number != n:
            row.reader.add(f"{row.location} 'K'", f"control points must be numbered 0, 1, 2, … "
                                                  f"in order; expected {n}")
        e = row.get("E", kind="number", required=False, default=1.0, check=_positive)
        weight[n] = e if e is not MISSING else np.nan
        if task_class in (1, 2, 4):
            phi[n] = _deg(row.get("phi", kind="number"))
        if task_class == 1:
            if row.has(lo_col) or row.has(hi_col):
                zone_rows += 1
                lo[n] = convert(row.get(lo_col, kind="number"))
                hi[n] = convert(row.get(hi_col, kind="number"))
                if row.has(value_col):
                    row.reader.add(f"{row.location} {value_col!r}",
                                   f"a zone row gives {lo_col} and {hi_col}, not {value_col}")
                elif lo[n] > hi[n]:
                    row.reader.add(f"{row.location} {hi_col!r}",
                                   f"the upper limit must not be below the lower one "
                                   f"({row.mapping[lo_col]:g})")
            else:
                value[n] = convert(row.get(value_col, kind="number"))
        elif task_class == 2:
            value[n] = _num(row.get("S", kind="number"))
        elif task_class in (3, 4):
            point[n] = complex(_num(row.get("x", kind="number")), _num(row.get("y", kind="number")))
    if 0 < zone_rows < k:
        top.reader.add("control_points", f"either every row is a zone ({lo_col}, {hi_col}) or "
                                         f"none is; {zone_rows} of {k} rows are")
    if n_points not in (None, MISSING) and k != n_points:
        top.reader.add("general 'control_points'", f"the control-point table has {k} rows; "
                                                   f"found {n_points}")
    if k == 0 and not top.reader.issues:
        top.reader.add("control_points", "the table has no rows")
    zone = task_class == 1 and zone_rows == k and k > 0
    return ControlPoints(phi=phi, value=value, point=point, weight=weight,
                         lower=lo if zone else None, upper=hi if zone else None)


def _read_allowable(top: Node, groups: dict[GroupKey, Any]
                    ) -> tuple[dict[GroupKey, float], dict[GroupKey, dict[str, float]],
                               dict[GroupKey, tuple[float, float, float, float]]]:
    """Tables 2.7–2.11: allowable pressure angles and joint rotations (degrees → radians),
    and working-space boxes of the groups' joints (mm)."""
    pressure: dict[GroupKey, float] = {}
    rotations: dict[GroupKey, dict[str, float]] = {}
    boxes: dict[GroupKey, tuple[float, float, float, float]] = {}
    for row in top.rows("allowable", ("links", "pressure_angle", "rotations", "workspace"),
                        required=False):
        key = _group_of(row, groups)
        angle = None
        if row.mapping.get("pressure_angle") == "default":
            angle = DEFAULT_PRESSURE_ANGLE
        else:
            angle = row.get("pressure_angle", kind="number", required=False, default=None,
                            check=lambda v: None if 0 < v <= 90 else
                            Message("rule.pressure_angle"))
        turns = row.child("rotations", required=False)
        limits = {}
        if turns is not None:
            for joint in turns.mapping:
                value = turns.get(joint, kind="number", check=_positive)
                if value is not MISSING:
                    limits[str(joint)] = math.radians(value)
        box = _read_box(row)
        if key is None:
            continue
        if angle not in (None, MISSING):
            pressure[key] = math.radians(angle)
        if limits:
            rotations[key] = limits
        if box is not None:
            boxes[key] = box
    return pressure, rotations, boxes


def _read_box(row: Node) -> tuple[float, float, float, float] | None:
    node = row.child("workspace", ("x", "y"), required=False)
    if node is None:
        return None
    out = []
    for axis in ("x", "y"):
        value = node.get(axis, kind="list")
        if value is MISSING:
            return None
        if len(value) != 2 or not all(map(_is_number, value)) or value[0] >= value[1]:
            row.reader.add(f"{node.location} {axis!r}", f"expected [min, max] with min < max "
                                                        f"(mm); found {value}")
            return None
        out.extend(float(v) for v in value)
    return out[0], out[1], out[2], out[3]


def _check_allowable(reader: TableReader, model: Any, pressure: dict[str, float],
                     rotations: dict[str, dict[str, float]]) -> None:
    """Pressure angles exist only for L1/L2 groups with a two-hinge rod; rotations only in
    the group's revolute joints (``method.md`` §2.7–2.8)."""
    if pressure:
        motion = assur.analyse(model, np.zeros(1))
        computed = {item.label for item in assur.pressure_angles(motion)}
        for label in pressure:
            if label not in computed:
                reader.add(f"allowable ({label}) 'pressure_angle'",
                           f"the pressure angle is computed only for L1 and L2 groups with a "
                           f"two-hinge rod; {label} has none")
    for label, limits in rotations.items():
        group = model.group(label)
        joints = [role for role in group.pairs if not role.startswith("P")]
        for role in limits:
            if role not in joints:
                reader.add(f"allowable ({label}) 'rotations'",
                           f"unknown revolute joint {role!r}; the joints of {label} are "
                           f"{', '.join(joints) or 'none'}")


def _read_search(top: Node) -> dict[str, Any]:
    node = top.child("search", allowed=_SEARCH, required=False)
    if node is None:
        return {}
    out: dict[str, Any] = {}
    checks = {"budget": ("int", lambda v: None if 0 <= v <= 24 else
                         Message("rule.in_range", {"range": "0..24"})),
              "seed": ("int", None), "refine": ("bool", None),
              "shrink_passes": ("int", lambda v: None if 0 <= v <= 10 else
                                Message("rule.in_range", {"range": "0..10"})),
              "stall": ("int", _positive), "time_limit": ("number", _positive),
              "refine_evaluations": ("int", _positive)}
    for key, (kind, check) in checks.items():
        value = node.get(key, kind=kind, required=False, default=None, check=check,
                         nullable=True)
        if value not in (None, MISSING):
            out[key] = value
    return out


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _deg(v: Any) -> float:
    return math.radians(v) if _is_number(v) else math.nan


def _num(v: Any) -> float:
    return float(v) if _is_number(v) else math.nan
