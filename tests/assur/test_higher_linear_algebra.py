"""The small linear algebra and bookkeeping of the higher groups, against independent forms.

- ``cofactors``, ``det_rows`` and ``cramer`` (Cramer's rule for stacked 2×2 and 3×3 systems,
  on a few and on many positions) against ``numpy.linalg``;
- ``stack_last`` against ``np.stack`` of the broadcast arrays;
- a triad's ``assessed`` (residuals, Jacobian and margin rows from one evaluation of the
  constraint lines) against its generic ``residual`` and ``lines``, for every leash kind;
- the assembly modes sorted by the eliminated angle, each with the sign of det J and the
  Hadamard ratio computed here with ``numpy.linalg``;
- the grid of the path's columns against a brute-force distance to every requested angle;
- the path of the root (:func:`~assur.kinematics.higher.track.chains`): wherever a chain
  (forward or backward) links two columns, each root is the nearest real root of the other
  column, the real roots found here by numpy's polynomial roots;
- the poses recovered at roots a little off, corrected by Newton's method to the modes.
"""

from __future__ import annotations

import numpy as np
import pytest

from assur.kinematics.higher.continuation import _poses
from assur.kinematics.higher.groups import (
    Leash,
    Triad,
    TriadInputs,
    cofactors,
    det_rows,
    stack_last,
    values,
)
from assur.kinematics.higher.modes import assembly_modes, cramer
from assur.kinematics.higher.track import BASE, SAME, chains, grid
from assur.kinematics.jets import Jet

TWO_PI = 2.0 * np.pi
BASE_POINTS = (77.5 + 30.5j, 112 + 7.5j, 114 + 52j)
FRAME = (-17 - 0.5j, 81 + 31j, 150 + 80j)
BARS = (Leash.RR, Leash.RR, Leash.RR)


def _jittered(rng: np.random.Generator, designs: int, size: float) -> Triad:
    """The RRR triad with its base hinges moved by up to ``size`` (shape (D,))."""
    jitter = rng.uniform(-size, size, (3, designs)) + 1j * rng.uniform(-size, size, (3, designs))
    return Triad(BARS, (BASE_POINTS[0] + jitter[0], BASE_POINTS[1] + jitter[1],
                        BASE_POINTS[2] + jitter[2]), FRAME)


def _frame(designs: int) -> TriadInputs:
    """The external hinges as drawn, for D designs."""
    return TriadInputs((np.full(designs, FRAME[0]), np.full(designs, FRAME[1]),
                        np.full(designs, FRAME[2])))


@pytest.mark.parametrize("n", [2, 3])
@pytest.mark.parametrize("count", [1, 7, 3000])
def test_cramer_and_determinants_are_numpys(n: int, count: int) -> None:
    rng = np.random.default_rng(n * count)
    jac = rng.normal(size=(count, 2, n, n))
    rhs = rng.normal(size=(count, 2, n))
    cof, det = cofactors(jac)
    assert np.allclose(det, np.linalg.det(jac), rtol=1e-12, atol=1e-12)
    assert np.allclose(det_rows(jac), det, rtol=1e-12, atol=1e-12)
    assert np.allclose(cramer(cof, det, rhs), np.linalg.solve(jac, rhs[..., None])[..., 0],
                       rtol=1e-9, atol=1e-9)
    # a singular matrix gives NaN or inf, never an error
    jac[0, 0, 1] = 0.0
    assert not np.isfinite(cramer(*cofactors(jac), rhs)[0, 0]).all()


def test_stack_last_is_the_stack_of_the_broadcast_arrays() -> None:
    parts: list[np.ndarray] = [np.arange(6.0).reshape(2, 3), np.asarray(1j), np.arange(3)]
    assert np.array_equal(stack_last(parts), np.stack(np.broadcast_arrays(*parts), axis=-1))
    assert stack_last(parts).dtype == complex
    assert stack_last([np.zeros(2), np.ones(2)]).dtype == float


def _triads() -> list[tuple[Triad, TriadInputs]]:
    """Triads of every leash kind (bar first, a P–P leash last), inputs on 5 positions."""
    rng = np.random.default_rng(3)
    crank = FRAME[0] * np.exp(1j * rng.uniform(0, TWO_PI, 5))
    guide = np.exp(0.3j)
    out = []
    for names in ("RR RR RR", "RR RP RR", "RR PR RP", "RP PR RP", "RR RR PP"):
        kinds = [Leash(name) for name in names.split()]
        guides = [None if kind.bar else guide for kind in kinds]
        triad = Triad((kinds[0], kinds[1], kinds[2]), BASE_POINTS, FRAME,
                      (guides[0], guides[1], guides[2]))
        u = [guide * np.exp(0.1j * rng.normal(size=5)) if kind.slides[1] else None
             for kind in kinds]
        out.append((triad, TriadInputs((crank, FRAME[1], FRAME[2]), (u[0], u[1], u[2]))))
    return out


@pytest.mark.parametrize("index", range(5))
def test_a_triads_assessment_is_its_residuals_and_lines(index: int) -> None:
    triad, k = _triads()[index]
    rng = np.random.default_rng(index)
    x = triad.drawn() + rng.normal(scale=[5.0, 5.0, 0.2], size=(5, 3))
    f, jac, rows = triad.assessed(x, k)
    residual = np.stack(np.broadcast_arrays(*(np.asarray(v) for v in triad.residual(x, k))),
                        axis=-1)
    lines = triad.lines(x, k)
    assert np.allclose(f, residual, rtol=1e-12, atol=1e-9)
    assert np.allclose(jac, lines[0], rtol=1e-12, atol=1e-12)
    assert np.allclose(rows, lines[1], rtol=1e-12, atol=1e-12)


