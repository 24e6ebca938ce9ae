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

import networkx as nx  # type: ignore[import-untyped]

from assur.io.chain_table import recentre_hinge
from assur.structure.classification import AssurGroup, classify, input_group, roman
from assur.structure.peeling import BodyGraph, Peeling, body_graph, peel
from assur.structure.diagnostics import Diagnostic, diagnostic
from assur.model import Chain, Drive, LinkId, PairId, PairType, id_key
from assur.structure.rank_test import RankResult, pose_from_geometry, rank_test

__all__ = ["AssurGroup", "Diagnostic", "StructuralAnalysis", "analyse_structure"]

_RANK_LIMIT = 300  # links; the rank test is an SVD of a (2p × 3n) matrix


@dataclass(frozen=True)
class StructuralAnalysis:
    """Everything the structural analysis found.

    Attributes
    ----------
    chain : Chain
        The analysed chain (compound hinges re-centred if needed).
    n, p5, p4, W : int
        Moving links, lower pairs, higher pairs, W = 3n − 2p5 − p4.
    W_star : int
        W corrected for loops of prismatic pairs only (``structure.md`` §3.3).
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
    applicability, applicability_ru : tuple of str
        Each failed DGTU condition as a sentence.
    issues : tuple of Diagnostic
        All diagnostics.
    leftover : tuple
        Links that no group could take.
    rank : RankResult or None
        The rank test at the table's pose, when a complete pose was given.

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
    applicability: tuple[str, ...]
    applicability_ru: tuple[str, ...]
    issues: tuple[Diagnostic, ...]
    leftover: tuple[LinkId, ...]
    rank: RankResult | None = None

    @property
    def decomposed(self) -> bool:
        """Whether every link was placed in a group with no error."""
        return not self.leftover and not any(d.code.startswith("E") for d in self.issues)

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
            "applicable": self.applicable, "applicability": list(self.applicability),
            "applicability_ru": list(self.applicability_ru),
            "issues": [d.to_dict() for d in self.issues],
            "leftover": list(self.leftover),
            "rank_test": self.rank.to_dict() if self.rank else None,
        }


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
    loops = _prismatic_loops(chain)
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
    issues += _idle(chain)
    if rank is not None:
        issues += _rank_issues(chain, rank, peeling)
    issues += [diagnostic("I_HIGH_DEGREE", [link], [p.id for p in chain.pairs_of(link)],
                          k=len(chain.pairs_of(link)))
               for link in chain.moving_links if len(chain.pairs_of(link)) > 3]

    formula, formula_levels = _formula(inputs, groups)
    analysis = StructuralAnalysis(
        chain=chain, n=n, p5=p5, p4=p4, W=w, W_star=w_star, m=m, input_groups=inputs,
        groups=tuple(groups), formula=formula, formula_levels=formula_levels,
        mechanism_class=max((g.group_class for g in groups), default=1), applicable=False,
        applicability=(), applicability_ru=(), issues=tuple(issues),
        leftover=tuple(sorted(peeling.leftover + peeling.disconnected, key=id_key)), rank=rank)
    failed = _applicability(analysis, graph)
    return replace(analysis, applicable=not failed, applicability=tuple(f[0] for f in failed),
                   applicability_ru=tuple(f[1] for f in failed))


def _formula(inputs: tuple[AssurGroup, ...], groups: list[AssurGroup]
             ) -> tuple[str, tuple[tuple[str, ...], ...]]:
    """Structure formula (input groups, then the groups in layering order) and its levels."""
    levels: dict[int, list[str]] = {}
    for group in groups:
        levels.setdefault(group.level, []).append(group.label)
    head = ", ".join(g.label for g in inputs)
    formula = " → ".join(([head] if head else []) + [g.label for g in groups])
    by_level = tuple(([tuple(g.label for g in inputs)] if inputs else []) +
                     [tuple(levels[k]) for k in sorted(levels)])
    return formula, by_level


def _mismatch(n: int, p5: int, p4: int, w: int, w_star: int, m: int,
              rank: RankResult | None) -> Diagnostic:
    star = f" (W* = {w_star})" if w_star != w else ""
    star_ru = star
    if rank is not None and rank.W_geom != w:
        star += f"; with the given dimensions W_geom = {rank.W_geom}"
        star_ru += f"; при заданных размерах W_geom = {rank.W_geom}"
    return diagnostic("E_MOBILITY_MISMATCH", pairs=(), n=n, p5=p5, p4=p4, W=w, m=m, star=star,
                      star_ru=star_ru)


# ------------------------------------------------------------------------- compound hinges


def _recentre_compound_hinges(chain: Chain, graph: BodyGraph, peeling: Peeling) -> Chain | None:
    """Put the centre of each compound hinge on its link known first (§2.2)."""
    star: dict[Any, list] = {}
    for pair in chain.pairs:
        if pair.origin != pair.id:
            star.setdefault(pair.origin, []).append(pair)
    if not star:
        return None
    inputs = {d.link for d in chain.inputs}
    huge = len(chain.links) + 1

    def rank(link: LinkId) -> tuple:
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
    seen: dict[frozenset, list] = {}
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
    graph = nx.MultiGraph()
    graph.add_edges_from((*pair.links, pair.id) for pair in prismatic)
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

    Parallel pairs are distinct edges, so two pairs between the same links are no bridge.
    A bridge is an edge of the depth-first tree from the frame; its far side is the subtree
    of its deeper end. Sides come in depth-first order, each in depth-first order.
    """
    graph = nx.MultiGraph()
    graph.add_nodes_from(chain.links)
    graph.add_edges_from((*pair.links, pair.id) for pair in chain.pairs)
    tree = nx.dfs_tree(graph, chain.frame)
    order = {node: k for k, node in enumerate(nx.dfs_preorder_nodes(graph, chain.frame))}
    candidates = []
    for a, b in _bridges(graph):
        if a not in order:  # a part not connected to the frame
            continue
        child = b if order[b] > order[a] else a
        side = {child} | nx.descendants(tree, child)
        if not side & inputs:
            candidates.append((order[child], side))
    sides: list[set[LinkId]] = []
    for _, side in sorted(candidates, key=lambda item: item[0]):
        if not any(side <= bigger for bigger in sides):
            sides.append(side)
    return [sorted(side, key=order.__getitem__) for side in sides]


