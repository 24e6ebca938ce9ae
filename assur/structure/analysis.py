"""Structural analysis of a planar chain: mobility, Assur groups, formula, diagnostics.

:func:`analyse_structure` is the entry point. It counts n, p5, p4 and W = 3n − 2p5 − p4,
peels the chain into its input groups and Assur groups (:mod:`assur.structure.peeling`),
classifies them (:mod:`assur.structure.classification`), writes the structure formula
(формула строения) in Artobolevsky's notation, finds the mechanism class and gives the
DGTU applicability verdict (``method.md`` §1.1) with every failed condition named.

Examples
--------
>>> from assur.io.chain_table import chain_from_dict
>>> chain = chain_from_dict({"mechanism": {"pairs": [
...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
...     {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
...     "inputs": [1]}})
>>> analysis = analyse_structure(chain)
>>> analysis.W, analysis.formula, analysis.applicable
(1, 'I(0,1) → II₁(2,3)', True)
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from assur.io.chain_table import recentre_hinge
from assur.model import Chain, Drive, LinkId, Pair, PairId, PairType, id_key
from assur.structure._fast import closed_by_dyads, no_prismatic_loop
from assur.structure._nx import networkx
from assur.structure.classification import AssurGroup, classify, input_group, roman
from assur.structure.diagnostics import Diagnostic, diagnostic
from assur.structure.fixes import with_fixes
from assur.structure.peeling import BodyGraph, Peeling, body_graph, peel
from assur.structure.rank_test import RankResult, pose_from_geometry, rank_test
from assur.structure.replacing import PassiveDof, Replacement, replacement
from assur.text import Message, joined, language_key, languages

__all__ = ["AssurGroup", "Diagnostic", "StructuralAnalysis", "analyse_structure"]

_RANK_LIMIT = 300  # links; the rank test is an SVD of a (2p × 3n) matrix


@dataclass(frozen=True)
class StructuralAnalysis:
    """Everything the structural analysis found.

    Attributes
    ----------
    chain : Chain
        The analysed chain (compound hinges re-centred if needed); for a chain with higher
        pairs, its replacing mechanism (:mod:`assur.structure.replacing`), which the groups,
        the formula and the findings describe.
    n, p5, p4, W : int
        Moving links, lower pairs, higher pairs, W = 3n − 2p5 − p4 (of the chain as given).
    W_star : int
        W less the passive degrees of freedom, corrected for loops of prismatic pairs only
        (``structure.md`` §3.3).
    m : int
        Number of inputs.
    input_groups, groups : tuple of AssurGroup
        Input groups (class I) and Assur groups in layering order (level, then smallest
        link id).
    formula : str
        Structure formula, e.g. ``I(0,1) → II₁(2,3) → II₄(4,5)``.
    formula_levels : tuple of tuple of str
        The same, grouped by level.
    mechanism_class : int
        Highest group class (1 when there are no Assur groups).
    applicable : bool
        Whether the DGTU program handles the mechanism (all conditions of §1.1 hold).
    applicability : tuple of Message
        Each failed DGTU condition as a sentence (:meth:`conditions` renders them).
    issues : tuple of Diagnostic
        All diagnostics.
    leftover : tuple
        Links that no group could take.
    rank : RankResult or None
        The rank test at the table's pose, when a complete pose was given.
    original : Chain or None
        The chain as given, when it has higher pairs (``chain`` is then its replacing
        mechanism); None otherwise.
    passive : tuple of PassiveDof
        The passive (local) degrees of freedom, each with its reason, subtracted from W.
    replacements : tuple of Replacement
        Each higher pair and the link that replaces it.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> analysis.n, analysis.p5, analysis.p4, analysis.W
    (3, 4, 0, 1)
    """

    chain: Chain
    n: int
    p5: int
    p4: int
    W: int
    W_star: int
    m: int
    input_groups: tuple[AssurGroup, ...]
    groups: tuple[AssurGroup, ...]
    formula: str
    formula_levels: tuple[tuple[str, ...], ...]
    mechanism_class: int
    applicable: bool
    applicability: tuple[Message, ...]
    issues: tuple[Diagnostic, ...]
    leftover: tuple[LinkId, ...]
    rank: RankResult | None = None
    original: Chain | None = None
    passive: tuple[PassiveDof, ...] = ()
    replacements: tuple[Replacement, ...] = ()

    def __repr__(self) -> str:
        return (f"StructuralAnalysis({self.chain.name!r}: n={self.n}, p5={self.p5}, "
                f"p4={self.p4}, W={self.W}\n  formula: {self.formula}\n"
                f"  class {self.mechanism_class}, applicable={self.applicable}, "
                f"{len(self.issues)} diagnostics)")

    @property
    def W_active(self) -> int:
        """W less the passive (local) degrees of freedom: the mobility the inputs must give."""
        return self.W - len(self.passive)

    @property
    def decomposed(self) -> bool:
        """Whether every link was placed in a group with no error."""
        return not self.leftover and not any(d.code.startswith("E") for d in self.issues)

    def conditions(self, lang: str = "en") -> tuple[str, ...]:
        """Each failed DGTU condition as a sentence in ``lang``."""
        return tuple(condition.text(lang) for condition in self.applicability)

    def group_of(self, link: LinkId) -> AssurGroup | None:
        """The (input or Assur) group that holds ``link``."""
        for group in (*self.input_groups, *self.groups):
            if link in group.links:
                return group
        return None

    def _inputs(self) -> list[dict[str, Any]]:
        """Each input with its driven pair (found for driven links)."""
        driven = {g.i: g.pair_i for g in self.input_groups}
        return [{"link": d.link, "pair": d.pair if d.pair is not None else driven.get(d.link)}
                for d in self.chain.inputs]

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``assur check --json``."""
        return {
            "name": self.chain.name, "source": self.chain.source,
            "n": self.n, "p5": self.p5, "p4": self.p4, "W": self.W, "W_star": self.W_star,
            "m": self.m,
            "inputs": self._inputs(),
            "input_groups": [g.to_dict() for g in self.input_groups],
            "groups": [g.to_dict() for g in self.groups],
            "formula": self.formula, "formula_levels": [list(x) for x in self.formula_levels],
            "mechanism_class": self.mechanism_class, "mechanism_class_roman":
                roman(self.mechanism_class),
            "applicable": self.applicable,
            **{language_key("applicability", lang): list(self.conditions(lang))
               for lang in languages()},
            "issues": [d.to_dict() for d in self.issues],
            "leftover": list(self.leftover),
            "rank_test": self.rank.to_dict() if self.rank else None,
            "passive": [{**dof.to_dict(), **{language_key("reason", lang): dof.reason.text(lang)
                                             for lang in languages()}}
                        for dof in self.passive],
            "replacing_mechanism": self._replacing(),
        }

    def _replacing(self) -> dict[str, Any] | None:
        """The replacing mechanism's counts and links (None without higher pairs)."""
        if self.original is None:
            return None
        n, p5 = len(self.chain.moving_links), len(self.chain.pairs)
        return {"n": n, "p5": p5, "p4": 0, "W": 3 * n - 2 * p5,
                "replacements": [item.to_dict() for item in self.replacements]}


