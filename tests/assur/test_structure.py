"""Structural analysis: generated layered chains, frame/input choices, report contents."""

from __future__ import annotations

import hypothesis.strategies as st
from hypothesis import given

from assur import analyse_structure, chain_from_dict
from assur.structure.report import structure_report

STEPHENSON = [("A", 0, 1), ("B", 1, 5), ("C", 1, 2), ("D", 2, 3), ("E", 3, 4), ("F", 4, 5),
              ("G", 0, 4)]


def _revolute_chain(pairs: list[tuple], inputs: list, frame: object = 0) -> object:
    return chain_from_dict({"mechanism": {"frame": frame, "pairs": [
        {"id": p, "type": "R", "links": [a, b]} for p, a, b in pairs], "inputs": inputs}})


# Pairs of a dyad of each kind, as (type, end a, end b, guide) with i = "u", j = "v",
# known links "a" and "b" (method.md §2.0).
_KINDS = {
    1: [("R", "a", "u", None), ("R", "u", "v", None), ("R", "v", "b", None)],
    2: [("P", "a", "u", "a"), ("R", "u", "v", None), ("R", "v", "b", None)],
    3: [("R", "a", "u", None), ("P", "u", "v", "u"), ("R", "v", "b", None)],
    4: [("P", "a", "u", "a"), ("R", "u", "v", None), ("P", "v", "b", "b")],
    5: [("P", "a", "u", "a"), ("P", "u", "v", "v"), ("R", "v", "b", None)],
}


@st.composite
def layered_chains(draw: st.DrawFn) -> tuple[dict, list[tuple]]:
    """A mechanism built forward by attaching random dyads to random known links."""
    level = {0: 0, 1: 0}
    pairs = [{"id": "p0", "type": "R", "links": [0, 1]}]
    groups = []
    for g in range(draw(st.integers(1, 8))):
        known = sorted(level)
        a = draw(st.sampled_from(known))
        b = draw(st.sampled_from([x for x in known if x != a]))
        kind = draw(st.integers(1, 5))
        u, v = 2 + 2 * g, 3 + 2 * g
        names = {"a": a, "b": b, "u": u, "v": v}
        for k, (ptype, x, y, guide) in enumerate(_KINDS[kind]):
            row = {"id": f"g{g}p{k}", "type": ptype, "links": [names[x], names[y]]}
            if guide:
                row["guide"] = names[guide]
            pairs.append(row)
        level[u] = level[v] = 1 + max(level[a], level[b])
        groups.append((frozenset((u, v)), kind, level[u], u, v))
    # renumber the moving links after the crank at random and shuffle the pair rows: the
    # decomposition must not depend on either
    new = dict(zip(range(2, 2 + 2 * len(groups)),
                   draw(st.permutations(range(2, 2 + 2 * len(groups)))), strict=True))
    new.update({0: 0, 1: 1})
    for row in pairs:
        row["links"] = [new[x] for x in row["links"]]
        if "guide" in row:
            row["guide"] = new[row["guide"]]
    groups = [(frozenset(new[x] for x in links), kind, lev, new[u], new[v])
              for links, kind, lev, u, v in groups]
    order = draw(st.permutations(range(len(pairs))))
    return {"mechanism": {"pairs": [pairs[k] for k in order], "inputs": [1]}}, groups


@given(layered_chains())
def test_generated_layered_chains_are_recovered(case: tuple[dict, list[tuple]]) -> None:
    data, built = case
    analysis = analyse_structure(chain_from_dict(data))
    assert analysis.W == 1 and analysis.W_star == 1
    assert not analysis.leftover
    assert not [d for d in analysis.issues if d.code.startswith("E")]
    found = {frozenset(g.links): g for g in analysis.groups}
    assert set(found) == {links for links, *_ in built}
    for links, kind, level, u, v in built:
        group = found[links]
        assert (group.kind, group.level) == (kind, level)
        if kind in (2, 3, 5):            # roles fixed by the pair types
            assert (group.i, group.j) == (u, v)
    keys = [(g.level, min(g.links)) for g in analysis.groups]
    assert keys == sorted(keys)


def test_stephenson_chain_gives_class_ii_iii_or_iv_by_frame_and_input() -> None:
    # structure.md §4.6. Frame 0, input 1: two dyads (T8). Frame 2 (the binary link between
    # ternaries 1 and 3-side): with input 1 the links {0,3,4,5} form a triad on base 4
    # (internal E, F, G; leashes 0, 3, 5); with input 3 the links {0,1,4,5} form the
    # four-sided contour A, B, F, G with the external pairs C and E on the opposite links 1, 4.
    assert analyse_structure(_revolute_chain(STEPHENSON, [1])).mechanism_class == 2
    triad = analyse_structure(_revolute_chain(STEPHENSON, [1], frame=2))
    assert [g.name for g in triad.groups] == ["III(base 4; leashes R–R, R–R, R–R)"]
    assert triad.formula == "I(2,1) → III(0,3,4,5)"
    contour = analyse_structure(_revolute_chain(STEPHENSON, [3], frame=2))
    assert [(g.group_class, g.order) for g in contour.groups] == [(4, 2)]
    assert contour.mechanism_class == 4


