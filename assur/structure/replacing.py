"""The replacing mechanism (заменяющий механизм) of a chain with higher pairs, and its passive
degrees of freedom.

A higher pair takes one degree of freedom; a link with two lower pairs takes one too
(3 − 2·2 = −1). So each higher pair is replaced, at one position, by one link hinged at the
centres of curvature of the two profiles at the contact: the replacing mechanism has the
same mobility and, at that position, the same velocities and accelerations as the original
up to the second order (Артоболевский, *Теория механизмов и машин*, 1988, §8 «Заменяющие
механизмы»; Uicker, Pennock & Shigley, *Theory of Machines and Mechanisms*, 5th ed., §3.6
"Equivalent linkages"). The rule used here (``docs/structure.md``, "Higher pairs"):

* two curved profiles (circles, a point, a table): a link with a revolute pair at each
  centre of curvature (a knife edge's centre of curvature is its point);
* a straight profile (a flat face) has its centre of curvature at infinity: the replacing
  link is hinged at the other profile's centre of curvature and slides in a prismatic pair
  along the straight profile's direction;
* a gear mesh (involute teeth): the centres of curvature of the two tooth profiles at the
  contact are the points N1, N2 where the line of action touches the base circles
  (:func:`assur.profiles.gear_contact`): a link N1N2 hinged to both gears.

For circles and lines the centres of curvature are fixed on their links, so the replacement
is exact at every position (an eccentric cam with a roller follower *is* a four-bar or a
slider-crank); for a tabulated profile it holds at the sketched position only.

A **passive** (local) degree of freedom is a motion of one link that moves no other: a
roller turning freely about its pin, whose profile in every higher pair it makes is a
circle centred on that pin. It is counted in W = 3n − 2p5 − p4 and subtracted; the roller
is welded to the link that carries its pin before the higher pairs are replaced.

Examples
--------
>>> from assur.io.chain_table import chain_from_dict
>>> chain = chain_from_dict({"mechanism": {"pairs": [
...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [2, 3]},
...     {"id": "C", "type": "P", "links": [3, 0], "guide": 0},
...     {"id": "K", "type": "H", "links": [1, 2]}], "inputs": [1]},
...     "geometry": {"A": {"point": [0, 0]}, "B": {"point": [15, 50]},
...                  "C": {"point": [15, 80], "direction": 90},
...                  "K": {"profiles": [{"circle": {"centre": [15, 0], "radius": 40}},
...                                     {"circle": {"centre": [15, 50], "radius": 10}}]}}})
>>> replaced = replacement(chain)
>>> [(dof.link, dof.pin) for dof in replaced.passive]
[(2, 'B')]
>>> [(pair.id, pair.type.value, pair.links) for pair in replaced.chain.pairs]
[('A', 'R', (0, 1)), ('C', 'P', (3, 0)), ('K1', 'R', (1, "K'")), ('K2', 'R', ("K'", 3))]
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace
from typing import Any

from assur.model import (
    Chain,
    CircleProfile,
    Direction,
    HigherPair,
    LineProfile,
    LinkId,
    Pair,
    PairId,
    PairType,
    Profile,
    Sketch,
    joint_key,
)
from assur.profiles import TOUCH_TOLERANCE, contact, gear_contact
from assur.text import Message

__all__ = ["PassiveDof", "Replaced", "Replacement", "passive_dofs", "replacement",
           "replacing_mechanism"]


@dataclass(frozen=True, slots=True)
class PassiveDof:
    """A passive (local) degree of freedom: a roller turning about its pin.

    Attributes
    ----------
    link : link id
        The roller.
    pin : pair id
        Its revolute pair.
    carrier : link id
        The link the pin joins it to (the roller is welded to it in the replacing
        mechanism).
    pairs : tuple of pair ids
        The higher pairs in which its profile is a circle centred on the pin.
    """

    link: LinkId
    pin: PairId
    carrier: LinkId
    pairs: tuple[PairId, ...]

    @property
    def reason(self) -> Message:
        """Why the motion is passive, as a sentence."""
        return Message("structure.passive.roller",
                       {"link": self.link, "pin": self.pin, "carrier": self.carrier,
                        "pairs": ", ".join(map(str, self.pairs))})

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (the reason in every language is added by the analysis)."""
        return {"link": self.link, "pin": self.pin, "carrier": self.carrier,
                "pairs": list(self.pairs)}


