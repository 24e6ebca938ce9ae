"""Force transmission and joint rotations: pressure angles (L1, L2) and relative rotations.

``method.md`` §2.7: the pressure angle is computed only at the internal revolute pair C of
L1 and L2 groups where a link of the group is a two-hinge rod (a binary link: no attachment
point of a later group and no guide for a later group on it):

* L1: ``α = arccos |sin(φ_i − φ_j)|`` (``|π/2 − μ|``, μ the transmission angle at C);
* L2 (rod j binary): ``α = arccos |cos(φ_j − θ)|``.

``method.md`` §2.8: every revolute joint between links a and b turns by
``θ_ab = φ_a − φ_b`` (unwrapped over the cycle; the frame angle is 0); its swing is
``max θ_ab − min θ_ab``. The crank pivot turns fully and is not checked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.analysis import Motion, unwrap
from assur.kinematics.model import KinematicModel
from assur.kinematics.rules import given, rules_of
from assur.model import LinkId, PairId
from assur.typing import FloatArray

__all__ = [
    "JointRotation",
    "PressureAngle",
    "binary_links",
    "joint_rotations",
    "pressure_angles",
]


@dataclass(frozen=True)
class PressureAngle:
    """Pressure angle at C of one L1/L2 group over the positions (radians)."""

    label: str
    pair: PairId
    binary: tuple[LinkId, ...]
    alpha: np.ndarray

    @property
    def maximum(self) -> float:
        """Largest pressure angle over the positions where the group assembles (radians)."""
        return float(np.nanmax(self.alpha)) if np.isfinite(self.alpha).any() else math.nan


@dataclass(frozen=True)
class JointRotation:
    """Relative rotation in one revolute joint over the positions (radians)."""

    pair: PairId
    links: tuple[LinkId, LinkId]
    group: str
    theta: np.ndarray
    full_turn: bool

    @property
    def swing(self) -> float:
        """``max θ_ab − min θ_ab`` over the positions (radians); 2π for a full-turn joint."""
        if self.full_turn:
            return 2 * math.pi
        if not np.isfinite(self.theta).any():
            return math.nan
        return float(np.nanmax(self.theta) - np.nanmin(self.theta))


def binary_links(model: KinematicModel) -> set[LinkId]:
    """Links of the dyads that are two-hinge rods (``method.md`` §2.7, binary test).

    A link is binary when no later group is hinged to it and no later group slides on a
    guide it carries.
    """
    loaded: set[LinkId] = set()
    for group in model.groups:
        for anchor in (group.hinge_i, group.hinge_j):
            if anchor is not None:
                loaded.add(anchor.link)
        for guide in (group.guide_i, group.guide_j):
            if guide is not None:
                loaded.add(guide.carrier)
    for group in model.groups:
        if loaded & set(group.composite):
            loaded |= set(group.composite)
    out: set[LinkId] = set()
    for group in model.groups:
        if group.group_kind.is_input:
            continue
        out |= {link for link in (group.i, group.j) if link is not None and link not in loaded}
    return out


def pressure_angles(motion: Motion) -> list[PressureAngle]:
    """Pressure angle at C of every L1 and L2 group with a two-hinge rod.

    Parameters
    ----------
    motion : Motion
        An analysis over the cycle.

    Returns
    -------
    list of PressureAngle
        One entry per group output pair where the angle is defined, radians per position.

    Examples
    --------
    At the sketch the four-bar's coupler BC points at 26.57° and the rocker DC at 82.87°, so
    the transmission angle is 56.31° and the pressure angle at C is 90° − 56.31° = 33.69°:

    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> import numpy as np
    >>> from assur.kinematics.analysis import analyse
    >>> angle = assur.pressure_angles(analyse(model, points=4))[0]
    >>> angle.pair, round(float(np.degrees(angle.alpha[0])), 2)
    ('C', 33.69)
    """
    model = motion.model
    binary = binary_links(model)
    out = []
    for group in model.groups:
        rule = rules_of(group.group_kind).pressure
        if rule is None:
            continue
        sol = motion.solutions[group.label]
        phi_i = np.asarray(J.value(sol.angle_i))
        phi_j = np.asarray(J.value(given(sol.angle_j)))
        with np.errstate(invalid="ignore"):
            rods, alpha = rule(group, binary, phi_i, phi_j)
        if not rods:
            continue
        out.append(PressureAngle(group.label, group.pairs["C"], rods, alpha))
    return out


def joint_rotations(motion: Motion) -> list[JointRotation]:
    """Relative rotation θ_ab(q) of every revolute joint, with its swing.

    Parameters
    ----------
    motion : Motion
        An analysis over the cycle.

    Returns
    -------
    list of JointRotation
        Per pair the relative rotation of its two links over the positions, and whether it
        turns fully.

    Examples
    --------
    The crank's pair A turns fully:

    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> model = assur.load_model(table)
    >>> from assur.kinematics.analysis import analyse
    >>> rotation = assur.joint_rotations(analyse(model, points=36))[0]
    >>> rotation.pair, rotation.full_turn
    ('A', True)
    """
    model = motion.model
    owner: dict[PairId, str] = {}
    for group in model.groups:
        for role, pid in group.pairs.items():
            if not role.startswith("P"):
                owner[pid] = group.label
    pivots = {g.pairs["H_i"] for g in model.groups if g.group_kind.is_input and "H_i" in g.pairs}
    out = []
    for pid, (ptype, links, _) in model.pair_links.items():
        if ptype != "R" or pid not in owner:
            continue
        a, b = links
        theta = _angle(motion, a) - _angle(motion, b)
        full = pid in pivots
        out.append(JointRotation(pid, (a, b), owner[pid], unwrap(theta), full))
    return out


def _angle(motion: Motion, link: LinkId) -> FloatArray:
    if link == motion.model.frame:
        return np.zeros(np.shape(motion.q))
    return np.asarray(J.value(motion.frames[link][1]))
