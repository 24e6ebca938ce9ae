"""The ``geometry:`` section of a chain table (the sketch) → a typed :class:`Sketch`.

A sketch gives the mechanism at one reference position, as a student draws it: a point per
joint (``<joint id>: {point: [x, y]}``) and, for a slider pair, the direction of its slide
line (``direction: <degrees>`` or ``[dx, dy]``). Reserved keys: ``input`` (``{rotation: ccw}``
or ``cw``; ``{stroke: [min, max]}`` for an actuator, mm), ``tracing``
(``{name: {link: L, point: [x, y]}}``) and ``margin`` (δ in [0, 1), one number or a mapping
group label → δ).

The section is read once, when the chain table is read, with every problem collected; the
rank test, the scheme and the kinematic model all use the one :class:`Sketch`. Every joint
needs a point and every slider pair a direction, except a driven actuator pair, which the
kinematic model does not use (without it the rank test and the scheme do without the
sketch).

Examples
--------
>>> joints = {"A": ("R", (0, 1)), "B": ("P", (1, 2))}
>>> sketch = sketch_from_dict({"A": {"point": [0, 0]}, "B": {"point": [1, 0], "direction": 90},
...                            "margin": 0.1}, joints, links=(0, 1, 2), frame=0)
>>> sketch.points["B"], round(sketch.directions["B"].angle, 6), sketch.margin
((1+0j), 1.570796, 0.1)
"""

from __future__ import annotations

import cmath
import difflib
import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import replace
from typing import Any

from assur.errors import Issue
from assur.io.reader import (
    MISSING,
    Node,
    TableReader,
    describe,
    is_number,
    latin_form,
    lookalike_letters,
    normalise_id,
    positive,
    radian_look,
    with_commas,
)
from assur.model import (
    Chain,
    CircleProfile,
    Direction,
    GearMesh,
    LineProfile,
    LinkId,
    PairId,
    PolarProfile,
    Profile,
    Sketch,
    SketchTrace,
    joint_key,
)
from assur.profiles import (
    MIN_TABLE_NODES,
    TOUCH_TOLERANCE,
    Contact,
    contact,
    gear_contact,
    pitch_circles,
)
from assur.text import Message

__all__ = ["higher_pair_problem", "read_sketch", "sketch_from_dict", "with_sketch"]

RESERVED = ("input", "tracing", "margin")
#: Joint id → (pair type ``"R"``/``"P"``/``"H"``, the links the joint joins).
Joints = Mapping[PairId, tuple[str, tuple[LinkId, ...]]]


def sketch_from_dict(data: Any, joints: Joints, *, links: Iterable[LinkId], frame: LinkId,
                     source: str = "<data>", optional: Iterable[PairId] = (),
                     gears: Mapping[PairId, GearMesh] | None = None) -> Sketch:
    """Read a sketch given as a mapping (see :func:`read_sketch`).

    Raises
    ------
    TableError
        Listing every problem of the sketch.
    """
    reader = TableReader.from_data({"geometry": data}, source)
    sketch = read_sketch(reader, data, joints, links=links, frame=frame, optional=optional,
                         gears=gears)
    reader.raise_if_any()
    assert sketch is not None
    return sketch


def with_sketch(chain: Chain, data: Any) -> Chain:
    """A copy of ``chain`` with the sketch ``data`` (a ``geometry:`` mapping), read and checked.

    Raises
    ------
    TableError
        Listing every problem of the sketch.

    >>> from assur.io.chain_table import chain_from_dict
    >>> chain = chain_from_dict({"mechanism": {"pairs": [
    ...     {"id": "A", "type": "R", "links": [0, 1]}], "inputs": [1]}})
    >>> with_sketch(chain, {"A": {"point": [1, 2]}}).geometry.points
    {'A': (1+2j)}
    """
    joints: dict[PairId, tuple[str, tuple[LinkId, ...]]] = {}
    for pair in chain.pairs:
        joints.setdefault(joint_key(pair), (pair.type.value, pair.links))
    for higher in chain.higher:
        joints[higher.id] = ("H", higher.links)
    sketch = sketch_from_dict(data, joints, links=chain.links, frame=chain.frame,
                              source=chain.source, optional=actuator_pairs(chain.inputs, joints,
                                                                           chain.frame),
                              gears={pair.id: pair.gear for pair in chain.higher
                                     if pair.gear is not None})
    return replace(chain, geometry=sketch)


