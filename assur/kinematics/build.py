"""Builders of the kinematic model: from a chain's sketch, or from its rows' ``params:``.

* :func:`model_from_sketch` — from the chain's :class:`~assur.model.Sketch` (the joint
  coordinates at one reference position, as a student sketches the mechanism); lengths,
  attachment points, guide directions relative to their carriers and every assembly variant
  are derived from the sketch (``docs/kinematics.md``), by each kind's sketch rule
  (:attr:`assur.kinematics.rules.KindRules.sketch`), which works on a :class:`Builder`;
* :func:`model_from_params` — from the ``params:`` of the rows of an identification table
  (the parameter columns of ``method.md`` §4.3; each kind declares its hinge and guide
  columns in :mod:`assur.kinds`).

:func:`build_model` picks the right one; :func:`load_model` reads a table file, and
:func:`load_with_forces` its force sections too.

Examples
--------
>>> from assur.io.chain_table import chain_from_dict
>>> from assur.structure.analysis import analyse_structure
>>> chain = chain_from_dict({"mechanism": {"pairs": [
...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
...     {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
...     "inputs": [1]}, "geometry": {"A": {"point": [0, 0]}, "B": {"point": [0, 30]},
...     "C": {"point": [80, 60]}, "D": {"point": [100, 0]}}})
>>> model = build_model(analyse_structure(chain))
>>> [group.name for group in model.groups]
['L0 input-link group (1)', 'L1 RRR (2, 3)']
>>> round(model.params["L0(1).l_1"], 6)
30.0
"""

from __future__ import annotations

import cmath
import difflib
import math
import os
from collections.abc import Mapping
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.errors import Issue, StructureError, TableError
from assur.io.chain_table import load_chain
from assur.io.reader import Node, TableReader, describe, latin_form, lookalike_letters
from assur.kinds import KINDS, GroupKind, GuideColumns, HingeColumns, kind_of, kind_of_class
from assur.kinematics import jets as J
from assur.kinematics.laws import STROKE, InputLaw
from assur.kinematics.model import (
    KIND_COLUMNS,
    Anchor,
    GroupModel,
    Guide,
    KinematicModel,
    TracePoint,
)
from assur.kinematics.rules import rules_of
from assur.model import (
    CircleProfile,
    Drive,
    ForceData,
    GroupParams,
    LineProfile,
    LinkId,
    Pair,
    PairId,
    PairType,
    PolarProfile,
    Profile,
    Sketch,
    joint_key,
)
from assur.structure.analysis import StructuralAnalysis, analyse_structure
from assur.structure.classification import AssurGroup
from assur.text import Message, joined

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.higher.kind import Layout

__all__ = ["Builder", "Topology", "build_model", "load_model", "load_with_forces",
           "model_from_params", "model_from_sketch", "with_contacts"]


def load_model(path: str | os.PathLike[str]) -> KinematicModel:
    """Read a chain table or an identification table and build its kinematic model.

    Parameters
    ----------
    path : str or os.PathLike
        A chain table with a ``geometry:`` sketch, or an identification table with ``params:``.

    Returns
    -------
    KinematicModel
        The groups in layering order with their DGTU parameters.

    Raises
    ------
    TableError
        For a table problem (all problems at once).
    StructureError
        When the chain is not a class II mechanism with one input.

    Examples
    --------
    >>> import pathlib, assur
    >>> tables = pathlib.Path(assur.__file__).parents[1] / "input_tables"
    >>> model = assur.load_model(tables / "four_bar.yaml")
    >>> [group.label for group in model.groups]
    ['L0(1)', 'L1(2,3)']
    """
    return build_model(analyse_structure(load_chain(path)))


def load_with_forces(path: str | os.PathLike[str]
                     ) -> tuple[KinematicModel, ForceData | None]:
    """The kinematic model of a chain table and its force sections (``Chain.forces``).

    Parameters
    ----------
    path : str or os.PathLike
        A chain table with a ``geometry:`` sketch and, for the force analysis, ``masses:``,
        ``loads:`` or ``gravity:`` (``docs/forces.md`` §1).

    Returns
    -------
    model : KinematicModel
        As :func:`load_model` gives it.
    forces : ForceData or None
        None for a table with neither masses nor loads.

    Raises
    ------
    TableError
        For every problem of the table at once.
    StructureError
        When the chain is not a class II mechanism with one input.

    Examples
    --------
    >>> from pathlib import Path; import assur
    >>> TABLES = Path(assur.__file__).parents[1] / "input_tables"
    >>> model, data = load_with_forces(TABLES / "four_bar_gravity.yaml")
    >>> model.groups[1].label, data.gravity
    ('L1(2,3)', -9.81j)
    """
    chain = load_chain(path)
    return build_model(analyse_structure(chain)), chain.forces


