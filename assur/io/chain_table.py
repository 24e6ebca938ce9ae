"""Chain tables and DGTU identification tables (YAML) → :class:`~assur.model.Chain`.

Two forms are read (see ``docs/tables.md``):

* the **chain form** (``structure.md`` §2.1): a ``mechanism:`` mapping with ``frame``,
  ``links``, ``pairs``, ``inputs`` and an optional ``geometry``; it may also carry a
  ``structure_identification:`` table, which is then checked against the chain;
* the **identification form** (``method.md`` §3.3): only ``structure_identification:``
  rows (``L``, ``i_minus_1``, ``j_minus_1``, ``i``, ``j``, …); the chain is rebuilt from
  the rows: every row names its group's kind, so the pair types and the guide carriers
  follow from the kind (``method.md`` §2.0).

The ``geometry:`` sketch is read here, once, into a :class:`~assur.model.Sketch`
(:mod:`assur.io.sketch`); the identification rows become
:class:`~assur.model.IdentificationRow` objects; ``general:`` becomes a
:class:`~assur.model.General` (:mod:`assur.io.general`) and the rows' ``params:`` are kept
for the kinematic model. Every problem of a table is collected and raised as one
:class:`~assur.errors.TableError`.
"""

from __future__ import annotations

import datetime
import itertools
import os
from collections.abc import Collection
from dataclasses import replace
from typing import Any

from assur.errors import TableError
from assur.io.general import read_general
from assur.io.params import read_params
from assur.io.reader import MISSING, Node, TableReader, describe, is_number, normalise_id
from assur.io.sketch import Joints, actuator_pairs, read_sketch
from assur.kinds import KINDS, kind_of
from assur.model import (
    Chain,
    Drive,
    ForceData,
    GroupParams,
    IdentificationRow,
    LinkId,
    Pair,
    PairId,
    PairType,
    Sketch,
    Student,
    id_key,
)
from assur.text import DEFAULT, Message, languages

__all__ = [
    "IDENTIFICATION_FIELDS",
    "chain_from_dict",
    "load_chain",
    "pair_label",
    "read_student",
    "recentre_hinge",
]

#: The sections of the force analysis (:data:`assur.forces.table.SECTIONS`).
_FORCES = ("masses", "loads", "gravity")
_TOP_CHAIN = ("schema_version", "mechanism", "general", "geometry", "structure_identification",
              "n_moving_links", "p5", "p4", "W", "N_Q", "layering_order", "student", *_FORCES)
_TOP_TABLE = ("schema_version", "mechanism", "name", "frame", "general", "geometry",
              "structure_identification", "n_moving_links", "p5", "p4", "W", "N_Q",
              "layering_order", "student")
_MECHANISM = ("name", "frame", "links", "pairs", "inputs", "geometry")
_PAIR = ("id", "type", "links", "guide", "name")
_LINK = ("id", "name")
_INPUT = ("link", "pair", "stroke", "phase", "ratio", "table")
IDENTIFICATION_FIELDS = ("L", "seq", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1",
                         "j_plus_1", "variant", "out_code", "params")
_CLAIMS = ("n_moving_links", "p5", "p4", "W", "N_Q")


def load_chain(path: str | os.PathLike[str]) -> Chain:
    """Read a chain table or an identification table.

    Parameters
    ----------
    path : path-like
        The YAML file.

    Returns
    -------
    Chain

    Raises
    ------
    TableError
        Listing every problem of the file (file, table, row, field, expected, found).

    Examples
    --------
    >>> import pathlib, assur
    >>> tables = pathlib.Path(assur.__file__).parents[1] / "input_tables"
    >>> chain = assur.load_chain(tables / "four_bar.yaml")
    >>> len(chain.links), len(chain.pairs)
    (4, 4)
    """
    reader = TableReader.from_path(path, kind="chain")
    return _read(reader)


def chain_from_dict(data: Any, source: str = "<data>") -> Chain:
    """Build a chain from already parsed table data (see :func:`load_chain`).

    Parameters
    ----------
    data : mapping
        The table as YAML would give it (``mechanism:`` with ``pairs:`` and ``inputs:``, or an
        identification table).
    source : str, optional
        The file name used in messages.

    Returns
    -------
    Chain
        The typed chain with its sketch and identification rows, if any.

    Raises
    ------
    TableError
        For every problem of the table at once.

    Examples
    --------
    >>> from assur import chain_from_dict
    >>> chain = chain_from_dict({"mechanism": {"pairs": [
    ...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
    ...     {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
    ...     "inputs": [1]}})
    >>> len(chain.links), len(chain.pairs)
    (4, 4)
    """
    return _read(TableReader.from_data(data, source))


