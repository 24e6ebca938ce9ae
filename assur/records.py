"""An analysis as a JSON-ready record: what ``assur analyze --json`` prints
(:meth:`assur.api.Analysis.to_dict`).

Kinematics: every list is aligned with ``input.values``. Points are in mm; ``d1``/``d2`` are the
velocity and acceleration analogs (derivatives w.r.t. the input coordinate: per radian of
crank rotation, or per mm of actuator length); link angles are in degrees, their analogs in
rad/rad. Missing values (no assembly) are null.

Forces (``docs/forces.md`` §4): lists aligned with ``input.values``, null where a position is
not solved, with the reason beside it. Forces are in N (global axes, the force of a pair's
first listed link on its second), torques in N·m (counter-clockwise positive).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from assur.kinematics.analysis import acceleration, unwrap, values, velocity
from assur.kinematics.existence import CONDITIONS
from assur.kinematics.higher.kind import HigherGroupSolution
from assur.kinematics.jets import Jet, as_jet
from assur.kinematics.model import KinematicModel
from assur.kinematics.transmission import joint_rotations, pressure_angles
from assur.model import LinkId

if TYPE_CHECKING:  # pragma: no cover
    from assur.api import Analysis

__all__ = ["INPUT_NAMES", "analysis_record", "floats", "higher_item", "moving_links", "number"]

#: The name of the input coordinate in the JSON record, by the model's drive (an actuator's
#: length otherwise).
INPUT_NAMES = {"crank": "phi", "laws": "t", "slider": "slider_displacement"}

#: A JSON value of the record.
Record = dict[str, Any]


def higher_item(sol: object) -> Record:
    """The keys a triad or class IV group adds to its group entry: no σ, and its assembly
    modes at the sketch (``mode``: how many, the sign of det J of the drawn one, every mode
    with its angle in degrees, joints, margin and sign); nothing for a dyad.

    Parameters
    ----------
    sol : GroupSolution
        A group's solution in the motion.

    Returns
    -------
    dict
        The keys to add to the group's entry.
    """
    if not isinstance(sol, HigherGroupSolution):
        return {}
    modes = sol.modes()
    drawn = next((m for m in modes if m.drawn), None)
    return {"sigma": None, "mode": {
        "count_at_sketch": len(modes), "det_sign": drawn.det_sign if drawn else None,
        "modes": [{"angle_deg": math.degrees(m.angle), "drawn": m.drawn,
                   "margin": number(m.margin), "det_sign": m.det_sign,
                   "joints": {str(pid): [z.real, z.imag] for pid, z in m.joints.items()}}
                  for m in modes],
        **({"ends_deg": [number(math.degrees(v)) for v in np.ravel(sol.follow.ends)],
            "full_turn": not bool(np.ravel(sol.follow.overlap)[0])} if sol.follow.periodic
           else {"ends_mm": [number(v) for v in np.ravel(sol.follow.ends)]})}}


def number(value: float) -> float | None:
    """A float for JSON: None where it is not finite."""
    return float(value) if math.isfinite(value) else None


def floats(data: npt.ArrayLike) -> list[float | None]:
    return [number(v) for v in np.asarray(data, dtype=float).ravel()]


def _xy(z: npt.ArrayLike) -> Record:
    z = np.asarray(z)
    return {"x": floats(z.real), "y": floats(z.imag)}


def _derivatives(jet: Jet, omega: float | None, out: Record,
                 form: Callable[[npt.ArrayLike], Any]) -> Record:
    """``out`` with the analogs of ``jet`` and, given ``omega``, its velocity and
    acceleration, each written by ``form`` (points or numbers)."""
    out["d1"] = form(jet.d1)
    out["d2"] = form(jet.d2)
    if omega is not None:
        out["velocity"] = form(velocity(jet, omega))
        out["acceleration"] = form(acceleration(jet, omega))
    return out


def _point(jet: Jet, omega: float | None) -> Record:
    return _derivatives(jet, omega, _xy(jet.v), _xy)


def _scalar(jet: Jet, omega: float | None) -> Record:
    return _derivatives(jet, omega, {"value": floats(jet.v)}, floats)


def moving_links(model: KinematicModel) -> list[LinkId]:
    """The moving links in the order of their numbers (named links after numbered ones)."""
    return sorted(model.links, key=lambda link: (isinstance(link, str), str(link).zfill(6)))


def analysis_record(result: Analysis) -> Record:
    """Every position of an analysis as a JSON-ready mapping (without its forces).

    Parameters
    ----------
    result : Analysis

    Returns
    -------
    dict
        ``mechanism``, ``source``, ``drive``, ``direction``, ``input``, ``parameters``,
        ``groups`` (with their existence), ``links``, ``joints``, ``sliders``, ``tracing``,
        ``all_exist``, ``pressure_angles``, ``joint_rotations``; ``omega`` when given.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> tables = Path(assur.__file__).parents[1] / "input_tables"
    >>> record = analysis_record(assur.analyse(tables / "course_11_link.yaml", points=8))
    >>> record["input"]["values"][:3], record["all_exist"]
    ([0.0, 45.0, 90.0], True)
    """
    model, motion, report, omega = result.model, result.motion, result.existence, result.omega
    crank = result.crank
    out: Record = {
        "mechanism": model.name, "source": model.source, "drive": model.drive,
        "direction": model.direction,
        "input": {"name": INPUT_NAMES.get(model.drive, "actuator_length"),
                  "unit": "deg" if crank else "mm",
                  "values": floats(np.degrees(motion.q) if crank else motion.q)},
        "parameters": {name: float(np.asarray(v)) for name, v in model.params.items()},
        "groups": [], "links": {}, "joints": {}, "sliders": {}, "tracing": {},
        "all_exist": report.all_exist,
    }
    if omega is not None:
        out["omega"] = omega
    dyad_reports = {g.label: g for g in report.groups}
    for group in model.groups:
        sol = motion.solutions[group.label]
        item: Record = {"label": group.label, "name": group.name, "kind": group.kind,
                        "i": group.i, "j": group.j, "sigma": group.sigma,
                        "pairs": dict(group.pairs)}
        if group.label in dyad_reports:
            ex = dyad_reports[group.label]
            item["existence"] = {
                "verdict": ex.verdict, "delta": ex.delta, "min_margin": number(ex.min_margin),
                "condition": CONDITIONS[group.kind],
                "intervals": [i.to_dict(crank) for i in ex.intervals],
                "evaluated": [bool(v) for v in ex.evaluated],
                "exists": [bool(v) for v in np.asarray(sol.exists).ravel()],
                "first_failing": [bool(v) for v in ex.fails],
                "margin": floats(sol.margin),
                "reason": [int(v) for v in np.asarray(sol.reason).ravel()]}
        item.update(higher_item(sol))
        out["groups"].append(item)
    for link in moving_links(model):
        origin, angle = motion.frames[link]
        entry = _scalar(as_jet(angle), omega)
        entry["value"] = floats(np.degrees(unwrap(values(angle))))
        out["links"][str(link)] = {"angle_deg": entry, "origin": _xy(values(origin)),
                                   "group": model.links[link][0]}
    for pid, z in motion.joints.items():
        entry = _point(as_jet(z), omega)
        entry["links"] = list(model.pair_links[pid][1])
        out["joints"][str(pid)] = entry
    for pid, slider in motion.sliders.items():
        out["sliders"][str(pid)] = {
            "carrier": slider.carrier, "slider": slider.slider,
            "s": _scalar(as_jet(slider.s), omega), "point": _xy(values(slider.point)),
            "base": _xy(values(slider.base)),
            "angle_deg": floats(np.degrees(values(slider.angle))),
            "offset": float(np.asarray(slider.offset))}
    for name, point in motion.tracing.items():
        entry = _point(as_jet(point), omega)
        entry["link"] = next(t.anchor.link for t in model.tracing if t.name == name)
        out["tracing"][name] = entry
    out["pressure_angles"] = [
        {"group": p.label, "pair": p.pair, "binary_links": list(p.binary),
         "alpha_deg": floats(np.degrees(p.alpha)), "max_deg": number(math.degrees(p.maximum)),
         "allowed_deg": result.allowed_pressure[p.label]}
        for p in pressure_angles(motion)]
    out["joint_rotations"] = [
        {"pair": r.pair, "links": list(r.links), "group": r.group, "full_turn": r.full_turn,
         "swing_deg": number(math.degrees(r.swing)), "theta_deg": floats(np.degrees(r.theta))}
        for r in joint_rotations(motion)]
    return out

