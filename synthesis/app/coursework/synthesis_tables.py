"""The synthesis result in the coursework report as tables: the design, the criteria, the
deviations at the control points, the limits checked, the conditions that bind and how the
search went (the same data as the text report, :func:`synthesis.report.text_report`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from assur.text import render
from synthesis.app.coursework.page import esc, table

__all__ = ["synthesis_tables"]


def _w(key: str, lang: str, **data: Any) -> str:
    return render(f"synth.report.{key}", lang, **data)


def _num(value: Any) -> str:
    return "—" if value is None else f"{value:.6g}"


def _heading(key: str, lang: str) -> str:
    return f"<h3>{esc(_w(key, lang))}</h3>"


def _design(data: Mapping[str, Any], lang: str) -> str:
    rows = [(name, data["initial"][name], *data["bounds"][name], value)
            for name, value in data["design"].items()]
    header = tuple(_w(key, lang) for key in ("param", "initial", "lower", "upper", "found"))
    return _heading("design", lang) + table(header, rows, numeric=(1, 2, 3, 4),
                                            table_id="synthesis-design")


def _criteria(data: Mapping[str, Any], lang: str) -> str:
    unit = "" if data["unit"] == "1" else _w(data["unit"], lang)
    q = f"{_num(data['Q'])} {unit}".strip()
    if data["unit"] == "rad" and data["Q"] is not None:
        q += f" ({math.degrees(data['Q']):.4g}°)"
    rows = [(_w("q", lang), q), (_w("rms", lang), f"{_num(data['Q_rms'])} {unit}".strip()),
            (_w("p1", lang), _num(data["P1"])), (_w("p2", lang), _num(data["P2"]))]
    if data["accuracy"] is not None:
        rows += [(_w("required", lang), f"{data['accuracy']:g} {unit}".strip()),
                 (_w("favourable", lang), _w("yes" if data["favourable"] else "no", lang))]
    body = _heading("criteria", lang) + table(("", ""), rows, table_id="synthesis-criteria")
    if not data["feasible"]:
        body += f'<p class="bad">{esc(_w("not_feasible", lang))}</p>'
    return body


def _deviations(data: Mapping[str, Any], lang: str) -> str:
    rows = data["control_points"]
    if not rows:
        return ""
    unit = "" if data["unit"] == "1" else f", {_w(data['unit'], lang)}"
    cells: list[tuple[Any, ...]]
    if data["task_class"] in (1, 2):
        header = ("K", "φ, °", _w("target", lang), _w("reproduced", lang), f"Δ{unit}")
        cells = [(r["K"], r["phi"],
                  r["target"] if "target" in r else f"[{r['lower']:.6g}, {r['upper']:.6g}]",
                  r["reproduced"], r["deviation"]) for r in rows]
    else:
        timed = "phi" in rows[0]  # (classes 4, and 5 with timing)
        header = ("K", "φ, °" if timed else "φ*, °", "x, mm", "y, mm", f"Δ{unit}")
        cells = [(r["K"], r["phi"] if timed else r["phi_nearest"], r["x"], r["y"],
                  r["deviation"]) for r in rows]
    return _heading("deviations", lang) + table(header, cells, numeric=(0, 1, 2, 3, 4),
                                                table_id="synthesis-deviations")


def _limits(data: Mapping[str, Any], lang: str) -> str:
    body = ""
    rows: list[tuple[Any, ...]]
    if data["pressure_angles"]:
        rows = [(label, f"{info['max_deg']:.3f}°", f"{info['allowed_deg']:.3f}°")
                for label, info in data["pressure_angles"].items()]
        body += _heading("pressure", lang) + table(("", "max", _w("allowed", lang)), rows,
                                                   numeric=(1, 2), table_id="synthesis-pressure")
    if data["rotations"]:
        rows = [(label, role, f"{info['range_deg']:.3f}°", f"{info['allowed_deg']:.3f}°")
                for label, joints in data["rotations"].items() for role, info in joints.items()]
        body += _heading("rotations", lang) + table(("", "", "Δ", _w("allowed", lang)), rows,
                                                    numeric=(2, 3), table_id="synthesis-rotations")
    if data["workspace"]:
        rows = [(label, f"[{info['box_mm'][0]:g}, {info['box_mm'][1]:g}]",
                 f"[{info['box_mm'][2]:g}, {info['box_mm'][3]:g}]", info["max_outside_mm"])
                for label, info in data["workspace"].items()]
        body += _heading("workspace", lang) + table(("", "x, mm", "y, mm", _w("outside", lang)),
                                                    rows, numeric=(3,),
                                                    table_id="synthesis-workspace")
    return body


def _binding(data: Mapping[str, Any], lang: str) -> str:
    items = []
    for item in data["binding"]:
        if item["kind"] == "bound":
            items.append(_w("at_bound", lang, p=item["parameter"],
                            side=_w(f"side_{item['side']}", lang)))
        elif item["kind"] == "alternance":
            items.append(_w("alternance", lang, k=", ".join(map(str, item["points"]))))
        elif item["kind"] == "pressure":
            items.append(_w("near_limit", lang, g=item["group"]))
        else:
            items.append(_w("margin", lang, g=item["group"], m=item["margin"], d=item["delta"]))
    listed = "".join(f"<li>{esc(text)}</li>" for text in items or [_w("none", lang)])
    return _heading("binding", lang) + f'<ul class="findings" id="synthesis-binding">{listed}</ul>'


def _search(data: Mapping[str, Any], lang: str) -> str:
    s = data["search"]
    rows = [(_w("trials", lang), s["trials"]), (_w("feasible_trials", lang), s["feasible_trials"]),
            (_w("stop", lang), _w(s["stop"] + "_stop", lang)),
            (_w("time", lang), f"{s['seconds']:.2f} {_w('seconds', lang)}"),
            ("LPτ", f"2^{s['budget_log2']}, seed {'—' if s['seed'] is None else s['seed']}")]
    body = _heading("search", lang) + table(("", ""), rows, numeric=(1,),
                                            table_id="synthesis-search")
    trials = data["feasible_table"][:10]
    if trials:
        names = list(data["design"])
        header = (_w("trial", lang), _w("stage", lang), "Q", *names)
        cells = [(row["trial"], _w("stage_" + row["stage"], lang), row["Q"],
                  *(row[n] for n in names)) for row in trials]
        body += (f"<h3>{esc(_w('table', lang, n=len(trials)))}</h3>"
                 + table(header, cells, numeric=tuple(k for k in range(len(header)) if k != 1),
                         table_id="synthesis-trials"))
    return body


def synthesis_tables(data: Mapping[str, Any], lang: str) -> str:
    """The synthesis result as HTML tables.

    Parameters
    ----------
    data : mapping
        :func:`synthesis.report.summary` of the run (numbers in table units: mm, degrees;
        the criteria in the unit the data name).
    lang : str
        Language of the headings.

    Returns
    -------
    str
        HTML: the design, the criteria, the deviations at the control points, pressure
        angles, joint rotations and workspace where the problem limits them, the conditions
        that bind, the search (with up to ten feasible trials).
    """
    return (_design(data, lang) + _criteria(data, lang) + _deviations(data, lang)
            + _limits(data, lang) + _binding(data, lang) + _search(data, lang))
