"""The contact of a higher pair's two profiles over the positions: cams, followers, gears.

A higher pair touches at one point K with a common normal n, and transmits a force along n
only (friction ignored). Each function here solves the contact at every position of the
input at once — positions shaped ``(N,)``, designs ``(D, 1)`` — with or without analogs
(the cam's pose given as :class:`~assur.kinematics.jets.Jet`\\ s gives the follower's
velocity and acceleration analogs exactly):

* **Circles** (an eccentric, a roller, a knife edge = a circle of radius 0). The centres of
  curvature of the two profiles are the centres of the circles, fixed on their links, so the
  replacing link joining them has a constant length (:func:`replacing_length`) and the
  replacement is exact at every position: a roller follower on an eccentric *is* a four-bar
  (rocking follower, :func:`~assur.kinematics.dyads.solve_rrr`) or a slider-crank
  (translating follower, :func:`~assur.kinematics.dyads.solve_rrp`) whose links are the
  centre distances (:func:`circle_follower`).
* **A circle on a straight line** (a flat-faced translating follower on an eccentric). The
  replacing link is hinged at the circle's centre and slides parallel to the face, at the
  circle's radius from it: an RPP dyad (:func:`~assur.kinematics.dyads.solve_rpp`,
  :func:`flat_follower`).
* **A tabulated closed profile** (:class:`PolarSpline`: radii over angles around a point of
  the cam). The table is interpolated by a periodic cubic spline and the contact is solved at
  every position (:func:`polar_follower`): the contact point, the normal, the curvature and
  its centre, the follower's coordinate; the analogs by implicit differentiation.
* **Gears**: two pitch circles rolling without slip turn at the fixed ratio
  (:func:`gear_angle`).

In a mechanism (:func:`assur.kinematics.build.with_contacts`) each higher pair's replacing
link is a member of a dyad: :class:`ExactContact` solves it by its kind (circles, lines),
:class:`CamContact` and :class:`GearContact` through the contact (a tabulated profile, a
mesh), and :func:`followers` gives each follower's coordinate with its analogs.

Existence is data, as for every group: a :class:`Contact` carries ``exists`` and a
:class:`~assur.kinematics.reasons.Reason` per position — the replacing dyad's own reasons,
:attr:`~Reason.UNDERCUT` (a roller passing over a concave part of the profile whose radius of
curvature is smaller than its own), :attr:`~Reason.PRESSURE_ANGLE` (beyond the allowed one),
:attr:`~Reason.CONTACT_LOST` (the follower's path never touches the profile; the force
analysis adds the positions where the contact force would have to pull,
:mod:`assur.forces.contact`).

References
----------
.. [1] Артоболевский И. И. Теория механизмов и машин. М.: Наука, 1988, §§ 8, 24
   (заменяющие механизмы высших пар; угол давления кулачковых механизмов).
.. [2] Uicker J. J., Pennock G. R., Shigley J. E. Theory of Machines and Mechanisms, 5th ed.
   Oxford, 2017, §§ 3.6 (equivalent linkages), 6.6–6.8 (cam pressure angle, radius of
   curvature, undercutting).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.dyads import DyadSolution, solve_rpp, solve_rrp, solve_rrr
from assur.kinematics.jets import Jet
from assur.kinematics.reasons import Reason
from assur.kinematics.rules import given, rules_of
from assur.model import LinkId, PairId
from assur.profiles import radius_spline
from assur.typing import BoolArray, FloatArray, Value

if TYPE_CHECKING:  # pragma: no cover
    from scipy.interpolate import CubicSpline

    from assur.kinematics.analysis import GroupSolution, Motion, State
    from assur.kinematics.model import GroupModel

__all__ = [
    "CamContact",
    "Contact",
    "ExactContact",
    "Follower",
    "GearContact",
    "PolarSpline",
    "Rocker",
    "Slider",
    "circle_follower",
    "flat_follower",
    "followers",
    "gear_angle",
    "polar_follower",
    "replacing_length",
]

#: Newton steps that polish a contact found on the sampled profile: the bracket is a sample
#: step, so a dozen steps reach round-off (bisection takes over where Newton would leave it).
_POLISH = 12

#: Profile samples per table node when the contact is searched for (at least ``_LEAST``).
_PER_NODE = 8
_LEAST = 720


class Slider(NamedTuple):
    """The path of a translating follower's point (the roller's centre, a knife's edge).

    Attributes
    ----------
    base : complex
        A point of the path (mm); the follower's coordinate ``s`` is measured from it.
    angle : float
        The path's direction u (rad, absolute), pointing away from the cam: the follower
        rests on the cam at the largest ``s`` where it touches.
    """

    base: Value
    angle: Value


class Rocker(NamedTuple):
    """The path of a rocking follower's point: a circle about the arm's pivot.

    Attributes
    ----------
    pivot : complex
        The arm's pivot on the frame (mm).
    arm : float
        The distance from the pivot to the roller's centre (mm).
    away : {+1, -1}
        The sense in which the arm turning leaves the cam: +1 counter-clockwise. The
        follower rests on the cam at the arm angle furthest that way where it touches.
    """

    pivot: Value
    arm: Value
    away: int = 1


class Contact(NamedTuple):
    """A higher pair's contact over the positions.

    Attributes
    ----------
    point : complex ndarray or Jet
        The contact point K (mm).
    normal : complex ndarray or Jet
        The unit common normal at K, from the cam (first profile) towards the follower.
    centre : complex ndarray or Jet
        The cam profile's centre of curvature at K, K − n/κ (mm; NaN where κ = 0): the hinge
        of the replacing link on the cam.
    curvature : ndarray
        The cam profile's signed curvature at K (1/mm; > 0 convex, < 0 concave).
    follower : ndarray or Jet
        The follower's coordinate: ``s`` along a :class:`Slider` path (mm), or the arm's
        angle on a :class:`Rocker` path (rad, absolute).
    centre_b : complex ndarray or Jet
        The follower's point on its path (the roller's centre), the replacing link's other
        hinge.
    pressure_angle : ndarray
        The angle between the normal and the velocity of the follower's point (rad, in
        [0, π/2]).
    exists : ndarray, bool
        Where the pair keeps its contact and every condition holds.
    reason : ndarray, int8
        0 where it exists, else a :class:`~assur.kinematics.reasons.Reason` code.
    """

    point: Value
    normal: Value
    centre: Value
    curvature: FloatArray
    follower: Value
    centre_b: Value
    pressure_angle: FloatArray
    exists: BoolArray
    reason: np.ndarray


@dataclass(frozen=True)
class PolarSpline:
    """A closed cam profile tabulated as polar radii over angles around a point of the cam.

    The profile is r(θ) in the cam's own frame (θ from its axis, counter-clockwise), read by
    a periodic cubic spline through the table: it passes through every tabulated point, is
    2π-periodic with its first and second derivatives continuous, so the tangent and the
    curvature (which needs r″) are continuous round the whole profile. A Fourier fit would
    be as smooth but would not pass through the table's points and rings near a steep
    rise; the spline's error is local to a table interval.

    Parameters
    ----------
    spline : scipy.interpolate.CubicSpline
        r(θ) in mm over θ in rad, ``bc_type='periodic'``.

    Examples
    --------
    >>> import numpy as np
    >>> angles = np.arange(0.0, 360.0, 10.0)
    >>> profile = PolarSpline.from_table(angles, 40.0 + 0.0 * angles)
    >>> round(float(profile.curvature(np.array(1.0))), 12)    # a circle of radius 40
    0.025
    """

    spline: CubicSpline

    @classmethod
    def from_table(cls, angles: FloatArray, radii: FloatArray) -> PolarSpline:
        """The profile through a table: angles in degrees (increasing, spanning less than
        a turn), radii in mm (positive)."""
        return cls(radius_spline(angles, radii))

    @property
    def nodes(self) -> int:
        """The number of tabulated points."""
        return len(self.spline.x) - 1

    def radius(self, theta: Value, order: int = 0) -> Value:
        """The ``order``-th derivative of r(θ) (mm/rad^order); a jet for a jet ``theta``.

        The spline is a cubic per interval, so its derivatives beyond the third are 0.
        """
        if not isinstance(theta, Jet):
            return self._derivative(theta, order)
        v = theta.v.real
        first = self._derivative(v, order + 1)
        return Jet(self._derivative(v, order), first * theta.d1,
                   self._derivative(v, order + 2) * theta.d1 ** 2 + first * theta.d2)

    def _derivative(self, theta: Value, order: int) -> np.ndarray:
        if order > 3:
            return np.zeros(np.shape(theta))
        return np.asarray(self.spline(theta, order))

    def local(self, theta: Value) -> tuple[Value, Value]:
        """The profile's point X(θ) and unit outward normal n(θ), in the cam's frame.

        With X = r·e^{iθ}, X′ = (r′ + i·r)·e^{iθ} runs counter-clockwise round the profile,
        so n = −i·X′/|X′| points out of the cam.
        """
        r, dr = self.radius(theta), self.radius(theta, 1)
        turn = J.expi(theta)
        tangent = (dr + 1j * r) * turn
        return r * turn, -1j * tangent / J.abs(tangent)

    def curvature(self, theta: FloatArray) -> FloatArray:
        """The signed curvature κ(θ) = (r² + 2r′² − r·r″)/(r² + r′²)^{3/2} (1/mm; > 0
        convex)."""
        r, dr, ddr = (np.asarray(self.radius(theta, k)) for k in range(3))
        curvature: FloatArray = (r * r + 2.0 * dr * dr - r * ddr) / (r * r + dr * dr) ** 1.5
        return curvature


def replacing_length(radius_a: float, radius_b: float, *, concave_a: bool = False,
                     concave_b: bool = False) -> float:
    """The length of the link replacing two circular profiles: the distance of their centres.

    Two touching circles keep their centres at the sum of their signed radii (a concave
    profile's radius counts negative): an eccentric of radius R and a roller r give R + r;
    a roller inside a circular groove of radius R gives R − r. A knife edge is a roller of
    radius 0.

    Parameters
    ----------
    radius_a, radius_b : float
        The radii (mm, ≥ 0).
    concave_a, concave_b : bool
        Whether the profile is the inside of its circle.

    Returns
    -------
    float
        The centre distance (mm); negative where the roller is larger than the concave
        circle it should run in (it cannot: an undercut).

    Raises
    ------
    ValueError
        For two concave profiles.

    Examples
    --------
    >>> replacing_length(40.0, 10.0), replacing_length(40.0, 10.0, concave_a=True)
    (50.0, 30.0)
    """
    if concave_a and concave_b:
        raise ValueError("two concave profiles cannot touch each other")
    if concave_a:
        return radius_a - radius_b
    if concave_b:
        return radius_b - radius_a
    return radius_a + radius_b


def circle_follower(centre: Value, radius: float, path: Slider | Rocker, roller: float = 0.0,
                    *, concave: bool = False, allowed: float = 0.5 * math.pi,
                    delta: float = 0.0) -> Contact:
    """A roller (or knife-edge) follower on a circular cam profile, by its exact replacement.

    The replacing link joins the circle's centre to the roller's centre at the constant
    length :func:`replacing_length`, so the follower is the last link of an RRR dyad (a
    rocking follower: the four-bar pivot–eccentric–link–arm) or an RRP dyad (a translating
    follower: the slider-crank), solved in closed form at every position.

    Parameters
    ----------
    centre : complex ndarray or Jet
        The circle's centre at every position (mm): a point fixed on the cam.
    radius : float
        The circle's radius R (mm).
    path : Slider or Rocker
        The path of the roller's centre.
    roller : float
        The roller's radius r (mm); 0 for a knife edge.
    concave : bool
        The profile is the inside of the circle (a groove): the roller runs inside it.
    allowed : float
        The largest pressure angle allowed (rad).
    delta : float
        The replacing dyad's assigned tolerance δ (:mod:`assur.kinematics.dyads`).

    Returns
    -------
    Contact
        NaN geometry where the dyad does not assemble (its own reason) or the roller is
        larger than the groove (:attr:`Reason.UNDERCUT`).

    Examples
    --------
    An eccentric of radius 40 mm whose centre is 10 mm from the shaft, under a radial
    translating roller follower of radius 10 mm: at the top the roller's centre is
    10 + 40 + 10 mm above the shaft.

    >>> import numpy as np
    >>> centre = 10.0 * np.exp(1j * np.radians([90.0, 0.0]))
    >>> contact = circle_follower(centre, 40.0, Slider(0j, np.pi / 2), 10.0)
    >>> print(np.round(contact.follower, 6), np.degrees(contact.pressure_angle).round(4))
    [60.       48.989795] [ 0.    11.537]
    """
    length = replacing_length(radius, roller, concave_a=concave)
    if length < 0.0:
        return _undercut(centre)
    with np.errstate(all="ignore"):
        if isinstance(path, Slider):
            solution = solve_rrp(centre, path.base, path.angle, 0.0, length, 1.0, delta)
            follower = solution.s_i
        else:
            solution = solve_rrr(centre, path.pivot, length, path.arm, -path.away, delta)
            follower = solution.angle_j
        towards = (solution.c - centre) / length
        normal = -towards if concave else towards
        point = centre + radius * towards
        curvature = np.full(np.shape(solution.exists), -1.0 / radius if concave else 1.0 / radius)
        return _contact(point, normal, centre, curvature, given(follower), solution.c, path,
                        solution.exists, solution.reason, allowed)


def flat_follower(centre: Value, radius: float, path: Slider, gamma: float = 0.5 * math.pi,
                  *, allowed: float = 0.5 * math.pi, delta: float = 0.0) -> Contact:
    """A translating flat-faced follower on a circular cam profile (an eccentric).

    The replacing link is hinged at the circle's centre C and slides, parallel to the face,
    in a guide of the follower through C: an RPP dyad whose internal point is where the
    line through C parallel to the face crosses the follower's path. The face itself lies R
    further from C, on the follower's side, so the follower's point on its path is R/|sin γ|
    ahead of that crossing.

    Parameters
    ----------
    centre : complex ndarray or Jet
        The circle's centre at every position (mm).
    radius : float
        The circle's radius R (mm).
    path : Slider
        The path of the follower's point where its face crosses the path; ``angle`` points
        away from the cam.
    gamma : float
        The angle from the path's direction to the face (rad); π/2 for a face square to
        the path.
    allowed : float
        The largest pressure angle allowed (rad); a face at γ has the constant pressure angle
        |π/2 − |γ||.
    delta : float
        The replacing dyad's assigned tolerance δ₅ (``|sin γ| >= δ``).

    Returns
    -------
    Contact
        ``follower`` is the coordinate of the follower's point along its path; ``centre_b``
        that point.

    Examples
    --------
    >>> import numpy as np
    >>> centre = 10.0 * np.exp(1j * np.radians([90.0, 0.0, 270.0]))
    >>> print(flat_follower(centre, 40.0, Slider(0j, np.pi / 2)).follower.round(6))
    [50. 40. 30.]
    """
    with np.errstate(all="ignore"):
        solution = solve_rpp(centre, gamma, path.base, path.angle, 0.0, delta)
        side = -1.0 if math.sin(gamma) > 0.0 else 1.0
        normal = side * 1j * J.expi(path.angle + gamma) + 0.0 * centre
        shift = radius / abs(math.sin(gamma))
        follower = given(solution.s_i) + shift
        reference = solution.c + shift * J.expi(path.angle)
        curvature = np.full(np.shape(solution.exists), 1.0 / radius)
        return _contact(centre + radius * normal, normal, centre, curvature, follower,
                        reference, path, solution.exists, solution.reason, allowed)


def polar_follower(profile: PolarSpline, origin: Value, angle: Value, path: Slider | Rocker,
                   roller: float = 0.0, *, allowed: float = 0.5 * math.pi) -> Contact:
    """A roller (or knife-edge) follower on a tabulated cam profile, solved at every position.

    Parameters
    ----------
    profile : PolarSpline
        r(θ) around the point of the cam given by ``origin``.
    origin : complex ndarray or Jet
        The profile's pole at every position (mm) — the cam's shaft for a disc cam.
    angle : ndarray or Jet
        The direction of the profile's θ = 0 at every position (rad, absolute).
    path : Slider or Rocker
        The path of the roller's centre.
    roller : float
        The roller's radius ρ (mm); 0 for a knife edge.
    allowed : float
        The largest pressure angle allowed (rad).

    Returns
    -------
    Contact
        Jets (the follower's analogs) where ``origin``, ``angle`` or the path are jets.

    Notes
    -----
    The roller's centre touching the profile at X(θ) is on the offset curve
    P(θ) = X(θ) + ρ·n(θ), turned with the cam. The follower rests where its path meets the
    offset curve furthest away from the cam (the largest ``s`` on a slider's path, the arm
    angle furthest in its ``away`` sense): that is where it touches without entering the
    cam, the position a brute-force search over the profile's points gives. The path's
    equation g(θ) = 0 (a slider: Im(ū·(P − b)) = 0; a rocker: (|P − F|² − L²)/(2L) = 0) is
    sampled over the profile (8 samples per table node, at least 720), its sign changes are
    the meeting points, and the outermost one is polished by a bracketed Newton iteration
    with dg/dθ, dP/dθ = X′·(1 + ρκ).

    The analogs come from implicit differentiation of g(θ(φ), φ) = 0, carried out on the
    jets: starting from the solved θ, two steps θ ← θ − g(θ, φ)/g_θ make the first and then
    the second derivative of θ exact (each step of this chord iteration in truncated power
    series gains one order), and the follower's coordinate follows from θ.

    A roller passing over a concave part of the profile whose radius of curvature is
    smaller than its own (1 + ρκ < 0, an undercut: the offset curve folds into a
    swallowtail there) bridges it, touching two points; the positions where its path still
    meets that part of the offset curve are reported as :attr:`Reason.UNDERCUT` — the follower
    does not follow the profile there. A path that never meets the offset curve is
    :attr:`Reason.CONTACT_LOST`.

    Examples
    --------
    A circle of radius 40 mm about the shaft keeps a roller of 10 mm at 50 mm:

    >>> import numpy as np
    >>> profile = PolarSpline.from_table(np.arange(0.0, 360.0, 15.0), np.full(24, 40.0))
    >>> contact = polar_follower(profile, 0j, np.radians([0.0, 33.0]), Slider(0j, 1.2), 10.0)
    >>> contact.follower.round(9), bool(contact.exists.all())
    (array([50., 50.]), True)
    """
    samples = max(_LEAST, _PER_NODE * profile.nodes)
    step = 2.0 * math.pi / samples
    grid: FloatArray = float(profile.spline.x[0]) + step * np.arange(samples, dtype=float)
    pose = _Pose(origin, angle, path)
    values = pose.values()
    with np.errstate(all="ignore"):
        best, found, undercut = _meetings(profile, roller, pose, grid)
        theta = np.where(found, _polish(profile, roller, values, grid[best], step), np.nan)
        solved: Value = theta
        if any(isinstance(v, Jet) for v in (origin, angle, *path[:2])):
            slope = _array(_derivative(_residual(profile, roller, values, Jet(theta, 1.0))))
            solved = Jet(theta)
            for _ in range(2):
                solved = solved - _residual(profile, roller, pose, solved) / slope
        x, n = profile.local(solved)
        point = pose.globally(x)
        normal = pose.rotor * n
        centre_b = point + roller * normal
        kappa = profile.curvature(theta)
        centre = values.globally(_array(x) - _array(n) / kappa)
        reason = np.where(found, np.where(undercut, Reason.UNDERCUT, Reason.ASSEMBLES),
                          Reason.CONTACT_LOST).astype(np.int8)
        return _contact(point, normal, centre, kappa, _coordinate(pose.path, centre_b),
                        centre_b, path, reason == 0, reason, allowed)


def _meetings(profile: PolarSpline, roller: float, pose: _Pose, grid: FloatArray
              ) -> tuple[np.ndarray, BoolArray, BoolArray]:
    """Where the follower's path meets the offset curve sampled at ``grid``, per position.

    Returns the sample after which the outermost meeting lies, whether there is one, and
    whether the path meets the offset curve where the roller cannot follow the profile (an
    undercut: 1 + ρκ < 0 on the side of the cam facing the follower).
    """
    sampled = pose.sampled()
    x, n = (_array(part) for part in profile.local(grid))
    offset = _array(sampled.globally(x + roller * n))
    g, rank = (_array(part) for part in _on_path(sampled.path, offset, sampled.origin))
    ahead = np.roll(g, -1, axis=-1)
    meets = np.isfinite(g) & np.isfinite(ahead) & ((g == 0.0) | (np.sign(g) != np.sign(ahead)))
    share = np.clip(g / (g - ahead), 0.0, 1.0)
    reach = np.where(meets, rank + share * (np.roll(rank, -1, axis=-1) - rank), -np.inf)
    facing = _facing(sampled.path, offset, _array(sampled.rotor) * n)
    concave = 1.0 + roller * profile.curvature(grid) < 0.0
    return (np.argmax(reach, axis=-1), meets.any(axis=-1),
            (meets & concave & facing).any(axis=-1))


@dataclass(frozen=True)
class ExactContact:
    """A higher pair of circles or a straight profile in a mechanism: the replacing link
    joins points fixed on the two links, so its group, solved by its own kind, moves exactly
    like the original over the cycle.

    Attributes
    ----------
    pair : pair id
        The higher pair.
    replacing : link id
        The replacing link, a member of the group.
    face : complex or None
        For a straight profile (a flat face), the unit normal of the contact from the cam
        towards the follower in the frame of the group's other member (the follower); None
        for two circles, whose normal is the replacing link itself.
    """

    pair: PairId
    replacing: LinkId
    face: complex | None = None

    def solve(self, state: State, group: GroupModel, q: Value) -> GroupSolution:
        """Solve the group by its kind (:mod:`assur.kinematics.rules`)."""
        return rules_of(group.group_kind).solve(state, group, q)


class Follower(NamedTuple):
    """The follower of a higher pair over the positions (:func:`followers`).

    Attributes
    ----------
    pair : pair id
        The higher pair.
    group : str
        The label of the group of its replacing link.
    link : link id
        The follower (the driven gear of a mesh): the group's other member.
    unit : {'mm', 'deg'}
        A slider's coordinate S along its guide (mm), or a rocking link's angle (degrees,
        continuous over the cycle).
    coordinate : Jet
        The coordinate with its first and second analogs (per radian of the input).
    normal : Jet or None
        The unit common normal at the contact, from the first link's side towards the
        follower's (the replacing link's axis); None where the replacing link slides along a
        straight profile.
    hinge : pair id
        The pair of the replacing link with the follower (its reaction carries the contact
        force).
    reason : ndarray, int8
        The group's reason per position (0 where the contact holds).
    """

    pair: PairId
    group: str
    link: LinkId
    unit: str
    coordinate: Jet
    normal: Jet | None
    hinge: PairId
    reason: np.ndarray


def followers(motion: Motion) -> list[Follower]:
    """The follower of every higher pair of an analysed mechanism (none without any).

    Parameters
    ----------
    motion : Motion
        Analysed with analogs.

    Returns
    -------
    list of Follower
        In the order of the groups.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/cam_table_roller.yaml"
    >>> follower, = followers(assur.analyse(table, points=36).motion)
    >>> follower.link, follower.unit, round(float(np.ptp(follower.coordinate.v)), 6)
    (3, 'mm', 10.0)
    """
    model = motion.model
    found = []
    for label, contact in model.contacts.items():
        group = model.group(label)
        link = next(member for member in group.members if member != contact.replacing)
        hinge = next(pair for pair, (_, links, _) in model.pair_links.items()
                     if set(links) == {link, contact.replacing})
        solution = motion.solutions[label]
        if group.guide_i is not None and group.i == link:
            unit, coordinate = "mm", J.as_jet(motion.sliders[group.pairs["P_i"]].s)
        else:
            angle = J.as_jet(motion.frames[link][1])
            unit = "deg"
            coordinate = Jet(np.degrees(_unwrapped(angle.v)), np.degrees(angle.d1),
                             np.degrees(angle.d2))
        if model.pair_links[hinge][0] != "P":  # along the replacing link K1 → K2
            normal: Jet | None = J.as_jet(J.expi(motion.frames[contact.replacing][1]))
        elif isinstance(contact, ExactContact) and contact.face is not None:  # a flat face
            normal = J.as_jet(J.expi(motion.frames[link][1])) * contact.face
        else:
            normal = None
        found.append(Follower(contact.pair, label, link, unit, coordinate, normal, hinge,
                              np.asarray(solution.reason)))
    return found


def _unwrapped(angle: np.ndarray) -> np.ndarray:
    """Angles continuous along the positions (the last axis)."""
    return np.unwrap(angle, axis=-1) if np.all(np.isfinite(angle)) else angle


@dataclass(frozen=True)
class CamContact:
    """A tabulated cam profile on a roller (or knife-edge) follower, in a mechanism.

    The replacing mechanism (:mod:`assur.structure.replacing`) holds for a tabulated profile
    at the sketched position only; over the cycle, the group made of the replacing link and
    the follower is solved through the contact instead (:meth:`solve`): a slider follower
    (an RRP dyad) or a rocking one (an RRR dyad).

    Attributes
    ----------
    pair : pair id
        The higher pair.
    cam : link id
        The link carrying the profile (solved by an earlier group).
    spline : PolarSpline
        The profile, θ from the x-axis at the sketched position.
    pole : complex
        The profile's pole in the cam's frame of the kinematics (mm).
    turn : float
        The cam frame's angle at the sketched position (rad).
    roller : float
        The roller's radius (mm; 0 a knife edge).
    replacing : link id
        The replacing link, a member of the group.
    away : int
        +1 where the follower's coordinate (the slider's ``S``, the arm's angle) grows away
        from the cam, else −1.
    """

    pair: PairId
    cam: LinkId
    spline: PolarSpline
    pole: complex
    turn: float
    roller: float
    replacing: LinkId
    away: int

    @property
    def excess(self) -> float:
        """How much the roller's radius exceeds the smallest radius of curvature of a
        concave part of the profile (mm; ≤ 0 when the roller follows every hollow)."""
        theta = np.linspace(0.0, 2.0 * math.pi, _LEAST * 8, endpoint=False)
        curvature = self.spline.curvature(theta)
        hollow = curvature[curvature < 0.0]
        return self.roller - float(np.min(-1.0 / hollow)) if hollow.size else -math.inf

    def shortfall(self, margin: float) -> tuple[float, str]:
        """The violated condition at a failing position, from its margin: an undercut's
        excess of the roller's radius over the hollow's radius of curvature (mm); NaN
        where the path does not touch the profile."""
        return (-margin * max(self.roller, 1.0) if margin > -1.0 else math.nan), "mm"

    def solve(self, state: State, group: GroupModel, q: Value) -> DyadSolution:
        """Solve the group (the replacing link and the follower) through the contact,
        writing its joints (the replacing link's hinges: the cam's centre of curvature and
        the roller's centre), slider and link frames into the analysis state."""
        origin, angle = state.frames[self.cam]
        rotor = J.expi(angle)
        pole = origin + self.pole * rotor
        roles, p = group.pairs, state.p
        if group.guide_i is not None:  # RRP: the follower slides, the replacing link is j
            base, theta, e = state.guide(group.guide_i)
            start = base + e * 1j * J.expi(theta)
            path: Slider | Rocker = Slider(start, theta if self.away > 0 else theta + math.pi)
        else:  # RRR: the follower rocks about its hinge
            side = "j" if group.i == self.replacing else "i"
            anchor = group.hinge_j if side == "j" else group.hinge_i
            assert anchor is not None
            path = Rocker(state.point(anchor), p(group.column(f"l_{side}")), self.away)
        contact = polar_follower(self.spline, pole, angle - self.turn, path, self.roller)
        b, centre, normal = contact.centre_b, contact.centre, contact.normal
        margin = np.where(contact.exists, 1.0, np.where(
            contact.reason == Reason.UNDERCUT, -self.excess / max(self.roller, 1.0), -1.0))
        if isinstance(path, Slider):
            assert group.guide_i is not None and group.j is not None
            s = J.real(J.conj(J.expi(theta)) * (b - start))
            state.joints.update({roles["C"]: b, roles["H_j"]: centre})
            state.slider(roles["P_i"], group.guide_i.carrier, group.i, b, s, base, theta, e)
            return DyadSolution(b, b, theta, centre, J.arg(normal), s, None, margin,
                                contact.exists, contact.reason)
        rocker = (path.pivot, contact.follower)
        ends = (centre, J.arg(normal))
        first, second = (ends, rocker) if group.i == self.replacing else (rocker, ends)
        hinges = {"H_i": first[0], "H_j": second[0]}
        state.joints.update({roles["C"]: b, **{roles[r]: z for r, z in hinges.items()}})
        return DyadSolution(b, first[0], first[1], second[0], second[1], None, None, margin,
                            contact.exists, contact.reason)


@dataclass(frozen=True)
class GearContact:
    """A gear mesh in a mechanism: the driven gear turns at the fixed ratio.

    The replacing link N₁N₂ of a mesh holds at the sketched position only (its ends, the
    points where the line of action touches the base circles, are fixed on the carrier,
    not on the gears); over the cycle the group of the replacing link and the driven gear
    is solved from the ratio (:meth:`solve`): the driven gear turns, relative to the
    carrier of the two axles, by ∓(r₁/r₂) times the driving gear's turn.

    Attributes
    ----------
    pair : pair id
        The higher pair.
    driver : link id
        The driving gear (solved by an earlier group).
    carrier : link id
        The link carrying the driven gear's axle (the frame for fixed axles).
    radii : (float, float)
        Pitch radii of the driving and the driven gear (mm).
    internal : bool
        An internal mesh.
    start : (float, float, float)
        The kinematic frame angles of the driver, the carrier and the driven gear at the
        sketched position (rad; the driven gear's with the group's convention: its axis
        from its axle to N₂).
    ends : (complex, complex)
        N₁ and N₂ in the carrier's frame of the kinematics (mm).
    replacing : link id
        The replacing link, a member of the group.
    """

    pair: PairId
    driver: LinkId
    carrier: LinkId
    radii: tuple[float, float]
    internal: bool
    start: tuple[float, float, float]
    ends: tuple[complex, complex]
    replacing: LinkId

    def solve(self, state: State, group: GroupModel, q: Value) -> DyadSolution:
        """Solve the group (the replacing link and the driven gear) from the gear ratio."""
        carrier = state.frames.get(self.carrier)
        origin, turn = carrier if carrier is not None else (0j, 0.0)
        rotor = J.expi(turn)
        n1, n2 = (origin + end * rotor for end in self.ends)
        relative = turn - self.start[1]
        driver = state.frames[self.driver][1] - self.start[0] - relative
        angle = gear_angle(driver, self.radii, internal=self.internal,
                           start=self.start[2] + relative)
        driven = group.hinge_j if group.i == self.replacing else group.hinge_i
        assert driven is not None
        axle = state.point(driven)
        link = (n1, J.arg(n2 - n1))
        gear = (axle, angle)
        first, second = (link, gear) if group.i == self.replacing else (gear, link)
        hinges = (n1, axle) if group.i == self.replacing else (axle, n1)
        roles = group.pairs
        state.joints.update({roles["C"]: n2, roles["H_i"]: hinges[0], roles["H_j"]: hinges[1]})
        shape = np.shape(J.value(n2 + 0.0 * J.value(angle)))
        return DyadSolution(n2, first[0], first[1], second[0], second[1], None, None,
                            np.ones(shape), np.ones(shape, bool), np.zeros(shape, np.int8))


def gear_angle(angle: Value, radii: tuple[float, float], *, internal: bool = False,
               start: Value = 0.0) -> Value:
    """The angle of the second of two meshing gears, from the rotation of the first.

    The pitch circles roll without slip: r₁·dφ₁ = ∓r₂·dφ₂, so the second gear turns at the
    fixed ratio ψ = start − (r₁/r₂)·φ (external mesh: the opposite sense), or
    ψ = start + (r₁/r₂)·φ (internal mesh: the same sense).

    Parameters
    ----------
    angle : ndarray or Jet
        The first gear's rotation φ from the reference position (rad).
    radii : (float, float)
        The pitch radii r₁, r₂ (mm).
    internal : bool
        An internal mesh (one gear's teeth inside a ring).
    start : float or ndarray
        The second gear's angle at the reference position (rad).

    Returns
    -------
    ndarray or Jet
        ψ (rad); a jet for a jet ``angle``.

    Examples
    --------
    >>> print(gear_angle(0.6, (20.0, 60.0)), gear_angle(0.6, (20.0, 60.0), internal=True))
    -0.19999999999999998 0.19999999999999998
    """
    ratio = radii[0] / radii[1]
    turned: Value = start + (ratio if internal else -ratio) * angle
    return turned


class _Pose(NamedTuple):
    """The cam's pose and the follower's path, values or jets."""

    origin: Value
    angle: Value
    path: Slider | Rocker

    @property
    def rotor(self) -> Value:
        return J.expi(self.angle)

    def globally(self, local: Value) -> Value:
        """A point of the cam's frame in the plane: origin + e^{i·angle}·local."""
        moved: Value = self.origin + self.rotor * local
        return moved

    def values(self) -> _Pose:
        """The plain values, without derivatives."""
        return self._mapped(_array)

    def sampled(self) -> _Pose:
        """The plain values with an axis added last, for the profile's samples."""
        return self._mapped(lambda x: _array(x)[..., None])

    def _mapped(self, change: Callable[[Value], np.ndarray]) -> _Pose:
        path = self.path
        return _Pose(change(self.origin), change(self.angle),
                     Slider(change(path.base), change(path.angle)) if isinstance(path, Slider)
                     else Rocker(change(path.pivot), change(path.arm), path.away))


def _array(x: Value) -> np.ndarray:
    """The plain values of a quantity (a jet's value) as an array."""
    return np.asarray(J.value(x))


def _derivative(x: Value) -> Value:
    """A jet's first derivative (0 for a plain value)."""
    return x.d1 if isinstance(x, Jet) else 0.0


def _on_path(path: Slider | Rocker, point: Value, origin: Value) -> tuple[Value, Value]:
    """The residual g of a point on the path (0 on it, mm) and how far along the path away
    from the cam it is (the quantity the follower's rest maximises)."""
    if isinstance(path, Slider):
        along = J.conj(J.expi(path.angle)) * (point - path.base)
        return J.imag(along), J.real(along)
    pivot, arm = path.pivot, path.arm
    arm_to = point - pivot
    cam = J.conj(origin - pivot)
    g = (J.real(arm_to * J.conj(arm_to)) - arm * arm) / (2.0 * arm)
    return g, path.away * J.arg(arm_to * cam)


def _coordinate(path: Slider | Rocker, point: Value) -> Value:
    """The follower's coordinate of its point on the path: ``s`` (mm) or the arm angle."""
    if isinstance(path, Slider):
        return J.real(J.conj(J.expi(path.angle)) * (point - path.base))
    return J.arg(point - path.pivot)


def _heading(path: Slider | Rocker, point: Value) -> Value:
    """The unit direction in which the follower's point leaves the cam."""
    if isinstance(path, Slider):
        return J.expi(path.angle)
    return path.away * 1j * (point - path.pivot) / path.arm


def _facing(path: Slider | Rocker, point: np.ndarray, normal: np.ndarray) -> BoolArray:
    """Where the profile's outward normal faces the follower (the near side of the cam)."""
    facing: BoolArray = np.real(np.conj(normal) * _array(_heading(path, point))) > 0.0
    return facing


def _residual(profile: PolarSpline, roller: float, pose: _Pose, theta: Value) -> Value:
    """g(θ) of the roller's centre touching the profile at θ, on the follower's path."""
    x, n = profile.local(theta)
    return _on_path(pose.path, pose.globally(x + roller * n), pose.origin)[0]


def _polish(profile: PolarSpline, roller: float, pose: _Pose, lo: FloatArray,
            step: float) -> FloatArray:
    """The root of g in [lo, lo + step] at every position: Newton, bisection where Newton
    would leave the bracket."""
    hi = lo + step
    g_lo = np.asarray(_residual(profile, roller, pose, lo))
    theta = lo + 0.5 * step
    for _ in range(_POLISH):
        g = _residual(profile, roller, pose, Jet(theta, 1.0, 0.0))
        assert isinstance(g, Jet)
        same = np.sign(g.v) == np.sign(g_lo)
        lo, g_lo, hi = np.where(same, theta, lo), np.where(same, g.v, g_lo), np.where(same, hi, theta)
        newton = theta - g.v / g.d1
        theta = np.where((newton >= lo) & (newton <= hi), newton, 0.5 * (lo + hi))
    return theta


def _undercut(centre: Value) -> Contact:
    """No contact anywhere: the roller is larger than the groove it should run in."""
    shape = np.shape(J.value(centre))
    nan = np.full(shape, np.nan)
    return Contact(nan + 0j, nan + 0j, nan + 0j, nan, nan, nan + 0j, nan,
                   np.zeros(shape, bool), np.full(shape, Reason.UNDERCUT, np.int8))


def _contact(point: Value, normal: Value, centre: Value, curvature: FloatArray,
             follower: Value, centre_b: Value, path: Slider | Rocker, exists: BoolArray,
             reason: np.ndarray, allowed: float) -> Contact:
    """The contact with its pressure angle; a pressure angle beyond ``allowed`` fails
    where nothing else does."""
    heading = np.asarray(J.value(_heading(path, J.value(centre_b))))
    cosine = np.abs(np.real(np.conj(np.asarray(J.value(normal))) * heading))
    pressure = np.arccos(np.minimum(cosine, 1.0))
    steep = np.asarray(exists) & (pressure > allowed)
    reason = np.where(steep, Reason.PRESSURE_ANGLE, reason).astype(np.int8)
    return Contact(point, normal, centre, np.asarray(curvature), follower, centre_b, pressure,
                   np.asarray(exists) & ~steep, reason)
