"""Block B5: the result file, the text report (English/Russian) and the machine-readable summary.

* :func:`write_result` — the identification table of the best design (every varied column a
  plain number), YAML or JSON by the file's suffix, written atomically; ``assur analyze``
  reads it back.  A YAML result starts with comment lines giving the criteria.
* :func:`summary` — everything a report needs, as plain data (``--json``).
* :func:`text_report` — the designer's report: the design, Q, P1, P2, the deviations at the
  control points, pressure angles, the conditions that bind, how the search went, and the
  table of feasible trials (the parameter-space view from which a designer picks).
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import yaml

from assur.io.files import atomic_write_text
from assur.text import render
from synthesis.criteria import criterion_rms
from synthesis.evaluate import Analysis
from synthesis.problem import Problem
from synthesis.search_result import SearchResult, distinct_optima

__all__ = ["allowable_rows", "summary", "text_report", "write_result", "write_trials"]

#: The report's label of Q by the way it is built (``general: criterion``).
_Q_LABEL = {"max": "q", "rms": "q_rms"}


def _w(key: str, lang: str, **data: Any) -> str:
    """A sentence of the report from the catalogue (codes ``synth.report.<key>``)."""
    return render(f"synth.report.{key}", lang, **data)


def _num(value: Any) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def summary(problem: Problem, result: SearchResult, analysis: Analysis, *,
            top: int = 20) -> dict[str, Any]:
    """The outcome as plain data, in table units: mm, degrees (ψ, its deviations, Q, Q_rms
    and [Q] of class 1 too), the ratio n as a plain number.

    Parameters
    ----------
    problem : Problem
    result : SearchResult
    analysis : Analysis
        The analysis of the best design alone (``Evaluator.analyse(result.x[None])``).
    top : int
        Number of feasible trials listed.
    """
    c = analysis.criteria
    control = problem.control
    out = analysis.output_control[0]
    scale = problem.output_scale
    trials = _feasible_trials(problem, result, top)
    points = []
    for k in range(control.weight.size):
        row: dict[str, Any] = {"K": k, "E": float(control.weight[k]),
                               "deviation": _num(c.deviations[0, k] * scale)}
        if problem.task_class in (3, 4, 5):
            row.update(x=float(control.point[k].real), y=float(control.point[k].imag),
                       x_reproduced=_num(out[k].real), y_reproduced=_num(out[k].imag))
        if control.angle is not None:  # (class 5: the segment's direction)
            row["theta"] = math.degrees(control.angle[k])
        if control.timed:
            row["phi"] = math.degrees(control.phi[k])
        if problem.task_class in (1, 2):
            if control.lower is not None and control.upper is not None:  # a zone
                row.update(lower=float(control.lower[k]) * scale,
                           upper=float(control.upper[k]) * scale)
            else:
                row["target"] = float(control.value[k]) * scale
            row["reproduced"] = _num(np.real(out[k]) * scale)
        else:
            row["phi_nearest"] = _num(math.degrees(analysis.phi_control[0, k] % (2 * math.pi)))
        points.append(row)
    return {
        "problem": problem.source,
        "name": problem.name,
        "task_class": problem.task_class,
        "design": problem.design(result.x),
        "initial": problem.design(problem.initial),
        "bounds": {p.name: [p.lower, p.upper] for p in problem.parameters},
        "Q": _num(c.q[0] * scale),
        "criterion": problem.criterion,
        "unit": problem.output_unit,
        "output": problem.output.quantity,
        "Q_rms": _num(criterion_rms(c.deviations[0], control.weight) * scale),
        "P1": float(c.p1[0]),
        "P2": _num(c.p2[0]),
        "accuracy": problem.accuracy,
        "feasible": bool(c.feasible[0]),
        "favourable": bool(c.favourable(problem.q_required)[0]),
        "control_points": points,
        "pressure_angles": {k: {"max_deg": math.degrees(float(v[0, 0])),
                                "allowed_deg": math.degrees(problem.pressure_angles[k])}
                            for k, v in analysis.pressure.items()},
        "rotations": {k: {role: {"range_deg": math.degrees(float(v[0, n])),
                                 "allowed_deg": math.degrees(lim)}
                          for n, (role, lim) in enumerate(problem.rotations[k].items())}
                      for k, v in analysis.rotations.items()},
        "workspace": {k: {"max_outside_mm": float(np.max(v[0])),
                          "box_mm": list(problem.workspace[k])}
                      for k, v in analysis.workspace.items()},
        "strokes": {k: {role: {"max_outside_mm": float(v[0, n]), "range_mm": list(limits)}
                        for n, (role, limits) in enumerate(problem.strokes[k].items())}
                    for k, v in analysis.strokes.items()},
        "advice": _advice(problem, result, float(c.q[0]) * scale),
        "margins": _margins(analysis),
        "binding": _binding(problem, result, analysis),
        "search": {
            "trials": int(result.trials.shape[0]),
            "feasible_trials": int(np.sum(result.trial_criteria.feasible)),
            "stop": result.stop, "stopped_in": result.stopped_in, "message": result.message,
            "seconds": result.elapsed, "seed": result.seed,
            "budget_log2": result.settings.budget_log2, "refine": result.settings.refine,
            "restarts": result.settings.restarts,
            "shrink_passes": result.settings.shrink_passes,
            "history": [{**h.as_dict(), "q": h.q * scale} for h in result.history],
        },
        "feasible_table": trials,
    }


def _advice(problem: Problem, result: SearchResult, q: float) -> dict[str, Any] | None:
    """What to try when the run did not reach [Q] (or found no feasible design), with the
    evidence: the distinct local optima the search met and the spread of their Q.

    None when the run reached [Q], was interrupted, or the problem gives no [Q] and a
    feasible design was found.
    """
    feasible = result.feasible
    reached = feasible and (problem.accuracy is None or q <= problem.accuracy)
    if reached or result.stop == "interrupted":
        return None
    s = result.settings
    optima = [o for o in distinct_optima(result.optima, problem.lower, problem.upper)
              if o.p1 == 0 and o.p2 == 0]
    qs = [o.q * problem.output_scale for o in optima]
    rounds = 1 + max((o.round for o in result.optima), default=0)
    tries = [{"what": "budget", "value": min(s.budget_log2 + 2, 24)}]
    if not s.refine:
        tries.append({"what": "refine"})
    if len(optima) > 1 or s.restarts == 0:
        tries.append({"what": "restarts", "value": max(2 * s.restarts, 3)})
    if s.refine and s.restarts > 0 and len(optima) == 1:
        tries.append({"what": "relax"})
    return {"optima": len(optima), "rounds": rounds,
            "q_min": min(qs) if qs else None, "q_max": max(qs) if qs else None,
            "try": tries}


def _margins(analysis: Analysis) -> dict[str, dict[str, float | None]]:
    motion = analysis.motion
    n = analysis.grid.size
    out = {}
    for group in motion.model.groups[1:]:
        margin = np.asarray(motion.solutions[group.label].margin, dtype=float)
        margin = np.broadcast_to(margin, (1, motion.q.size))[0, :n]
        delta = float(np.asarray(motion.model.params.get(group.column("delta"), 0.0)).ravel()[0])
        out[group.label] = {"min_margin": _num(np.nanmin(margin)) if np.isfinite(margin).any()
                            else None, "delta": delta}
    return out


def _binding(problem: Problem, result: SearchResult, analysis: Analysis) -> list[dict[str, Any]]:
    """Which conditions are active at the best design."""
    out: list[dict[str, Any]] = []
    for p, x in zip(problem.parameters, result.x):
        span = p.upper - p.lower
        if x - p.lower <= 1e-6 * span:
            out.append({"kind": "bound", "parameter": p.name, "side": "lower"})
        elif p.upper - x <= 1e-6 * span:
            out.append({"kind": "bound", "parameter": p.name, "side": "upper"})
    dev = np.abs(analysis.criteria.deviations[0])
    q = analysis.criteria.q[0]
    if np.isfinite(q) and q > 0:
        ks = [int(k) for k in np.flatnonzero(dev >= q * (1 - 1e-3))]
        out.append({"kind": "alternance", "points": ks})
    for label, v in analysis.pressure.items():
        if v[0, 0] >= 0.95 * problem.pressure_angles[label]:
            out.append({"kind": "pressure", "group": label})
    for label, info in _margins(analysis).items():
        margin, delta = info["min_margin"], info["delta"]
        if margin is not None and delta is not None and margin < delta + 0.02:
            out.append({"kind": "margin", "group": label, "margin": margin, "delta": delta})
    return out


def _feasible_order(result: SearchResult) -> npt.NDArray[np.intp]:
    """Indices of the feasible passive trials (P1 = P2 = 0, not a refinement step), best Q
    first."""
    c = result.trial_criteria
    passive = np.array([stage != "refine" for stage in result.stage])
    ok = np.flatnonzero(c.feasible & np.isfinite(c.q) & passive)
    return ok[np.argsort(c.q[ok], kind="stable")]


def _feasible_trials(problem: Problem, result: SearchResult, top: int) -> list[dict[str, Any]]:
    c = result.trial_criteria
    order = _feasible_order(result)[:top]
    return [{"trial": int(k), "stage": result.stage[k],
             "Q": float(c.q[k]) * problem.output_scale,
             **problem.design(result.trials[k])} for k in order]


def text_report(data: dict[str, Any], lang: str = "en") -> str:
    """The report of :func:`summary` data as text in English or Russian."""
    def w(key: str, **data: Any) -> str:
        return _w(key, lang, **data)

    what = f"class{data['task_class']}" + ("_ratio" if data.get("output") == "ratio" else "")
    lines = [w("title", name=data["name"], cls=data["task_class"], what=w(what)), ""]
    lines += [w("design"),
              (f"  {w('param'):<22} {w('initial'):>12} {w('lower'):>12} {w('upper'):>12} "
               f"{w('found'):>14}")]
    for name, value in data["design"].items():
        lo, hi = data["bounds"][name]
        lines.append(f"  {name:<22} {data['initial'][name]:>12.6g} {lo:>12.6g} {hi:>12.6g} "
                     f"{value:>14.9g}")
    def yes_no(flag: bool) -> str:
        return w("yes") if flag else w("no")

    unit = "" if data["unit"] == "1" else w(data["unit"])  # the ratio n has no unit
    lines += ["", w("criteria"),
              f"  {w(_Q_LABEL[data.get('criterion', 'max')]):<40} {_fmt(data['Q'])} {unit}",
              f"  {w('rms'):<40} {_fmt(data['Q_rms'])} {unit}",
              f"  {w('p1'):<40} {_fmt(data['P1'])}",
              f"  {w('p2'):<40} {_fmt(data['P2'])}"]
    if data["accuracy"] is not None:
        lines.append(f"  {w('required'):<40} {data['accuracy']:g} {unit}")
        lines.append(f"  {w('favourable'):<40} {yes_no(data['favourable'])}")
    if not data["feasible"]:
        lines += ["", w("not_feasible")]
    lines += _advice_lines(data, w, unit)
    lines += ["", w("deviations")]
    cls = data["task_class"]
    for row in data["control_points"]:
        if cls in (1, 2):
            target = (f"{row['target']:.6g}" if "target" in row
                      else f"[{row['lower']:.6g}, {row['upper']:.6g}]")
            lines.append(f"  K={row['K']:<3} φ={row['phi']:8.3f}  {w('target')} {target:>12}  "
                         f"{w('reproduced')} {_fmt(row['reproduced']):>12}  "
                         f"Δ={_fmt(row['deviation'])} {unit}")
        else:
            where = (f"φ={row['phi']:8.3f}" if "phi" in row
                     else f"φ*={_fmt(row['phi_nearest']):>8}")
            if "theta" in row:
                where += f"  θ={row['theta']:8.3f}"
            lines.append(f"  K={row['K']:<3} {where}  ({row['x']:.6g}, {row['y']:.6g})  "
                         f"Δ={_fmt(row['deviation'])} {unit}")
    if data["pressure_angles"]:
        lines += ["", w("pressure")]
        for label, info in data["pressure_angles"].items():
            lines.append(f"  {label:<12} {info['max_deg']:8.3f}°   {w('allowed')} "
                         f"{info['allowed_deg']:.3f}°")
    if data["rotations"]:
        lines += ["", w("rotations")]
        for label, joints in data["rotations"].items():
            for role, info in joints.items():
                lines.append(f"  {label:<12} {role:<4} {info['range_deg']:8.3f}°   "
                             f"{w('allowed')} {info['allowed_deg']:.3f}°")
    if data["workspace"]:
        lines += ["", w("workspace")]
        for label, info in data["workspace"].items():
            x0, x1, y0, y1 = info["box_mm"]
            lines.append(f"  {label:<12} x ∈ [{x0:g}, {x1:g}], y ∈ [{y0:g}, {y1:g}]   "
                         f"{w('outside')} {info['max_outside_mm']:.6g}")
    for label, pairs in data.get("strokes", {}).items():
        for role, info in pairs.items():
            s0, s1 = info["range_mm"]
            lines.append(f"  {label:<12} {role:<4} s ∈ [{s0:g}, {s1:g}]   "
                         f"{w('outside')} {info['max_outside_mm']:.6g}")
    lines += ["", w("binding")]
    if not data["binding"]:
        lines.append(f"  {w('none')}")
    for item in data["binding"]:
        if item["kind"] == "bound":
            lines.append("  " + w("at_bound", p=item["parameter"],
                                           side=w(f"side_{item['side']}")))
        elif item["kind"] == "alternance":
            lines.append("  " + w("alternance", k=", ".join(map(str, item["points"]))))
        elif item["kind"] == "pressure":
            lines.append("  " + w("near_limit", g=item["group"]))
        else:
            lines.append("  " + w("margin", g=item["group"], m=item["margin"],
                                                   d=item["delta"]))
    s = data["search"]
    lines += ["", w("search"),
              f"  {w('trials')}: {s['trials']}   {w('feasible_trials')}: {s['feasible_trials']}",
              (f"  {w('stop')}: {w(s['stop'] + '_stop')} "
               f"({w('stopped_in', stage=w('stage_' + s['stopped_in']))})   "
               f"{w('time')}: {s['seconds']:.2f} {w('seconds')}   "
               f"seed {'—' if s['seed'] is None else s['seed']}, 2^{s['budget_log2']} LPτ"),
              f"  {w('history')}:"]
    history = s["history"]
    if len(history) > 12:
        history = history[:6] + history[-6:]
    for h in history:
        lines.append(f"    {w('trial')} {int(h['trial']):>7}  "
                     f"{h['seconds']:8.3f} {w('seconds')}  "
                     f"{w('stage_' + h['stage']):<10} "
                     f"P1={h['p1']:.4g} P2={_fmt(h['p2'])} Q={_fmt(h['q'])}")
    table = data["feasible_table"]
    if table:
        names = list(data["design"])
        lines += ["", w("table", n=len(table)),
                  "  " + f"{w('trial'):>7} {w('stage'):<8} {'Q':>12} "
                  + " ".join(f"{n:>16}" for n in names)]
        for row in table:
            stage = w("stage_" + row["stage"])
            lines.append(f"  {row['trial']:>7} {stage:<8} {row['Q']:>12.5g} "
                         + " ".join(f"{row[n]:>16.8g}" for n in names))
    return "\n".join(lines) + "\n"


def _advice_lines(data: dict[str, Any], w: Any, unit: str) -> list[str]:
    """The advice of :func:`_advice` as sentences."""
    advice = data.get("advice")
    if not advice:
        return []
    lines = [""]
    if data["feasible"] and data["accuracy"] is not None:
        lines.append(w("advice_not_reached", q=_fmt(data["Q"]), acc=f"{data['accuracy']:g}",
                       unit=unit))
    if advice["optima"]:
        lines.append(w("advice_optima", n=advice["optima"], rounds=advice["rounds"],
                       lo=_fmt(advice["q_min"]), hi=_fmt(advice["q_max"]), unit=unit))
    lines.append(w("advice_try"))
    for item in advice["try"]:
        lines.append("  - " + w(f"try_{item['what']}", value=item.get("value")))
    return lines


def _fmt(value: Any) -> str:
    return "—" if value is None else f"{value:.6g}"


def write_result(path: str | os.PathLike[str], problem: Problem, result: SearchResult,
                 data: Mapping[str, Any], lang: str = "en") -> None:
    """Write the identification table of the best design (YAML, or JSON for ``.json``).

    The file is a mechanism table that ``assur analyze`` reads; the criteria stand in comment
    lines at the top of a YAML file, in ``lang`` (a JSON file carries only the table).
    """
    table = problem.mechanism_table(result.x)
    conditions = allowable_rows(problem)
    if conditions:
        table["general"] = {**(table.get("general") or {}), "allowable": conditions}
    if Path(path).suffix.lower() == ".json":
        atomic_write_text(path, json.dumps(table, indent=2, ensure_ascii=False) + "\n")
        return
    seed = "—" if result.seed is None else result.seed
    head = _w("result_head", lang, source=problem.source, cls=problem.task_class,
              q=_fmt(data["Q"]), p1=_fmt(data["P1"]), p2=_fmt(data["P2"]),
              rms=_fmt(data["Q_rms"]), seed=seed, trials=data["search"]["trials"],
              stop=result.stop)
    body = yaml.safe_dump(table, sort_keys=False, allow_unicode=True, default_flow_style=None,
                          width=100)
    atomic_write_text(path, "".join(f"# {line}\n" for line in head.splitlines()) + body)


def allowable_rows(problem: Problem) -> list[dict[str, Any]]:
    """The problem's allowable conditions as rows of its ``allowable`` table (degrees, mm).

    The result file keeps them (``general: {allowable: [...]}``) so that ``assur analyze``
    judges the design against the problem's own limits
    (:meth:`assur.model.General.pressure_angles`).
    """
    rows: dict[str, dict[str, Any]] = {}

    def row(label: str) -> dict[str, Any]:
        links = [int(v) if v.strip().isdigit() else v.strip()
                 for v in label[label.index("(") + 1:label.rindex(")")].split(",")]
        return rows.setdefault(label, {"links": links})

    for label, angle in problem.pressure_angles.items():
        row(label)["pressure_angle"] = _clean_deg(angle)
    for label, limits in problem.rotations.items():
        row(label)["rotations"] = {joint: _clean_deg(v) for joint, v in limits.items()}
    for label, (x0, x1, y0, y1) in problem.workspace.items():
        row(label)["workspace"] = {"x": [x0, x1], "y": [y0, y1]}
    return list(rows.values())


def _clean_deg(radians: float) -> float:
    """An angle in radians back to the degrees a table gave (12 significant digits)."""
    return float(f"{math.degrees(radians):.12g}")


def write_trials(path: str | os.PathLike[str], problem: Problem, result: SearchResult) -> int:
    """Write every feasible passive trial (P1 = P2 = 0) as CSV, best Q first; returns the count.

    Columns: trial number, stage (initial, lptau, shrink), Q (degrees for ψ, else as the
    output), then the varied parameters in table units — the parameter-space table from which a designer picks a mechanism.
    """
    import csv
    import io

    c = result.trial_criteria
    order = _feasible_order(result)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["trial", "stage", "Q", *problem.names])
    for k in order:
        writer.writerow([int(k), result.stage[k], repr(float(c.q[k]) * problem.output_scale),
                         *(repr(float(v)) for v in result.trials[k])])
    atomic_write_text(path, buffer.getvalue())
    return int(order.size)
