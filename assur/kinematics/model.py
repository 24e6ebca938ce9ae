"""The kinematic model of a mechanism: the DGTU parameters of every Assur group.

A :class:`KinematicModel` holds, in layering order, one :class:`GroupModel` per group (the
input group L0 first) and one flat table of named parameters. The names are
``"<group label>.<column>"`` with the columns of ``method.md`` §4.3, e.g. ``"L0(1).l_1"``,
``"L1(2,3).l_i"``, ``"L4(4,5).beta_i"``. Parameters are kept in table units (mm and
degrees); any of them may be replaced by an array shaped ``(D, 1)`` to evaluate D candidate
designs in one call (:meth:`KinematicModel.with_params`).

Two builders:

* :func:`model_from_sketch` — from the ``geometry:`` section of a chain table: the joint
  coordinates at one reference position, as a student sketches the mechanism; lengths,
  attachment points, guide directions relative to their carriers and every assembly variant
  are derived from the sketch (``docs/kinematics.md``);
* :func:`model_from_params` — from the ``params:`` of the rows of an identification table
  (the parameter columns of ``method.md`` §4.3).

:func:`build_model` picks the right one; :func:`load_model` reads a table file.
"""

from __future__ import annotations

import cmath
import difflib
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from assur.io.chain_table import group_key
from assur.errors import Issue, StructureError, TableError
from assur.model import LinkId, PairId, PairType
from assur.io.reader import MISSING, Node, TableReader, describe, normalise_id
from assur.text import Message

__all__ = [
    "KIND_COLUMNS",
    "Anchor",
    "GroupModel",
    "Guide",
    "KinematicModel",
    "TracePoint",
    "build_model",
    "is_angle",
    "load_model",
    "model_from_params",
    "model_from_sketch",
]

#: Parameter columns of each group kind, in the fixed order of tables 2.1–2.6.
KIND_COLUMNS: dict[int, tuple[str, ...]] = {
    0: ("x_O1", "y_O1", "l_1", "phi_1_0"),
    1: ("x_Hi", "y_Hi", "x_Hj", "y_Hj", "l_i", "l_j", "l_N", "beta_N", "l_M", "beta_M"),
    2: ("x_Hj", "y_Hj", "l_j", "x_Ak", "y_Ak", "beta_g", "e", "l_N", "beta_N", "l_M", "beta_M"),
    3: ("x_Hi", "y_Hi", "x_Hj", "y_Hj", "d", "l_N", "beta_N", "l_M", "beta_M"),
    4: ("x_Ak", "y_Ak", "beta_i", "e_i", "x_Bk", "y_Bk", "beta_j", "e_j", "l_N", "beta_N",
        "l_M", "beta_M"),
    5: ("x_Hj", "y_Hj", "gamma", "x_Ak", "y_Ak", "beta_S", "e", "l_N", "beta_N", "l_M",
        "beta_M"),
}

#: Columns of the external hinges H_i, H_j of a dyad.
_HINGE_COLUMNS = {"i": ("x_Hi", "y_Hi"), "j": ("x_Hj", "y_Hj")}

#: Columns (base x, y, direction β, offset e) of the external guides of a dyad, by kind and side.
_GUIDE_COLUMNS: dict[tuple[int, str], tuple[str, str, str, str | None]] = {
    (2, "i"): ("x_Ak", "y_Ak", "beta_g", "e"),
    (4, "i"): ("x_Ak", "y_Ak", "beta_i", "e_i"),
    (4, "j"): ("x_Bk", "y_Bk", "beta_j", "e_j"),
    (5, "i"): ("x_Ak", "y_Ak", "beta_S", "e"),
}

#: The symbol of a value supplied by an earlier group (``method.md`` §4.3).
SUPPLIED = "A"

_KIND_NAMES = {0: "input group", 1: "RRR", 2: "RRP", 3: "RPR", 4: "PRP", 5: "RPP"}
_RESERVED = ("input", "tracing", "margin")


def is_angle(column: str) -> bool:
    """Whether a column holds an angle (degrees in tables, radians inside the program)."""
    return column.startswith(("beta", "phi", "gamma"))


@dataclass(frozen=True, slots=True)
class Anchor:
    """A point fixed on a link, given by two parameter columns of a group.

    On the frame the columns are absolute coordinates ``x, y``. On a moving link they are
    either polar ``l, β`` (attachment points N, M, tracing points) or Cartesian ``a, b``
    (guide base points) in the link's local frame (``method.md`` §2.0). ``second`` None
    means 0 (the crank pin lies on the crank's axis).
    """

    link: LinkId
    owner: str
    first: str
    second: str | None
    polar: bool


@dataclass(frozen=True, slots=True)
class Guide:
    """The guide of a prismatic pair: carrier link, base point, direction, offset.

    The direction is ``φ_carrier + β`` (``β`` absolute on the frame); the slider's reference
    point runs along ``base + e·n(θ) + S·u(θ)``.
    """

    pair: PairId
    carrier: LinkId
    base: Anchor
    beta: str
    offset: str | None


@dataclass(frozen=True, slots=True)
class TracePoint:
    """A named point fixed on a link (a tracing point Ж), polar in the link's frame."""

    name: str
    anchor: Anchor


