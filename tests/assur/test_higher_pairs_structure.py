"""Structure of mechanisms with higher pairs against counts derived by hand.

The mechanisms are the classic ones of the textbooks:

- Артоболевский И. И. Теория механизмов и машин. 4-е изд. М.: Наука, 1988, гл. 1–2
  (число степеней подвижности W = 3n − 2p5 − p4; лишние (местные) степени свободы —
  ролик толкателя; заменяющие механизмы высших пар; кулачковые и зубчатые механизмы);
- Uicker J. J., Pennock G. R., Shigley J. E. Theory of Machines and Mechanisms, 5th ed.
  Oxford University Press, 2017, ch. 1 (mobility with higher pairs, the roller follower's
  idle freedom), ch. 3 (equivalent linkages of a cam and of gears);
- Norton R. L. Design of Machinery, 5th ed. McGraw-Hill, 2012, ch. 2 (Kutzbach's equation
  with half joints: a cam contact or a gear mesh takes one freedom).

For each: n, p5, p4 and the passive degrees of freedom counted on the drawing, W by
Chebyshev's formula, and the Assur groups of the replacing mechanism (each higher pair a
link with two lower pairs at the centres of curvature; a free roller welded to its pin's
link), written out by hand in the comments. The replacing link of the pair ``K`` is ``K'``
(``docs/structure.md``, "Higher pairs"). The points of the replacing pairs are checked
against the geometry of the drawing: the circles' centres, the base-circle points of an
involute mesh, the centre of curvature of a densely tabulated eccentric circle.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from assur.io.chain_table import chain_from_dict, load_chain
from assur.model import Chain, Sketch
from assur.structure.analysis import analyse_structure
from assur.structure.classification import AssurGroup
from assur.structure.replacing import replacement, replacing_mechanism
from synthesis.cli import main

TABLES = Path(__file__).resolve().parents[2] / "input_tables"
ALPHA = math.radians(20.0)


def _pair(pid: str, ptype: str, a: Any, b: Any, **extra: Any) -> dict[str, Any]:
    return {"id": pid, "type": ptype, "links": [a, b], **extra}


def _sketch(chain: Chain) -> Sketch:
    assert chain.geometry is not None
    return chain.geometry


def _chain(pairs: list[dict[str, Any]], geometry: dict[str, Any], inputs: list[Any]
           ) -> Chain:
    return chain_from_dict({"mechanism": {"pairs": pairs, "inputs": inputs},
                            "geometry": geometry})


def _circle(x: float, y: float, r: float, concave: bool = False) -> dict[str, Any]:
    return {"circle": {"centre": [x, y], "radius": r, "concave": concave}}


def _roller_cam_translating() -> Chain:
    """Eccentric disc 1 (radius 40, centre (15, 0) off the shaft A) under a roller 2 (radius
    10) on the pin B of the translating follower 3 (guide C)."""
    return _chain([_pair("A", "R", 0, 1), _pair("B", "R", 2, 3),
                   _pair("C", "P", 3, 0, guide=0), _pair("K", "H", 1, 2)],
                  {"A": {"point": [0, 0]}, "B": {"point": [15, 50]},
                   "C": {"point": [15, 80], "direction": 90},
                   "K": {"profiles": [_circle(15, 0, 40), _circle(15, 50, 10)]}}, [1])


def _knife_edge_table() -> Chain:
    """A disc cam given by a table (r = 45 − 5 sin θ every 30°) under the knife edge of a
    translating follower 2 (guide B)."""
    angles = list(range(0, 360, 30))
    radii = [45 - 5 * math.sin(math.radians(a)) for a in angles]
    return _chain([_pair("A", "R", 0, 1), _pair("B", "P", 2, 0, guide=0),
                   _pair("K", "H", 1, 2)],
                  {"A": {"point": [0, 0]}, "B": {"point": [0, 80], "direction": 90},
                   "K": {"profiles": [{"table": {"centre": [0, 0], "angles": angles,
                                                 "radii": radii}},
                                      {"point": [0, 40]}]}}, [1])


def _rocking_roller() -> Chain:
    """Eccentric disc 1 (radius 30, centre (10, 0)) rocking the lever 3 (pivot D) through the
    roller 2 (radius 8) on its pin B."""
    b = [10 + 38 * math.cos(math.pi / 3), 38 * math.sin(math.pi / 3)]
    return _chain([_pair("A", "R", 0, 1), _pair("B", "R", 2, 3), _pair("D", "R", 3, 0),
                   _pair("K", "H", 1, 2)],
                  {"A": {"point": [0, 0]}, "B": {"point": b}, "D": {"point": [70, 10]},
                   "K": {"profiles": [_circle(10, 0, 30), _circle(b[0], b[1], 8)]}}, [1])


def _rocking_flat() -> Chain:
    """Eccentric disc 1 (radius 30, centre (10, 0)) under the flat face y = 30 of the lever 2
    pivoted at D (80, 45)."""
    return _chain([_pair("A", "R", 0, 1), _pair("D", "R", 2, 0), _pair("K", "H", 1, 2)],
                  {"A": {"point": [0, 0]}, "D": {"point": [80, 45]},
                   "K": {"profiles": [_circle(10, 0, 30),
                                      {"line": {"point": [0, 30], "direction": 0}}]}}, [1])


def _gear_pair() -> Chain:
    """Gears 1 (pitch radius 30, on A) and 2 (60, on D), 20° involute, on fixed axles."""
    return _chain([_pair("A", "R", 0, 1), _pair("D", "R", 0, 2),
                   _pair("G", "H", 1, 2, gear={"radii": [30, 60]})],
                  {"A": {"point": [0, 0]}, "D": {"point": [90, 0]},
                   "G": {"centres": [[0, 0], [90, 0]]}}, [1])


def _planetary(driven: int) -> Chain:
    """A simple epicyclic train: the sun 1 (pitch radius 20, on A), the planet 2 (20) on the
    carrier 3's pin C, the fixed ring (60, internal teeth) part of the frame 0."""
    return _chain([_pair("A", "R", 0, 1), _pair("O", "R", 0, 3), _pair("C", "R", 3, 2),
                   _pair("S", "H", 1, 2, gear={"radii": [20, 20]}),
                   _pair("M", "H", 2, 0, gear={"radii": [20, 60], "internal": True})],
                  {"A": {"point": [0, 0]}, "O": {"point": [0, 0]}, "C": {"point": [40, 0]},
                   "S": {"centres": [[0, 0], [40, 0]]}, "M": {"centres": [[40, 0], [0, 0]]}},
                  [driven])