def actuator_pairs(inputs: Iterable[Any], joints: Joints, frame: Any) -> set[PairId]:
    """The driven pairs that join two moving links (actuators): their joints may be left out
    of a sketch."""
    return {drive.pair for drive in inputs if drive.pair in joints
            and frame not in joints[drive.pair][1]}


def read_sketch(reader: TableReader, data: Any, joints: Joints, *, links: Iterable[LinkId],
                frame: LinkId, optional: Iterable[PairId] = (),
                reported: Iterable[PairId] | None = (),
                gears: Mapping[PairId, GearMesh] | None = None) -> Sketch | None:
    """Read the ``geometry:`` section, recording every problem in ``reader``.

    Parameters
    ----------
    reader : TableReader
        Collects the problems.
    data : mapping
        The section as parsed from YAML.
    joints : mapping
        Joint id → (pair type, links) of every joint of the chain.
    links, frame
        The chain's links and frame (tracing points lie on moving links).
    optional : iterable of joint ids
        Joints that may be left out: driven actuator pairs, which the kinematic model does
        not use (the rank test and the scheme then do without the sketch).
    reported : iterable of joint ids, or None
        Pairs whose absence is reported already (a pair an input names): a key naming one
        is not reported again.  None when a row of the pairs table could not be read: a key
        that names no joint may then name that row's pair, and is not reported.
    gears : mapping, optional
        Joint id of every gear mesh (a higher pair with ``gear:``) → its mesh data: the
        sketch gives the centres of its pitch circles, not profiles.

    Returns
    -------
    Sketch or None
        None when a problem was recorded.
    """
    count = len(reader.issues)
    optional = set(optional)
    if not isinstance(data, dict):
        reader.problem("geometry", "sketch.not_mapping", found=describe(data))
        return None
    raw = {normalise_id(key): value for key, value in data.items()}
    meant = set() if reported is None else _unknown_keys(reader, raw, joints, set(reported))
    points: dict[PairId, complex] = {}
    directions: dict[PairId, Direction] = {}
    profiles: dict[PairId, tuple[Profile, Profile]] = {}
    for key, (ptype, ends) in joints.items():
        if key in meant:
            continue
        if ptype == "H":
            found = _higher(reader, key, raw.get(key), ends, (gears or {}).get(key))
            if found is not None:
                profiles[key] = found
        else:
            _joint(reader, key, raw.get(key), ptype, ends, points, directions,
                   key in optional)
    rotation, stroke = _input(reader, raw.get("input"))
    tracing = _tracing(reader, raw.get("tracing"), set(links) - {frame})
    margin = _margin(reader, raw.get("margin"))
    if len(reader.issues) > count:
        return None
    _suspicious_directions(reader, raw, joints, frame, points, directions)
    return Sketch(points, directions, rotation, stroke, tracing, margin, profiles)


#: A hinge farther from its slider's guide than this share of the sketch's size is "far off".
FAR_OFF_GUIDE = 0.05


