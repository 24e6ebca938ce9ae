"""The DGTU structure-identification table (``method.md`` §3.1, table 1.4/1.6).

:func:`identification_table` fills the table from a structural analysis: one row per group,
the input group(s) included, in layering order. :func:`check_identification` compares a
table filled by hand with the analysis and reports every mismatch by row and field
(expected versus found); the rows may come in any order (the course prints them by kind).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, overload

from assur.errors import StructureError
from assur.kinds import kind_of
from assur.model import COLUMNS, IdentificationRow, LinkId, PairType, id_key
from assur.structure.analysis import StructuralAnalysis
from assur.structure.classification import AssurGroup
from assur.text import Message, in_every_language, joined

__all__ = ["COLUMNS", "IdentificationRow", "Mismatch", "check_identification",
           "field_mismatch", "identification_table", "require_dgtu"]

#: The form of an output-parameter code in the course's table 1.6: ``5`` or ``8;2``.
_CODE = re.compile(r"\s*-?\d+\s*(;\s*-?\d+\s*)?")


@dataclass(frozen=True)
class Mismatch:
    """A difference between a user's identification table and the analysis.

    Attributes
    ----------
    row : int or None
        Index of the row in the user's table (None for a missing row or a table-level count).
    label : str
        Where, e.g. ``structure_identification[2] (L2, i = 9, j = 8)``; the same in both languages.
    field : str
        The column (``"i_plus_1"``) or count (``"W"``); ``"row"`` for a missing row.
    expected, found : object
        The analysis' value and the table's value.
    message : Message
        The sentence.
    """

    row: int | None
    label: str
    field: str
    expected: Any
    found: Any
    message: Message

    def text(self, lang: str = "en") -> str:
        """The sentence in ``lang``."""
        return self.message.text(lang)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: the sentence in every language (``message`` in English, ``message_<lang>`` in the others)."""
        return {"row": self.row, "label": self.label, "field": self.field,
                "expected": self.expected, "found": self.found,
                **in_every_language("message", self.message)}


def require_dgtu(analysis: StructuralAnalysis) -> None:
    """Raise :class:`StructureError` unless the mechanism is made of input groups and dyads
    of kinds 1–5 only (the tables of the course describe no other groups)."""
    others = [g.label for g in analysis.groups if not g.is_dyad or g.composite]
    placed = {link for g in (*analysis.input_groups, *analysis.groups) for link in g.links}
    unplaced = [link for link in analysis.chain.moving_links if link not in placed]
    if unplaced or others:
        parts = []
        if others:
            parts.append(Message("structure.not_dyads", {"groups": ", ".join(others)}))
        if unplaced:
            parts.append(Message("structure.in_no_group",
                                 {"links": ", ".join(map(str, unplaced))}))
        raise StructureError(Message("ident.dyads_only", {
            "name": analysis.chain.name, "why": joined(parts, "term.clauses")}))


def identification_table(analysis: StructuralAnalysis,
                         variants: Mapping[tuple[Any, Any], int] | None = None, *,
                         out_codes: Mapping[tuple[Any, Any], str] | None = None,
                         ) -> list[IdentificationRow]:
    """Fill the structure-identification table from an analysis, in layering order.

    The assembly variant is a property of the dimensions, not of the structure: pass the
    σ of each dyad (keyed by its links ``(i, j)``) when the dimensions are known, e.g. from
    the kinematic model of the table's sketch; otherwise the table gets the default (+1 for
    L1/L2, 0 for L3). For L3 the course writes its default branch σ = +1 as 0.

    The output-parameter code is written only where the caller knows it (``out_codes``, e.g.
    from a synthesis problem's ``output:``): what the course's codes mean is lost from the
    text (``method.md`` §3.2), so the structure alone gives none and ``out_code`` is None.

    Raises
    ------
    StructureError
        If the mechanism is not made of input groups and dyads of kinds 1–5 only.

    Parameters
    ----------
    analysis : StructuralAnalysis
        The analysed chain.
    variants : mapping, optional
        Assembly variant σ per group, keyed by the group's links ``(i, j)``; default +1.
    out_codes : mapping, optional
        The output-parameter code of the groups whose output the caller knows, keyed by the
        group's links ``(i, j)`` (``(i, None)`` for an input group).

    Returns
    -------
    list of IdentificationRow
        One row per group in layering order, L0 first.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> [(row.L, row.i, row.j) for row in assur.identification_table(analysis)]
    [(0, 1, None), (1, 2, 3)]
    """
    require_dgtu(analysis)
    rows = []
    for seq, group in enumerate((*analysis.input_groups, *analysis.groups), start=1):
        kind = group.kind or 0
        assert group.i is not None  # an input group or a dyad names its link i
        rows.append(IdentificationRow(
            L=kind, seq=seq, i_minus_1=group.i_minus_1, j_minus_1=group.j_minus_1, i=group.i,
            j=group.j, i_plus_1=_successor(analysis, group, group.i),
            j_plus_1=_successor(analysis, group, group.j) if group.j is not None else None,
            variant=_variant(kind, (variants or {}).get((group.i, group.j))),
            out_code=(out_codes or {}).get((group.i, group.j))))
    return rows