#: name → (chain, n, p5, p4, passive rollers, the groups of the replacing mechanism as
#: (links, the types of their three pairs in any order)), each counted by hand below.
CLASSIC = {
    # Cam, translating roller follower: n = 3 (cam, roller, follower), p5 = 3 (A, B: R;
    # C: P), p4 = 1; W = 9 − 6 − 1 = 2, the roller's turning passive: W = 1. Replacing:
    # the roller welded to 3, K' from the disc's centre (on 1) to B (on 3): dyad {3, K'} of
    # pairs C (P), K1 (R), K2 (R).
    "cam, translating roller follower": (_roller_cam_translating, 3, 3, 1, [2],
                                         [({3, "K'"}, "PRR")]),
    # Eccentric cam, translating flat-faced follower (input_tables): n = 2, p5 = 2 (A: R;
    # B: P), p4 = 1; W = 6 − 4 − 1 = 1. Replacing: K' hinged at the disc's centre on 1,
    # sliding along the face on 2: dyad {2, K'} of pairs B (P), K1 (R), K2 (P).
    "eccentric cam, flat-faced follower": (lambda: load_chain(
        TABLES / "cam_eccentric_flat.yaml"), 2, 2, 1, [], [({2, "K'"}, "PPR")]),
    # Disc cam, translating knife-edge follower: n = 2, p5 = 2 (A: R; B: P), p4 = 1;
    # W = 1, no roller. Replacing: K' from the profile's centre of curvature (on 1) to the
    # knife's edge (on 2): dyad {2, K'} of pairs B (P), K1 (R), K2 (R).
    "disc cam, knife-edge follower": (_knife_edge_table, 2, 2, 1, [],
                                      [({2, "K'"}, "PRR")]),
    # Cam, oscillating roller follower: n = 3, p5 = 3 (A, B, D: R), p4 = 1; W = 2, roller
    # passive: W = 1. Replacing: the four-bar A, disc centre, B, D: dyad {3, K'} RRR.
    "cam, oscillating roller follower": (_rocking_roller, 3, 3, 1, [2],
                                         [({3, "K'"}, "RRR")]),
    # Cam, oscillating flat-faced follower: n = 2, p5 = 2 (A, D: R), p4 = 1; W = 1.
    # Replacing: K' hinged at the disc's centre on 1, sliding along the lever's face:
    # dyad {2, K'} of pairs D (R), K1 (R), K2 (P).
    "cam, oscillating flat-faced follower": (_rocking_flat, 2, 2, 1, [],
                                             [({2, "K'"}, "PRR")]),
    # Gear pair on fixed axles: n = 2, p5 = 2, p4 = 1; W = 6 − 4 − 1 = 1. Replacing: the
    # link N1N2 makes the four-bar A, N1, N2, D: dyad {2, G'} RRR.
    "gear pair": (_gear_pair, 2, 2, 1, [], [({2, "G'"}, "RRR")]),
    # Epicyclic train, the carrier 3 driven: n = 3 (sun, planet, carrier), p5 = 3 (A, O, C),
    # p4 = 2 (the sun's and the ring's mesh); W = 9 − 6 − 2 = 1. Replacing: the planet 2 and
    # M' (planet to ring) hang on the carrier and the frame: dyad {2, M'} RRR; then the sun 1
    # and S' (sun to planet): dyad {1, S'} RRR.
    "planetary gear, carrier driven": (lambda: _planetary(3), 3, 3, 2, [],
                                       [({2, "M'"}, "RRR"), ({1, "S'"}, "RRR")]),
    # The same train driven by the sun: the planet, the carrier, S' and M' form one group
    # of four links and six pairs (externals S1 to 1, M2 to 0, O to 0; internals S2, M1, C):
    # a class III triad with the planet as its central link.
    "planetary gear, sun driven": (lambda: _planetary(1), 3, 3, 2, [],
                                   [({2, 3, "S'", "M'"}, "RRRRRR")]),
    # Geared five-bar (input_tables): n = 4, p5 = 5, p4 = 1; W = 12 − 10 − 1 = 1.
    # Replacing: dyad {2, G'} RRR (the gears' four-bar), then dyad {3, 4} RRR.
    "geared five-bar": (lambda: load_chain(TABLES / "geared_five_bar.yaml"), 4, 5, 1, [],
                        [({2, "G'"}, "RRR"), ({3, 4}, "RRR")]),
    # Cam-lever mechanism (input_tables): n = 5, p5 = 6 (A, B, D, E, F: R; G: P), p4 = 1;
    # W = 15 − 12 − 1 = 2, roller passive: W = 1. Replacing: dyad {3, K'} RRR, then the
    # slider's dyad {4, 5} of pairs E, F (R) and G (P).
    "cam-lever mechanism": (lambda: load_chain(TABLES / "cam_lever.yaml"), 5, 6, 1, [2],
                            [({3, "K'"}, "RRR"), ({4, 5}, "PRR")]),
    # Tabulated disc cam, roller follower (input_tables): n = 3, p5 = 3, p4 = 1; W = 2,
    # roller passive: W = 1; dyad {3, K'} of pairs C (P), K1, K2 (R).
    "tabulated cam, roller follower": (lambda: load_chain(TABLES / "cam_table_roller.yaml"),
                                       3, 3, 1, [2], [({3, "K'"}, "PRR")]),
}