def build_model(analysis: StructuralAnalysis) -> KinematicModel:
    """The kinematic model of an analysed chain (from its sketch or from its row params).

    Parameters
    ----------
    analysis : StructuralAnalysis

    Returns
    -------
    KinematicModel
        Built by :func:`model_from_sketch` or :func:`model_from_params`.

    Raises
    ------
    TableError
        When the table gives no dimensions, or for a problem of them.
    StructureError
        When the chain is not a class II mechanism with one input.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> model = assur.build_model(analysis)
    >>> [group.label for group in model.groups]
    ['L0(1)', 'L1(2,3)']
    """
    chain = analysis.chain
    if chain.geometry is not None:
        return with_contacts(analysis, model_from_sketch(analysis))
    if chain.group_params:
        return model_from_params(analysis)
    raise TableError(chain.source, [Issue("geometry", Message("model.no_dimensions", {}))])


def _face_normal(links: tuple[LinkId, LinkId], profiles: tuple[Profile, Profile],
                 follower: LinkId) -> complex | None:
    """The unit normal at the sketch of a straight profile touching a circle, from the cam
    towards the follower (the link ``follower`` of the pair); None without a straight one."""
    lines = [k for k, profile in enumerate(profiles) if isinstance(profile, LineProfile)]
    circles = [k for k, profile in enumerate(profiles) if isinstance(profile, CircleProfile)]
    if len(lines) != 1 or len(circles) != 1:
        return None
    line, circle = profiles[lines[0]], profiles[circles[0]]
    assert isinstance(line, LineProfile) and isinstance(circle, CircleProfile)
    normal = 1j * line.direction.unit
    if ((line.point - circle.centre) * normal.conjugate()).real < 0:  # centre → face
        normal = -normal
    return normal if links[lines[0]] == follower else -normal


def with_contacts(analysis: StructuralAnalysis, model: KinematicModel) -> KinematicModel:
    """The model of a replacing mechanism with the higher pairs its replacement does not
    hold for over the cycle: a tabulated cam profile, a gear mesh.

    The replacing links of circles and straight profiles join points fixed on their links,
    so the replacing mechanism's own groups move exactly like the original; a tabulated
    profile's centre of curvature moves on the cam, and a mesh's N₁N₂ stays on the carrier
    while the gears turn. The group of such a replacing link is solved through its contact
    (:class:`~assur.kinematics.contact.CamContact`,
    :class:`~assur.kinematics.contact.GearContact`), from the sketched position of the
    replacing mechanism (where it holds).

    Parameters
    ----------
    analysis : StructuralAnalysis
        The analysis of a chain (its replacing mechanism when it has higher pairs).
    model : KinematicModel
        The replacing mechanism's model from its sketch.

    Returns
    -------
    KinematicModel
        ``model`` with :attr:`~KinematicModel.contacts` (``model`` itself without any).

    Raises
    ------
    StructureError
        When such a replacing link is not in a dyad with the follower or the driven gear.
    """
    original = analysis.original
    if original is None or original.geometry is None:
        return model
    from assur.kinematics.analysis import analyse, sketch_input
    from assur.kinematics.contact import CamContact, ExactContact, GearContact, PolarSpline
    from assur.profiles import contact

    sketched = analyse(model, np.array([sketch_input(model)]))
    frames = {link: (complex(np.ravel(J.value(o))[0]), float(np.ravel(J.value(a))[0]))
              for link, (o, a) in sketched.frames.items()}

    def local(link: LinkId, point: complex) -> complex:
        origin, angle = frames.get(link, (0j, 0.0))
        return (point - origin) * cmath.exp(-1j * angle)

    def point(pair: PairId) -> complex:
        return complex(np.ravel(J.value(sketched.joints[pair]))[0])

    contacts: dict[str, CamContact | GearContact | ExactContact] = {}
    for item in analysis.replacements:
        higher = next(pair for pair in original.higher if pair.id == item.pair)
        profiles = original.geometry.profiles[higher.id]
        group = next((g for g in model.groups if item.link in g.members), None)
        tabulated = [isinstance(profile, PolarProfile) for profile in profiles]
        if higher.gear is None and not any(tabulated):
            if group is not None and group.layout is None:
                follower = next(m for m in group.members if m != item.link)
                face = _face_normal(higher.links, profiles, follower)
                contacts[group.label] = ExactContact(
                    higher.id, item.link,
                    None if face is None else face * cmath.exp(-1j * frames[follower][1]))
            continue
        if group is None or group.layout is not None or group.kind not in (1, 2) \
                or (group.kind == 2 and group.j != item.link):
            raise StructureError(Message("contact.unsupported_group",
                                         {"pair": higher.id, "link": item.link}))
        member = next(link for link in group.members if link != item.link)
        roles = group.pairs
        if higher.gear is not None:
            driver = next(link for link in higher.links if link not in group.members)
            first = higher.links[0] == driver
            anchor = group.hinge_j if group.i == item.link else group.hinge_i
            assert anchor is not None
            carrier = anchor.link
            ends = item.points if first else item.points[::-1]
            assert ends[0] is not None and ends[1] is not None
            radii = higher.gear.radii if first else higher.gear.radii[::-1]
            contacts[group.label] = GearContact(
                higher.id, driver, carrier, (radii[0], radii[1]), higher.gear.internal,
                (frames[driver][1], frames.get(carrier, (0j, 0.0))[1], frames[member][1]),
                (local(carrier, ends[0]), local(carrier, ends[1])), item.link)
            continue
        index = tabulated.index(True)
        table, other = profiles[index], profiles[1 - index]
        if not isinstance(other, CircleProfile) or other.concave:
            raise StructureError(Message("contact.unsupported_profile", {"pair": higher.id}))
        assert isinstance(table, PolarProfile)
        cam = higher.links[index]
        touch = contact(table, other)
        assert touch is not None  # the sketch reader refuses profiles that do not touch
        roller = point(roles["C"])
        if group.kind == 2:
            heading = cmath.exp(1j * float(np.ravel(J.value(sketched.sliders[roles["P_i"]]
                                                            .angle))[0]))
        else:
            pivot = point(roles["H_j"] if group.i == item.link else roles["H_i"])
            heading = 1j * (roller - pivot)
        away = 1 if (heading.conjugate() * touch.normal).real > 0 else -1
        contacts[group.label] = CamContact(
            higher.id, cam, PolarSpline.from_table(np.asarray(table.angles, dtype=float),
                                                   np.asarray(table.radii, dtype=float)),
            local(cam, table.centre), frames[cam][1], other.radius, item.link, away)
    return replace(model, contacts=contacts) if contacts else model


