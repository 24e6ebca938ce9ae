"""The closed-form coefficients of the triad's eliminant against an FFT of Φ written here.

``Triad.coefficients`` builds p(E) = E^m·Φ from each leash's line as a polynomial in E. Here
Φ is evaluated from the geometry at 2m + 2 base rotations, by the definitions of
``docs/higher_groups.md`` §2 and §2.2 of the note (with a bar: W from the other two leashes'
lines by ``numpy.linalg.solve``, Φ = (|W|² − r₁²)·det²; without one, the 3×3 determinant of
the rows [a_k, p_k]; with a P–P leash, the second leash's equation on the first one's circle,
or L·sin(θ − θ_K)), and its coefficients are read off numpy's FFT. Every form of leashes, many
random designs and positions at once; inputs that are not finite give a NaN row, never an
error or a warning.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import pytest

from assur.kinematics.higher import Triad, TriadInputs

BLOCKS = ("RP", "PR")
FORMS = ([("RR", *rest) for rest in itertools.product(("RR", "RP", "PR"), repeat=2)]
         + [tuple(kinds) for kinds in itertools.product(BLOCKS, repeat=3)]
         + [("RR", second, "PP") for second in ("RR", "RP", "PR")]
         + [(*kinds, "PP") for kinds in itertools.product(BLOCKS, repeat=2)])


def _unit(rng: np.random.Generator, shape: tuple[int, ...]) -> np.ndarray:
    return np.asarray(np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, shape)))


def _points(rng: np.random.Generator, shape: tuple[int, ...]) -> np.ndarray:
    return rng.normal(0.0, 60.0, shape) + 1j * rng.normal(0.0, 60.0, shape)


@dataclass
class Case:
    """D random designs of one form of leashes and their inputs at U positions (U, D)."""

    kinds: tuple[str, ...]
    base: np.ndarray      # (3, D)
    external: np.ndarray  # (3, D)
    guide: np.ndarray     # (3, D): drawn unit guides (unused for a bar)
    a: np.ndarray         # (3, U, D)
    u: np.ndarray         # (3, U, D)

    def triad(self) -> Triad:
        guide = tuple(None if kind == "RR" else self.guide[i]
                      for i, kind in enumerate(self.kinds))
        return Triad(self.kinds, tuple(self.base), tuple(self.external), guide)  # type: ignore[arg-type]

    def inputs(self) -> TriadInputs:
        u = tuple(self.u[i] if kind in ("RP", "PP") else None
                  for i, kind in enumerate(self.kinds))
        return TriadInputs(tuple(self.a), u)  # type: ignore[arg-type]


def _case(kinds: tuple[str, ...], seed: int, designs: int = 40, positions: int = 5) -> Case:
    rng = np.random.default_rng(seed)
    return Case(kinds, _points(rng, (3, designs)), _points(rng, (3, designs)),
                _unit(rng, (3, designs)), _points(rng, (3, positions, designs)),
                _unit(rng, (3, positions, designs)))


def _line(case: Case, i: int, e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Leash i's line a·W = p in W = P₁ − A₁ at the base rotation e (complex a, real p)."""
    offset = (case.base[i] - case.base[0]) * e
    a1, ai = case.a[0], case.a[i]
    kind = case.kinds[i]
    if kind == "RR":  # |W + v|² = r_i² minus |W|² = r₁², halved
        v = a1 + offset - ai
        r1, ri = (np.abs(case.base[j] - case.external[j]) for j in (0, i))
        return v, (ri ** 2 - r1 ** 2 - np.abs(v) ** 2) / 2.0
    # P_i = A₁ + W + offset on the known link's guide (R–P), or A_i on the base's (P–R)
    normal = 1j * (case.u[i] if kind == "RP" else case.guide[i] * e)
    p = (np.conj(normal) * (ai - a1 - offset)).real
    return np.broadcast_to(normal, p.shape), p


def _real(z: np.ndarray) -> np.ndarray:
    return np.stack([z.real, z.imag], axis=-1)