@pytest.mark.parametrize("name", list(CLASSIC))
def test_counts_and_groups_of_the_replacing_mechanism_match_the_hand_count(name: str) -> None:
    build, n, p5, p4, rollers, groups = CLASSIC[name]
    analysis = analyse_structure(build())
    assert (analysis.n, analysis.p5, analysis.p4) == (n, p5, p4)
    assert analysis.W == 3 * n - 2 * p5 - p4
    assert [dof.link for dof in analysis.passive] == rollers
    assert analysis.W_star == analysis.W - len(rollers) == 1
    assert analysis.rank is not None and analysis.rank.W_geom == 1  # the replacing pose
    found = [(set(group.links), "".join(sorted(_pair_types(analysis.chain, group))))
             for group in analysis.groups]
    assert found == groups
    assert not analysis.applicable
    assert "lower pairs only" in analysis.conditions("en")[0]
    assert "только на низшие пары" in analysis.conditions("ru")[0]


def _pair_types(chain: Chain, group: AssurGroup) -> list[str]:
    """The types of a group's external and internal pairs."""
    ids = [pair for pair, _, _ in group.external] + list(group.internal)
    return [chain.pair(pid).type.value for pid in ids]


def test_the_replacing_pairs_stand_at_the_centres_of_the_circles() -> None:
    replaced = replacing_mechanism(_roller_cam_translating())
    points = _sketch(replaced).points
    assert points["K1"] == 15 + 0j and points["K2"] == 15 + 50j  # disc centre, roller centre
    assert {link for pair in replaced.pairs for link in pair.links} == {0, 1, 3, "K'"}


