"""Picture of a design: n(θ) with the zone, the peak and the tolerance band; the mechanism."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from assur.text import render
from synthesis.cases.figures import write_figure
from synthesis.cases.fourbar_velocity_ratio.conditions import Design
from synthesis.cases.fourbar_velocity_ratio.kinematics import rocker_angle, velocity_ratio

__all__ = ["save_plot"]


def save_plot(design: Design, path: str | Path, lang: str = "en") -> Path:
    """Draw the design and write the picture (format from the file suffix) atomically."""
    from matplotlib.figure import Figure

    def words(key: str, **data: float) -> str:
        return render(f"case.fourbar.plot.{key}", lang, **data)

    d = design
    theta = np.linspace(0.0, 2.0 * np.pi, 1441)
    phi, _ = rocker_angle(d.e, d.c, d.r, theta)
    n = velocity_ratio(d.e, d.r, theta, phi)
    fig = Figure(figsize=(12, 5))
    left, right = fig.subplots(1, 2, width_ratios=(3, 2))
    degrees = np.degrees(theta)
    left.plot(degrees, n, color="C0")
    low, high = sorted((d.n_end, d.n_star))
    left.axhspan(low, high, color="C2", alpha=0.25, label=words("band"))
    start, end = (math.degrees(a) % 360.0 for a in (d.theta1, d.theta3))
    spans = [(start, end)] if start < end else [(start, 360.0), (0.0, end)]
    for k, (a, b) in enumerate(spans):
        left.axvspan(a, b, color="C1", alpha=0.15, label=words("zone") if k == 0 else None)
    left.plot([math.degrees(d.theta2) % 360.0], [d.n_star], "o", color="C3", label=words("peak"))
    left.set_xlim(0.0, 360.0)
    left.set_xlabel(words("crank"))
    left.set_ylabel(words("ratio"))
    left.grid(True, alpha=0.3)
    left.legend(loc="best")

    phi2, _ = rocker_angle(d.e, d.c, d.r, d.theta2)
    crank_pin = d.e * np.exp(1j * d.theta2)
    rocker_end = 1.0 + d.r * 1j * np.exp(1j * float(phi2))
    chain = np.array([0.0, crank_pin, rocker_end, 1.0])
    right.plot(chain.real, chain.imag, "-o", color="k", lw=2)
    right.plot([0.0, 1.0], [0.0, 0.0], color="0.5", lw=4, alpha=0.5)
    circle = d.e * np.exp(1j * theta)
    right.plot(circle.real, circle.imag, ":", color="C0")
    swing = 1.0 + d.r * 1j * np.exp(1j * phi)
    right.plot(swing.real, swing.imag, "-", color="C1", alpha=0.7, label=words("path"))
    right.set_aspect("equal")
    right.set_title(words("mechanism", e=d.e, c=d.c, r=d.r))
    right.grid(True, alpha=0.3)
    right.legend(loc="best")
    fig.tight_layout()
    return write_figure(fig, path)