@dataclass(frozen=True, slots=True)
class GroupModel:
    """The kinematic model of one group (L0..L5).

    Parameters
    ----------
    label : str
        ``"L<kind>(<i>,<j>)"``, the prefix of the group's parameter names.
    kind : int
        0 (input group) or 1..5 (dyad kinds L1..L5).
    seq : int
        Ordinal in the layering order, L0 = 1 (the index k of base points A_k, B_k).
    i, j : link id
        The group's links (j None for L0).
    sigma : int
        Assembly variant σ = ±1 (L1, L2, L3); 1 where the kind has none.
    hinge_i, hinge_j : Anchor or None
        External revolute joints H_i, H_j (O_1 for L0).
    guide_i, guide_j : Guide or None
        External prismatic guides of links i and j.
    pairs : mapping
        Role → pair id: ``"H_i"``, ``"H_j"``, ``"C"`` (revolute) and ``"P_i"``, ``"P_j"``,
        ``"P_c"`` (prismatic).
    driven : {'i', 'j'} or None
        The RRR side whose length is the input coordinate (a linear actuator).
    composite : tuple of link ids
        Members of the actuator's composite link (cylinder, rod), when ``driven`` is set.
    """

    label: str
    kind: int
    seq: int
    i: LinkId
    j: LinkId | None
    sigma: int = 1
    hinge_i: Anchor | None = None
    hinge_j: Anchor | None = None
    guide_i: Guide | None = None
    guide_j: Guide | None = None
    pairs: Mapping[str, PairId] = field(default_factory=dict)
    driven: str | None = None
    composite: tuple[LinkId, ...] = ()

    @property
    def name(self) -> str:
        """Kind and links for reports, e.g. ``'L1 RRR (2, 3)'``."""
        links = f"{self.i}" if self.j is None else f"{self.i}, {self.j}"
        return f"L{self.kind} {_KIND_NAMES[self.kind]} ({links})"

    def column(self, name: str) -> str:
        """Full parameter name of one of this group's columns."""
        return f"{self.label}.{name}"


@dataclass(frozen=True)
class KinematicModel:
    """A mechanism ready for kinematic analysis.

    Parameters
    ----------
    name : str
        Label for reports.
    frame : link id
        The fixed link.
    groups : tuple of GroupModel
        Layering order, the input group first.
    params : mapping
        Parameter name → value (float or array broadcasting as ``(D, 1)``), table units.
    direction : int
        Input direction s = +1 (counter-clockwise) or −1 (clockwise) for a crank.
    drive : {'crank', 'actuator'}
        What the input coordinate q is: the crank rotation φ (radians, φ = 0 at the
        reference position) or the actuator length (mm).
    input_range : tuple of float
        The analysed interval of q: (0, 2π) for a full-turn crank, the stroke for an
        actuator.
    tracing : tuple of TracePoint
        Named tracing points.
    links : mapping
        Moving link → (group label, ``'i'`` or ``'j'``): which group solves its pose.
    pair_links : mapping
        Pair id → (type ``'R'``/``'P'``, the two links, guide carrier or None).
    bounds : mapping
        Parameter name → (lower, upper) where a table gave them.
    source : str
        The table the model was built from.
    """

    name: str
    frame: LinkId
    groups: tuple[GroupModel, ...]
    params: Mapping[str, Any]
    direction: int = 1
    drive: str = "crank"
    input_range: tuple[float, float] = (0.0, 2.0 * math.pi)
    tracing: tuple[TracePoint, ...] = ()
    links: Mapping[LinkId, tuple[str, str]] = field(default_factory=dict)
    pair_links: Mapping[PairId, tuple[str, tuple[LinkId, LinkId], LinkId | None]] = field(
        default_factory=dict)
    bounds: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    source: str = "<data>"

    def parameter_names(self) -> tuple[str, ...]:
        """Every parameter name, in layering order and column order."""
        return tuple(self.params)

    def group(self, label: str) -> GroupModel:
        """The group with this label."""
        for group in self.groups:
            if group.label == label:
                return group
        raise KeyError(f"no group {label!r}; groups: {', '.join(g.label for g in self.groups)}")

    def value(self, name: str) -> Any:
        """A parameter in program units (angles in radians)."""
        value = self.params[name]
        return np.radians(value) if is_angle(name.rsplit(".", 1)[-1]) else value

    def with_params(self, values: Mapping[str, Any]) -> KinematicModel:
        """A copy with some parameters replaced (e.g. by ``(D, 1)`` arrays of D designs).

        Raises
        ------
        KeyError
            For an unknown name, with the closest known names.
        """
        unknown = [name for name in values if name not in self.params]
        if unknown:
            hints = difflib.get_close_matches(unknown[0], list(self.params), n=3)
            raise KeyError(f"unknown parameter {unknown[0]!r}"
                           + (f"; did you mean {', '.join(map(repr, hints))}?" if hints else ""))
        params = dict(self.params)
        params.update({name: np.asarray(value, dtype=float) for name, value in values.items()})
        return replace(self, params=params)

    @property
    def design_shape(self) -> tuple[int, ...]:
        """Broadcast shape of the parameters (``()`` for one design, ``(D, 1)`` for D)."""
        return np.broadcast_shapes(*(np.shape(v) for v in self.params.values()))

    def parameter_table(self) -> list[dict[str, Any]]:
        """One row per group: label, kind, and every column in table order (or ``'A'``)."""
        rows = []
        for group in self.groups:
            row: dict[str, Any] = {"group": group.label, "L": group.kind}
            for column in KIND_COLUMNS[group.kind]:
                name = group.column(column)
                row[column] = _plain(self.params[name]) if name in self.params else SUPPLIED
            rows.append(row)
        return rows


def _plain(value: Any) -> Any:
    array = np.asarray(value)
    return float(array) if array.ndim == 0 else array.tolist()


# --------------------------------------------------------------------------- loading


def load_model(path: str | os.PathLike[str]) -> KinematicModel:
    """Read a chain table or an identification table and build its kinematic model.

    Raises
    ------
    TableError
        For a table problem (all problems at once).
    StructureError
        When the chain is not a class II mechanism with one input.
    """
    from assur.io.chain_table import load_chain
    from assur.structure.analysis import analyse_structure

    return build_model(analyse_structure(load_chain(path)))


