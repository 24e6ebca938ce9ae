"""Checks shared by the tests of triads and class IV groups on seeded random designs."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from assur.errors import TableError
from assur.kinematics.build import load_model
from assur.kinematics.higher import HigherGroup, follow_mode
from assur.kinematics.higher.continuation import HigherSolution
from assur.kinematics.higher.groups import ClassIVDrawing

TABLES = Path(__file__).resolve().parents[2] / "input_tables"


def refused(table: str, changes: Mapping[str, str], tmp_path: Path) -> list[tuple[str, Any]]:
    """The problems (code, data) of the shipped ``table`` with each text ``old`` (found once)
    replaced by ``new``; the model must not build."""
    text = (TABLES / table).read_text(encoding="utf-8")
    for old, new in changes.items():
        assert text.count(old) == 1
        text = text.replace(old, new)
    path = tmp_path / "table.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(TableError) as error:
        load_model(path)
    return [(i.message.code, i.message.data) for i in error.value.issues]


def check_analogs_against_central_differences(group: HigherGroup, inputs: Callable[[Any], Any],
                                              d: int) -> None:
    """The exact analogs of every joint and rotation of ``d`` designs against central
    differences (step 1e-5 rad) at four crank angles, where the mode exists with margin."""
    centre = np.radians([17.0, 95.0, 200.0, 290.0])
    h = 1e-5
    solution = follow_mode(group, inputs, np.concatenate([centre, centre - h, centre + h]),
                           analogs=True)
    n = len(centre)
    ok = solution.exists.reshape(d, 3, n).all(axis=1) & (solution.margin[:, :n] > 0.05)
    assert ok.any()
    size = np.asarray(group.size)[:, None]
    for name, jet in list(solution.joints.items()) + list(solution.rotations.items()):
        v, v1 = jet.v.reshape(d, 3, n), jet.d1.reshape(d, 3, n)
        d2 = jet.d2.reshape(d, 3, n)
        unit = np.broadcast_to(size, ok.shape) if name in solution.joints else 1.0
        for fd, analog in (((v[:, 2] - v[:, 1]) / (2 * h), v1[:, 0]),
                           ((v1[:, 2] - v1[:, 1]) / (2 * h), d2[:, 0])):
            error = np.abs(fd - analog) / (np.abs(analog) + unit)
            assert (error[ok] <= 1e-5).all(), (name, error[ok].max())


def random_base(rng: np.random.Generator, d: int
                ) -> tuple[Callable[[float, float], np.ndarray], tuple[np.ndarray, ...],
                           tuple[np.ndarray, ...]]:
    """A sampler of random vectors (length in [low, high], any direction), the drawn base
    points P₁ (20–40 from the origin), P₂, P₃ (30–60 from P₁) and three unit guide directions
    of ``d`` designs."""
    def polar(low: float, high: float) -> np.ndarray:
        return rng.uniform(low, high, d) * np.exp(2j * np.pi * rng.uniform(size=d))

    p1 = polar(20, 40)
    base = (p1, p1 + polar(30, 60), p1 + polar(30, 60))
    guide = tuple(np.exp(2j * np.pi * rng.uniform(size=d)) for _ in range(3))
    return polar, base, guide


def check_class_iv_rigid(solution: HigherSolution, g: ClassIVDrawing, own: str = "") -> np.ndarray:
    """Every distance on every link of a class IV group constant over the cycle (1e-9 L) and
    each link's reported rotation that of a vector between two of its joints (1e-9).

    ``own`` is the suffix of the points of a and c drawn at the internal pairs ("" where C,
    D, E, F are hinges, "a"/"c" for ``Ca``, ``Dc``, … of the coupled solver). Returns where
    the group exists (at least 30 % of the cycle is required).
    """
    ok = solution.exists
    assert ok.mean() > 0.3
    j = solution.joints
    a_, c_ = ("a", "c") if own else ("", "")
    ca, fa, dc, ec = "C" + a_, "F" + a_, "D" + c_, "E" + c_
    size = np.broadcast_to(np.asarray(g.size)[:, None], ok.shape)[ok]
    pairs = [(ca, "Ha", g.c, g.h_a), (fa, "Ha", g.f, g.h_a), (ca, fa, g.c, g.f),
             (dc, "Hc", g.d, g.h_c), (ec, "Hc", g.e, g.h_c), (dc, ec, g.d, g.e),
             ("C", "D", g.c, g.d), ("F", "E", g.f, g.e)]
    for a, b, a0, b0 in pairs:
        error = np.abs(np.abs(j[a] - j[b]) - np.abs(np.asarray(a0) - b0)[:, None])
        assert (error[ok] <= 1e-9 * size).all(), (a, b)
    for link, (x, y, x0, y0) in {"a": ("Ha", ca, g.h_a, g.c), "b": ("C", "D", g.c, g.d),
                                 "c": ("Hc", dc, g.h_c, g.d), "d": ("F", "E", g.f, g.e)}.items():
        turn = (j[y] - j[x]) / (np.asarray(y0) - x0)[:, None]
        with np.errstate(invalid="ignore"):  # NaN where the group does not assemble
            error = np.abs(np.exp(1j * solution.rotations[link]) - turn / np.abs(turn))
        assert (error[ok] <= 1e-9).all(), link
    return np.asarray(ok)
