"""The compiled corrector of a triad against numpy's, and against checks of its own.

``compiled.correct`` runs Newton's method, the Jacobian, the margin and the acceptance tests
per position in compiled code. Here, on every form of leashes without a P–P leash, many
random designs and predictors:

* it agrees with the corrector written with numpy (``continuation._correct`` without its
  ``kernel``): the same positions pass, the same poses, Jacobians and margins;
* where a position passes, the pose satisfies the loop equations (the group's residual),
  the Jacobian is the residual's by central differences, and the root is farther than four
  times the correction from every other root of the eliminant (the roots by ``numpy.roots``);
* its analogs x′, x″ are numpy's (``continuation.analogs``) and the central differences of
  poses solved along a path of the inputs;
* the root-free form of the separation test (``_jit.close``) decides as the bound of
  ``roots.separation`` does, on random polynomials either side of the threshold.
"""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from assur.kinematics.higher import Triad, TriadInputs, compiled, continuation
from assur.kinematics.higher.groups import plain
from assur.kinematics.higher.modes import newton
from assur.kinematics.higher.roots import separation
from assur.kinematics.jets import Jet

FORMS = ([("RR", *rest) for rest in itertools.product(("RR", "RP", "PR"), repeat=2)]
         + [tuple(kinds) for kinds in itertools.product(("RP", "PR"), repeat=3)])
DESIGNS = 300


def _case(kinds: tuple[str, ...], seed: int) -> tuple[Triad, TriadInputs, np.ndarray]:
    """Random designs of one form, inputs moved off the drawing, and predictors near it."""
    rng = np.random.default_rng(seed)

    def points() -> tuple[np.ndarray, ...]:
        return tuple(rng.normal(0.0, 60.0, DESIGNS) + 1j * rng.normal(0.0, 60.0, DESIGNS)
                     for _ in range(3))

    base, external = points(), list(points())
    guide = tuple(None if kind == "RR" else np.exp(1j * rng.uniform(0.0, 6.3, DESIGNS))
                  for kind in kinds)
    for i, g in enumerate(guide):  # a sliding leash's guide through its drawn base point
        if g is not None:
            external[i] = base[i] + rng.normal(0.0, 60.0, DESIGNS) * g
    triad = Triad(kinds, base, tuple(external), guide)  # type: ignore[arg-type]
    a = [p + rng.normal(0.0, 0.5, DESIGNS) + 1j * rng.normal(0.0, 0.5, DESIGNS)
         for p in external]
    a[1][7] = np.nan  # an input that is not finite: no pose, never an error
    u = tuple(g * np.exp(1j * rng.normal(0.0, 0.01, DESIGNS)) if kind == "RP" else None
              for g, kind in zip(guide, kinds, strict=True))
    k = TriadInputs(tuple(a), u)  # type: ignore[arg-type]
    spread = 0.01 * np.stack([triad.size, triad.size, np.ones(DESIGNS)], axis=-1)  # L, rad
    guess = triad.drawn() + rng.normal(0.0, 1.0, (DESIGNS, 3)) * spread
    return triad, k, guess


def _sign(triad: Triad, k: TriadInputs) -> np.ndarray:
    """The sign of det J at the drawn unknowns (the mode of the sketch)."""
    with np.errstate(invalid="ignore"):
        return np.asarray(np.sign(np.linalg.det(triad.jacobian(triad.drawn(), k))))


