"""Forward peeling of a chain into its input groups and Assur groups (``structure.md`` §4.3).

The chain is first turned into a *body graph*: every link is a body, except that the two
links of a driven pair between moving links (an actuator) are frozen into one composite body
(§2.1, T21). Starting from the known set K = frame ∪ input links, the loop repeatedly

(a) accepts every dyad (two unknown bodies joined by one pair, each with one pair into K);
(b) otherwise searches connected unknown sets S by increasing size: the local count
    d(S) = 3|S| − 2·p(S) < 0 is a redundancy, the first d(S) = 0 is a group;
(c) stops when no set up to ``S_MAX`` bodies is determined, reporting each leftover
    component with its count.

A group's level is 1 + the highest level of the known bodies its external pairs attach to.
"""

from __future__ import annotations

from collections import Counter, deque
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from assur.model import Chain, LinkId, PairId, id_key
from assur.structure._nx import networkx
from assur.structure.diagnostics import Diagnostic, diagnostic
from assur.text import Message

__all__ = ["S_MAX", "BodyGraph", "Peeling", "RawGroup", "body_graph", "peel"]

S_MAX = 6


@dataclass
class BodyGraph:
    """The chain seen as rigid bodies (composite bodies for frozen actuators)."""

    chain: Chain
    body_of: dict[LinkId, LinkId]
    members: dict[LinkId, tuple[LinkId, ...]]
    edges: list[tuple[PairId, LinkId, LinkId]]
    frozen: tuple[PairId, ...]
    inner: list[PairId]
    input_bodies: list[LinkId]
    driven: dict[LinkId, PairId]
    issues: list[Diagnostic] = field(default_factory=list)

    def links(self, bodies: Iterable[LinkId]) -> list[LinkId]:
        """The real links of some bodies."""
        return sorted((link for body in bodies for link in self.members[body]), key=id_key)


@dataclass
class RawGroup:
    """A set of bodies accepted as a group, before classification."""

    bodies: tuple[LinkId, ...]
    level: int
    external: list[tuple[PairId, LinkId, LinkId]]  # (pair, body of the group, known body)
    internal: list[PairId]


@dataclass
class Peeling:
    """The result of the peeling loop."""

    graph: BodyGraph
    groups: list[RawGroup]
    issues: list[Diagnostic]
    leftover: list[LinkId]
    level: dict[LinkId, int]
    disconnected: list[LinkId]


def body_graph(chain: Chain) -> BodyGraph:
    """Freeze actuators and find the driven pair of every input link.

    The links joined by frozen actuator pairs become one body, named by its smallest link.
    """
    frozen: list[PairId] = []
    input_links: list[LinkId] = []
    driven: dict[LinkId, PairId] = {}
    issues: list[Diagnostic] = []
    for drive in chain.inputs:
        if drive.pair is not None:
            pair = chain.pair(drive.pair)
            if chain.frame in pair.links:
                link = pair.other(chain.frame)
                input_links.append(link)
                driven[link] = pair.id
            else:
                frozen.append(pair.id)
            continue
        assert drive.link is not None  # a drive names a link or a pair
        link = drive.link
        on_frame = [p for p in chain.pairs_of(link) if chain.frame in p.links]
        input_links.append(link)
        if len(on_frame) == 1:
            driven[link] = on_frame[0].id
        elif link != chain.frame:
            issues.append(diagnostic("E_INPUT_NOT_ON_FRAME", [link], [p.id for p in on_frame],
                                     k=len(on_frame)))
    body_of = {link: link for link in chain.links}
    if frozen:  # the links welded by frozen actuator pairs; a link of no actuator stays alone
        nx = networkx()
        welded = nx.Graph()
        welded.add_edges_from(chain.pair(pid).links for pid in frozen)
        body_of.update({link: min(body, key=id_key) for body in nx.connected_components(welded)
                        for link in body})
    members: dict[LinkId, list[LinkId]] = {}
    for link in chain.links:
        members.setdefault(body_of[link], []).append(link)
    edges: list[tuple[PairId, LinkId, LinkId]] = []
    inner: list[PairId] = []
    frozen_set = set(frozen)
    for pair in chain.pairs:
        if pair.id in frozen_set:
            continue
        a, b = body_of[pair.links[0]], body_of[pair.links[1]]
        if a == b:
            inner.append(pair.id)
        else:
            edges.append((pair.id, a, b))
    input_bodies = []
    for link in input_links:
        if body_of[link] not in input_bodies and link != chain.frame:
            input_bodies.append(body_of[link])
    return BodyGraph(chain, body_of, {k: tuple(v) if len(v) == 1 else tuple(sorted(v, key=id_key))
                                      for k, v in members.items()},
                     edges, tuple(frozen), inner, input_bodies, driven, issues)


