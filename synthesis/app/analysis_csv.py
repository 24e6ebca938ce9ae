"""A kinematic analysis as a CSV table, one row per position (``assur analyze --csv``)."""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Sequence

import numpy as np

from assur import Jet
from assur.api import Analysis
from assur.kinematics.analysis import acceleration, unwrap, values, velocity
from assur.kinematics.jets import as_jet
from assur.records import INPUT_NAMES, moving_links

__all__ = ["analysis_csv"]


def analysis_csv(result: Analysis,
                 extra: Sequence[tuple[str, np.ndarray]] = ()) -> str:
    """One row per position: input, joints, link angles, sliders, tracing points, existence.

    Points give ``_x``/``_y`` columns; every quantity its value and its analogs (``_d1``,
    ``_d2``) and, when the analysis has an input speed, its velocity and acceleration
    (``_vel``, ``_acc``). A position where the mechanism does not assemble has empty cells.

    Parameters
    ----------
    result : Analysis
    extra : sequence of (name, values)
        More columns aligned with the positions (the force analysis), written last.

    Returns
    -------
    str
        The CSV text, a header line first.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> import assur
    >>> text = analysis_csv(assur.analyse(tables / "course_11_link.yaml", points=4))
    >>> lines = text.splitlines()
    >>> len(lines), lines[0].split(",")[:3], lines[2].split(",")[0]
    (5, ['phi_deg', 'joint_0-1_x', 'joint_0-1_y'], '90.0')
    """
    model, motion, omega = result.model, result.motion, result.omega
    q = motion.q
    columns: list[tuple[str, np.ndarray]] = [
        (f"{INPUT_NAMES.get(result.model.drive, 'actuator')}_{'deg' if result.crank else 'mm'}",
         np.degrees(q) if result.crank else q)]

    def add(name: str, jet: Jet, point: bool) -> None:
        parts = [("", jet.v), ("_d1", jet.d1), ("_d2", jet.d2)]
        if omega is not None:
            parts += [("_vel", velocity(jet, omega)), ("_acc", acceleration(jet, omega))]
        for suffix, data in parts:
            data = np.broadcast_to(data, q.shape)
            if point:
                columns.append((f"{name}_x{suffix}", data.real))
                columns.append((f"{name}_y{suffix}", data.imag))
            else:
                columns.append((f"{name}{suffix}", data))

    for pid, z in motion.joints.items():
        add(f"joint_{pid}", as_jet(z), True)
    for link in moving_links(model):
        columns.append((f"link_{link}_deg", np.degrees(unwrap(values(motion.frames[link][1])))))
    for pid, slider in motion.sliders.items():
        add(f"slider_{pid}_s", as_jet(slider.s), False)
    for name, point in motion.tracing.items():
        add(f"trace_{name}", as_jet(point), True)
    for group in result.existence.groups:
        columns.append((f"exists_{group.label}",
                        np.asarray(motion.solutions[group.label].exists, dtype=int)))
    columns += extra
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([name for name, _ in columns])
    for row in zip(*(np.asarray(data).ravel() for _, data in columns)):
        writer.writerow(["" if isinstance(v, float) and not math.isfinite(v) else
                         (repr(float(v)) if isinstance(v, (float, np.floating)) else int(v))
                         for v in row])
    return buffer.getvalue()