def test_input_link_off_the_frame_is_reported() -> None:
    four_bar = [("A", 0, 1), ("B", 1, 2), ("C", 2, 3), ("D", 3, 0)]
    analysis = analyse_structure(_revolute_chain(four_bar, [2]))
    # link 2 has no pair with the frame; its neighbour 1 is hinged to it: named as the fix
    assert [(d.code, d.data) for d in analysis.issues] == [("E_INPUT_NOT_HINGED", {"other": 1})]
    by_pair = analyse_structure(_revolute_chain(four_bar, [{"pair": "A"}]))
    assert by_pair.formula == "I(0,1) → II₁(2,3)" and by_pair.applicable


def test_json_object_has_the_documented_keys() -> None:
    four_bar = [("A", 0, 1), ("B", 1, 2), ("C", 2, 3), ("D", 3, 0), ("E", 2, 4)]
    data = analyse_structure(_revolute_chain(four_bar, [1])).to_dict()
    for key in ("n", "p5", "p4", "W", "inputs", "groups", "formula", "mechanism_class",
                "applicable", "issues"):
        assert key in data
    group = data["groups"][0]
    assert {k: group[k] for k in ("links", "class", "order", "kind", "name", "level", "i", "j")} \
        == {"links": [2, 3], "class": 2, "order": 2, "kind": 1, "name": "RRR", "level": 1,
            "i": 2, "j": 3}
    assert {"code", "links", "message"} <= set(data["issues"][0])


def test_report_speaks_the_course_terms() -> None:
    slider_crank = chain_from_dict({"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
        {"id": "C", "type": "R", "links": [2, 3]},
        {"id": "D", "type": "P", "links": [3, 0], "guide": 0}], "inputs": [1]}})
    analysis = analyse_structure(slider_crank)
    russian = structure_report(analysis, lang="ru")
    assert "группа Ассура 2 класса 2 порядка 2 вида (ВВП)" in russian
    assert "Формула строения: I(0,1) → II₂(2,3)" in russian
    assert "группа входных звеньев (нулевая группа) L0" in russian
    english = structure_report(analysis)
    assert "Assur group of class 2, order 2, kind 2 (RRP); i = 3, j = 2" in english
    assert "DGTU method applicable: yes" in english


def test_groups_larger_than_the_search_limit_are_still_found() -> None:
    # the triad of tests/assur/chains/x01_triad.yaml with the subset search limited to 2
    # links: the leftover component {2,3,4,5} has d = 12 − 12 = 0 and is taken whole
    from assur.structure.peeling import body_graph, peel

    pairs = [("A", 0, 1), ("B", 1, 2), ("C", 2, 4), ("D", 3, 4), ("E", 3, 0), ("F", 4, 5),
             ("G", 5, 0)]
    result = peel(body_graph(_revolute_chain(pairs, [1])), s_max=2)
    assert [g.bodies for g in result.groups] == [(2, 3, 4, 5)]
    assert not result.issues and not result.leftover


def test_russian_report_has_no_english_sentences() -> None:
    # four-bar with a disconnected part (structure.md T26): every finding and every failed
    # condition is written in Russian
    pairs = [("A", 0, 1), ("B", 1, 2), ("C", 2, 3), ("D", 3, 0), ("E", 4, 5)]
    russian = structure_report(analyse_structure(_revolute_chain(pairs, [1])), lang="ru")
    assert "звенья {4, 5} не связаны со стойкой" in russian
    # a closed four-bar with a chain of three links from 2 to 3 (W = 2, and no input on the
    # frame can take it): links 4, 5, 6 are left over (condition 8)
    loop = [("A", 0, 1), ("B", 1, 2), ("C", 2, 3), ("D", 3, 0), ("E", 2, 4), ("F", 4, 5),
            ("G", 5, 6), ("H", 6, 3)]
    leftover = structure_report(analyse_structure(_revolute_chain(loop, [1])), lang="ru")
    assert "звенья 4, 5, 6 не вошли в группы" in leftover
    for english in ("links", "group", "condition", "expected", "found"):
        assert english not in russian and english not in leftover


def test_two_pairs_between_the_same_links_make_no_bridge() -> None:
    """A link hung from the rocker by one hinge is an open appendage (W_IDLE_LINK); held by two
    pairs to the same link it closes a loop, so it is no appendage (structure.md: parallel
    pairs are distinct edges)."""
    def idle(extra: list[dict[str, object]]) -> list[list[object]]:
        pairs = [{"id": k, "type": "R", "links": links} for k, links in
                 (("A", [0, 1]), ("B", [1, 2]), ("C", [2, 3]), ("D", [3, 0]))]
        chain = chain_from_dict({"mechanism": {"pairs": pairs + extra, "inputs": [1]}})
        return [list(d.links) for d in analyse_structure(chain).issues
                if d.code == "W_IDLE_LINK"]

    hinge = {"id": "E", "type": "R", "links": [3, 4]}
    assert idle([hinge]) == [[4]]
    assert idle([hinge, {"id": "F", "type": "P", "links": [3, 4], "guide": 3}]) == []
