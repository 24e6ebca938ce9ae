"""Every kind of the registry has its behaviour where the program looks it up.

The registry (:mod:`assur.kinds`) is data; the kinematics (:mod:`assur.kinematics.rules`) and
the kinetostatics (:data:`assur.forces.solver.EQUILIBRIA`) keep their own tables keyed by
the kind's code. A kind added to the registry and forgotten in one of them fails here, not
at the first mechanism that has such a group.
"""

from __future__ import annotations

import pytest

from assur.forces.solver import EQUILIBRIA
from assur.kinds import HIGHER, KINDS, GroupKind
from assur.kinematics.rules import rules_of

EVERY_KIND = (*KINDS.values(), *HIGHER.values())


@pytest.mark.parametrize("kind", EVERY_KIND, ids=lambda kind: kind.code)
def test_a_kind_has_a_solver_and_but_the_input_group_a_sketch_rule_and_a_shortfall(
        kind: GroupKind) -> None:
    rules = rules_of(kind)
    assert callable(rules.solve)
    # the input group always assembles and the builder sketches the crank itself
    assert (rules.sketch is None, rules.shortfall is None) == (kind.is_input, kind.is_input)


def test_every_kind_but_the_input_group_has_an_equilibrium() -> None:
    assert set(EQUILIBRIA) == {kind.code for kind in EVERY_KIND if not kind.is_input}


def test_the_pressure_angle_at_c_is_that_of_the_dyads_with_a_rod_hinged_at_c() -> None:
    """``method.md``: the angle between the rod and the path of C, for RRR and RRP."""
    with_pressure = {kind.code for kind in EVERY_KIND if rules_of(kind).pressure is not None}
    assert with_pressure == {"L1", "L2"}
