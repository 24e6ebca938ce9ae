"""The kinematic chain as data: links, kinematic pairs, inputs and optional geometry.

A :class:`Chain` is what the chain tables describe (``structure.md`` §2.1) after
normalisation (§2.2): every pair joins exactly two links, a hinge shared by k links has
become k − 1 binary pairs that remember the user's joint id in :attr:`Pair.origin`.

Link and pair ids are whole numbers or texts; digit-only texts are turned into numbers
(:func:`assur.io.reader.normalise_id`), so ``"3"`` and ``3`` name the same link.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Any

__all__ = [
    "Chain",
    "Drive",
    "Input",
    "Link",
    "LinkId",
    "Pair",
    "PairId",
    "PairType",
    "id_key",
]

LinkId = int | str
PairId = int | str


def id_key(value: LinkId | PairId) -> tuple[int, int | str]:
    """Sort key for ids that may be numbers or texts: numbers first, in numeric order.

    >>> sorted([10, "B", 2, "A"], key=id_key)
    [2, 10, 'A', 'B']
    """
    if isinstance(value, int):
        return (0, value)
    return (1, str(value))


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
class Drive:
    """One input of the mechanism.

    Either a driven link (``link``; it must share exactly one pair with the frame, which is
    the driven pair) or a driven pair (``pair``), which may join two moving links — an
    actuator such as a hydraulic cylinder. Both may be given for a link driven through a
    named pair.
    """

    link: LinkId | None = None
    pair: PairId | None = None


Input = Drive


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
    geometry : dict or None
        The table's ``geometry`` section, untouched (a pose for the rank test and the
        kinematic model).
    general : dict or None
        The table's ``general`` section, untouched.
    source : str
        The file the chain came from.
    group_params : dict
        ``(i, j)`` (a dyad) or ``(i,)`` (an input group) → the ``params`` of that row of an
        identification table, untouched.
    names : dict
        Optional human names of links.
    identification : tuple of dict or None
        The rows of an identification table given with the chain (to be checked).
    claims : dict
        Counts stated in an identification table (``n_moving_links``, ``p5``, ``p4``, ``W``,
        ``N_Q``), to be checked.
    """

    name: str
    frame: LinkId
    links: tuple[LinkId, ...]
    pairs: tuple[Pair, ...]
    inputs: tuple[Drive, ...]
    geometry: dict[str, Any] | None = None
    general: dict[str, Any] | None = None
    source: str = "<data>"
    group_params: dict[tuple[LinkId, ...], dict[str, Any]] = field(default_factory=dict)
    names: dict[LinkId, str] = field(default_factory=dict)
    identification: tuple[dict[str, Any], ...] | None = None
    claims: dict[str, Any] = field(default_factory=dict)
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
            return self._lookup("by_id")[pair_id]
        except KeyError:
            raise KeyError(f"no pair {pair_id!r} in chain {self.name!r}") from None

    def link(self, link_id: LinkId) -> Link:
        """The link with its human name, if the table gave one."""
        return Link(link_id, self.names.get(link_id))

    @property
    def moving_links(self) -> tuple[LinkId, ...]:
        """All links but the frame."""
        return tuple(link for link in self.links if link != self.frame)

    def pairs_of(self, link: LinkId) -> tuple[Pair, ...]:
        """The pairs that touch ``link``."""
        return self._lookup("at").get(link, ())
