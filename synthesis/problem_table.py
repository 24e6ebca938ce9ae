"""The one reader of synthesis problem tables: YAML → :class:`~synthesis.problem.Problem`.

:func:`load_problem` (also ``synthesis.load_problem``) reads a file, :func:`problem_from_dict`
already parsed data.

Every table of a problem file (``docs/synthesis.md``) is read and checked here, once, and
every problem found is collected into one :class:`~assur.errors.TableError`.  The
varied-parameter cells ``[initial, lower, upper]`` are parsed here: the bounds belong to the
synthesis, and the mechanism is handed to :mod:`assur` with plain numbers (the initial
values), in new rows; the rows read from the table are never changed.  What :mod:`assur`
finds wrong with the mechanism it reports under its own locations: the problems of rows
given inline join the problem file's list, an identification table in another file raises
its own error under its own name (after the problem file's own problems, if any).

Reading runs no kinematic analysis: the kinematic model of the initial design is built
(structure, parameters), not analysed.  The check that needs an analysis — that a group
given an allowable pressure angle has one — is made when the problem is evaluated
(:class:`synthesis.evaluate.Evaluator`).

Examples
--------
>>> problem = load_problem("input_tables/problems/class1_fourbar_rocker.yaml")
>>> problem.task_class, len(problem.parameters), problem.search["budget"]
(1, 3, 10)
"""

from __future__ import annotations

import cmath
import math
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass, replace
from itertools import pairwise
from pathlib import Path
from typing import Any

import numpy as np

import assur
import assur.kinematics.model
import assur.model
from assur import AssurError, KinematicModel, StructureError, TableError
from assur.errors import Issue
from assur.io.chain_table import read_student
from assur.io.general import read_box
from assur.io.params import SUPPLIED, read_cell
from assur.io.reader import (
    MISSING,
    Node,
    TableReader,
    describe,
    is_number,
    normalise_id,
    positive,
    with_commas,
)
from assur.structure.analysis import StructuralAnalysis
from assur.text import Message
from synthesis.expressions import LawError, parse_law
from synthesis.force_conditions import LINEAR_DRIVES, read_force_conditions
from synthesis.problem import (
    CRITERIA,
    DEFAULT_PRESSURE_ANGLE,
    OUTPUT_QUANTITIES,
    SEARCH_FIELDS,
    SEGMENT_ANGLE,
    ControlPoints,
    GroupKey,
    GroupModelRow,
    Output,
    Parameter,
    Problem,
    output_slider,
    row_key,
)
from synthesis.problem_chain import group_key, is_chain_form
from synthesis.search_settings import setting_problem

__all__ = ["load_problem", "problem_from_dict"]

_TOP = ("schema_version", "name", "general", "mechanism", "structure_identification",
        "frame", "geometry", "group_models", "output", "parameters", "allowable",
        "control_points", "search", "forces", "student", "law")
_GENERAL = ("control_points", "direction", "groups", "task_class", "grid", "accuracy",
            "objective", "p2_weight", "output", "criterion")
#: Control-point columns of the target value and of the zone limits, per class-1 output.
_VALUE_COLUMNS = {"angle": ("psi", "psi_lo", "psi_hi"), "ratio": ("n", "n_lo", "n_hi")}
#: Class-2 control-point columns of the target stroke and of the zone limits.
_S_COLUMNS = ("S", "S_lo", "S_hi")
_POINT_COLUMNS = {
    1: ("K", "phi", "psi", "psi_lo", "psi_hi", "E"),
    2: ("K", "phi", "S", "S_lo", "S_hi", "E"),
    3: ("K", "x", "y", "E"),
    4: ("K", "phi", "x", "y", "E"),
    5: ("K", "phi", "x", "y", "theta", "E"),
}
#: The task classes.
TASK_CLASSES = (1, 2, 3, 4, 5)
#: Fewest control poses of a class-5 task: a motion of the segment needs two positions.
MIN_POSES = 2
#: Columns of the ``law`` table: the angle range and the formula of each class's output.
_LAW_COLUMNS = {1: ("psi",), 2: ("S",), 4: ("x", "y")}
#: Locations whose problems leave no mechanism to build.
_STRUCTURE = ("mechanism", "structure_identification", "parameters", "frame", "geometry")
Bounds = dict[tuple[GroupKey, str], tuple[float, float, float]]
#: Where the kinematic model puts a problem of a cell of a group's parameters.
_PARAMS_AT = re.compile(r"structure_identification \(L\d+\((?P<links>[^)]*)\)\) 'params' "
                        r"'(?P<column>[^']+)'")
#: The same with the column optional: a problem of a row's ``params`` that names its column
#: in the message (an unknown column).
_PARAMS_OF = re.compile(r"structure_identification \(L\d+\((?P<links>[^)]*)\)\) 'params'"
                        r"(?: '(?P<column>[^']+)')?")
#: Codes of the kinematic model's problems of a parameter cell that holds a number where its
#: group wants ``'A'``, and ``'A'`` where it wants a number (:func:`_tell_swapped_cells`).
_WANTS_A = frozenset({"model.moving_hinge_supplied"})
_WANTS_NUMBER = frozenset({"model.frame_hinge_needs_number", "model.frame_guide_needs_number",
                           "model.supplied_here"})
#: Most positions of the analysis grid over a crank turn.
MAX_GRID = 20_000


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
        Listing every problem of the file (and of the identification rows it gives inline);
        an identification table in another file reports its own problems under its own name.
    StructureError
        When the mechanism is not one the kinematics solves (e.g. a group of class III).

    Examples
    --------
    >>> problem = load_problem("input_tables/problems/class3_fourbar_path.yaml")
    >>> problem.task_class, problem.names[:2]
    (3, ('L0(1).l_1', 'L1(2,3).l_i'))
    """
    return _read(TableReader.from_path(path, kind="problem"), Path(path).parent)


def problem_from_dict(data: Any, source: str = "<data>",
                      base: str | os.PathLike[str] = ".") -> Problem:
    """Build a problem from already parsed data (see :func:`load_problem`).

    ``source`` names the data in messages; ``base`` is the folder against which a
    ``mechanism:`` file name is resolved.
    """
    return _read(TableReader.from_data(data, source), Path(base))


@dataclass(frozen=True)
class _General:
    """The ``general`` table; a field is :data:`MISSING` where it is absent or invalid."""

    n_points: Any = MISSING
    direction: Any = 1
    n_groups: Any = MISSING
    task_class: Any = MISSING
    grid: Any = 360
    accuracy: Any = None
    objective: Any = "lexicographic"
    p2_weight: Any = 1.0
    output: Any = "angle"
    criterion: Any = "max"


@dataclass(frozen=True)
class _Mechanism:
    """The identification table (or the chain table) as given: its data, the file it is in,
    and the prefix of the locations of its cells in this file's messages."""

    data: dict[str, Any]
    source: str
    prefix: str = ""

    @property
    def rows(self) -> list[Any]:
        rows = self.data.get("structure_identification")
        return rows if isinstance(rows, list) else []

    @property
    def chain(self) -> bool:
        """Whether the mechanism is given in the chain form (with its sketch)."""
        return is_chain_form(self.data)


