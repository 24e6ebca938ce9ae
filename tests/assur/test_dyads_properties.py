"""Property tests of the group solvers (Hypothesis, deterministic profile).

Each example is one dyad whose moving input follows a crank over 48 angles, at a scale drawn
from 1e-3 to 1e6, so that part of the cycle may fail to assemble. Checked, against relations
derived independently of the solver formulas:

- the link lengths and guide constraints hold to 1e-9 relative wherever the group exists;
- existence agrees with the textbook inequality, away from its boundary;
- a rigid motion of the frame moves every output the same way;
- the vectorised result equals a loop over scalar calls;
- the two assembly variants mirror each other.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from assur.kinematics.dyads import (
    DyadSolution,
    solve_prp,
    solve_rpp,
    solve_rpr,
    solve_rrp,
    solve_rrr,
)

N = 48
PHI = np.linspace(0.0, 2.0 * np.pi, N, endpoint=False)
REL = 1e-9


def u(theta: np.ndarray | float) -> np.ndarray:
    return np.exp(1j * np.asarray(theta))


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a.real * b.imag - a.imag * b.real


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a.real * b.real + a.imag * b.imag


def wrap(angle: np.ndarray) -> np.ndarray:
    return np.angle(np.exp(1j * angle))


@dataclass(frozen=True)
class Kind:
    """A dyad kind: its solver, argument roles and an independent existence test."""

    solve: Callable[..., DyadSolution]
    points: tuple[str, ...]  # arguments that are points (move with the frame)
    angles: tuple[str, ...]  # absolute directions (turn with the frame)
    branch: str | None  # name of the assembly-variant argument


KINDS = {
    "RRR": Kind(solve_rrr, ("h_i", "h_j"), (), "sigma"),
    "RRP": Kind(solve_rrp, ("h_j", "a"), ("theta",), "sigma"),
    "RPR": Kind(solve_rpr, ("h_i", "h_j"), (), "sigma"),
    "PRP": Kind(solve_prp, ("a", "b"), ("theta_i", "theta_j"), None),
    "RPP": Kind(solve_rpp, ("h_j", "a"), ("theta_s",), None),
}


# --- strategies ---------------------------------------------------------------------------

unit = st.floats(-1.0, 1.0, allow_nan=False, allow_infinity=False)
positive = st.floats(0.1, 2.0, allow_nan=False)
angle = st.floats(-np.pi, np.pi, allow_nan=False)
scales = st.sampled_from([1e-3, 1.0, 1e3, 1e6])


@st.composite
def configurations(draw: st.DrawFn, kind: str) -> tuple[dict, float]:
    """Arguments of one dyad whose first point argument rides on a crank; and the scale."""
    s = draw(scales)

    def point() -> complex:
        return s * complex(draw(unit), draw(unit))

    crank = point() + s * draw(st.floats(0.05, 1.0)) * u(PHI + draw(angle))
    sigma = draw(st.sampled_from([1.0, -1.0]))
    if kind == "RRR":
        args = {"h_i": crank, "h_j": point(), "l_i": s * draw(positive),
                "l_j": s * draw(positive), "sigma": sigma}
    elif kind == "RRP":
        args = {"h_j": crank, "a": point(), "theta": draw(angle), "e": s * draw(unit),
                "l_j": s * draw(positive), "sigma": sigma}
    elif kind == "RPR":
        args = {"h_i": point(), "h_j": crank, "h": s * draw(unit),
                "sigma": draw(st.sampled_from([1.0, 0.0, -1.0]))}
    elif kind == "PRP":
        args = {"a": crank, "theta_i": draw(angle) + 0.4 * np.sin(PHI), "e_i": s * draw(unit),
                "b": point(), "theta_j": draw(angle), "e_j": s * draw(unit)}
    else:
        gamma = draw(st.floats(0.05, np.pi - 0.05)) * draw(st.sampled_from([1.0, -1.0]))
        args = {"h_j": crank, "gamma": gamma, "a": point(),
                "theta_s": draw(angle) + 0.4 * np.sin(PHI), "e": s * draw(unit)}
    return args, s


# --- independent checks ---------------------------------------------------------------------

def residuals(kind: str, a: dict, sol: DyadSolution, s: float) -> list[np.ndarray]:
    """Relative violations of the constraints of the group (should all be ~0)."""
    c = sol.c
    if kind == "RRR":
        return [
            (np.abs(c - a["h_i"]) - a["l_i"]) / a["l_i"],
            (np.abs(c - a["h_j"]) - a["l_j"]) / a["l_j"],
            np.abs(a["h_i"] + a["l_i"] * u(sol.angle_i) - c) / a["l_i"],
            np.abs(a["h_j"] + a["l_j"] * u(sol.angle_j) - c) / a["l_j"],
            np.abs(sol.origin_i - a["h_i"]) / s + np.abs(sol.origin_j - a["h_j"]) / s,
        ]
    if kind == "RRP":
        ut = u(a["theta"])
        return [
            (np.abs(c - a["h_j"]) - a["l_j"]) / a["l_j"],
            (cross(ut, c - a["a"]) - a["e"]) / s,  # C on its path, offset e from the guide
            (dot(ut, c - a["a"]) - sol.s_i) / (s + np.abs(sol.s_i)),
            np.abs(a["h_j"] + a["l_j"] * u(sol.angle_j) - c) / a["l_j"],
            np.abs(sol.origin_i - c) / s + np.abs(wrap(sol.angle_i - a["theta"])),
        ]
    if kind == "RPR":
        r = a["h_j"] - a["h_i"]
        rho = np.abs(r)
        frame = sol.s_i * u(sol.angle_i) + a["h"] * 1j * u(sol.angle_i)
        return [
            np.abs(frame - r) / rho,
            np.abs(a["h_i"] + sol.s_i * u(sol.angle_i) - c) / rho,
            np.abs(wrap(sol.angle_j - sol.angle_i)),
        ]
    if kind == "PRP":
        ui, uj = u(a["theta_i"]), u(a["theta_j"])
        size = s + np.abs(sol.s_i) + np.abs(sol.s_j)
        return [
            (cross(ui, c - a["a"]) - a["e_i"]) / size,
            (cross(uj, c - a["b"]) - a["e_j"]) / size,
            (dot(ui, c - a["a"]) - sol.s_i) / size,
            (dot(uj, c - a["b"]) - sol.s_j) / size,
        ]
    us, ut = u(a["theta_s"]), u(a["theta_s"] + a["gamma"])
    size = s + np.abs(sol.s_i) + np.abs(sol.s_j)
    return [
        np.abs(a["h_j"] + sol.s_j * ut - c) / size,  # C on the guide of j through H_j
        (cross(us, c - a["a"]) - a["e"]) / size,  # C on the path of slider i
        (dot(us, c - a["a"]) - sol.s_i) / size,
        np.abs(wrap(sol.angle_j - sol.angle_i - a["gamma"])),
    ]


def textbook_margin(kind: str, a: dict) -> np.ndarray:
    """Existence indicator from the textbook inequalities, normalised like the margin."""
    if kind == "RRR":
        d = np.abs(a["h_j"] - a["h_i"])
        # |l_i - l_j| <= d <= l_i + l_j, as a fraction of the nearer limit
        return np.minimum(a["l_i"] + a["l_j"] - d, d - np.abs(a["l_i"] - a["l_j"])) / d
    if kind == "RRP":
        h = cross(u(a["theta"]), a["h_j"] - a["a"]) - a["e"]
        return 1.0 - np.abs(h) / a["l_j"]
    if kind == "RPR":
        return 1.0 - np.abs(a["h"]) / np.abs(a["h_j"] - a["h_i"])
    if kind == "PRP":
        return np.abs(np.sin(a["theta_j"] - a["theta_i"])) + 0.0 * PHI
    return np.abs(np.sin(a["gamma"])) + 0.0 * PHI


@pytest.mark.parametrize("kind", sorted(KINDS))
@given(data=st.data())
def test_constraints_hold_where_the_group_exists(kind: str, data: st.DataObject) -> None:
    args, s = data.draw(configurations(kind))
    sol = KINDS[kind].solve(**args)
    ok = sol.exists
    for residual in residuals(kind, args, sol, s):
        assert np.all(np.abs(residual[ok]) <= REL), (kind, np.max(np.abs(residual[ok])))
    # failure is data: NaN geometry, a reason code, never a silent number
    assert np.all(np.isnan(sol.c[~ok])) and np.all(sol.reason[~ok] > 0)
    assert np.all(sol.reason[ok] == 0)
    # existence agrees with the textbook inequality away from its boundary
    reference = textbook_margin(kind, args)
    clear = np.abs(reference) > 1e-9
    np.testing.assert_array_equal(sol.exists[clear], reference[clear] >= 0.0)


@given(data=st.data())
def test_assembly_variant_sign_conventions(data: st.DataObject) -> None:
    args, _ = data.draw(configurations("RRR"))
    sol = solve_rrr(**args)
    ok = sol.exists & (sol.margin > 1e-6)
    side = cross(args["h_j"] - args["h_i"], sol.c - args["h_i"])  # > 0: C left of H_i -> H_j
    assert np.all(np.sign(side[ok]) == args["sigma"])

    args, _ = data.draw(configurations("RRP"))
    sol = solve_rrp(**args)
    ok = sol.exists & (sol.margin < 1 - 1e-6)
    ut = u(args["theta"])
    ahead = dot(ut, sol.c - args["h_j"])  # along +u(θ) from the foot of the perpendicular
    assert np.all(np.sign(ahead[ok]) == args["sigma"])

    args, _ = data.draw(configurations("RPR"))
    sol = solve_rpr(**args)
    ok = sol.exists & (sol.margin > 1e-6)
    assert np.all(np.sign(sol.s_i[ok]) == (-1.0 if args["sigma"] < 0 else 1.0))


def move(kind: str, args: dict, turn: float, shift: complex) -> dict:
    """The same dyad after a rigid motion of the frame: rotate by ``turn``, then shift."""
    moved = dict(args)
    for name in KINDS[kind].points:
        moved[name] = shift + args[name] * u(turn)
    for name in KINDS[kind].angles:
        moved[name] = args[name] + turn
    return moved


@pytest.mark.parametrize("kind", sorted(KINDS))
@given(data=st.data(), turn=angle, shift_x=unit, shift_y=unit)
def test_invariance_under_rigid_motion(kind: str, data: st.DataObject, turn: float,
                                       shift_x: float, shift_y: float) -> None:
    args, s = data.draw(configurations(kind))
    shift = s * complex(shift_x, shift_y)
    before = KINDS[kind].solve(**args)
    after = KINDS[kind].solve(**move(kind, args, turn, shift))
    clear = np.abs(before.margin) > 1e-9
    np.testing.assert_array_equal(after.exists[clear], before.exists[clear])
    ok = before.exists & after.exists
    tol = REL * s
    size = s + np.abs(before.c - shift)
    assert np.all(np.abs(after.c - (shift + before.c * u(turn)))[ok] <= tol * size[ok] / s)
    for name in ("angle_i", "angle_j"):
        turned = wrap(getattr(after, name) - getattr(before, name) - turn)
        assert np.all(np.abs(turned[ok]) <= REL)
    for name in ("s_i", "s_j"):
        if getattr(before, name) is not None:
            diff = getattr(after, name) - getattr(before, name)
            assert np.all(np.abs(diff[ok]) <= tol * (1 + np.abs(getattr(before, name)[ok]) / s))
    np.testing.assert_allclose(after.margin[ok], before.margin[ok], atol=REL)


@pytest.mark.parametrize("kind", sorted(KINDS))
@given(data=st.data())
def test_vectorised_equals_scalar_loop(kind: str, data: st.DataObject) -> None:
    args, s = data.draw(configurations(kind))
    whole = KINDS[kind].solve(**args)
    for k in range(0, N, 7):
        one = KINDS[kind].solve(**{n: (v[k] if np.ndim(v) else v) for n, v in args.items()})
        assert bool(one.exists) == bool(whole.exists[k])
        assert int(one.reason) == int(whole.reason[k])
        if one.exists:
            assert abs(one.c - whole.c[k]) <= 1e-12 * (s + abs(whole.c[k]))
            for name in ("angle_i", "angle_j"):
                assert abs(wrap(getattr(one, name) - getattr(whole, name)[k])) <= 1e-12
            assert abs(one.margin - whole.margin[k]) <= 1e-12


def test_designs_times_angles_broadcast() -> None:
    lengths = np.array([[70.0], [80.0], [90.0]])  # 3 designs, shape (3, 1)
    pins = 30.0 * u(PHI)  # 48 angles, shape (48,)
    sol = solve_rrr(pins, 100.0 + 0j, lengths, 90.0, 1.0)
    assert sol.c.shape == sol.margin.shape == sol.exists.shape == sol.reason.shape == (3, N)
    for row in range(3):
        alone = solve_rrr(pins, 100.0 + 0j, float(lengths[row, 0]), 90.0, 1.0)
        np.testing.assert_allclose(sol.c[row], alone.c, rtol=1e-14)


def test_large_calls_in_blocks_equal_row_by_row_calls() -> None:
    # 40 designs x 500 angles is larger than two blocks of the plain-array kernel
    lengths = np.linspace(40.0, 90.0, 40)[:, None]  # the shortest couplers fail part of a turn
    pins = 30.0 * u(np.linspace(0.0, 2.0 * np.pi, 500))
    sol = solve_rrr(pins, 100.0 + 0j, lengths, 90.0, -1.0, delta=0.05)
    assert sol.exists.any() and not sol.exists.all()
    for row in range(40):
        alone = solve_rrr(pins, 100.0 + 0j, float(lengths[row, 0]), 90.0, -1.0, delta=0.05)
        np.testing.assert_array_equal(sol.reason[row], alone.reason)
        np.testing.assert_array_equal(sol.margin[row], alone.margin)
        np.testing.assert_array_equal(sol.c[row], alone.c)
        np.testing.assert_array_equal(sol.angle_j[row], alone.angle_j)


def mirror(p: np.ndarray, base: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Reflection of the point ``p`` in the line through ``base`` along ``direction``."""
    e = direction / np.abs(direction)
    return base + e * np.conj((p - base) / e)