def build_model(analysis: Any) -> KinematicModel:
    """The kinematic model of an analysed chain (from its sketch or from its row params)."""
    chain = analysis.chain
    if chain.geometry:
        return model_from_sketch(analysis)
    if chain.group_params:
        return model_from_params(analysis)
    raise TableError(chain.source, [Issue("geometry", "the table gives no dimensions: add a "
                                          "'geometry:' section (joint coordinates at one "
                                          "position) or 'params:' in the identification rows")])


class _Topology:
    """Roles of the pairs of an analysed chain, common to both builders."""

    def __init__(self, analysis: Any) -> None:
        chain = analysis.chain
        self.chain = chain
        self.frame = chain.frame
        if not analysis.decomposed:
            found = "; ".join(d.message for d in analysis.issues
                              if d.code.startswith("E")) or "links left over: " + ", ".join(
                                  map(str, analysis.leftover))
            raise StructureError(f"{chain.source}: the chain does not split into Assur groups, "
                                 f"so it has no kinematic model ({found}); see 'assur check'")
        if len(chain.inputs) != 1:
            raise StructureError(f"{chain.source}: kinematic analysis needs exactly one input; "
                                 f"found {len(chain.inputs)}")
        for group in analysis.groups:
            if group.group_class != 2:
                raise StructureError(f"{chain.source}: group {group.name} is of class "
                                     f"{group.group_class}; only dyads (class II) are solved")
        self.pairs = {pair.id: pair for pair in chain.pairs}
        self.drive = chain.inputs[0]
        self.groups = list(analysis.groups)
        self.composite_group = next((g for g in self.groups if g.composite), None)
        self.labels = {group: f"L{group.kind}({_link_text(group.i)},{_link_text(group.j)})"
                       for group in self.groups}

    def crank(self) -> tuple[LinkId, PairId]:
        """The crank and its driven pair (to the frame)."""
        drive = self.drive
        if drive.link is not None:
            link = drive.link
            pairs = [p for p in self.chain.pairs
                     if link in p.links and self.frame in p.links]
            if drive.pair is not None:
                pairs = [self.pairs[drive.pair]] if drive.pair in self.pairs else pairs
            if len(pairs) != 1 or pairs[0].type != PairType.R:
                raise StructureError(f"{self.chain.source}: the input link {link!r} must be a "
                                     f"crank hinged to the frame")
            return link, pairs[0].id
        raise AssertionError("not a crank drive")  # pragma: no cover

    def input_group(self) -> GroupModel:
        """The input group L0: the crank, hinged to the frame at O_1."""
        crank, driven = self.crank()
        label = f"L0({crank})"
        return GroupModel(label, 0, 1, crank, None,
                          hinge_i=Anchor(self.frame, label, "x_O1", "y_O1", False),
                          pairs={"H_i": driven})

    def pair_roles(self, group: Any) -> dict[str, PairId]:
        """Role → pair id of a dyad's external pairs i, j and its internal pair C."""
        ids = {"i": group.pair_i, "j": group.pair_j, "c": group.pair_c}
        return {role: ids[side] for role, side in _PAIR_ROLES[group.kind]}


#: The roles of a dyad's pairs i, c, j by kind, in the order the groups list them.
_PAIR_ROLES: dict[int, tuple[tuple[str, str], ...]] = {
    1: (("H_i", "i"), ("H_j", "j"), ("C", "c")),
    2: (("P_i", "i"), ("C", "c"), ("H_j", "j")),
    3: (("H_i", "i"), ("P_c", "c"), ("H_j", "j")),
    4: (("P_i", "i"), ("C", "c"), ("P_j", "j")),
    5: (("P_i", "i"), ("P_c", "c"), ("H_j", "j")),
}


def _link_text(link: Any) -> str:
    if isinstance(link, (tuple, frozenset, list, set)):
        return "+".join(str(x) for x in link)
    return str(link)


# ----------------------------------------------------------------------- sketch form


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _vector(value: Any) -> complex | None:
    if isinstance(value, list) and len(value) == 2 and all(_is_number(v) for v in value):
        return complex(value[0], value[1])
    return None


class _Sketch:
    """The ``geometry:`` section read through :class:`TableReader` (all problems at once)."""

    def __init__(self, chain: Any) -> None:
        self.reader = TableReader.from_data(chain.geometry, source=chain.source)
        raw = {normalise_id(k) if not isinstance(k, int) else k: v
               for k, v in chain.geometry.items()}
        self.raw = raw
        joints = {_joint_key(pair) for pair in chain.pairs}
        allowed = [str(j) for j in joints] + list(_RESERVED)
        for key in raw:
            if key not in joints and key not in _RESERVED:
                hint = difflib.get_close_matches(str(key), allowed, n=1, cutoff=0.5)
                tail = f"; did you mean {hint[0]!r}?" if hint else (
                    f"; expected a joint id ({', '.join(sorted(map(str, joints)))}) or one of "
                    f"{', '.join(_RESERVED)}")
                self.reader.add(f"geometry {key!r}", f"unknown key{tail}")
        self.points: dict[PairId, complex] = {}
        self.directions: dict[PairId, float] = {}
        for key in joints:
            if key in raw:
                self._joint(key, raw[key])

    def _joint(self, key: PairId, value: Any) -> None:
        where = f"geometry {key!r}"
        if not isinstance(value, dict):
            self.reader.add(where, f"expected {{point: [x, y]}} (and 'direction' for a slider "
                                   f"pair); found {describe(value)}")
            return
        node = Node(self.reader, where, value, ("point", "direction"))
        point = node.get("point", kind="list", required=False, default=None)
        if point is not None and point is not MISSING:
            vec = _vector(point)
            if vec is None:
                self.reader.add(f"{where} 'point'", f"expected two numbers [x, y] (mm); found "
                                                    f"{describe(point)}")
            else:
                self.points[key] = vec
        direction = node.get("direction", required=False, default=None)
        if direction is not None and direction is not MISSING:
            vec = _vector(direction)
            if _is_number(direction):
                self.directions[key] = math.radians(direction)
            elif vec is not None and vec != 0:
                self.directions[key] = cmath.phase(vec)
            else:
                self.reader.add(f"{where} 'direction'", f"expected an angle in degrees or a "
                                                        f"vector [dx, dy]; found "
                                                        f"{describe(direction)}")

    def point(self, pair: Any) -> complex | None:
        """The sketched point of a pair; None (and the problem recorded) when missing."""
        return self._entry(self.points, pair, pair.type.value,
                           "'point: [x, y]' at the reference position")

    def direction(self, pair: Any) -> float | None:
        """The sketched slide direction (radians); None (and recorded) when missing."""
        return self._entry(self.directions, pair, "slider", "'direction' (degrees or [dx, dy])")

    def _entry(self, entries: Mapping[PairId, Any], pair: Any, kind: str, needs: str) -> Any:
        key = _joint_key(pair)
        if key in entries:
            return entries[key]
        self.reader.add(f"geometry {key!r}", f"the {kind} pair {key!r} (links "
                                             f"{pair.links[0]}–{pair.links[1]}) needs {needs}")
        return None