def pair_label(a: LinkId, b: LinkId, frame: LinkId) -> str:
    """Name of a pair rebuilt from an identification table: the two link numbers.

    The frame is written last, other pairs in increasing order, as in ``method.md`` §3.5
    (``"3-0"``, ``"2-6"``); the input pair is written ``"0-1"`` by the caller.
    """
    if a == frame or (b != frame and id_key(b) < id_key(a)):
        a, b = b, a
    return f"{a}-{b}"


def _read(reader: TableReader) -> Chain:
    data = reader.data
    if isinstance(data, dict) and isinstance(data.get("mechanism"), dict):
        chain = _read_chain_form(reader)
    elif isinstance(data, dict) and "structure_identification" in data:
        chain = _read_table_form(reader)
    else:
        reader.root(allowed=None)
        if isinstance(data, dict):
            reader.problem("", "chain.no_table")
        raise TableError(reader.source, reader.issues)
    reader.raise_if_any()
    return replace(chain, warnings=tuple(reader.warnings)) if reader.warnings else chain


# ----------------------------------------------------------------------------- chain form


def _local_name(row: Node, link: LinkId, local: dict[str, dict[LinkId, str]]) -> str | None:
    """A link name given per language (``{en: crank, ru: кривошип}``): each form checked and
    kept in ``local``; the default language's form (else the first) returned."""
    node = row.child("name", allowed=languages())
    forms = {lang: node.get(lang, kind="str") for lang in node.mapping} if node else {}
    forms = {lang: text for lang, text in forms.items() if isinstance(text, str) and text}
    if link is not MISSING:
        for lang, text in forms.items():
            local.setdefault(lang, {})[link] = text
    return forms.get(DEFAULT, next(iter(forms.values()), None))


def _read_chain_form(reader: TableReader) -> Chain:
    top = reader.root(allowed=_TOP_CHAIN)
    mech = top.child("mechanism", allowed=_MECHANISM)
    assert mech is not None
    name = mech.get("name", kind="str", required=False, default=None)
    frame = mech.get("frame", kind="id", required=False, default=0)
    names: dict[LinkId, str] = {}
    local: dict[str, dict[LinkId, str]] = {}
    links = _read_links(mech, names, local)
    raw_pairs, mentioned = _read_pairs(mech)
    if mech.mapping.get("pairs") == []:
        reader.problem("mechanism 'pairs'", "chain.no_pairs")
    known = set(links) if links is not None else None
    if links is None:
        links = [] if frame is MISSING else [frame]
        links += [link for link in dict.fromkeys(mentioned) if link not in links]
    elif frame is not MISSING and frame not in set(links):
        reader.problem("mechanism 'frame'", "chain.frame_not_a_link", frame=repr(frame),
                       links=_list(links))
    inputs = _read_inputs(mech)
    _check_pairs(reader, raw_pairs, set(links) | ({frame} - {MISSING}))  # (frame: reported)
    read = isinstance(mech.mapping.get("pairs"), list) and \
        len(raw_pairs) == len(mech.mapping["pairs"])
    _check_inputs(reader, inputs, set(links) | set(mentioned), raw_pairs, frame,  # (reported)
                  links_known=known is not None or read, pairs_known=read)
    joints = {pair.id: (pair.type.value, tuple(pair.links)) for pair in raw_pairs}
    named = {drive.pair for drive in inputs if drive.pair is not None} - set(joints)
    geometry = _geometry(reader, top, mech, joints, links, frame, inputs,
                         reported=named if read else None)
    general = read_general(top)
    student = read_student(top)
    rows, _ = _read_rows(top, required=False)
    claims = _read_claims(top)
    every = [*links, *(link for link in dict.fromkeys(mentioned) if link not in links)]
    forces = _read_forces(top, every, frame, inputs, joints,  # (a link not in links: reported)
                          geometry)
    if reader.issues:
        return _empty(reader.source)
    input_links = [d.link for d in inputs if d.link is not None]
    pairs = _normalise(raw_pairs, frame, input_links)
    return Chain(name=name or _stem(reader.source), frame=frame, links=tuple(links),
                 pairs=tuple(pairs), inputs=tuple(inputs), geometry=geometry, general=general,
                 source=reader.source, group_params=_group_params(rows), names=names,
                 local_names=local, identification=tuple(rows) if rows else None, claims=claims,
                 forces=forces, student=student)