def analyse_structure(chain: Chain, *, suggest: bool = True) -> StructuralAnalysis:
    """Analyse the structure of a chain.

    Parameters
    ----------
    chain : Chain
        From :func:`assur.io.chain_table.load_chain` or built in code.
    suggest : bool
        Whether to try extra inputs for an under-constrained leftover and suggest those that
        complete the decomposition.

    Returns
    -------
    StructuralAnalysis

    Examples
    --------
    Three moving links and four lower pairs: W = 3·3 − 2·4 = 1, the input group and one RRR dyad:

    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> analysis.W, analysis.formula
    (1, 'I(0,1) → II₁(2,3)')
    """
    if chain.higher:
        return _with_higher_pairs(chain, suggest=suggest)
    graph = body_graph(chain)
    peeling = peel(graph)
    recentred = _recentre_compound_hinges(chain, graph, peeling)
    if recentred is not None:
        chain = recentred
        graph = body_graph(chain)
        peeling = peel(graph)
    groups = sorted((classify(raw, graph) for raw in peeling.groups),
                    key=lambda g: (g.level, id_key(g.links[0])))
    inputs = tuple(input_group(body, graph.driven.get(body), chain.frame)
                   for body in graph.input_bodies if len(graph.members[body]) == 1)
    n = len(chain.moving_links)
    p5 = len(chain.pairs)
    p4 = 0
    w = 3 * n - 2 * p5 - p4
    loops = [] if no_prismatic_loop(graph, peeling) else _prismatic_loops(chain)
    w_star = w + sum(d.data["r"] for d in loops)
    m = len(chain.inputs)

    pose = pose_from_geometry(chain) if n <= _RANK_LIMIT else None
    rank = _rank(chain, graph, groups, pose) if pose is not None else None
    issues: list[Diagnostic] = []
    if w_star != m:
        issues.append(_mismatch(n, p5, p4, w, w_star, m, rank))
    if peeling.disconnected:
        issues.append(diagnostic("E_DISCONNECTED", peeling.disconnected))
    issues += graph.issues
    issues += _duplicates(chain)
    issues += loops
    issues += _with_suggestions(chain, peeling.issues) if suggest else peeling.issues
    for group in groups:
        issues += [d for d in group.issues if not _in_loop(d, loops)]
    if not closed_by_dyads(graph, peeling):
        issues += _idle(chain)
    if rank is not None:
        issues += _rank_issues(chain, rank, peeling)
    issues += [diagnostic("I_HIGH_DEGREE", [link], [p.id for p in chain.pairs_of(link)],
                          k=len(chain.pairs_of(link)))
               for link in chain.moving_links if len(chain.pairs_of(link)) > 3]

    issues = with_fixes(chain, issues)
    formula, formula_levels = _formula(inputs, groups)
    analysis = StructuralAnalysis(
        chain=chain, n=n, p5=p5, p4=p4, W=w, W_star=w_star, m=m, input_groups=inputs,
        groups=tuple(groups), formula=formula, formula_levels=formula_levels,
        mechanism_class=max((g.group_class for g in groups), default=1), applicable=False,
        applicability=(), issues=tuple(issues),
        leftover=tuple(sorted(peeling.leftover + peeling.disconnected, key=id_key)), rank=rank)
    failed = _applicability(analysis, graph)
    return replace(analysis, applicable=not failed, applicability=tuple(failed))