def test_the_modes_are_sorted_with_their_signs_and_margins() -> None:
    triad = _jittered(np.random.default_rng(11), 40, 3.0)
    modes = assembly_modes(triad, _frame(40))
    assert (modes.count >= 2).all()
    for d in range(40):
        c = int(modes.count[d])
        x = modes.x[d, :c]
        assert np.isnan(modes.x[d, c:]).all() and np.isnan(modes.margin[d, c:]).all()
        assert (np.diff(x[:, triad.eliminated]) > 0).all()
        base = [np.asarray(b)[d] for b in triad.base]
        one = Triad(BARS, (base[0], base[1], base[2]), FRAME)
        jac, rows = one.lines(x, TriadInputs(FRAME))
        assert np.array_equal(modes.det_sign[d, :c], np.sign(np.linalg.det(jac)))
        hadamard = np.abs(np.linalg.det(rows)) / np.linalg.norm(rows, axis=-1).prod(axis=-1)
        assert np.allclose(modes.margin[d, :c], hadamard, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("seed", range(6))
def test_the_grid_leaves_out_the_uniform_columns_at_requested_angles(seed: int) -> None:
    rng = np.random.default_rng(seed)
    uniform = TWO_PI / BASE * np.arange(BASE)
    wanted = np.concatenate([rng.uniform(0, TWO_PI, 30), uniform[rng.integers(0, BASE, 5)],
                             uniform[rng.integers(0, BASE, 3)] + 1e-12,
                             uniform[rng.integers(1, BASE, 3)] - 1e-12])
    columns = grid(np.mod(wanted, TWO_PI))
    expected = set(np.mod(wanted, TWO_PI)) | {0.0}
    expected |= {u for u in uniform if np.min(np.abs(u - np.array(sorted(expected)))) > SAME}
    assert np.array_equal(columns, np.array(sorted(expected)))


def test_the_chains_link_mutually_nearest_roots() -> None:
    designs = 6
    triad = _jittered(np.random.default_rng(5), designs, 2.0)
    columns = grid(np.radians(np.arange(0.0, 360.0, 3.0)))
    phi = np.append(columns, TWO_PI)[:, None]
    k = TriadInputs((np.broadcast_to(FRAME[0] * np.exp(1j * phi), (phi.size, designs)),
                     FRAME[1], FRAME[2]))
    modes = assembly_modes(triad, _frame(designs))
    theta0 = modes.x[:, 0, triad.eliminated]
    paths = chains(triad, k, columns, theta0, np.ones(designs, dtype=bool))
    coef = triad.coefficients(k)
    checked = 0
    for d in range(designs):
        real = []
        for c in range(phi.size):
            every = np.roots(coef[c, d, ::-1])
            real.append(np.angle(every[np.abs(np.abs(every) - 1.0) < 1e-6]))
        for c in range(phi.size - 1):
            if not ((paths.forward[c, d] and paths.forward[c + 1, d])
                    or (paths.backward[c, d] and paths.backward[c + 1, d])):
                continue
            here, there = paths.theta[c, d], paths.theta[c + 1, d]

            def nearest(t: float, roots: np.ndarray) -> float:
                return float(roots[np.argmin(np.abs(np.angle(np.exp(1j * (roots - t)))))])

            assert abs(np.angle(np.exp(1j * (nearest(here, real[c + 1]) - there)))) < 1e-8
            assert abs(np.angle(np.exp(1j * (nearest(there, real[c]) - here)))) < 1e-8
            checked += 1
    assert checked > designs * (phi.size - 1) // 3


def test_poses_recovered_from_roots_a_little_off_are_corrected_to_roundoff() -> None:
    """:func:`_poses` from roots of the eliminant 1e-6 rad off: the recovered poses miss the
    equations by up to about 1e-7·L, the Newton iterations bring them to roundoff; the sketch's
    modes pass, the other modes are told apart by the sign of det J."""
    designs = 30
    triad = _jittered(np.random.default_rng(8), designs, 3.0)
    modes = assembly_modes(triad, _frame(designs))
    # the first two modes of each design, shape (2, D) as the path's columns
    theta = modes.x[:, :2, triad.eliminated].T + 1e-6
    k = TriadInputs(tuple(Jet(np.asarray(a), 0.0, 0.0)  # type: ignore[arg-type]
                          for a in _frame(designs).a))
    sign = modes.det_sign[:, 0]
    x, x1, x2, _, posed = _poses(triad, k, theta, sign)
    size = float(np.max(triad.size))
    off = np.abs(triad.residuals(triad.recover(np.exp(1j * theta), values(k)), values(k)))
    assert off.max() > 1e-8 * size
    assert np.abs(triad.residuals(x, values(k))).max() < 1e-11 * size
    assert np.allclose(x, modes.x[:, :2].transpose(1, 0, 2), rtol=0.0, atol=1e-9 * size)
    assert np.array_equal(posed, modes.det_sign[:, :2].T == sign)
    assert np.all(x1 == 0.0) and np.all(x2 == 0.0)  # the inputs do not move