def test_a_flat_face_gives_a_slider_along_it() -> None:
    replaced = replacing_mechanism(_rocking_flat())
    slider = next(pair for pair in replaced.pairs if pair.id == "K2")
    assert slider.type.value == "P" and slider.guide == 2
    assert _sketch(replaced).points["K1"] == 10 + 0j
    assert _sketch(replaced).directions["K2"].unit == 1 + 0j  # the face's direction


def test_a_gear_mesh_is_replaced_by_the_link_between_the_base_circle_points() -> None:
    """The pitch point P = (30, 0); the line of action through it at 20° to the tangent,
    direction (sin α, cos α); N1, N2 the feet of the perpendiculars from the centres."""
    points = _sketch(replacing_mechanism(_gear_pair())).points
    n1 = 30 * math.cos(ALPHA) * complex(math.cos(ALPHA), -math.sin(ALPHA))
    n2 = complex(30 + 60 * math.sin(ALPHA) ** 2, 60 * math.sin(ALPHA) * math.cos(ALPHA))
    assert abs(points["G1"] - n1) < 1e-12 and abs(points["G2"] - n2) < 1e-12
    assert abs(abs(points["G2"] - 90) - 60 * math.cos(ALPHA)) < 1e-12  # on the base circle


def test_a_tabulated_eccentric_circle_has_its_centre_of_curvature_at_the_circle_centre() -> None:
    """A circle of radius 40 whose centre is 12 mm from the pole, tabulated every 5° about
    the pole (r(θ) = e cos θ + √(R² − e² sin² θ)): at the contact with a roller above it,
    the spline's centre of curvature is the circle's centre."""
    e, big = 12.0, 40.0
    angles = list(range(0, 360, 5))
    radii = [e * math.cos(math.radians(a)) + math.sqrt(big ** 2 - (e * math.sin(
        math.radians(a))) ** 2) for a in angles]
    top = complex(e, 0) + big * 1j  # the roller of radius 10 touches it here, centre above
    chain = _chain([_pair("A", "R", 0, 1), _pair("B", "R", 2, 3),
                    _pair("C", "P", 3, 0, guide=0), _pair("K", "H", 1, 2)],
                   {"A": {"point": [0, 0]}, "B": {"point": [e, top.imag + 10]},
                    "C": {"point": [e, 90], "direction": 90},
                    "K": {"profiles": [{"table": {"centre": [0, 0], "angles": angles,
                                                  "radii": radii}},
                                       _circle(e, top.imag + 10, 10)]}}, [1])
    found = replacement(chain)
    assert [dof.link for dof in found.passive] == [2]
    centre, roller = found.replacements[0].points
    assert centre is not None and abs(centre - complex(e, 0)) < 2e-3
    assert roller == complex(e, top.imag + 10)


# --------------------------------------------------------------------- bad profiles, gears