def _bridges(graph: nx.MultiGraph) -> list[tuple[LinkId, LinkId]]:
    """The bridges of a multigraph: the single-edge biconnected components of its simple
    graph whose two links share no parallel pair (one pass, no copy of the multigraph)."""
    return [edge[0] for edge in nx.biconnected_component_edges(nx.Graph(graph))
            if len(edge) == 1 and graph.number_of_edges(*edge[0]) == 1]


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
            names = ", ".join(f"link {x} (pair {p})" for x, p in good)
            names_ru = ", ".join(f"звено {x} (пара {p})" for x, p in good)
            item = diagnostic(item.code, item.links, item.pairs, **item.data,
                              hint=f"; an input at {names} completes the decomposition",
                              hint_ru=f"; входное {names_ru} даёт полное разложение на группы")
        out.append(item)
    return out


def _rank(chain: Chain, graph: BodyGraph, groups: list[AssurGroup],
          pose: dict) -> RankResult:
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
        hint = hint_ru = ""
        if link in unplaced:
            hint = "; this is the link the decomposition could not place"
            hint_ru = "; именно это звено не удалось включить в группы"
        out.append(diagnostic("W_PASSIVE_LINK", [link], [p.id for p in chain.pairs_of(link)],
                              hint=hint, hint_ru=hint_ru))
    for links in rank.singular:
        out.append(diagnostic("W_SINGULAR_POSE", links, ()))
    return out


# ---------------------------------------------------------------------------- applicability

_BLOCKING = {"E_OVERCONSTRAINED", "E_UNDERCONSTRAINED", "W_PASSIVE_LINK", "E_PRISMATIC_LOOP",
             "E_RIGID_TRUSS", "E_DUPLICATE_PAIR", "W_GROUP_ON_ONE_LINK"}


def _applicability(a: StructuralAnalysis, graph: BodyGraph) -> list[tuple[str, str]]:
    """Failed DGTU conditions of ``method.md`` §1.1, as (English, Russian) sentences."""
    failed: list[tuple[str, str]] = []
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

    bad_inputs = [d for d in chain.inputs if not driven_by_hinge(d)]
    if bad_inputs:
        names = ", ".join(str(d.link if d.link is not None else d.pair) for d in bad_inputs)
        failed.append((f"condition 3: every input must be a crank turning on the frame in a "
                       f"revolute pair; input(s) {names} are not",
                       f"условие 3: входное звено должно быть кривошипом, вращающимся "
                       f"относительно стойки; входы {names} этому не отвечают"))
    if "W_IDLE_LINK" in codes or "E_DISCONNECTED" in codes:
        failed.append(("condition 4: the kinematic chain must be closed and connected to the "
                       "frame; it has idle or disconnected links",
                       "условие 4: кинематическая цепь должна быть замкнутой и связанной со "
                       "стойкой; есть незамкнутые или несвязанные звенья"))
    if a.W != 1 or a.W_star != 1 or a.m != 1:
        failed.append((f"condition 5: the mechanism must have W = 1 and one input; here "
                       f"W = {a.W}, W* = {a.W_star}, inputs = {a.m}",
                       f"условие 5: степень подвижности должна быть W = 1 при одном входном "
                       f"звене; здесь W = {a.W}, W* = {a.W_star}, входов {a.m}"))
    blocking = sorted(codes & _BLOCKING)
    if blocking:
        failed.append((f"condition 6: no redundant constraints, passive links or idle "
                       f"freedoms are allowed; found {', '.join(blocking)}",
                       f"условие 6: не допускаются избыточные связи, пассивные звенья и "
                       f"лишние степени свободы; найдено {', '.join(blocking)}"))
    heavy = [link for link in chain.moving_links if len(chain.pairs_of(link)) > 3]
    if heavy:
        names = ", ".join(map(str, heavy))
        failed.append((f"condition 7: each moving link may form at most three pairs; "
                       f"link(s) {names} form more",
                       f"условие 7: каждое подвижное звено может входить не более чем в три "
                       f"кинематические пары; звенья {names} входят в большее число"))
    others = [g.label for g in a.groups if not g.is_dyad]
    if a.leftover or others or any(d.code in {"E_UNSUPPORTED_GROUP", "E_INTERNAL"} for d in
                                   a.issues):
        what, what_ru = [], []
        if others:
            what.append(f"groups {', '.join(others)} are not dyads")
            what_ru.append(f"группы {', '.join(others)} не являются двухповодковыми")
        if a.leftover:
            what.append(f"links {', '.join(map(str, a.leftover))} are in no group")
            what_ru.append(f"звенья {', '.join(map(str, a.leftover))} не вошли в группы")
        text = "; ".join(what) or "the decomposition is incomplete"
        text_ru = "; ".join(what_ru) or "разложение на группы не завершено"
        failed.append((f"condition 8: the mechanism must be built by layering dyads of kinds "
                       f"1–5 on the input group (class II); {text}",
                       f"условие 8: механизм должен образовываться наслоением двухповодковых "
                       f"групп 1–5 видов на начальный механизм (II класс); {text_ru}"))
    return failed
