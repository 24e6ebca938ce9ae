"""The kinematic chain as data: links, kinematic pairs, inputs and optional geometry.

A :class:`Chain` is what the chain tables describe (``structure.md`` §2.1) after
normalisation (§2.2): every pair joins exactly two links, a hinge shared by k links has
become k − 1 binary pairs that remember the user's joint id in :attr:`Pair.origin`.

Link and pair ids are whole numbers or texts; digit-only texts are turned into numbers
(:func:`assur.io.reader.normalise_id`), so ``"3"`` and ``3`` name the same link.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass, field, replace
from enum import Enum
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np

from assur.errors import Issue

if TYPE_CHECKING:  # pragma: no cover
    import numpy.typing as npt

    from assur.kinematics.model import KinematicModel
    from assur.typing import ComplexArray, FloatArray

__all__ = [
    "DEFAULT_PRESSURE_ANGLE",
    "Allowable",
    "Chain",
    "Direction",
    "Drive",
    "ForceData",
    "General",
    "GroupParams",
    "IdentificationRow",
    "Input",
    "Link",
    "LinkId",
    "Load",
    "Mass",
    "Pair",
    "PairId",
    "PairType",
    "Sketch",
    "SketchTrace",
    "Student",
    "Tabulated",
    "id_key",
    "joint_key",
]

LinkId = int | str
PairId = int | str

#: The program default of the allowable pressure angle [α], degrees (``method.md`` §2.7).
DEFAULT_PRESSURE_ANGLE = 45.0


def id_key(value: LinkId | PairId) -> tuple[int, int | str]:
    """Sort key for ids that may be numbers or texts: numbers first, in numeric order.

    >>> sorted([10, "B", 2, "A"], key=id_key)
    [2, 10, 'A', 'B']
    """
    if isinstance(value, int):
        return (0, value)
    return (1, str(value))


@dataclass(frozen=True, slots=True)
class Direction:
    """A slide direction as given: ``angle`` (radians from the x-axis) and ``vector`` (the
    given vector, or the unit vector of the given angle)."""

    angle: float
    vector: complex

    @property
    def unit(self) -> complex:
        """The unit vector along the slide line."""
        return self.vector / abs(self.vector)


@dataclass(frozen=True, slots=True)
class SketchTrace:
    """A tracing point of the sketch: its name, the link it is fixed on, its point."""

    name: str
    link: LinkId
    point: complex


@dataclass(frozen=True, slots=True)
class Sketch:
    """The mechanism at its reference position (the ``geometry:`` section).

    Attributes
    ----------
    points : mapping
        Joint id → point (complex, mm) of every joint the sketch gives.
    directions : mapping
        Joint id of every slider pair the sketch gives → :class:`Direction`.
    rotation : int
        Crank direction: +1 counter-clockwise (default), −1 clockwise.
    stroke : tuple of float or None
        Actuator lengths (min, max), mm.
    tracing : tuple of SketchTrace
    margin : float, mapping or None
        δ for every group, or group label → δ.

    Examples
    --------
    >>> import pathlib, assur
    >>> tables = pathlib.Path(assur.__file__).parents[1] / "input_tables"
    >>> sketch = assur.load_chain(tables / "four_bar.yaml").geometry
    >>> sketch.points["C"]
    (110+80j)
    """

    points: Mapping[PairId, complex]
    directions: Mapping[PairId, Direction]
    rotation: int = 1
    stroke: tuple[float, float] | None = None
    tracing: tuple[SketchTrace, ...] = ()
    margin: float | Mapping[str, float] | None = None

    def pose(self, pairs: Iterable[Pair]) -> dict[PairId, tuple[complex, complex | None]] | None:
        """Point and (for a P pair) slide vector of each pair, keyed by pair id; None when
        the sketch leaves out a joint.

        A split compound hinge finds its point under its joint id (``pair.origin``).
        """
        out: dict[PairId, tuple[complex, complex | None]] = {}
        for pair in pairs:
            key = joint_key(pair)
            direction = self.directions.get(key)
            if key not in self.points or (pair.type.value == "P" and direction is None):
                return None
            out[pair.id] = (self.points[key], None if direction is None or
                            pair.type.value == "R" else direction.vector)
        return out


def joint_key(pair: Pair) -> PairId:
    """The key of a pair in the sketch: its joint (origin) for a split compound hinge."""
    return pair.origin if pair.origin is not None else pair.id


class PairType(str, Enum):
    """Kind of a lower kinematic pair (5th class): revolute R (В) or prismatic P (П)."""

    R = "R"
    P = "P"


@dataclass(frozen=True, slots=True)
class Link:
    """A link (звено) with an optional human name, e.g. ``Link(1, "crank")``."""

    id: LinkId
    name: str | None = None


@dataclass(frozen=True, slots=True)
class Pair:
    """A kinematic pair joining two distinct links.

    Parameters
    ----------
    id : int or str
        Pair id, unique in the chain. For a normalised compound hinge the k − 1 binary pairs
        get ids ``"<origin>/<link>"``.
    type : PairType
        R (revolute) or P (prismatic).
    links : tuple of two link ids
        The two links, in the user's order.
    guide : link id or None
        For a P pair, the link that carries the slide line (направляющая); None for R.
    origin : int or str
        The user's joint id (equal to ``id`` except for normalised compound hinges).
    """

    id: PairId
    type: PairType
    links: tuple[LinkId, LinkId]
    guide: LinkId | None = None
    origin: PairId | None = None

    def other(self, link: LinkId) -> LinkId:
        """The link at the other end of the pair from ``link``."""
        a, b = self.links
        return b if link == a else a


@dataclass(frozen=True, slots=True)
class GroupParams:
    """The ``params:`` of an identification row, read and checked with the row.

    Attributes
    ----------
    values : mapping
        Column → value in table units (mm, degrees). A column written ``'A'`` (supplied by
        an earlier group) is absent.
    supplied : frozenset of str
        Columns written ``'A'`` (supplied by an earlier group).
    direction : int
        ``s`` of the input group: +1 counter-clockwise, −1 clockwise.
    tracing : tuple of (name, link)
        Tracing points with columns ``l_<name>``, ``beta_<name>``.
    keys : tuple of str
        Every key the row gave, in its order (the model checks them against the group's
        columns).
    problems : tuple of Issue
        Problems of the values, reported by the model with the problems of the columns.
    """

    values: Mapping[str, float]
    supplied: frozenset[str] = frozenset()
    direction: int = 1
    tracing: tuple[tuple[str, LinkId], ...] = ()
    keys: tuple[str, ...] = ()
    problems: tuple[Issue, ...] = ()


#: The columns of the structure-identification table, in the course's order.
COLUMNS = ("L", "seq", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1", "j_plus_1", "variant",
           "out_code")


@dataclass(frozen=True)
class IdentificationRow:
    """One row of the structure-identification table; None is the source's dash.

    A row read from a table may carry ``params`` (its group's parameter columns, read by the
    kinematic model) and ``location`` (where it stands in the file); neither is a column.
    """

    L: int
    seq: int | None
    i_minus_1: LinkId | None
    j_minus_1: LinkId | None
    i: LinkId
    j: LinkId | None
    i_plus_1: LinkId | list[LinkId] | None
    j_plus_1: LinkId | list[LinkId] | None
    variant: int | None
    out_code: str | None
    params: GroupParams | None = field(default=None, compare=False, repr=False)
    location: str = field(default="", compare=False, repr=False)

    @property
    def key(self) -> tuple[LinkId, ...]:
        """The links of the row's group: ``(i,)`` for L0, else ``(i, j)``."""
        return (self.i,) if self.L == 0 or self.j is None else (self.i, self.j)

    def get(self, column: str, default: Any = None) -> Any:
        """The value of a column by name (as in the table), ``default`` for another name."""
        return getattr(self, column) if column in COLUMNS else default

    def to_dict(self) -> dict[str, Any]:
        """The row as a mapping with the table's keys."""
        row = asdict(self)
        return {key: row[key] for key in COLUMNS}