#: The fields of the ``student:`` section, in the order of :class:`~assur.model.Student`.
_STUDENT = ("name", "group", "variant", "date")


def read_student(top: Node) -> Student | None:
    """The ``student:`` section of a table: every field optional, each checked (a wrong one
    recorded with the section and the field named).

    Parameters
    ----------
    top : Node
        The top of the table; problems go to its reader.

    Returns
    -------
    Student or None
        None when the table has no ``student:`` section.

    Examples
    --------
    >>> reader = TableReader.from_data({"student": {"name": "Ivanova A. A.", "variant": 7}})
    >>> read_student(reader.root(allowed=None))
    Student(name='Ivanova A. A.', group=None, variant='7', date=None)
    """
    node = top.child("student", allowed=_STUDENT, required=False)
    if node is None:
        return None
    values = {key: node.get(key, required=False, default=None,
                            check=_date if key == "date" else _text) for key in _STUDENT}
    return Student(**{key: None if value is None or value is MISSING else str(value).strip()
                      for key, value in values.items()})


def _text(value: object) -> Message | None:
    """The rule for a title-block value: a text or a whole number, not empty."""
    if isinstance(value, bool) or not isinstance(value, (str, int)) or str(value).strip() == "":
        return Message("rule.text_or_number")
    return None


def _date(value: object) -> Message | None:
    """The rule for the date: a calendar date, ``YYYY-MM-DD``."""
    if isinstance(value, datetime.date):
        return None
    try:
        datetime.date.fromisoformat(str(value))
    except ValueError:
        return Message("rule.iso_date")
    return None


def _read_forces(top: Node, links: list[LinkId], frame: LinkId, inputs: list[Drive],
                 joints: Joints, geometry: Sketch | None) -> ForceData | None:
    """The ``masses:``, ``loads:`` and ``gravity:`` sections (``docs/forces.md`` §1), their
    points within reach of the sketch.

    The force analysis is loaded only for a table that has one of them.
    """
    if not any(top.has(section) for section in _FORCES):
        return None
    from assur.forces.table import Reach, read_sections

    driven = [joints.get(drive.pair) for drive in inputs
              if drive.link is None and drive.pair is not None]
    actuated = any(pair is not None and pair[0] == "P" for pair in driven)
    reach = Reach.around(geometry.points.values()) if geometry is not None else None
    return read_sections(top, tuple(link for link in links if link != frame), actuated, reach)


def _read_links(mech: Node, names: dict[LinkId, str],
                local: dict[str, dict[LinkId, str]]) -> list[LinkId] | None:
    """The links table; None when there is none, or when it could not be read whole (the
    problem is recorded, and the pairs are not checked against what is left of it).  A name
    given in several languages (``name: {en: crank, ru: кривошип}``) goes into ``local``,
    its default-language form into ``names``."""
    if not mech.has("links"):
        return None
    count = len(mech.reader.issues)
    value = mech.get("links", kind="list")
    if value is MISSING:
        return None
    links: list[LinkId] = []
    seen: dict[LinkId, int] = {}
    for index, item in enumerate(value):
        where = f"mechanism.links[{index}]"
        if isinstance(item, dict):
            row = Node(mech.reader, where, item, _LINK)
            row.swapped({"id": _is_id, "name": lambda v: isinstance(v, (str, dict))})
            link = row.get("id", kind="id")
            if isinstance(row.mapping.get("name"), dict):
                name = _local_name(row, link, local)
            else:
                name = row.get("name", kind="str", required=False, default=None)
            if link is not MISSING and name:
                names[link] = name
        elif _is_id(item):
            link = normalise_id(item)
        else:
            mech.reader.problem(where, "chain.link_row", found=describe(item))
            continue
        if link is MISSING:
            continue
        if link in seen:
            mech.reader.problem(where, "chain.duplicate_link", link=repr(link), index=seen[link])
            continue
        seen[link] = index
        links.append(link)
    return links if len(mech.reader.issues) == count else None


