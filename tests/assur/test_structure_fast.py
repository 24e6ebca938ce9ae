"""The speed path of the structural analysis (:mod:`assur.structure._fast`) against the readable
one: on random chains, whenever the peeling is said to prove that no link hangs open, the
bridge search through networkx finds no open appendage, and the analysis is the same."""

from __future__ import annotations

import random

import pytest

from assur.io.chain_table import chain_from_dict
from assur.structure import analysis as readable
from assur.structure._fast import closed_by_dyads
from assur.structure.peeling import body_graph, peel

#: Pair types of the three pairs of each dyad kind: (u to a), (u to v), (v to b).
_KINDS = ["RRR", "PRR", "RPR", "PRP", "PPR"]


def _random_table(rng: random.Random) -> dict:
    """A crank with random dyads, then one random slip of the structure (or none)."""
    pairs = [{"id": "p0", "type": "R", "links": [0, 1]}]
    known = [0, 1]
    inputs: list = [1]
    for g in range(rng.randint(1, 6)):
        a, b = rng.choice(known), rng.choice(known)
        u, v = 2 + 2 * g, 3 + 2 * g
        for k, (ptype, ends) in enumerate(zip(rng.choice(_KINDS), ((a, u), (u, v), (v, b)),
                                              strict=True)):
            row = {"id": f"g{g}p{k}", "type": ptype, "links": list(ends)}
            if ptype == "P":
                row["guide"] = ends[0]
            pairs.append(row)
        known += [u, v]
    slip = rng.randrange(10)  # 6 to 9: none
    if slip == 0:  # a link hung on one hinge: an open appendage
        pairs.append({"id": "hang", "type": "R", "links": [rng.choice(known), 99]})
        if rng.random() < 0.5:  # and one more beyond it
            pairs.append({"id": "hang2", "type": "R", "links": [99, 98]})
    elif slip == 1:  # a pair dropped
        pairs.pop(rng.randrange(1, len(pairs)))
    elif slip == 2:  # a pair doubled
        twin = dict(rng.choice(pairs[1:]))
        pairs.append({**twin, "id": "twin"})
    elif slip == 3:  # a second crank
        pairs.append({"id": "crank2", "type": "R", "links": [0, 50]})
        pairs.append({"id": "rod2", "type": "R", "links": [50, rng.choice(known[2:] or [1])]})
        inputs.append(50)
    elif slip == 4:  # a two-link chain hung on one hinge, closed on itself by two pairs
        link = rng.choice(known)
        pairs += [{"id": "h1", "type": "R", "links": [link, 90]},
                  {"id": "h2", "type": "R", "links": [90, 91]},
                  {"id": "h3", "type": "R", "links": [90, 91]}]
    elif slip == 5:  # the input driven by an actuator between two moving links
        actuator = next((p for p in pairs[1:] if 0 not in p["links"]), None)
        if actuator is not None:
            actuator["type"] = "P"
            actuator["guide"] = actuator["links"][0]
            inputs = [{"pair": actuator["id"]}]
            pairs.pop(0)
    return {"mechanism": {"pairs": pairs, "inputs": inputs}}


@pytest.mark.parametrize("seed", range(3))
def test_the_speed_path_gives_the_readable_analysis(seed: int,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed)
    proved = hanging = 0
    for _ in range(40):
        chain = chain_from_dict(_random_table(rng))
        graph = body_graph(chain)
        if closed_by_dyads(graph, peel(graph)):
            proved += 1
            assert readable._idle(chain) == []
        hanging += bool(readable._idle(chain))
        fast = readable.analyse_structure(chain)
        with monkeypatch.context() as patch:
            patch.setattr(readable, "closed_by_dyads", lambda graph, peeling: False)
            slow = readable.analyse_structure(chain)
        assert fast == slow
    assert proved >= 10 and hanging >= 3  # both ways are taken
