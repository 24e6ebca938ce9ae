"""The geometry of the profiles of a higher pair at one position: where two profiles touch,
how far apart they are, and the centres of curvature at the contact.

A profile is a :class:`~assur.model.CircleProfile` (a point for radius 0),
:class:`~assur.model.LineProfile` or :class:`~assur.model.PolarProfile` (a table of polar
radii, smooth between its nodes: a periodic cubic spline of the radius over the angle).
Points are complex numbers (mm), as everywhere in the program.

The gap of two profiles is signed: positive when they stand apart, negative when they cut
into each other; the sketch reader refuses a pair whose gap is larger than
:data:`TOUCH_TOLERANCE` either way. The centres of curvature at the contact are the joints
of the replacing mechanism (:mod:`assur.structure.replacing`); a straight profile has none
(None).

Examples
--------
An eccentric disc of radius 40 centred 15 mm right of its pivot, under a roller of radius
10 whose centre is 50 mm above the disc's centre:

>>> from assur.model import CircleProfile
>>> touch = contact(CircleProfile(15 + 0j, 40.0), CircleProfile(15 + 50j, 10.0))
>>> touch.gap, touch.point, touch.centres
(0.0, (15+40j), ((15+0j), (15+50j)))
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from assur.model import CircleProfile, GearMesh, LineProfile, PolarProfile, Profile

if TYPE_CHECKING:  # pragma: no cover
    from scipy.interpolate import CubicSpline

    from assur.typing import ComplexArray, FloatArray

__all__ = ["MIN_TABLE_NODES", "TOUCH_TOLERANCE", "Contact", "contact", "gear_contact",
           "pitch_circles", "polar_points", "radius_spline"]

#: Two profiles of the sketch farther apart, or cut into each other deeper, than this (mm)
#: do not touch.
TOUCH_TOLERANCE = 0.01
#: The fewest nodes of a profile table (a periodic cubic spline through them).
MIN_TABLE_NODES = 6
#: Samples of a tabulated profile in the search for the contact, before it is refined.
_SAMPLES = 4096
#: A curvature below this (1/mm) is a straight stretch of a tabulated profile.
_FLAT = 1e-12


@dataclass(frozen=True, slots=True)
class Contact:
    """Two profiles at one position.

    Attributes
    ----------
    gap : float
        mm: positive apart, negative cut into each other, 0 touching.
    point : complex
        The contact point (for a gap: the point of the first profile nearest the second).
    normal : complex
        The unit common normal at the contact, pointing from the first profile to the
        second.
    centres : tuple of two (complex or None)
        The centre of curvature of each profile at the contact; None for a straight one.
    """

    gap: float
    point: complex
    normal: complex
    centres: tuple[complex | None, complex | None]

    def swapped(self) -> Contact:
        """The same contact seen from the second profile."""
        return Contact(self.gap, self.point - self.gap * self.normal, -self.normal,
                       (self.centres[1], self.centres[0]))


def contact(first: Profile, second: Profile) -> Contact | None:
    """The contact of two profiles at the sketch.

    Parameters
    ----------
    first, second : Profile

    Returns
    -------
    Contact or None
        None for two profiles that cannot touch at one point: two straight lines, two
        tables, two concave circles, a concave circle with a line or a table.

    Examples
    --------
    A flat face 5 mm below a knife edge; a roller of radius 10 standing on the face:

    >>> from assur.model import Direction, LineProfile
    >>> face = LineProfile(0j, Direction(0.0, 1 + 0j))
    >>> contact(CircleProfile(5j, 0.0), face).gap
    5.0
    >>> contact(face, CircleProfile(3 + 10j, 10.0)).point
    (3+0j)
    """
    if isinstance(first, CircleProfile) and isinstance(second, CircleProfile):
        return None if first.concave and second.concave else _circles(first, second)
    if isinstance(second, CircleProfile):
        found = contact(second, first)
        return None if found is None else found.swapped()
    if isinstance(first, CircleProfile) and not first.concave:
        if isinstance(second, LineProfile):
            return _circle_line(first, second)
        return _circle_table(first, second)
    if isinstance(first, LineProfile) and isinstance(second, PolarProfile):
        return _line_table(first, second)
    if isinstance(first, PolarProfile) and isinstance(second, LineProfile):
        found = _line_table(second, first)
        return found.swapped()
    return None


def gear_contact(mesh: GearMesh, centres: tuple[complex, complex]) -> Contact:
    """The contact of two involute gears at the sketch, on the pitch point.

    The line of action passes through the pitch point P at the pressure angle α to the
    common tangent: its direction is the tangent ``i·e`` (``e`` the unit vector from the
    first gear's centre towards P) turned by −α. The centres of curvature of the two tooth
    profiles at the contact are the points N1, N2 where the line of action touches the base
    circles (radius r·cos α): the feet of the perpendiculars from the centres.

    Parameters
    ----------
    mesh : GearMesh
    centres : tuple of two complex
        The centres of the pitch circles at the sketch, in the order of the pair's links.

    Returns
    -------
    Contact
        ``point`` is P, ``normal`` the unit vector of the line of action, ``centres`` N1, N2.

    Examples
    --------
    >>> touch = gear_contact(GearMesh((30.0, 60.0)), (0j, 90 + 0j))
    >>> round(abs(touch.centres[0]), 9) == round(30 * math.cos(math.radians(20)), 9)
    True
    """
    first, second = pitch_circles(mesh, centres)
    touch = _circles(first, second)
    towards = (touch.point - centres[0]) / mesh.radii[0]
    line = 1j * towards * cmath.exp(-1j * math.radians(mesh.pressure_angle))
    feet = tuple(touch.point + line * _dot(line, centre - touch.point) for centre in centres)
    return Contact(touch.gap, touch.point, line, (feet[0], feet[1]))


def pitch_circles(mesh: GearMesh, centres: tuple[complex, complex]
                  ) -> tuple[CircleProfile, CircleProfile]:
    """The two pitch circles of a mesh about the given centres; the larger of an internal
    mesh is concave (the ring).

    >>> pitch_circles(GearMesh((20.0, 50.0), internal=True), (0j, 30 + 0j))[1].concave
    True
    """
    r1, r2 = mesh.radii
    return (CircleProfile(centres[0], r1, concave=mesh.internal and r1 > r2),
            CircleProfile(centres[1], r2, concave=mesh.internal and r2 > r1))


def polar_points(profile: PolarProfile, theta: FloatArray
                 ) -> tuple[ComplexArray, ComplexArray, ComplexArray]:
    """Points of a tabulated profile and their first and second derivatives over the polar
    angle (radians from the x-axis).

    Parameters
    ----------
    profile : PolarProfile
    theta : ndarray
        Polar angles, radians (any; the table is periodic).

    Returns
    -------
    tuple of three ndarray
        p, dp/dθ, d²p/dθ² (complex, mm).

    Examples
    --------
    A table of a constant radius is that circle:

    >>> table = PolarProfile(0j, tuple(range(0, 360, 45)), (20.0,) * 8)
    >>> p, dp, ddp = polar_points(table, np.array([0.3]))
    >>> bool(np.allclose([abs(p[0]), abs(dp[0]), abs(ddp[0])], 20.0))
    True
    """
    spline = radius_spline(profile.angles, profile.radii)
    start = float(spline.x[0])
    angle = start + np.mod(np.asarray(theta, dtype=float) - start, 2 * np.pi)
    r, dr, ddr = spline(angle), spline(angle, 1), spline(angle, 2)
    turn = np.exp(1j * angle)
    return (profile.centre + r * turn, (dr + 1j * r) * turn,
            (ddr - r + 2j * dr) * turn)


def radius_spline(angles: FloatArray | tuple[float, ...], radii: FloatArray | tuple[float, ...]
                  ) -> CubicSpline:
    """r(θ) of a tabulated profile: the periodic cubic spline through its table (angles in
    degrees, increasing and spanning less than a turn; radii in mm), over θ in radians from
    the first tabulated angle to one turn past it. It passes through every point of the
    table with r, r′ and r″ continuous round the whole profile (so the tangent and the
    curvature are continuous).

    Examples
    --------
    >>> spline = radius_spline((0.0, 90.0, 180.0, 270.0), (10.0, 20.0, 10.0, 20.0))
    >>> float(spline(np.pi / 2)), float(spline(2 * np.pi))
    (20.0, 10.0)
    """
    from scipy.interpolate import CubicSpline  # only a tabulated profile needs scipy

    nodes = np.radians(np.asarray(angles, dtype=float))
    r = np.asarray(radii, dtype=float)
    return CubicSpline(np.append(nodes, nodes[0] + 2 * np.pi), np.append(r, r[0]),
                       bc_type="periodic")


def _dot(a: complex, b: complex) -> float:
    return (a.conjugate() * b).real


def _cross(a: complex, b: complex) -> float:
    return (a.conjugate() * b).imag


def _unit(vector: complex, fallback: complex = 1 + 0j) -> complex:
    size = abs(vector)
    return vector / size if size > 0 else fallback


def _circles(first: CircleProfile, second: CircleProfile) -> Contact:
    """Two circles: outside each other, or one (concave) around the other."""
    apart = second.centre - first.centre
    e = _unit(apart)
    distance = abs(apart)
    if first.concave:  # the second inside the first
        gap = first.radius - second.radius - distance
        return Contact(gap, first.centre + first.radius * e, -e, (first.centre, second.centre))
    if second.concave:  # the first inside the second
        gap = second.radius - first.radius - distance
        return Contact(gap, first.centre - first.radius * e, -e,
                       (first.centre, second.centre))
    gap = distance - first.radius - second.radius
    return Contact(gap, first.centre + first.radius * e, e, (first.centre, second.centre))


def _circle_line(circle: CircleProfile, line: LineProfile) -> Contact:
    """A convex circle (or a point) and a straight line."""
    unit = line.direction.unit
    side = _cross(unit, circle.centre - line.point)
    towards = -1j * unit * math.copysign(1.0, side)  # from the circle's centre to the line
    return Contact(abs(side) - circle.radius, circle.centre + circle.radius * towards, towards,
                   (circle.centre, None))


def _circle_table(circle: CircleProfile, table: PolarProfile) -> Contact:
    """A convex circle (or a point) and a tabulated profile: the nearest point of the table to
    the circle's centre."""
    def distance(theta: FloatArray) -> FloatArray:
        return np.abs(polar_points(table, theta)[0] - circle.centre)

    theta = _minimum(distance)
    point, tangent, bend = (value[0] for value in polar_points(table, np.array([theta])))
    inside = _inside(table, circle.centre)
    reach = abs(point - circle.centre)
    gap = -(reach + circle.radius) if inside else reach - circle.radius
    normal = _unit(point - circle.centre, -1j * _unit(tangent))
    return Contact(gap, circle.centre + circle.radius * normal, normal,
                   (circle.centre, _curvature_centre(point, tangent, bend)))


def _inside(table: PolarProfile, point: complex) -> bool:
    """Whether a point lies inside a tabulated profile (star-shaped about its pole)."""
    offset = point - table.centre
    edge = polar_points(table, np.array([cmath.phase(offset)]))[0][0]
    return bool(abs(offset) < abs(edge - table.centre))


def _line_table(line: LineProfile, table: PolarProfile) -> Contact:
    """A straight line and a tabulated profile: the point of the table nearest the line, or
    deepest beyond it."""
    unit = line.direction.unit

    def side(theta: FloatArray) -> FloatArray:
        return np.imag(np.conj(unit) * (polar_points(table, theta)[0] - line.point))

    sides = side(np.linspace(0.0, 2 * np.pi, _SAMPLES, endpoint=False))
    sign = math.copysign(1.0, _cross(unit, table.centre - line.point))
    best = _minimum(lambda theta: sign * side(theta))
    point, tangent, bend = (value[0] for value in polar_points(table, np.array([best])))
    depth = sign * _cross(unit, point - line.point)
    crossing = bool(np.any(sides > 0) and np.any(sides < 0))
    gap = -min(float(np.max(sides)), float(-np.min(sides))) if crossing else depth
    towards = 1j * unit * sign  # from the line into the table's side
    return Contact(gap, point - depth * towards, towards,
                   (None, _curvature_centre(point, tangent, bend)))


def _minimum(function: Callable[[FloatArray], FloatArray]) -> float:
    """The polar angle where a function of the angle is smallest: the best of a dense
    sampling, refined by a bounded scalar search around it."""
    from scipy.optimize import minimize_scalar

    theta = np.linspace(0.0, 2 * np.pi, _SAMPLES, endpoint=False)
    best = float(theta[int(np.argmin(function(theta)))])
    step = 2 * np.pi / _SAMPLES
    found = minimize_scalar(lambda t: float(function(np.array([t]))[0]),
                            bounds=(best - step, best + step), method="bounded",
                            options={"xatol": 1e-12})
    return float(found.x)


def _curvature_centre(point: complex, tangent: complex, bend: complex) -> complex | None:
    """The centre of curvature of a curve at a point from its first two derivatives; None
    where it is straight."""
    speed = abs(tangent)
    curvature = _cross(tangent, bend) / speed ** 3
    if abs(curvature) < _FLAT:
        return None
    return point + 1j * tangent / speed / curvature