class _RawPair:
    """A pair as written by the user (a compound hinge may list more than two links)."""

    __slots__ = ("guide", "id", "links", "type", "where")

    def __init__(self, pid: PairId, ptype: PairType, links: list[LinkId], guide: LinkId | None,
                 where: str) -> None:
        self.id, self.type, self.links, self.guide, self.where = pid, ptype, links, guide, where


def _read_pairs(mech: Node) -> tuple[list[_RawPair], list[LinkId]]:
    """The valid pairs, and every link id mentioned by any pair row (valid or not)."""
    pairs: list[_RawPair] = []
    mentioned: list[LinkId] = []
    seen: dict[PairId, str] = {}
    for row in mech.rows("pairs", _PAIR, label=_pair_label):
        row.swapped({"id": _is_id, "type": lambda v: v in ("R", "P"),
                     "links": lambda v: isinstance(v, list), "guide": _is_id})
        pid = row.get("id", kind="id")
        ptype = row.choice("type", ["R", "P"])
        links = row.get("links", kind="list")
        guide = row.get("guide", kind="id", required=False, default=None)
        ok = True
        if isinstance(links, list):
            bad = [item for item in links if not _is_id(item)]
            if bad:
                row.reader.problem(row._where("links"), "chain.pair_link_ids",
                                   found=describe(bad[0]))
                ok = False
            elif len(links) < 2:
                row.reader.problem(row._where("links"), "chain.pair_two_links",
                                   found=describe(links))
                ok = False
            else:
                links = [normalise_id(item) for item in links]
                mentioned.extend(links)
                if len(set(links)) != len(links):
                    row.reader.problem(row._where("links"), "chain.self_pair", found=str(links))
                    ok = False
                elif len(links) > 2 and ptype == "P":
                    row.reader.problem(row._where("links"), "chain.compound_prismatic",
                                       found=str(links))
                    ok = False
        if ptype == "P" and guide is None and not row.has("guide"):
            row.reader.problem(row._where("guide"), "chain.guide_missing")
            ok = False
        elif ptype == "R" and guide not in (None, MISSING):
            row.reader.problem(row._where("guide"), "chain.guide_on_revolute",
                               found=describe(guide))
            ok = False
        elif ptype == "P" and isinstance(links, list) and guide not in (MISSING, None) and ok \
                and guide not in links:
            row.reader.problem(row._where("guide"), "chain.guide_not_in_pair", links=str(links),
                               found=describe(guide))
            ok = False
        if pid is not MISSING:
            if pid in seen:
                row.reader.problem(row._where("id"), "chain.duplicate_pair", pair=repr(pid),
                                   other=seen[pid])
                ok = False
            else:
                seen[pid] = row.location
        if ok and MISSING not in (pid, ptype, links, guide):
            pairs.append(_RawPair(pid, PairType(ptype), links, guide, row.location))
    return pairs, mentioned


def _pair_label(row: dict[str, Any]) -> str | None:
    return f"id {row['id']!r}" if "id" in row else None


def _read_inputs(mech: Node) -> list[Drive]:
    value = mech.get("inputs", kind="list")
    if value is MISSING:
        return []
    drives: list[Drive] = []
    for index, item in enumerate(value):
        where = f"mechanism.inputs[{index}]"
        if _is_id(item):
            drives.append(Drive(link=normalise_id(item)))
            continue
        if not isinstance(item, dict):
            mech.reader.problem(where, "chain.input_row", found=describe(item))
            continue
        row = Node(mech.reader, where, item, _INPUT)
        link = row.get("link", kind="id", required=False, default=None)
        pair = row.get("pair", kind="id", required=False, default=None)
        if link is None and pair is None and not item.keys() - set(_INPUT):
            mech.reader.problem(where, "chain.input_empty")
        law = _read_law(row)
        if MISSING not in (link, pair) and (link is not None or pair is not None) \
                and law is not None:
            drives.append(Drive(link, pair, *law))
    return drives


