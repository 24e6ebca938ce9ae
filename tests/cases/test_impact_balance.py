"""Impact case: the solved systems against from-scratch impulse balances.

Two independent checks, written here without the solver's matrices:

* the momentum and angular-momentum balance of every link, from the points' positions and
  the returned impulses;
* a generalised-coordinate solution: the mass matrix from the kinetic energy of the three
  links, the contact impulse through the Jacobian of the relative velocity at the pin, the
  restitution law on the exact normal velocity and f = μF. It gives the normal impulse as one
  scalar division and the velocities after impact from it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from synthesis.cases.impact.data import PAPER, ImpactData
from synthesis.cases.impact.energy import alpha_slip, energy_balance
from synthesis.cases.impact.models import ImpactResult, solve_paper, solve_townsend_mansour
from synthesis.cases.impact.position import ImpactPosition, impact_position


def _cross(a: complex, b: complex) -> float:
    return a.real * b.imag - a.imag * b.real


def _at(array: np.ndarray, index: tuple[int, ...]) -> float | complex:
    return array[index].item()


def _link_residuals(data: ImpactData, pos: ImpactPosition, res: ImpactResult,
                    index: tuple[int, ...]) -> list[float]:
    """Impulse-momentum residuals of each link, scaled by the largest impulse moment."""
    th2, th3, th4, psi = (_at(x, index) for x in (pos.theta2, pos.theta3, pos.theta4, pos.psi))
    w2, w3, w4 = (_at(x, index) for x in (pos.omega2, pos.omega3, pos.omega4))
    w2p, w3p, w4p = (_at(x, index) for x in (res.omega2, res.omega3, res.omega4))
    normal, friction = _at(res.normal, index), _at(res.friction, index)
    r_a, r_o2 = _at(res.r_a, index), _at(res.r_o2, index)
    drive = _at(res.drive, index)
    a = data.r2 * complex(math.cos(th2), math.sin(th2))
    u3 = complex(math.cos(th3), math.sin(th3))
    u_psi = complex(math.cos(psi), math.sin(psi))
    pin = a + data.r3 * u3
    g3 = a + data.r3 / 2 * u3
    contact = data.r1 + data.r4 * complex(math.cos(th4), math.sin(th4)) + data.clearance * u_psi
    on_pin = -normal * u_psi - friction * 1j * u_psi

    def v_g2(w: float) -> complex:
        return 1j * w * a / 2

    def v_g3(w_2: float, w_3: float) -> complex:
        return 1j * w_2 * a + 1j * w_3 * (g3 - a)

    scale = abs(normal) * data.r1
    crank_linear = data.m2 * (v_g2(w2p) - v_g2(w2)) - (r_o2 - r_a)
    crank_angular = data.inertia_o2 * (w2p - w2) - (_cross(a, -r_a) + drive)
    coupler_linear = data.m3 * (v_g3(w2p, w3p) - v_g3(w2, w3)) - (r_a + on_pin)
    coupler_angular = data.inertia3 * (w3p - w3) - (_cross(a - g3, r_a)
                                                    + _cross(pin - g3, on_pin))
    rocker_angular = (data.inertia4 + data.m4 * data.r4 ** 2 / 4) * (w4p - w4) \
        - _cross(contact - data.r1, -on_pin)
    return [abs(crank_linear) * data.r1 / scale, abs(crank_angular) / scale,
            abs(coupler_linear) * data.r1 / scale, abs(coupler_angular) / scale,
            abs(rocker_angular) / scale]


def _generalised(data: ImpactData, pos: ImpactPosition, index: tuple[int, ...], k: float,
                 mu: float, crank_held: bool) -> dict[str, float]:
    """The impact solved in generalised velocities (ω2, ω3, ω4) from scratch."""
    th2, th3, th4, psi = (_at(x, index) for x in (pos.theta2, pos.theta3, pos.theta4, pos.psi))
    q = np.array([_at(pos.omega2, index), _at(pos.omega3, index), _at(pos.omega4, index)])
    a = data.r2 * np.exp(1j * th2)
    u3, u4, u_psi = np.exp(1j * th3), np.exp(1j * th4), np.exp(1j * psi)
    # velocity Jacobians (complex) of the points with respect to (ω2, ω3, ω4)
    jac_g3 = np.array([1j * a, 1j * data.r3 / 2 * u3, 0])
    jac_pin = np.array([1j * a, 1j * data.r3 * u3, 0])
    jac_contact = np.array([0, 0, 1j * (data.r4 * u4 + data.clearance * u_psi)])
    spin = {2: np.array([1.0, 0, 0]), 3: np.array([0, 1.0, 0]), 4: np.array([0, 0, 1.0])}
    mass = (data.inertia_o2 * np.outer(spin[2], spin[2])
            + data.m3 * np.real(np.conj(jac_g3)[:, None] * jac_g3[None, :])
            + data.inertia3 * np.outer(spin[3], spin[3])
            + (data.inertia4 + data.m4 * data.r4 ** 2 / 4) * np.outer(spin[4], spin[4]))
    relative = jac_pin - jac_contact
    jac_n = np.real(np.conj(u_psi) * relative)
    jac_t = np.real(np.conj(1j * u_psi) * relative)
    free = slice(1, 3) if crank_held else slice(0, 3)
    v_n, v_t = jac_n @ q, jac_t @ q
    sign = 1.0 if v_t >= 0 else -1.0
    inverse = np.linalg.inv(mass[free, free])
    direction = jac_n[free] + mu * sign * jac_t[free]
    normal = (1 + k) * v_n / (jac_n[free] @ inverse @ direction)
    q_after = q.copy()
    q_after[free] = q[free] - inverse @ direction * normal
    return {"omega2": q_after[0], "omega3": q_after[1], "omega4": q_after[2],
            "normal": normal, "friction": mu * sign * normal,
            "approach_after": jac_n @ q_after, "approach_before": v_n}


def _compare(data: ImpactData, pos: ImpactPosition, k: float, mu: float) -> None:
    for crank_held, solve in ((False, solve_paper), (True, solve_townsend_mansour)):
        res = solve(data, pos, k=k, mu=mu, lever="exact")
        for index in np.ndindex(pos.shape):
            if not pos.exists[index]:
                continue
            ref = _generalised(data, pos, index, k, mu, crank_held)
            scale_w = abs(ref["omega2"]) + abs(ref["omega3"]) + abs(ref["omega4"])
            for name in ("omega2", "omega3", "omega4"):
                assert _at(getattr(res, name), index) == pytest.approx(ref[name],
                                                                      abs=1e-11 * scale_w)
            assert _at(res.normal, index) == pytest.approx(ref["normal"], rel=1e-10)
            assert _at(res.friction, index) == pytest.approx(ref["friction"], rel=1e-10, abs=1e-18)
            assert max(_link_residuals(data, pos, res, index)) < 1e-12


def test_paper_position_balances_to_machine_precision() -> None:
    pos = impact_position(PAPER)
    for solve in (solve_paper, solve_townsend_mansour):
        for lever in ("paper", "exact"):
            res = solve(PAPER, pos, lever=lever)
            for index in np.ndindex(pos.shape):
                assert max(_link_residuals(PAPER, pos, res, index)) < 1e-13


def test_paper_case_agrees_with_generalised_coordinates() -> None:
    _compare(PAPER, impact_position(PAPER), k=PAPER.k, mu=PAPER.mu)


@given(theta2=st.floats(0.0, 360.0), omega4=st.floats(-300.0, 300.0),
       k=st.floats(0.0, 1.0), mu=st.floats(0.0, 0.5), clearance_mm=st.floats(0.05, 2.0),
       sigma=st.sampled_from([1, -1]))
def test_other_positions_and_coefficients_agree_with_generalised_coordinates(
        theta2: float, omega4: float, k: float, mu: float, clearance_mm: float,
        sigma: int) -> None:
    data = PAPER.with_changes(clearance=clearance_mm * 1e-3, sigma=sigma)
    pos = impact_position(data, math.radians(theta2), omega4)
    _compare(data, pos, k=k, mu=mu)


def test_position_geometry() -> None:
    theta2 = np.radians(np.arange(0.0, 360.0, 15.0))
    for sigma in (1, -1):
        data = PAPER.with_changes(sigma=sigma)
        pos = impact_position(data, theta2, -30.0)
        assert pos.exists.all()  # a Grashof crank-rocker assembles at every crank angle
        assert np.allclose(np.abs(pos.pin - pos.a), data.r3, rtol=0, atol=1e-14)
        assert np.allclose(np.abs(pos.pin - data.r1), data.r4, rtol=0, atol=1e-14)
        assert np.allclose(np.abs(pos.bearing - data.r1), data.r4, rtol=0, atol=1e-14)
        assert np.allclose(np.abs(pos.pin - pos.bearing), data.clearance, rtol=0, atol=1e-14)
        side = np.sign(np.imag(np.conj(data.r1 - pos.a) * (pos.pin - pos.a)))
        assert (side == sigma).all()
        # rigid rates against central differences of a plain circle intersection
        step = 1e-6
        for name, value in (("theta3", pos.omega3), ("theta4", pos.omega4_rigid)):
            ahead = _closure(data, theta2 + step, sigma)[name]
            behind = _closure(data, theta2 - step, sigma)[name]
            rate = np.angle(np.exp(1j * (ahead - behind))) / (2 * step) * data.omega2
            assert np.allclose(value, rate, rtol=1e-6, atol=1e-6), name


def _closure(data: ImpactData, theta2: np.ndarray, sigma: int) -> dict[str, np.ndarray]:
    """Coupler and rocker angles by intersecting two circles (independent of assur)."""
    a = data.r2 * np.exp(1j * theta2)
    d = np.abs(data.r1 - a)
    along = (data.r3 ** 2 - data.r4 ** 2 + d ** 2) / (2 * d)
    height = np.sqrt(data.r3 ** 2 - along ** 2)
    unit = (data.r1 - a) / d
    pin = a + unit * (along + 1j * sigma * height)
    return {"theta3": np.angle(pin - a), "theta4": np.angle(pin - data.r1)}


def test_pin_moves_into_the_wall() -> None:
    theta2 = np.radians(np.arange(0.0, 360.0, 10.0))[:, None]
    pos = impact_position(PAPER, theta2, np.array([-200.0, 0.0, 250.0]))
    res = solve_paper(PAPER, pos, lever="exact")
    assert (res.approach_before[pos.exists] > 0).all()
    assert (res.normal[pos.exists] > 0).all()


def test_no_impact_when_the_rocker_moves_with_the_pin() -> None:
    rigid = impact_position(PAPER, omega4=0.0).omega4_rigid
    pos = impact_position(PAPER, omega4=rigid)
    assert not pos.exists and pos.reason == 2
    res = solve_paper(PAPER, pos)
    assert np.isnan(res.omega2) and np.isnan(res.normal)


def test_a_four_bar_that_does_not_assemble_is_reported() -> None:
    data = PAPER.with_changes(r2=0.09)  # |O4 A| = r1 + r2 = 190 mm > r3 + r4 at θ2 = 180°
    pos = impact_position(data, np.radians([0.0, 180.0]), -30.0)
    assert pos.exists.tolist() == [True, False]
    assert pos.reason.tolist() == [0, 1]
    res = solve_townsend_mansour(data, pos)
    assert np.isfinite(res.omega3[0]) and np.isnan(res.omega3[1])


def test_elastic_frictionless_energy_is_conserved_up_to_the_alpha_slip() -> None:
    pos = impact_position(PAPER)
    slip = alpha_slip(PAPER, pos)
    # α from (8) by hand: sin α = ξ sin(ψ − θ4)/ρ with ψ − θ4 ≈ 90°: α ≈ ξ/r4
    assert np.allclose(slip.alpha, PAPER.clearance / PAPER.r4, rtol=1e-3)
    # the printed lever is ρ cos α ≈ r4 (1 − ξ²/2r4²·…); the exact one r4 sin(ψ − θ4)
    assert np.all(np.abs(slip.lever_error) < 1e-4) and np.all(np.abs(slip.lever_error) > 1e-6)
    for model in ("P", "TM"):
        assert np.all(np.abs(slip.exact_energy_error[model]) < 1e-13)
        assert np.all(np.abs(slip.energy_error[model]) > 1e-6)
        assert np.all(np.abs(slip.energy_error[model]) < 1e-4)
        # the printed lever acts as a slightly wrong restitution coefficient
        assert np.allclose(slip.restitution[model], 1.0, atol=1e-4)
        assert np.all(slip.restitution[model] != 1.0)


def test_drive_work_closes_the_energy_balance_of_the_held_crank() -> None:
    pos = impact_position(PAPER)
    res = solve_townsend_mansour(PAPER, pos, k=1.0, mu=0.0, lever="exact")
    # drive work from the impulse at A, independently: the drive cancels the moment of −r_A
    moment = np.imag(np.conj(pos.a) * -res.r_a)
    balance = energy_balance(PAPER, pos, res)
    assert np.allclose(balance.drive_work, -pos.omega2 * moment, rtol=1e-12)
    assert np.allclose(balance.after - balance.before, balance.drive_work, rtol=1e-12)


@pytest.mark.parametrize("solve", [solve_paper, solve_townsend_mansour])
def test_limits_of_restitution_and_friction_are_physical(solve) -> None:  # type: ignore[no-untyped-def]
    theta2 = np.radians(np.arange(0.0, 360.0, 5.0))[:, None]
    pos = impact_position(PAPER, theta2, np.array([-200.0, -30.0, 0.0, 250.0]))
    plastic = solve(PAPER, pos, k=0.0, mu=0.0, lever="exact")
    # k = 0: the pin stays on the wall, the energy only falls
    assert np.allclose(plastic.approach_after[pos.exists], 0.0, atol=1e-12)
    assert (energy_balance(PAPER, pos, plastic).loss[pos.exists] > 0).all()
    for k in (0.0, 0.5, 1.0):
        for mu in (0.1, 0.3):
            res = solve(PAPER, pos, k=k, mu=mu, lever="exact")
            slipping = pos.exists & res.full_slip
            assert slipping.sum() > 10
            assert np.allclose(res.friction[slipping], mu * np.abs(res.normal[slipping])
                               * np.sign(res.slip_before[slipping]))
            loss = energy_balance(PAPER, pos, res).relative_loss[slipping]
            assert (loss > -1e-12).all()
            if k == 1.0:
                assert (loss > 0).all()  # friction dissipates