def _variant(number: int, sigma: int | None) -> int | None:
    """The table's variant of a dyad with assembly sign ``sigma`` (None: not known).

    A kind whose default variant is 0 (L3) writes its default branch σ = +1 as 0.
    """
    kind = kind_of(number)
    if sigma is None or not kind.sided:
        return kind.default_variant
    return kind.default_variant if sigma > 0 else int(sigma)


def _successor(analysis: StructuralAnalysis, group: AssurGroup, link: LinkId | None
               ) -> LinkId | list[LinkId] | None:
    """Links of later groups hinged (R pair) to ``link``: one id, a list, or None."""
    if link is None:
        return None
    own = {p for p, _, _ in group.external} | set(group.internal)
    found = sorted({pair.other(link) for pair in analysis.chain.pairs_of(link)
                    if pair.type is PairType.R and pair.id not in own}, key=id_key)
    if not found:
        return None
    return found[0] if len(found) == 1 else found


def _flexible(group: AssurGroup, frame: LinkId) -> bool:
    """Whether the course leaves the choice of i and j free for this dyad."""
    kind = group.group_kind
    if kind is None or not kind.j_rule.startswith("frame"):
        return False
    return (group.i_minus_1 == frame) == (group.j_minus_1 == frame)


@overload
def check_identification(analysis: StructuralAnalysis,
                         rows: Iterable[Mapping[str, Any] | IdentificationRow],
                         *, table: str = ...,
                         out_codes: Mapping[tuple[Any, Any], str] | None = ...
                         ) -> list[Mismatch]: ...


@overload
def check_identification(analysis: StructuralAnalysis, rows: None,
                         *, table: str = ...,
                         out_codes: Mapping[tuple[Any, Any], str] | None = ...) -> None: ...


