"""Velocity and acceleration analogs from jets against numerical derivatives.

Every group is driven by the crank angle φ through its inputs (a crank pin, a guide turning
with φ, ...). The jet outputs (first and second derivatives w.r.t. φ) are compared with
central differences of plain-array solves, and, for the four-bar and the slider-crank, with
complex-step derivatives of textbook closed forms in real arithmetic (the Freudenstein
equation and the slider displacement formula), which share no code with the solvers.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from assur.kinematics import jets as J
from assur.kinematics.dyads import (
    DyadSolution,
    solve_input,
    solve_prp,
    solve_rpp,
    solve_rpr,
    solve_rrp,
    solve_rrr,
)
from assur.kinematics.jets import Jet

PHI = np.linspace(0.0, 2.0 * np.pi, 25)
H1, H2 = 1e-5, 1e-4
HC = 1e-30


def pin(phi: Jet | np.ndarray, radius: float = 30.0, centre: complex = 0j) -> Jet | np.ndarray:
    return solve_input(centre, radius, phi).c


def swing(phi: Jet | np.ndarray, mean: float, amplitude: float = 0.3) -> Jet | np.ndarray:
    """A guide direction turning with the crank: θ(φ) = mean + amplitude·sin φ."""
    if isinstance(phi, Jet):
        return Jet(mean + amplitude * np.sin(phi.v), amplitude * np.cos(phi.v),
                   -amplitude * np.sin(phi.v))
    return mean + amplitude * np.sin(phi)


MECHANISMS: dict[str, Callable[[Jet | np.ndarray], DyadSolution]] = {
    "RRR four-bar": lambda phi: solve_rrr(pin(phi), 100 + 0j, 80.0, 90.0, 1.0),
    "RRR, pivot on a crank": lambda phi: solve_rrr(40j, pin(phi, 25.0, 110 + 5j), 95.0, 60.0, -1.0),
    "RRP offset slider": lambda phi: solve_rrp(pin(phi), 5 + 0j, 0.1, 8.0, 90.0, 1.0),
    "RRP on a turning guide": lambda phi: solve_rrp(pin(phi), 20j, swing(phi, 0.3), -4.0, 80.0, -1),
    "RPR kulisa": lambda phi: solve_rpr(60j, pin(phi), 6.0, 1.0),
    "RPR kulisa, other branch": lambda phi: solve_rpr(60j, pin(phi), -6.0, -1.0),
    "PRP": lambda phi: solve_prp(pin(phi), swing(phi, 0.4), 3.0, 100 + 0j, 1.9, -2.0),
    "RPP": lambda phi: solve_rpp(pin(phi, 20.0, 50j), 1.2, 10 + 0j, swing(phi, -0.2), 4.0),
}

OUTPUTS = ("c", "angle_i", "angle_j", "s_i", "s_j")


def numeric(mech: Callable, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Central differences of one output over the crank angle (angles unwrapped)."""
    def f(phi: np.ndarray) -> np.ndarray:
        return getattr(mech(phi), name)

    base = f(PHI)
    if name.startswith("angle"):
        def g(phi: np.ndarray) -> np.ndarray:  # continuous near PHI: unwrap against the base
            return base + np.angle(np.exp(1j * (f(phi) - base)))
    else:
        g = f
    d1 = (g(PHI + H1) - g(PHI - H1)) / (2 * H1)
    d2 = (g(PHI + H2) - 2 * g(PHI) + g(PHI - H2)) / (H2 * H2)
    return d1, d2


@pytest.mark.parametrize("mechanism", sorted(MECHANISMS))
def test_analogs_against_central_differences(mechanism: str) -> None:
    mech = MECHANISMS[mechanism]
    sol = mech(Jet(PHI, 1.0, 0.0))
    plain = mech(PHI)
    assert plain.exists.all()
    for name in OUTPUTS:
        jet = getattr(sol, name)
        if jet is None:
            continue
        value = getattr(plain, name)
        np.testing.assert_allclose(J.value(jet), value, rtol=1e-12, atol=1e-12)
        d1, d2 = numeric(mech, name)
        scale = 1.0 + np.max(np.abs(d1))
        np.testing.assert_allclose(np.broadcast_to(jet.d1, d1.shape), d1, atol=1e-7 * scale,
                                   err_msg=f"{mechanism} {name}'")
        scale = 1.0 + np.max(np.abs(d2))
        np.testing.assert_allclose(np.broadcast_to(jet.d2, d2.shape), d2, atol=1e-5 * scale,
                                   err_msg=f"{mechanism} {name}''")


