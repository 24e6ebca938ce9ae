"""Second-order jets against central differences and complex-step derivatives.

Each function is fed a jet ``x(t)`` whose value and derivatives are known in closed form, and
the result is compared with derivatives of ``f(x(t))`` obtained numerically: central
differences of plain numpy evaluations, and the complex step ``Im f(t + i·h)/h`` on analytic
real formulas written independently of the jet code (second derivatives: central differences
of complex-step first derivatives).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from assur.kinematics import jets as J
from assur.kinematics.jets import Jet

T = np.linspace(-1.2, 1.3, 11)  # parameter values (the "crank angle")
H1, H2 = 1e-5, 1e-4  # central-difference steps for first and second derivatives
HC = 1e-30  # complex step


def path(t: np.ndarray | complex) -> np.ndarray:
    """A smooth real input x(t) = 0.35 + 0.3·sin(t) + 0.1·t², inside (−1, 1) for arccos."""
    return 0.35 + 0.3 * np.sin(t) + 0.1 * t * t


def path_jet(t: np.ndarray) -> Jet:
    return Jet(path(t), 0.3 * np.cos(t) + 0.2 * t, -0.3 * np.sin(t) + 0.2)


def central(f: Callable[[np.ndarray], np.ndarray], t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivatives of f at t by central differences."""
    d1 = (f(t + H1) - f(t - H1)) / (2 * H1)
    d2 = (f(t + H2) - 2 * f(t) + f(t - H2)) / (H2 * H2)
    return d1, d2


def complex_step(f: Callable[[np.ndarray], np.ndarray], t: np.ndarray) -> tuple[np.ndarray, ...]:
    """First derivative by complex step; second by central differences of the complex step."""
    def cs(s: np.ndarray) -> np.ndarray:
        return np.imag(f(s + 1j * HC)) / HC
    return cs(t), (cs(t + H2) - cs(t - H2)) / (2 * H2)


