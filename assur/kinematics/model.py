"""The kinematic model of a mechanism: the DGTU parameters of every Assur group.

A :class:`KinematicModel` holds, in layering order, one :class:`GroupModel` per group (the
input group L0 first) and one flat table of named parameters. The names are
``"<group label>.<column>"`` with the columns of ``method.md`` §4.3, e.g. ``"L0(1).l_1"``,
``"L1(2,3).l_i"``, ``"L4(4,5).beta_i"``. Parameters are kept in table units (mm and
degrees); any of them may be replaced by an array shaped ``(D, 1)`` to evaluate D candidate
designs in one call (:meth:`KinematicModel.with_params`).

The builders (from a sketch, from the rows' ``params:``) are in
:mod:`assur.kinematics.build`; what each kind of group means is in :mod:`assur.kinds`.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.io.params import SUPPLIED
from assur.kinds import HIGHER, KINDS, GroupKind, kind_of
from assur.kinematics.laws import InputLaw
from assur.model import LinkId, PairId

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.higher.kind import Layout

__all__ = [
    "KIND_COLUMNS",
    "Anchor",
    "GroupModel",
    "Guide",
    "KinematicModel",
    "Sketched",
    "TracePoint",
    "is_angle",
]

#: Parameter columns of each group kind, in the fixed order of tables 2.1–2.6.
#: Triads and class IV groups have no fixed columns: their parameters are named after their
#: pairs (:mod:`assur.kinematics.higher.kind`).
KIND_COLUMNS: Mapping[int | str, tuple[str, ...]] = {
    **{number: kind.columns for number, kind in KINDS.items()},
    **{code: kind.columns for code, kind in HIGHER.items()}}


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
class Sketched:
    """What a kind's sketch rule (:mod:`assur.kinematics.rules`) derives from the joints of
    a sketch, for the builder to enter as a :class:`GroupModel`.

    ``frame_i``/``frame_j`` are the link frames (origin, angle) at the reference position.
    A triad or class IV group gives its :class:`~assur.kinematics.higher.kind.Layout` and the
    frames of all its links in ``frames``.
    """

    sigma: int
    frame_i: tuple[complex, float]
    frame_j: tuple[complex, float]
    hinge_i: Anchor | None = None
    hinge_j: Anchor | None = None
    guide_i: Guide | None = None
    guide_j: Guide | None = None
    driven: str | None = None
    layout: Layout | None = None
    frames: Mapping[LinkId, tuple[complex, float]] = field(default_factory=dict)


@dataclass(frozen=True, slots=True)
class GroupModel:
    """The kinematic model of one group (L0..L5).

    Parameters
    ----------
    label : str
        ``"L<kind>(<i>,<j>)"``, the prefix of the group's parameter names.
    kind : int or str
        0 (input group), 1..5 (dyad kinds L1..L5), ``"III"`` (triad) or ``"IV"`` (class IV).
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
    kind: int | str
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
    layout: Layout | None = None

    @property
    def members(self) -> dict[LinkId, str]:
        """The group's links and their names (``"i"``, ``"j"``; a triad's ``"base"``, …)."""
        if self.layout is not None:
            return dict(zip(self.layout.links, self.layout.names, strict=True))
        return {link: side for link, side in ((self.i, "i"), (self.j, "j")) if link is not None}

    @property
    def group_kind(self) -> GroupKind:
        """What the group's kind means (:mod:`assur.kinds`)."""
        return kind_of(self.kind)

    @property
    def name(self) -> str:
        """Kind and links for reports, e.g. ``'L1 RRR (2, 3)'``, ``'L0 input group (1)'``."""
        return self.title("en")

    def title(self, lang: str) -> str:
        """Kind and links in ``lang``: ``'L1 RRR (2, 3)'``, ``'L1 ВВВ (2, 3)'``."""
        members = list(self.members)
        links = ", ".join(map(str, members if self.layout is None else sorted(members, key=str)))
        kind = self.group_kind
        title = kind.pair_text(lang) or (kind.title(lang) if kind.is_input else "")
        return f"{kind.code} {title} ({links})" if title else f"{kind.code} ({links})"

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
    drive : {'crank', 'actuator', 'slider', 'laws'}
        What the input coordinate q is: the crank rotation φ (radians, φ = 0 at the
        reference position), the actuator length (mm), a slider's displacement along its
        frame guide from the reference position (mm), or the cycle parameter t (radians) of
        which every input's coordinate is a law (``laws``; several inputs, or one given a law).
    input_range : tuple of float
        The analysed interval of q: (0, 2π) for a full-turn crank or a cycle of laws, the
        stroke for an actuator or a slider.
    tracing : tuple of TracePoint
        Named tracing points.
    links : mapping
        Moving link → (group label, ``'i'`` or ``'j'``): which group solves its pose.
    pair_links : mapping
        Pair id → (type ``'R'``/``'P'``, the two links, guide carrier or None).
    source : str
        The table the model was built from.
    laws : mapping
        Label of the group holding an input → its :class:`~assur.kinematics.laws.InputLaw`
        (``drive == 'laws'`` only).

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> model.input_range
    (0.0, 6.283185307179586)
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
    source: str = "<data>"
    laws: Mapping[str, InputLaw] = field(default_factory=dict)

    @property
    def periodic(self) -> bool:
        """Whether the analysed interval is one full cycle (a crank's turn, a cycle of laws)."""
        lo, hi = self.input_range
        return self.drive in ("crank", "laws") and math.isclose(hi - lo, 2 * math.pi)

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