class Topology:
    """Roles of the pairs of an analysed chain, common to both builders."""

    def __init__(self, analysis: StructuralAnalysis) -> None:
        chain = analysis.chain
        self.chain = chain
        self.frame = chain.frame
        if not analysis.decomposed:
            errors = [d.message for d in analysis.issues if d.code.startswith("E")]
            found = (joined(errors, "term.clauses") if errors else Message(
                "structure.in_no_group", {"links": ", ".join(map(str, analysis.leftover))}))
            raise StructureError(Message("structure.no_model",
                                         {"source": chain.source, "found": found}))
        for group in analysis.groups:
            if group.kind is None and kind_of_class(group.group_class) is None:
                raise StructureError(Message("structure.unsolved_class", {
                    "source": chain.source, "group": group.name, "cls": group.group_class}))
        self.pairs = {pair.id: pair for pair in chain.pairs}
        self.drives = chain.inputs
        self.groups = list(analysis.groups)
        self.composite_group = next((g for g in self.groups if g.composite), None)
        self.labels = {id(group): f"{self.kind(group).code}("
                                  f"{','.join(_link_text(link) for link in _links(group))})"
                       for group in self.groups}

    @staticmethod
    def kind(group: AssurGroup) -> GroupKind:
        """The kind of an accepted dyad, triad or class IV group."""
        higher = kind_of_class(group.group_class) if group.kind is None else None
        return higher if higher is not None else kind_of(group.kind or 0)

    def label(self, group: AssurGroup) -> str:
        """The group's label, the prefix of its parameter names (``"L1(2,3)"``)."""
        return self.labels[id(group)]

    def on_frame(self, drive: Drive) -> tuple[LinkId, Pair] | None:
        """The driven link and its driven pair with the frame (a crank's hinge, a slider's
        guide); None for an actuator, a driven pair between two moving links."""
        if drive.link is None:
            pair = self.pairs.get(drive.pair) if drive.pair is not None else None
            if pair is None or self.frame not in pair.links:
                return None
            return pair.other(self.frame), pair
        link = drive.link
        pairs = [p for p in self.chain.pairs if link in p.links and self.frame in p.links]
        if drive.pair is not None:
            named = self.pairs.get(drive.pair)
            if named is not None and self.frame not in named.links:
                return None
            pairs = [named] if named is not None else pairs
        if len(pairs) != 1:
            raise StructureError(Message("structure.input_not_crank",
                                         {"source": self.chain.source, "link": link}))
        return link, pairs[0]

    def input_groups(self) -> list[GroupModel]:
        """The input groups L0: a crank hinged to the frame at O_1, or a slider on a frame
        guide through S (columns ``x_S``, ``y_S``, ``beta_S``), one per input on the frame."""
        groups = []
        for drive in self.drives:
            found = self.on_frame(drive)
            if found is None:
                continue
            link, pair = found
            label = f"L0({link})"
            if pair.type == PairType.R:
                groups.append(GroupModel(label, 0, 1, link, None,
                                         hinge_i=Anchor(self.frame, label, "x_O1", "y_O1", False),
                                         pairs={"H_i": pair.id}))
            else:
                guide = Guide(pair.id, self.frame, Anchor(self.frame, label, "x_S", "y_S", False),
                              "beta_S", None)
                groups.append(GroupModel(label, 0, 1, link, None, guide_i=guide,
                                         pairs={"P_i": pair.id}))
        return groups

    def dyad_pairs(self, group: AssurGroup) -> tuple[Pair, Pair, Pair]:
        """The external pair of i, the external pair of j and the internal pair."""
        i, j, c = group.pair_i, group.pair_j, group.pair_c
        assert i is not None and j is not None and c is not None
        return self.pairs[i], self.pairs[j], self.pairs[c]

    def pair_roles(self, group: AssurGroup) -> dict[str, PairId]:
        """Role → pair id of a dyad's external pairs i, j and its internal pair C."""
        ids = {"i": group.pair_i, "j": group.pair_j, "c": group.pair_c}
        return {role: pair for role, side in self.kind(group).roles
                if (pair := ids[side]) is not None}