def _suspicious_directions(reader: TableReader, raw: Mapping[Any, Any], joints: Joints,
                           frame: LinkId, points: Mapping[PairId, complex],
                           directions: Mapping[PairId, Direction]) -> None:
    """Warn (without refusing the sketch) of directions that look written in radians and of
    slider hinges drawn far off their guide.

    A direction looks like radians when it is π/2, π, 3π/2 or 2π to three decimals, or when
    every direction of the sketch is within 2π and some is not zero, or when the hinge of the
    slider's block (a moving link with the slider pair and one revolute pair) is farther off
    the guide line than :data:`FAR_OFF_GUIDE` of the sketch's size and the direction taken
    as radians puts it on the line.  (A block's hinge off its guide alone is a valid design,
    as in the class IV groups with a block in a slot, and is not named.)
    """
    written = {key: raw[key]["direction"] for key in directions
               if isinstance(raw.get(key), dict) and is_number(raw[key].get("direction"))}
    flagged = set()
    for key, value in written.items():
        look = radian_look(value)
        if look is not None:
            flagged.add(key)
            reader.warnings.append(Issue(f"geometry {key!r} 'direction'", look))
    small = {key: value for key, value in written.items() if key not in flagged}
    if small and all(abs(v) <= 2 * math.pi for v in written.values()) and \
            any(v != 0 for v in small.values()):
        reader.warn("geometry", "sketch.warn_radian_all",
                    joints=", ".join(repr(key) for key, v in small.items() if v != 0),
                    limit=2 * math.pi)
    for joint, hinge, distance, scale in _far_off_guides(joints, frame, points, directions):
        value = written.get(joint)
        if value is None or value == 0 or abs(value) > 2 * math.pi:
            continue
        turned = Direction(value, complex(math.cos(value), math.sin(value)))
        if _off_line(points[hinge], points[joint], turned) <= FAR_OFF_GUIDE * scale:
            reader.warn(f"geometry {joint!r} 'direction'", "sketch.warn_off_guide",
                        joint=repr(joint), hinge=repr(hinge), distance=distance, value=value,
                        degrees=round(math.degrees(value), 2))


def _off_line(point: complex, through: complex, direction: Direction) -> float:
    """The distance of ``point`` from the line through ``through`` along ``direction``."""
    unit = direction.vector / abs(direction.vector)
    return abs(((point - through) * unit.conjugate()).imag)


def _far_off_guides(joints: Joints, frame: LinkId, points: Mapping[PairId, complex],
                    directions: Mapping[PairId, Direction]
                    ) -> Iterable[tuple[PairId, PairId, float, float]]:
    """The slider joints whose block's hinge is far off the guide line: (slider joint, hinge,
    distance, size of the sketch)."""
    if len(points) < 2:
        return
    xs = [p.real for p in points.values()]
    ys = [p.imag for p in points.values()]
    scale = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    at: dict[LinkId, list[PairId]] = {}
    for key, (_, ends) in joints.items():
        for link in ends:
            at.setdefault(link, []).append(key)
    for joint, (ptype, ends) in joints.items():
        if ptype != "P" or joint not in points or joint not in directions:
            continue
        for link in ends:
            others = [key for key in at.get(link, []) if key != joint and link != frame]
            if len(others) != 1 or joints[others[0]][0] != "R" or others[0] not in points:
                continue
            distance = _off_line(points[others[0]], points[joint], directions[joint])
            if distance > FAR_OFF_GUIDE * scale:
                yield joint, others[0], distance, scale


def _unknown_keys(reader: TableReader, raw: dict[Any, Any], joints: Joints,
                  reported: set[PairId]) -> set[PairId]:
    """Report the keys that name no joint (but those in ``reported``); returns the joints
    they were meant for (a joint with a look-alike or a close name), whose missing point is
    then not reported again."""
    allowed = [str(j) for j in joints] + list(RESERVED)
    by_latin = {latin_form(str(joint)): joint for joint in joints if joint not in raw}
    meant: set[PairId] = set()
    for key in raw:
        if key in joints or key in RESERVED:
            continue
        where = f"geometry {key!r}"
        twin = by_latin.get(latin_form(str(key)))
        hint = difflib.get_close_matches(str(key), allowed, n=1, cutoff=0.5)
        if key in reported:
            meant.update(() if twin is None else (twin,))
        elif twin is not None:
            reader.problem(where, "sketch.unknown_key_lookalike", hint=str(twin),
                           letters=lookalike_letters(str(key)) or lookalike_letters(str(twin)))
            meant.add(twin)
        elif hint:
            reader.problem(where, "sketch.unknown_key_hint", hint=hint[0])
            meant.update(joint for joint in joints if str(joint) == hint[0])
        else:
            reader.problem(where, "sketch.unknown_key",
                           joints=", ".join(sorted(map(str, joints))),
                           reserved=", ".join(RESERVED))
    return meant


