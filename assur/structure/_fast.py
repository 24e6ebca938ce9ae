"""Speed paths of the structural analysis: answers the peeling already proves.

:func:`closed_by_dyads` tells, from the peeling, that no link hangs beyond a bridge without an
input, so that the readable search for open appendages (``analysis._appendages``: the bridges
of the chain's graph through networkx) is not run for the usual mechanism built of dyads;
:func:`no_prismatic_loop` tells that no loop is made of prismatic pairs only, so that the
readable search (``analysis._prismatic_loops``: the components of the prismatic pairs through
networkx) is not run either.  With both, the analysis of such a chain never imports networkx
(:mod:`assur.structure._nx`).  ``tests/assur/test_structure_fast.py`` checks on random chains
that whenever they say so the readable searches find nothing, and that the analysis is the
same with the speed paths switched off.
"""

from __future__ import annotations

from assur.model import PairType
from assur.structure.peeling import BodyGraph, Peeling, RawGroup

__all__ = ["closed_by_dyads", "no_prismatic_loop"]


def closed_by_dyads(graph: BodyGraph, peeling: Peeling) -> bool:
    """Whether the peeling proves that the chain has no open appendage (``W_IDLE_LINK``).

    It does when every link is a body of its own (no frozen actuator), every input link is
    driven by a pair with the frame (no problem with the inputs), and the peeling placed
    every link, in dyads only, with no finding.  The links known before a dyad are then
    joined to the frame, so each of the dyad's three pairs lies on a cycle (external pair,
    internal pair, external pair, a path between its two known links), and so does every
    other pair (it joins two links already joined); the only bridges are driven pairs,
    whose far side holds the input.

    Parameters
    ----------
    graph : BodyGraph
        The chain's body graph.
    peeling : Peeling
        The peeling of ``graph``.

    Returns
    -------
    bool
        True when no open appendage can exist; False when the readable search must decide.
    """
    if (graph.frozen or graph.issues or peeling.leftover or peeling.disconnected
            or peeling.issues):
        return False
    return all(_dyad(group) for group in peeling.groups)


def _dyad(group: RawGroup) -> bool:
    """Whether a group is a dyad: two bodies, each with one external pair, one internal."""
    ends = [body for _, body, _ in group.external]
    return (len(group.bodies) == 2 and len(group.internal) == 1 and len(ends) == 2
            and set(ends) == set(group.bodies))


def no_prismatic_loop(graph: BodyGraph, peeling: Peeling) -> bool:
    """Whether the peeling proves that no loop is made of prismatic pairs only.

    It does when the chain is closed by dyads (:func:`closed_by_dyads`), no pair joins a link
    to itself, no dyad has three prismatic pairs, and the only pairs among the frame and the
    input links are the driven ones.  Every pair is then a pair of one dyad (a link placed in
    a dyad has one pair into the links known before it, and one with its partner) or one of
    the driven pairs.  A loop through the links of some dyads takes, at the dyad placed last
    among them, both links' external pairs and the internal pair (their other pairs lead to
    links placed later): all three pairs of that dyad, one of which is a revolute pair.  A
    loop through the frame and the input links only would run on the driven pairs, which
    form a star around the frame.  So no loop has prismatic pairs only (``E_PRISMATIC_LOOP``).

    Parameters
    ----------
    graph : BodyGraph
        The chain's body graph.
    peeling : Peeling
        The peeling of ``graph``.

    Returns
    -------
    bool
        True when no loop of prismatic pairs can exist; False when the readable search must
        decide.
    """
    if graph.inner or not closed_by_dyads(graph, peeling):
        return False
    start = {graph.chain.frame, *graph.input_bodies}
    among = sum(1 for _, a, b in graph.edges if a in start and b in start)
    return among == len(graph.input_bodies) and not any(
        all(graph.chain.pair(pid).type is PairType.P
            for pid in (*(pid for pid, _, _ in group.external), *group.internal))
        for group in peeling.groups)