def complex_step(f: Callable[[np.ndarray], np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    def cs(phi: np.ndarray) -> np.ndarray:
        return np.imag(f(phi + 1j * HC)) / HC
    return cs(PHI), (cs(PHI + H2) - cs(PHI - H2)) / (2 * H2)


def freudenstein_rocker_angle(phi: np.ndarray, branch: float) -> np.ndarray:
    """Rocker angle ψ(φ) of the four-bar O₁ = 0, O₂ = a, crank b, coupler c, rocker d.

    From |a + d·u(ψ) − b·u(φ)|² = c²:  P cos ψ + Q sin ψ = R, solved as
    ψ = atan(Q/P) + branch·arccos(R/√(P² + Q²)) (P > 0 here), analytic in φ.
    """
    a, b, c, d = 100.0, 30.0, 80.0, 90.0
    p = 2 * a * d - 2 * b * d * np.cos(phi)
    q = -2 * b * d * np.sin(phi)
    r = c * c - a * a - b * b - d * d + 2 * a * b * np.cos(phi)
    return np.arctan(q / p) + branch * np.arccos(r / np.sqrt(p * p + q * q))


def test_four_bar_analogs_against_complex_step_of_freudenstein() -> None:
    sol = solve_rrr(pin(Jet(PHI, 1.0, 0.0)), 100 + 0j, 80.0, 90.0, 1.0)
    # pick the closed-form branch that is the solver's assembly (C left of A -> O₂)
    branch = min((1.0, -1.0), key=lambda b: np.max(np.abs(
        np.angle(np.exp(1j * (freudenstein_rocker_angle(PHI, b) - sol.angle_j.v))))))

    def psi(phi: np.ndarray) -> np.ndarray:
        return freudenstein_rocker_angle(phi, branch)

    np.testing.assert_allclose(np.angle(np.exp(1j * (psi(PHI) - sol.angle_j.v))), 0, atol=1e-12)
    d1, d2 = complex_step(psi)
    np.testing.assert_allclose(sol.angle_j.d1, d1, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(sol.angle_j.d2, d2, rtol=1e-6, atol=1e-8)
    # coupler joint C = O₂ + d·u(ψ): both coordinates are analytic in φ
    coordinates = {
        "x": (J.real(sol.c), lambda phi: 100.0 + 90.0 * np.cos(psi(phi))),
        "y": (J.imag(sol.c), lambda phi: 90.0 * np.sin(psi(phi))),
    }
    for jet, formula in coordinates.values():
        d1, d2 = complex_step(formula)
        np.testing.assert_allclose(jet.d1, d1, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(jet.d2, d2, rtol=1e-6, atol=1e-6)


def test_slider_crank_analogs_against_complex_step() -> None:
    """Offset slider-crank: S(φ) = b cos φ + √(l² − (b sin φ − e)²) on the x-axis guide."""
    b, length, e = 30.0, 90.0, 8.0
    sol = solve_rrp(pin(Jet(PHI, 1.0, 0.0), b), 0j, 0.0, e, length, 1.0)

    def stroke(phi: np.ndarray) -> np.ndarray:
        return b * np.cos(phi) + np.sqrt(length**2 - (b * np.sin(phi) - e) ** 2)

    np.testing.assert_allclose(sol.s_i.v, stroke(PHI), rtol=1e-13)
    d1, d2 = complex_step(stroke)
    np.testing.assert_allclose(sol.s_i.d1, d1, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(sol.s_i.d2, d2, rtol=1e-6, atol=1e-6)


def test_blanked_positions_have_no_analogs() -> None:
    sol = solve_rrr(pin(Jet(PHI, 1.0, 0.0)), 100 + 0j, 50.0, 30.0, 1.0)  # fails part of a turn
    bad = ~sol.exists
    assert bad.any() and sol.exists.any()
    for part in (sol.c.v, sol.c.d1, sol.c.d2, sol.angle_j.d2):
        assert np.all(np.isnan(np.broadcast_to(part, bad.shape)[bad]))
        assert np.all(np.isfinite(np.broadcast_to(part, bad.shape)[~bad]))