@dataclass(frozen=True)
class _Form:
    """What the mechanism's form gives the rest of the reader: the groups by their links,
    the model of the initial design (or the error of another file), the bounds of the varied
    columns, the mechanism table the problem keeps, and the structural analysis the model
    is built from."""

    groups: dict[GroupKey, Any]
    model: KinematicModel | None
    foreign: AssurError | None
    bounds: Bounds
    table: dict[str, Any]
    analysis: StructuralAnalysis | None = None


def _read(reader: TableReader, base: Path) -> Problem:
    top = reader.root(allowed=_TOP)
    name = top.get("name", kind="str", required=False, default=None)
    general = _read_general(top)
    mechanism = _read_mechanism(reader, top, base)
    form = (_chain_form(top, mechanism, general) if mechanism.chain
            else _identification_form(top, mechanism, general))
    groups, model, bounds = form.groups, form.model, form.bounds
    quantity = general.output if general.output in OUTPUT_QUANTITIES else "angle"
    output = _read_output(top, general.task_class, groups, quantity)
    if top.has("law"):
        control = _read_law(top, general.task_class, general.n_points)
    else:
        control = _read_control(top, general.task_class, general.n_points, general.output)
    pressure, rotations, boxes, strokes = _read_allowable(top, groups)
    models = _read_group_models(top, groups)
    search = _read_search(top)
    parameters: tuple[Parameter, ...] = ()
    labels: dict[GroupKey, str] = {}
    if model is not None:
        labels = {group_key(g): g.label for g in model.groups}
        if not mechanism.chain:
            _check_varied(reader, model, bounds, labels)
        parameters = _parameters(model, bounds) + _segment_parameter(top, general.task_class)
        if not parameters and "parameters" not in top.misspelt and not any(
                issue.location.lstrip("'").startswith("parameters") for issue in reader.issues):
            reader.problem("parameters", "problem.nothing_varied")
        _check_rotations(reader, model, {labels[k]: v for k, v in rotations.items()})
        _check_strokes(reader, model, {labels[k]: v for k, v in strokes.items()})
        if output.link is not MISSING:
            _check_output(reader, model, output, general.task_class)
        models = tuple(replace(row, label=labels.get(row.links, row.label)) for row in models)
    if form.analysis is not None and models and not any(
            issue.location.startswith("group_models") for issue in reader.issues):
        _check_group_models(reader, form.analysis, models)
    forces = read_force_conditions(top, model)
    student = read_student(top)
    reader.raise_if_any()
    if form.foreign is not None:
        raise form.foreign
    assert model is not None
    return Problem(
        source=reader.source, name=name or Path(reader.source).stem,
        task_class=general.task_class, n_points=general.n_points,
        direction=model.direction if mechanism.chain else general.direction, n_groups=general.n_groups, grid=general.grid,
        accuracy=general.accuracy, objective=general.objective,
        p2_weight=float(general.p2_weight), mechanism=form.table, model=model,
        parameters=parameters, control=control, output=output,
        pressure_angles={labels[k]: v for k, v in pressure.items()},
        rotations={labels[k]: v for k, v in rotations.items()},
        workspace={labels[k]: v for k, v in boxes.items()},
        strokes={labels[k]: v for k, v in strokes.items()}, criterion=general.criterion,
        group_models=models, search=search, forces=forces, student=student,
        warnings=tuple(reader.warnings))


def _read_general(top: Node) -> _General:
    general = top.child("general", allowed=_GENERAL)
    if general is None:
        return _General()
    task_class = general.choice("task_class", TASK_CLASSES)
    out = _General(
        n_points=general.get("control_points", kind="int", check=positive),
        direction=general.choice("direction", [1, -1], required=False, default=1),
        n_groups=general.get("groups", kind="int", check=positive),
        task_class=task_class,
        grid=general.get("grid", kind="int", required=False, default=360,
                         check=lambda v: None if 8 <= v <= MAX_GRID else
                         Message("rule.in_range", {"range": f"[8, {MAX_GRID}]"})),
        accuracy=general.get("accuracy", kind="number", required=False, default=None,
                             check=positive),
        objective=general.choice("objective", ["lexicographic", "weighted"], required=False,
                                 default="lexicographic"),
        p2_weight=general.get("p2_weight", kind="number", required=False, default=1.0,
                              check=positive),
        output=general.choice("output", OUTPUT_QUANTITIES, required=False, default="angle"),
        criterion=general.choice("criterion", CRITERIA, required=False, default="max"))
    if general.has("output") and task_class in (2, 3, 4, 5):
        top.reader.problem("general 'output'", "problem.output_class", task_class=task_class)
    return out


def _identification_form(top: Node, mechanism: _Mechanism, general: _General) -> _Form:
    """The identification form: groups keyed by the rows, parameters merged into them."""
    reader = top.reader
    groups: dict[GroupKey, Any] = {row_key(row): row for row in mechanism.rows
                                   if _has_links(row)}
    _check_links(reader, mechanism)
    named = _named_groups(top)
    for key in _tie_to_rows(reader, mechanism, groups, named):
        groups[key] = named[key]
    named = {key: places for key, places in named.items() if key not in groups}
    count = len(mechanism.rows)
    if general.n_groups is not MISSING and count and general.n_groups != count:
        if general.n_groups > count and named:
            # rows left out: told once, with the groups the other tables name; those tables
            # are then read as if the rows were there
            reader.problem(f"{mechanism.prefix}structure_identification",
                           "problem.rows_missing", rows=count, found=general.n_groups,
                           links=", ".join(str(list(key)) for key in named),
                           places=", ".join(p for places in named.values() for p in places))
            groups.update(named)
        else:
            reader.problem("general 'groups'", "problem.groups_count", rows=count,
                           found=general.n_groups)
    rows, bounds, places = _merge_parameters(top, mechanism, groups, general.direction)
    table = {**mechanism.data, "structure_identification": rows}
    structure_ok = bool(mechanism.rows) and "parameters" not in top.misspelt and not any(
        issue.location.startswith(_STRUCTURE) for issue in reader.issues)
    start = len(reader.issues)
    model, analysis, foreign = _build_model(reader, table, mechanism.source) if structure_ok \
        else (None, None, None)
    if model is None and structure_ok:
        _tell_swapped_cells(reader, start, places)
        foreign = _own_cells(reader, start, foreign, places)
    return _Form(groups, model, foreign, bounds, table, analysis)