def _joint_key(pair: Any) -> PairId:
    """The key of a pair in the sketch: its joint (origin) for a split compound hinge."""
    return pair.origin if pair.origin is not None else pair.id


class _Builder:
    """Collects groups, parameters and link frames while a model is built."""

    def __init__(self, topo: _Topology) -> None:
        self.topo = topo
        self.params: dict[str, Any] = {}
        self.groups: list[GroupModel] = []
        self.links: dict[LinkId, tuple[str, str]] = {}
        self.frames: dict[LinkId, tuple[complex, float]] = {topo.frame: (0j, 0.0)}
        self.attach_count: dict[LinkId, int] = {}
        self.owner: dict[LinkId, GroupModel] = {}
        self.bounds: dict[str, tuple[float, float]] = {}

    def put(self, label: str, column: str, value: float) -> None:
        self.params[f"{label}.{column}"] = float(value)

    def local(self, link: LinkId, point: complex) -> complex:
        origin, angle = self.frames[link]
        return (point - origin) * cmath.exp(-1j * angle)

    def attachment(self, link: LinkId, point: complex, label: str, side: str) -> Anchor:
        """Anchor of an external hinge of group ``label`` at ``point`` on ``link``."""
        if link == self.topo.frame:
            cols = _HINGE_COLUMNS[side]
            self.put(label, cols[0], point.real)
            self.put(label, cols[1], point.imag)
            return Anchor(link, label, cols[0], cols[1], False)
        owner = self.owner[link]
        count = self.attach_count.get(link, 0)
        self.attach_count[link] = count + 1
        if owner.kind == 0 and count == 0:
            self.put(owner.label, "l_1", abs(self.local(link, point)))
            return Anchor(link, owner.label, "l_1", None, True)
        letter = "N" if self.links[link][1] == "i" else "M"
        return self.polar(link, point, letter if count == 0 else f"{letter}{count + 1}")

    def polar(self, link: LinkId, point: complex, suffix: str) -> Anchor:
        """A point fixed on a moving link: columns ``l_<suffix>``, ``beta_<suffix>`` of its
        owner group, polar in the link's frame."""
        owner = self.owner[link]
        local = self.local(link, point)
        self.put(owner.label, f"l_{suffix}", abs(local))
        self.put(owner.label, f"beta_{suffix}", math.degrees(cmath.phase(local)))
        return Anchor(link, owner.label, f"l_{suffix}", f"beta_{suffix}", True)

    def guide(self, pair: Any, carrier: LinkId, base: complex, theta: float, label: str,
              cols: tuple[str, str, str, str | None], slider_point: complex | None) -> Guide:
        """A guide on ``carrier`` through ``base`` with absolute direction ``theta``."""
        x, y, beta, offset = cols
        origin_angle = self.frames[carrier][1]
        local = self.local(carrier, base)
        self.put(label, x, local.real)
        self.put(label, y, local.imag)
        self.put(label, beta, math.degrees(_wrap(theta - origin_angle)))
        if offset is not None:
            e = 0.0 if slider_point is None else _cross(cmath.exp(1j * theta), slider_point - base)
            self.put(label, offset, e)
        return Guide(pair.id, carrier, Anchor(carrier, label, x, y, False), beta, offset)

    def add(self, group: GroupModel, frame_i: tuple[complex, float] | None = None,
            frame_j: tuple[complex, float] | None = None) -> None:
        """Record a group: the owner and side of its links and, in the sketch form, their
        frames at the reference position."""
        self.groups.append(group)
        for link, side, frame in ((group.i, "i", frame_i), (group.j, "j", frame_j)):
            if link is None:
                continue
            if frame is not None:
                self.frames[link] = frame
            self.links[link] = (group.label, side)
            self.owner[link] = group
        if group.driven is not None:
            frame = frame_i if group.driven == "i" else frame_j
            for member in group.composite:
                self.frames[member] = frame
                self.links[member] = (group.label, group.driven)
                self.owner[member] = group


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _cross(a: complex, b: complex) -> float:
    return (a.conjugate() * b).imag


def _dot(a: complex, b: complex) -> float:
    return (a.conjugate() * b).real


def _sign(value: float) -> int:
    return -1 if value < 0 else 1