@pytest.mark.parametrize("kinds", FORMS, ids="-".join)
def test_the_compiled_corrector_is_numpys(kinds: tuple[str, ...]) -> None:
    triad, k, guess = _case(kinds, sum(map(ord, "".join(kinds))))
    assert compiled.supports(triad)
    sign = _sign(triad, k)
    x, jac, margin, ok = compiled.correct(triad, k, guess, sign, continuation.ITERATIONS,
                                          continuation.CONVERGED)
    xn, jn, mn, okn = continuation._correct(triad, k, guess, sign)
    assert np.array_equal(ok, okn)
    assert 0.2 < ok.mean() < 1.0 and not ok[7]  # both outcomes are compared
    size = triad.size[:, None]
    scale = np.concatenate([size, size, np.ones_like(size)], axis=-1)
    assert np.allclose(x[ok] / scale[ok], xn[ok] / scale[ok], rtol=0.0, atol=1e-12)
    assert np.isnan(x[7]).all() and np.isnan(xn[7]).all()
    assert np.allclose(jac[ok], jn[ok], rtol=1e-12, atol=1e-12 * size.max())
    assert np.allclose(margin[ok], mn[ok], rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("kinds", FORMS[:4] + FORMS[-2:], ids="-".join)
def test_a_pose_that_passes_is_a_pose_of_its_own_root(kinds: tuple[str, ...]) -> None:
    triad, k, guess = _case(kinds, 7 + sum(map(ord, "".join(kinds))))
    sign = _sign(triad, k)
    x, jac, _, ok = compiled.correct(triad, k, guess, sign, continuation.ITERATIONS,
                                     continuation.CONVERGED)
    residual = np.stack(np.broadcast_arrays(*map(plain, triad.residual(x, k))), axis=-1)
    assert np.abs(residual[ok]).max(axis=-1).max() <= 1e-9 * triad.size[ok].max()
    width = 1e-6 * np.array([triad.size.max(), triad.size.max(), 1.0])
    columns = []
    for i in range(3):
        shift = np.zeros(3)
        shift[i] = width[i]
        ahead, behind = (np.stack(np.broadcast_arrays(*map(plain, triad.residual(x + h, k))),
                                  axis=-1) for h in (shift, -shift))
        columns.append((ahead - behind) / (2.0 * width[i]))
    assert np.allclose(jac[ok], np.stack(columns, axis=-1)[ok], rtol=1e-6, atol=1e-6)
    # every other root of p is farther than four times the correction
    coef = triad.coefficients(k)
    apart = (np.abs(x - guess) * np.array([1.0, 1.0, 0.0])).sum(axis=-1) / triad.size \
        + np.abs(x - guess)[:, 2]
    for design in np.flatnonzero(ok):
        found = np.roots(coef[design][::-1])
        own = np.exp(1j * x[design, 2])
        others = np.sort(np.abs(found - own))[1:]
        assert others.min() >= 4.0 * apart[design] * (1.0 - 1e-9)


def test_the_root_free_separation_test_decides_as_the_bound() -> None:
    from assur.kinematics.higher.compiled._jit import close

    rng = np.random.default_rng(26)
    work = np.empty(7, dtype=complex)
    checked = 0
    for degree in (1, 2, 3):
        for _ in range(300):
            half = rng.normal(0.0, 1.0, degree + 1) + 1j * rng.normal(0.0, 1.0, degree + 1)
            half[0] = half[0].real
            coef = np.concatenate([np.conj(half[:0:-1]), half])  # p_{m±n} = φ_n, φ̄_n
            theta = rng.uniform(0.0, 2.0 * np.pi)
            bound = float(separation(coef[None], np.array([theta]))[0])
            for factor in (0.9, 0.999, 1.001, 1.1):
                reach = 0.25 * bound * factor
                assert close(coef, theta, reach, work[:coef.size]) == (factor < 1.0)
                checked += 1
    assert checked == 3 * 300 * 4


@pytest.mark.parametrize("kinds", FORMS[:3] + FORMS[4:5] + FORMS[-3:], ids="-".join)
def test_the_compiled_analogs_are_the_derivatives_of_the_poses(kinds: tuple[str, ...]) -> None:
    """x′ and x″ against numpy's implicit differentiation (``continuation.analogs``) and
    against central differences of poses solved on a path of the inputs: a_k(φ) = a_k +
    a′_kφ + a″_kφ²/2, u_k(φ) = u_k·e^{iωφ}, and, for a bar, an actuator's length
    r(φ) = r + r′φ + r″φ²/2."""
    triad, k, guess = _case(kinds, 11 + sum(map(ord, "".join(kinds))))
    x, jac, _, ok = continuation._correct(triad, k, guess, _sign(triad, k))
    rng = np.random.default_rng(5)

    def complex_normal() -> np.ndarray:
        return rng.normal(0.0, 1.0, DESIGNS) + 1j * rng.normal(0.0, 1.0, DESIGNS)

    slope, bend = [complex_normal() for _ in k.a], [complex_normal() for _ in k.a]
    omega = 0.3
    lengths = [triad.leash_length(i, k) for i in range(3)]
    stretch = [rng.normal(0.0, 1.0, (2, DESIGNS)) if kind == "RR" else None for kind in kinds]

    def inputs(phi: float) -> TriadInputs:
        a = tuple(a + s * phi + 0.5 * c * phi * phi for a, s, c in zip(k.a, slope, bend))
        u = tuple(None if v is None else v * np.exp(1j * omega * phi) for v in k.u)
        r = tuple(None if t is None else r + t[0] * phi + 0.5 * t[1] * phi * phi
                  for r, t in zip(lengths, stretch))
        return TriadInputs(a, u, r)  # type: ignore[arg-type]

    points = tuple(Jet(plain(a), s, c) for a, s, c in zip(k.a, slope, bend))
    guides = tuple(None if v is None else Jet(plain(v), 1j * omega * plain(v),
                                              -omega * omega * plain(v)) for v in k.u)
    bars = tuple(None if t is None else Jet(plain(r), t[0], t[1])
                 for r, t in zip(lengths, stretch))
    jets = TriadInputs(points, guides, bars)  # type: ignore[arg-type]
    x1, x2 = compiled.analogs(triad, jets, x, jac)
    n1, n2 = continuation.analogs(triad, jets, x, jac)
    assert np.allclose(x1[ok], n1[ok], rtol=1e-12, atol=1e-12 * np.abs(n1[ok]).max())
    assert np.allclose(x2[ok], n2[ok], rtol=1e-12, atol=1e-12 * np.abs(n2[ok]).max())
    h = 1e-4
    ahead, _ = newton(triad, inputs(h), x + h * x1, 8)
    behind, _ = newton(triad, inputs(-h), x - h * x1, 8)
    first = (ahead - behind) / (2.0 * h)
    second = (ahead - 2.0 * x + behind) / (h * h)
    assert np.allclose(x1[ok], first[ok], rtol=1e-5, atol=1e-5 * np.abs(first[ok]).max())
    assert np.allclose(x2[ok], second[ok], rtol=1e-3, atol=1e-3 * np.abs(second[ok]).max())


def test_the_compiled_predictor_is_the_taylor_polynomial_of_the_nearest_state() -> None:
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0.0, 6.0, 40))
    x, x1, x2 = (rng.normal(0.0, 1.0, (40, 3)) for _ in range(3))
    nearest = rng.integers(0, 40, (50, 7))
    targets = t[nearest] + rng.uniform(-0.1, 0.1, nearest.shape)
    for s in (1.0, -1.0):
        h = (targets - t[nearest])[..., None]
        expected = x[nearest] + s * h * x1[nearest] + 0.5 * h * h * x2[nearest]
        found = compiled.predict(t, x, x1, x2, nearest, targets, s)
        assert np.allclose(found, expected, rtol=1e-15, atol=1e-15)


