"""Classification of accepted groups: class, order, kind, name and DGTU roles.

Rules of ``structure.md`` §4.5 (dyad kinds L1–L5, triads of class III, class IV groups with
a four-sided contour, higher groups reported as unsupported) and of §5.4 / ``method.md``
§2.0 for the roles i and j of a dyad.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from itertools import combinations
from typing import TYPE_CHECKING, Any

from assur.kinds import GroupKind, kind_of, kind_of_pattern
from assur.model import LinkId, PairId, id_key
from assur.structure._nx import networkx
from assur.structure.diagnostics import Diagnostic, diagnostic
from assur.structure.peeling import BodyGraph, RawGroup
from assur.text import Message, joined

if TYPE_CHECKING:  # pragma: no cover
    from networkx import MultiGraph

__all__ = ["AssurGroup", "classify", "input_group", "roman", "signature", "subscript"]

_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
#: The dyad kind of every (internal, external, external) pair-type triple, looked up in the
#: registry once.
_DYAD_KINDS: dict[tuple[str, str, str], GroupKind | None] = {
    (c, a, b): kind_of_pattern(c, (a, b)) for c in "RP" for a in "RP" for b in "RP"}


def roman(number: int) -> str:
    """Roman numeral of a group class (1 → I, 4 → IV)."""
    out = ""
    for value, mark in ((10, "X"), (9, "IX"), (5, "V"), (4, "IV"), (1, "I")):
        while number >= value:
            out, number = out + mark, number - value
    return out


def subscript(number: int) -> str:
    """Subscript digits, e.g. ``subscript(4) == '₄'``."""
    return str(number).translate(_SUB)


@dataclass(frozen=True)
class AssurGroup:
    """An input group (class I) or an Assur group.

    Parameters
    ----------
    links : tuple
        The group's links (all members of a frozen actuator included), sorted.
    group_class : int
        1 for input groups, 2 for dyads, 3 for triads, 4, … (Artobolevsky's numbering).
    order : int
        Number of external pairs.
    kind : int or None
        1–5 for dyads (L1 RRR, L2 RRP, L3 RPR, L4 PRP, L5 RPP), None otherwise.
    name : str
        ``"RRR"`` … for dyads, a signature such as ``"III(base 3; leashes R–R, R–R, R–P)"``
        for triads and class IV groups, ``"L0"`` for input groups.
    level : int
        Layering level: 0 for input groups.
    external : tuple of (pair, group link, known link)
        The external pairs and the known links they attach to.
    internal : tuple
        The internal pairs.
    i, j : link id or None
        DGTU roles of a dyad (``method.md`` §2.0); for an input group i is the input link.
        For a frozen composite the role names the member that carries the external pair.
    pair_i, pair_j, pair_c : pair id or None
        External pair of i, external pair of j, internal pair (dyads); for an input group
        ``pair_i`` is the driven pair.
    i_minus_1, j_minus_1 : link id or None
        The known links that i and j attach to.
    composite : tuple or None
        Members of a frozen actuator composite link in the group.
    issues : tuple of Diagnostic
        Findings about this group (truss, prismatic loop, unsupported …).

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> group = analysis.groups[0]
    >>> group.name, group.group_class, group.order, group.links
    ('RRR', 2, 2, (2, 3))
    """

    links: tuple[LinkId, ...]
    group_class: int
    order: int
    kind: int | None
    name: str
    level: int
    external: tuple[tuple[PairId, LinkId, LinkId], ...]
    internal: tuple[PairId, ...]
    i: LinkId | None = None
    j: LinkId | None = None
    pair_i: PairId | None = None
    pair_j: PairId | None = None
    pair_c: PairId | None = None
    i_minus_1: LinkId | None = None
    j_minus_1: LinkId | None = None
    composite: tuple[LinkId, ...] | None = None
    issues: tuple[Diagnostic, ...] = ()
    parts: tuple[tuple[LinkId, ...], ...] = ()

    @property
    def group_kind(self) -> GroupKind | None:
        """What the group's kind means: L0 for an input group, L1–L5 for a dyad, else None."""
        if self.group_class == 1:
            return kind_of(0)
        return kind_of(self.kind) if self.kind is not None else None

    @property
    def is_dyad(self) -> bool:
        """Whether this is a dyad of one of the five kinds."""
        return self.kind is not None

    @property
    def label(self) -> str:
        """Artobolevsky notation, e.g. ``II₁(2,3)``, ``I(0,1)``, ``II₁(1,{2,3})``."""
        if self.group_class == 1:
            return f"I({self.i_minus_1},{self.i})"
        parts = ",".join(str(p[0]) if len(p) == 1 else "{" + ",".join(map(str, p)) + "}"
                         for p in self.parts)
        kind = subscript(self.kind) if self.kind else ""
        return f"{roman(self.group_class)}{kind}({parts})"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (the keys of the ``--json`` output)."""
        return {"links": list(self.links), "class": self.group_class, "order": self.order,
                "kind": self.kind, "name": self.name, "label": self.label, "level": self.level,
                "i": self.i, "j": self.j, "i_minus_1": self.i_minus_1,
                "j_minus_1": self.j_minus_1, "pair_i": self.pair_i, "pair_j": self.pair_j,
                "pair_c": self.pair_c,
                "external": [{"pair": p, "link": g, "known": k} for p, g, k in self.external],
                "internal": list(self.internal),
                "composite": list(self.composite) if self.composite else None}


def input_group(link: LinkId, pair: PairId | None, frame: LinkId) -> AssurGroup:
    """The input group L0: the frame and one driven link."""
    external = ((pair, link, frame),) if pair is not None else ()
    return AssurGroup(links=(link,), group_class=1, order=1, kind=None, name="L0", level=0,
                      external=external, internal=(), i=link, pair_i=pair, i_minus_1=frame,
                      parts=((link,),))


def classify(raw: RawGroup, graph: BodyGraph) -> AssurGroup:
    """Class, order, kind, name and roles of an accepted group."""
    chain = graph.chain
    bodies = raw.bodies
    ext_real = tuple(_real_external(graph, pid, body) for pid, body, _ in raw.external)
    composite = next((graph.members[b] for b in bodies if len(graph.members[b]) > 1), None)
    common: dict[str, Any] = {
        "links": tuple(graph.links(bodies)), "order": len(raw.external), "level": raw.level,
        "external": ext_real, "internal": tuple(raw.internal), "composite": composite,
        "parts": tuple(graph.members[b] for b in bodies)}
    issues: list[Diagnostic] = []
    truss = _truss(raw, graph)
    if truss is not None:
        issues.append(truss)
    knowns = {k for _, _, k in ext_real}
    if len(knowns) == 1 and composite is None and len(ext_real) >= 2:
        issues.append(diagnostic("W_GROUP_ON_ONE_LINK", common["links"],
                                 [p for p, _, _ in ext_real], base=next(iter(knowns))))
    if len(bodies) == 2 and len(raw.external) == 2 and len(raw.internal) == 1:
        return _dyad(raw, graph, common, issues)
    nx = networkx()
    internal = nx.MultiGraph()
    internal.add_nodes_from(bodies)
    for pid in raw.internal:
        a, b = (graph.body_of[x] for x in chain.pair(pid).links)
        internal.add_edge(a, b, key=pid)
    ext_count = {b: sum(1 for _, body, _ in raw.external if body == b) for b in bodies}
    if len(bodies) == 4 and truss is None:
        named = _four(raw, graph, internal, ext_count)
        if named is not None:
            group_class, name = named
            return AssurGroup(group_class=group_class, kind=None, name=name,
                              issues=tuple(issues), **common)
    simple = nx.Graph(internal)
    longest = max((len(c) for c in nx.simple_cycles(simple)), default=0) if len(bodies) <= 12 \
        else 0
    group_class = max(max((d for _, d in internal.degree()), default=0), longest, 2)
    if truss is None:
        if len(bodies) >= 6:
            issues.append(diagnostic("E_UNSUPPORTED_GROUP", common["links"],
                                     [*(p for p, _, _ in ext_real), *raw.internal],
                                     cls=roman(group_class), order=len(raw.external),
                                     k=len(common["links"])))
        else:
            pattern = ", ".join(f"{a}-{b}" for a, b in sorted(
                (tuple(sorted(e, key=id_key)) for e in simple.edges), key=str))
            issues.append(diagnostic("E_INTERNAL", common["links"], raw.internal,
                                     pattern=pattern))
    return AssurGroup(group_class=group_class, kind=None,
                      name=f"{roman(group_class)}({len(bodies)} links)", issues=tuple(issues),
                      **common)


def _real_external(graph: BodyGraph, pid: PairId, body: LinkId) -> tuple[PairId, LinkId, LinkId]:
    a, b = graph.chain.pair(pid).links
    return (pid, a, b) if graph.body_of[a] == body else (pid, b, a)


def _type(graph: BodyGraph, pid: PairId) -> str:
    return graph.chain.pair(pid).type.value


def _dyad(raw: RawGroup, graph: BodyGraph, common: dict[str, Any],
          issues: list[Diagnostic]) -> AssurGroup:
    chain = graph.chain
    (pa, ba, ka), (pb, bb, kb) = raw.external
    pc = raw.internal[0]
    tc = _type(graph, pc)
    ta, tb = _type(graph, pa), _type(graph, pb)
    kind = _DYAD_KINDS[tc, ta, tb]
    frame = graph.body_of[chain.frame]
    first, second = sorted((ba, bb), key=id_key)
    ext = {ba: (pa, ka, ta), bb: (pb, kb, tb)}
    if kind is None:
        issues.append(diagnostic("E_PRISMATIC_LOOP", common["links"], [pa, pb, pc], r=1))
        return AssurGroup(group_class=2, kind=None, name="PPP", issues=tuple(issues), **common)
    on_frame = [b for b in (ba, bb) if ext[b][1] == frame]
    if kind.j_rule in ("frame_last", "frame_first"):
        # the link hinged to (L1) or guided by (L4) the frame is j; otherwise i < j for L1
        # and j < i for L4 (structure.md §5.4)
        default = second if kind.j_rule == "frame_last" else first
        j = on_frame[0] if len(on_frame) == 1 else default
    elif kind.j_rule == "revolute":
        j = ba if ta == "R" else bb
    else:  # "not_carrier"
        guide = chain.pair(pc).guide
        assert guide is not None  # a P pair names its guide carrier
        j = bb if graph.body_of[guide] == ba else ba
    i = bb if j == ba else ba
    real = dict(zip((ba, bb), common["external"], strict=True))
    ext_i, ext_j = real[i], real[j]
    return AssurGroup(group_class=2, kind=kind.number, name=kind.pairs, i=ext_i[1], j=ext_j[1],
                      pair_i=ext_i[0], pair_j=ext_j[0], pair_c=pc, i_minus_1=ext_i[2],
                      j_minus_1=ext_j[2], issues=tuple(issues), **common)


#: The signatures of a triad and of a class IV group (:attr:`AssurGroup.name`); they read
#: back into words of the catalogue by :func:`signature`.
_TRIAD = "III(base {base}; leashes {leashes})"
_CLASS_IV = "IV(contour {contour}; external {external})"


def _pattern(form: str) -> re.Pattern[str]:
    fields = re.escape(form).replace(r"\{", "{").replace(r"\}", "}")
    return re.compile(re.sub(r"{(\w+)}", r"(?P<\1>.+?)", fields) + "$")


def _letters(pairs: str, code: str) -> Message:
    """Pair letters (``"R–P"``, ``"R, R"``) as the course writes them in each language."""
    parts = [Message(f"term.pair_letter.{letter.lower()}")
             for letter in re.split(r"–|, ", pairs)]
    return joined(parts, code)


def signature(name: str) -> Message | str:
    """A group's :attr:`~AssurGroup.name` in the words and pair letters of each language.

    >>> signature("III(base 4; leashes R–R, R–P, R–R)").text("ru")
    'III(базовое звено 4; поводки В–В, В–П, В–В)'
    >>> signature("IV(contour R–R–P–R; external R, R)").text("ru")
    'IV(контур В–В–П–В; внешние: В, В)'
    >>> signature("RRP").text("ru"), signature("L0")
    ('ВВП', 'L0')
    """
    triad = _pattern(_TRIAD).match(name)
    if triad:
        leashes = [_letters(leash, "term.dash_joined")
                   for leash in triad["leashes"].split(", ")]
        return Message("group.signature.iii", {"base": triad["base"],
                                               "leashes": joined(leashes)})
    four = _pattern(_CLASS_IV).match(name)
    if four:
        return Message("group.signature.iv", {
            "contour": _letters(four["contour"], "term.dash_joined"),
            "external": _letters(four["external"], "term.list")})
    if re.fullmatch("[RP]+", name):
        return _letters(name.replace("", "–").strip("–"), "term.concat")
    return name


def _four(raw: RawGroup, graph: BodyGraph, internal: MultiGraph,
          ext_count: dict[LinkId, int]) -> tuple[int, str] | None:
    degree = dict(internal.degree())
    ext_type = {body: _type(graph, pid) for pid, body, _ in raw.external}
    bases = [b for b, d in degree.items() if d == 3]
    if len(raw.external) == 3 and len(bases) == 1 and internal.number_of_edges() == 3:
        base = bases[0]
        leashes = []
        for _, leash, pid in sorted(internal.edges(base, keys=True), key=lambda e: id_key(e[1])):
            if degree[leash] != 1 or ext_count[leash] != 1:
                return None
            leashes.append(f"{_type(graph, pid)}–{ext_type[leash]}")
        return 3, _TRIAD.format(base=base, leashes=", ".join(leashes))
    nx = networkx()
    simple = nx.Graph(internal)
    if (len(raw.external) == 2 and internal.number_of_edges() == 4
            and simple.number_of_edges() == 4 and all(d == 2 for d in degree.values())
            and nx.is_connected(simple)):
        ternary = [b for b in internal.nodes if ext_count[b] == 1]
        if len(ternary) == 2 and not simple.has_edge(*ternary):
            start = min(ternary, key=id_key)
            cycle = [start]
            while len(cycle) < 4:
                options = sorted((n for n in simple.neighbors(cycle[-1]) if n not in cycle),
                                 key=id_key)
                cycle.append(options[0])
            contour = [_type(graph, next(iter(internal[a][b])))
                       for a, b in zip(cycle, cycle[1:] + cycle[:1], strict=True)]
            external = ", ".join(ext_type[b] for b in sorted(ternary, key=id_key))
            return 4, _CLASS_IV.format(contour="–".join(contour), external=external)
    return None


def _truss(raw: RawGroup, graph: BodyGraph) -> Diagnostic | None:
    """The first set T of ≥ 3 bodies of the group with 3(|T| − 1) − 2·p_int(T) ≤ 0."""
    bodies = raw.bodies
    if len(bodies) < 3 or len(bodies) > 10:
        return None
    inner = [tuple(graph.body_of[x] for x in graph.chain.pair(pid).links) for pid in raw.internal]
    for size in range(3, len(bodies) + 1):
        for subset in combinations(bodies, size):
            chosen = set(subset)
            pairs = [pid for pid, (a, b) in zip(raw.internal, inner, strict=True)
                     if a in chosen and b in chosen]
            f = 3 * (size - 1) - 2 * len(pairs)
            if f <= 0:
                return diagnostic("E_RIGID_TRUSS", graph.links(chosen), pairs, k=size,
                                  p=len(pairs), f=f)
    return None

