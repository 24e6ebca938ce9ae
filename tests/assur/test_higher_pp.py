"""Triads with a P–P leash on seeded random crank-driven designs.

The P–P leash slides on a guide of the base and on a guide of the crank, so the base turns
with the crank; the first leash (a bar) hangs on the crank, the second (R–R, R–P or P–R) on
the frame. Each check compares with a computation written here: the number of real modes by
a dense sweep of the first leash's angle (the second leash's offset from its circle or line,
sign changes counted), the closure of every leash and the base's rotation over full cycles,
and central differences of the positions. ``ASSUR_HIGHER_FULL=1`` takes more designs.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from higher_checks import check_analogs_against_central_differences, random_base, refused

from assur.kinematics import jets as J
from assur.kinematics.higher import Triad, TriadInputs, assembly_modes, follow_mode

TWO_PI = 2 * np.pi
FULL = os.environ.get("ASSUR_HIGHER_FULL") == "1"
COUNTED, CYCLED, DIFFERENCED = (1000, 60, 12) if FULL else (200, 6, 4)
SECOND = ["RR", "RP", "PR"]
#: The second leash's kinds followed over cycles in the default run (each costs a full
#: continuation; the P–P code is the same for all three).
CYCLED_KINDS, DIFFERENCED_KINDS = (SECOND, SECOND) if FULL else (["RR"], ["PR"])


@dataclass
class Designs:
    """Per leash the drawn base point b_k, the external point a_k (hinge A_k, or a point of
    the known link's guide for R–P and P–P) and the guide direction u_k (the known link's
    for R–P and P–P, the base's for P–R)."""

    second: str
    base: tuple[np.ndarray, ...]
    external: tuple[np.ndarray, ...]
    guide: tuple[np.ndarray, ...]

    @property
    def group(self) -> Triad:
        guides = (None, None if self.second == "RR" else self.guide[1], self.guide[2])
        return Triad(("RR", self.second, "PP"), self.base, self.external,  # type: ignore[arg-type]
                     guides)  # type: ignore[arg-type]

    def inputs(self, phi: Any) -> TriadInputs:
        """The crank turns leash 1's hinge and leash 3's guide; leash 2 is on the frame."""
        turn = J.expi(phi)
        return TriadInputs((self.external[0] * turn, self.external[1], self.external[2] * turn),
                           (None, self.guide[1] if self.second == "RP" else None,
                            self.guide[2] * turn))


def random_designs(seed: int, d: int, second: str) -> Designs:
    """Drawn assembled: an R–P guide through its base hinge, a P–R hinge on the base's guide."""
    rng = np.random.default_rng(seed)
    polar, base, guide = random_base(rng, d)
    second_hinge = {"RR": base[1] + polar(30, 80), "RP": base[1],
                    "PR": base[1] + rng.uniform(-30, 30, d) * guide[1]}[second]
    external = (base[0] + polar(40, 60), second_hinge, base[2] + polar(10, 30))
    return Designs(second, base, external, guide)


def _second_offset(designs: Designs, p1: Any, turn: Any, phi: Any) -> np.ndarray:
    """The second leash's distance from its circle (R–R) or line (R–P, P–R), the base at P₁
    turned by ``turn``, the crank at φ."""
    b = designs.base
    point = p1 + (b[1] - b[0])[..., None] * turn
    a2 = designs.external[1][..., None]
    if designs.second == "RR":
        return np.asarray(np.abs(point - a2) - np.abs(b[1] - a2[..., 0])[..., None])
    if designs.second == "RP":
        return np.asarray((np.conj(designs.guide[1][..., None]) * (point - a2)).imag)
    return np.asarray((np.conj(designs.guide[1][..., None] * turn) * (a2 - point)).imag)


@pytest.mark.parametrize("second", SECOND)
def test_mode_count_agrees_with_a_sweep_of_the_first_leash(second: str) -> None:
    """At a random crank angle the base turns with the crank; the first leash's angle ψ is
    swept and the sign changes of the second leash's offset counted."""
    designs = random_designs(90 + SECOND.index(second), COUNTED, second)
    rng = np.random.default_rng(7)
    phi = rng.uniform(0, TWO_PI, COUNTED)
    modes = assembly_modes(designs.group, designs.inputs(phi))
    samples = 8192
    psi = (np.arange(samples) + 0.5) * TWO_PI / samples
    r1 = np.abs(designs.base[0] - designs.external[0])[:, None]
    a1 = (designs.external[0] * np.exp(1j * phi))[:, None]
    turn = np.exp(1j * phi)[:, None]
    offset = _second_offset(designs, a1 + r1 * np.exp(1j * psi), turn, phi)
    swept = (np.sign(offset) != np.sign(np.roll(offset, -1, axis=1))).sum(axis=1)
    grazing = np.abs(np.log(np.abs(modes.roots)))
    robust = ~((grazing > 1e-6) & (grazing < 1e-3)).any(axis=1) \
        & ~(np.nan_to_num(modes.margin, nan=1.0) < 1e-3).any(axis=1)
    assert robust.mean() >= 0.95
    assert (swept[robust] == modes.count[robust]).all()
    assert set(modes.count.tolist()) == {0, 2}
    assert designs.group.degree == 1


@pytest.mark.parametrize("second", CYCLED_KINDS)
def test_every_leash_stays_closed_and_the_base_turns_with_the_crank(second: str) -> None:
    """Over the cycle leash 1 keeps its length, leash 2 stays on its circle or line, the
    base keeps its shape and turns with the crank (to 1e-9 L), wherever the mode exists."""
    designs = random_designs(100 + SECOND.index(second), CYCLED, second)
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    solution = follow_mode(designs.group, designs.inputs, phi)
    ok = solution.exists
    assert ok.any(axis=1).all()
    assert (~ok).any()  # some designs stop assembling: both ends of the mode are exercised
    size = np.broadcast_to(np.asarray(designs.group.size)[:, None], ok.shape)
    b = designs.base
    p = [np.asarray(solution.joints[f"P{i + 1}"]) for i in range(3)]
    a1 = designs.external[0][:, None] * np.exp(1j * phi)
    errors = [np.abs(p[0] - a1) - np.abs(b[0] - designs.external[0])[:, None],
              _second_offset(designs, p[0], np.exp(1j * phi), phi)]
    shape = ((0, 1), (0, 2)) if second != "PR" else ((0, 2),)  # a P–R leash's P2 is A₂
    errors += [np.abs(p[i] - p[j]) - np.abs(b[i] - b[j])[:, None] for i, j in shape]
    errors.append(np.angle(np.exp(1j * (solution.rotations["base"] - phi))) * size)
    errors.append(np.angle(np.exp(1j * (solution.rotations["leash3"] - phi))) * size)
    for error in errors:
        assert (np.abs(error[ok]) <= 1e-9 * size[ok]).all()


@pytest.mark.parametrize("second", DIFFERENCED_KINDS)
def test_analogs_against_central_differences(second: str) -> None:
    designs = random_designs(110 + SECOND.index(second), DIFFERENCED, second)
    check_analogs_against_central_differences(designs.group, designs.inputs, DIFFERENCED)


def test_a_pp_leash_comes_last_and_alone() -> None:
    designs = random_designs(120, 1, "RP")
    g = designs.group
    for kinds in (("RR", "PP", "RP"), ("RP", "PP", "PP")):
        with pytest.raises(ValueError, match="P–P"):
            Triad(kinds, g.base, g.external, (designs.guide[0], designs.guide[1],  # type: ignore[arg-type]
                                              designs.guide[2]))


def test_the_example_table_keeps_its_leashes_on_their_pairs() -> None:
    """``six_bar_triad_pp.yaml``: 2 modes at the sketch; over the turn the base turns with
    the crank, the bars keep their lengths, the leash 5 slides on the base's guide through
    G4 and on the crank's guide through G1 at a fixed angle to both, and both blocks stay
    on one rigid leash."""
    from assur.kinematics.analysis import analyse, values
    from assur.kinematics.build import load_model
    from assur.kinematics.higher.kind import HigherGroupSolution

    table = Path(__file__).parents[2] / "input_tables" / "six_bar_triad_pp.yaml"
    model = load_model(table)
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    motion = analyse(model, phi)
    assert motion.exists.all()
    turn = np.exp(1j * phi)
    b, c, d, g4, g1 = (np.asarray(values(motion.joints[p])) for p in ("B", "C", "D", "G4", "G1"))
    drawn = {"B": 40 + 0j, "C": 60 + 90j, "D": 40 + 100j, "E": -30 + 140j, "G4": 100 + 100j,
             "G1": 50 + 40j}
    assert np.abs(b - drawn["B"] * turn).max() < 1e-9
    assert np.abs(np.abs(c - b) - abs(drawn["C"] - drawn["B"])).max() < 1e-9
    assert np.abs(np.abs(d - drawn["E"]) - abs(drawn["D"] - drawn["E"])).max() < 1e-9
    assert np.abs(d - c - (drawn["D"] - drawn["C"]) * turn).max() < 1e-9  # base turns by φ
    base_guide = (np.conj(turn) * (g4 - c - (drawn["G4"] - drawn["C"]) * turn)).imag
    crank_guide = (np.conj(np.exp(1j * np.radians(70)) * turn)
                   * (g1 - drawn["G1"] * turn)).imag
    assert np.abs(base_guide).max() < 1e-9 and np.abs(crank_guide).max() < 1e-9
    assert np.abs(g1 - g4 - (drawn["G1"] - drawn["G4"]) * turn).max() < 1e-9  # one leash
    solution = motion.solutions["III(2,3,4,5)"]
    assert isinstance(solution, HigherGroupSolution) and len(solution.modes()) == 2


@pytest.mark.parametrize(("changes", "code", "data"), [
    ({"{id: E, type: R, links: [3, 0]}": "{id: E, type: P, links: [3, 0], guide: 0}",
      "{id: D, type: R, links: [3, 4]}": "{id: D, type: P, links: [3, 4], guide: 4}",
      "E: {point: [-30, 140]}": "E: {point: [-30, 140], direction: 20}",
      "D: {point: [40, 100]}": "D: {point: [40, 100], direction: 80}"},
     "higher.sketch.leashes", {"group": "III(2,3,4,5)", "found": "R–R, P–P, P–P"}),
    ({"direction: 70}": "direction: 0}"},
     "higher.sketch.pp_parallel", {"group": "III(2,3,4,5)", "pair": "G1"}),
])
def test_two_pp_leashes_or_a_pp_leash_on_parallel_guides_are_refused(
        tmp_path: Path, changes: dict[str, str], code: str, data: dict[str, str]) -> None:
    """The example with the bar E–D made a second P–P leash (on the frame and the base), or
    with the crank's guide drawn parallel to the base's: one problem naming the group."""
    assert refused("six_bar_triad_pp.yaml", changes, tmp_path) == [(code, data)]