@dataclass(frozen=True, slots=True)
class Replacement:
    """One higher pair and the link that replaces it.

    Attributes
    ----------
    pair : pair id
        The higher pair.
    link : link id
        The replacing link.
    pairs : tuple of two Pair
        Its lower pairs: with the first and with the second link of the higher pair (after
        the passive rollers are welded to their carriers).
    points : tuple of two (complex or None)
        The sketch points of those pairs: the centres of curvature at the contact (for a
        prismatic pair, a point of its slide line); None without a sketch.
    """

    pair: PairId
    link: LinkId
    pairs: tuple[Pair, Pair]
    points: tuple[complex | None, complex | None] = (None, None)

    def to_dict(self) -> dict[str, Any]:
        """The JSON form."""
        return {"pair": self.pair, "link": self.link,
                "pairs": [{"id": p.id, "type": p.type.value, "links": list(p.links),
                           "point": None if point is None else [point.real, point.imag]}
                          for p, point in zip(self.pairs, self.points, strict=True)]}


@dataclass(frozen=True, slots=True)
class Replaced:
    """A chain with higher pairs and its replacing mechanism.

    Attributes
    ----------
    chain : Chain
        The replacing mechanism: lower pairs only, the passive rollers welded, a replacing
        link per higher pair, its sketch at the original's sketched position.
    passive : tuple of PassiveDof
    replacements : tuple of Replacement
    """

    chain: Chain
    passive: tuple[PassiveDof, ...]
    replacements: tuple[Replacement, ...]


def passive_dofs(chain: Chain) -> tuple[PassiveDof, ...]:
    """The passive degrees of freedom of a chain: its free rollers.

    A roller is a moving link, not an input, with one lower pair, revolute (its pin), and
    higher pairs only besides, none a gear mesh, its profile in each a convex circle centred
    on the pin (within :data:`~assur.profiles.TOUCH_TOLERANCE`). Its turning about the pin
    changes no contact and moves no other link. The profiles come from the sketch: a chain
    without one has none found.

    Parameters
    ----------
    chain : Chain

    Returns
    -------
    tuple of PassiveDof
        In the order of the chain's links.
    """
    sketch = chain.geometry
    if sketch is None or not chain.higher:
        return ()
    driven = {drive.link for drive in chain.inputs}
    found = []
    for link in chain.moving_links:
        lower = chain.pairs_of(link)
        higher = [pair for pair in chain.higher if link in pair.links]
        if link in driven or len(lower) != 1 or lower[0].type is not PairType.R or not higher:
            continue
        pin = sketch.points.get(joint_key(lower[0]))
        profiles = [_profile_of(sketch, pair, link) for pair in higher]
        if pin is not None and all(
                pair.gear is None and isinstance(profile, CircleProfile) and
                not profile.concave and profile.radius > 0 and
                abs(profile.centre - pin) <= TOUCH_TOLERANCE
                for pair, profile in zip(higher, profiles, strict=True)):
            found.append(PassiveDof(link, lower[0].id, lower[0].other(link),
                                    tuple(pair.id for pair in higher)))
    return tuple(found)


def replacing_mechanism(chain: Chain) -> Chain:
    """The replacing mechanism of a chain at its sketched position: the passive rollers
    welded to their carriers, each higher pair replaced by a link with two lower pairs at
    the centres of curvature of its profiles (see the module's rule).

    For circle and line profiles (an eccentric, a roller, a knife edge, a flat face) the
    replacing link joins points fixed on the two links, so the replacement holds at every
    position; for a tabulated profile, at the sketched position only. A chain without a
    sketch gets revolute pairs without points (its structure only).

    Parameters
    ----------
    chain : Chain
        A chain with higher pairs (one without any is returned as it is).

    Returns
    -------
    Chain
        Lower pairs only; the replacing links are named ``"<pair id>'"``, their pairs
        ``"<pair id>1"`` (with the pair's first link) and ``"<pair id>2"``; the sketch gives
        their points and, for a prismatic pair, its direction.

    Examples
    --------
    A gear pair on fixed axles: the link N1N2 on the line of action makes it a four-bar.

    >>> from assur.io.chain_table import chain_from_dict
    >>> gears = chain_from_dict({"mechanism": {"pairs": [
    ...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [0, 2]},
    ...     {"id": "G", "type": "H", "links": [1, 2], "gear": {"radii": [30, 60]}}],
    ...     "inputs": [1]}, "geometry": {"A": {"point": [0, 0]}, "B": {"point": [90, 0]},
    ...                                  "G": {"centres": [[0, 0], [90, 0]]}}})
    >>> four_bar = replacing_mechanism(gears)
    >>> [pair.links for pair in four_bar.pairs]
    [(0, 1), (0, 2), (1, "G'"), ("G'", 2)]
    >>> round(abs(four_bar.geometry.points["G1"]), 6)  # the base radius 30·cos 20°
    28.190779
    """
    return replacement(chain).chain