@given(data=st.data())
def test_branches_mirror_each_other(data: st.DataObject) -> None:
    args, s = data.draw(configurations("RRR"))
    plus, minus = solve_rrr(**{**args, "sigma": 1.0}), solve_rrr(**{**args, "sigma": -1.0})
    np.testing.assert_array_equal(plus.exists, minus.exists)
    ok = plus.exists
    image = mirror(plus.c, args["h_i"], args["h_j"] - args["h_i"])  # about the line H_i H_j
    assert np.all(np.abs(image - minus.c)[ok] <= REL * s * 10)

    args, s = data.draw(configurations("RRP"))
    plus, minus = solve_rrp(**{**args, "sigma": 1.0}), solve_rrp(**{**args, "sigma": -1.0})
    ok = plus.exists
    normal = 1j * u(args["theta"])  # about the perpendicular from H_j to the path of C
    image = mirror(plus.c, args["h_j"], normal + 0.0 * args["h_j"])
    assert np.all(np.abs(image - minus.c)[ok] <= REL * s * 10)
    np.testing.assert_allclose(
        plus.s_i[ok] + minus.s_i[ok],
        2 * dot(u(args["theta"]), args["h_j"] - args["a"])[ok], atol=REL * s * 10)

    args, s = data.draw(configurations("RPR"))
    plus, minus = solve_rpr(**{**args, "sigma": 1.0}), solve_rpr(**{**args, "sigma": -1.0})
    ok = plus.exists
    image = mirror(plus.c, args["h_i"], args["h_j"] - args["h_i"])  # about the line H_i H_j
    assert np.all(np.abs(image - minus.c)[ok] <= REL * s * 10)
    np.testing.assert_allclose(minus.s_i[ok], -plus.s_i[ok], rtol=1e-12, atol=REL * s)