ROLLER = ("mechanism:\n  pairs:\n    - {id: A, type: R, links: [0, 1]}\n"
          "    - {id: B, type: R, links: [2, 3]}\n"
          "    - {id: C, type: P, links: [3, 0], guide: 0}\n"
          "    - {id: K, type: H, links: [1, 2]}\n  inputs: [1]\n"
          "geometry:\n  A: {point: [0, 0]}\n  B: {point: [15, 50]}\n"
          "  C: {point: [15, 80], direction: 90}\n  K: {profiles: [%s, %s]}\n")
GEARS = ("mechanism:\n  pairs:\n    - {id: A, type: R, links: [0, 1]}\n"
         "    - {id: D, type: R, links: [0, 2]}\n"
         "    - {id: G, type: H, links: [1, 2], gear: %s}\n  inputs: [1]\n"
         "geometry:\n  A: {point: [0, 0]}\n  D: {point: [90, 0]}\n  G: {centres: %s}\n")
DISC = "{circle: {centre: [15, 0], radius: 40}}"
ROLL = "{circle: {centre: [15, 50], radius: 10}}"

#: A table, and each place and words its refusal must name.
BAD = {
    "roller radius zero": (ROLLER % (DISC, "{circle: {centre: [15, 50], radius: 0}}"),
                           ["geometry 'K' 'profiles'[1].circle 'radius': must be positive"]),
    "profiles apart": (ROLLER % ("{circle: {centre: [15, 0], radius: 39}}", ROLL),
                       ["geometry 'K' 'profiles': the profiles do not touch",
                        "1.0 mm apart"]),
    "profiles cut": (ROLLER % ("{circle: {centre: [15, 0], radius: 40.5}}", ROLL),
                     ["cut into each other 0.5 mm deep"]),
    "table short and unsorted, radius negative, lengths differ": (ROLLER % (
        "{table: {centre: [0, 0], angles: [0, 90, 80, 200], radii: [30, 30, -2]}}", ROLL),
        ["'profiles'[0].table 'angles': a profile table needs at least 6 nodes; found 4",
         "'profiles'[0].table 'angles': the angles must increase strictly: angle [2] = 80",
         "'profiles'[0].table 'radii'[2]: must be positive; found -2",
         "'profiles'[0].table 'radii': one radius per angle: 3 radii for 4 angles"]),
    "table beyond a turn": (ROLLER % (
        ("{table: {centre: [0, 0], angles: [0, 60, 120, 180, 240, 300, 360], "
        "radii: [40, 40, 40, 40, 40, 40, 40]}}"), ROLL),
        ["'profiles'[0].table 'angles': the angles must lie within one turn"]),
    "one profile": (ROLLER.replace("[%s, %s]", "[%s]") % DISC,
                    ["geometry 'K' 'profiles': expected a list of two profiles"]),
    "two lines": (ROLLER % ("{line: {point: [0, 40], direction: 0}}",
                            "{line: {point: [0, 40], direction: 0}}"),
                  ["geometry 'K' 'profiles': a 'line' profile and a 'line' profile cannot"]),
    "unknown profile": (ROLLER % ("{ellipse: [1, 2]}", ROLL),
                        ["geometry 'K' 'profiles'[0]: expected one profile"]),
    "gear radius negative, angle 95": (GEARS % ("{radii: [30, -60], pressure_angle: 95}",
                                                "[[0, 0], [90, 0]]"),
                                       ["(id 'G').gear 'radii': must be two positive pitch",
                                        ("(id 'G').gear 'pressure_angle': must lie strictly "
                                        "between 0 and 90; found 95")]),
    "gear internal, equal radii": (GEARS % ("{radii: [30, 30], internal: true}",
                                            "[[0, 0], [90, 0]]"),
                                   [("(id 'G').gear 'radii': an internal mesh needs two "
                                    "different pitch radii")]),
    "gear centres apart": (GEARS % ("{radii: [30, 50]}", "[[0, 0], [90, 0]]"),
                           ["geometry 'G' 'centres': the profiles do not touch",
                            "10.0 mm apart"]),
    "gear on a lower pair": (GEARS.replace("type: R, links: [0, 2]}",
                                           "type: R, links: [0, 2], gear: {radii: [1, 2]}}")
                             % ("{radii: [30, 60]}", "[[0, 0], [90, 0]]"),
                             [("(id 'D') 'gear': 'gear' is given for a higher pair (type H) "
                              "only; this pair is of type R")]),
    "gear without centres": (GEARS.replace("  G: {centres: %s}\n", "") % "{radii: [30, 60]}",
                             ["geometry 'G': the gear mesh 'G' (links 1–2) needs 'centres"]),
}