def _joint(reader: TableReader, key: PairId, value: Any, ptype: str,
           ends: tuple[LinkId, ...], points: dict[PairId, complex],
           directions: dict[PairId, Direction], optional: bool) -> None:
    where = f"geometry {key!r}"
    a, b = ends[0], ends[1]
    if value is None and optional:
        return  # a driven actuator pair: the kinematic model does not use its point
    if value is not None and not isinstance(value, dict):
        reader.problem(where, "sketch.joint", found=describe(value))
        return
    node = Node(reader, where, value or {}, ("point", "direction"))
    node.swapped({"point": lambda v: _vector(v) is not None,
                  "direction": lambda v: is_number(v) or _vector(v) is not None})
    point = node.get("point", required=False, default=None)
    if point is MISSING:
        pass  # misspelt: reported already
    elif point is None:
        reader.problem(where, "sketch.needs_point", type=ptype, joint=repr(key), a=a, b=b)
    elif _vector(point) is None:
        reader.problem(f"{where} 'point'", "sketch.point", found=describe(point))
    else:
        points[key] = _vector(point) or 0j
    direction = node.get("direction", required=False, default=None)
    if direction is MISSING:
        return  # misspelt: reported already
    if direction is None:
        if ptype == "P":
            reader.problem(where, "sketch.needs_direction", joint=repr(key), a=a, b=b)
        return
    read = _direction(reader, f"{where} 'direction'", direction)
    if read is not None:
        directions[key] = read


def _direction(reader: TableReader, where: str, value: Any) -> Direction | None:
    """A direction: an angle in degrees from the x-axis or a vector ``[dx, dy]``; None when
    it is neither (recorded)."""
    vector = _vector(value)
    if is_number(value):
        angle = math.radians(value)
        return Direction(angle, complex(math.cos(angle), math.sin(angle)))
    if vector is not None and vector != 0:
        return Direction(cmath.phase(vector), vector)
    reader.problem(where, "sketch.direction", found=describe(value))
    return None


# ------------------------------------------------------------------------ higher pairs

#: The codes of a higher pair's sketch entry as a whole (missing, not a mapping).
_HIGHER_CODES = frozenset({"sketch.needs_profiles", "sketch.needs_centres", "sketch.profiles",
                           "sketch.centres"})
_HIGHER_PLACE = re.compile(r"geometry '[^']*' '(?:profiles|centres)'")


def higher_pair_problem(issue: Issue) -> bool:
    """Whether a problem of the sketch is one of a higher pair's profiles or a gear mesh's
    centres. The structure needs them (the passive rollers, the replacing pairs), so such a
    problem refuses the table, where the structure of a chain of lower pairs does without
    its sketch.

    >>> from assur.text import Message
    >>> higher_pair_problem(Issue("geometry 'K' 'profiles'[1].circle 'radius'",
    ...                           Message("rule.positive")))
    True
    """
    return issue.message.code in _HIGHER_CODES or bool(_HIGHER_PLACE.match(issue.location))

#: The kinds of profile of a cam pair's sketch entry.
PROFILE_KINDS = ("circle", "point", "line", "table")


def _higher(reader: TableReader, key: PairId, value: Any, ends: tuple[LinkId, ...],
            gear: GearMesh | None) -> tuple[Profile, Profile] | None:
    """The sketch of a higher pair: the two profiles of a cam pair (``profiles:``), or the
    centres of a gear mesh's pitch circles (``centres:``), checked to touch."""
    where = f"geometry {key!r}"
    field = "profiles" if gear is None else "centres"
    if value is None:
        reader.problem(where, f"sketch.needs_{field}", joint=repr(key), a=ends[0], b=ends[1])
        return None
    if not isinstance(value, dict):
        reader.problem(where, f"sketch.{field}", found=describe(value))
        return None
    node = Node(reader, where, value, (field,))
    items = node.get(field, kind="list")
    if items is MISSING:
        return None
    if len(items) != 2:
        reader.problem(f"{where} {field!r}", f"sketch.two_{field}", found=describe(items))
        return None
    if gear is not None:
        centres = [_vector(item) for item in items]
        for index, (item, centre) in enumerate(zip(items, centres, strict=True)):
            if centre is None:
                reader.problem(f"{where} 'centres'[{index}]", "sketch.point",
                               found=describe(item))
        if centres[0] is None or centres[1] is None:
            return None
        pair = pitch_circles(gear, (centres[0], centres[1]))
        return _touching(reader, f"{where} {field!r}", pair,
                         gear_contact(gear, (centres[0], centres[1])))
    read = [_profile(reader, f"{where} 'profiles'[{index}]", item)
            for index, item in enumerate(items)]
    if read[0] is None or read[1] is None:
        return None
    touch = contact(read[0], read[1])
    if touch is None:
        reader.problem(f"{where} {field!r}", "sketch.profiles_cannot_touch",
                       first=_kind_of(read[0]), second=_kind_of(read[1]))
        return None
    return _touching(reader, f"{where} {field!r}", (read[0], read[1]), touch)


