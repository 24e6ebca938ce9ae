"""``assur analyze TABLE.yaml``: kinematic analysis of a mechanism over the input cycle.

Reads a chain table with a ``geometry:`` sketch or an identification table with ``params:``,
solves the groups in layering order at ``--points`` positions and prints a summary: the
existence verdict of every group (with the intervals where it cannot be assembled), the
ranges of the outputs, the largest pressure angle and the swing of every revolute joint.
``--json`` prints every position instead; ``--csv``, ``--plot`` and ``--animate`` write files.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import math
import sys
from typing import Any

import numpy as np

import assur

NAME = "analyze"
HELP = "kinematic analysis over the crank cycle: positions, analogs, existence of groups"
ORDER = 20

_TEXT = {
    "title": ("Kinematic analysis: {name} ({source})", "Кинематический анализ: {name} ({source})"),
    "crank": (("Input: crank {link}, {dir}, {n} positions over φ = 0…360° from the sketched "
               "position"), "Вход: кривошип {link}, {dir}, {n} положений φ = 0…360° от исходного"),
    "actuator": ("Input: actuator length {lo:.3f}…{hi:.3f} mm, {n} positions",
                 "Вход: длина привода {lo:.3f}…{hi:.3f} мм, {n} положений"),
    "ccw": ("counter-clockwise", "против часовой стрелки"),
    "cw": ("clockwise", "по часовой стрелке"),
    "existence": ("Existence of the groups (layering order; margin against δ):",
                  "Существование групп (в порядке наслоения; запас против δ):"),
    "assembles": ("assembles over the whole cycle", "собирается на всём цикле"),
    "reached": ("assembles wherever it is reached", "собирается везде, где проверялась"),
    "fails": ("CANNOT BE ASSEMBLED", "НЕ СОБИРАЕТСЯ"),
    "not evaluated": ("not evaluated (an earlier group always fails)",
                      "не проверялась (раньше не собирается предыдущая группа)"),
    "margin": ("min margin {m:.4f}, δ = {d:g}", "мин. запас {m:.4f}, δ = {d:g}"),
    "interval": ("{a} … {b}: {why}; worst {v:.4g} {unit} at {w}",
                 "{a} … {b}: {why}; наихудшее {v:.4g} {unit} при {w}"),
    "skipped": ("not evaluated at {n} positions (an earlier group fails there)",
                "не проверялась в {n} положениях (раньше не собирается предыдущая группа)"),
    "verdict_ok": ("Verdict: the mechanism assembles at every analysed position.",
                   "Вывод: механизм собирается во всех положениях."),
    "verdict_bad": ("Verdict: the mechanism breaks at {n} of {total} positions.",
                    "Вывод: механизм разрывается в {n} из {total} положений."),
    "outputs": ("Output ranges (where assembled):", "Диапазоны выходных величин (где собран):"),
    "link": ("link {link} angle", "угол звена {link}"),
    "slider": ("slider {slider} on {carrier}, pair {pair}: S",
               "ползун {slider} на {carrier}, пара {pair}: S"),
    "trace": ("tracing point {name}", "точка {name}"),
    "pressure": ("Pressure angles at C (L1/L2 with a two-hinge rod, [α] = 45°):",
                 "Углы давления в паре C (L1/L2 с двухшарнирным звеном, [α] = 45°):"),
    "no_pressure": ("Pressure angles: no L1/L2 group has a two-hinge rod, so the course "
                    "computes none.",
                    "Углы давления: нет групп L1/L2 с двухшарнирным звеном, по методике они "
                    "не вычисляются."),
    "alpha": ("{label}, pair {pair}: max {a:.2f}° at {at}",
              "{label}, пара {pair}: макс. {a:.2f}° при {at}"),
    "rotations": ("Relative rotation in the revolute joints (swing):",
                  "Относительный поворот во вращательных парах (размах):"),
    "full": ("full turn (crank pivot)", "полный оборот (опора кривошипа)"),
    "written": ("written: {path}", "записан файл: {path}"),
}


def _t(key: str, lang: str, **kw: Any) -> str:
    text = _TEXT[key][0 if lang == "en" else 1]
    return text.format(**kw) if kw else text


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``assur analyze``."""
    parser.add_argument("table", help="chain table with a geometry: sketch, or an "
                                      "identification table with params:")
    parser.add_argument("--points", type=int, default=360,
                        help="number of analysed positions (default 360)")
    parser.add_argument("--json", action="store_true",
                        help="print every position as JSON instead of the summary")
    parser.add_argument("--csv", metavar="FILE", help="write one row per position")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="draw the mechanism at --at with the traced paths")
    parser.add_argument("--at", type=float, default=0.0,
                        help="crank angle φ (degrees; actuator: length in mm) drawn by --plot "
                             "(default: the first position)")
    parser.add_argument("--animate", metavar="FILE.gif", help="animate a whole cycle")
    parser.add_argument("--frames", type=int, default=48, help="frames of --animate (48)")
    parser.add_argument("--omega", type=float, default=None,
                        help="input speed (rad/s of the crank, mm/s of an actuator): add "
                             "velocities and accelerations to --json and --csv")
    parser.add_argument("--lang", choices=("en", "ru"), default="en", help="report language")


