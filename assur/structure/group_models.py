"""The identification array of the group models (table 1.5, ``method.md`` §3.6).

Step 11 of the course's structural procedure ties every group to its generalised model: "на
каждой группе Ассура необходимо указать две внешние и одну внутреннюю кинематические пары, а
также точки N и [M] … присоединения звеньев"; step 15 asks for the array, which is also input
array 3 of block B1. The table itself is lost from the text; :func:`group_models_table` builds
the record ``method.md`` §3.6 reconstructs, one per group in layering order, L0 included:

* ``k``: the group's place in the layering order, L0 = 1, the index of its base points
  (the course's L4 of fig. 1.25, third in layering, has A_3 and B_3; its L2, fifth, A_5);
* the group's three pairs under the roles of its kind (:attr:`assur.kinds.GroupKind.roles`):
  ``H_i``/``P_i`` the external pair of link i, ``C``/``P_c`` the internal pair, ``H_j``/
  ``P_j`` the external pair of link j (L0: ``H_i``, the driven pair);
* ``N``, ``M``: the attachment points on links i and j, the pairs where links of later
  groups join them; a point is fixed where they are hinged and "не фиксированное" where a
  later link slides on a guide the link carries (link 3 of fig. 1.25);
* ``A``, ``B``: the base points A_k, B_k of the guides of the group's prismatic pairs, on the
  link that carries each guide: A_k for the guide link i slides on, B_k for the one link j
  slides on, the internal guide taking the letter left (L3: A_k, L5: B_k). The course fixes
  two of them at a hinge: L3 "базовая точка … должна совпадать с" the
  kulisa's hinge H_i, L5 takes "за базу отсчета" of T the hinge H_j; the others lie anywhere
  on their carrier (L4: "удобнее совместить" A_3 with a hinge of link 3, B_3 "в любом месте").

:func:`check_group_models` compares a student's copy with the table field by field, as
:func:`~assur.structure.identification.check_identification` does for table 1.6.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, overload

from assur.kinds import kind_of
from assur.model import Chain, LinkId, Pair, PairId, PairType, id_key
from assur.structure.analysis import StructuralAnalysis
from assur.structure.classification import AssurGroup
from assur.structure.identification import Mismatch, field_mismatch, require_dgtu
from assur.text import Message

__all__ = ["Attachment", "BasePoint", "GroupModelRow", "check_group_models",
           "group_models_table"]

#: The pair roles a row of table 1.5 may name, in the order of a kind's pairs.
PAIR_ROLES = ("H_i", "P_i", "C", "P_c", "H_j", "P_j")


@dataclass(frozen=True)
class Attachment:
    """Where links of later groups join a link of the group (the point N or M).

    Attributes
    ----------
    link : link id
        The group's link.
    hinges : tuple of pair ids
        Pairs with links of later groups at a fixed point of the link: hinges, and the
        guides of later links that slide over the point.
    guides : tuple of pair ids
        Prismatic pairs whose guide the link carries for a later link: the point slides,
        "не фиксированное".
    """

    link: LinkId
    hinges: tuple[PairId, ...]
    guides: tuple[PairId, ...]

    @property
    def pairs(self) -> tuple[PairId, ...]:
        """Every pair of the attachment, hinges first."""
        return (*self.hinges, *self.guides)

    @property
    def fixed(self) -> bool:
        """Whether the point is fixed on the link (every later link is hinged to it)."""
        return not self.guides

    def text(self) -> str:
        """The cell of the printed table: the pairs, a sliding one marked ``~``."""
        return ";".join([*map(str, self.hinges), *(f"~{p}" for p in self.guides)])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {"link": self.link, "hinges": list(self.hinges), "guides": list(self.guides),
                "fixed": self.fixed}


@dataclass(frozen=True)
class BasePoint:
    """A base point A_k or B_k of the guide of a prismatic pair of the group.

    Attributes
    ----------
    letter : str
        ``"A"`` (the guide on the side of link i) or ``"B"`` (of link j).
    k : int
        The group's place in the layering order, L0 = 1.
    pair : pair id
        The prismatic pair whose guide the point is on.
    link : link id
        The link that carries the guide: the base point is a point of this link.
    at : pair id or None
        The hinge of that link the course puts the point at (L3: H_i, L5: H_j); None where
        the point may be anywhere on the carrier.
    """

    letter: str
    k: int
    pair: PairId
    link: LinkId
    at: PairId | None

    @property
    def name(self) -> str:
        """``A_3``, ``B_6``."""
        return f"{self.letter}_{self.k}"

    def text(self) -> str:
        """The cell of the printed table: ``A_3 ∈ 3`` or ``A_4 = 2-6``."""
        return f"{self.name} = {self.at}" if self.at is not None else f"{self.name} ∈ {self.link}"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {"name": self.name, "pair": self.pair, "link": self.link, "at": self.at}


@dataclass(frozen=True)
class GroupModelRow:
    """One record of table 1.5: a group tied to its generalised model.

    Attributes
    ----------
    k : int
        Place of the group in the layering order, L0 = 1 (the index of A_k, B_k).
    L : int
        The group's kind, 0 for the input group.
    i, j : link id
        The group's links in the course's roles (j None for L0).
    pairs : tuple of (role, pair id)
        The group's pairs under the roles of its kind.
    N, M : Attachment or None
        Where later links join link i / link j; None where none does.
    A, B : BasePoint or None
        The base points of the guides on the side of link i / link j.
    """

    k: int
    L: int
    i: LinkId
    j: LinkId | None
    pairs: tuple[tuple[str, PairId], ...]
    N: Attachment | None
    M: Attachment | None
    A: BasePoint | None
    B: BasePoint | None

    @property
    def label(self) -> str:
        """``L1(2,3)``, ``L0(1)``."""
        links = self.i if self.j is None else f"{self.i},{self.j}"
        return f"L{self.L}({links})"

    def pair(self, role: str) -> PairId | None:
        """The pair of a role (``"H_i"``), None when the kind has none."""
        return dict(self.pairs).get(role)

    def cells(self) -> list[str]:
        """The row as printed: k, L, i, j, external pair of i, internal pair, external pair
        of j, N, M, A_k, B_k (a dash for none)."""
        def shown(value: object) -> str:
            return "–" if value is None else str(value)

        by_side = {side: next((f"{r} {p}" for r, p in self.pairs if r.endswith(side)), None)
                   for side in ("_i", "C", "_c", "_j")}
        internal = by_side["C"] or by_side["_c"]
        return [str(self.k), str(self.L), str(self.i), shown(self.j), shown(by_side["_i"]),
                shown(internal), shown(by_side["_j"]),
                *(shown(x.text() if x is not None else None)
                  for x in (self.N, self.M, self.A, self.B))]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: the keys of a student's copy (``docs/structure.md``)."""
        return {"k": self.k, "L": self.L, "i": self.i, "j": self.j, **dict(self.pairs),
                **{name: None if value is None else value.to_dict()
                   for name, value in (("N", self.N), ("M", self.M), ("A", self.A),
                                       ("B", self.B))}}