def _python(script: str) -> subprocess.CompletedProcess[str]:
    """``script`` run by a fresh interpreter on this tree (what it imports, it loads anew)."""
    root = Path(__file__).resolve().parents[2]
    return subprocess.run([sys.executable, "-c", script], cwd=root, capture_output=True,
                          text=True, check=False, timeout=300,
                          env=dict(os.environ, PYTHONPATH=str(root)))


def test_numba_loads_for_a_large_grid_only() -> None:
    """One design of a triad mechanism over 360 angles (followed by the path of its root)
    and 200 designs at 36 angles (by steps, 7,400 positions) are corrected by numpy: numba is
    not loaded, as importing it and the cached kernels would cost more than the analysis;
    200 designs at 360 angles (72,200 positions) load it."""
    script = ("import sys, numpy as np, assur\n"
              "from assur.kinematics.analysis import analyse\n"
              "model = assur.load_model('input_tables/eight_bar_triad.yaml')\n"
              "analyse(model, assur.input_grid(model, 360))\n"
              "many = model.with_params({name: value + np.linspace(-0.3, 0.3, 200)[:, None]\n"
              "                          for name, value in model.params.items()\n"
              "                          if name.startswith('III(') and '.x_' in name})\n"
              "analyse(many, assur.input_grid(model, 36))\n"
              "print('numba' in sys.modules)\n"
              "analyse(many, assur.input_grid(model, 360))\n"
              "print('numba' in sys.modules)\n")
    done = _python(script)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-2:] == ["False", "True"]