@pytest.mark.parametrize("name", list(BAD))
def test_bad_profiles_and_gear_data_are_refused_naming_the_field(
        name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text, expected = BAD[name]
    table = tmp_path / "bad.yaml"
    table.write_text(text, encoding="utf-8")
    assert main(["check", str(table)]) == 2
    err = capsys.readouterr().err
    for words in expected:
        assert words in err, err
    assert "Traceback" not in err


def test_the_picture_shows_the_profiles_beside_the_replacing_mechanism() -> None:
    """The left panel draws both pitch circles, both base circles, the line of action and
    the replacing link dashed; the right panel is the replacing mechanism's scheme (its
    replacing link G' among the pairs drawn)."""
    import re

    from assur.plot.formats import figure_bytes
    from assur.plot.higher import replacing_figure

    analysis = analyse_structure(load_chain(TABLES / "geared_five_bar.yaml"))
    svg = figure_bytes(replacing_figure(analysis, lang="ru"), "svg", tight=False).decode()
    ids = set(re.findall(r'id="([^"]*)"', svg))
    assert {"profile-G-0", "profile-G-1", "base-G", "line-of-action-G", "replacing-G'",
            "pair-G1", "pair-G2"} <= ids
    assert "Заменяющий механизм" in svg and "Механизм с высшими парами" in svg


def test_the_gap_of_two_profiles_against_the_drawing() -> None:
    """Gaps measured on the drawing: a roller of radius 10 above the table cam r = 45 − 5 sin θ
    (its lowest radius 40 at 90°, a node) stands y − 50 off it; a face at height y stands
    y − 40 off it; a pinion of radius 20 inside a ring of radius 60 with its centre 39 mm
    off the ring's stands 1 mm off; a knife edge 5 mm above a face, 5 mm."""
    from assur.model import CircleProfile, Direction, LineProfile, PolarProfile
    from assur.profiles import contact

    angles = tuple(float(a) for a in range(0, 360, 30))
    cam = PolarProfile(0j, angles, tuple(45 - 5 * math.sin(math.radians(a)) for a in angles))
    for y in (45.0, 49.0, 50.0, 51.0, 60.0):
        touch = contact(cam, CircleProfile(complex(0, y), 10.0))
        assert touch is not None and abs(touch.gap - (y - 50)) < 1e-9
        face = contact(LineProfile(complex(0, y - 10), Direction(0.0, 1 + 0j)), cam)
        assert face is not None and abs(face.gap - (y - 50)) < 1e-9
    ring = contact(CircleProfile(39 + 0j, 20.0), CircleProfile(0j, 60.0, concave=True))
    assert ring is not None and ring.gap == 1.0 and ring.point == 59 + 0j
    knife = contact(CircleProfile(5j, 0.0), LineProfile(0j, Direction(0.0, 1 + 0j)))
    assert knife is not None and knife.gap == 5.0


def test_the_coursework_report_shows_both_mechanisms_and_the_passive_freedom() -> None:
    """The cam-lever mechanism's report: the counts section subtracts the roller's passive
    freedom (W = 2 − 1 = 1 = m, no mismatch told), and the schemes section holds the figure
    of the mechanism beside its replacing mechanism."""
    from synthesis.app.coursework import build_report

    report = build_report(TABLES / "cam_lever.yaml", lang="ru", points=12)
    sections = {section.ident: section.body for section in report.sections}
    assert "исключены: W = 1" in sections["counts"]
    assert 'class="bad"' not in sections["counts"]
    # the page's W and its summary are the mobility with the roller subtracted (n = 5,
    # p5 = 6, p4 = 1 by the table's header: W = 15 − 12 − 1 = 2, less 1 passive)
    assert '<p id="value-W" data-value="1">W = 1</p>' in sections["counts"]
    assert "W = 3·5 − 2·6 − 1 = 2 − 1 = 1" in sections["counts"]
    assert 'id="replacing-mechanism"' in sections["schemes"]