def _read_law(row: Node) -> tuple[tuple[float, float] | None, float, int,
                                  tuple[tuple[float, float], ...]] | None:
    """An input row's stroke limits and law (``docs/tables.md``, "Inputs"); None after a
    problem was recorded."""
    ok = True
    stroke = row.get("stroke", kind="list", required=False, default=None)
    if stroke is not None and stroke is not MISSING:
        if len(stroke) != 2 or not all(is_number(v) for v in stroke):
            row.reader.problem(f"{row.location} 'stroke'", "chain.input_stroke",
                               found=describe(stroke))
            ok = False
        elif float(stroke[0]) > float(stroke[1]):
            row.reader.problem(f"{row.location} 'stroke'", "chain.input_stroke_order",
                               lower=describe(stroke[0]), upper=describe(stroke[1]))
            ok = False
        else:
            stroke = (float(stroke[0]), float(stroke[1]))
    phase = row.get("phase", kind="number", required=False, default=0.0)
    ratio = row.get("ratio", kind="int", required=False, default=1, check=_not_zero)
    table = row.get("table", kind="list", required=False, default=())
    rows = _law_table(row, table) if table not in ((), MISSING) else ()
    if table and stroke is None and rows is not None:
        row.reader.problem(f"{row.location} 'table'", "chain.input_table_stroke")
        ok = False
    if MISSING in (stroke, phase, ratio, table) or rows is None or not ok:
        return None
    return stroke, float(phase), int(ratio), rows


def _not_zero(value: Any) -> Message | None:
    return Message("rule.not_zero") if value == 0 else None


def _law_table(row: Node, table: list[Any]) -> tuple[tuple[float, float], ...] | None:
    """The rows [t, value] of a law table: t in degrees, increasing in [0, 360); None after a
    problem was recorded."""
    where = f"{row.location} 'table'"
    if len(table) < 2 or not all(isinstance(r, list) and len(r) == 2
                                 and all(is_number(v) for v in r) for r in table):
        row.reader.problem(where, "chain.input_table", found=describe(table))
        return None
    rows = tuple((float(t), float(v)) for t, v in table)
    ts = [t for t, _ in rows]
    if ts[0] < 0 or ts[-1] >= 360 or any(b <= a for a, b in itertools.pairwise(ts)):
        row.reader.problem(where, "chain.input_table_order", found=describe(ts))
        return None
    return rows


def _check_pairs(reader: TableReader, pairs: list[_RawPair], links: set[LinkId]) -> None:
    """Report each link of the pairs that is not in the links table once, at the first pair
    that joins it, naming the other pairs that join it."""
    users: dict[LinkId, list[_RawPair]] = {}
    for pair in pairs:
        for link in pair.links:
            if link not in links:
                users.setdefault(link, []).append(pair)
    for link, (first, *others) in users.items():
        if others:
            reader.problem(f"{first.where} 'links'", "chain.unknown_link_pairs",
                           link=repr(link), links=_list(links),
                           pairs=", ".join(repr(pair.id) for pair in others))
        else:
            reader.problem(f"{first.where} 'links'", "chain.unknown_link", link=repr(link),
                           links=_list(links))


def _check_inputs(reader: TableReader, inputs: list[Drive], links: set[LinkId],
                  pairs: list[_RawPair], frame: Any, *, links_known: bool,
                  pairs_known: bool) -> None:
    """Check the inputs against the links and pairs; a link or pair that is not known is
    reported only when its table was read whole (a row that failed may hold it)."""
    by_id = {pair.id: pair for pair in pairs}
    seen: set[Any] = set()
    for index, drive in enumerate(inputs):
        where = f"mechanism.inputs[{index}]"
        if drive.link is not None and drive.link == frame:
            reader.problem(f"{where} 'link'", "chain.frame_input", frame=repr(frame))
        elif drive.link is not None and drive.link not in links and links_known:
            reader.problem(f"{where} 'link'", "chain.unknown_link", link=repr(drive.link),
                           links=_list(links))
        if drive.pair is not None:
            pair = by_id.get(drive.pair)
            if pair is None:
                if pairs_known:
                    reader.problem(f"{where} 'pair'", "chain.unknown_pair",
                                   pair=repr(drive.pair), pairs=_list(by_id))
            elif len(pair.links) != 2:
                reader.problem(f"{where} 'pair'", "chain.driven_pair_links",
                               pair=repr(drive.pair), links=str(pair.links))
            elif drive.link is not None and drive.link not in pair.links:
                reader.problem(f"{where} 'link'", "chain.input_not_in_pair",
                               link=repr(drive.link), links=str(pair.links),
                               pair=repr(drive.pair))
        key = (drive.link, drive.pair)
        if key in seen:
            reader.problem(where, "chain.input_twice", found=describe(drive.link or drive.pair))
        seen.add(key)