def _with_higher_pairs(chain: Chain, *, suggest: bool) -> StructuralAnalysis:
    """A chain with higher pairs: counted as given, W less its passive degrees of freedom,
    decomposed as its replacing mechanism; the DGTU program takes lower pairs only."""
    replaced = replacement(chain)
    inner = analyse_structure(replaced.chain, suggest=suggest)
    n, p5, p4 = len(chain.moving_links), len(chain.pairs), len(chain.higher)
    lower_only = Message("structure.condition.lower_pairs",
                         {"pairs": ", ".join(str(pair.id) for pair in chain.higher)})
    return replace(inner, n=n, p5=p5, p4=p4, W=3 * n - 2 * p5 - p4, original=chain,
                   passive=replaced.passive, replacements=replaced.replacements,
                   applicable=False, applicability=(lower_only, *inner.applicability))


def _formula(inputs: tuple[AssurGroup, ...], groups: list[AssurGroup]
             ) -> tuple[str, tuple[tuple[str, ...], ...]]:
    """Structure formula (input groups, then the groups in layering order) and its levels."""
    labels = [group.label for group in groups]
    heads = tuple(group.label for group in inputs)
    levels: dict[int, list[str]] = {}
    for group, label in zip(groups, labels, strict=True):
        levels.setdefault(group.level, []).append(label)
    formula = " → ".join(([", ".join(heads)] if heads else []) + labels)
    by_level = tuple(([heads] if heads else []) + [tuple(levels[k]) for k in sorted(levels)])
    return formula, by_level