def peel(graph: BodyGraph, s_max: int = S_MAX) -> Peeling:
    """Run the peeling loop of ``structure.md`` §4.3 on a body graph."""
    return _Peeler(graph, s_max).run()


class _Peeler:
    def __init__(self, graph: BodyGraph, s_max: int) -> None:
        self.g = graph
        self.s_max = s_max
        frame = graph.body_of[graph.chain.frame]
        self.frame = frame
        self.adj: dict[LinkId, list[tuple[PairId, LinkId]]] = {b: [] for b in graph.members}
        self.mult: Counter[frozenset[LinkId]] = Counter()
        for pid, a, b in graph.edges:
            self.adj[a].append((pid, b))
            self.adj[b].append((pid, a))
            self.mult[frozenset((a, b))] += 1
        reach = {frame}
        queue = deque([frame])
        while queue:
            for _, other in self.adj[queue.popleft()]:
                if other not in reach:
                    reach.add(other)
                    queue.append(other)
        self.disconnected = [b for b in graph.members if b not in reach]
        self.level: dict[LinkId, int] = {frame: 0}
        for body in graph.input_bodies:
            self.level[body] = 0
        self.known: set[LinkId] = set(self.level)
        self.unknown: set[LinkId] = {b for b in reach if b not in self.known}
        self.kpairs: dict[LinkId, int] = {
            b: sum(1 for _, o in self.adj[b] if o in self.known) for b in self.unknown}
        self.groups: list[RawGroup] = []
        self.issues: list[Diagnostic] = []
        #: The sort key of every body (:func:`id_key`), computed once.
        self.key = {body: id_key(body) for body in graph.members}
        keys = self.key
        self.work: deque[tuple[PairId, LinkId, LinkId]] = deque(
            sorted((e for e in graph.edges if e[1] in self.unknown and e[2] in self.unknown),
                   key=lambda e: (keys[e[1]], keys[e[2]]) if keys[e[1]] <= keys[e[2]]
                   else (keys[e[2]], keys[e[1]])))

    # -- bookkeeping -------------------------------------------------------------------

    def _pairs(self, bodies: set[LinkId]
               ) -> tuple[list[tuple[PairId, LinkId, LinkId]], list[PairId]]:
        """External (pair, body, known body) and internal pairs of a set of unknown bodies."""
        external: list[tuple[PairId, LinkId, LinkId]] = []
        internal: list[PairId] = []
        key = self.key
        for body in sorted(bodies, key=key.__getitem__):
            for pid, other in self.adj[body]:
                if other in self.known:
                    external.append((pid, body, other))
                elif other in bodies and key[body] < key[other]:
                    internal.append(pid)
        return external, internal

    def _mark_known(self, bodies: set[LinkId],
                    external: list[tuple[PairId, LinkId, LinkId]]) -> int:
        level = 1 + max((self.level[k] for _, _, k in external), default=-1)
        for body in bodies:
            self.level[body] = level
        self.known |= bodies
        self.unknown -= bodies
        for body in bodies:
            self.kpairs.pop(body, None)
        for body in bodies:
            for _, other in self.adj[body]:
                if other in self.unknown:
                    self.kpairs[other] += 1
                    self.work.extend((pid, other, y) for pid, y in self.adj[other]
                                     if y in self.unknown)
        return level

    def _accept(self, bodies: set[LinkId]) -> None:
        external, internal = self._pairs(bodies)
        level = self._mark_known(bodies, external)
        self.groups.append(RawGroup(tuple(sorted(bodies, key=self.key.__getitem__)), level,
                                    external, internal))

    def _count(self, bodies: set[LinkId]) -> tuple[int, int]:
        p = 0
        for body in bodies:
            for _, other in self.adj[body]:
                if other in self.known:
                    p += 2
                elif other in bodies:
                    p += 1
        p //= 2
        return 3 * len(bodies) - 2 * p, p

    # -- the loop ------------------------------------------------------------------------

    def run(self) -> Peeling:
        while self.unknown:
            if self._dyads():
                continue
            if self._search() or self._large_group():
                continue
            self._stall()
            break
        leftover = self.g.links(self.unknown)
        return Peeling(self.g, self.groups, self.issues, leftover, dict(self.level),
                       self.g.links(self.disconnected))

    def _dyads(self) -> bool:
        found = False
        while self.work:
            _, u, v = self.work.popleft()
            if (u in self.unknown and v in self.unknown and self.kpairs[u] == 1
                    and self.kpairs[v] == 1 and self.mult[frozenset((u, v))] == 1):
                self._accept({u, v})
                found = True
        return found

    def _search(self) -> bool:
        order = sorted(self.unknown, key=self.key.__getitem__)
        for size in range(1, min(len(order), self.s_max) + 1):
            for subset in _connected_subsets(order, self.adj, self.unknown, size):
                d, p = self._count(subset)
                if d < 0:
                    external, internal = self._pairs(subset)
                    self.issues.append(self._overconstrained(subset, external, internal, d, p))
                    self._mark_known(subset, external)
                    return True
                if d == 0:
                    self._accept(subset)
                    return True
        return False

    def _overconstrained(self, subset: set[LinkId],
                         external: list[tuple[PairId, LinkId, LinkId]],
                         internal: list[PairId], d: int, p: int) -> Diagnostic:
        inputs = sorted({k for _, _, k in external if k in self.g.input_bodies}, key=id_key)
        notes = {}
        if len(inputs) >= 2:
            notes["why"] = Message("diag.note.inputs_overspecify", {
                "first": ", ".join(map(str, inputs[:-1])), "last": inputs[-1]})
        pairs = [pid for pid, _, _ in external] + internal
        return diagnostic("E_OVERCONSTRAINED", self.g.links(subset), pairs, notes, k=len(subset),
                          p=p, d=d, q=-d)

    def _components(self) -> list[set[LinkId]]:
        nx = networkx()
        sub = nx.Graph()
        sub.add_nodes_from(self.unknown)
        sub.add_edges_from((a, b) for _, a, b in self.g.edges
                           if a in self.unknown and b in self.unknown)
        return sorted(nx.connected_components(sub), key=lambda c: min(id_key(x) for x in c))

    def _large_group(self) -> bool:
        """Accept a leftover component with d = 0 that is larger than ``s_max`` as a group."""
        for component in self._components():
            if self._count(component)[0] == 0:
                self._accept(component)
                return True
        return False

    def _stall(self) -> None:
        for component in self._components():
            d, p = self._count(component)
            external, internal = self._pairs(component)
            pairs = [pid for pid, _, _ in external] + internal
            code = "E_UNDERCONSTRAINED" if d > 0 else "E_OVERCONSTRAINED"
            self.issues.append(diagnostic(code, self.g.links(component), pairs,
                                          k=len(component), p=p, d=d, q=-d))


def _connected_subsets(order: list[LinkId], adj: dict[LinkId, list[tuple[PairId, LinkId]]],
                       allowed: set[LinkId], size: int) -> Iterator[set[LinkId]]:
    """Every connected set of ``size`` bodies among ``allowed`` once (ESU enumeration)."""
    index = {body: k for k, body in enumerate(order)}

    def neighbours(body: LinkId) -> set[LinkId]:
        return {other for _, other in adj[body] if other in allowed}

    def extend(subset: set[LinkId], extension: list[LinkId], reach: set[LinkId],
               root: int) -> Iterator[set[LinkId]]:
        if len(subset) == size:
            yield set(subset)
            return
        pending = list(extension)
        while pending:
            w = pending.pop(0)
            fresh = [u for u in sorted(neighbours(w), key=index.__getitem__)
                     if index[u] > root and u not in subset and u not in reach]
            yield from extend(subset | {w}, pending + fresh, reach | set(fresh), root)

    for body in order:
        root = index[body]
        start = [u for u in sorted(neighbours(body), key=index.__getitem__) if index[u] > root]
        yield from extend({body}, start, {body, *start}, root)

