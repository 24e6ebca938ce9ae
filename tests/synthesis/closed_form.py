"""Closed-form mechanisms written out by hand, independent of the program's group solvers.

Used by the synthesis tests to generate targets and to re-analyse the designs the search
returns.  Points are complex numbers x + 1j*y; angles in radians.
"""

from __future__ import annotations

import numpy as np


def crank_rocker(rng: np.random.Generator) -> dict[str, float]:
    """A random Grashof crank-rocker (crank shortest, clear of the dead positions), with a
    coupler point at distance ln and angle beta (radians)."""
    while True:
        l1 = rng.uniform(15, 40)
        xhj, li, lj = rng.uniform(70, 130, size=3)
        longest = max(xhj, li, lj)
        # Grashof with 10 mm to spare: shortest + longest <= sum of the other two - 10
        if l1 + longest <= xhj + li + lj - longest - 10:
            return {"l1": l1, "xhj": xhj, "li": li, "lj": lj,
                    "ln": rng.uniform(20, 80), "beta": rng.uniform(-1.0, 1.0)}


def fourbar(phi: np.ndarray, l1: float, li: float, lj: float, xhj: float, *, phi0: float = 0.0,
            sigma: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Crank pin A, joint C and the coupler and rocker angles of a four-bar.

    Crank pivot at the origin, rocker pivot at (xhj, 0), crank angle phi0 + phi.  The
    coupler angle is measured along A → C, the rocker angle along H_j → C; sigma = +1
    puts C to the left of the line A → H_j.
    """
    a = l1 * np.exp(1j * (phi0 + np.asarray(phi, dtype=float)))
    w = xhj - a
    d = np.abs(w)
    cos_g = (li ** 2 + d ** 2 - lj ** 2) / (2 * li * d)
    phi_i = np.angle(w) + sigma * np.arccos(cos_g)
    c = a + li * np.exp(1j * phi_i)
    phi_j = np.angle(c - xhj)
    return a, c, phi_i, phi_j


def coupler_point(phi: np.ndarray, l1: float, li: float, lj: float, xhj: float, ln: float,
                  beta: float, **kw: float) -> np.ndarray:
    """A point of the coupler at distance ln from the crank pin, at angle beta from A → C."""
    a, _, phi_i, _ = fourbar(phi, l1, li, lj, xhj, **kw)
    return a + ln * np.exp(1j * (phi_i + beta))


def rocker_rotation(phi: np.ndarray, *args: float) -> np.ndarray:
    """ψ(φ) of the rocker measured from φ = 0 (counter-clockwise positive)."""
    _, _, _, start = fourbar(np.zeros(1), *args)
    _, _, _, phi_j = fourbar(phi, *args)
    return np.angle(np.exp(1j * (phi_j - start)))


def slider_crank(phi: np.ndarray, a: float, rod: float, e: float) -> np.ndarray:
    """Slider displacement S(φ) − S(0) of an offset slider-crank (guide along x at y = e)."""
    def s(angle: np.ndarray) -> np.ndarray:
        return a * np.cos(angle) + np.sqrt(rod ** 2 - (a * np.sin(angle) - e) ** 2)

    return s(np.asarray(phi, dtype=float)) - s(np.zeros(1))


def distance_to_curve(curve: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Distance from each point to a closed polygon through ``curve`` (dense sampling)."""
    a = curve
    seg = np.roll(curve, -1) - a
    rel = points[:, None] - a[None, :]
    t = np.clip((np.conj(seg)[None, :] * rel).real / np.abs(seg)[None, :] ** 2, 0.0, 1.0)
    return np.min(np.abs(rel - t * seg[None, :]), axis=1)


def dyad(a: np.ndarray, h: complex, li: float, lj: float, sigma: int = 1) -> np.ndarray:
    """Joint C of an RRR dyad with a moving hinge a and a frame pivot h (circle intersection).

    sigma = +1 puts C to the left of the line a → h.
    """
    w = h - a
    d = np.abs(w)
    cos_g = (li ** 2 + d ** 2 - lj ** 2) / (2 * li * d)
    return a + li * np.exp(1j * (np.angle(w) + sigma * np.arccos(cos_g)))


def sixbar_rotation(phi: np.ndarray, l1: float, li: float, lj: float, xhj: float, lm: float,
                    beta_m: float, l4: float, l5: float, h5: complex) -> np.ndarray:
    """ψ(φ) of link 5 of a Watt six-bar, measured from φ = 0 (counter-clockwise positive).

    Crank 1 and the four-bar 1-2-3 of :func:`fourbar`; link 4 is hinged to rocker 3 at
    M = H_j + lm·exp(i(φ_3 + beta_m)) and to link 5, which turns about the frame pivot h5;
    both dyads in assembly +1.
    """
    def angle(p: np.ndarray) -> np.ndarray:
        _, _, _, phi_j = fourbar(p, l1, li, lj, xhj)
        m = xhj + lm * np.exp(1j * (phi_j + beta_m))
        return np.angle(dyad(m, h5, l4, l5) - h5)

    start = angle(np.zeros(1))
    return np.angle(np.exp(1j * (angle(np.asarray(phi, dtype=float)) - start)))
