"""Pictures of the impact case: the mechanism with the impact normal and the impulses, and a
chart comparing the two models."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np

from assur.text import render
from synthesis.cases.figures import write_figure
from synthesis.cases.impact.data import PAPER_IMPULSE_UNIT
from synthesis.cases.impact.study import ImpactStudy

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_case", "save_plot"]

Lang = str
_MODEL_KEY = {"TM": "model_tm", "P": "model_p"}


def _label(key: str, lang: Lang, **data: float) -> str:
    return render(f"case.impact.plot.{key}", lang, **data)


def plot_case(study: ImpactStudy, lang: Lang = "en", row: int | None = None) -> Figure:
    """Draw the case; returns a :class:`matplotlib.figure.Figure` (not shown).

    Parameters
    ----------
    study : ImpactStudy
    lang : str
        A language of the catalogue.
    row : int, optional
        Which rocker velocity (index into ``study.data.omega4``) the mechanism panel shows;
        by default the first one with an impact.
    """
    from matplotlib.figure import Figure

    if row is None:
        row = int(np.argmax(study.position.exists))

    figure = Figure(figsize=(15, 5.2), layout="constrained")
    mech, jumps, impulses = figure.subplots(1, 3, width_ratios=[1.3, 1, 1])
    _draw_mechanism(mech, study, lang, row)
    _draw_comparison(jumps, impulses, study, lang)
    return figure


def save_plot(study: ImpactStudy, path: str | os.PathLike[str], lang: Lang = "en") -> None:
    """Draw the case and write it atomically; the format follows the file suffix."""
    write_figure(plot_case(study, lang), path)


def _xy(point: complex) -> tuple[float, float]:
    return point.real * 1e3, point.imag * 1e3


def _draw_mechanism(ax: Axes, study: ImpactStudy, lang: Lang, row: int) -> None:
    p, d = study.position, study.data
    ax.set_title(_label("mechanism", lang, w4=float(p.omega4[row])), fontsize=10)
    ax.set_aspect("equal")
    ax.set_xlabel(render("case.common.axis.x_mm", lang))
    ax.set_ylabel(render("case.common.axis.y_mm", lang))
    if not p.exists[row]:
        return
    o2, o4 = 0j, complex(p.o4[row])
    a, pin, bearing = complex(p.a[row]), complex(p.pin[row]), complex(p.bearing[row])
    ax.plot(*zip(_xy(o2), _xy(o4)), color="0.6", lw=1, ls="--")
    for start, end, colour, name in ((o2, a, "C0", "2"), (a, pin, "C1", "3"),
                                     (o4, bearing, "C2", "4")):
        ax.plot(*zip(_xy(start), _xy(end)), color=colour, lw=3, solid_capstyle="round")
        ax.annotate(name, _xy((start + end) / 2), textcoords="offset points", xytext=(4, 4))
    for point, name in ((o2, "O2"), (o4, "O4"), (a, "A"), (pin, "B")):
        ax.plot(*_xy(point), "ko", ms=4)
        ax.annotate(name, _xy(point), textcoords="offset points", xytext=(-12, 6))
    u_psi = np.exp(1j * float(p.psi[row]))
    reach = 0.25 * d.r1
    ax.annotate("", _xy(pin + reach * u_psi), _xy(pin),
                arrowprops={"arrowstyle": "->", "color": "k", "ls": ":"})
    ax.annotate(_label("normal", lang), _xy(pin + reach * u_psi), fontsize=8)
    result = study.results["P"]
    scale = 0.4 * d.r1 / max(float(result.normal[row]), 1e-300)
    on_pin = -(float(result.normal[row]) + 1j * float(result.friction[row])) * u_psi
    extent = [o2, o4, a, pin, bearing, pin + reach * u_psi]
    for origin, impulse, name in ((pin, on_pin, "F"), (a, complex(result.r_a[row]), "r_A"),
                                  (o2, complex(result.r_o2[row]), "r_O2")):
        tip = origin + scale * impulse
        extent.append(tip)
        ax.annotate("", _xy(tip), _xy(origin),
                    arrowprops={"arrowstyle": "-|>", "color": "C3", "lw": 1.5})
        ax.annotate(name, _xy(tip), color="C3", fontsize=9)
    xs, ys = zip(*(_xy(point) for point in extent))
    pad = 0.08 * d.r1 * 1e3
    ax.set_xlim(min(xs) - pad, max(xs) + pad)
    ax.set_ylim(min(ys) - pad, max(ys) + 3 * pad)
    _draw_bearing(ax, study, lang, row)


def _draw_bearing(ax: Axes, study: ImpactStudy, lang: Lang, row: int) -> None:
    """Inset: the bearing and the pin touching along ψ, the clearance drawn to scale of its
    own (bearing radius 4ξ)."""
    from matplotlib.patches import Circle

    p, xi = study.position, study.data.clearance
    inset = ax.inset_axes((0.74, 0.66, 0.25, 0.33))
    radius = 4.0 * xi
    centre = 0j
    pin = centre + xi * np.exp(1j * float(p.psi[row]))
    inset.add_patch(Circle(_xy(centre), radius * 1e3, fill=False, color="C2", lw=2))
    inset.add_patch(Circle(_xy(pin), (radius - xi) * 1e3, fill=False, color="C1", lw=2))
    inset.plot(*zip(_xy(centre), _xy(pin + (radius - xi) * np.exp(1j * float(p.psi[row])))),
               "k:", lw=1)
    inset.plot(*_xy(centre), "+", color="C2")
    inset.plot(*_xy(pin), "+", color="C1")
    inset.set_aspect("equal")
    inset.set_xlim(-1.3 * radius * 1e3, 1.3 * radius * 1e3)
    inset.set_ylim(-1.3 * radius * 1e3, 1.3 * radius * 1e3)
    inset.set_xticks([])
    inset.set_yticks([])
    inset.set_xlabel(_label("zoom", lang), fontsize=7)


def _draw_comparison(jumps: Axes, impulses: Axes, study: ImpactStudy, lang: Lang) -> None:
    p = study.position
    rows = [i for i in range(len(p.omega4)) if p.exists[i]]
    names_w = ["Δθ2'", "Δθ3'", "Δθ4'"]
    names_i = ["F", "r_A", "r_O2"]
    width = 0.8 / (2 * max(len(rows), 1))
    for slot, (model, row) in enumerate((m, r) for m in ("TM", "P") for r in rows):
        res = study.results[model]
        dw = [res.omega2[row] - p.omega2[row], res.omega3[row] - p.omega3[row],
              res.omega4[row] - p.omega4[row]]
        imp = [res.normal[row], abs(res.r_a[row]), abs(res.r_o2[row])]
        label = f"{_label(_MODEL_KEY[model], lang)}, θ4' = {p.omega4[row]:g}"
        hatch = "" if model == "TM" else "//"
        colour = f"C{rows.index(row)}"
        offset = (slot - len(rows) + 0.5) * width
        jumps.bar(np.arange(3) + offset, dw, width, label=label, color=colour, hatch=hatch,
                  edgecolor="k", lw=0.5)
        impulses.bar(np.arange(3) + offset, np.asarray(imp) / PAPER_IMPULSE_UNIT, width,
                     label=label, color=colour, hatch=hatch, edgecolor="k", lw=0.5)
    for ax, names, key in ((jumps, names_w, "jumps"), (impulses, names_i, "impulses")):
        ax.set_xticks(np.arange(3), names)
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_title(_label(key, lang), fontsize=10)
        ax.grid(axis="y", alpha=0.3)
    if rows:
        impulses.set_ylim(top=impulses.get_ylim()[1] * (1.0 + 0.08 * 2 * len(rows)))
        impulses.legend(fontsize=7, loc="upper right")