def check_against_central(jet: Jet, f: Callable[[np.ndarray], np.ndarray]) -> None:
    d1, d2 = central(f, T)
    np.testing.assert_allclose(jet.v, f(T), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(jet.d1, d1, rtol=1e-7, atol=1e-8)
    np.testing.assert_allclose(jet.d2, d2, rtol=1e-5, atol=1e-5)


def check_against_complex_step(jet: Jet, f: Callable[[np.ndarray], np.ndarray]) -> None:
    d1, d2 = complex_step(f, T)
    np.testing.assert_allclose(jet.d1, d1, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(jet.d2, d2, rtol=1e-7, atol=1e-8)


# --- real functions: both central differences and complex step -------------------------------

REAL_CASES = {
    # name: (jet function of t, analytic formula of t valid for complex t)
    "sqrt": (lambda t: J.sqrt(path_jet(t)), lambda t: np.sqrt(path(t))),
    "arccos": (lambda t: J.arccos(path_jet(t)), lambda t: np.arccos(path(t))),
    "arctan2": (
        lambda t: J.arctan2(path_jet(t), 2.0 - path_jet(t) * path_jet(t)),
        lambda t: np.arctan(path(t) / (2.0 - path(t) ** 2)),  # x > 0: no quadrant offset
    ),
    "arctan2 of jet and array": (
        lambda t: J.arctan2(-0.7 * np.ones_like(t), path_jet(t) - 1.0),
        lambda t: np.arctan(-0.7 / (path(t) - 1.0)) - np.pi,  # third quadrant: x < 0, y < 0
    ),
    "product and quotient": (
        lambda t: (3.0 * path_jet(t) * path_jet(t) - 1.0) / (path_jet(t) + 2.0),
        lambda t: (3.0 * path(t) ** 2 - 1.0) / (path(t) + 2.0),
    ),
    "number divided by jet": (lambda t: 2.0 / path_jet(t), lambda t: 2.0 / path(t)),
    "array minus jet": (lambda t: np.linspace(1.0, 2.0, t.size) - path_jet(t), None),
    "abs": (lambda t: J.abs(path_jet(t) - 0.4), None),
    "real part of expi": (lambda t: J.real(J.expi(path_jet(t))), lambda t: np.cos(path(t))),
    "imag part of expi": (lambda t: J.imag(J.expi(path_jet(t))), lambda t: np.sin(path(t))),
}


@pytest.mark.parametrize("name", sorted(REAL_CASES))
def test_real_function_against_central_differences(name: str) -> None:
    jet_fn, analytic = REAL_CASES[name]
    reference = analytic if analytic is not None else plain_formula(name)
    check_against_central(jet_fn(T), lambda t: np.real(reference(t)))


@pytest.mark.parametrize("name", sorted(n for n, (_, f) in REAL_CASES.items() if f is not None))
def test_real_function_against_complex_step(name: str) -> None:
    jet_fn, analytic = REAL_CASES[name]
    check_against_complex_step(jet_fn(T), analytic)


def plain_formula(name: str) -> Callable[[np.ndarray], np.ndarray]:
    """Formulas for the cases that have no analytic continuation (abs, mixed array)."""
    return {
        "array minus jet": lambda t: np.linspace(1.0, 2.0, t.size) - path(t),
        "abs": lambda t: np.abs(path(t) - 0.4),
    }[name]


# --- complex-valued functions: central differences ---------------------------------------------

def point(t: np.ndarray) -> np.ndarray:
    """A moving point z(t) = (1.5 + 0.4 cos 2t) + j(0.8 sin t − 0.3)."""
    return (1.5 + 0.4 * np.cos(2 * t)) + 1j * (0.8 * np.sin(t) - 0.3)


def point_jet(t: np.ndarray) -> Jet:
    return Jet(point(t), -0.8 * np.sin(2 * t) + 0.8j * np.cos(t),
               -1.6 * np.cos(2 * t) - 0.8j * np.sin(t))


COMPLEX_CASES = {
    "expi": (lambda z: J.expi(J.real(z)), lambda z: np.exp(1j * z.real)),
    "arg": (J.arg, np.angle),
    "modulus": (J.abs, np.abs),
    "conj times z": (lambda z: J.conj(z) * (z - 0.5j), lambda z: np.conj(z) * (z - 0.5j)),
    "cross": (lambda z: J.cross(z, J.expi(J.imag(z))),
              lambda z: (np.conj(z) * np.exp(1j * z.imag)).imag),
    "dot": (lambda z: J.dot(z * 2.0, 1j - z), lambda z: (np.conj(z * 2.0) * (1j - z)).real),
    "quotient": (lambda z: (z + 1.0) / (z * z), lambda z: (z + 1.0) / (z * z)),
    "sqrt": (J.sqrt, np.sqrt),
}


@pytest.mark.parametrize("name", sorted(COMPLEX_CASES))
def test_complex_function_against_central_differences(name: str) -> None:
    jet_fn, plain_fn = COMPLEX_CASES[name]
    check_against_central(jet_fn(point_jet(T)), lambda t: plain_fn(point(t)))


@pytest.mark.parametrize("name", sorted(COMPLEX_CASES))
def test_plain_arrays_take_the_plain_path(name: str) -> None:
    jet_fn, plain_fn = COMPLEX_CASES[name]
    out = jet_fn(point(T))
    assert not isinstance(out, Jet)
    np.testing.assert_allclose(out, plain_fn(point(T)), rtol=1e-15, atol=1e-15)


def test_arithmetic_with_numbers_and_arrays_on_either_side() -> None:
    x = path_jet(T)
    a = np.linspace(1.0, 2.0, T.size)
    forms = [
        (a + x, a + path(T)), (x + a, path(T) + a), (a - x, a - path(T)), (x - 2.0, path(T) - 2.0),
        (a * x, a * path(T)), (x * 3j, path(T) * 3j), (a / x, a / path(T)), (x / a, path(T) / a),
        (-x, -path(T)), (2.0 - x, 2.0 - path(T)),
    ]
    for jet, values in forms:
        assert isinstance(jet, Jet)
        np.testing.assert_allclose(jet.v, values, rtol=1e-15)
    # the derivative of a·x(t) is a·x'(t); of a/x it is −a·x'/x²
    np.testing.assert_allclose((a * x).d1, a * x.d1, rtol=1e-15)
    np.testing.assert_allclose((a / x).d1, -a * x.d1 / x.v**2, rtol=1e-14)


def test_broadcasting_and_indexing() -> None:
    designs = Jet(np.array([[1.0], [2.0], [3.0]]), 1.0, 0.0)  # shape (3, 1)
    angles = J.expi(Jet(np.linspace(0, 1, 4), 1.0, 0.0))  # shape (4,)
    product = designs * angles
    assert product.shape == (3, 4)
    row = product[1]
    np.testing.assert_allclose(row.v, 2.0 * np.exp(1j * np.linspace(0, 1, 4)))
    # d/dt [t·e^{it}] = e^{it} + i·t·e^{it}: the jet keeps the independent broadcasting
    np.testing.assert_allclose(row.d1, (1 + 2j) * np.exp(1j * np.linspace(0, 1, 4)))


def test_where_follows_the_condition_in_every_part() -> None:
    x = path_jet(T)
    mask = T > 0
    chosen = J.where(mask, x, np.nan)
    assert np.all(np.isnan(chosen.v[~mask])) and np.all(np.isnan(chosen.d2[~mask]))
    np.testing.assert_array_equal(chosen.d1[mask], x.d1[mask])


def test_value_of_plain_and_jet() -> None:
    a = np.arange(3.0)
    assert J.value(a) is a
    assert J.value(Jet(a, 1.0)) is not None and np.array_equal(J.value(Jet(a, 1.0)), a)


@pytest.mark.parametrize("size", [J.TANGENT_FROM - 1, J.TANGENT_FROM, 50_000])
def test_unit_vectors_are_the_correctly_rounded_cosine_and_sine_to_two_eps(size: int) -> None:
    """Both forms of ``expi`` (a cosine and a sine; the tangent of the half angle) against
    ``math.cos``/``math.sin`` angle by angle: angles of every size, the multiples of π/2 and
    π and their neighbours (the tangent's poles and zeros), and angles far out."""
    rng = np.random.default_rng(size)
    special = np.arange(-16, 17) * (np.pi / 4)  # ±4π in steps of π/4
    special = np.concatenate([special, np.nextafter(special, np.inf),
                              np.nextafter(special, -np.inf), [0.0, -0.0, 1e-300, 5e-324]])
    scales = rng.choice([1e-8, 1.0, 10.0, 1e3, 1e6, 1e15], size)
    t = np.resize(np.concatenate([special, rng.uniform(-1.0, 1.0, size) * scales]), size)
    u = J.expi(t)
    assert isinstance(u, np.ndarray) and u.shape == (size,)
    cos = np.array([math.cos(x) for x in t.tolist()])
    sin = np.array([math.sin(x) for x in t.tolist()])
    eps = np.finfo(float).eps
    assert np.max(np.abs(u.real - cos)) <= 2 * eps
    assert np.max(np.abs(u.imag - sin)) <= 2 * eps
    small = (np.abs(t) < 1e-3) & (np.abs(t) >= np.finfo(float).tiny)  # sin t ≈ t: the sine
    # keeps its relative accuracy there (not for subnormal t, whose half may round to 0)
    assert np.all(np.abs(u.imag - sin)[small] <= 2 * eps * np.abs(sin[small]))
    assert np.all(np.isnan(J.expi(np.full(size, np.nan))))
