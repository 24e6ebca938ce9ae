"""Structural scheme and formalised structural scheme pictures.

Expected values come from the tables themselves (read here with plain YAML) and from the
course's description of the fig. 1.25 mechanism (``method.md`` §3.5), not from the drawing
code.
"""

from __future__ import annotations

import io
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image

from assur import analyse_structure, chain_from_dict, load_chain
from assur.plot.schemes import group_graph, save_schemes, scheme_bytes, scheme_layout

# method.md §3.5: the groups of fig. 1.25 and the formalised scheme's edges
# ("an edge means uses a link of"), with the hinge that makes each attachment.
COURSE_GROUPS = ("II₁(2,3)", "II₄(4,5)", "II₃(6,7)", "II₂(8,9)", "II₅(10,11)")
COURSE_EDGES = {("I(0,1)", "II₁(2,3)"): ("1-2",), ("II₁(2,3)", "II₄(4,5)"): ("3-4",),
                ("II₁(2,3)", "II₃(6,7)"): ("2-6",), ("II₃(6,7)", "II₂(8,9)"): ("6-8",),
                ("II₂(8,9)", "II₅(10,11)"): ("8-10",)}

FOUR_BAR = {"mechanism": {"pairs": [
    {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
    {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
    "inputs": [1]}}


@pytest.fixture(scope="module")
def tables_dir_module():
    return Path(__file__).resolve().parent.parent / "input_tables"


@pytest.fixture(scope="module")
def course(tables_dir_module):
    chain = load_chain(tables_dir_module / "course_11_link.yaml")
    return chain, analyse_structure(chain)


def _gids(svg: bytes) -> list[str]:
    return re.findall(r'<g id="([^"]+)"', svg.decode("utf-8"))


def test_every_pair_and_group_is_drawn_once(course, tables_dir_module):
    chain, analysis = course
    raw = yaml.safe_load((tables_dir_module / "course_11_link.yaml").read_text("utf-8"))
    table_pairs = [str(p["id"]) for p in raw["mechanism"]["pairs"]]
    gids = _gids(scheme_bytes(chain, analysis, "svg", which="structural"))
    drawn_pairs = sorted(g[len("pair-"):] for g in gids if g.startswith("pair-"))
    assert drawn_pairs == sorted(table_pairs)
    drawn_groups = sorted(g[len("group-"):] for g in gids if g.startswith("group-"))
    assert drawn_groups == sorted(COURSE_GROUPS)


def test_formalised_scheme_edges_are_the_course_dependencies(course):
    chain, analysis = course
    edges = {(a, b): pairs for a, b, pairs in group_graph(chain, analysis)}
    assert edges == COURSE_EDGES
    gids = _gids(scheme_bytes(chain, analysis, "svg", which="formalised"))
    assert sorted(g for g in gids if g.startswith("edge-")) == sorted(
        f"edge-{a}-{b}" for a, b in COURSE_EDGES)
    assert sorted(g[5:] for g in gids if g.startswith("node-")) == sorted(
        ("I(0,1)",) + COURSE_GROUPS)


def test_geometric_layout_uses_the_table_points(course, tables_dir_module):
    chain, analysis = course
    raw = yaml.safe_load((tables_dir_module / "course_11_link.yaml").read_text("utf-8"))
    geometry = raw["geometry"]
    layout = scheme_layout(chain, analysis)
    assert layout.from_geometry
    types = {str(p["id"]): p["type"] for p in raw["mechanism"]["pairs"]}
    for pid, kind in types.items():
        x, y = geometry[pid]["point"]
        if kind == "R":  # hinges stay where the sketch puts them
            assert layout.pairs[pid] == pytest.approx(complex(x, y), abs=1e-12)
        else:  # a slider block stays on its slide line, drawn along the table's direction
            angle = math.radians(geometry[pid]["direction"])
            along = complex(math.cos(angle), math.sin(angle))
            offset = layout.pairs[pid] - complex(x, y)
            assert (np.conj(along) * offset).imag == pytest.approx(0.0, abs=1e-9)
            assert abs(layout.directions[pid] - along) < 1e-12
    # slider 9 sits under its hinge 8-9: the foot of the perpendicular on the line y = 230
    assert layout.pairs["9-0"] == pytest.approx(complex(*geometry["8-9"]["point"]), abs=1e-9)
    # slider 11 has no hinge: it sits where its two slide lines cross (x = 250 and the line
    # through 10-11, whose given point already has x = 250)
    assert layout.pairs["11-0"] == pytest.approx(complex(*geometry["10-11"]["point"]), abs=1e-9)


def test_layered_layout_without_coordinates(tables_dir_module):
    chain = load_chain(tables_dir_module / "course_11_link_table.yaml")
    chain = replace(chain, geometry=None)
    analysis = analyse_structure(chain)
    layout = scheme_layout(chain, analysis)
    assert not layout.from_geometry
    points = np.array(list(layout.pairs.values()))
    assert np.isfinite(points).all()
    assert len(np.unique(np.round(points, 9))) == len(chain.pairs)  # no two pairs overlap
    # links sit in columns by layering level: the level-4 dyad is right of the level-1 dyad
    level = {link: g.level for g in analysis.groups for link in g.links}
    assert min(layout.links[k].real for k in (10, 11)) > max(
        layout.links[k].real for k, lv in level.items() if lv == 1)


def test_png_and_svg_files(tmp_path, course):
    chain, analysis = course
    png = save_schemes(chain, analysis, tmp_path / "schemes.png")
    with Image.open(png) as image:
        assert image.format == "PNG"
        pixels = np.asarray(image.convert("RGB"), dtype=int)
    # the groups' colours are really painted (the RRR dyad is red, #d62728)
    red = (abs(pixels - np.array([214, 39, 40])).sum(axis=2) < 60).sum()
    assert red > 100
    svg = save_schemes(chain, analysis, tmp_path / "schemes.svg", lang="ru")
    text = svg.read_text("utf-8")
    assert "Структурная схема" in text and "Формализованная структурная схема" in text
    assert "класс II, порядок 2, вид 1 (ВВВ)" in text


def test_svg_is_reproducible(course):
    chain, analysis = course
    assert scheme_bytes(chain, analysis, "svg") == scheme_bytes(chain, analysis, "svg")


def test_four_bar_without_geometry_has_one_dyad():
    chain = chain_from_dict(FOUR_BAR)
    analysis = analyse_structure(chain)
    gids = _gids(scheme_bytes(chain, analysis, "svg"))
    assert sorted(g for g in gids if g.startswith("pair-")) == ["pair-A", "pair-B", "pair-C",
                                                                 "pair-D"]
    assert [g for g in gids if g.startswith("group-")] == ["group-II₁(2,3)"]
    assert group_graph(chain, analysis) == [("I(0,1)", "II₁(2,3)", ("B",))]


def test_bad_picture_name(tmp_path, course):
    chain, analysis = course
    with pytest.raises(ValueError, match=r"\.bmp; write one of: \.png, \.svg, \.pdf, \.jpg"):
        save_schemes(chain, analysis, tmp_path / "schemes.bmp")
    assert not (tmp_path / "schemes.bmp").exists()
    with pytest.raises(ValueError, match="which must be"):
        scheme_bytes(chain, analysis, "svg", which="kinematic")


def test_png_opens(course):
    chain, analysis = course
    with Image.open(io.BytesIO(scheme_bytes(chain, analysis, "png", which="formalised"))) as im:
        assert im.size[0] > 400 and im.size[1] > 200


def test_check_command_draws_the_schemes(tmp_path, tables_dir_module, capsys):
    from synthesis.cli import main

    table = tables_dir_module / "course_11_link.yaml"
    out = tmp_path / "schemes.svg"
    assert main(["check", str(table), "--plot", str(out), "--lang", "ru"]) == 0
    gids = _gids(out.read_bytes())
    assert sum(g.startswith("pair-") for g in gids) == 16  # p5 = 16 (method.md §1.2)
    assert "Формула строения" in capsys.readouterr().out
    assert main(["check", str(table), "--plot", str(tmp_path / "schemes.gif"), "--lang", "ru"]) == 2
    captured = capsys.readouterr()
    assert "рисунок нельзя записать в формате .gif" in captured.err
    assert captured.out == ""  # refused before the table was read or analysed


def test_triad_is_outlined_with_class_and_order():
    # a class III triad: base link 4 with leashes 2, 3, 5 (three external pairs B, E, G)
    chain = chain_from_dict({"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
        {"id": "C", "type": "R", "links": [2, 4]}, {"id": "D", "type": "R", "links": [3, 4]},
        {"id": "E", "type": "R", "links": [3, 0]}, {"id": "F", "type": "R", "links": [4, 5]},
        {"id": "G", "type": "P", "links": [5, 0], "guide": 0}], "inputs": [1]}})
    analysis = analyse_structure(chain)
    svg = scheme_bytes(chain, analysis, "svg").decode("utf-8")
    assert "group-III(2,3,4,5)" in svg
    assert "class III, order 3, III(base 4; leashes R–R, R–R, R–P)" in svg
    assert group_graph(chain, analysis) == [("I(0,1)", "III(2,3,4,5)", ("B",))]


# kind → (pair of i with its known link, internal pair, pair of j with its known link);
# for a P pair, which side carries the guide ("known", "i" or "j")  (structure.md §4.5)
_DYADS = {1: (("R", None), ("R", None), ("R", None)),
          2: (("P", "known"), ("R", None), ("R", None)),
          3: (("R", None), ("P", "i"), ("R", None)),
          4: (("P", "known"), ("R", None), ("P", "known")),
          5: (("P", "known"), ("P", "j"), ("R", None))}


@st.composite
def dyad_chains(draw):
    """A crank and a random series of dyads, each on two different known links."""
    pairs = [{"id": "0-1", "type": "R", "links": [0, 1]}]
    known, built, link = [0, 1], [], 1
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.integers(1, 5))
        a, b = draw(st.lists(st.sampled_from(known), min_size=2, max_size=2, unique=True))
        i, j = link + 1, link + 2
        link += 2
        ends = ((i, a), (i, j), (j, b))
        for (ptype, carrier), (p, q) in zip(_DYADS[kind], ends):
            pair = {"id": f"{p}-{q}", "type": ptype, "links": [p, q]}
            if ptype == "P":
                pair["guide"] = {"known": q, "i": i, "j": j}[carrier]
            pairs.append(pair)
        built.append({"links": (i, j), "on": {f"{i}-{a}": a, f"{j}-{b}": b}})
        known += [i, j]
    return {"mechanism": {"pairs": pairs, "inputs": [1]}}, built