def _own_cells(reader: TableReader, start: int, foreign: AssurError | None,
               places: dict[tuple[GroupKey, str], str]) -> AssurError | None:
    """The kinematic model's problems of cells that a row of ``parameters`` gave, told at
    that row of this file (``parameters[2] 'y_Hj'``), not at the identification row they
    were merged into (which may be in the mechanism's own file); returns what is left of
    ``foreign`` (None when every problem was this file's)."""
    def own(issue: Issue) -> Issue | None:
        match = _PARAMS_OF.fullmatch(issue.location)
        if match is None:
            return None
        column = match["column"] or str(issue.message.data.get("column", "")).strip("'")
        key = tuple(normalise_id(link) for link in match["links"].split(","))
        where = places.get((key, column), "")
        if not where.startswith("parameters"):
            return None
        return Issue(f"{where} {column!r}" if match["column"] else where, issue.message)

    reader.issues[start:] = [own(issue) or issue for issue in reader.issues[start:]]
    if not isinstance(foreign, TableError):
        return foreign
    moved = [(issue, own(issue)) for issue in foreign.issues]
    reader.issues.extend(mine for _, mine in moved if mine is not None)
    left = [issue for issue, mine in moved if mine is None]
    return TableError(foreign.source, left) if left else None


def _tell_swapped_cells(reader: TableReader, start: int,
                        places: dict[tuple[GroupKey, str], str]) -> None:
    """Two cells of one group that the kinematic model finds wrong the opposite ways — a
    number where the group's rule wants ``'A'`` (a hinge on a moving link, supplied by its
    group) and ``'A'`` where it wants a number — are right once swapped: told once, as
    swapped, at the row they were read from.  The model's problems say what each cell
    wants (their codes); ``start`` is the first of them."""
    wrong: dict[str, list[tuple[int, str, str]]] = {}
    for n, issue in enumerate(reader.issues[start:], start):
        match = _PARAMS_AT.fullmatch(issue.location)
        if match:
            wrong.setdefault(match["links"], []).append((n, match["column"],
                                                         issue.message.code))
    told: list[int] = []
    for links, cells in wrong.items():
        wants = sorted("A" if code in _WANTS_A else "number" if code in _WANTS_NUMBER
                       else "other" for _, _, code in cells)
        if wants != ["A", "number"]:
            continue
        (n_a, a, _), (n_b, b, _) = cells
        key = tuple(normalise_id(link) for link in links.split(","))
        where = places.get((key, a))
        if where is not None and places.get((key, b)) == where:  # (two cells of one row)
            reader.issues[n_a] = Issue(where, Message("table.swapped", {"a": a, "b": b}))
            told.append(n_b)
    for n in sorted(told, reverse=True):
        del reader.issues[n]


def _named_groups(top: Node) -> dict[GroupKey, list[str]]:
    """The groups that rows of ``parameters`` and ``allowable`` name by their links, with
    the rows that name them."""
    named: dict[GroupKey, list[str]] = {}
    for table in ("parameters", "allowable"):
        rows = top.mapping.get(table)
        for index, row in enumerate(rows if isinstance(rows, list) else []):
            links = row.get("links") if isinstance(row, dict) else None
            if isinstance(links, list) and links and all(map(_is_link, links)):
                key = tuple(normalise_id(link) for link in links)
                named.setdefault(key, []).append(f"{table}[{index}]")
    return named


def _tie_to_rows(reader: TableReader, mechanism: _Mechanism, groups: dict[GroupKey, Any],
                 named: dict[GroupKey, list[str]]) -> list[GroupKey]:
    """The groups named elsewhere that a row of the identification table nearly has: no row
    has the group, and a row that no other table names has as many links and shares one
    with it.  That row is reported once (as two swapped columns when swapping them back
    gives it the group's links); the groups returned are then read as that row's."""
    tied = []
    for key, places in named.items():
        if key in groups:
            continue
        for index, row in enumerate(mechanism.rows):
            if not _has_links(row) or row_key(row) in named or len(row_key(row)) != len(key) \
                    or not set(map(str, row_key(row))) & set(map(str, key)):
                continue
            where = f"{mechanism.prefix}structure_identification[{index}]"
            pair = _swap_giving(row, key)
            if pair is not None:
                reader.problem(where, "table.swapped", a=pair[0], b=pair[1])
            else:
                reader.problem(where, "problem.row_links", links=list(row_key(row)),
                               group=list(key), places=", ".join(places))
            tied.append(key)
            break
    return tied


def _swap_giving(row: dict[str, Any], key: GroupKey) -> tuple[str, str] | None:
    """Two columns of an identification row whose values, swapped, give it the links
    ``key`` (None if no two do)."""
    columns = [c for c in ("L", "seq", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1",
                           "j_plus_1", "variant") if c in row]
    for n, a in enumerate(columns):
        for b in columns[n + 1:]:
            if "i" in (a, b) or "j" in (a, b):
                swapped = {**row, a: row[b], b: row[a]}
                if _has_links(swapped) and row_key(swapped) == key:
                    return a, b
    return None


def _is_link(value: Any) -> bool:
    return isinstance(value, (int, str)) and not isinstance(value, bool)


def _chain_form(top: Node, mechanism: _Mechanism, general: _General) -> _Form:
    """The chain form: the model from the sketch, its groups keyed by the links of their
    labels, each parameter cell naming a column the sketch defines (``x_F``, ``l_1``, …).

    Every cell given (a number, or ``[initial, lower, upper]`` whose initial value is used)
    replaces the sketch's value in the model of the initial design.
    """
    reader = top.reader
    model, analysis, foreign = _build_model(reader, mechanism.data, mechanism.source)
    if model is None:
        return _Form({}, None, foreign, {}, mechanism.data)
    if model.drive in LINEAR_DRIVES:  # (one cylinder or slider: its stroke over the cycle)
        holder = next(g for g in model.groups if g.driven is not None or g.group_kind.is_input)
        if holder.layout is not None:  # (a higher group follows its actuator's length only)
            reader.problem("mechanism", "problem.actuator_in_group", source=mechanism.source,
                           group=holder.label)
            return _Form({}, None, foreign, {}, mechanism.data)
        model = assur.cycle_model(model)
    groups: dict[GroupKey, Any] = {group_key(g): g.label for g in model.groups}
    if general.n_groups is not MISSING and general.n_groups != len(groups):
        reader.problem("general 'groups'", "higher.problem.groups_count", rows=len(groups),
                       found=general.n_groups)
    stated = (top.mapping.get("general") or {}).get("direction") \
        if isinstance(top.mapping.get("general"), dict) else None
    if stated in (1, -1) and stated != model.direction:
        reader.problem("general 'direction'", "higher.problem.direction_mismatch",
                       rotation=model.direction, found=stated)
    bounds: Bounds = {}
    values: dict[str, float] = {}
    for row, key in _parameter_rows(top, groups):
        for column, value in row.mapping.items():
            name = f"{groups[key]}.{column}"
            location = f"{row.location} {column!r}"
            if column == "links":
                continue
            if name not in model.params:
                reader.problem(location, "higher.problem.column_unknown", column=column,
                               group=groups[key], known=", ".join(_columns(model, groups[key])))
            elif not is_number(value) and not isinstance(value, list):
                reader.problem(location, "higher.problem.cell", found=describe(value))
            else:
                initial = _cell(reader, value, location, key, column, bounds)
                if initial == SUPPLIED:  # (the course's [0, A, 0]: the sketch gives it)
                    reader.problem(location, "higher.problem.cell", found=with_commas(value))
                elif is_number(initial):
                    values[name] = float(initial)
    return _Form(groups, model.with_params(values) if values else model, foreign, bounds,
                 mechanism.data, analysis)