@dataclass(frozen=True, slots=True)
class Drive:
    """One input of the mechanism and its law over the cycle (``docs/tables.md``, "Inputs").

    Either a driven link (``link``; it must share exactly one pair with the frame, which is
    the driven pair: a crank's hinge or a slider's guide) or a driven pair (``pair``), which
    may join two moving links — an actuator such as a hydraulic cylinder. Both may be given
    for a link driven through a named pair.

    Attributes
    ----------
    link, pair : id or None
        The driven link, the driven pair.
    stroke : (float, float) or None
        A linear input's limits, mm: a slider's displacement from its sketched position along
        the drawn direction, or an actuator's length; reaching beyond them is a failure to
        assemble (:attr:`assur.kinematics.reasons.Reason.STROKE_END`).
    phase : float
        Degrees: a crank's rotation at t = 0; a linear input's phase of its harmonic law.
    ratio : int
        A crank turns ``ratio`` times per cycle (its rotation ``phase + ratio·t``); a linear
        input makes ``ratio`` double strokes per cycle.
    table : tuple of (float, float)
        A linear input's law as a table: cycle parameter t (degrees, increasing in
        [0, 360)) → its coordinate (mm), interpolated by a periodic cubic spline.
    """

    link: LinkId | None = None
    pair: PairId | None = None
    stroke: tuple[float, float] | None = None
    phase: float = 0.0
    ratio: int = 1
    table: tuple[tuple[float, float], ...] = ()

    @property
    def has_law(self) -> bool:
        """Whether the row gives a law (a phase, a ratio other than 1, or a table)."""
        return self.phase != 0.0 or self.ratio != 1 or bool(self.table)