def model_from_sketch(analysis: Any) -> KinematicModel:
    """Build the model from a chain's ``geometry:`` sketch (joint coordinates at φ = 0).

    The sketch gives ``point: [x, y]`` for every revolute joint and ``point`` plus
    ``direction`` (degrees, or a vector) for every slider pair; ``input: {rotation: ccw}``
    (or ``cw``; for an actuator ``stroke: [min, max]`` in mm); ``tracing: {name: {link: L,
    point: [x, y]}}``; ``margin: δ`` (one number, or a mapping group label → δ). Every
    length, attachment point, guide direction relative to its carrier and assembly variant
    follows from the sketch.

    Raises
    ------
    TableError
        Listing every missing or invalid entry of the sketch.
    StructureError
        For a chain that is not a class II mechanism with one input.
    """
    topo = _Topology(analysis)
    sketch = _Sketch(topo.chain)
    build = _Builder(topo)
    inp = _read_input(sketch.reader, sketch.raw.get("input"), topo)
    if topo.composite_group is None:
        _sketch_crank(topo, sketch, build)
    for seq, group in enumerate(topo.groups, start=2):
        _sketch_group(topo, sketch, build, group, seq)
    tracing = _read_tracing(sketch, build)
    margins = _read_margin(sketch.reader, sketch.raw.get("margin"), build)
    sketch.reader.raise_if_any()
    for label, delta in margins.items():
        build.params[f"{label}.delta"] = float(delta)
    drive, direction, span = inp
    if drive == "actuator" and span is None:
        group = build.groups[0]
        length = build.params[group.column("l_i" if group.driven == "i" else "l_j")]
        span = (length, length)
    return KinematicModel(name=topo.chain.name, frame=topo.frame, groups=tuple(build.groups),
                          params=_ordered(build), direction=direction, drive=drive,
                          input_range=span or (0.0, 2 * math.pi), tracing=tracing,
                          links=build.links, pair_links=_pair_links(topo),
                          source=topo.chain.source)


def _ordered(build: _Builder) -> dict[str, Any]:
    """Parameters in layering and column order; every dyad gets its margin δ (default 0)."""
    out: dict[str, Any] = {}
    for group in build.groups:
        if group.kind != 0:
            build.params.setdefault(group.column("delta"), 0.0)
        extra = sorted(k for k in build.params if k.startswith(group.label + ".")
                       and k.split(".", 1)[1] not in KIND_COLUMNS[group.kind])
        for column in KIND_COLUMNS[group.kind]:
            name = group.column(column)
            if name in build.params:
                out[name] = build.params[name]
        for name in extra:
            out[name] = build.params[name]
    return out


def _pair_links(topo: _Topology) -> dict[PairId, tuple[str, tuple[LinkId, LinkId], LinkId | None]]:
    return {p.id: (p.type.value, p.links, p.guide) for p in topo.chain.pairs}


def _read_input(reader: TableReader, value: Any, topo: _Topology
                ) -> tuple[str, int, tuple[float, float] | None]:
    actuator = topo.composite_group is not None
    if value is None:
        return ("actuator" if actuator else "crank", 1, None)
    if not isinstance(value, dict):
        reader.add("geometry 'input'", f"expected {{rotation: ccw}} or {{stroke: [min, max]}}; "
                                       f"found {describe(value)}")
        return ("crank", 1, None)
    node = Node(reader, "geometry 'input'", value, ("rotation", "stroke"))
    if actuator:
        stroke = node.get("stroke", kind="list", required=False, default=None)
        span = None
        if stroke not in (None, MISSING):
            vec = _vector(stroke)
            if vec is None or not 0 < vec.real < vec.imag:
                reader.add("geometry 'input' 'stroke'", f"expected [min, max] actuator lengths "
                                                        f"(mm), 0 < min < max; found "
                                                        f"{describe(stroke)}")
            else:
                span = (vec.real, vec.imag)
        return ("actuator", 1, span)
    rotation = node.choice("rotation", ["ccw", "cw"], required=False, default="ccw")
    return ("crank", -1 if rotation == "cw" else 1, None)


def _read_tracing(sketch: _Sketch, build: _Builder) -> tuple[TracePoint, ...]:
    value = sketch.raw.get("tracing")
    if value is None:
        return ()
    reader = sketch.reader
    if not isinstance(value, dict):
        reader.add("geometry 'tracing'", f"expected {{name: {{link: L, point: [x, y]}}}}; "
                                         f"found {describe(value)}")
        return ()
    points = []
    for name, row in value.items():
        where = f"geometry.tracing {name!r}"
        if not isinstance(row, dict):
            reader.add(where, f"expected {{link: L, point: [x, y]}}; found {describe(row)}")
            continue
        node = Node(reader, where, row, ("link", "point"))
        link = node.get("link", kind="id")
        point = _vector(node.get("point", kind="list"))
        if link is MISSING or point is None:
            if point is None and node.has("point"):
                reader.add(f"{where} 'point'", "expected two numbers [x, y] (mm)")
            continue
        if link not in build.frames or link == build.topo.frame:
            reader.add(f"{where} 'link'", f"expected a moving link of the mechanism; found "
                                          f"{describe(link)}")
            continue
        points.append(TracePoint(str(name), build.polar(link, point, f"{name}")))
    return tuple(points)


def _read_margin(reader: TableReader, value: Any, build: _Builder) -> dict[str, float]:
    labels = [g.label for g in build.groups if g.kind != 0]

    def ok(v: Any) -> bool:
        return isinstance(v, (int, float)) and not isinstance(v, bool) and 0 <= v < 1

    if value is None:
        return {}
    if ok(value):
        return {label: float(value) for label in labels}
    if isinstance(value, dict):
        node = Node(reader, "geometry 'margin'", value, labels)
        out = {}
        for label in labels:
            v = node.get(label, kind="number", required=False, default=None,
                         check=lambda v: None if 0 <= v < 1 else Message("rule.margin"))
            if v not in (None, MISSING):
                out[label] = v
        return out
    reader.add("geometry 'margin'", f"expected δ in [0, 1) or a mapping group → δ; found "
                                    f"{describe(value)}")
    return {}