def _links(group: AssurGroup) -> tuple[Any, ...]:
    """The links named in a group's label: i and j of a dyad, every link of a higher group."""
    return (group.i, group.j) if group.kind is not None else group.links


def _link_text(link: object) -> str:
    if isinstance(link, (tuple, frozenset, list, set)):
        return "+".join(str(x) for x in link)
    return str(link)


class Builder:
    """Collects groups, parameters and link frames while a model is built.

    Problems found while building (they depend on the structure, not only on the table) are
    recorded in ``reader`` and raised together at the end. Each kind's sketch rule
    (:mod:`assur.kinematics.rules`) reads the sketch and enters the group's parameters,
    anchors and guides through it.
    """

    def __init__(self, topo: Topology, sketch: Sketch | None = None) -> None:
        self.topo = topo
        self.sketch = sketch
        self.reader = TableReader.from_data({}, source=topo.chain.source)
        self.params: dict[str, Any] = {}
        self.groups: list[GroupModel] = []
        self.links: dict[LinkId, tuple[str, str]] = {}
        self.frames: dict[LinkId, tuple[complex, float]] = {topo.frame: (0j, 0.0)}
        self.attach_count: dict[LinkId, int] = {}
        self.owner: dict[LinkId, GroupModel] = {}

    def point(self, pair: Pair) -> complex:
        """The sketched point of a pair."""
        assert self.sketch is not None
        return self.sketch.points[joint_key(pair)]

    def direction(self, pair: Pair) -> float:
        """The sketched slide direction of a prismatic pair (radians)."""
        assert self.sketch is not None
        return self.sketch.directions[joint_key(pair)].angle

    def problem(self, location: str, code: str, /, **data: Any) -> None:
        """Record a problem found while building."""
        self.reader.problem(location, code, **data)

    def put(self, label: str, column: str, value: float) -> None:
        self.params[f"{label}.{column}"] = float(value)

    def local(self, link: LinkId, point: complex) -> complex:
        origin, angle = self.frames[link]
        return (point - origin) * cmath.exp(-1j * angle)

    def attachment(self, link: LinkId, point: complex, label: str,
                   cols: HingeColumns) -> Anchor:
        """Anchor of an external hinge of group ``label`` at ``point`` on ``link``."""
        if link == self.topo.frame:
            self.put(label, cols[0], point.real)
            self.put(label, cols[1], point.imag)
            return Anchor(link, label, cols[0], cols[1], False)
        owner = self.owner[link]
        count = self.attach_count.get(link, 0)
        self.attach_count[link] = count + 1
        local = self.local(link, point)
        if owner.hinge_i is not None and owner.group_kind.is_input and count == 0 and \
                abs(local.imag) <= 1e-9 * max(abs(local), 1.0) and local.real > 0:
            self.put(owner.label, "l_1", abs(local))
            return Anchor(link, owner.label, "l_1", None, True)
        letter = _LETTERS.get(self.links[link][1], self.links[link][1])
        return self.polar(link, point, letter if count == 0 else f"{letter}{count + 1}")

    def polar(self, link: LinkId, point: complex, suffix: str) -> Anchor:
        """A point fixed on a moving link: columns ``l_<suffix>``, ``beta_<suffix>`` of its
        owner group, polar in the link's frame."""
        owner = self.owner[link]
        local = self.local(link, point)
        self.put(owner.label, f"l_{suffix}", abs(local))
        self.put(owner.label, f"beta_{suffix}", math.degrees(cmath.phase(local)))
        return Anchor(link, owner.label, f"l_{suffix}", f"beta_{suffix}", True)

    def guide(self, pair: Pair, carrier: LinkId, base: complex, theta: float, label: str,
              cols: GuideColumns, slider_point: complex | None) -> Guide:
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

    def driven_side(self, group: AssurGroup) -> str:
        """The side (``'i'`` or ``'j'``) of a dyad that is the actuator's composite link."""
        members = set(group.composite or ())
        link_i = group.i
        if isinstance(link_i, (tuple, frozenset)):
            return "i" if set(link_i) & members else "j"
        return "i" if link_i in members or _link_text(group.i) == "+".join(map(str, members)) \
            else "j"

    def add(self, group: GroupModel, frame_i: tuple[complex, float] | None = None,
            frame_j: tuple[complex, float] | None = None,
            frames: Mapping[LinkId, tuple[complex, float]] | None = None) -> None:
        """Record a group: the owner and side of its links and, in the sketch form, their
        frames at the reference position (``frames`` for every link of a higher group)."""
        self.groups.append(group)
        given = dict(frames or {})
        given.update({link: frame for link, frame in ((group.i, frame_i), (group.j, frame_j))
                      if link is not None and frame is not None})
        for link, side in group.members.items():
            if link in given:
                self.frames[link] = given[link]
            self.links[link] = (group.label, side)
            self.owner[link] = group
        if group.driven is not None:
            frame = given.get(group.composite[0], frame_i if group.driven == "i" else frame_j)
            for member in group.composite:
                if frame is not None:
                    self.frames[member] = frame
                self.links[member] = (group.label, group.driven)
                self.owner[member] = group

    def model(self, *, direction: int, drive: str,
              input_range: tuple[float, float] = (0.0, 2 * math.pi),
              tracing: tuple[TracePoint, ...] = (),
              laws: Mapping[str, InputLaw] | None = None) -> KinematicModel:
        """The model of what was built (after every problem was raised)."""
        chain = self.topo.chain
        return KinematicModel(name=chain.name, frame=self.topo.frame, groups=tuple(self.groups),
                              params=self._ordered(), direction=direction, drive=drive,
                              input_range=input_range, tracing=tracing, links=self.links,
                              pair_links={p.id: (p.type.value, p.links, p.guide)
                                          for p in chain.pairs},
                              source=chain.source, laws=dict(laws or {}))

    def _ordered(self) -> dict[str, Any]:
        """Parameters in layering and column order; every dyad gets its margin δ (default 0)."""
        out: dict[str, Any] = {}
        for group in self.groups:
            if not group.group_kind.is_input:
                self.params.setdefault(group.column("delta"), 0.0)
            extra = sorted(k for k in self.params if k.startswith(group.label + ".")
                           and k.split(".", 1)[1] not in KIND_COLUMNS[group.kind])
            for column in KIND_COLUMNS[group.kind]:
                name = group.column(column)
                if name in self.params:
                    out[name] = self.params[name]
            for name in extra:
                out[name] = self.params[name]
        return out