Input = Drive


@dataclass(frozen=True)
class Allowable:
    """One row of ``general: {allowable: [...]}``: the limits a mechanism table states for
    one group (a synthesis result keeps its problem's own, ``method.md`` tables 2.7–2.11).

    Attributes
    ----------
    links : tuple of link ids
        The group's links: ``(i, j)`` of a dyad, ``(i,)`` of an input group, the links of
        the label of a triad or class IV group (``(2, 3, 4, 5)``), in any order.
    pressure_angle : float or None
        Allowable pressure angle, degrees in (0, 90]; None: the program default.
    rotations : mapping
        Joint role → allowable rotation, degrees (> 0).
    workspace : tuple of 4 floats or None
        ``(x_low, x_high, y_low, y_high)`` of the working-space box, mm.
    """

    links: tuple[LinkId, ...]
    pressure_angle: float | None = None
    rotations: Mapping[str, float] = field(default_factory=dict)
    workspace: tuple[float, float, float, float] | None = None


@dataclass(frozen=True)
class General:
    """The ``general:`` section of a mechanism table, read once by the table reader.

    Attributes
    ----------
    omega : float or None
        Input speed (rad/s of a crank, mm/s of an actuator), finite and positive; None when
        the table gives none.
    allowable : tuple of Allowable
        The limits stated per group.

    Examples
    --------
    >>> General(omega=10.0).omega, General().allowable
    (10.0, ())
    """

    omega: float | None = None
    allowable: tuple[Allowable, ...] = ()

    def pressure_angles(self, model: KinematicModel) -> dict[str, float]:
        """Every group of ``model`` → its allowable pressure angle, degrees: the one this
        section states for the group's links (in any order), else
        :data:`DEFAULT_PRESSURE_ANGLE`.

        Parameters
        ----------
        model : KinematicModel
            The mechanism (its groups give the labels).

        Returns
        -------
        dict
        """
        stated = {frozenset(row.links): row.pressure_angle for row in self.allowable
                  if row.pressure_angle is not None}
        return {group.label: stated.get(frozenset(group.members), DEFAULT_PRESSURE_ANGLE)
                for group in model.groups}


@dataclass(frozen=True, slots=True)
class Student:
    """The ``student:`` section of a table, read once by the table reader: who hands the
    report in, in which group, which variant, and when; None where not given (a blank on
    the title page of the report).

    Attributes
    ----------
    name, group, variant : str or None
        As written in the table (a whole number kept as its digits).
    date : str or None
        ISO date (``2026-05-12``).

    Examples
    --------
    >>> Student(name="Ivanova A. A.", variant="7").merged(variant="12", group=None)
    Student(name='Ivanova A. A.', group=None, variant='12', date=None)
    """

    name: str | None = None
    group: str | None = None
    variant: str | None = None
    date: str | None = None

    def merged(self, **typed: str | None) -> Student:
        """This student with the values typed as options (those not None) put in."""
        return replace(self, **{key: value for key, value in typed.items()
                                if value is not None})


# ------------------------------------------------------------------ force sections
# The ``masses:``, ``loads:`` and ``gravity:`` sections of a table (``docs/forces.md`` §1),
# kept in table units: points in mm (sketch points, at the sketched position), forces in N,
# torques in N·m, masses in kg, moments of inertia in kg·m² about the centre of mass,
# gravity in m/s². A tabulated value is a function of the input coordinate: the crank angle
# in degrees from the sketched position (periodic over 360°), or the actuator length in mm
# (constant beyond the ends).

#: A value per design: a number, or an array broadcast against the positions (``(D, 1)``).
PerDesign: TypeAlias = "float | FloatArray"