def _sketch_crank(topo: _Topology, sketch: _Sketch, build: _Builder) -> None:
    group = topo.input_group()
    crank, driven, label = group.i, group.pairs["H_i"], group.label
    pivot = sketch.point(topo.pairs[driven])
    pins = [p for p in topo.chain.pairs if crank in p.links and p.id != driven]
    pin = sketch.point(pins[0]) if pins else None
    if pivot is None or pin is None:
        return  # recorded; the groups hinged to the crank are skipped too
    if pin == pivot:
        sketch.reader.add(f"geometry {_joint_key(pins[0])!r}", "the crank pin coincides with the "
                                                          "crank pivot (zero crank length)")
        return
    angle = cmath.phase(pin - pivot)
    build.put(label, "x_O1", pivot.real)
    build.put(label, "y_O1", pivot.imag)
    build.add(group, (pivot, angle), None)
    build.put(label, "l_1", abs(pin - pivot))
    build.put(label, "phi_1_0", math.degrees(angle))


def _sketch_group(topo: _Topology, sketch: _Sketch, build: _Builder, group: Any,
                  seq: int) -> None:
    label = topo.labels[group]
    pi, pj, pc = (topo.pairs[group.pair_i], topo.pairs[group.pair_j], topo.pairs[group.pair_c])
    roles = topo.pair_roles(group)
    kind = group.kind
    i_prev, j_prev = group.i_minus_1, group.j_minus_1
    reader = sketch.reader
    if i_prev not in build.frames or j_prev not in build.frames:
        return  # an earlier group could not be built; its problem is already recorded
    count = len(reader.issues)

    def need(values: list[Any]) -> bool:
        return all(v is not None for v in values) and len(reader.issues) == count

    if kind == 1:
        hi, hj, c = sketch.point(pi), sketch.point(pj), sketch.point(pc)
        if not need([hi, hj, c]):
            return
        driven = _composite_side(group) if group.composite else None
        anchor_i = build.attachment(i_prev, hi, label, "i")
        anchor_j = build.attachment(j_prev, hj, label, "j")
        build.put(label, "l_i", abs(c - hi))
        build.put(label, "l_j", abs(c - hj))
        sigma = _sign(_cross(hj - hi, c - hi))
        model = GroupModel(label, 1, seq, group.i, group.j, sigma, anchor_i, anchor_j,
                           pairs=roles, driven=driven,
                           composite=tuple(group.composite or ()))
        build.add(model, (hi, cmath.phase(c - hi)), (hj, cmath.phase(c - hj)))
    elif kind == 2:
        c, hj, base, theta = (sketch.point(pc), sketch.point(pj), sketch.point(pi),
                              sketch.direction(pi))
        if not need([c, hj, base, theta]):
            return
        anchor_j = build.attachment(j_prev, hj, label, "j")
        build.put(label, "l_j", abs(c - hj))
        guide = build.guide(pi, i_prev, base, theta, label, _GUIDE_COLUMNS[2, "i"], c)
        sigma = _sign(_dot(c - hj, cmath.exp(1j * theta)))
        model = GroupModel(label, 2, seq, group.i, group.j, sigma, None, anchor_j, guide,
                           pairs=roles)
        build.add(model, (c, theta), (hj, cmath.phase(c - hj)))
    elif kind == 3:
        hi, hj, theta = sketch.point(pi), sketch.point(pj), sketch.direction(pc)
        if not need([hi, hj, theta]):
            return
        anchor_i = build.attachment(i_prev, hi, label, "i")
        anchor_j = build.attachment(j_prev, hj, label, "j")
        axis = cmath.exp(1j * theta)
        build.put(label, "d", _cross(axis, hj - hi))
        sigma = _sign(_dot(axis, hj - hi))
        model = GroupModel(label, 3, seq, group.i, group.j, sigma, anchor_i, anchor_j,
                           pairs=roles)
        build.add(model, (hi, theta), (hj, theta))
    elif kind == 4:
        c = sketch.point(pc)
        a, ti, b, tj = (sketch.point(pi), sketch.direction(pi), sketch.point(pj),
                        sketch.direction(pj))
        if not need([c, a, ti, b, tj]):
            return
        gi = build.guide(pi, i_prev, a, ti, label, _GUIDE_COLUMNS[4, "i"], c)
        gj = build.guide(pj, j_prev, b, tj, label, _GUIDE_COLUMNS[4, "j"], c)
        model = GroupModel(label, 4, seq, group.i, group.j, 1, None, None, gi, gj,
                           pairs=roles)
        build.add(model, (c, ti), (c, tj))
    elif kind == 5:
        hj, a, ts, tt = (sketch.point(pj), sketch.point(pi), sketch.direction(pi),
                         sketch.direction(pc))
        if not need([hj, a, ts, tt]):
            return
        us, ut = cmath.exp(1j * ts), cmath.exp(1j * tt)
        denominator = _cross(ut, us)
        if abs(denominator) < 1e-12:
            reader.add(f"geometry {_joint_key(pc)!r} 'direction'",
                       f"the guides of group {label} are parallel: the group cannot be "
                       f"assembled")
            return
        c = hj + _cross(a - hj, us) / denominator * ut
        anchor_j = build.attachment(j_prev, hj, label, "j")
        build.put(label, "gamma", math.degrees(_wrap(tt - ts)))
        gi = build.guide(pi, i_prev, a, ts, label, _GUIDE_COLUMNS[5, "i"], c)
        model = GroupModel(label, 5, seq, group.i, group.j, 1, None, anchor_j, gi,
                           pairs=roles)
        build.add(model, (c, ts), (hj, tt))
    else:  # pragma: no cover - the structure analyzer gives kinds 1..5 only
        raise StructureError(f"unsupported group kind {kind}")