#: Suffix of the attachment columns of a point on a group's link, by the link's side
#: (a higher group's links give their names: ``l_base``, ``l_leash2``, ``l_a`` …).
_LETTERS = {"i": "N", "j": "M"}


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _cross(a: complex, b: complex) -> float:
    return (a.conjugate() * b).imag


def _sign(value: float) -> int:
    return -1 if value < 0 else 1


# ----------------------------------------------------------------------- sketch form


def model_from_sketch(analysis: StructuralAnalysis) -> KinematicModel:
    """Build the model from a chain's sketch (joint coordinates at φ = 0).

    The sketch (:class:`~assur.model.Sketch`, read with the chain table) gives a point for
    every joint and a direction for every slider pair; ``input: {rotation: ccw}`` (or ``cw``;
    for an actuator ``stroke: [min, max]`` in mm); tracing points; the margin δ (one number,
    or a mapping group label → δ). Every length, attachment point, guide direction relative
    to its carrier and assembly variant follows from the sketch.

    Parameters
    ----------
    analysis : StructuralAnalysis
        Of a chain that has a sketch.

    Returns
    -------
    KinematicModel
        Parameters in table units; ``bounds`` empty.

    Raises
    ------
    TableError
        For a problem that shows only once the groups are known (a crank of zero length,
        parallel guides of an RPP group, a margin for an unknown group).
    StructureError
        For a chain that is not a class II mechanism with one input.
    """
    topo = Topology(analysis)
    sketch = topo.chain.geometry
    assert sketch is not None
    build = Builder(topo, sketch)
    for start in topo.input_groups():
        _sketch_input(topo, build, start)
    for seq, group in enumerate(topo.groups, start=2):
        _sketch_group(topo, build, group, seq)
    tracing = tuple(TracePoint(trace.name, build.polar(trace.link, trace.point, trace.name))
                    for trace in sketch.tracing if trace.link in build.frames)
    margins = _margins(build, sketch.margin)
    build.reader.raise_if_any()
    for label, delta in margins.items():
        build.params[f"{label}.delta"] = float(delta)
    return _driven_model(topo, build, sketch, tracing)


def _driven_model(topo: Topology, build: Builder, sketch: Sketch,
                  tracing: tuple[TracePoint, ...]) -> KinematicModel:
    """The model with its drive: one crank, one actuator or one slider moved over its
    stroke, or every input a law of one cycle parameter (several inputs, or a law given)."""
    drives = topo.drives
    holders = [_holder(topo, build, drive) for drive in drives]
    if len(drives) > 1 or drives[0].has_law:
        laws = _laws(topo, build, sketch, holders)
        build.reader.raise_if_any()
        return build.model(direction=1, drive="laws", laws=laws, tracing=tracing)
    drive, group = drives[0], holders[0]
    if group.driven is None and group.hinge_i is not None:
        if drive.stroke is not None:
            build.problem("mechanism.inputs[0] 'stroke'", "model.crank_stroke", group=group.label)
            build.reader.raise_if_any()
        return build.model(direction=sketch.rotation, drive="crank", tracing=tracing)
    span = drive.stroke or sketch.stroke
    if group.driven is None:
        return build.model(direction=1, drive="slider", input_range=span or (0.0, 0.0),
                           tracing=tracing)
    if span is None:
        span = (_drawn_length(topo, build, group),) * 2
    return build.model(direction=1, drive="actuator", input_range=span, tracing=tracing)


def _holder(topo: Topology, build: Builder, drive: Drive) -> GroupModel:
    """The group that holds an input: its input group L0, or the actuator's group."""
    found = topo.on_frame(drive)
    if found is None:
        return next(group for group in build.groups if group.driven is not None)
    return next(group for group in build.groups
                if group.group_kind.is_input and group.i == found[0])


