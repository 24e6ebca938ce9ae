"""Structural analysis of a long generated chain: time to decompose 1,000 dyads.

The chain is built forward: starting from the frame 0 and the crank 1, each new dyad (of a
kind drawn from L1–L5 with a fixed seed) is attached to two distinct known links chosen among
the frame and the last few links, so that the layering grows deep (hundreds of levels) as
well as wide. The script times

(a) the peeling loop alone (``assur.structure.peeling.peel``), and
(b) the whole ``analyse_structure`` (counts, peeling, classification, diagnostics, formula),
(c) ``identification_table`` on the result,

reports the median over the rounds and checks that every generated dyad is found.

Run: ``python benchmarks/bench_structure.py [--dyads N] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from assur import analyse_structure, chain_from_dict
from assur.structure.identification import identification_table
from assur.structure.peeling import body_graph, peel

_KINDS = {
    1: [("R", "a", "u", None), ("R", "u", "v", None), ("R", "v", "b", None)],
    2: [("P", "a", "u", "a"), ("R", "u", "v", None), ("R", "v", "b", None)],
    3: [("R", "a", "u", None), ("P", "u", "v", "u"), ("R", "v", "b", None)],
    4: [("P", "a", "u", "a"), ("R", "u", "v", None), ("P", "v", "b", "b")],
    5: [("P", "a", "u", "a"), ("P", "u", "v", "v"), ("R", "v", "b", None)],
}


def generated_chain(dyads: int, seed: int = 7) -> dict:
    """Chain-table data of ``dyads`` dyads layered on a crank."""
    rng = np.random.default_rng(seed)
    pairs = [{"id": "p0", "type": "R", "links": [0, 1]}]
    known = [0, 1]
    for g in range(dyads):
        recent = known[-6:]
        a = int(rng.choice(recent))
        b = int(rng.choice([0, *(x for x in recent if x != a)]))
        if a == b:
            b = 0 if a != 0 else known[-1]
        u, v = 2 + 2 * g, 3 + 2 * g
        names = {"a": a, "b": b, "u": u, "v": v}
        for k, (ptype, x, y, guide) in enumerate(_KINDS[int(rng.integers(1, 6))]):
            row = {"id": f"g{g}p{k}", "type": ptype, "links": [names[x], names[y]]}
            if guide:
                row["guide"] = names[guide]
            pairs.append(row)
        known += [u, v]
    order = rng.permutation(len(pairs))
    return {"mechanism": {"name": f"{dyads} dyads", "pairs": [pairs[k] for k in order],
                          "inputs": [1]}}


def _median_time(func, rounds: int) -> float:
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dyads", type=int, default=1000)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    chain = chain_from_dict(generated_chain(args.dyads), source="generated")
    analysis = analyse_structure(chain)
    assert len(analysis.groups) == args.dyads and not analysis.leftover, "decomposition failed"
    assert all(g.is_dyad for g in analysis.groups)
    depth = max(g.level for g in analysis.groups)
    t_peel = _median_time(lambda: peel(body_graph(chain)), args.rounds)
    t_all = _median_time(lambda: analyse_structure(chain), args.rounds)
    t_table = _median_time(lambda: identification_table(analysis), args.rounds)
    print(f"chain: {args.dyads} dyads, n = {analysis.n} links, p5 = {analysis.p5} pairs, "
          f"W = {analysis.W}, {depth} levels")
    print(f"peeling loop             {t_peel * 1e3:8.1f} ms")
    print(f"analyse_structure        {t_all * 1e3:8.1f} ms   (target < 1000 ms)")
    print(f"identification_table     {t_table * 1e3:8.1f} ms")


if __name__ == "__main__":
    main()