def _mismatch(n: int, p5: int, p4: int, w: int, w_star: int, m: int,
              rank: RankResult | None) -> Diagnostic:
    notes = {}
    if w_star != w:
        notes["star"] = Message("diag.note.w_star", {"w_star": w_star})
    if rank is not None and rank.W_geom != w:
        notes["geom"] = Message("diag.note.w_geom", {"w_geom": rank.W_geom})
    return diagnostic("E_MOBILITY_MISMATCH", pairs=(), notes=notes, n=n, p5=p5, p4=p4, W=w, m=m)


# ------------------------------------------------------------------------- compound hinges


def _recentre_compound_hinges(chain: Chain, graph: BodyGraph, peeling: Peeling) -> Chain | None:
    """Put the centre of each compound hinge on its link known first (§2.2)."""
    star: dict[PairId, list[Pair]] = {}
    for pair in chain.pairs:
        if pair.origin is not None and pair.origin != pair.id:
            star.setdefault(pair.origin, []).append(pair)
    if not star:
        return None
    inputs = {d.link for d in chain.inputs}
    huge = len(chain.links) + 1

    def rank(link: LinkId) -> tuple[int, int, tuple[int, int | str]]:
        level = peeling.level.get(graph.body_of[link], huge)
        return (level, 0 if link == chain.frame else 1 if link in inputs else 2, id_key(link))

    pairs = list(chain.pairs)
    changed = False
    for origin, members in star.items():
        centre = members[0].links[0]
        links = [centre] + [p.links[1] for p in members]
        best = min(links, key=rank)
        if best != centre:
            changed = True
            first = pairs.index(members[0])
            pairs = [p for p in pairs if p.origin != origin]
            pairs[first:first] = recentre_hinge(origin, links, best)
    return replace(chain, pairs=tuple(pairs)) if changed else None


# ------------------------------------------------------------------------------ diagnostics


def _duplicates(chain: Chain) -> list[Diagnostic]:
    seen: dict[frozenset[LinkId], list[PairId]] = {}
    for pair in chain.pairs:
        seen.setdefault(frozenset(pair.links), []).append(pair.id)
    out = []
    for links, pids in seen.items():
        if len(pids) > 1:
            a, b = sorted(links, key=id_key)
            out.append(diagnostic("E_DUPLICATE_PAIR", links, pids, a=a, b=b))
    return out


def _prismatic_loops(chain: Chain) -> list[Diagnostic]:
    """One E_PRISMATIC_LOOP per component of the P-pair subgraph that holds a loop.

    r_P = |E_P| − |V_P| + c(P-subgraph) (``structure.md`` §3.3), counted per component.
    """
    prismatic = [pair for pair in chain.pairs if pair.type is PairType.P]
    nx = networkx()
    graph = nx.Graph()
    graph.add_edges_from(pair.links for pair in prismatic)
    component = {link: k for k, links in enumerate(nx.connected_components(graph))
                 for link in links}
    parts: dict[int, tuple[set[LinkId], list[PairId]]] = {}
    for pair in prismatic:
        nodes, pids = parts.setdefault(component[pair.links[0]], (set(), []))
        nodes.update(pair.links)
        pids.append(pair.id)
    out = []
    for nodes, pids in parts.values():
        r = len(pids) - len(nodes) + 1
        if r > 0:
            out.append(diagnostic("E_PRISMATIC_LOOP", nodes, pids, r=r))
    return out


def _in_loop(finding: Diagnostic, loops: list[Diagnostic]) -> bool:
    return finding.code == "E_PRISMATIC_LOOP" and any(
        set(finding.links) <= set(loop.links) for loop in loops)


def _idle(chain: Chain) -> list[Diagnostic]:
    """Open appendages: the far side of a bridge (seen from the frame) holding no input."""
    inputs = {link for d in chain.inputs for link in
              ([d.link] if d.link is not None else
               list(chain.pair(d.pair).links) if d.pair is not None else [])}
    out = []
    for side in _appendages(chain, inputs):
        pairs = {p.id for link in side for p in chain.pairs_of(link)}
        out.append(diagnostic("W_IDLE_LINK", side, pairs))
    return out