def _columns(model: KinematicModel, label: str) -> list[str]:
    """The columns of a group in the model built from the sketch."""
    return [name[len(label) + 1:] for name in model.params if name.startswith(f"{label}.")]


def _build_model(reader: TableReader, data: dict[str, Any], source: str
                 ) -> tuple[KinematicModel | None, StructuralAnalysis | None,
                            AssurError | None]:
    """The kinematic model of the initial design (built, not analysed), with the structural
    analysis it is built from.

    Problems that :mod:`assur` finds in rows of this file join its list unchanged; an error
    of another file, or of the structure, is returned to be raised as it is.
    """
    try:
        analysis = assur.analyse_structure(assur.chain_from_dict(data, source=source))
        return assur.build_model(analysis), analysis, None
    except TableError as exc:
        if exc.source != reader.source:
            return None, None, exc
        reader.issues.extend(exc.issues)
    except assur.StructureError as exc:
        return None, None, exc
    return None, None, None


def _read_mechanism(reader: TableReader, top: Node, base: Path) -> _Mechanism:
    """The identification table, or the chain table with its sketch: from a file named by
    ``mechanism``, or given inline (rows of ``structure_identification``; the sections
    ``mechanism`` and ``geometry`` of a chain table)."""
    here = _Mechanism({}, reader.source)
    inline = isinstance(top.mapping.get("mechanism"), dict)
    if top.has("geometry") and not inline:
        reader.problem("geometry", "higher.problem.geometry_alone")
    if inline:
        if not top.has("geometry"):
            reader.problem("geometry", "higher.problem.no_geometry")
            return here
        return _Mechanism({"mechanism": top.mapping["mechanism"],
                           "geometry": top.mapping["geometry"]}, reader.source)
    if top.has("mechanism") and top.has("structure_identification"):
        reader.problem("mechanism", "problem.mechanism_both")
        return here
    if top.has("structure_identification"):
        rows = top.get("structure_identification", kind="list")
        frame = top.get("frame", kind="id", required=False, default=0)
        if rows is MISSING:
            return here
        if not rows:
            reader.problem("structure_identification", "chain.no_rows")
        return _Mechanism({"frame": frame, "structure_identification": rows}, reader.source)
    path = top.get("mechanism", kind="str", required=False, default=None)
    if path is None:
        if not top.given("structure_identification"):  # (written misspelt: reported)
            reader.problem("mechanism", "problem.mechanism_missing")
        return here
    if path is MISSING:
        return here
    target = base / path
    try:
        inner = TableReader.from_path(target, kind="chain")
    except TableError as exc:
        # the file named by this table's 'mechanism' field cannot be read: a problem of
        # that field, told in the words of the file reader
        for issue in exc.issues:
            reader.problem("mechanism", "problem.mechanism_unreadable", file=str(target),
                           problem=issue.message)
        return here
    data = inner.data
    if isinstance(data, dict) and is_chain_form(data) and "geometry" in data:
        return _Mechanism({"mechanism": data["mechanism"], "geometry": data["geometry"]},
                          str(target), f"mechanism ({target}) ")
    if not isinstance(data, dict) or not isinstance(data.get("structure_identification"), list) \
            or not data["structure_identification"]:
        reader.problem("mechanism", "problem.mechanism_no_rows", file=str(target))
        return here
    keep = ("frame", "structure_identification", "name", "mechanism")
    return _Mechanism({k: v for k, v in data.items() if k in keep}, str(target),
                      f"mechanism ({target}) ")


def _group_of(row: Node, groups: dict[GroupKey, Any]) -> GroupKey | None:
    links = row.get("links", kind="list")
    if links is MISSING:
        return None
    if not all(map(_is_link, links)):
        row.reader.problem(f"{row.location} 'links'", "table.wrong_kind",
                           expected=Message("value.kind.id_list"), found=describe(links))
        return None
    key = tuple(normalise_id(v) for v in links)
    if groups and key not in groups:
        row.reader.problem(f"{row.location} 'links'", "problem.links_unknown", links=list(key),
                           known=", ".join(str(list(k)) for k in groups))
        return None
    return key


def _parameter_rows(top: Node, groups: dict[GroupKey, Any]
                    ) -> Iterator[tuple[Node, GroupKey]]:
    """The rows of ``parameters`` that name a group, with its key; a group named twice is
    reported (its cells are still read)."""
    done: set[GroupKey] = set()
    for row in top.rows("parameters", None, required=False):
        key = _group_of(row, groups)
        if key is None or key not in groups:
            continue
        if key in done:
            top.reader.problem(f"{row.location} 'links'", "problem.links_repeated",
                               links=list(key))
        done.add(key)
        yield row, key


def _merge_parameters(top: Node, mechanism: _Mechanism, groups: dict[GroupKey, Any],
                      direction: Any) -> tuple[list[Any], Bounds, dict[tuple[GroupKey, str], str]]:
    """New identification rows with the cells of ``parameters`` and plain numbers, their
    bounds, and the row each cell was read from (by links and column).

    Each row of ``parameters`` replaces the same columns of the identification row with the
    same links.  A cell ``[initial, lower, upper]`` (in either table) is checked here and
    becomes its initial value; its bounds are returned by (links, column).  The L0 row
    gets ``s`` = the direction of ``general``.  Everything else about the columns is checked
    by the kinematic model.
    """
    reader = top.reader
    cells: dict[GroupKey, dict[str, tuple[Any, str]]] = {}
    for row, key in _parameter_rows(top, groups):
        cells.setdefault(key, {}).update(
            {column: (value, f"{row.location} {column!r}")
             for column, value in row.mapping.items() if column != "links"})
    bounds: Bounds = {}
    places: dict[tuple[GroupKey, str], str] = {}
    rows: list[Any] = []
    for index, row in enumerate(mechanism.rows):
        if not _has_links(row):
            rows.append(row)
            continue
        key = row_key(row)
        given = row.get("params")
        where = f"{mechanism.prefix}structure_identification[{index}] 'params'"
        merged = ({column: (value, f"{where} {column!r}") for column, value in given.items()}
                  if isinstance(given, dict) else {})
        merged.update(cells.get(key, {}))
        if not merged and not isinstance(given, dict):
            rows.append(row)
            continue
        params = {}
        for column, (value, location) in merged.items():
            params[column] = _cell(reader, value, location, key, column, bounds)
            places[key, column] = location[:-len(f" {column!r}")]
        if row.get("L") == 0 and direction in (1, -1) \
                and params.setdefault("s", direction) != direction:
            reader.problem("general 'direction'", "problem.direction_mismatch",
                           s=params["s"], found=direction)
        rows.append({**row, "params": params})
    return rows, bounds, places