def check_identification(analysis: StructuralAnalysis,
                         rows: Iterable[Mapping[str, Any] | IdentificationRow] | None,
                         *, table: str = "structure_identification",
                         out_codes: Mapping[tuple[Any, Any], str] | None = None,
                         ) -> list[Mismatch] | None:
    """Compare a filled identification table with the analysis, field by field.

    Parameters
    ----------
    analysis : StructuralAnalysis
    rows : iterable of mappings (or :class:`IdentificationRow`), or None
        The user's rows, in any order, with the keys of ``method.md`` §3.3; None when
        there is no table to check (``Chain.identification`` of a table without one).
    table : str
        Table name used in the labels.
    out_codes : mapping, optional
        The output-parameter codes the caller knows, keyed by the group's links ``(i, j)``
        (:func:`identification_table`): a student's code of such a group is checked against
        it; any other code only for its form, one whole number or two joined by ``;`` (all
        the course's table 1.6 shows: what the codes mean is lost from the text).

    Returns
    -------
    list of Mismatch or None
        Empty when the table agrees with the analysis; None when no table was given.

    Examples
    --------
    The table the program builds agrees with itself; a row with the wrong kind does not:

    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> import dataclasses
    >>> rows = assur.identification_table(analysis)
    >>> assur.check_identification(analysis, rows)
    []
    >>> wrong = [rows[0], dataclasses.replace(rows[1], L=2)]
    >>> len(assur.check_identification(analysis, wrong)) > 0
    True
    >>> assur.check_identification(analysis, analysis.chain.identification) is None
    True
    """
    if rows is None:
        return None
    table_rows = [r.to_dict() if isinstance(r, IdentificationRow) else dict(r) for r in rows]
    groups = (*analysis.input_groups, *analysis.groups)
    seq_of = {id(g): k for k, g in enumerate(groups, start=1)}
    frame = analysis.chain.frame
    out: list[Mismatch] = []
    used: dict[int, int] = {}
    user_seq: dict[int, tuple[int, int, str]] = {}
    rows_of = {link: f"{table}[{index}] (L{row.get('L')})"
               for index, row in enumerate(table_rows)
               for link in (row.get("i"), row.get("j")) if link is not None}

    for index, row in enumerate(table_rows):
        label = _label(table, index, row)

        def miss(field: str, expected: Any, found: Any, why: Message | None = None,
                 shown: Message | None = None, index: int = index, label: str = label) -> None:
            out.append(field_mismatch(index, label, field, expected, found, why, shown))

        user_i, user_j = row.get("i"), row.get("j")
        group = analysis.group_of(user_i) if user_i is not None else None
        if group is None and user_j is not None:
            group = analysis.group_of(user_j)
        if group is None:
            miss("i", None, user_i, Message("ident.why.no_group"), Message("ident.a_link"))
            continue
        key = id(group)
        if key in used:
            miss("row", None, group.label, Message("ident.why.described",
                                                   {"group": group.label, "row": used[key]}))
            continue
        used[key] = index
        if group.group_class > 1 and not group.is_dyad:
            miss("L", None, row.get("L"), Message("ident.why.not_dyad", {"group": group.label}))
            continue
        expected_links = set(group.links)
        found_links = {x for x in (user_i, user_j) if x is not None}
        if found_links != expected_links:
            partner = sorted(expected_links - {user_i}, key=id_key)
            field = "j" if user_i in expected_links else "i"
            miss(field, partner[0] if len(partner) == 1 else (partner or None),
                 row.get(field), Message("ident.why.row_group", {"group": group.label}))
            continue
        kind = group.kind or 0
        if row.get("L") != kind:
            title = kind_of(kind)
            miss("L", kind, row.get("L"), Message(
                "ident.why.is_input" if title.is_input else "ident.why.is_kind",
                {"group": group.label, "kind": Message(f"{title.key}.name")}))
        i, j = group.i, group.j
        if (user_i, user_j) != (i, j):
            if not (group.j is not None and _flexible(group, frame)):
                rule = Message(f"{kind_of(kind).key}.roles")
                miss("i", group.i, user_i, rule)
                if group.j is not None:
                    miss("j", group.j, user_j, rule)
            # judge the neighbour columns in the orientation that explains the row better
            theirs = _neighbours(analysis, group, user_i, user_j, row, index, label, rows_of)
            ours = _neighbours(analysis, group, i, j, row, index, label, rows_of)
            out.extend(theirs if len(theirs) < len(ours) else ours)
        else:
            out.extend(_neighbours(analysis, group, i, j, row, index, label, rows_of))
        if row.get("variant") not in kind_of(kind).variants and "variant" in row:
            allowed = kind_of(kind).variants
            if len(allowed) == 1:
                miss("variant", allowed[0], row.get("variant"),
                     Message("ident.why.variant", {"kind": kind}))
            else:
                miss("variant", list(allowed), row.get("variant"),
                     Message("ident.why.variant", {"kind": kind}),
                     Message("ident.any_of", {"values": ", ".join(map(_shown, allowed))}))
        code = row.get("out_code")
        known = (out_codes or {}).get((i, j))
        if code is not None and known is not None and str(code) != known:
            miss("out_code", known, code, Message("ident.why.out_code", {"group": group.label}))
        elif code is not None and known is None and not _CODE.fullmatch(str(code)):
            miss("out_code", None, code, Message("ident.why.out_code_form"),
                 Message("ident.code_form"))
        if row.get("seq") is not None:
            user_seq[key] = (row["seq"], index, label)

    for group in groups:
        if id(group) not in used and (group.group_class == 1 or group.is_dyad):
            out.append(Mismatch(None, table, "row", group.label, None,
                                Message("ident.no_row", {"table": table, "group": group.label})))
    out += _check_seq(analysis, groups, seq_of, user_seq)
    out += _check_claims(analysis, table)
    return out


def _neighbours(analysis: StructuralAnalysis, group: AssurGroup, i: LinkId | None,
                j: LinkId | None, row: Mapping[str, Any], index: int, label: str,
                rows_of: Mapping[LinkId, str]) -> list[Mismatch]:
    """Mismatches of the columns i−1, j−1, i+1, j+1 for the roles (i, j); ``rows_of``
    names the user's row of each link."""
    out = []
    for field, link in (("i_minus_1", i), ("j_minus_1", j)):
        expected = _known_end(group, link)
        if field in row and row[field] != expected:
            why = (Message("ident.why.external", {"link": link, "known": expected})
                   if expected is not None else None)
            out.append(field_mismatch(index, label, field, expected, row[field], why))
    for field, link in (("i_plus_1", i), ("j_plus_1", j)):
        later = _successor(analysis, group, link)
        if field in row and link is not None and not _same(row[field], later):
            out.append(field_mismatch(index, label, field, later, row[field],
                                 _successor_why(analysis, link, row[field], later, rows_of)))
    return _swaps(out)