def _composite_side(group: Any) -> str:
    members = set(group.composite)
    link_i = group.i if not isinstance(group.i, (tuple, frozenset)) else set(group.i)
    if isinstance(link_i, set):
        return "i" if link_i & members else "j"
    return "i" if link_i in members or _link_text(group.i) == "+".join(map(str, members)) \
        else "j"


# ---------------------------------------------------------------- identification form


def model_from_params(analysis: Any) -> KinematicModel:
    """Build the model from the ``params:`` of the identification-table rows.

    Every row lists the columns of its kind (``KIND_COLUMNS``): a number, ``'A'`` for a
    value supplied by an earlier group, or ``[initial, lower, upper]`` (tables 2.1–2.6; the
    bounds are kept in :attr:`KinematicModel.bounds`). Coordinates of a hinge on a moving
    link are always supplied: the hinge is the attachment point N/M (the crank pin for
    L0) of its link's group. A guide base point on a moving carrier is given in the
    carrier's local frame; ``'A'`` puts it at the carrier's origin hinge. The assembly
    variant is the row's ``variant`` (L3: 0 means +1). Extra keys: ``delta`` (margin),
    ``s`` (on L0: +1 counter-clockwise, −1 clockwise), ``l_<name>``/``beta_<name>``
    tracing points with ``tracing: [name, ...]`` on the row of the carrying link.
    """
    topo = _Topology(analysis)
    chain = topo.chain
    reader = TableReader.from_data({}, source=chain.source)
    build = _Builder(topo)
    rows = chain.group_params
    variants = {group_key(row): row.get("variant") for row in chain.identification or ()}
    if topo.composite_group is not None:
        raise StructureError(f"{chain.source}: an actuator input needs the chain form with a "
                             f"'geometry:' sketch")
    group0 = topo.input_group()
    crank, label0 = group0.i, group0.label
    direction = 1
    node0 = _param_node(reader, rows, (crank,), label0, 0)
    _param_values(node0, 0, build, label0, supplied_ok=False)
    if node0 is not None:
        s = node0.get("s", kind="int", required=False, default=1,
                      check=lambda v: None if v in (1, -1) else
                      Message("rule.plus_minus_one", {"name": "s"}))
        direction = s if s in (1, -1) else 1
    build.add(group0)
    tracing: list[TracePoint] = []
    for seq, group in enumerate(topo.groups, start=2):
        label = topo.labels[group]
        key = (group.i, group.j)
        node = _param_node(reader, rows, key, label, group.kind)
        _param_values(node, group.kind, build, label, supplied_ok=True)
        model = _param_group(topo, build, group, label, seq, variants.get(key), reader, node)
        build.add(model)
        tracing.extend(_param_tracing(node, model, build))
    reader.raise_if_any()
    return KinematicModel(name=chain.name, frame=topo.frame, groups=tuple(build.groups),
                          params=_ordered(build), direction=direction, drive="crank",
                          tracing=tuple(tracing), links=build.links, pair_links=_pair_links(topo),
                          bounds=build.bounds, source=chain.source)


def _param_node(reader: TableReader, rows: dict[Any, Any], key: tuple[Any, ...], label: str,
                kind: int) -> Node | None:
    where = f"structure_identification ({label}) 'params'"
    value = rows.get(key)
    if value is None:
        reader.add(where, f"the row of group {label} has no 'params:'; expected the columns "
                          f"{', '.join(KIND_COLUMNS[kind])}")
        return None
    return Node(reader, where, value, None)  # the columns are checked by _param_values


def _param_values(node: Node | None, kind: int, build: _Builder, label: str, *,
                  supplied_ok: bool) -> None:
    if node is None:
        return
    allowed = set(KIND_COLUMNS[kind]) | {"delta", "tracing"} | ({"s"} if kind == 0 else set())
    extra = set()
    for key in node.mapping:
        if key in allowed:
            continue
        if isinstance(key, str) and key.startswith(("l_", "beta_")):
            extra.add(key)
            continue
        hint = difflib.get_close_matches(str(key), sorted(allowed), n=1, cutoff=0.6)
        node.reader.add(node.location, f"unknown column {key!r}" + (
            f"; did you mean {hint[0]!r}?" if hint else
            f"; the columns of L{kind} are {', '.join(KIND_COLUMNS[kind])}"))
    for column in (*KIND_COLUMNS[kind], "delta", *sorted(extra)):
        raw = node.mapping.get(column, MISSING)
        if raw is MISSING:
            if column == "delta":
                continue
            node.reader.add(f"{node.location} {column!r}", "this column is missing; write 0 for "
                                                           "an absent parameter, 'A' for one "
                                                           "supplied by an earlier group")
            continue
        where = f"{node.location} {column!r}"
        if raw == SUPPLIED and supplied_ok and column.startswith(("x_", "y_")):
            continue  # checked against the link the point lies on (_param_anchor, _param_guide)
        if raw == SUPPLIED:
            node.reader.add(where, "expected a number; 'A' (supplied by an earlier group) "
                                   "applies only to coordinates of points on moving links")
            continue
        if isinstance(raw, list) and len(raw) == 3 and all(_is_number(v) for v in raw):
            value, lo, hi = (float(v) for v in raw)
            if not lo <= value <= hi:
                node.reader.add(where, f"expected [initial, lower, upper] with lower ≤ initial "
                                       f"≤ upper; found {raw}")
                continue
            build.bounds[f"{label}.{column}"] = (lo, hi)
        elif _is_number(raw):
            value = float(raw)
        else:
            node.reader.add(where, f"expected a number, 'A' (supplied by an earlier group) or "
                                   f"[initial, lower, upper]; found {describe(raw)}")
            continue
        build.params[f"{label}.{column}"] = value


