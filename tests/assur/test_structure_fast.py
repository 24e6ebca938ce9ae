"""The speed paths of the structural analysis (:mod:`assur.structure._fast`) against the
readable ones: on random chains and on every shipped table, whenever the peeling is said to
prove that no link hangs open, the bridge search through networkx finds no open appendage;
whenever it is said to prove that no loop is made of prismatic pairs only, the search of the
prismatic pairs' components through networkx finds none; and the analysis is the same with
the speed paths switched off (networkx for every question)."""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import pytest

from assur.errors import AssurError
from assur.io.chain_table import chain_from_dict
from assur.model import Chain
from assur.structure import analysis as readable
from assur.structure._fast import closed_by_dyads, no_prismatic_loop
from assur.structure.peeling import body_graph, peel
from synthesis.app.assess import load_table_chain

ROOT = Path(__file__).resolve().parents[2]
#: Pair types of the three pairs of each dyad kind: (u to a), (u to v), (v to b).
_KINDS = ["RRR", "PRR", "RPR", "PRP", "PPR"]


def _random_table(rng: random.Random) -> dict:
    """A crank or an input slider with random dyads, then one random slip (or none)."""
    first = rng.choice("RP")
    pairs: list[dict[str, Any]] = [
        {"id": "p0", "type": first, "links": [0, 1], **({"guide": 0} if first == "P" else {})}]
    known = [0, 1]
    inputs: list = [1]
    for g in range(rng.randint(1, 6)):
        a, b = rng.choice(known), rng.choice(known)
        u, v = 2 + 2 * g, 3 + 2 * g
        types = "PPP" if rng.random() < 0.05 else rng.choice(_KINDS)  # PPP: a prismatic loop
        for k, (ptype, ends) in enumerate(zip(types, ((a, u), (u, v), (v, b)), strict=True)):
            row: dict[str, Any] = {"id": f"g{g}p{k}", "type": ptype, "links": list(ends)}
            if ptype == "P":
                row["guide"] = ends[0]
            pairs.append(row)
        known += [u, v]
    slip = rng.randrange(10)  # 8 and 9: none
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
    elif slip == 6:  # a second input slider on the frame, sliding on the first input too
        pairs.append({"id": "s1", "type": "P", "links": [0, 60], "guide": 0})
        pairs.append({"id": "s2", "type": "P", "links": [60, 1], "guide": 60})
        inputs.append(60)
    elif slip == 7:  # the input link held to the frame by a second, prismatic, pair
        pairs.append({"id": "s3", "type": "P", "links": [0, 1], "guide": 0})
    return {"mechanism": {"pairs": pairs, "inputs": inputs}}


def _without_speed_paths(chain: Chain, monkeypatch: pytest.MonkeyPatch
                         ) -> readable.StructuralAnalysis:
    """The analysis with every structural question answered by networkx."""
    with monkeypatch.context() as patch:
        patch.setattr(readable, "closed_by_dyads", lambda graph, peeling: False)
        patch.setattr(readable, "no_prismatic_loop", lambda graph, peeling: False)
        return readable.analyse_structure(chain)


@pytest.mark.parametrize("seed", range(3))
def test_the_speed_paths_give_the_readable_analysis(seed: int,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed)
    closed = hanging = loopless = looped = 0
    for _ in range(60):
        chain = chain_from_dict(_random_table(rng))
        graph = body_graph(chain)
        peeling = peel(graph)
        idle, loops = readable._idle(chain), readable._prismatic_loops(chain)
        if closed_by_dyads(graph, peeling):
            closed += 1
            assert idle == []
        if no_prismatic_loop(graph, peeling):
            loopless += 1
            assert loops == []
        hanging += bool(idle)
        looped += bool(loops)
        assert readable.analyse_structure(chain) == _without_speed_paths(chain, monkeypatch)
    # every way is taken: proofs given, appendages and loops found by the readable searches
    assert closed >= 12 and loopless >= 8 and hanging >= 3 and looped >= 3


def _shipped() -> list[Path]:
    return sorted([*(ROOT / "input_tables").glob("*.yaml"),
                   *(ROOT / "input_tables" / "problems").glob("*.yaml")])


def test_every_shipped_table_gets_the_same_analysis_without_the_speed_paths(
        monkeypatch: pytest.MonkeyPatch) -> None:
    proved = 0
    for path in _shipped():
        try:
            chain = load_table_chain(path)
        except AssurError:  # the tables of the built-in cases are not mechanism tables
            assert path.name.startswith("case_")
            continue
        fast = readable.analyse_structure(chain)
        slow = _without_speed_paths(chain, monkeypatch)
        assert fast.to_dict() == slow.to_dict(), path.name
        assert fast.issues == slow.issues, path.name
        graph = body_graph(fast.chain)
        proved += no_prismatic_loop(graph, peel(graph))
    assert proved >= 20  # the tables of dyads take the speed paths