def _normalise(raw: list[_RawPair], frame: LinkId, input_links: list[LinkId]) -> list[Pair]:
    pairs: list[Pair] = []
    for item in raw:
        if len(item.links) == 2:
            pairs.append(Pair(item.id, item.type, (item.links[0], item.links[1]), item.guide,
                              item.id))
        else:
            centre = next((c for c in [frame, *input_links] if c in item.links), item.links[0])
            pairs.extend(recentre_hinge(item.id, item.links, centre))
    return pairs


def recentre_hinge(origin: PairId, links: list[LinkId] | tuple[LinkId, ...],
                   centre: LinkId) -> list[Pair]:
    """Split a hinge shared by k links into k − 1 binary R pairs around ``centre``.

    The pairs are named ``"<origin>/<link>"`` and keep ``origin`` (``structure.md`` §2.2).
    """
    return [Pair(f"{origin}/{link}", PairType.R, (centre, link), None, origin)
            for link in links if link != centre]


def _geometry(reader: TableReader, top: Node, mech: Node | None, joints: Joints,
              links: list[LinkId], frame: LinkId, inputs: list[Drive], *,
              reported: Collection[PairId] | None = ()) -> Sketch | None:
    """The sketch, given inside ``mechanism:`` or at the top of the file (not both);
    ``reported`` as in :func:`~assur.io.sketch.read_sketch`."""
    inner = mech.get("geometry", kind="mapping", required=False, default=None) if mech else None
    outer = top.get("geometry", kind="mapping", required=False, default=None)
    if isinstance(inner, dict) and isinstance(outer, dict):
        reader.problem("geometry", "chain.geometry_twice")
        return None
    data = inner if isinstance(inner, dict) else outer
    if not isinstance(data, dict) or frame is MISSING:
        return None
    return read_sketch(reader, data, joints, links=links, frame=frame,
                       optional=actuator_pairs(inputs, joints, frame), reported=reported)


def _read_claims(top: Node) -> dict[str, int]:
    claims = {}
    for key in _CLAIMS:
        value = top.get(key, kind="int", required=False, default=None)
        if isinstance(value, int):
            claims[key] = value
    return claims


# ----------------------------------------------------------------------- identification form


def _row_label(row: dict[str, Any]) -> str | None:
    parts = []
    if "L" in row:
        parts.append(f"L{row['L']}")
    parts.extend(f"{key} = {row[key]}" for key in ("i", "j") if row.get(key) is not None)
    return ", ".join(parts) or None