#: The header of the printed table 1.5 (:meth:`GroupModelRow.cells`).
HEADER = ("k", "L", "i", "j", "ext. i", "int.", "ext. j", "N", "M", "A_k", "B_k")


def group_models_table(analysis: StructuralAnalysis) -> list[GroupModelRow]:
    """Build table 1.5 of a mechanism: one record per group, L0 included, in layering order.

    Parameters
    ----------
    analysis : StructuralAnalysis
        The analysed chain.

    Returns
    -------
    list of GroupModelRow

    Raises
    ------
    StructureError
        If the mechanism is not made of input groups and dyads of kinds 1–5 only.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> rows = group_models_table(assur.analyse_structure(assur.load_chain(table)))
    >>> [(row.label, row.pairs) for row in rows]
    [('L0(1)', (('H_i', 'A'),)), ('L1(2,3)', (('H_i', 'B'), ('H_j', 'D'), ('C', 'C')))]
    """
    require_dgtu(analysis)
    groups = (*analysis.input_groups, *analysis.groups)
    return [_row(analysis, group, k) for k, group in enumerate(groups, start=1)]


def _row(analysis: StructuralAnalysis, group: AssurGroup, k: int) -> GroupModelRow:
    kind = group.group_kind
    assert kind is not None and group.i is not None
    side_pair = {"i": group.pair_i, "j": group.pair_j, "c": group.pair_c}
    pairs = tuple((role, pair_id) for role, side in kind.roles
                  if (pair_id := side_pair[side]) is not None)
    chain = analysis.chain
    own = {pair for _, pair in pairs}
    hinge = {group.i: group.pair_i, group.j: group.pair_j}
    base: dict[str, BasePoint] = {}
    # the guides of the external prismatic pairs of i and j first: A_k on the side of i,
    # B_k on the side of j; the internal guide takes the letter left (L3: A_k, L5: B_k)
    guides = [(side, pair_id) for side, pair_id in (("A", group.pair_i), ("B", group.pair_j),
                                                   ("", group.pair_c))
              if pair_id is not None and chain.pair(pair_id).type is PairType.P]
    for side, pair_id in guides:
        carrier = chain.pair(pair_id).guide
        assert carrier is not None  # a prismatic pair names the link carrying its guide
        letter = side or ("B" if "A" in base else "A")
        # a guide the group's own link carries: the course puts the base at its hinge
        at = hinge.get(carrier)
        if at is not None and chain.pair(at).type is not PairType.R:
            at = None
        base[letter] = BasePoint(letter, k, pair_id, carrier, at)
    return GroupModelRow(k, group.kind or 0, group.i, group.j, pairs,
                         _attachment(analysis, group.i, own),
                         _attachment(analysis, group.j, own) if group.j is not None else None,
                         base.get("A"), base.get("B"))


