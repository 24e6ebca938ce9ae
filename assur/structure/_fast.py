"""Speed paths of the structural analysis: answers the peeling already proves.

:func:`closed_by_dyads` tells, from the peeling, that no link hangs beyond a bridge without an
input, so that the readable search for open appendages (``analysis._appendages``: the bridges
of the chain's graph through networkx) is not run for the usual mechanism built of dyads.
``tests/assur/test_structure_fast.py`` checks on random chains that whenever it says so the
readable search finds no appendage.
"""

from __future__ import annotations

from assur.structure.peeling import BodyGraph, Peeling, RawGroup

__all__ = ["closed_by_dyads"]


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