def _drawn_length(topo: Topology, build: Builder, group: GroupModel) -> float:
    """An actuator's length as sketched (the distance of the hinges of the bar it is)."""
    from assur.kinematics.higher.kind import actuator_ends  # only for an actuator

    ends = actuator_ends(group)
    return abs(build.point(topo.pairs[ends[0]]) - build.point(topo.pairs[ends[1]]))


def _laws(topo: Topology, build: Builder, sketch: Sketch, holders: list[GroupModel]
          ) -> dict[str, InputLaw]:
    """Each input's law of the cycle parameter (``docs/tables.md``, "Inputs"); a linear
    input's stroke limits become its group's parameters ``s_min``, ``s_max``."""
    laws: dict[str, InputLaw] = {}
    for index, (drive, group) in enumerate(zip(topo.drives, holders, strict=True)):
        where = f"mechanism.inputs[{index}]"
        crank = group.driven is None and group.hinge_i is not None
        if crank:
            if drive.stroke is not None or drive.table:
                build.problem(f"{where} {'stroke' if drive.stroke else 'table'!r}",
                              "model.crank_stroke", group=group.label)
            laws[group.label] = InputLaw(group.label, False, math.radians(drive.phase),
                                         drive.ratio)
            continue
        if group.layout is not None:  # a triad or class IV group follows its mode in length
            build.problem(f"{where} 'pair'", "model.law_higher_actuator", group=group.label)
            continue
        stroke = drive.stroke or (sketch.stroke if group.driven is not None else None)
        if stroke is None:
            build.problem(f"{where} 'stroke'", "model.law_stroke", group=group.label)
            continue
        for column, value in zip(STROKE, stroke, strict=True):
            build.put(group.label, column, value)
        table = tuple((math.radians(t), v) for t, v in drive.table)
        laws[group.label] = InputLaw(group.label, True, math.radians(drive.phase),
                                     drive.ratio, table, limited=True)
    return laws


def _margins(build: Builder, value: float | Mapping[str, float] | None) -> dict[str, float]:
    labels = [g.label for g in build.groups if not g.group_kind.is_input]
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        return {label: float(value) for label in labels}
    Node(build.reader, "geometry 'margin'", dict(value), labels)  # unknown groups, with hints
    return {label: value[label] for label in labels if label in value}


def _sketch_input(topo: Topology, build: Builder, group: GroupModel) -> None:
    """An input group from the sketch: a slider's guide line through its drawn point, or a
    crank from its pivot to its first pin."""
    label = group.label
    if group.guide_i is not None:
        pair = topo.pairs[group.pairs["P_i"]]
        point, theta = build.point(pair), build.direction(pair)
        build.put(label, "x_S", point.real)
        build.put(label, "y_S", point.imag)
        build.put(label, "beta_S", math.degrees(theta))
        build.add(group, (point, theta), None)
        return
    crank, driven = group.i, group.pairs["H_i"]
    pivot = build.point(topo.pairs[driven])
    pins = [p for p in topo.chain.pairs if crank in p.links and p.id != driven]
    if not pins:
        return  # a crank that carries nothing: no group is hinged to it
    pin = build.point(pins[0])
    if pin == pivot and pins[0].type == PairType.P:
        # a slot of the crank drawn through its pivot: any point of the slot line serves,
        # so the crank's frame takes the one a unit along the slot
        pin = pivot + cmath.rect(1.0, build.direction(pins[0]))
    if pin == pivot:
        build.problem(f"geometry {joint_key(pins[0])!r}", "sketch.crank_length")
        return
    angle = cmath.phase(pin - pivot)
    build.put(label, "x_O1", pivot.real)
    build.put(label, "y_O1", pivot.imag)
    build.add(group, (pivot, angle), None)
    build.put(label, "l_1", abs(pin - pivot))
    build.put(label, "phi_1_0", math.degrees(angle))


def _sketch_group(topo: Topology, build: Builder, group: AssurGroup, seq: int) -> None:
    if any(known not in build.frames for _, _, known in group.external):
        return  # an earlier group could not be built; its problem is already recorded
    kind = topo.kind(group)
    label = topo.label(group)
    sketch = rules_of(kind).sketch
    assert sketch is not None  # every kind but the input group has a sketch rule
    made = sketch(build, group, label)
    if made is None:
        return
    layout = made.layout
    first = group.i if layout is None else layout.links[0]
    assert first is not None
    key: int | str = kind.code if kind.number is None else kind.number
    model = GroupModel(label, key, seq, first,
                       group.j, made.sigma, made.hinge_i, made.hinge_j, made.guide_i,
                       made.guide_j, pairs=_roles(topo, group, layout), driven=made.driven,
                       composite=tuple(group.composite or ()) if made.driven else (),
                       layout=layout)
    build.add(model, made.frame_i, None if layout else made.frame_j, made.frames)