def _appendages(chain: Chain, inputs: set[LinkId]) -> list[list[LinkId]]:
    """Maximal sides beyond a bridge (seen from the frame) that hold no input.

    The bridges are the single-edge biconnected components of the chain's graph whose two
    links share one pair only (two pairs between the same links are no bridge). A bridge is
    an edge of the depth-first tree from the frame; its far side is the subtree of its deeper
    end, a contiguous run of the preorder. Sides come in depth-first order, each in
    depth-first order.
    """
    nx = networkx()
    graph = nx.Graph()
    graph.add_node(chain.frame)
    graph.add_edges_from(pair.links for pair in chain.pairs)
    bridges = [edges[0] for edges in nx.biconnected_component_edges(graph)
               if len(edges) == 1 and _single_pair(chain, *edges[0])]
    if not bridges:
        return []
    visit = [chain.frame]
    parent: dict[LinkId, LinkId] = {}
    for a, b in nx.dfs_edges(graph, chain.frame):
        parent[b] = a
        visit.append(b)
    order = {node: k for k, node in enumerate(visit)}
    size = dict.fromkeys(visit, 1)
    has_input = {node: node in inputs for node in visit}
    for node in reversed(visit[1:]):
        size[parent[node]] += size[node]
        has_input[parent[node]] = has_input[parent[node]] or has_input[node]
    children = [b if parent.get(b) == a else a for a, b in bridges if a in order]
    sides = []
    covered_until = -1
    for child in sorted(children, key=order.__getitem__):
        start = order[child]
        if start < covered_until or has_input[child]:
            continue
        covered_until = start + size[child]
        sides.append(visit[start:covered_until])
    return sides


def _single_pair(chain: Chain, a: LinkId, b: LinkId) -> bool:
    """Whether links ``a`` and ``b`` share one pair only."""
    return sum(1 for pair in chain.pairs_of(a) if b in pair.links) == 1


def _with_suggestions(chain: Chain, found: list[Diagnostic]) -> list[Diagnostic]:
    out = []
    for item in found:
        if item.code != "E_UNDERCONSTRAINED":
            out.append(item)
            continue
        good = []
        for link in item.links:
            on_frame = [p for p in chain.pairs_of(link) if chain.frame in p.links]
            if len(on_frame) != 1:
                continue
            trial = replace(chain, inputs=chain.inputs + (Drive(link=link),))
            result = peel(body_graph(trial))
            if not result.leftover and not result.issues and not result.disconnected:
                good.append((link, on_frame[0].id))
        if good:
            places = joined([Message("diag.note.input_at", {"link": x, "pair": p})
                             for x, p in good])
            item = replace(item, notes={"hint": Message("diag.note.inputs_complete",
                                                        {"places": places})})
        out.append(item)
    return out


def _rank(chain: Chain, graph: BodyGraph, groups: list[AssurGroup],
          pose: dict[PairId, tuple[complex, complex | None]]) -> RankResult:
    fixed = {link for body in graph.input_bodies for link in graph.members[body]}
    fixed |= {link for members in graph.members.values() if len(members) > 1 for link in members}
    blocks = []
    for group in groups:
        locked = tuple(chain.pair(p) for p in graph.frozen
                       if set(chain.pair(p).links) <= set(group.links))
        own = tuple(chain.pair(p) for p in (*(e[0] for e in group.external), *group.internal,
                                            *graph.inner)
                    if set(chain.pair(p).links) & set(group.links))
        blocks.append((group.links, own + locked, locked))
    return rank_test(chain, pose, fixed=fixed, groups=blocks)


def _rank_issues(chain: Chain, rank: RankResult, peeling: Peeling) -> list[Diagnostic]:
    unplaced = {link for d in peeling.issues if d.code == "E_OVERCONSTRAINED"
                for link in d.links}
    out = []
    for link in rank.passive:
        notes = {"hint": Message("diag.note.unplaced")} if link in unplaced else {}
        out.append(diagnostic("W_PASSIVE_LINK", [link], [p.id for p in chain.pairs_of(link)],
                              notes))
    for links in rank.singular:
        out.append(diagnostic("W_SINGULAR_POSE", links, ()))
    return out