def _read_rows(top: Node, *, required: bool
               ) -> tuple[list[IdentificationRow], set[LinkId] | None]:
    """Read and validate identification rows (every problem recorded in the reader).

    Returns the rows read whole, and the links ``i`` and ``j`` of every row, also of the rows
    that failed on another field (None if a row's ``i`` or ``j`` could not be read).
    """
    rows: list[IdentificationRow] = []
    clean_rows: list[tuple[dict[str, Any], str]] = []
    owner: dict[LinkId, str] = {}
    for row in top.rows("structure_identification", IDENTIFICATION_FIELDS, required=required,
                        label=_row_label):
        kind = row.get("L", kind="int", check=lambda v: None if v in KINDS else
                       Message("rule.group_kind"))
        clean: dict[str, Any] = {"L": kind}
        dyad = kind is not MISSING and kind != 0
        if kind == 0:  # the input group: a link i on i_minus_1, no j
            row.swapped({"i_minus_1": _is_id, "j": lambda v: v is None,
                         "j_minus_1": lambda v: v is None,
                         "i_plus_1": lambda v: v is None or _is_id(v)})
        for key in ("i", "i_minus_1"):
            clean[key] = row.get(key, kind="id")
        for key in ("j", "j_minus_1"):
            clean[key] = row.get(key, kind="id", nullable=True)
            if kind == 0 and clean[key] not in (None, MISSING):
                row.reader.problem(row._where(key), "chain.input_group_j",
                                   found=describe(clean[key]))
            elif dyad and clean[key] is None:
                row.reader.problem(row._where(key), "chain.dyad_needs_link", kind=kind)
        for key in ("i_plus_1", "j_plus_1"):
            clean[key] = row.get(key, kind="id", required=False, default=None, nullable=True)
        clean["seq"] = row.get("seq", kind="int", required=False, default=None, nullable=True)
        clean["variant"] = row.get("variant", kind="int", required=False, default=None,
                                   nullable=True, check=_variant_rule)
        code = row.get("out_code", required=False, default=None, nullable=True)
        clean["out_code"] = None if code is None else str(code)
        clean["params"] = row.get("params", kind="mapping", required=False, default=None)
        if clean["i"] is not MISSING and clean["i"] == clean["j"]:
            row.reader.problem(row._where("j"), "chain.same_i_j", link=repr(clean["i"]))
        for key in ("i", "j"):
            link = clean[key]
            if link in (None, MISSING):
                continue
            if link in owner:
                row.reader.problem(row._where(key), "chain.link_in_two_groups", link=repr(link),
                                   owner=owner[link])
            else:
                owner[link] = row.location
        clean_rows.append((clean, row.location))
    for clean, location in clean_rows:
        for key, partner in (("i_minus_1", "i"), ("j_minus_1", "j")):
            if clean[key] not in (None, MISSING) and clean[key] == clean[partner]:
                top.reader.problem(f"{location} {key!r}", "chain.joined_to_itself",
                                   link=repr(clean[key]), a=repr(partner), b=repr(key))
        if MISSING not in clean.values():
            if clean["params"] is not None:
                clean["params"] = _read_params(top.reader, clean)
            rows.append(IdentificationRow(**clean, location=location))
    value = top.mapping.get("structure_identification")
    whole = isinstance(value, list) and len(clean_rows) == len(value) and \
        all(clean[key] is not MISSING for clean, _ in clean_rows for key in ("i", "j"))
    members = {clean[key] for clean, _ in clean_rows for key in ("i", "j")} - {None}
    return rows, members if whole else None


def _read_params(reader: TableReader, row: dict[str, Any]) -> GroupParams:
    kind = kind_of(row["L"])
    links = f"{row['i']}" if kind.is_input else f"{row['i']},{row['j']}"
    return read_params(reader.source, f"{kind.code}({links})", row["params"],
                       reader.warnings)


def _read_table_form(reader: TableReader) -> Chain:
    top = reader.root(allowed=_TOP_TABLE)
    name = top.get("mechanism", kind="str", required=False, default=None)
    name = top.get("name", kind="str", required=False, default=name)
    frame = top.get("frame", kind="id", required=False, default=0)
    rows, read = _read_rows(top, required=True)
    general = read_general(top)
    student = read_student(top)
    claims = _read_claims(top)
    if not rows and not reader.issues:
        reader.problem("structure_identification", "chain.no_rows")
    if read is not None:  # (a row whose i or j could not be read may hold the link)
        _check_members(reader, rows, read | {frame}, frame)
    if not reader.issues:
        _check_seq_gap(reader, rows, claims)
    if reader.issues:
        return _empty(reader.source)
    members = {frame} | {link for row in rows for link in (row.i, row.j) if link is not None}
    links = [frame, *sorted((m for m in members if m != frame), key=id_key)]
    pairs: list[Pair] = []
    inputs: list[Drive] = []
    for row in rows:
        pairs.extend(_group_pairs(row, frame))
        if row.L == 0:
            inputs.append(Drive(link=row.i))
    pairs = _unique_ids(pairs)
    joints = {pair.id: (pair.type.value, pair.links) for pair in pairs}
    geometry = _geometry(reader, top, None, joints, links, frame, inputs)
    reader.raise_if_any()
    return Chain(name=name or _stem(reader.source), frame=frame, links=tuple(links),
                 pairs=tuple(pairs), inputs=tuple(inputs), geometry=geometry, general=general,
                 source=reader.source, group_params=_group_params(rows),
                 identification=tuple(rows), claims=claims, student=student)