def _attachment(analysis: StructuralAnalysis, link: LinkId, own: set[PairId]
                ) -> Attachment | None:
    """Where links of later groups join ``link``: its pairs that are not the group's own
    (the group reaches the frame and earlier links through its external pairs only)."""
    later = [pair for pair in analysis.chain.pairs_of(link) if pair.id not in own]
    guides = tuple(sorted((p.id for p in later if p.type is PairType.P and p.guide == link),
                          key=id_key))
    hinges = tuple(sorted((p.id for p in later if p.id not in guides), key=id_key))
    return Attachment(link, hinges, guides) if hinges or guides else None


# ----------------------------------------------------------------------------- the check


@overload
def check_group_models(analysis: StructuralAnalysis, rows: Iterable[Mapping[str, Any]], *,
                       table: str = ...) -> list[Mismatch]: ...


@overload
def check_group_models(analysis: StructuralAnalysis, rows: None, *,
                       table: str = ...) -> None: ...


def check_group_models(analysis: StructuralAnalysis,
                       rows: Iterable[Mapping[str, Any]] | None, *,
                       table: str = "group_models") -> list[Mismatch] | None:
    """Compare a student's table 1.5 with the one the mechanism gives, field by field.

    A row names its group by ``i`` and ``j`` or by ``links`` (in any order). Every field it
    gives is checked, the others are not: ``k``, ``L``, ``i``, ``j``, the pair roles
    ``H_i``, ``P_i``, ``C``, ``P_c``, ``H_j``, ``P_j`` (a pair id, or the two links it joins
    as ``"2-6"``), ``N`` and ``M`` (a pair or a list of pairs, null for none) and ``A`` and
    ``B`` (the carrier link, or ``{link: …, at: …}``; a point the course leaves free on its
    carrier may be put at any pair of the carrier). Every group needs a row.

    Parameters
    ----------
    analysis : StructuralAnalysis
    rows : iterable of mappings, or None
        The student's records, in any order; None when there is no table.
    table : str
        Table name used in the labels.

    Returns
    -------
    list of Mismatch or None
        Empty when the copy agrees; None when no table was given.

    Raises
    ------
    StructureError
        If the mechanism is not made of input groups and dyads of kinds 1–5 only.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> rows = [{"links": [1]}, {"links": [2, 3], "H_i": "B", "C": "C", "H_j": "A"}]
    >>> [(m.field, m.expected, m.found) for m in check_group_models(analysis, rows)]
    [('H_j', 'D', 'A')]
    """
    if rows is None:
        return None
    built = group_models_table(analysis)
    by_link = {link: row for row in built for link in (row.i, row.j) if link is not None}
    chain = analysis.chain
    out: list[Mismatch] = []
    used: dict[int, int] = {}
    for index, given in enumerate(rows):
        links = _links(given)
        row = next((by_link[x] for x in links if x in by_link), None)
        label = f"{table}[{index}]" + (f" ({row.label})" if row is not None else
                                       f" ({', '.join(map(str, links))})" if links else "")
        if row is None:
            out.append(field_mismatch(index, label, "links", None, links or None,
                                      Message("ident.why.no_group"), Message("ident.a_link")))
            continue
        if row.k in used:
            out.append(field_mismatch(index, label, "row", None, row.label, Message(
                "ident.why.described", {"group": row.label, "row": used[row.k]})))
            continue
        used[row.k] = index
        out += _check_row(chain, row, given, index, label)
    out += [Mismatch(None, table, "row", row.label, None,
                     Message("ident.no_row", {"table": table, "group": row.label}))
            for row in built if row.k not in used]
    return out