def _param_anchor(topo: _Topology, build: _Builder, link: LinkId, label: str,
                  cols: tuple[str, str], reader: TableReader, node: Node | None) -> Anchor:
    """An external hinge: absolute columns on the frame, supplied N/M on a moving link."""
    if link == topo.frame:
        _need_numbers(cols, reader, node, "the hinge lies on the frame")
        return Anchor(link, label, cols[0], cols[1], False)
    if node is not None:
        for col in cols:
            if node.mapping.get(col) not in (SUPPLIED, None):
                reader.add(f"{node.location} {col!r}", f"the hinge lies on moving link "
                                                       f"{link!r}: its coordinates are supplied "
                                                       f"by that link's group; expected 'A'; "
                                                       f"found {describe(node.mapping.get(col))}")
    owner = build.owner.get(link)
    if owner is None:  # pragma: no cover - the layering order guarantees the owner exists
        raise StructureError(f"link {link!r} is used before its group is solved")
    if owner.kind == 0:
        return Anchor(link, owner.label, "l_1", None, True)
    letter = "N" if build.links[link][1] == "i" else "M"
    return Anchor(link, owner.label, f"l_{letter}", f"beta_{letter}", True)


def _need_numbers(cols: tuple[str, ...], reader: TableReader, node: Node | None,
                  why: str) -> None:
    """Report coordinate columns written 'A' although the point is on the frame."""
    for col in cols:
        if node is not None and node.mapping.get(col) == SUPPLIED:
            reader.add(f"{node.location} {col!r}", f"{why}: expected its coordinate (mm); "
                                                   f"found 'A'")


def _param_guide(topo: _Topology, build: _Builder, pair: Any, carrier: LinkId, label: str,
                 cols: tuple[str, str, str, str | None], reader: TableReader,
                 node: Node | None) -> Guide:
    x, y, beta, offset = cols
    if carrier == topo.frame:
        _need_numbers((x, y), reader, node, "the guide is on the frame")
    for col in (x, y):
        name = f"{label}.{col}"
        if name not in build.params:
            # 'A' on a moving carrier: the base point is the carrier's origin hinge
            build.params[name] = 0.0
    return Guide(pair.id, carrier, Anchor(carrier, label, x, y, False), beta, offset)


def _param_group(topo: _Topology, build: _Builder, group: Any, label: str, seq: int,
                 variant: Any, reader: TableReader, node: Node | None) -> GroupModel:
    pi, pj = topo.pairs[group.pair_i], topo.pairs[group.pair_j]
    roles = topo.pair_roles(group)
    kind = group.kind
    i_prev, j_prev = group.i_minus_1, group.j_minus_1
    sigma = 1 if variant in (None, 0) else _sign(variant)

    def hinge(link: LinkId, cols: tuple[str, str]) -> Anchor:
        return _param_anchor(topo, build, link, label, cols, reader, node)

    def guide(pair: Any, carrier: LinkId, cols: tuple[str, str, str, str | None]) -> Guide:
        return _param_guide(topo, build, pair, carrier, label, cols, reader, node)

    if kind in (1, 3):
        return GroupModel(label, kind, seq, group.i, group.j, sigma,
                          hinge(i_prev, _HINGE_COLUMNS["i"]), hinge(j_prev, _HINGE_COLUMNS["j"]),
                          pairs=roles)
    if kind == 2:
        return GroupModel(label, 2, seq, group.i, group.j, sigma, None,
                          hinge(j_prev, _HINGE_COLUMNS["j"]),
                          guide(pi, i_prev, _GUIDE_COLUMNS[2, "i"]), pairs=roles)
    if kind == 4:
        return GroupModel(label, 4, seq, group.i, group.j, 1, None, None,
                          guide(pi, i_prev, _GUIDE_COLUMNS[4, "i"]),
                          guide(pj, j_prev, _GUIDE_COLUMNS[4, "j"]), pairs=roles)
    return GroupModel(label, 5, seq, group.i, group.j, 1, None,
                      hinge(j_prev, _HINGE_COLUMNS["j"]),
                      guide(pi, i_prev, _GUIDE_COLUMNS[5, "i"]), pairs=roles)


def _param_tracing(node: Node | None, group: GroupModel, build: _Builder
                   ) -> list[TracePoint]:
    if node is None:
        return []
    names = node.mapping.get("tracing") or []
    out = []
    for entry in names if isinstance(names, list) else []:
        if not isinstance(entry, dict) or set(entry) - {"name", "link"}:
            node.reader.add(f"{node.location} 'tracing'", f"expected rows {{name: Ж, link: L}} "
                                                          f"with columns l_<name>, "
                                                          f"beta_<name>; found {describe(entry)}")
            continue
        name, link = str(entry.get("name")), normalise_id(entry.get("link"))
        cols = (f"l_{name}", f"beta_{name}")
        if link not in (group.i, group.j) or any(group.column(c) not in build.params
                                                 for c in cols):
            node.reader.add(f"{node.location} 'tracing'", f"tracing point {name!r} needs link "
                                                          f"{group.i} or {group.j} and the "
                                                          f"columns {cols[0]}, {cols[1]}")
            continue
        out.append(TracePoint(name, Anchor(link, group.label, cols[0], cols[1], True)))
    return out