# ---------------------------------------------------------------------------- applicability

_BLOCKING = {"E_OVERCONSTRAINED", "E_UNDERCONSTRAINED", "W_PASSIVE_LINK", "E_PRISMATIC_LOOP",
             "E_RIGID_TRUSS", "E_DUPLICATE_PAIR", "W_GROUP_ON_ONE_LINK"}


def _applicability(a: StructuralAnalysis, graph: BodyGraph) -> list[Message]:
    """Failed DGTU conditions of ``method.md`` §1.1, each as a sentence.

    An open chain (idle or disconnected links) fails condition 4 only: the count of W, the
    free or redundant constraints and the layering into dyads (conditions 5, 6 and 8) then
    count the idle links too, and fail only because of them; an input link with no pair
    with the frame is then a part of the gap (a link number mistyped in its pair), not a
    failure of condition 3.  A chain short of inputs (none, or fewer than W where more
    inputs would complete the decomposition, as the finding suggests) fails condition 5
    only: the free links and the links in no group (conditions 6 and 8) are the inputs
    that are missing.
    """
    failed: list[Message] = []
    codes = {d.code for d in a.issues}
    chain = a.chain

    def driven_link(drive: Drive) -> LinkId | None:
        if drive.pair is not None:
            pair = chain.pair(drive.pair)
            return pair.other(chain.frame) if chain.frame in pair.links else None
        return drive.link

    def driven_by_hinge(drive: Drive) -> bool:
        link = driven_link(drive)
        return link in graph.driven and chain.pair(graph.driven[link]).type is PairType.R

    def off_frame(drive: Drive) -> bool:  # an input link with no pair with the frame
        return drive.link is not None and drive.pair is None and all(
            chain.frame not in p.links for p in chain.pairs_of(drive.link))

    closed = "W_IDLE_LINK" not in codes and "E_DISCONNECTED" not in codes
    bad_inputs = [d for d in chain.inputs if not driven_by_hinge(d)
                  and (closed or not off_frame(d))]
    if bad_inputs:
        names = ", ".join(str(d.link if d.link is not None else d.pair) for d in bad_inputs)
        failed.append(Message("structure.condition.crank", {"names": names}))
    if not closed:
        failed.append(Message("structure.condition.closed"))
    if closed and (a.W != 1 or a.W_star != 1 or a.m != 1):
        failed.append(Message("structure.condition.mobility",
                              {"W": a.W, "W_star": a.W_star, "m": a.m}))
    blocking = sorted(codes & _BLOCKING)
    under = [d for d in a.issues if d.code == "E_UNDERCONSTRAINED"]
    short = a.m == 0 or (a.W_star > a.m and bool(under) and all("hint" in d.notes for d in under)
                         and not codes & (_BLOCKING - {"E_UNDERCONSTRAINED"}))
    layered = closed and not short
    if layered and blocking:
        failed.append(Message("structure.condition.redundant", {"codes": ", ".join(blocking)}))
    heavy = [link for link in chain.moving_links if len(chain.pairs_of(link)) > 3]
    if heavy:
        failed.append(Message("structure.condition.degree",
                              {"names": ", ".join(map(str, heavy))}))
    others = [g.label for g in a.groups if not g.is_dyad]
    if layered and (a.leftover or others or any(
            d.code in {"E_UNSUPPORTED_GROUP", "E_INTERNAL"} for d in a.issues)):
        failed.append(Message("structure.condition.dyads", {"what": _incomplete(a, others)}))
    return failed


def _incomplete(a: StructuralAnalysis, others: list[str]) -> Message:
    """What keeps a mechanism from being layered of dyads."""
    what = []
    if others:
        what.append(Message("structure.not_dyads", {"groups": ", ".join(others)}))
    if a.leftover:
        what.append(Message("structure.in_no_group",
                            {"links": ", ".join(map(str, a.leftover))}))
    return joined(what, "term.clauses") if what else Message("structure.incomplete")