def _cell(reader: TableReader, value: Any, location: str, key: GroupKey, column: str,
          bounds: Bounds) -> Any:
    """The plain value of one parameter cell, in the program's encoding or the course's
    (:func:`assur.io.params.read_cell`): a range ``[initial, lower, upper]`` has its bounds
    recorded, the course's ``[v, v, 0]`` and ``[0, A, 0]`` become ``v`` and ``'A'``.  A
    list that is neither is told; other values go to the kinematic model unchanged."""
    if column == "tracing":
        return value
    cell = read_cell(value)
    if cell.problem is not None:
        reader.problem(location, cell.problem.code, **cell.problem.data)
        return value
    if cell.warning is not None:
        reader.warn(location, cell.warning.code, **cell.warning.data)
    if cell.both_forms:
        reader.warn(location, "params.both_forms", found=with_commas(value), v=value[0])
    if cell.bounds is not None:
        bounds[key, column] = cell.bounds
    return cell.value


def _check_varied(reader: TableReader, model: KinematicModel, bounds: Bounds,
                  labels: dict[GroupKey, str]) -> None:
    """A varied column must change the mechanism: a column of its group's kind, ``delta``, or
    a column of a tracing point of that group (``l_Ж``/``beta_Ж`` with ``tracing:``)."""
    traced = {(point.anchor.owner, column) for point in model.tracing
              for column in (point.anchor.first, point.anchor.second)}
    for (key, column), (_, lower, upper) in bounds.items():
        label = labels.get(key)
        if label is None or upper <= lower:
            continue
        kind = model.group(label).kind
        columns = (*assur.kinematics.model.KIND_COLUMNS[kind], "delta")
        if column not in columns and (label, column) not in traced:
            reader.problem(f"parameters ({label}) {column!r}", "problem.varied_unused",
                           column=column, group=label)


def _parameters(model: KinematicModel, bounds: Bounds) -> tuple[Parameter, ...]:
    """The varied parameters (lower < upper): groups in layering order, then the columns of
    the kind in table order, ``delta``, and the tracing-point columns by name (a triad's or
    class IV group's columns, named after its pairs, in the order the table gives them)."""
    out = []
    for group in model.groups:
        key = group_key(group)
        columns = [column for (links, column) in bounds if links == key]
        fixed = (*assur.kinematics.model.KIND_COLUMNS[group.kind], "delta")
        rest = [c for c in columns if c not in fixed]
        ordered = [c for c in fixed if c in columns] + (rest if group.layout else sorted(rest))
        for column in ordered:
            initial, lower, upper = bounds[key, column]
            if upper > lower:
                out.append(Parameter(f"{group.label}.{column}", initial, lower, upper, key))
    return tuple(out)


def _read_output(top: Node, task_class: Any, groups: dict[GroupKey, Any],
                 quantity: str) -> Output:
    node = top.child("output", allowed=("link", "point", "length", "angle"))
    if node is None:
        return Output(MISSING, quantity=quantity)
    link = node.get("link", kind="id")
    point = node.get("point", kind="str", required=False, default=None)
    length, angle = _read_segment(node, task_class)
    members = {k for key in groups for k in key}
    if link is not MISSING and members and link not in members:
        top.reader.problem("output 'link'", "problem.output_link_unknown", link=link)
        link = MISSING  # (told: not judged again against the mechanism)
    if task_class in (3, 4, 5) and point is None:
        top.reader.problem("output 'point'", "problem.point_needed")
    elif task_class in (1, 2) and point is not None:
        top.reader.problem("output 'point'", "problem.point_extra", task_class=task_class)
    return Output(link, point, quantity, length, angle)


def _read_segment(node: Node, task_class: Any) -> tuple[float | None, float]:
    """The guided segment of a class-5 task: ``length`` (mm, required) and ``angle`` on the
    link (degrees; a number, or ``[initial, lower, upper]`` when varied — read as a
    parameter by :func:`_segment_parameter`); both belong to class 5 only.  Returns the
    length (None when absent or invalid) and the fixed angle or the initial one (radians).
    """
    if task_class != 5:
        for key in ("length", "angle"):
            if node.has(key) and task_class is not MISSING:
                node.reader.problem(f"output {key!r}", "problem.segment_extra", field=key,
                                    task_class=task_class)
        return None, 0.0
    length = node.get("length", kind="number", check=positive)
    value = node.mapping.get("angle", 0.0)
    angle = _segment_cell(node.reader, value)
    return (None if length is MISSING else float(length),
            math.radians(angle[0]) if angle is not None else 0.0)


def _segment_cell(reader: TableReader, value: Any) -> tuple[float, float, float] | None:
    """``output: angle``: a number (fixed) or ``[initial, lower, upper]`` (varied), degrees;
    a bad cell is reported (None)."""
    if is_number(value):
        return float(value), float(value), float(value)
    if isinstance(value, list) and len(value) == 3 and all(map(is_number, value)):
        initial, lower, upper = (float(v) for v in value)
        if lower > upper:
            reader.problem("output 'angle'", "problem.bounds_order", found=value)
        elif not lower <= initial <= upper:
            reader.problem("output 'angle'", "problem.initial_outside", found=value)
        else:
            return initial, lower, upper
        return None
    reader.problem("output 'angle'", "problem.segment_angle_cell", found=with_commas(value)
                   if isinstance(value, list) else describe(value))
    return None


def _segment_parameter(top: Node, task_class: Any) -> tuple[Parameter, ...]:
    """The segment's angle as a varied parameter (:data:`SEGMENT_ANGLE`, degrees) when
    a class-5 task gives it as ``[initial, lower, upper]`` with lower < upper."""
    node = top.mapping.get("output")
    value = node.get("angle") if isinstance(node, dict) else None
    if task_class != 5 or not isinstance(value, list) or len(value) != 3 \
            or not all(map(is_number, value)):
        return ()
    initial, lower, upper = (float(v) for v in value)
    if not lower <= initial <= upper or lower == upper:
        return ()
    return (Parameter(SEGMENT_ANGLE, initial, lower, upper),)