def _touching(reader: TableReader, where: str, pair: tuple[Profile, Profile],
              touch: Contact) -> tuple[Profile, Profile] | None:
    """The profiles, when they touch at the sketch; else None (recorded)."""
    if abs(touch.gap) <= TOUCH_TOLERANCE:
        return pair
    code = "sketch.profiles_apart" if touch.gap > 0 else "sketch.profiles_cut"
    reader.problem(where, code, gap=round(abs(touch.gap), 6), tolerance=TOUCH_TOLERANCE)
    return None


def _kind_of(profile: Profile) -> str:
    """The table's word for a profile."""
    if isinstance(profile, CircleProfile):
        return "point" if profile.is_point else "circle"
    return "line" if isinstance(profile, LineProfile) else "table"


def _profile(reader: TableReader, where: str, value: Any) -> Profile | None:
    """One profile: ``{circle: {centre, radius, concave}}``, ``{point: [x, y]}``,
    ``{line: {point, direction}}`` or ``{table: {centre, angles, radii}}``; None when it
    is wrong (every problem recorded)."""
    if not isinstance(value, dict) or len(value) != 1 or next(iter(value)) not in PROFILE_KINDS:
        reader.problem(where, "sketch.profile", kinds=", ".join(PROFILE_KINDS),
                       found=describe(value))
        return None
    kind, body = next(iter(value.items()))
    inner = f"{where}.{kind}"
    if kind == "point":
        point = _vector(body)
        if point is None:
            reader.problem(inner, "sketch.point", found=describe(body))
            return None
        return CircleProfile(point, 0.0)
    if not isinstance(body, dict):
        reader.problem(inner, "sketch.profile_body", kind=kind, found=describe(body))
        return None
    if kind == "circle":
        return _circle(reader, Node(reader, inner, body, ("centre", "radius", "concave")))
    if kind == "line":
        return _line(reader, Node(reader, inner, body, ("point", "direction")))
    return _table(reader, Node(reader, inner, body, ("centre", "angles", "radii")))


def _point_of(reader: TableReader, node: Node, key: str) -> complex | None:
    """A point ``[x, y]`` of a profile's field; None when absent or wrong (recorded)."""
    value = node.get(key)
    if value is MISSING:
        return None
    point = _vector(value)
    if point is None:
        reader.problem(f"{node.location} {key!r}", "sketch.point", found=describe(value))
    return point


def _circle(reader: TableReader, node: Node) -> CircleProfile | None:
    """A circle profile: its centre, a positive radius, convex unless ``concave: true``."""
    centre = _point_of(reader, node, "centre")
    radius = node.get("radius", kind="number", check=positive)
    concave = node.get("concave", kind="bool", required=False, default=False)
    if centre is None or MISSING in (radius, concave):
        return None
    return CircleProfile(centre, float(radius), bool(concave))


def _line(reader: TableReader, node: Node) -> LineProfile | None:
    """A straight profile: a point of it and its direction."""
    point = _point_of(reader, node, "point")
    value = node.get("direction")
    direction = None if value is MISSING else _direction(
        reader, f"{node.location} 'direction'", value)
    if point is None or direction is None:
        return None
    return LineProfile(point, direction)


