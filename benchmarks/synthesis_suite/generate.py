"""Write the problems of the synthesis benchmark suite (``problems/*.yaml``, ``suite.yaml``).

Three kinds of problem (``docs/synthesis_suite.md``):

* ``exact`` — targets computed from a known mechanism by the hand-written closed forms of
  ``tests/synthesis/closed_form.py`` (independent of the program's group solvers), the
  mechanism inside the bounds: the optimum is Q* = 0 and a run succeeds when Q ≤ [Q];
* ``constrained`` — a condition (pressure angle, joint rotation, a bound)
  excludes the generating mechanism: Q* > 0 is established by ``establish.py``;
* ``inexact`` — targets no design of the structure reproduces (a law, a curve): Q* > 0,
  established the same way.

Run ``python benchmarks/synthesis_suite/generate.py``; the output is deterministic (seeded
draws), so the committed files can be regenerated and compared.
"""

from __future__ import annotations

import copy
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import yaml

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tests" / "synthesis"))

from closed_form import (  # type: ignore[import-not-found]
    coupler_point,
    crank_rocker,
    rocker_rotation,
    sixbar_rotation,
    slider_crank,
)

GRID = 120                   # positions of the analysis grid (the shipped problems use 360)
ACCURACY = 1e-4              # [Q] of the exact problems (degrees or mm)
PHI = np.radians(np.arange(12) * 30.0)
FOURBAR: list[dict[str, Any]] = [
    {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
    {"L": 1, "i": 2, "j": 3, "i_minus_1": 1, "j_minus_1": 0, "variant": 1},
]
SIXBAR: list[dict[str, Any]] = [
    {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
    {"L": 1, "i": 2, "j": 3, "i_minus_1": 1, "j_minus_1": 0, "j_plus_1": 4, "variant": 1},
    {"L": 1, "i": 4, "j": 5, "i_minus_1": 3, "j_minus_1": 0, "variant": 1},
]
SLIDER_CRANK: list[dict[str, Any]] = [
    {"L": 0, "i": 1, "j": None, "i_minus_1": 0, "j_minus_1": None, "i_plus_1": 2},
    {"L": 2, "i": 3, "j": 2, "i_minus_1": 0, "j_minus_1": 1, "variant": 1},
]


def r6(v: float) -> float:
    """A value as written in a table (6 decimals)."""
    return round(float(v), 6)


def box(rng: np.random.Generator, true: float, spread: float) -> list[float]:
    """[initial, lower, upper]: width 2·spread·|true|, placed at random around ``true``."""
    width = 2 * spread * abs(true)
    lower = true - rng.uniform(0.2, 0.8) * width
    return [r6(rng.uniform(lower, lower + width)), r6(lower), r6(lower + width)]


def problem(name: str, task_class: int, rows: list[dict[str, Any]], output: dict[str, Any],
            parameters: list[dict[str, Any]], points: list[dict[str, Any]], *,
            accuracy: float = ACCURACY, allowable: list[dict[str, Any]] | None = None
            ) -> dict[str, Any]:
    data: dict[str, Any] = {
        "name": name,
        "general": {"control_points": len(points), "direction": 1,
                    "groups": len(rows), "task_class": task_class, "grid": GRID,
                    "accuracy": accuracy},
        "structure_identification": copy.deepcopy(rows),
        "output": output,
        "parameters": parameters,
    }
    if allowable:
        data["allowable"] = allowable
    data["control_points"] = points
    return data


def angle_points(psi: np.ndarray) -> list[dict[str, Any]]:
    return [{"K": k, "phi": r6(math.degrees(PHI[k])), "psi": r6(math.degrees(psi[k])),
             "E": 1} for k in range(PHI.size)]


def fourbar_params(rng: np.random.Generator, d: dict[str, float], *, vary_pivot: bool = False,
                   point: bool = False) -> list[dict[str, Any]]:
    return [
        {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": box(rng, d["l1"], 0.2), "phi_1_0": 0},
        {"links": [2, 3], "x_Hi": "A", "y_Hi": "A",
         "x_Hj": box(rng, d["xhj"], 0.1) if vary_pivot else r6(d["xhj"]), "y_Hj": 0,
         "l_i": box(rng, d["li"], 0.1), "l_j": box(rng, d["lj"], 0.1),
         "l_N": box(rng, d["ln"], 0.2) if point else 0,
         "beta_N": box(rng, math.degrees(d["beta"]), 0.3) if point else 0,
         "l_M": 0, "beta_M": 0},
    ]


def fourbar_angle(seed: int, *, vary_pivot: bool) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    # the pivot distance is written to 6 decimals: the targets use the written value
    d["xhj"] = r6(d["xhj"])
    psi = rocker_rotation(PHI, d["l1"], d["li"], d["lj"], d["xhj"])
    return problem(f"four-bar rocker angle (seed {seed})", 1, FOURBAR, {"link": 3},
                   fourbar_params(rng, d, vary_pivot=vary_pivot), angle_points(psi))


def fourbar_zone(seed: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    d["xhj"] = r6(d["xhj"])
    psi = np.degrees(rocker_rotation(PHI, d["l1"], d["li"], d["lj"], d["xhj"]))
    offset = rng.uniform(-0.4, 0.4, size=PHI.size)
    offset[0] = 0.0
    points = [{"K": k, "phi": r6(math.degrees(PHI[k])), "psi_lo": r6(psi[k] + offset[k] - 0.5),
               "psi_hi": r6(psi[k] + offset[k] + 0.5), "E": 1} for k in range(PHI.size)]
    return problem(f"four-bar rocker angle in a ±0.5° zone (seed {seed})", 1, FOURBAR,
                   {"link": 3}, fourbar_params(rng, d), points, accuracy=1e-9)


def fourbar_path(seed: int, task_class: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    d["xhj"] = r6(d["xhj"])
    params = fourbar_params(rng, d, point=True)
    # the point angle as written (degrees, 6 decimals) generates the targets
    d["beta"] = math.radians(r6(math.degrees(d["beta"])))
    p = coupler_point(PHI, d["l1"], d["li"], d["lj"], d["xhj"], d["ln"], d["beta"])
    if task_class == 3:
        points = [{"K": k, "x": r6(p[k].real), "y": r6(p[k].imag), "E": 1}
                  for k in range(PHI.size)]
        what = "path without timing"
    else:
        points = [{"K": k, "phi": r6(math.degrees(PHI[k])), "x": r6(p[k].real),
                   "y": r6(p[k].imag), "E": 1} for k in range(PHI.size)]
        what = "path with timing"
    return problem(f"four-bar coupler point, {what} (seed {seed})", task_class, FOURBAR,
                   {"link": 2, "point": "N"}, params, points)


def slider_crank_params(rng: np.random.Generator, a: float, rod: float, e: float,
                        e_box: list[float] | None = None) -> list[dict[str, Any]]:
    return [
        {"links": [1], "x_O1": 0, "y_O1": 0, "l_1": box(rng, a, 0.2), "phi_1_0": 0},
        {"links": [3, 2], "x_Hj": "A", "y_Hj": "A", "l_j": box(rng, rod, 0.2),
         "x_Ak": 0, "y_Ak": 0, "beta_g": 0,
         "e": e_box or [r6(rng.uniform(-25, 25)), -25.0, 25.0],
         "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0},
    ]


def stroke_points(s: np.ndarray) -> list[dict[str, Any]]:
    return [{"K": k, "phi": r6(math.degrees(PHI[k])), "S": r6(s[k]), "E": 1}
            for k in range(PHI.size)]


def slider_crank_stroke(seed: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    a, rod, e = rng.uniform(20, 50), rng.uniform(120, 200), rng.uniform(-20, 20)
    return problem(f"slider-crank stroke (seed {seed})", 2, SLIDER_CRANK, {"link": 3},
                   slider_crank_params(rng, a, rod, e), stroke_points(slider_crank(PHI, a, rod, e)))


def sixbar(seed: int) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    d = crank_rocker(rng)
    d["xhj"] = r6(d["xhj"])
    lm, beta_m = rng.uniform(40, 70), round(rng.uniform(-40, 40), 3)
    h5 = complex(round(rng.uniform(-20, 20), 3), round(rng.uniform(90, 130), 3))
    m0 = d["xhj"] + lm * np.exp(1j * math.radians(beta_m))
    # links 4 and 5 long enough to assemble around the swing of M
    span = abs(h5 - m0)
    l4, l5 = span * rng.uniform(0.6, 0.8), span * rng.uniform(0.6, 0.8)
    psi = sixbar_rotation(PHI, d["l1"], d["li"], d["lj"], d["xhj"], lm, math.radians(beta_m),
                          l4, l5, h5)
    if not np.all(np.isfinite(psi)):
        raise ValueError(f"six-bar of seed {seed} does not assemble")
    params = fourbar_params(rng, d)
    params[1].update(l_M=box(rng, lm, 0.15), beta_M=beta_m)
    params.append({"links": [4, 5], "x_Hi": "A", "y_Hi": "A", "x_Hj": h5.real, "y_Hj": h5.imag,
                   "l_i": box(rng, l4, 0.15), "l_j": box(rng, l5, 0.15),
                   "l_N": 0, "beta_N": 0, "l_M": 0, "beta_M": 0})
    return problem(f"Watt six-bar output angle (seed {seed})", 1, SIXBAR, {"link": 5}, params,
                   angle_points(psi))


def shipped(name: str) -> dict[str, Any]:
    """A shipped problem with the suite's grid and no search table."""
    path = ROOT / "input_tables" / "problems" / f"{name}.yaml"
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    data.pop("search", None)
    data["general"]["grid"] = GRID
    if "mechanism" in data:
        data["mechanism"] = str(Path("../../../input_tables/problems") / data["mechanism"])
    return data


def course_wide() -> dict[str, Any]:
    """The 11-link problem with eight varied dimensions (the table's values inside)."""
    data = shipped("class2_course_11_link")
    params = {tuple(row["links"]): row for row in data["parameters"]}
    params[(2, 3)].update(l_i=[132, 125, 155], l_j=[108, 90, 115])
    params[(9, 8)].update(l_j=[124, 115, 145])
    params[(6, 7)].update(x_Hj=[66, 50, 75])
    data["name"] = "course 11-link mechanism, eight varied dimensions"
    return data


def with_allowable(data: dict[str, Any], name: str, allowable: list[dict[str, Any]]
                   ) -> dict[str, Any]:
    data = copy.deepcopy(data)
    data["name"] = name
    data["allowable"] = allowable
    return data


def rocker_law() -> dict[str, Any]:
    """ψ = 20°(1 − cos φ): a four-bar cannot reproduce it exactly."""
    data = shipped("class1_fourbar_rocker")
    data.pop("allowable", None)
    data["name"] = "four-bar for the law ψ = 20°(1 − cos φ)"
    data["control_points"] = angle_points(np.radians(20.0 * (1 - np.cos(PHI))))
    data["parameters"][1]["x_Hj"] = [110, 90, 130]
    return data


def d_shape_path() -> dict[str, Any]:
    """Twelve points of a D (a straight stroke and a half circle): no coupler curve has them."""
    rng = np.random.default_rng(501)
    d = {"l1": 30.0, "xhj": 100.0, "li": 90.0, "lj": 95.0, "ln": 50.0, "beta": 0.5}
    straight = [complex(60 + 10 * k, 80) for k in range(6)]
    arc = [complex(85, 80) + 25 * np.exp(1j * (np.pi * k / 5)) * -1j for k in range(6)]
    points = [{"K": k, "x": r6(p.real), "y": r6(p.imag), "E": 1}
              for k, p in enumerate(straight + arc)]
    params = fourbar_params(rng, d, vary_pivot=True, point=True)
    params[1]["l_N"] = [50, 20, 120]
    params[1]["beta_N"] = [30, -90, 90]
    return problem("four-bar coupler point through a D-shaped path", 3, FOURBAR,
                   {"link": 2, "point": "N"}, params, points)


def harmonic_stroke() -> dict[str, Any]:
    """S = 30(1 − cos φ)·(−1): a slider-crank with a rod of at most 150 mm only approaches it."""
    rng = np.random.default_rng(502)
    s = -30.0 * (1 - np.cos(PHI))
    params = slider_crank_params(rng, 30.0, 120.0, 0.0, e_box=[0.0, -20.0, 20.0])
    params[1]["l_j"] = [110, 80, 150]
    return problem("slider-crank for a harmonic stroke", 2, SLIDER_CRANK, {"link": 3}, params,
                   stroke_points(s))


def timed_ellipse() -> dict[str, Any]:
    """A coupler point on an ellipse at uniform timing."""
    rng = np.random.default_rng(503)
    d = {"l1": 30.0, "xhj": 100.0, "li": 100.0, "lj": 90.0, "ln": 50.0, "beta": 0.5}
    p = complex(60, 90) + 40 * np.cos(PHI) + 1j * 20 * np.sin(PHI)
    points = [{"K": k, "phi": r6(math.degrees(PHI[k])), "x": r6(p[k].real),
               "y": r6(p[k].imag), "E": 1} for k in range(PHI.size)]
    params = fourbar_params(rng, d, point=True)
    params[0]["phi_1_0"] = [0, -180, 180]
    return problem("four-bar coupler point on an ellipse with timing", 4, FOURBAR,
                   {"link": 2, "point": "N"}, params, points)


def sixbar_dwell() -> dict[str, Any]:
    """A six-bar output that rises 30° over half a turn and dwells near 0 over the rest."""
    data = sixbar(601)
    psi = np.where(PHI <= np.pi, 15 * (1 - np.cos(2 * PHI)), 0.0)
    data["name"] = "Watt six-bar for a rise-dwell law"
    data["control_points"] = angle_points(np.radians(psi))
    return data


def suite() -> list[tuple[str, str, dict[str, Any], str]]:
    """(file stem, kind, problem, what it is) of every problem."""
    rocker = shipped("class1_fourbar_rocker")
    slider = slider_crank_stroke(203)
    six = sixbar(301)
    items = [
        ("e01_fourbar_angle", "exact", fourbar_angle(101, vary_pivot=False),
         "class 1, four-bar, 3 varied"),
        ("e02_fourbar_angle_pivot", "exact", fourbar_angle(102, vary_pivot=True),
         "class 1, four-bar, 4 varied"),
        ("e03_fourbar_zone", "exact", fourbar_zone(103), "class 1 zone, four-bar, 3 varied"),
        ("e04_fourbar_path", "exact", fourbar_path(104, 3), "class 3, four-bar, 5 varied"),
        ("e05_fourbar_path", "exact", fourbar_path(105, 3), "class 3, four-bar, 5 varied"),
        ("e06_fourbar_timed", "exact", fourbar_path(106, 4), "class 4, four-bar, 5 varied"),
        ("e07_fourbar_timed", "exact", fourbar_path(107, 4), "class 4, four-bar, 5 varied"),
        ("e08_slider_crank", "exact", slider_crank_stroke(201), "class 2, slider-crank, 3 varied"),
        ("e09_slider_crank", "exact", slider_crank_stroke(202), "class 2, slider-crank, 3 varied"),
        ("e10_sixbar_angle", "exact", six, "class 1, Watt six-bar, 6 varied"),
        ("e11_sixbar_angle", "exact", sixbar(302), "class 1, Watt six-bar, 6 varied"),
        ("e12_course_11_link", "exact", shipped("class2_course_11_link"),
         "class 2, 11-link (shipped), 4 varied"),
        ("e13_course_11_link_wide", "exact", course_wide(), "class 2, 11-link, 8 varied"),
        ("e14_shipped_rocker", "exact", rocker, "class 1, four-bar (shipped), 3 varied"),
        ("e15_shipped_zone", "exact", shipped("class1_fourbar_zone"),
         "class 1 zone, four-bar (shipped)"),
        ("e16_shipped_path", "exact", shipped("class3_fourbar_path"),
         "class 3, four-bar (shipped)"),
        ("e17_shipped_timed", "exact", shipped("class4_fourbar_timed"),
         "class 4, four-bar (shipped)"),
        ("c01_rocker_pressure_45", "constrained", with_allowable(
            rocker, "four-bar rocker angle, pressure angle ≤ 45°",
            [{"links": [2, 3], "pressure_angle": 45}]),
         "class 1, four-bar, [α] = 45° binds (the known case)"),
        ("c02_rocker_rotation", "constrained", with_allowable(
            rocker, "four-bar rocker angle, rocker swing ≤ 50°",
            [{"links": [2, 3], "rotations": {"H_j": 50}}]),
         "class 1, four-bar, joint rotation binds"),
        ("c04_slider_crank_short_rod", "constrained", _short_rod(slider),
         "class 2, slider-crank, the rod's upper bound binds"),
        ("c05_sixbar_pressure_30", "constrained", with_allowable(
            six, "Watt six-bar, pressure angle of the second dyad ≤ 30°",
            [{"links": [4, 5], "pressure_angle": 30}]),
         "class 1, six-bar, [α] = 30° binds"),
        ("i01_rocker_law", "inexact", rocker_law(), "class 1, four-bar, 4 varied"),
        ("i02_d_shape_path", "inexact", d_shape_path(), "class 3, four-bar, 6 varied"),
        ("i03_harmonic_stroke", "inexact", harmonic_stroke(), "class 2, slider-crank, 3 varied"),
        ("i04_timed_ellipse", "inexact", timed_ellipse(), "class 4, four-bar, 6 varied"),
        ("i05_sixbar_dwell", "inexact", sixbar_dwell(), "class 1, six-bar, 6 varied"),
    ]
    return items


def _short_rod(data: dict[str, Any]) -> dict[str, Any]:
    data = copy.deepcopy(data)
    data["name"] = "slider-crank stroke, rod shorter than the generating one"
    rod = data["parameters"][1]["l_j"]
    true_low = rod[1]
    data["parameters"][1]["l_j"] = [true_low, true_low * 0.8, true_low]
    return data


def main() -> None:
    folder = HERE / "problems"
    folder.mkdir(exist_ok=True)
    manifest = []
    for stem, kind, data, what in suite():
        text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True,
                              default_flow_style=None, width=100)
        head = (f"# Synthesis benchmark suite: {what} ({kind}).\n"
                "# Written by benchmarks/synthesis_suite/generate.py; units mm and degrees.\n")
        (folder / f"{stem}.yaml").write_text(head + text, encoding="utf-8")
        manifest.append({"problem": f"problems/{stem}.yaml", "kind": kind, "what": what})
    (HERE / "suite.yaml").write_text(yaml.safe_dump({"problems": manifest}, sort_keys=False,
                                                    allow_unicode=True), encoding="utf-8")
    print(f"{len(manifest)} problems written to {folder}")


if __name__ == "__main__":
    main()