def _read_control(top: Node, task_class: Any, n_points: Any, quantity: Any) -> ControlPoints:
    """Tables 2.12–2.15.

    Class 1 reads ψ (degrees → radians) or, with ``output: ratio``, the dimensionless ratio n
    (columns ``n``, ``n_lo``, ``n_hi``); with an invalid or misspelt ``output`` (already
    reported) the rows are read in the columns they use, so that it is reported once.
    A row cut by a decimal comma (reported by the reader) is not checked against itself or
    the other rows: its values are not the ones meant.
    """
    if task_class == 1:
        columns: tuple[str, ...] = (
            "K", "phi", *(_VALUE_COLUMNS[quantity] if quantity in _VALUE_COLUMNS else
                          (c for v in _VALUE_COLUMNS.values() for c in v)), "E")
    else:
        columns = _POINT_COLUMNS.get(task_class, (  # (no valid class: every column passes)
            "K", "phi", *(c for v in _VALUE_COLUMNS.values() for c in v), "S", "S_lo", "S_hi",
            "x", "y", "theta", "E"))
    rows = list(top.rows("control_points", columns))
    if quantity not in _VALUE_COLUMNS:
        used = {column for row in rows for column in row.mapping}
        quantity = "ratio" if used & set(_VALUE_COLUMNS["ratio"]) else "angle"
    value_col, lo_col, hi_col = _VALUE_COLUMNS[quantity] if task_class != 2 else _S_COLUMNS
    convert = _num if quantity == "ratio" or task_class == 2 else _deg
    k = len(rows)
    phi, value, lo, hi, weight, angle = (np.full(k, np.nan) for _ in range(6))
    point = np.full(k, np.nan, dtype=complex)
    zone_rows = timed_rows = 0
    reader = top.reader
    table = top.mapping.get("control_points")
    places = [n for n, row in enumerate(table) if isinstance(row, dict)] \
        if isinstance(table, list) else []
    numbers = []
    for n, row in enumerate(rows):
        row.swapped({"K": lambda v: isinstance(v, int) and not isinstance(v, bool),
                     "phi": is_number})
        numbers.append(row.get("K", kind="int", required=False, default=places[n]))
        e = row.get("E", kind="number", required=False, default=1.0, check=positive)
        weight[n] = e if e is not MISSING else np.nan
        cut = _cut_by_comma(row)
        if task_class in (1, 2, 4) or (task_class == 5 and row.has("phi")):
            timed_rows += 1
            phi[n] = _deg(row.get("phi", kind="number"))
        if task_class in (1, 2):
            if row.has(lo_col) or row.has(hi_col):
                zone_rows += 1
                lo[n] = convert(row.get(lo_col, kind="number"))
                hi[n] = convert(row.get(hi_col, kind="number"))
                if row.has(value_col):
                    reader.problem(f"{row.location} {value_col!r}", "problem.zone_value",
                                   lo=lo_col, hi=hi_col, value=value_col)
                elif lo[n] > hi[n] and not cut:
                    reader.problem(f"{row.location} {hi_col!r}", "problem.zone_order",
                                   lower=row.mapping[lo_col])
            else:
                value[n] = convert(row.get(value_col, kind="number"))
        elif task_class in (3, 4, 5):
            point[n] = complex(_num(row.get("x", kind="number")), _num(row.get("y", kind="number")))
        if task_class == 5:
            angle[n] = _deg(row.get("theta", kind="number"))
        if cut:
            phi[n] = np.nan
    _check_repeated_angles(reader, rows, phi, value, point, lo, hi, angle)
    if task_class == 5:
        _check_poses(top, k, timed_rows)
    if 0 < zone_rows < k:
        reader.problem("control_points", "problem.zone_mixed", lo=lo_col, hi=hi_col,
                       zone=zone_rows, rows=k)
    left_out = _check_numbering(reader, rows, places, numbers)
    if n_points is not MISSING and isinstance(table, list) \
            and n_points not in (len(table), len(table) + left_out):
        reader.problem("general 'control_points'", "problem.control_count", rows=len(table),
                       found=n_points)
    if k == 0 and not reader.issues:
        reader.problem("control_points", "problem.control_empty")
    zone = task_class in (1, 2) and zone_rows == k and k > 0
    return ControlPoints(phi=phi, value=value, point=point, weight=weight,
                         lower=lo if zone else None, upper=hi if zone else None,
                         angle=angle if task_class == 5 else None)


def _check_poses(top: Node, rows: int, timed: int) -> None:
    """A class-5 task gives at least :data:`MIN_POSES` poses, and either every pose its
    crank angle ``phi`` (a timed task) or none."""
    if rows < MIN_POSES:
        top.reader.problem("control_points", "problem.poses_few", needed=MIN_POSES,
                           found=rows)
    if 0 < timed < rows:
        top.reader.problem("control_points", "problem.poses_timing", timed=timed, rows=rows)


def _cut_by_comma(row: Node) -> bool:
    """Whether a number of the row was written with a decimal comma inside ``{…}``, which
    YAML splits into a value and a stray key (reported by the reader)."""
    return any(isinstance(key, int) and value is None for key, value in row.mapping.items())


def _check_numbering(reader: TableReader, rows: list[Node], places: list[int],
                     numbers: list[Any]) -> int:
    """Control points are numbered 0, 1, 2, … in table order (``K``).

    When the numbers rise with gaps, rows were left out: the first gap is reported once, at
    the row after it, and the rows after it are not reported again.  Otherwise each row whose
    number is not its place is reported.  Returns how many rows the gaps leave out.
    """
    given = [(row, place, number) for row, place, number in zip(rows, places, numbers)
             if number is not MISSING]
    wrong = [(row, place) for row, place, number in given if number != place]
    if not wrong:
        return 0
    values = [number for _, _, number in given]
    if values[0] >= 0 and all(b > a for a, b in pairwise(values)):
        gaps = sorted(set(range(values[-1] + 1)) - set(values))
        first = next(n for n, (_, place, number) in enumerate(given) if number != place)
        shown = values[max(0, first - 3):max(first + 1, 3)]
        numbers_shown = ("…, " if first > 3 else "") + ", ".join(map(str, shown)) + (
            ", …" if len(values) > max(first + 1, 3) else "")
        reader.problem(f"{given[first][0].location} 'K'",
                       "problem.control_row_missing" if len(gaps) == 1
                       else "problem.control_rows_missing",
                       missing=", ".join(map(str, gaps)), numbers=numbers_shown)
        return len(gaps)
    for row, place in wrong:
        reader.problem(f"{row.location} 'K'", "problem.control_numbering", expected=place)
    return 0