def run(args: argparse.Namespace) -> int:
    """Analyse the table and report."""
    if args.points < 2:
        raise assur.TableError("--points", [assur.Issue("--points", f"expected at least 2 "
                                                                    f"positions; found "
                                                                    f"{args.points}")])
    model = assur.load_model(args.table)
    motion = assur.analyse(model, points=args.points, analogs=True)
    report = assur.check_existence(model, motion=motion)
    if args.json:
        json.dump(record(motion, report, args.omega), sys.stdout, ensure_ascii=False)
        sys.stdout.write("\n")
    else:
        print(summary(motion, report, args.lang))
    if args.csv:
        assur.atomic_write_text(args.csv, table_csv(motion, report, args.omega))
        _note(args, args.csv)
    if args.plot:
        at = _at_index(motion, args.at)
        assur.save_mechanism_png(motion, args.plot, index=at, lang=args.lang)
        _note(args, args.plot)
    if args.animate:
        assur.save_animation_gif(motion, args.animate, frames=args.frames, lang=args.lang)
        _note(args, args.animate)
    return 0


def _note(args: argparse.Namespace, path: str) -> None:
    print(_t("written", args.lang, path=path), file=sys.stderr if args.json else sys.stdout)


def _at_index(motion: Any, at: float) -> int:
    target = math.radians(at) if motion.model.drive == "crank" else at
    if motion.model.drive == "crank":
        distance = np.abs(np.angle(np.exp(1j * (motion.q - target))))
    else:
        distance = np.abs(motion.q - target)
    return int(np.argmin(distance))


def _position(motion: Any, value: float) -> str:
    if motion.model.drive == "crank":
        return f"φ = {math.degrees(value):.2f}°"
    return f"l = {value:.3f} mm"


# ------------------------------------------------------------------------------- summary


def summary(motion: Any, report: Any, lang: str = "en") -> str:
    """The text report of one analysis."""
    model = motion.model
    lines = [_t("title", lang, name=model.name, source=model.source)]
    n = motion.q.size
    if model.drive == "crank":
        crank = model.groups[0].i
        lines.append(_t("crank", lang, link=crank, n=n,
                        dir=_t("ccw" if model.direction > 0 else "cw", lang)))
    else:
        lines.append(_t("actuator", lang, lo=model.input_range[0], hi=model.input_range[1], n=n))
    lines += ["", _t("existence", lang)]
    unit_words = {"mm": "mm" if lang == "en" else "мм", "deg": "°"}
    for group in report.groups:
        reached = group.verdict == "assembles" and not group.evaluated.all()
        verdict = _t("reached" if reached else group.verdict, lang)
        lines.append(f"  {group.name:<20} {verdict}; "
                     + _t("margin", lang, m=group.min_margin, d=group.delta))
        lines.append(f"  {'':<20} {assur.CONDITIONS[group.kind]}")
        for item in group.intervals:
            why = assur.REASONS[item.reason][0 if lang == "en" else 1]
            lines.append("    " + _t("interval", lang, a=_position(motion, item.start),
                                     b=_position(motion, item.end), why=why,
                                     v=item.shortfall, unit=unit_words[item.unit],
                                     w=_position(motion, item.worst_at)))
        skipped = int((~group.evaluated).sum())
        if skipped and group.evaluated.any():
            lines.append("    " + _t("skipped", lang, n=skipped))
    broken = int((report.first >= 0).sum())
    lines.append(_t("verdict_ok", lang) if broken == 0 else
                 _t("verdict_bad", lang, n=broken, total=n))
    lines += ["", _t("outputs", lang)]
    for link in _moving_links(model):
        angle = np.degrees(assur.unwrap(assur.values(motion.link_angle(link))))
        lines.append(f"  {_t('link', lang, link=link):<34} {_range(angle, '°')}")
    for pid, slider in motion.sliders.items():
        s = assur.values(slider.s)
        label = _t("slider", lang, slider=slider.slider, carrier=slider.carrier, pair=pid)
        lines.append(f"  {label:<34} {_range(s, ' mm')}")
    for name, point in motion.tracing.items():
        z = assur.values(point)
        lines.append(f"  {_t('trace', lang, name=name):<34} x {_range(z.real, ' mm')}, "
                     f"y {_range(z.imag, ' mm')}")
    angles = assur.pressure_angles(motion)
    lines.append("")
    if angles:
        lines.append(_t("pressure", lang))
        for item in angles:
            at = int(np.nanargmax(item.alpha)) if np.isfinite(item.alpha).any() else 0
            lines.append("  " + _t("alpha", lang, label=item.label, pair=item.pair,
                                   a=math.degrees(item.maximum),
                                   at=_position(motion, float(motion.q[at]))))
    else:
        lines.append(_t("no_pressure", lang))
    lines += ["", _t("rotations", lang)]
    for item in assur.joint_rotations(motion):
        swing = _t("full", lang) if item.full_turn else f"{math.degrees(item.swing):8.2f}°"
        lines.append(f"  {item.pair!s:<8} {item.links[0]}–{item.links[1]:<4} "
                     f"{item.group:<12} {swing}")
    return "\n".join(lines)