def _links(given: Mapping[str, Any]) -> list[Any]:
    value = given.get("links")
    if isinstance(value, list):
        return list(value)
    return [given[key] for key in ("i", "j") if given.get(key) is not None]


def _check_row(chain: Chain, row: GroupModelRow, given: Mapping[str, Any], index: int,
               label: str) -> list[Mismatch]:
    """Every field of one record the student gives, against the built row."""
    out = []

    def miss(field: str, expected: Any, found: Any, why: Message) -> None:
        out.append(field_mismatch(index, label, field, expected, found, why))

    if "k" in given and given["k"] != row.k:
        miss("k", row.k, given["k"], Message("models.why.k", {"group": row.label}))
    if "L" in given and given["L"] != row.L:
        miss("L", row.L, given["L"], Message("models.why.kind", {"group": row.label}))
    for key in ("i", "j"):
        if key in given and given[key] != getattr(row, key):
            miss(key, getattr(row, key), given[key],
                 Message(f"{kind_of(row.L).key}.roles"))
    for role in PAIR_ROLES:
        if role not in given:
            continue
        expected = row.pair(role)
        if not _same_pairs(chain, given[role], () if expected is None else (expected,)):
            miss(role, expected, given[role], Message(
                "models.why.role", {"group": row.label, "role": role}) if expected is not None
                else Message("models.why.no_role", {"group": row.label, "role": role}))
    for name in ("N", "M"):
        if name not in given:
            continue
        point: Attachment | None = getattr(row, name)
        pairs = point.pairs if point is not None else ()
        if not _same_pairs(chain, given[name], pairs):
            link = row.i if name == "N" else row.j
            miss(name, list(pairs) if len(pairs) > 1 else (pairs[0] if pairs else None),
                 given[name], Message("models.why.attachment", {
                     "point": name, "link": link, "pairs": ", ".join(map(str, pairs)) or "—"}))
    for letter in ("A", "B"):
        if letter in given:
            why = _base_wrong(chain, getattr(row, letter), given[letter], letter, row)
            if why is not None:
                miss(letter, _base_value(getattr(row, letter)), given[letter], why)
    return out


def _base_value(point: BasePoint | None) -> object:
    """A base point as a student writes it: the carrier link, with the hinge when the
    course puts the point at one."""
    if point is None or point.at is None:
        return None if point is None else point.link
    return {"link": point.link, "at": point.at}


def _same_pairs(chain: Chain, value: Any, expected: tuple[PairId, ...]) -> bool:
    """Whether ``value`` (a pair, a list of pairs, None) names the pairs ``expected``."""
    values = [] if value is None else value if isinstance(value, list) else [value]
    return len(values) == len(expected) and all(
        any(_names(chain.pair(pair), written) for pair in expected) for written in values)


def _names(pair: Pair, written: Any) -> bool:
    """Whether ``written`` names ``pair``: its id, the user's id, or its links ``"a-b"``."""
    if written in (pair.id, pair.origin) or str(written) in (str(pair.id), str(pair.origin)):
        return True
    parts = str(written).split("-")
    return len(parts) == 2 and sorted(parts) == sorted(map(str, pair.links))


def _base_wrong(chain: Chain, point: BasePoint | None, value: Any, letter: str,
                row: GroupModelRow) -> Message | None:
    """Why a student's base point is wrong, or None when it is right."""
    if point is None:
        return (None if value is None else
                Message("models.why.no_base", {"group": row.label, "letter": letter}))
    if value is None:
        return Message("models.why.base", _point_data(point))
    link, at = (value.get("link"), value.get("at")) if isinstance(value, Mapping) else (value, None)
    if link is not None and link != point.link:
        return Message("models.why.base", _point_data(point))
    if point.at is not None:
        if at is not None and not _names(chain.pair(point.at), at):
            return Message("models.why.base_at", _point_data(point))
        return None
    if at is not None and not any(_names(pair, at) for pair in chain.pairs_of(point.link)):
        return Message("models.why.base", _point_data(point))
    return None


def _point_data(point: BasePoint) -> dict[str, Any]:
    """The values of a base point's sentences."""
    return {"name": point.name, "pair": point.pair, "link": point.link, "at": point.at}