def _phi(case: Case, theta: float) -> np.ndarray:
    """Φ at the base rotation θ (bar forms) or the first leash's rotation ψ (bar and P–P)."""
    e = np.exp(1j * theta)
    kinds = case.kinds
    size = np.abs(np.concatenate([case.base, case.external])[:, None]
                  - np.concatenate([case.base, case.external])[None]).max(axis=(0, 1))
    if kinds[2] == "PP":
        turn = case.u[2] / case.guide[2]
        if kinds[0] != "RR":
            return np.asarray(size * np.sin(theta - np.angle(turn)))
        w0 = case.base[0] - case.external[0]
        p2 = case.a[0] + np.abs(w0) * w0 / np.abs(w0) * e + (case.base[1] - case.base[0]) * turn
        if kinds[1] == "RR":
            r2 = np.abs(case.base[1] - case.external[1])
            return np.asarray((np.abs(p2 - case.a[1]) ** 2 - r2 ** 2) / (2.0 * r2))
        normal = 1j * (case.u[1] if kinds[1] == "RP" else case.guide[1] * turn)
        return np.asarray((np.conj(normal) * (p2 - case.a[1])).real)
    if kinds[0] != "RR":
        lines = [_line(case, i, e) for i in range(3)]
        rows = np.stack([np.concatenate([_real(a), p[..., None]], axis=-1) for a, p in lines],
                        axis=-2)
        return np.asarray(np.linalg.det(rows))
    (a2, p2), (a3, p3) = _line(case, 1, e), _line(case, 2, e)
    matrix = np.stack([_real(a2), _real(a3)], axis=-2)
    w = np.linalg.solve(matrix, np.stack([p2, p3], axis=-1)[..., None])[..., 0]
    r1 = np.abs(case.base[0] - case.external[0])
    return np.asarray(((w ** 2).sum(axis=-1) - r1 ** 2) * np.linalg.det(matrix) ** 2)


def _fft(case: Case, m: int) -> tuple[np.ndarray, np.ndarray]:
    """The coefficients of p from 2m + 2 samples of Φ, and the bin m + 1 (zero for degree m)."""
    count = 2 * m + 2
    samples = np.stack([_phi(case, 2.0 * np.pi * j / count) for j in range(count)], axis=-1)
    bins = np.fft.fft(samples, axis=-1) / count
    return bins[..., np.arange(-m, m + 1) % count], bins[..., m + 1]


@pytest.mark.parametrize("kinds", FORMS, ids=["-".join(kinds) for kinds in FORMS])
def test_the_closed_form_is_the_fft_of_phi(kinds: tuple[str, ...]) -> None:
    case = _case(kinds, seed=sum(map(ord, "".join(kinds))))
    triad = case.triad()
    got = triad.coefficients(case.inputs())
    want, above = _fft(case, triad.degree)
    scale = np.abs(want).max(axis=-1)
    assert got.shape == want.shape == (5, 40, 2 * triad.degree + 1)
    assert (np.abs(got - want).max(axis=-1) <= 1e-12 * scale).all()
    assert (np.abs(above) <= 1e-12 * scale).all()  # Φ has the form's degree m, not more


@pytest.mark.parametrize("kinds", [("RR", "RR", "RR"), ("RR", "RP", "PR"), ("RP", "PR", "PR"),
                                   ("RR", "RR", "PP"), ("RP", "PR", "PP")])
def test_inputs_that_are_not_finite_give_a_nan_row(kinds: tuple[str, ...]) -> None:
    case = _case(kinds, seed=7, designs=6, positions=4)
    case.a[1, 0, 2] = np.nan
    case.a[2, 1, 3] = complex(np.inf, 0.0)
    case.u[2, 2, 4] = np.nan
    case.a[0, 3, 5] = np.nan
    triad = case.triad()
    with np.errstate(invalid="ignore"):
        bad = np.isnan(_fft(case, triad.degree)[0]).any(axis=-1)
    got = triad.coefficients(case.inputs())
    assert bad.any()
    assert np.isnan(got[bad]).all()
    assert np.isfinite(got[~bad]).all()


def test_coincident_hinges_give_finite_or_nan_rows_without_a_warning() -> None:
    case = _case(("RR", "RR", "RR"), seed=8, designs=3, positions=2)
    case.external[0, 0] = case.base[0, 0]  # a bar of length 0
    case.a[1, :, 1] = case.a[0, :, 1]       # two external hinges in one place
    got = case.triad().coefficients(case.inputs())
    assert np.isfinite(got).all()
    polar = _case(("RR", "RR", "PP"), seed=9, designs=3, positions=2)
    polar.external[1, 2] = polar.base[1, 2]  # the second bar of length 0: Φ/(2r₂) has no value
    got = polar.triad().coefficients(polar.inputs())
    assert np.isnan(got[:, 2]).all() and np.isfinite(got[:, :2]).all()