def _range(values: np.ndarray, unit: str) -> str:
    values = np.asarray(values, dtype=float)
    if not np.isfinite(values).any():
        return "—"
    lo, hi = float(np.nanmin(values)), float(np.nanmax(values))
    return f"{lo:9.3f} … {hi:9.3f}{unit} (Δ {hi - lo:.3f})"


def _moving_links(model: Any) -> list[Any]:
    return sorted(model.links, key=lambda link: (isinstance(link, str), str(link).zfill(6)))


# ---------------------------------------------------------------------------------- JSON


def _floats(values: Any) -> list[float | None]:
    array = np.asarray(values, dtype=float).ravel()
    return [_nan(v) for v in array]


def _xy(z: Any, prefix: str = "") -> dict[str, list[float | None]]:
    z = np.asarray(z)
    return {f"{prefix}x": _floats(z.real), f"{prefix}y": _floats(z.imag)}


def _point(jet: Any, omega: float | None) -> dict[str, Any]:
    out = _xy(jet.v)
    out["d1"] = _xy(jet.d1)
    out["d2"] = _xy(jet.d2)
    if omega is not None:
        out["velocity"] = _xy(assur.velocity(jet, omega))
        out["acceleration"] = _xy(assur.acceleration(jet, omega))
    return out


def _scalar(jet: Any, omega: float | None, scale: float = 1.0) -> dict[str, Any]:
    out = {"value": _floats(np.asarray(jet.v) * scale), "d1": _floats(jet.d1),
           "d2": _floats(jet.d2)}
    if omega is not None:
        out["velocity"] = _floats(assur.velocity(jet, omega))
        out["acceleration"] = _floats(assur.acceleration(jet, omega))
    return out