@dataclass(frozen=True, slots=True)
class Tabulated:
    """A value given at nodes of the input coordinate, linear between them.

    Parameters
    ----------
    nodes : tuple of float
        Strictly increasing: crank angles in degrees from the sketched position, inside
        [0, 360], or actuator lengths in mm.
    values : tuple of float or complex
        The value at each node (a force as the complex number Fx + i·Fy, N; a torque, N·m).

    Examples
    --------
    >>> table = Tabulated(nodes=(0.0, 180.0, 360.0), values=(-500.0, 0.0, -500.0))
    >>> table.at(np.radians([90.0, 450.0]), periodic=True).tolist()
    [-250.0, -250.0]
    """

    nodes: tuple[float, ...]
    values: tuple[complex | float, ...]

    def at(self, q: np.ndarray, *, periodic: bool) -> np.ndarray:
        """The value at input positions ``q``.

        Parameters
        ----------
        q : ndarray
            Crank rotation in radians from the sketched position (``periodic``), or actuator
            lengths in mm.
        periodic : bool
            Crank input: evaluate at φ mod 360°, the table wrapped around (a node at 360
            repeats the value at 0 and is dropped). Otherwise constant beyond the ends.

        Returns
        -------
        ndarray
            Shaped like ``q``.

        Examples
        --------
        >>> Tabulated((10.0, 20.0), (1.0, 3.0)).at(np.array([0.0, 15.0, 99.0]),
        ...                                        periodic=False).tolist()
        [1.0, 2.0, 3.0]
        """
        nodes = np.asarray(self.nodes, dtype=float)
        values = np.asarray(self.values)
        if not periodic:
            return np.asarray(np.interp(q, nodes, values))
        if nodes[-1] == 360.0 and nodes.size > 1:
            nodes, values = nodes[:-1], values[:-1]
        return np.asarray(np.interp(np.degrees(q) % 360.0, nodes, values, period=360.0))


@dataclass(frozen=True, slots=True)
class Mass:
    """Inertia data of one moving link.

    Each value is one number, or (for a batch of designs whose masses follow their
    dimensions) an array that broadcasts against the kinematics' arrays: shape ``(D, 1)``
    for D designs × positions.

    Parameters
    ----------
    mass : float or ndarray
        kg, ≥ 0.
    centre : complex or ndarray or None
        Centre of mass as a sketch point x + i·y (mm), fixed on the link (or a point of the
        link's frame, see ``ForceData.local``); None when the mass is 0.
    inertia : float or ndarray
        Moment of inertia about the centre, kg·m², ≥ 0.
    """

    mass: PerDesign
    centre: complex | ComplexArray | None = None
    inertia: PerDesign = 0.0


@dataclass(frozen=True, slots=True)
class Load:
    """An external force (at a point of the link) or torque on one moving link.

    Parameters
    ----------
    link : link id
        The loaded link.
    force : complex or Tabulated or None
        Fx + i·Fy in global axes (N); its direction does not turn with the link.
    point : complex or None
        Sketch point of the link where the force acts (mm); required with ``force``.
    torque : float or Tabulated or None
        N·m, counter-clockwise positive.
    """

    link: LinkId
    force: complex | Tabulated | None = None
    point: complex | None = None
    torque: float | Tabulated | None = None


@dataclass(frozen=True, slots=True)
class ForceData:
    """The ``masses:``, ``loads:`` and ``gravity:`` sections of a table.

    Parameters
    ----------
    masses : mapping
        Moving link → :class:`Mass`.
    loads : tuple of Load
    gravity : complex
        gx + i·gy, m/s² (0 for none).
    local : bool
        The points (centres of mass, points of forces) are given in each link's own frame
        of the kinematics (origin and axis of ``Motion.frames``, mm) rather than as sketch
        points: so they follow a design whose dimensions change (synthesis).

    Examples
    --------
    >>> data = ForceData({2: Mass(1.2, 80 + 60j, 0.004)}, (Load(3, torque=-20.0),), -9.81j)
    >>> data.weight(2)
    -11.772j
    """

    masses: Mapping[LinkId, Mass] = field(default_factory=dict)
    loads: tuple[Load, ...] = ()
    gravity: complex = 0j
    local: bool = False

    def weight(self, link: LinkId) -> complex | npt.NDArray[np.complexfloating]:
        """The weight m·g of a link, N (0 without a mass; an array for masses per design)."""
        mass = self.masses.get(link)
        return 0j if mass is None else mass.mass * self.gravity

    @property
    def links(self) -> tuple[LinkId, ...]:
        """The links that carry a mass or a load, in table order."""
        return tuple(dict.fromkeys([*self.masses, *(load.link for load in self.loads)]))