def _roles(topo: Topology, group: AssurGroup, layout: Layout | None) -> dict[str, PairId]:
    """Role → pair id: a dyad's roles of its kind; a higher group's internal joints
    ``C1``…/``C``–``F`` and external hinges ``H1``…/``H_a``, ``H_c``, its slider pairs
    ``P1``… (roles of sliders start with ``P``)."""
    if layout is None:
        return topo.pair_roles(group)
    out: dict[str, PairId] = {}
    names = [(f"C{k + 1}", f"H{k + 1}", f"P{k + 1}") for k in range(len(layout.internal))]
    if not layout.leashes:
        names = [(internal, external, "") for internal, external in
                 zip(("C", "D", "E", "F"), ("H_a", "H_c", "", ""), strict=True)]
    for (internal, external, slider), pid in zip(names, layout.internal, strict=True):
        out[internal if topo.pairs[pid].type == PairType.R else slider] = pid
    for (_, external, slider), pid in zip(names, layout.external, strict=False):
        out[external if topo.pairs[pid].type == PairType.R else slider] = pid
    return out


# ---------------------------------------------------------------- identification form


def model_from_params(analysis: StructuralAnalysis) -> KinematicModel:
    """Build the model from the ``params:`` of the identification-table rows.

    Every row lists the columns of its kind (``KIND_COLUMNS``): a number, ``'A'`` for a
    value supplied by an earlier group (tables 2.1–2.6). Coordinates of a hinge on a moving
    link are always supplied: the hinge is the attachment point N/M (the crank pin for
    L0) of its link's group. A guide base point on a moving carrier is given in the
    carrier's local frame; ``'A'`` puts it at the carrier's origin hinge. The assembly
    variant is the row's ``variant`` (L3: 0 means +1). Extra keys: ``delta`` (margin),
    ``s`` (on L0: +1 counter-clockwise, −1 clockwise), ``l_<name>``/``beta_<name>``
    tracing points with ``tracing: [name, ...]`` on the row of the carrying link.

    Parameters
    ----------
    analysis : StructuralAnalysis
        Of a chain read from an identification table whose rows carry ``params:``.

    Returns
    -------
    KinematicModel
        The model of the rows' parameters.

    Raises
    ------
    TableError
        Listing every problem of the rows' parameters.
    StructureError
        For a chain that is not a class II mechanism with one crank input.
    """
    topo = Topology(analysis)
    chain = topo.chain
    build = Builder(topo)
    reader = build.reader
    rows = chain.group_params
    variants: dict[tuple[LinkId | None, ...], int | None] = {
        row.key: row.variant for row in chain.identification or ()}
    if topo.composite_group is not None:
        raise StructureError(Message("structure.actuator_sketch", {"source": chain.source}))
    inputs = topo.input_groups()
    if len(topo.drives) != 1 or len(inputs) != 1 or inputs[0].hinge_i is None \
            or topo.drives[0].has_law:
        raise StructureError(Message("structure.params_one_crank", {"source": chain.source}))
    group0 = inputs[0]
    params0 = _params(build, rows, group0, group0.label, kind_of(0))
    direction = params0.direction if params0 is not None else 1
    build.add(group0)
    tracing: list[TracePoint] = []
    for seq, group in enumerate(topo.groups, start=2):
        label = topo.label(group)
        params = _params(build, rows, group, label, topo.kind(group))
        model = _param_group(topo, build, group, label, seq, variants.get((group.i, group.j)))
        build.add(model)
        for name, link in params.tracing if params is not None else ():
            tracing.append(TracePoint(name, Anchor(link, label, f"l_{name}", f"beta_{name}",
                                                   True)))
    reader.raise_if_any()
    return build.model(direction=direction, drive="crank", tracing=tuple(tracing))


def _params(build: Builder, rows: Mapping[tuple[LinkId, ...], GroupParams],
            group: AssurGroup | GroupModel, label: str, kind: GroupKind
            ) -> GroupParams | None:
    """The row's parameters of one group, checked against the group's kind and entered in
    the model (None when the row has none)."""
    where = f"structure_identification ({label}) 'params'"
    ends = (group.i,) if kind.is_input else (group.i, group.j)
    key = tuple(link for link in ends if link is not None)  # a row names every end
    params = rows.get(key) if len(key) == len(ends) else None
    if params is None:
        build.problem(where, "model.no_params", group=label, columns=", ".join(kind.columns))
        return None
    build.reader.issues.extend(params.problems)
    allowed = set(kind.columns) | {"delta", "tracing"} | ({"s"} if kind.is_input else set())
    extra = [column for column in params.keys if column not in allowed
             and column.startswith(("l_", "beta_"))]
    other = _kind_of_columns(params, kind, allowed)
    if other is not None:  # the columns of another kind: the row's L is the mistake
        build.problem(where, "model.params_of_kind", found=other.code, kind=kind.code,
                      number=other.number)
        return params
    meant = set()  # columns written misspelt: reported so, not also as missing
    for column in params.keys:
        if column not in allowed and column not in extra:
            hint = difflib.get_close_matches(column, sorted(allowed), n=1, cutoff=0.6)
            if latin_form(column) in allowed:
                build.problem(where, "model.unknown_column_lookalike", column=repr(column),
                              letters=lookalike_letters(column), hint=latin_form(column))
                meant.add(latin_form(column))
            elif hint:
                build.problem(where, "model.unknown_column_hint", column=repr(column),
                              hint=hint[0])
                meant.add(hint[0])
            else:
                build.problem(where, "model.unknown_column", column=repr(column),
                              kind=kind.code, columns=", ".join(kind.columns))
    rules = _coordinate_rules(build.topo.frame, group, kind)
    for column in (*kind.columns, "delta", *sorted(extra)):
        at = f"{where} {column!r}"
        rule = rules.get(column)
        if column in params.supplied:
            if rule is None:
                build.problem(at, "model.supplied_here")
            elif rule[0].startswith("frame"):
                build.problem(at, f"model.{rule[0]}_needs_number")
        elif column not in params.values:
            if column != "delta" and column not in params.keys and column not in meant:
                build.problem(at, "model.missing_column")
        elif rule is not None and rule[0] == "moving_hinge":
            value = params.values[column]
            build.problem(at, "model.moving_hinge_supplied", link=repr(rule[1]),
                          found=describe(int(value) if value.is_integer() else value))
        else:
            build.params[f"{label}.{column}"] = params.values[column]
    for name, link in params.tracing:
        if link not in (group.i, group.j) or link is None or any(
                f"{prefix}{name}" not in params.values for prefix in ("l_", "beta_")):
            build.problem(f"{where} 'tracing'", "model.tracing_point", name=repr(name),
                          i=group.i, j=group.j, l=f"l_{name}", beta=f"beta_{name}")
    return params