def record(motion: Any, report: Any, omega: float | None = None) -> dict[str, Any]:
    """Every position of an analysis as a JSON-ready mapping.

    Every list is aligned with ``input.values``. Points are in mm; ``d1``/``d2`` are the
    velocity and acceleration analogs (derivatives w.r.t. the input coordinate: per radian
    of crank rotation, or per mm of actuator length); link angles are in degrees, their
    analogs in rad/rad. Missing values (no assembly) are null.
    """
    model = motion.model
    crank = model.drive == "crank"
    out: dict[str, Any] = {
        "mechanism": model.name, "source": model.source, "drive": model.drive,
        "direction": model.direction,
        "input": {"name": "phi" if crank else "actuator_length",
                  "unit": "deg" if crank else "mm",
                  "values": _floats(np.degrees(motion.q) if crank else motion.q)},
        "parameters": {name: float(np.asarray(v)) for name, v in model.params.items()},
        "groups": [], "links": {}, "joints": {}, "sliders": {}, "tracing": {},
        "all_exist": report.all_exist,
    }
    if omega is not None:
        out["omega"] = omega
    dyad_reports = {g.label: g for g in report.groups}
    for group in model.groups:
        sol = motion.solutions[group.label]
        item: dict[str, Any] = {"label": group.label, "name": group.name, "kind": group.kind,
                                "i": group.i, "j": group.j, "sigma": group.sigma,
                                "pairs": dict(group.pairs)}
        if group.label in dyad_reports:
            ex = dyad_reports[group.label]
            item["existence"] = {
                "verdict": ex.verdict, "delta": ex.delta, "min_margin": _nan(ex.min_margin),
                "condition": assur.CONDITIONS[group.kind],
                "intervals": [i.to_dict(crank) for i in ex.intervals],
                "evaluated": [bool(v) for v in ex.evaluated],
                "exists": [bool(v) for v in np.asarray(sol.exists).ravel()],
                "first_failing": [bool(v) for v in ex.fails],
                "margin": _floats(sol.margin), "reason": [int(v) for v in
                                                          np.asarray(sol.reason).ravel()]}
        out["groups"].append(item)
    for link in _moving_links(model):
        origin, angle = motion.frames[link]
        entry = _scalar(angle, omega, 1.0)
        entry["value"] = _floats(np.degrees(assur.unwrap(np.asarray(angle.v))))
        out["links"][str(link)] = {"angle_deg": entry, "origin": _xy(origin.v),
                                   "group": model.links[link][0]}
    for pid, z in motion.joints.items():
        entry = _point(z, omega)
        entry["links"] = list(model.pair_links[pid][1])
        out["joints"][str(pid)] = entry
    for pid, slider in motion.sliders.items():
        out["sliders"][str(pid)] = {
            "carrier": slider.carrier, "slider": slider.slider,
            "s": _scalar(slider.s, omega), "point": _xy(assur.values(slider.point)),
            "base": _xy(assur.values(slider.base)),
            "angle_deg": _floats(np.degrees(assur.values(slider.angle))),
            "offset": float(np.asarray(slider.offset))}
    for name, point in motion.tracing.items():
        entry = _point(point, omega)
        entry["link"] = next(t.anchor.link for t in model.tracing if t.name == name)
        out["tracing"][name] = entry
    out["pressure_angles"] = [
        {"group": p.label, "pair": p.pair, "binary_links": list(p.binary),
         "alpha_deg": _floats(np.degrees(p.alpha)), "max_deg": _nan(math.degrees(p.maximum))}
        for p in assur.pressure_angles(motion)]
    out["joint_rotations"] = [
        {"pair": r.pair, "links": list(r.links), "group": r.group, "full_turn": r.full_turn,
         "swing_deg": _nan(math.degrees(r.swing)), "theta_deg": _floats(np.degrees(r.theta))}
        for r in assur.joint_rotations(motion)]
    return out


def _nan(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


# ----------------------------------------------------------------------------------- CSV


def table_csv(motion: Any, report: Any, omega: float | None = None) -> str:
    """One row per position: input, joints, link angles, sliders, tracing points, existence."""
    model = motion.model
    crank = model.drive == "crank"
    columns: list[tuple[str, np.ndarray]] = [
        ("phi_deg" if crank else "actuator_mm", np.degrees(motion.q) if crank else motion.q)]

    def add(name: str, jet: Any, complex_: bool) -> None:
        parts = [("", jet.v), ("_d1", jet.d1), ("_d2", jet.d2)]
        if omega is not None:
            parts += [("_vel", assur.velocity(jet, omega)),
                      ("_acc", assur.acceleration(jet, omega))]
        for suffix, data in parts:
            data = np.broadcast_to(data, motion.q.shape)
            if complex_:
                columns.append((f"{name}_x{suffix}", data.real))
                columns.append((f"{name}_y{suffix}", data.imag))
            else:
                columns.append((f"{name}{suffix}", data))

    for pid, z in motion.joints.items():
        add(f"joint_{pid}", z, True)
    for link in _moving_links(model):
        angle = motion.frames[link][1]
        columns.append((f"link_{link}_deg", np.degrees(assur.unwrap(np.asarray(angle.v)))))
    for pid, slider in motion.sliders.items():
        add(f"slider_{pid}_s", slider.s, False)
    for name, point in motion.tracing.items():
        add(f"trace_{name}", point, True)
    for group in report.groups:
        columns.append((f"exists_{group.label}",
                        np.asarray(motion.solutions[group.label].exists, dtype=int)))
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([name for name, _ in columns])
    for row in zip(*(np.asarray(data).ravel() for _, data in columns)):
        writer.writerow(["" if isinstance(v, float) and not math.isfinite(v) else
                         (repr(float(v)) if isinstance(v, (float, np.floating)) else int(v))
                         for v in row])
    return buffer.getvalue()