def _check_repeated_angles(reader: TableReader, rows: list[Node], phi: np.ndarray,
                           *targets: np.ndarray) -> None:
    """Two control rows at the same crank angle (modulo 360°) must ask for the same target."""
    first: dict[float, int] = {}
    for n, angle in enumerate(phi):
        if not math.isfinite(angle):
            continue
        turn = round(math.degrees(angle) % 360.0, 9) % 360.0
        if turn not in first:
            first[turn] = n
            continue
        m = first[turn]
        if any(not _same(target[m], target[n]) for target in targets):
            reader.problem(f"{rows[n].location} 'phi'", "problem.control_angle_twice",
                           phi=_shown(math.degrees(angle)), other=rows[m].location)


def _same(a: complex, b: complex) -> bool:
    return a == b or (cmath.isnan(a) and cmath.isnan(b))  # equal, or both absent (NaN)


def _shown(value: float) -> float | int:
    return int(value) if float(value).is_integer() else value


def _read_allowable(top: Node, groups: dict[GroupKey, Any]
                    ) -> tuple[dict[GroupKey, float], dict[GroupKey, dict[str, float]],
                               dict[GroupKey, tuple[float, float, float, float]],
                               dict[GroupKey, dict[str, tuple[float, float]]]]:
    """Tables 2.7–2.11: allowable pressure angles and joint rotations (degrees → radians),
    working-space boxes of the groups' joints (mm), and stroke ranges of their prismatic
    pairs (mm, :func:`_read_stroke_limits`)."""
    pressure: dict[GroupKey, float] = {}
    rotations: dict[GroupKey, dict[str, float]] = {}
    boxes: dict[GroupKey, tuple[float, float, float, float]] = {}
    strokes: dict[GroupKey, dict[str, tuple[float, float]]] = {}
    for row in top.rows("allowable", ("links", "pressure_angle", "rotations", "workspace",
                                      "strokes"), required=False):
        row.swapped({"links": lambda v: isinstance(v, list),
                     "pressure_angle": lambda v: is_number(v) or v == "default",
                     "rotations": lambda v: isinstance(v, dict),
                     "workspace": lambda v: isinstance(v, dict)})
        key = _group_of(row, groups)
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
                value = turns.get(joint, kind="number", check=positive)
                if value is not MISSING:
                    limits[str(joint)] = math.radians(value)
        box = read_box(row)
        ranges = _read_stroke_limits(row)
        if key is None:
            continue
        if ranges:
            strokes[key] = ranges
        if angle not in (None, MISSING):
            pressure[key] = math.radians(angle)
        if limits:
            rotations[key] = limits
        if box is not None:
            boxes[key] = box
    return pressure, rotations, boxes, strokes


def _read_stroke_limits(row: Node) -> dict[str, tuple[float, float]]:
    """An ``allowable`` row's ``strokes``: prismatic pair role → ``[s_min, s_max]`` (mm),
    the range its slider coordinate must keep over the cycle (a working-space condition)."""
    node = row.child("strokes", required=False)
    limits: dict[str, tuple[float, float]] = {}
    if node is None:
        return limits
    for role, value in node.mapping.items():
        where = f"{row.location} 'strokes' {str(role)!r}"
        if not (isinstance(value, list) and len(value) == 2 and all(map(is_number, value))):
            row.reader.problem(where, "problem.stroke_cell", found=with_commas(value)
                               if isinstance(value, list) else describe(value))
        elif float(value[0]) > float(value[1]):
            row.reader.problem(where, "problem.stroke_order", lower=float(value[0]),
                               upper=float(value[1]))
        else:
            limits[str(role)] = (float(value[0]), float(value[1]))
    return limits


def _check_strokes(reader: TableReader, model: KinematicModel,
                   strokes: dict[str, dict[str, tuple[float, float]]]) -> None:
    """Stroke ranges are given only to the group's prismatic pairs."""
    for label, limits in strokes.items():
        group = model.group(label)
        pairs = [role for role in group.pairs if role.startswith("P")]
        for role in limits:
            if role not in pairs:
                reader.problem(f"allowable ({label}) 'strokes'", "problem.stroke_pair",
                               pair=role, group=label, pairs=", ".join(pairs) or "—")


def _read_law(top: Node, task_class: Any, n_points: Any) -> ControlPoints:
    """The ``law`` table: the required output as formulas of φ (the course's (2.22)) in
    place of the control-point table.

    ``phi: [first, last]`` (degrees) and one formula per output of the class — ``psi``
    (degrees, class 1), ``S`` (mm, class 2), ``x`` and ``y`` (mm, classes 3–4) — each read
    by :func:`synthesis.expressions.parse_law`.  The control points are the N_z angles
    evenly spaced from the first to the last (``general: control_points``), every weight
    E_K = 1; a class-3 task keeps the points and drops their angles.
    """
    reader = top.reader
    k = n_points if isinstance(n_points, int) and n_points > 0 else 0
    empty = np.full(k, np.nan)
    out = ControlPoints(phi=empty, value=empty.copy(), point=empty + 0j, weight=np.ones(k))
    if top.has("control_points"):
        reader.problem("law", "problem.law_and_table")
    law_of = task_class if task_class != 3 else 4
    if task_class is not MISSING and law_of not in _LAW_COLUMNS:
        reader.problem("law", "problem.law_class", task_class=task_class)
        return out
    names = _LAW_COLUMNS.get(law_of, ("psi", "S", "x", "y"))
    node = top.child("law", allowed=("phi", *names))
    if node is None or task_class is MISSING:
        return out
    laws = {}
    for name in names:
        text = node.get(name, kind="str")
        if text is MISSING:
            continue
        try:
            laws[name] = parse_law(text)
        except LawError as exc:
            reader.problem(f"law {name!r}", "problem.law_formula",
                           reason=Message(f"law.reason.{exc.reason}", {"detail": exc.detail}),
                           found=describe(text))
    span = node.get("phi", kind="list")
    if span is not MISSING and not (len(span) == 2 and all(map(is_number, span))
                                    and float(span[0]) < float(span[1])):
        reader.problem("law 'phi'", "problem.law_span", found=with_commas(span))
        span = MISSING
    if span is MISSING or len(laws) != len(names) or k == 0:
        return out
    phi = np.linspace(float(span[0]), float(span[1]), k)
    values = {name: law(phi) for name, law in laws.items()}
    for name, value in values.items():
        bad = np.flatnonzero(~np.isfinite(value))
        if bad.size:
            reader.problem(f"law {name!r}", "problem.law_undefined",
                           phi=_shown(float(phi[bad[0]])), count=int(bad.size))
    angles = np.radians(phi) if task_class != 3 else np.full(k, np.nan)
    if law_of == 4:
        return ControlPoints(phi=angles, value=empty.copy(),
                             point=values["x"] + 1j * values["y"], weight=np.ones(k))
    value = np.radians(values["psi"]) if task_class == 1 else values["S"]
    return ControlPoints(phi=angles, value=value, point=empty + 0j, weight=np.ones(k))