def _kind_of_columns(params: GroupParams, kind: GroupKind, allowed: set[str]
                     ) -> GroupKind | None:
    """The dyad kind other than ``kind`` whose columns the row gives exactly, when the row
    gives a column that ``kind`` does not have (None otherwise)."""
    given = {column for column in params.keys if column not in allowed - set(kind.columns)}
    if kind.is_input or given <= set(kind.columns):
        return None
    return next((other for number, other in KINDS.items() if number not in (0, kind.number)
                 and set(other.columns) == given), None)


def _coordinate_rules(frame: LinkId, group: AssurGroup | GroupModel, kind: GroupKind
                      ) -> dict[str, tuple[str, LinkId | None]]:
    """Coordinate column → (rule, link): a point on the frame needs its coordinates
    (``"frame_hinge"``, ``"frame_guide"``); a hinge on a moving link is supplied by that
    link's group (``"moving_hinge"``: ``'A'``); a guide base on a moving carrier may be
    either (``"moving_guide"``)."""
    ends: dict[str, LinkId | None] = {}
    if isinstance(group, AssurGroup):
        ends = {"i": group.i_minus_1, "j": group.j_minus_1}
    out: dict[str, tuple[str, LinkId | None]] = {}
    for part, columns in (("hinge", kind.hinges), ("guide", kind.guides)):
        for side, cols in columns.items():
            rule = f"frame_{part}" if ends.get(side) == frame else f"moving_{part}"
            out.update({cols[0]: (rule, ends.get(side)), cols[1]: (rule, ends.get(side))})
    return out


def _param_anchor(topo: Topology, build: Builder, link: LinkId | None, label: str,
                  cols: HingeColumns) -> Anchor:
    """An external hinge: absolute columns on the frame, supplied N/M on a moving link."""
    assert link is not None
    if link == topo.frame:
        return Anchor(link, label, cols[0], cols[1], False)
    owner = build.owner.get(link)
    if owner is None:  # pragma: no cover - the layering order guarantees the owner exists
        raise StructureError(Message("structure.used_early", {"link": link}))
    if owner.group_kind.is_input:
        return Anchor(link, owner.label, "l_1", None, True)
    letter = "N" if build.links[link][1] == "i" else "M"
    return Anchor(link, owner.label, f"l_{letter}", f"beta_{letter}", True)


def _param_guide(build: Builder, pair: Pair, carrier: LinkId | None, label: str,
                 cols: GuideColumns) -> Guide:
    x, y, beta, offset = cols
    assert carrier is not None
    for col in (x, y):
        # 'A' on a moving carrier: the base point is the carrier's origin hinge
        build.params.setdefault(f"{label}.{col}", 0.0)
    return Guide(pair.id, carrier, Anchor(carrier, label, x, y, False), beta, offset)


def _param_group(topo: Topology, build: Builder, group: AssurGroup, label: str, seq: int,
                 variant: int | None) -> GroupModel:
    """The group's hinges and guides, as its kind declares their columns."""
    kind = topo.kind(group)
    pi, pj, _ = topo.dyad_pairs(group)
    prev = {"i": group.i_minus_1, "j": group.j_minus_1}
    sigma = 1 if not kind.sided or variant in (None, 0) else _sign(variant)
    hinges = {side: _param_anchor(topo, build, prev[side], label, cols)
              for side, cols in kind.hinges.items()}
    guides = {side: _param_guide(build, pi if side == "i" else pj, prev[side], label, cols)
              for side, cols in kind.guides.items()}
    assert group.i is not None
    return GroupModel(label, group.kind or 0, seq, group.i, group.j, sigma, hinges.get("i"),
                      hinges.get("j"), guides.get("i"), guides.get("j"),
                      pairs=topo.pair_roles(group))