def test_the_kernels_compile_where_no_cache_directory_is_writable() -> None:
    """With every cache directory refused (as numba finds it when neither the package's
    folder nor the user's cache can be written), the kernels still compile and run."""
    script = ("import numpy as np\n"
              "from numba.core import caching\n"
              "def refuse(self):\n"
              "    raise OSError('read-only')\n"
              "caching._CacheLocator.ensure_cache_path = refuse\n"
              "from assur.kinematics.higher import compiled\n"
              "t = np.array([0.0, 1.0])\n"
              "x = np.array([[1.0, 2.0], [3.0, 4.0]])\n"
              "out = compiled.predict(t, x, x, x, np.array([1]), np.array([1.5]), 1.0)\n"
              "print(out.tolist())\n")
    done = _python(script)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-1] == str([[3.0 + 0.5 * 3.0 + 0.125 * 3.0,
                                                          4.0 + 0.5 * 4.0 + 0.125 * 4.0]])


@pytest.mark.parametrize("kinds", [("RR", "RR", "RR"), ("RR", "RP", "PR"), ("RP", "PR", "RP")],
                         ids="-".join)
def test_the_compiled_corrector_decides_alike_at_every_scale(kinds: tuple[str, ...]) -> None:
    """The drawing, the inputs and the predictor scaled from 1e-3 to 1e4 mm: the acceptance
    tests are dimensionless, so the same positions pass at every scale, and the poses scale
    with the drawing (to 1e-12 of its size) — no overflow or loss in the squared
    separation test or the margin."""
    triad, k, guess = _case(kinds, 5)
    sign = _sign(triad, k)
    x, _, margin, ok = compiled.correct(triad, k, guess, sign, continuation.ITERATIONS,
                                        continuation.CONVERGED)
    assert 0.2 < ok.mean() < 1.0
    size = triad.size[:, None]
    for scale in (1e-3, 1e-1, 1e2, 1e4):
        scaled = Triad(kinds, tuple(b * scale for b in triad.base),  # type: ignore[arg-type]
                       tuple(e * scale for e in triad.external),  # type: ignore[arg-type]
                       triad.guide)
        inputs = TriadInputs(tuple(a * scale for a in k.a), k.u)  # type: ignore[arg-type]
        start = guess * np.array([scale, scale, 1.0])
        xs, _, margins, oks = compiled.correct(scaled, inputs, start, sign,
                                               continuation.ITERATIONS, continuation.CONVERGED)
        assert np.array_equal(oks, ok)
        assert np.allclose(xs[ok, :2] / scale / size[ok], x[ok, :2] / size[ok], rtol=0.0,
                           atol=1e-12)
        assert np.allclose(xs[ok, 2], x[ok, 2], rtol=0.0, atol=1e-12)
        assert np.allclose(margins[ok], margin[ok], rtol=1e-12, atol=1e-15)


def test_loaded_on_purpose_the_kernels_correct_a_small_analysis_alike() -> None:
    """Before ``compiled.load()`` one design of the class IV group over 36 angles (followed by
    steps, 36 positions) is corrected by numpy and numba is not loaded; after it, the same
    analysis is corrected by the kernels, and every joint is where numpy put it (1e-9 mm)."""
    script = ("import sys, numpy as np, assur\n"
              "from assur.kinematics.analysis import analyse\n"
              "from assur.kinematics.higher import compiled\n"
              "calls = []\n"
              "real = compiled.correct\n"
              "def spy(*args, **kwargs):\n"
              "    calls.append(1)\n"
              "    return real(*args, **kwargs)\n"
              "compiled.correct = spy\n"
              "model = assur.load_model('input_tables/class_iv_group.yaml')\n"
              "q = assur.input_grid(model, 36)\n"
              "before = analyse(model, q)\n"
              "print('numba' in sys.modules, len(calls))\n"
              "compiled.load()\n"
              "after = analyse(model, q)\n"
              "print('numba' in sys.modules, len(calls) > 0)\n"
              "gap = max(float(np.nanmax(np.abs(after.joints[p] - before.joints[p])))\n"
              "          for p in before.joints)\n"
              "same = all(np.array_equal(np.isnan(after.joints[p]), np.isnan(before.joints[p]))\n"
              "           for p in before.joints)\n"
              "print(gap <= 1e-9, same, len(before.joints))\n")
    done = _python(script)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.strip().splitlines()[-3:]
    assert lines[:2] == ["False 0", "True True"]
    assert lines[2].split()[:2] == ["True", "True"] and int(lines[2].split()[2]) >= 4