@given(dyad_chains())
def test_random_dyad_chains_layout_and_group_graph(case):
    data, built = case
    chain = chain_from_dict(data)
    analysis = analyse_structure(chain)
    assert sorted(sorted(g.links) for g in analysis.groups) == sorted(
        sorted(d["links"]) for d in built)
    label = {link: g.label for g in (*analysis.input_groups, *analysis.groups)
             for link in g.links}
    expected: dict[tuple[str, str], list[str]] = {}
    for dyad in built:  # an arrow from the group of every moving link a dyad stands on
        target = label[dyad["links"][0]]
        for pid, known in dyad["on"].items():
            if known != 0:
                expected.setdefault((label[known], target), []).append(pid)
    edges = {(a, b): sorted(p) for a, b, p in group_graph(chain, analysis)}
    assert edges == {k: sorted(v) for k, v in expected.items()}
    layout = scheme_layout(chain, analysis)
    points = np.array([layout.pairs[p.id] for p in chain.pairs])
    assert np.isfinite(points).all()
    assert len(np.unique(np.round(points, 9))) == len(points)  # no two pairs drawn together
    for pair in chain.pairs:  # every slider has a unit guide direction
        if pair.type.value == "P":
            assert abs(abs(layout.directions[pair.id]) - 1) < 1e-12