def _table(reader: TableReader, node: Node) -> PolarProfile | None:
    """A polar profile table: at least :data:`MIN_TABLE_NODES` angles, strictly increasing
    within one turn, and as many positive radii."""
    count = len(reader.issues)
    centre = _point_of(reader, node, "centre")
    angles = node.get("angles", kind="list", check=_numbers)
    radii = node.get("radii", kind="list", check=_numbers)
    at = f"{node.location} 'angles'"
    if isinstance(angles, list):
        if len(angles) < MIN_TABLE_NODES:
            reader.problem(at, "sketch.table_short", least=MIN_TABLE_NODES, count=len(angles))
        down = next((k for k in range(1, len(angles)) if angles[k] <= angles[k - 1]), None)
        if down is not None:
            reader.problem(at, "sketch.table_unsorted", index=down, value=angles[down],
                           before=angles[down - 1])
        elif angles and angles[-1] - angles[0] >= 360:
            reader.problem(at, "sketch.table_turn", first=angles[0], last=angles[-1])
    if isinstance(radii, list):
        for index, radius in enumerate(radii):
            rule = positive(radius)
            if rule is not None:
                reader.problem(f"{node.location} 'radii'[{index}]", "table.rule_broken",
                               rule=rule, found=describe(radius))
        if isinstance(angles, list) and len(radii) != len(angles):
            reader.problem(f"{node.location} 'radii'", "sketch.table_lengths",
                           radii=len(radii), angles=len(angles))
    if len(reader.issues) > count or centre is None or not isinstance(angles, list) or \
            not isinstance(radii, list):
        return None
    return PolarProfile(centre, tuple(map(float, angles)), tuple(map(float, radii)))


def _numbers(value: Any) -> Message | None:
    """The rule of a list of numbers."""
    return None if all(is_number(item) for item in value) else Message("rule.list_numbers")


def _input(reader: TableReader, value: Any) -> tuple[int, tuple[float, float] | None]:
    if value is None:
        return 1, None
    if not isinstance(value, dict):
        reader.problem("geometry 'input'", "sketch.input", found=describe(value))
        return 1, None
    node = Node(reader, "geometry 'input'", value, ("rotation", "stroke"))
    rotation = node.choice("rotation", ["ccw", "cw"], required=False, default="ccw")
    stroke = node.get("stroke", kind="list", required=False, default=None)
    span = None
    if stroke not in (None, MISSING):
        vec = _vector(stroke)
        if vec is None or not 0 < vec.real < vec.imag:
            reader.problem("geometry 'input' 'stroke'", "sketch.stroke",
                           found=with_commas(stroke) if vec is not None else describe(stroke))
        else:
            span = (vec.real, vec.imag)
    return (-1 if rotation == "cw" else 1), span


def _tracing(reader: TableReader, value: Any, moving: set[LinkId]) -> tuple[SketchTrace, ...]:
    if value is None:
        return ()
    if not isinstance(value, dict):
        reader.problem("geometry 'tracing'", "sketch.tracing", found=describe(value))
        return ()
    points = []
    for name, row in value.items():
        where = f"geometry.tracing {name!r}"
        if not isinstance(row, dict):
            reader.problem(where, "sketch.tracing_row", found=describe(row))
            continue
        node = Node(reader, where, row, ("link", "point"))
        link = node.get("link", kind="id")
        point = _vector(node.get("point", kind="list"))
        if point is None and node.has("point"):
            reader.problem(f"{where} 'point'", "sketch.tracing_point")
        if link is not MISSING and link not in moving:
            reader.problem(f"{where} 'link'", "sketch.tracing_link", found=describe(link))
        elif link is not MISSING and point is not None:
            points.append(SketchTrace(str(name), link, point))
    return tuple(points)


def _margin(reader: TableReader, value: Any) -> float | dict[str, float] | None:
    if value is None:
        return None
    if is_number(value) and 0 <= value < 1:
        return float(value)
    if not isinstance(value, dict):
        reader.problem("geometry 'margin'", "sketch.margin", found=describe(value))
        return None
    node = Node(reader, "geometry 'margin'", value, None)
    out = {}
    for label in value:
        delta = node.get(label, kind="number",
                         check=lambda v: None if 0 <= v < 1 else Message("rule.margin"))
        if delta is not MISSING:
            out[str(label)] = float(delta)
    return out



def _vector(value: Any) -> complex | None:
    if isinstance(value, list) and len(value) == 2 and all(is_number(v) for v in value):
        return complex(value[0], value[1])
    return None