def _swaps(found: list[Mismatch]) -> list[Mismatch]:
    """Two mismatches of one row whose values cross (each column holds what the other
    should) told once, as swapped columns."""
    out = list(found)
    for a in found:
        for b in found:
            if a.field < b.field and a in out and b in out and \
                    _same(a.found, b.expected) and _same(b.found, a.expected):
                message = Message("ident.swapped", {"label": a.label, "a": a.field, "b": b.field,
                                                    "x": _shown(a.expected),
                                                    "y": _shown(b.expected)})
                out[out.index(a)] = Mismatch(a.row, a.label, a.field, a.expected, a.found,
                                             message)
                out.remove(b)
    return out


def _successor_why(analysis: StructuralAnalysis, link: LinkId, found: Any, expected: Any,
                   rows_of: Mapping[LinkId, str]) -> Message:
    """Why the links hinged to ``link`` are ``expected``, naming the row of every link the
    user's column gets wrong: a link it lists that slides on ``link`` (a prismatic pair), or
    a hinged link it leaves out. In a table given alone the kind of that row decided."""
    def links(value: Any) -> set[LinkId]:
        return {x for x in (value if isinstance(value, list) else [value]) if x is not None}

    notes = [Message("ident.why.successors", {"link": link, "links": _text(expected)})]
    pairs = {pair.other(link): pair for pair in analysis.chain.pairs_of(link)}
    for other in sorted(links(found) ^ links(expected), key=id_key):
        pair = pairs.get(other)
        if pair is None:
            continue
        code = "ident.why.guided" if pair.type is PairType.P else "ident.why.hinged"
        notes.append(Message(code, {"other": other, "link": link, "pair": pair.id,
                                    "row": rows_of.get(other, "—")}))
    return joined(notes, "term.clauses")


def _known_end(group: AssurGroup, link: LinkId | None) -> LinkId | None:
    if link is None:
        return None
    for _, member, known in group.external:
        if member == link:
            return known
    return None


def _same(found: Any, expected: Any) -> bool:
    if isinstance(expected, list):
        return isinstance(found, list) and sorted(found, key=id_key) == expected
    return bool(found == expected)


def _text(value: Any) -> str:
    if value is None:
        return "—"
    return ", ".join(map(str, value)) if isinstance(value, list) else str(value)


def _label(table: str, index: int, row: Mapping[str, Any]) -> str:
    roles = ", ".join(f"{k} = {row[k]}" for k in ("i", "j") if row.get(k) is not None)
    return f"{table}[{index}] (L{row.get('L')}, {roles})"


def field_mismatch(index: int | None, label: str, field: str, expected: Any, found: Any,
                   why: Message | None = None, shown: Message | None = None) -> Mismatch:
    """A mismatch of one field; ``shown`` describes the expected value when it is no value."""
    data = {"label": label, "field": field, "found": _shown(found),
            "expected": shown if shown is not None else _shown(expected)}
    message = (Message("ident.mismatch_because", {**data, "why": why}) if why is not None
               else Message("ident.mismatch", data))
    return Mismatch(index, label, field, expected, found, message)


def _shown(value: Any) -> str:
    return "null (–)" if value is None else repr(value) if isinstance(value, str) else str(value)


def _check_seq(analysis: StructuralAnalysis, groups: tuple[AssurGroup, ...],
               seq_of: dict[int, int], user_seq: dict[int, tuple[int, int, str]]
               ) -> list[Mismatch]:
    """A user's ``seq`` may differ from ours if it is still a valid layering order."""
    out = []
    by_link = {link: g for g in groups for link in g.links}
    values = [s for s, _, _ in user_seq.values()]
    for group in groups:
        if id(group) not in user_seq:
            continue
        seq, index, label = user_seq[id(group)]
        before = {id(by_link[k]) for _, _, k in group.external if k in by_link}
        late = [g for g in groups if id(g) in before and id(g) in user_seq
                and user_seq[id(g)][0] >= seq]
        clash = values.count(seq) > 1 or not 1 <= seq <= len(groups)
        if late or (clash and seq != seq_of[id(group)]):
            why = (Message("ident.why.seq_late", {"groups": ", ".join(g.label for g in late)})
                   if late else Message("ident.why.seq_unique", {"n": len(groups)}))
            out.append(field_mismatch(index, label, "seq", seq_of[id(group)], seq, why))
    return out


def _check_claims(analysis: StructuralAnalysis, table: str) -> list[Mismatch]:
    actual = {"n_moving_links": analysis.n, "p5": analysis.p5, "p4": analysis.p4,
              "W": analysis.W, "N_Q": len(analysis.input_groups) + len(analysis.groups)}
    out = []
    for key, found in analysis.chain.claims.items():
        if actual[key] != found:
            out.append(Mismatch(None, table, key, actual[key], found, Message(
                "ident.claim", {"field": key, "expected": actual[key], "found": found})))
    return out