def _read_group_models(top: Node, groups: dict[GroupKey, Any]) -> tuple[GroupModelRow, ...]:
    """Table 1.5: one row per group, named by its links as the other tables name it
    (``links: [i, j]``), or by its columns ``i`` and ``j`` as the printed table has them;
    every other column a :data:`~synthesis.problem.ModelValue` (a text, a number, null, a
    list of these, or a mapping of these such as ``{link: 3, at: 3-0}``); a group named
    twice is told.  Whether the columns are the ones the group's model has is judged
    against the table the structure analysis builds (:func:`_check_group_models`)."""
    out: list[GroupModelRow] = []
    for row in top.rows("group_models", None, required=False):
        key = _group_of(row, groups) if row.has("links") or not row.has("i") \
            else _group_by_roles(row, groups)
        fields = {}
        for column, value in row.mapping.items():
            if column == "links":
                continue
            if _model_value(value):
                fields[str(column)] = value
            else:
                top.reader.problem(f"{row.location} {column!r}", "table.wrong_kind",
                                   expected=Message("group_models.cell"), found=describe(value))
        if key is None:
            continue
        if any(done.links == key for done in out):
            top.reader.problem(f"{row.location} 'links'", "group_models.repeated",
                               links=list(key))
            continue
        out.append(GroupModelRow(key, "", fields, row.location))
    return tuple(out)


def _group_by_roles(row: Node, groups: dict[GroupKey, Any]) -> GroupKey | None:
    """The group of a row of table 1.5 that names its links in the columns ``i`` and ``j``
    (``j`` null or absent for L0)."""
    links = [row.mapping.get(column) for column in ("i", "j") if row.mapping.get(column)
             is not None]
    if not all(map(_is_link, links)):
        row.reader.problem(f"{row.location} 'i'", "table.wrong_kind",
                           expected=Message("value.kind.id"), found=describe(links[0]))
        return None
    key = tuple(normalise_id(link) for link in links)
    if key not in groups:
        row.reader.problem(f"{row.location} 'i'", "problem.links_unknown", links=list(key),
                           known=", ".join(str(list(k)) for k in groups))
        return None
    return key


def _model_value(value: Any, depth: int = 0) -> bool:
    """Whether ``value`` may stand in a cell of table 1.5: a text, a number or null, or
    (not nested further) a list or a mapping of these."""
    if value is None or isinstance(value, str) or is_number(value):
        return True
    if depth == 0 and isinstance(value, list):
        return all(_model_value(item, 1) for item in value)
    if depth == 0 and isinstance(value, dict):
        return all(isinstance(key, str) and _model_value(item, 1)
                   for key, item in value.items())
    return False


def _check_group_models(reader: TableReader, analysis: StructuralAnalysis,
                        rows: tuple[GroupModelRow, ...]) -> None:
    """Each difference of the problem's table 1.5 from the one the structure analysis
    builds is a problem of the table, told as the comparison words it (its row, its field,
    what was expected and what was found)."""
    reader.issues.extend(_group_model_mismatches(analysis, [row.as_row() for row in rows]))


def _group_model_mismatches(analysis: StructuralAnalysis,
                            rows: list[dict[str, object]]) -> list[Issue]:
    """The differences of table 1.5 as given (``rows``, in the problem's order) from the
    one the structure analysis builds (:func:`assur.check_group_models`); for a mechanism
    the course's table does not describe (a triad, a class IV group), the reason why."""
    try:
        mismatches = assur.check_group_models(analysis, rows)
    except StructureError as exc:
        assert isinstance(exc.message, Message)  # the dyads-only refusal is catalogued
        return [Issue("group_models", exc.message)]
    return [Issue("", mismatch.message) for mismatch in mismatches]


def _check_rotations(reader: TableReader, model: KinematicModel,
                     rotations: dict[str, dict[str, float]]) -> None:
    """Rotations are checked only in the group's revolute joints (``method.md`` §2.8)."""
    for label, limits in rotations.items():
        group = model.group(label)
        joints = [role for role in group.pairs if not role.startswith("P")]
        for role in limits:
            if role not in joints:
                reader.problem(f"allowable ({label}) 'rotations'", "problem.joint_unknown",
                               joint=role, group=label, joints=", ".join(joints) or "—")


def _check_output(reader: TableReader, model: KinematicModel, output: Output,
                  task_class: Any) -> None:
    """The output link moves; in task class 2 it slides in a prismatic pair; in classes 3
    and 4 its point is a tracing point, or a point ``l_Ж``, ``beta_Ж`` of its group."""
    link = output.link
    if link not in model.links:
        reader.problem("output 'link'", "problem.output_not_moving", link=link)
        return
    if task_class == 2 and output_slider(model, link) is None:
        reader.problem("output 'link'", "problem.output_no_slider", link=link)
    label = model.links[link][0]
    named = {point.name for point in model.tracing}
    carried = {name[len(f"{label}.l_"):] for name in model.params
               if name.startswith(f"{label}.l_")
               and f"{label}.beta_{name[len(f'{label}.l_'):]}" in model.params}
    if isinstance(output.point, str) and output.point not in named | carried:
        reader.problem("output 'point'", "problem.output_point_unknown", point=output.point,
                       link=link, known=", ".join(sorted(named | carried)) or "—")


def _read_search(top: Node) -> dict[str, Any]:
    """The ``search`` table, each value checked by the rule of its setting
    (:func:`synthesis.search_settings.setting_problem`, the same rule as on the command
    line)."""
    node = top.child("search", allowed=SEARCH_FIELDS, required=False)
    if node is None:
        return {}
    out: dict[str, Any] = {}
    for key, setting in SEARCH_FIELDS.items():
        value = node.mapping.get(key)
        if value is None:
            continue
        problem = setting_problem(setting, value)
        if problem is None:
            out[key] = value
        else:
            top.reader.problem(f"search {key!r}", problem.code, **problem.data)
    return out


def _check_links(reader: TableReader, mechanism: _Mechanism) -> None:
    """The link ids of the identification rows, which key the problem's other tables."""
    for index, row in enumerate(mechanism.rows):
        if isinstance(row, dict) and not _has_links(row):
            for key in ("i", "j"):
                if not _has_links({key: row.get(key)}):
                    reader.problem(f"{mechanism.prefix}structure_identification[{index}] "
                                   f"{key!r}", "table.wrong_kind",
                                   expected=Message("value.kind.id"), found=describe(row[key]))


def _has_links(row: Any) -> bool:
    """Whether an identification row names its links by ids (so that it has a key); the
    rows' other problems are reported by :mod:`assur`."""
    return isinstance(row, dict) and all(
        isinstance(row.get(key), (int, str, type(None))) and not isinstance(row.get(key), bool)
        for key in ("i", "j"))


def _deg(v: Any) -> float:
    return math.radians(v) if is_number(v) else math.nan


def _num(v: Any) -> float:
    return float(v) if is_number(v) else math.nan
