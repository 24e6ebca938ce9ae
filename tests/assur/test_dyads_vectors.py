"""The group solvers against the test vectors of method.md §2.9 (computed independently)."""

from __future__ import annotations

import numpy as np
import pytest

from assur.kinematics.dyads import solve_input, solve_prp, solve_rpp
from assur.kinematics.dyads import solve_rpr, solve_rrp, solve_rrr

DEG = np.pi / 180.0
TOL = 5e-5  # the table quotes 4 decimals


def close(actual: object, expected: float) -> None:
    assert np.asarray(actual) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize(("sigma", "c", "phi_i", "phi_j"), [
    (+1, 64 + 48j, 36.8699, 126.8699),
    (-1, 64 - 48j, -36.8699, -126.8699),
])
def test_rrr_vector(sigma: int, c: complex, phi_i: float, phi_j: float) -> None:
    sol = solve_rrr(0j, 100 + 0j, 80.0, 60.0, sigma)
    close(sol.c.real, c.real)
    close(sol.c.imag, c.imag)
    close(sol.angle_i / DEG, phi_i)
    close(sol.angle_j / DEG, phi_j)
    assert sol.exists and sol.reason == 0
    # transmission angle: alpha_C = arccos|sin(phi_i - phi_j)| = 0 in this right triangle
    close(np.arccos(np.abs(np.sin(sol.angle_i - sol.angle_j))) / DEG, 0.0)


@pytest.mark.parametrize(("sigma", "s", "phi_j"), [(+1, 86.6025, -30.0), (-1, -86.6025, -150.0)])
def test_rrp_vector(sigma: int, s: float, phi_j: float) -> None:
    sol = solve_rrp(50j, 0j, 0.0, 0.0, 100.0, sigma)
    close(sol.s_i, s)
    close(sol.c.real, s)
    close(sol.c.imag, 0.0)
    close(sol.angle_j / DEG, phi_j)
    # pressure angle alpha_C = arcsin(|h|/l_j) = 30 deg, with |h|/l_j = 1 - margin
    close(np.arcsin(1.0 - sol.margin) / DEG, 30.0)


@pytest.mark.parametrize(("sigma", "phi_i", "t"), [
    (+1, -11.5370, 97.9796),
    (-1, -168.4630, -97.9796),
    (0, -11.5370, 97.9796),  # table 1.6 writes 0 for L3: the default branch T > 0
])
def test_rpr_vector(sigma: int, phi_i: float, t: float) -> None:
    sol = solve_rpr(0j, 100 + 0j, 20.0, sigma)
    close(sol.angle_i / DEG, phi_i)
    close(sol.angle_j / DEG, phi_i)
    close(sol.s_i, t)


def test_prp_vector() -> None:
    sol = solve_prp(0j, 30 * DEG, 0.0, 100 + 0j, 90 * DEG, 0.0)
    close(sol.c.real, 100.0)
    close(sol.c.imag, 57.7350)
    close(sol.s_i, 115.4701)
    close(sol.s_j, 57.7350)


def test_rpp_vector() -> None:
    # theta_T = 90 deg with theta_S = 0 means gamma = 90 deg
    sol = solve_rpp(20 + 50j, 90 * DEG, 0j, 0.0, 0.0)
    close(sol.c.real, 20.0)
    close(sol.c.imag, 0.0)
    close(sol.s_j, -50.0)
    close(sol.s_i, 20.0)
    close(sol.angle_j / DEG, 90.0)


def test_input_vector() -> None:
    sol = solve_input(1 + 2j, 10.0, 90 * DEG)
    close(sol.c.real, 1.0)
    close(sol.c.imag, 12.0)
    assert sol.exists and sol.margin == 1.0
