"""networkx, imported when a structural question first needs a graph algorithm.

Importing networkx takes longer than the whole ``assur check`` of a small table, and the
usual table — a chain closed by dyads — needs none of its algorithms: the peeling
(:mod:`assur.structure.peeling`) places every link, and :mod:`assur.structure._fast` proves
from it that there is no open appendage and no loop of prismatic pairs.  The general path
(welded actuators, bridges, loops of prismatic pairs, the leftover components of a stalled
peeling, the contour of a group beyond a dyad) calls :func:`networkx` inside the function that
uses it; no module of :mod:`assur.structure` imports networkx at its top.
"""

from __future__ import annotations

from types import ModuleType
from typing import cast

__all__ = ["networkx"]


def networkx() -> ModuleType:
    """The networkx module, imported on the first call (later calls find it loaded).

    Returns
    -------
    module
        ``networkx``.
    """
    import networkx as nx

    return cast(ModuleType, nx)