@dataclass(frozen=True, slots=True)
class Chain:
    """A planar kinematic chain with its frame and inputs.

    Parameters
    ----------
    name : str
        A label for reports.
    frame : link id
        The fixed link (стойка), 0 by default in the tables.
    links : tuple of link ids
        Every link, frame included, in table order.
    pairs : tuple of Pair
        The normalised pairs.
    inputs : tuple of Drive
        The inputs (входные звенья / приводы).
    geometry : Sketch or None
        The table's ``geometry`` section: the pose for the rank test, the scheme and the
        kinematic model.
    general : General
        The table's ``general`` section, read and checked (empty when the table has none).
    source : str
        The file the chain came from.
    group_params : mapping
        ``(i, j)`` (a dyad) or ``(i,)`` (an input group) → the ``params`` of that row of an
        identification table.
    names : dict
        Optional human names of links.
    local_names : dict
        Language → link → its name in that language, for the links whose name the table gives
        in several languages (``name: {en: crank, ru: кривошип}``); see :meth:`link_names`.
    identification : tuple of IdentificationRow or None
        The rows of an identification table given with the chain (to be checked).
    claims : dict
        Counts stated in an identification table (``n_moving_links``, ``p5``, ``p4``, ``W``,
        ``N_Q``), to be checked.
    forces : ForceData or None
        The table's ``masses:``, ``loads:`` and ``gravity:`` sections (``docs/forces.md``);
        None when it has neither masses nor loads.
    student : Student or None
        The table's ``student:`` section (the title block of a report); None when the table
        has none.
    warnings : tuple of Issue
        What looks wrong in the table but does not refuse it (an angle that looks like
        radians, a slider hinge off its guide), found as it was read.

    Examples
    --------
    >>> import pathlib, assur
    >>> tables = pathlib.Path(assur.__file__).parents[1] / "input_tables"
    >>> chain = assur.load_chain(tables / "four_bar.yaml")
    >>> chain.inputs[0].link, sorted(chain.geometry.points)
    (1, ['A', 'B', 'C', 'D'])
    """

    name: str
    frame: LinkId
    links: tuple[LinkId, ...]
    pairs: tuple[Pair, ...]
    inputs: tuple[Drive, ...]
    geometry: Sketch | None = None
    general: General = field(default_factory=General)
    source: str = "<data>"
    group_params: Mapping[tuple[LinkId, ...], GroupParams] = field(default_factory=dict)
    names: Mapping[LinkId, str] = field(default_factory=dict)
    local_names: Mapping[str, Mapping[LinkId, str]] = field(default_factory=dict)
    identification: tuple[IdentificationRow, ...] | None = None
    claims: Mapping[str, int] = field(default_factory=dict)
    forces: ForceData | None = None
    student: Student | None = None
    warnings: tuple[Issue, ...] = ()
    _index: dict[str, dict[Any, Any]] = field(default_factory=dict, init=False, repr=False,
                                              compare=False)

    def _lookup(self, table: str) -> dict[Any, Any]:
        """Pair indexes, built on first use (the chain is immutable)."""
        if not self._index:
            by_id: dict[Any, Pair] = {}
            at: dict[Any, list[Pair]] = {link: [] for link in self.links}
            for pair in self.pairs:
                by_id.setdefault(pair.id, pair)
                for link in pair.links:
                    at.setdefault(link, []).append(pair)
            for pair in self.pairs:
                by_id.setdefault(pair.origin, pair)
            self._index.update(by_id=by_id, at={k: tuple(v) for k, v in at.items()})
        return self._index[table]

    def pair(self, pair_id: PairId) -> Pair:
        """The pair with this id (a user joint id of a compound hinge gives its first pair).

        Raises
        ------
        KeyError
            If no pair has this id.
        """
        try:
            found: Pair = self._lookup("by_id")[pair_id]
        except KeyError:
            raise KeyError(f"no pair {pair_id!r} in chain {self.name!r}") from None
        return found

    def link_names(self, lang: str) -> dict[LinkId, str]:
        """The human names of links in ``lang``: a name given in that language, else the one
        name the table gives."""
        return {**self.names, **self.local_names.get(lang, {})}

    def link(self, link_id: LinkId) -> Link:
        """The link with its human name, if the table gave one."""
        return Link(link_id, self.names.get(link_id))

    @property
    def moving_links(self) -> tuple[LinkId, ...]:
        """All links but the frame."""
        return tuple(link for link in self.links if link != self.frame)

    def pairs_of(self, link: LinkId) -> tuple[Pair, ...]:
        """The pairs that touch ``link``."""
        pairs: tuple[Pair, ...] = self._lookup("at").get(link, ())
        return pairs
