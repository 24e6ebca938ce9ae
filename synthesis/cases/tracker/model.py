"""Kinematic model of the rhomboid orientation mechanism over the actuator's stroke.

The chain is declared as a table like any other mechanism (``mechanism.yaml`` beside this
module): base 4, short rocker 1 (the platform), coupler 2, long rocker 3, actuator cylinder 5
and rod 6; hinges A = 4–1, B = 1–2, D = 3–4, E = 4–5, the compound hinge C of 2, 3 and 6, and
the driven prismatic pair S = 5–6. The structural analysis freezes the driven pair into a
composite link of variable length ``s = |EC|`` (the input coordinate) and finds two RRR
dyads (``structure.md`` T21): ``II₁(3,{5,6})`` on the base hinges D and E, then
``II₁(1,2)`` on A and C. The kinematic model is built from a sketch of one pose and solved
over the stroke by :func:`assur.kinematics.analysis.analyse`, with analogs (derivatives with respect to ``s``).

The sketch pose has the long rocker at right angles to the base (angle ADC = 90°, inside
every stroke ``[b_min, 180° − b_min]``) and B on the kite branch: the mirror image of D in the
diagonal AC (the other assembly of the dyad (1, 2) is D itself). Coordinates: A at the
origin (the post), D at ``−l1`` and E at ``l5 − l1`` on the x axis, C above it. Angles in
radians, lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from assur import (
    Chain,
    Jet,
    KinematicModel,
    StructuralAnalysis,
    analyse_structure,
    build_model,
    input_grid,
    load_chain,
)
from assur.io.sketch import with_sketch
from assur.kinematics.analysis import analyse, unwrap, values
from assur.typing import BoolArray, ComplexArray, FloatArray

__all__ = ["CHAIN_TABLE", "TrackerMotion", "chain", "mechanism_model", "simulate", "sketch"]

CHAIN_TABLE = Path(__file__).with_name("mechanism.yaml")
"""The chain table of the mechanism."""


@lru_cache(maxsize=1)
def chain() -> Chain:
    """The chain read from :data:`CHAIN_TABLE`."""
    return load_chain(CHAIN_TABLE)


def sketch(l1: float, l2: float, l5: float, l_i: float, l_d: float) -> dict[str, Any]:
    """The ``geometry:`` section of one design: joint coordinates at the sketch pose.

    Parameters
    ----------
    l1, l2, l5 : float
        Short rocker (= base), coupler (= long rocker), ``|DE|``; mm.
    l_i, l_d : float
        Actuator length retracted and extended (the analysed stroke); mm.

    Returns
    -------
    dict
        Joint id → ``{point: [x, y]}`` (and ``direction`` for the actuator's slide), plus
        ``input: {stroke: [l_i, l_d]}``.
    """
    a, d, e = 0j, complex(-l1), complex(l5 - l1)
    c = d + 1j * l2
    axis = (c - a) / abs(c - a)
    b = a + axis * axis * np.conj(d - a)       # D mirrored in the diagonal AC
    def xy(z: complex) -> list[float]:
        return [float(z.real), float(z.imag)]

    return {"A": {"point": xy(a)}, "B": {"point": xy(b)}, "C": {"point": xy(c)},
            "D": {"point": xy(d)}, "E": {"point": xy(e)},
            "S": {"point": xy(e), "direction": xy(c - e)},
            "input": {"stroke": [float(l_i), float(l_d)]}}


def mechanism_model(l1: float, l2: float, l5: float, l_i: float,
                    l_d: float) -> tuple[StructuralAnalysis, KinematicModel]:
    """Structural analysis and kinematic model of one design (see :func:`sketch`)."""
    analysis = analyse_structure(with_sketch(chain(), sketch(l1, l2, l5, l_i, l_d)))
    return analysis, build_model(analysis)


@dataclass(frozen=True)
class TrackerMotion:
    """The mechanism over the actuator's stroke; arrays of shape ``(N,)``.

    Attributes
    ----------
    formula : str
        The structure formula found by the structural analysis.
    s : ndarray
        Actuator length ``|EC|`` (the input coordinate).
    a, b, c, d, e : ndarray, complex
        Joints (NaN where the chain does not assemble); A is the post.
    platform : ndarray
        Angle of the short rocker AB (the platform), unwrapped along the stroke.
    angle_b : ndarray
        Angle at B between BA and BC, in [0, π] (the patent's transmission angle b).
    angle_c : ndarray
        Angle at C between CE (actuator) and CD (long rocker), in [0, π].
    angle_adc : ndarray
        Angle ADC of the base and the long rocker, in [0, π].
    post_distance : ndarray
        Signed distance from A to the actuator's axis EC (positive: A on the right of E→C).
    lever_arm : ndarray
        ``ds/dφ``, the actuator's length change per radian of the platform: by virtual work,
        the torque on the platform per unit of actuator force (its effective lever arm).
    exists : ndarray of bool
        Every group assembles.
    margin : ndarray
        The smallest existence margin of the groups.
    """

    formula: str
    s: FloatArray
    a: ComplexArray
    b: ComplexArray
    c: ComplexArray
    d: ComplexArray
    e: ComplexArray
    platform: FloatArray
    angle_b: FloatArray
    angle_c: FloatArray
    angle_adc: FloatArray
    post_distance: FloatArray
    lever_arm: FloatArray
    exists: BoolArray
    margin: FloatArray

    @property
    def stroke(self) -> float:
        """Platform stroke: the range of the platform angle over the positions."""
        return float(np.ptp(self.platform))

    @property
    def transmission(self) -> FloatArray:
        """Transmission angles at B and C folded into [0, π/2]: shape ``(2, N)``."""
        both = np.stack([self.angle_b, self.angle_c])
        return np.minimum(both, np.pi - both)

    @property
    def min_clearance(self) -> float:
        """Smallest distance from the post to the actuator's axis over the stroke."""
        return float(np.abs(self.post_distance).min())


def _angle(p: ComplexArray, q: ComplexArray, r: ComplexArray) -> FloatArray:
    """Angle at q between q→p and q→r, in [0, π]."""
    return np.abs(np.angle((r - q) / (p - q)))


def simulate(l1: float, l2: float, l5: float, l_i: float, l_d: float, *,
             positions: int = 721) -> TrackerMotion:
    """Solve the mechanism over the actuator's stroke ``[l_i, l_d]``.

    Parameters
    ----------
    l1, l2, l5 : float
        Short rocker (= base), coupler (= long rocker), ``|DE|``; mm.
    l_i, l_d : float
        Actuator lengths at the two ends of the stroke; mm.
    positions : int
        Actuator lengths evenly spread over the stroke.

    Returns
    -------
    TrackerMotion
    """
    analysis, model = mechanism_model(l1, l2, l5, l_i, l_d)
    motion = analyse(model, input_grid(model, positions), analogs=True)
    joint = {key: values(motion.joints[pair.id]) for pair in analysis.chain.pairs
             for key in [pair.origin] if pair.type.value == "R"}
    a, b, c, d, e = (joint[name] for name in "ABCDE")
    platform = motion.link_angle(1)
    if not isinstance(platform, Jet):  # analogs=True always gives jets
        raise TypeError("the analysis returned no derivatives")
    with np.errstate(invalid="ignore", divide="ignore"):
        arm = c - e
        post = np.imag(np.conj(arm) * (a - e)) / np.abs(arm)
        margin = np.fmin.reduce([s.margin for s in motion.solutions.values()])
        return TrackerMotion(
            formula=analysis.formula, s=np.asarray(motion.q), a=a, b=b, c=c, d=d, e=e,
            platform=unwrap(platform.v), angle_b=_angle(a, b, c), angle_c=_angle(e, c, d),
            angle_adc=_angle(a, d, c), post_distance=-post, lever_arm=1.0 / platform.d1,
            exists=motion.exists, margin=margin)
