"""The ``general:`` section of a mechanism table → :class:`~assur.model.General`.

The section holds the input speed ``omega`` (``assur report`` takes it from there) and the
``allowable`` limits a synthesis result keeps from its problem (``method.md`` tables
2.7–2.11), which ``assur analyze`` judges the design against. It is read once, with the rest
of the table: an unknown key gets a did-you-mean, every value is checked against its range,
and every problem is listed with the others of the file.

Examples
--------
>>> from assur.io.reader import TableReader
>>> reader = TableReader.from_data({"general": {"omgea": 10, "allowable": [
...     {"links": [2, 3], "pressure_angle": 120}]}}, "t.yaml")
>>> read_general(reader.root())
General(omega=None, allowable=())
>>> for issue in reader.issues:
...     print(issue.text())
general: unknown key 'omgea'; did you mean 'omega'?
general.allowable[0] 'pressure_angle': must lie in (0, 90] degrees, or be 'default'; found 120
"""

from __future__ import annotations

from typing import Any

from assur.io.reader import MISSING, Node, is_number, normalise_id, positive
from assur.model import Allowable, General, LinkId
from assur.text import Message

__all__ = ["read_box", "read_general"]

_GENERAL = ("omega", "allowable")
_ALLOWABLE = ("links", "pressure_angle", "rotations", "workspace")
#: The largest allowable pressure angle, degrees.
_RIGHT_ANGLE = 90.0


def read_general(top: Node) -> General:
    """The ``general:`` section of a table (empty when absent or wrong, the latter recorded).

    Parameters
    ----------
    top : Node
        The top of the table; problems go to its reader.

    Returns
    -------
    General
    """
    node = top.child("general", _GENERAL, required=False)
    if node is None:
        return General()
    omega = node.get("omega", kind="number", required=False, default=None, check=positive)
    rows = [_allowable(row) for row in node.rows("allowable", _ALLOWABLE, required=False)]
    speed = None if omega is None or omega is MISSING else float(omega)
    return General(speed, tuple(row for row in rows if row is not None))


def _allowable(row: Node) -> Allowable | None:
    """One row of ``allowable``; None when a field is wrong (recorded)."""
    before = len(row.reader.issues)
    links = row.get("links", kind="list", check=_group_links)
    if row.mapping.get("pressure_angle") == "default":
        angle = None
    else:
        angle = row.get("pressure_angle", kind="number", required=False, default=None,
                        check=_pressure_angle)
    rotations: dict[str, float] = {}
    turns = row.child("rotations", required=False)
    if turns is not None:
        for joint in turns.mapping:
            value = turns.get(joint, kind="number", check=positive)
            if value is not MISSING:
                rotations[str(joint)] = float(value)
    box = read_box(row)
    if len(row.reader.issues) > before or MISSING in (links, angle):
        return None  # (a misspelt key reads as MISSING: reported when the row was read)
    ids: tuple[LinkId, ...] = tuple(normalise_id(v) for v in links)
    return Allowable(ids, None if angle is None else float(angle), rotations, box)


def _group_links(value: list[Any]) -> Message | None:
    """The rule of ``links``: the links of one group (``[i]``, ``[i, j]``, or a higher
    group's ``[2, 3, 4, 5]``), each once."""
    if value and all(isinstance(v, (int, str)) and not isinstance(v, bool)
                                    for v in value) \
            and len({normalise_id(v) for v in value}) == len(value):
        return None
    return Message("rule.group_links")


def _pressure_angle(value: float) -> Message | None:
    return None if 0 < value <= _RIGHT_ANGLE else Message("rule.pressure_angle")


def read_box(row: Node) -> tuple[float, float, float, float] | None:
    """The working-space box ``{x: [low, high], y: [low, high]}`` of a row, mm (None when
    absent or wrong, the latter recorded); a mechanism's ``general:`` and a problem's
    allowable limits read it alike."""
    node = row.child("workspace", ("x", "y"), required=False)
    if node is None:
        return None
    out: list[float] = []
    for axis in ("x", "y"):
        value = node.get(axis, kind="list")
        if value is MISSING:
            return None
        if len(value) != 2 or not all(map(is_number, value)) or value[0] >= value[1]:
            row.reader.problem(f"{node.location} {axis!r}", "problem.box", found=value)
            return None
        out.extend(float(v) for v in value)
    return out[0], out[1], out[2], out[3]