def _check_members(reader: TableReader, rows: list[IdentificationRow], members: set[LinkId],
                   frame: LinkId) -> None:
    """Every link a row joins to (``i_minus_1`` … ``j_plus_1``) is the frame or a row's link;
    a link that is not is reported once, where it is first named, with the other places.
    Several such links (the two links of a dyad whose row was left out) are one finding,
    at the first place, naming every link and place."""
    places: dict[LinkId, list[str]] = {}
    for row in rows:
        for key in ("i_minus_1", "j_minus_1", "i_plus_1", "j_plus_1"):
            link = row.get(key)
            if link is not None and link not in members:
                places.setdefault(link, []).append(f"{row.location} {key!r}")
    if len(places) > 1:
        first = min((where[0] for where in places.values()), key=_row_order)
        reader.problem(first, "chain.links_not_in_rows", links=_list(places), frame=repr(frame),
                       places="; ".join(f"{link!r}: {', '.join(where)}"
                                        for link, where in places.items()))
        return
    for link, (first, *others) in places.items():
        if others:
            reader.problem(first, "chain.link_not_in_rows_also", link=repr(link),
                           frame=repr(frame), places="; ".join(others))
        else:
            reader.problem(first, "chain.link_not_in_rows", link=repr(link), frame=repr(frame))


def _row_order(location: str) -> int:
    """The index of the row of a location ``structure_identification[K] …``."""
    return int(location.split("[", 1)[1].split("]", 1)[0])


def _check_seq_gap(reader: TableReader, rows: list[IdentificationRow],
                   claims: dict[str, int]) -> None:
    """Rows left out of a table that numbers its rows (``seq``): the numbers have a gap, and
    the header's ``N_Q``, if given, counts the rows that are there and the ones left out.
    Told once; the header's counts are not judged against a table short of rows."""
    seqs = sorted(row.seq for row in rows if row.seq is not None)
    if len(seqs) != len(rows) or len(set(seqs)) != len(seqs) or not seqs or seqs[0] < 1:
        return
    gaps = sorted(set(range(1, seqs[-1] + 1)) - set(seqs))
    if not gaps or claims.get("N_Q", len(rows) + len(gaps)) != len(rows) + len(gaps):
        return
    reader.problem("structure_identification",
                   "chain.seq_row_missing" if len(gaps) == 1 else "chain.seq_rows_missing",
                   missing=", ".join(map(str, gaps)), seqs=", ".join(map(str, seqs)))


def _group_pairs(row: IdentificationRow, frame: LinkId) -> list[Pair]:
    """The pairs of a row's group; the kind gives their types and guide carriers
    (``method.md`` §2.0)."""
    i, j, i1, j1 = row.i, row.j, row.i_minus_1, row.j_minus_1
    assert i1 is not None
    row_pairs = kind_of(row.L).row_pairs
    if row_pairs is None:
        return [Pair(f"{i1}-{i}", PairType.R, (i1, i), None, f"{i1}-{i}")]
    assert j is not None and j1 is not None
    ext_i, internal, ext_j = row_pairs
    roles = {"i": i, "j": j}
    out = []
    for (ptype, carrier), (a, b), prev in ((ext_i, (i, i1), i1), (internal, (i, j), None),
                                           (ext_j, (j, j1), j1)):
        guide = None if carrier is None else (prev if carrier == "prev" else roles[carrier])
        label = pair_label(a, b, frame)
        out.append(Pair(label, PairType(ptype), (b, a) if b in (i1, j1) else (a, b),
                        guide, label))
    return out


def _unique_ids(pairs: list[Pair]) -> list[Pair]:
    count: dict[PairId, int] = {}
    out = []
    for pair in pairs:
        n = count.get(pair.id, 0)
        count[pair.id] = n + 1
        if n:
            label = f"{pair.id}#{n + 1}"
            pair = replace(pair, id=label, origin=label)
        out.append(pair)
    return out


def _group_params(rows: list[IdentificationRow]) -> dict[tuple[LinkId, ...], GroupParams]:
    return {row.key: row.params for row in rows if row.params is not None}


# ------------------------------------------------------------------------------ helpers


def _variant_rule(value: int) -> Message | None:
    """An assembly variant is +1 or −1 (0 where the group has one assembly, ``method.md``)."""
    return None if value in (-1, 0, 1) else Message("rule.variant")


def _is_id(value: Any) -> bool:
    return (isinstance(value, int) and not isinstance(value, bool)) or (
        isinstance(value, str) and value.strip() != "")


def _list(items: Any) -> str:
    return ", ".join(repr(item) for item in sorted(items, key=id_key))


def _stem(source: str) -> str:
    return os.path.splitext(os.path.basename(source))[0] or source


def _empty(source: str) -> Chain:
    return Chain(name="", frame=0, links=(), pairs=(), inputs=(), source=source)