def replacement(chain: Chain) -> Replaced:
    """The replacing mechanism of a chain with what was replaced and why
    (:func:`replacing_mechanism` gives its chain).

    Parameters
    ----------
    chain : Chain

    Returns
    -------
    Replaced
    """
    if not chain.higher:
        return Replaced(chain, (), ())
    passive = passive_dofs(chain)
    welded = {dof.link: dof.carrier for dof in passive}
    pins = {dof.pin for dof in passive}
    taken_links = set(chain.links)
    taken_pairs = {pair.id for pair in chain.pairs} | {pair.id for pair in chain.higher} | \
        {pair.origin for pair in chain.pairs if pair.origin is not None}
    replacements = []
    for higher in chain.higher:
        link = _fresh(f"{higher.id}'", taken_links)
        ids = (_fresh(f"{higher.id}1", taken_pairs), _fresh(f"{higher.id}2", taken_pairs))
        ends = (welded.get(higher.links[0], higher.links[0]),
                welded.get(higher.links[1], higher.links[1]))
        replacements.append(_replace(chain.geometry, higher, link, ids, ends))
    pairs = tuple(pair for pair in chain.pairs if pair.id not in pins) + tuple(
        pair for item in replacements for pair in item.pairs)
    links = tuple(link for link in chain.links if link not in welded) + tuple(
        item.link for item in replacements)
    geometry = None if chain.geometry is None else _sketch(chain.geometry, replacements)
    names = {link: name for link, name in chain.names.items() if link not in welded}
    replaced = replace(chain, links=links, pairs=pairs, higher=(), geometry=geometry,
                       names=names)
    return Replaced(replaced, passive, tuple(replacements))


def _profile_of(sketch: Sketch, pair: HigherPair, link: LinkId) -> Profile | None:
    """The profile of ``link`` in a higher pair (for a gear, its pitch circle)."""
    profiles = sketch.profiles.get(pair.id)
    if profiles is None:
        return None
    return profiles[0] if pair.links[0] == link else profiles[1]


def _fresh(name: str, taken: set[Any]) -> str:
    """``name``, primed until no link or pair has it; then taken."""
    while name in taken:
        name += "'"
    taken.add(name)
    return name


def _replace(sketch: Sketch | None, higher: HigherPair, link: LinkId, ids: tuple[str, str],
             ends: tuple[LinkId, LinkId]) -> Replacement:
    """The replacing link of one higher pair, by the module's rule."""
    profiles = None if sketch is None else sketch.profiles.get(higher.id)
    if profiles is None:
        return Replacement(higher.id, link, (
            Pair(ids[0], PairType.R, (ends[0], link), None, ids[0]),
            Pair(ids[1], PairType.R, (link, ends[1]), None, ids[1])))
    first, second = profiles
    if higher.gear is not None:
        assert isinstance(first, CircleProfile) and isinstance(second, CircleProfile)
        touch = gear_contact(higher.gear, (first.centre, second.centre))
    else:
        found = contact(first, second)
        assert found is not None  # the sketch reader refuses profiles that cannot touch
        touch = found
    centre_a, centre_b = touch.centres
    if centre_b is None:  # a straight second profile: slide along it
        assert centre_a is not None and isinstance(second, LineProfile)
        return Replacement(higher.id, link, (
            Pair(ids[0], PairType.R, (ends[0], link), None, ids[0]),
            Pair(ids[1], PairType.P, (link, ends[1]), ends[1], ids[1])), (centre_a, centre_a))
    if centre_a is None:  # a straight first profile
        assert isinstance(first, LineProfile)
        return Replacement(higher.id, link, (
            Pair(ids[0], PairType.P, (ends[0], link), ends[0], ids[0]),
            Pair(ids[1], PairType.R, (link, ends[1]), None, ids[1])), (centre_b, centre_b))
    return Replacement(higher.id, link, (
        Pair(ids[0], PairType.R, (ends[0], link), None, ids[0]),
        Pair(ids[1], PairType.R, (link, ends[1]), None, ids[1])), (centre_a, centre_b))


def _sketch(sketch: Sketch, replacements: Iterable[Replacement]) -> Sketch:
    """The sketch of the replacing mechanism: the points (and slide directions) of the
    replacing links' pairs added, the profiles dropped."""
    points = dict(sketch.points)
    directions = dict(sketch.directions)
    for item in replacements:
        for pair, point in zip(item.pairs, item.points, strict=True):
            if point is not None:
                points[pair.id] = point
            if pair.type is PairType.P:
                directions[pair.id] = _slide(sketch, item.pair)
    return replace(sketch, points=points, directions=directions, profiles={})


def _slide(sketch: Sketch, higher: PairId) -> Direction:
    """The direction of the straight profile of a higher pair: the slide line of its
    replacing prismatic pair."""
    return next(profile.direction for profile in sketch.profiles[higher]
                if isinstance(profile, LineProfile))
