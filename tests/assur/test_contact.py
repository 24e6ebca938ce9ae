"""The contact of a higher pair (assur.kinematics.contact) against closed forms and brute force.

* an eccentric with a roller follower is a four-bar (rocking) or a slider-crank
  (translating) whose links are the centre distances: positions and analogs against those
  closed forms, written here;
* a tabulated profile: the follower's rest against a brute-force search over the densely
  sampled profile (the largest position where the roller touches a profile point), the
  analogs against the instantaneous replacing slider-crank (centre of curvature computed here);
* a geared five-bar against its closed form;
* existence: undercut, pressure angle, no contact.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from assur.api import Analysis
from assur.forces import ForceAnalysis
from assur.kinematics.analysis import Motion, values
from assur.kinematics.contact import (
    Contact,
    PolarSpline,
    Rocker,
    Slider,
    circle_follower,
    flat_follower,
    followers,
    gear_angle,
    polar_follower,
    replacing_length,
)
from assur.kinematics.dyads import solve_rrr
from assur.kinematics.jets import Jet
from assur.kinematics.reasons import Reason
from assur.kinematics.transmission import pressure_angles
from assur.typing import Value

PHI = np.radians(np.arange(0.0, 360.0, 5.0))


def _cam_centre(e: float, start: float) -> Jet:
    """The eccentric's centre turning about the shaft at the origin, with its analogs."""
    turn = np.exp(1j * (start + PHI))
    return Jet(e * turn, 1j * e * turn, -e * turn)


def _jet(x: Value) -> Jet:
    """A quantity solved with analogs."""
    assert isinstance(x, Jet)
    return x


def _solve2(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Real x, y with a·x + b·y = c (complex a, b, c), by Cramer's rule."""
    det = (a * np.conj(b)).imag
    return (c * np.conj(b)).imag / det, (a * np.conj(c)).imag / det


def _four_bar(centre: Jet, length: float, pivot: complex, arm: float, away: int
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Arm angle ψ and its analogs of the four-bar shaft–eccentric centre–roller–pivot.

    The roller's centre B is where the circle (C, length) meets the circle (pivot, arm), the
    one turned furthest in the ``away`` sense about the pivot; then C + ℓ·e^{iθ} = F + L·e^{iψ}
    differentiated once and twice gives two linear equations each for (θ′, ψ′), (θ″, ψ″).
    """
    c = centre.v
    d = np.abs(pivot - c)
    u = (pivot - c) / d
    a = (length ** 2 - arm ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(length ** 2 - a ** 2)
    candidates = [c + a * u + sign * h * 1j * u for sign in (1, -1)]
    ranks = [away * np.angle((b - pivot) * np.conj(c - pivot)) for b in candidates]
    b = np.where(ranks[0] > ranks[1], candidates[0], candidates[1])
    psi = np.angle(b - pivot)
    theta = np.angle(b - c)
    ei, ej = length * np.exp(1j * theta), arm * np.exp(1j * psi)
    t1, p1 = _solve2(1j * ei, -1j * ej, -centre.d1)
    _, p2 = _solve2(1j * ei, -1j * ej, -centre.d2 + ei * t1 ** 2 - ej * p1 ** 2)
    return psi, p1, p2


def _slider_crank(centre: Jet, length: float, base: complex, angle: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """s and its analogs of the roller's centre on a line: s = p + √(ℓ² − q²) with p, q the
    eccentric centre's coordinates along and across the line."""
    rot = np.exp(-1j * angle)
    p, q = ((centre.v - base) * rot).real, ((centre.v - base) * rot).imag
    p1, q1 = (centre.d1 * rot).real, (centre.d1 * rot).imag
    p2, q2 = (centre.d2 * rot).real, (centre.d2 * rot).imag
    w = np.sqrt(length ** 2 - q ** 2)
    return (p + w, p1 - q * q1 / w,
            p2 - (q1 ** 2 + q * q2) / w - q ** 2 * q1 ** 2 / w ** 3)


@pytest.mark.parametrize("away", [1, -1])
def test_eccentric_with_a_rocking_roller_is_its_four_bar(away: int) -> None:
    centre = _cam_centre(12.0, 0.3)
    pivot, arm = 95.0 + 40.0j, 70.0
    contact = circle_follower(centre, 40.0, Rocker(pivot, arm, away), 10.0)
    psi, psi1, psi2 = _four_bar(centre, 50.0, pivot, arm, away)
    assert contact.exists.all()
    follower = contact.follower
    assert isinstance(follower, Jet)
    for got, want in ((follower.v, psi), (follower.d1, psi1), (follower.d2, psi2)):
        assert np.max(np.abs(got - want)) * arm <= 1e-9
    roller = contact.centre_b
    assert isinstance(roller, Jet)
    assert np.max(np.abs(roller.v - (pivot + arm * np.exp(1j * psi)))) <= 1e-9
    # the contact is on the eccentric, the normal through both centres
    assert np.max(np.abs(np.abs(_jet(contact.point).v - centre.v) - 40.0)) <= 1e-9
    assert np.max(np.abs(np.abs(roller.v - _jet(contact.point).v) - 10.0)) <= 1e-9


def test_eccentric_with_a_translating_roller_is_its_slider_crank() -> None:
    centre = _cam_centre(15.0, 0.0)
    base, angle = 8.0 - 5.0j, 1.4
    contact = circle_follower(centre, 40.0, Slider(base, angle), 10.0)
    s, s1, s2 = _slider_crank(centre, 50.0, base, angle)
    follower = contact.follower
    assert isinstance(follower, Jet)
    for got, want in ((follower.v, s), (follower.d1, s1), (follower.d2, s2)):
        assert np.max(np.abs(got - want)) <= 1e-9


def test_flat_faced_follower_on_an_eccentric() -> None:
    """A face square to its path stays R beyond the centre's projection on the path:
    s = u·(C − b) + R; a face at γ: the line through C parallel to the face meets the path
    at s = (n·… ) — here checked against the distance from C to the face, which must be R."""
    centre = _cam_centre(15.0, 0.2)
    base, angle = 3.0 + 1.0j, 1.3
    square = flat_follower(centre, 40.0, Slider(base, angle))
    rot = np.exp(-1j * angle)
    for part in ("v", "d1", "d2"):
        want = (getattr(centre, part) * rot).real + (40.0 - (base * rot).real
                                                    if part == "v" else 0.0)
        assert np.max(np.abs(getattr(_jet(square.follower), part) - want)) <= 1e-9
    gamma = 1.2
    slanted = flat_follower(centre, 40.0, Slider(base, angle), gamma)
    face_point = base + _jet(slanted.follower).v * np.exp(1j * angle)
    face = np.exp(1j * (angle + gamma))
    distance = ((centre.v - face_point) * np.conj(face)).imag
    assert np.max(np.abs(np.abs(distance) - 40.0)) <= 1e-9
    assert np.allclose(slanted.pressure_angle, abs(math.pi / 2 - gamma))


# --- a tabulated profile ------------------------------------------------------------------

TABLE_ANGLES = np.arange(0.0, 360.0, 10.0)
TABLE_RADII = 40.0 + 9.0 * np.sin(np.radians(TABLE_ANGLES)) \
    + 3.0 * np.cos(np.radians(2 * TABLE_ANGLES))


def _spline(angles: np.ndarray, radii: np.ndarray) -> CubicSpline:
    theta = np.radians(angles)
    return CubicSpline(np.append(theta, theta[0] + 2 * math.pi), np.append(radii, radii[0]),
                       bc_type="periodic")


def _dense(spline: CubicSpline, start: np.ndarray, samples: int = 100_000) -> np.ndarray:
    """The profile's points in the plane, the cam turned by ``start``: shape (N, samples)."""
    theta = 2 * math.pi * np.arange(samples) / samples
    local = spline(theta) * np.exp(1j * theta)
    points: np.ndarray = np.exp(1j * start)[:, None] * local[None, :]
    return points


def _brute_slider(points: np.ndarray, roller: float, base: complex, angle: float
                  ) -> np.ndarray:
    """The largest s where a roller on the line touches one of the points (the nearest
    touching position coming down the path); for a knife edge (radius 0), the furthest
    crossing of the line with the polygon through the points."""
    rel = (points - base) * np.exp(-1j * angle)
    across = rel.imag
    if roller == 0.0:
        ahead = np.roll(rel, -1, axis=1)
        crosses = np.sign(across) != np.sign(ahead.imag)
        share = across / (across - ahead.imag)
        at = rel.real + share * (ahead.real - rel.real)
        knife: np.ndarray = np.where(crosses, at, -np.inf).max(axis=1)
        return knife
    reach = np.where(np.abs(across) <= roller,
                     rel.real + np.sqrt(np.maximum(roller ** 2 - across ** 2, 0.0)), -np.inf)
    rest: np.ndarray = reach.max(axis=1)
    return rest


def _brute_rocker(points: np.ndarray, roller: float, pivot: complex, arm: float, away: int,
                  cam: complex = 0j) -> np.ndarray:
    """The arm angle furthest ``away`` where the roller touches one of the points."""
    rel = points - pivot
    d = np.abs(rel)
    cosine = (arm ** 2 + d ** 2 - roller ** 2) / (2 * arm * d)
    beta = np.arccos(np.clip(cosine, -1.0, 1.0))
    ok = np.abs(cosine) <= 1.0
    ref = np.angle(cam - pivot)
    best = np.full(points.shape[0], -np.inf)
    for sign in (1, -1):
        psi = np.angle(rel) + sign * beta
        rank = away * np.angle(np.exp(1j * (psi - ref)))
        best = np.maximum(best, np.where(ok, rank, -np.inf).max(axis=1))
    return ref + away * best


@pytest.mark.parametrize("roller", [0.0, 12.0])
def test_tabulated_profile_against_a_brute_force_contact_search(roller: float) -> None:
    profile = PolarSpline.from_table(TABLE_ANGLES, TABLE_RADII)
    start = np.radians(np.arange(0.0, 360.0, 10.0))
    base, angle = 6.0 + 0.0j, 1.5
    contact = polar_follower(profile, 0j, start, Slider(base, angle), roller)
    want = _brute_slider(_dense(_spline(TABLE_ANGLES, TABLE_RADII), start), roller, base, angle)
    assert contact.exists.all()
    assert np.max(np.abs(np.asarray(contact.follower) - want)) <= 1e-6


def test_tabulated_profile_with_a_rocking_roller_against_brute_force() -> None:
    profile = PolarSpline.from_table(TABLE_ANGLES, TABLE_RADII)
    start = np.radians(np.arange(0.0, 360.0, 10.0))
    pivot, arm, roller = 80.0 + 60.0j, 75.0, 10.0
    contact = polar_follower(profile, 0j, start, Rocker(pivot, arm, 1), roller)
    want = _brute_rocker(_dense(_spline(TABLE_ANGLES, TABLE_RADII), start), roller, pivot,
                         arm, 1)
    assert np.max(np.abs(np.asarray(contact.follower) - want)) * arm <= 1e-6


def test_tabulated_analogs_equal_the_instantaneous_replacing_slider_crank() -> None:
    """At every position the follower moves, to the second order, like the slider-crank whose
    crank ends at the profile's centre of curvature at the contact and whose rod reaches the
    roller's centre (the replacing mechanism); the curvature is computed here from the
    spline's derivatives."""
    spline = _spline(TABLE_ANGLES, TABLE_RADII)
    profile = PolarSpline(spline)
    start = np.radians(np.arange(0.0, 360.0, 10.0))
    base, angle, roller = 6.0 + 0.0j, 1.5, 12.0
    turning = Jet(start, 1.0, 0.0)
    contact = polar_follower(profile, 0j, turning, Slider(base, angle), roller)
    point = _jet(contact.point).v
    theta = np.angle(point * np.exp(-1j * start))
    r, dr, ddr = spline(theta), spline(theta, 1), spline(theta, 2)
    radius = (r * r + dr * dr) ** 1.5 / (r * r + 2 * dr * dr - r * ddr)
    normal = (_jet(contact.centre_b).v - point) / roller
    curvature_centre = point - radius * normal
    centre = Jet(curvature_centre, 1j * curvature_centre, -curvature_centre)
    s, s1, s2 = _slider_crank(centre, radius + roller, base, angle)
    follower = _jet(contact.follower)
    assert np.max(np.abs(follower.v - s)) <= 1e-9
    assert np.max(np.abs(follower.d1 - s1)) <= 1e-7 * np.max(np.abs(s1))
    assert np.max(np.abs(follower.d2 - s2)) <= 1e-7 * np.max(np.abs(s2))


def test_a_tabulated_eccentric_follows_like_the_eccentric() -> None:
    """An eccentric tabulated as r(θ) = e·cos θ + √(R² − e² sin² θ) every 2°: the spline's
    follower stays within the interpolation error of the exact replacement."""
    e, radius = 10.0, 40.0
    angles = np.arange(0.0, 360.0, 2.0)
    t = np.radians(angles)
    profile = PolarSpline.from_table(angles, e * np.cos(t) + np.sqrt(radius ** 2
                                                                      - (e * np.sin(t)) ** 2))
    pivot, arm = 90.0 + 30.0j, 70.0
    tabulated = polar_follower(profile, 0j, PHI, Rocker(pivot, arm, -1), 10.0)
    exact = circle_follower(e * np.exp(1j * PHI), radius, Rocker(pivot, arm, -1), 10.0)
    assert np.max(np.abs(np.asarray(tabulated.follower) - exact.follower)) * arm <= 1e-4


def test_a_roller_larger_than_a_hollow_is_an_undercut() -> None:
    """A hollow of radius of curvature ≈ 8 mm at its bottom (θ = 180°): a roller of 5 mm
    follows it, one of 14 mm cannot; the undercut is reported while the hollow passes under
    the follower, and nowhere else."""
    angles = np.arange(0.0, 360.0, 2.0)
    t = np.radians(angles)
    radii = 40.0 - 4.0 * np.exp(-((t - math.pi) / 0.2) ** 2)
    profile = PolarSpline.from_table(angles, radii)
    spline = _spline(angles, radii)
    fine = np.linspace(0.0, 2 * math.pi, 20_001)
    r, dr, ddr = spline(fine), spline(fine, 1), spline(fine, 2)
    kappa = (r * r + 2 * dr * dr - r * ddr) / (r * r + dr * dr) ** 1.5
    smallest = float(1.0 / -kappa[kappa < 0].min())
    assert 5.0 < smallest < 14.0
    start = np.radians(np.arange(0.0, 360.0, 1.0))
    path = Slider(0j, math.pi / 2)
    small = polar_follower(profile, 0j, start, path, 5.0)
    assert (small.reason != Reason.UNDERCUT).all()
    large = polar_follower(profile, 0j, start, path, 14.0)
    flagged = np.degrees(start[large.reason == Reason.UNDERCUT])
    assert flagged.size
    # the hollow's bottom (θ = 180°) faces the follower (90°) when the cam has turned −90°
    assert 270.0 in flagged
    assert flagged.min() > 240.0 and flagged.max() < 300.0
    near = slice(240, 301, 3)  # the roller bridges the hollow: still where it rests
    want = _brute_slider(_dense(spline, start[near]), 14.0, 0j, math.pi / 2)
    assert np.max(np.abs(np.asarray(large.follower)[near] - want)) <= 1e-6


def test_pressure_angle_beyond_the_allowed_one() -> None:
    """A radial roller follower on an eccentric: sin α = e·|cos φ|/(R + r)."""
    e, length = 15.0, 50.0
    centre = e * np.exp(1j * PHI)
    allowed = math.radians(14.0)
    contact = circle_follower(centre, 40.0, Slider(0j, math.pi / 2), 10.0, allowed=allowed)
    alpha = np.arcsin(e * np.abs(np.cos(PHI)) / length)
    assert np.max(np.abs(contact.pressure_angle - alpha)) <= 1e-12
    steep = alpha > allowed
    assert steep.any() and not steep.all()
    assert (contact.reason[steep] == Reason.PRESSURE_ANGLE).all()
    assert (contact.reason[~steep] == 0).all()
    assert (contact.exists == ~steep).all()


def test_no_contact_where_the_path_misses_the_cam() -> None:
    profile = PolarSpline.from_table(TABLE_ANGLES, TABLE_RADII)
    contact = polar_follower(profile, 0j, PHI, Slider(80.0j, 0.0), 5.0)
    assert (contact.reason == Reason.CONTACT_LOST).all()
    assert np.isnan(np.asarray(contact.follower)).all()


def test_a_roller_larger_than_its_groove() -> None:
    assert replacing_length(40.0, 10.0, concave_a=True) == 30.0
    contact = circle_follower(10.0 * np.exp(1j * PHI), 8.0, Slider(0j, 1.0), 10.0,
                              concave=True)
    assert (contact.reason == Reason.UNDERCUT).all()


# --- gears ----------------------------------------------------------------------------------

def test_geared_five_bar_against_its_closed_form() -> None:
    """Two cranks on meshing gears (pitch radii 30, 45 mm, centres 75 mm apart) joined by two
    couplers: the second crank's angle is −(r₁/r₂)·φ + const, the coupler joint where the
    couplers' circles meet."""
    r1, r2 = 30.0, 45.0
    o1, o2 = 0j, 75.0 + 0j
    a1, a2, l1, l2 = 25.0, 35.0, 90.0, 80.0
    phi = Jet(PHI, 1.0, 0.0)
    psi = _jet(gear_angle(phi, (r1, r2), start=2.0))
    a = o1 + a1 * Jet(np.exp(1j * PHI), 1j * np.exp(1j * PHI), -np.exp(1j * PHI))
    turn = np.exp(1j * psi.v)
    b = o2 + a2 * Jet(turn, 1j * turn * psi.d1, -turn * psi.d1 ** 2)
    joint = _jet(solve_rrr(a, b, l1, l2, 1.0).c)
    # closed form
    psi_c = 2.0 - r1 / r2 * PHI
    pa, pb = o1 + a1 * np.exp(1j * PHI), o2 + a2 * np.exp(1j * psi_c)
    d = np.abs(pb - pa)
    u = (pb - pa) / d
    along = (l1 ** 2 - l2 ** 2 + d ** 2) / (2 * d)
    c = pa + along * u + np.sqrt(l1 ** 2 - along ** 2) * 1j * u
    assert np.max(np.abs(psi.v - psi_c)) <= 1e-12 and np.all(psi.d1 == -r1 / r2)
    assert np.max(np.abs(joint.v - c)) <= 1e-9
    # the joint's velocity analog: both couplers keep their lengths
    assert np.max(np.abs(((joint.v - pa) * np.conj(joint.d1 - a.d1)).real)) <= 1e-9
    assert np.max(np.abs(((joint.v - pb) * np.conj(joint.d1 - b.d1)).real)) <= 1e-9


# --- the contact force ----------------------------------------------------------------------

E, START, RADIUS, ROLLER = 12.0, 0.3, 40.0, 10.0
PIVOT, ARM = 95.0 + 40.0j, 70.0
G1, M1, I1 = 5.0 + 3.0j, 2.0, 0.004       # cam: centre of mass (sketch, mm), kg, kg·m²
M3, I3 = 1.5, 0.02                         # follower arm
MM = 1e-3


def _sketch() -> tuple[complex, complex, complex]:
    """The eccentric's centre, the roller's centre and the arm's centre of mass, sketched."""
    centre = E * np.exp(1j * START)
    psi = _four_bar(Jet(np.array([centre]), 0.0, 0.0), RADIUS + ROLLER, PIVOT, ARM, 1)[0][0]
    roller = PIVOT + ARM * np.exp(1j * psi)
    return centre, roller, PIVOT + 0.5 * (roller - PIVOT) + 4.0j


def _replacing_forces(phi: np.ndarray, torque: float, omega: float
                      ) -> tuple[Motion, Contact, ForceAnalysis]:
    """The replacing four-bar (shaft–eccentric–replacing link–arm) through the program:
    its motion, the contact, and its group-by-group kinetostatics."""
    from assur.forces import ForceData, Load, Mass, kinetostatics
    from assur.io.chain_table import chain_from_dict
    from assur.kinematics.analysis import analyse
    from assur.kinematics.build import build_model
    from assur.structure.analysis import analyse_structure

    centre, roller, g3 = _sketch()
    point = {"A": 0j, "B": centre, "C": roller, "D": PIVOT}
    chain = chain_from_dict({"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
        {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
        "inputs": [1]}, "geometry": {k: {"point": [z.real, z.imag]} for k, z in point.items()}})
    motion = analyse(build_model(analyse_structure(chain)), phi, analogs=True)
    data = ForceData({1: Mass(M1, G1, I1), 3: Mass(M3, g3, I3)}, (Load(3, torque=torque),),
                     -9.81j)
    contact = circle_follower(motion.joints["B"], RADIUS, Rocker(PIVOT, ARM, 1), ROLLER)
    return motion, contact, kinetostatics(motion, data, omega)


def _newton_euler(phi: np.ndarray, torque: float, omega: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The cam and the arm, each in Newton–Euler equilibrium with d'Alembert's forces, the
    contact force N along the normal through both centres (on the arm; −N on the cam),
    the shaft's and the pivot's reactions and the driving torque: six unknowns per position.

    Returns N (N), the driving torque (N·m) and the relative power balance."""
    _, roller_sk, g3_sk = _sketch()
    psi0 = np.angle(roller_sk - PIVOT)
    centre = E * np.exp(1j * (START + phi)) * MM
    psi, psi1, psi2 = _four_bar(_cam_centre_at(phi), RADIUS + ROLLER, PIVOT, ARM, 1)
    pivot = PIVOT * MM
    roller = pivot + ARM * MM * np.exp(1j * psi)
    normal = (roller - centre) / np.abs(roller - centre)
    g1 = G1 * MM * np.exp(1j * phi)
    a1 = -omega ** 2 * g1
    arm_g = (g3_sk - PIVOT) * MM * np.exp(1j * (psi - psi0))
    a3 = omega ** 2 * (1j * psi2 - psi1 ** 2) * arm_g
    eps3 = psi2 * omega ** 2
    grav = -9.81j

    def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        moment: np.ndarray = (np.conj(a) * b).imag
        return moment

    size = phi.size
    matrix = np.zeros((size, 6, 6))
    rhs = np.zeros((size, 6))
    load1, load3 = M1 * (grav - a1), M3 * (grav - a3)
    # unknowns: R1x, R1y, R3x, R3y, M, N
    matrix[:, 0, 0], matrix[:, 0, 5], rhs[:, 0] = 1, -normal.real, -load1.real
    matrix[:, 1, 1], matrix[:, 1, 5], rhs[:, 1] = 1, -normal.imag, -load1.imag
    matrix[:, 2, 4], matrix[:, 2, 5], rhs[:, 2] = 1, -cross(centre, normal), -cross(g1, load1)
    matrix[:, 3, 2], matrix[:, 3, 5], rhs[:, 3] = 1, normal.real, -load3.real
    matrix[:, 4, 3], matrix[:, 4, 5], rhs[:, 4] = 1, normal.imag, -load3.imag
    matrix[:, 5, 5] = cross(roller - pivot, normal)
    rhs[:, 5] = -(cross(arm_g, load3) - I3 * eps3 + torque)
    x = np.linalg.solve(matrix, rhs[..., None])[..., 0]
    driving, force = x[:, 4], x[:, 5]
    v1 = 1j * omega * g1
    v3 = 1j * omega * psi1 * arm_g
    terms = [driving * omega, (np.conj(v1) * load1).real, (np.conj(v3) * load3).real,
             (-I3 * eps3 + torque) * psi1 * omega]
    balance = sum(terms) / sum(np.abs(t) for t in terms)
    return force, driving, balance


def _cam_centre_at(phi: np.ndarray) -> Jet:
    turn = np.exp(1j * (START + phi))
    return Jet(E * turn, 1j * E * turn, -E * turn)


def test_contact_force_against_a_newton_euler_solve_of_the_whole_mechanism() -> None:
    from assur.forces.contact import contact_force

    torque, omega = -15.0, 30.0
    motion, contact, forces = _replacing_forces(PHI, torque, omega)
    # the replacing four-bar moves the roller like the contact solved on its own
    assert np.max(np.abs(_jet(motion.joints["C"]).v - _jet(contact.centre_b).v)) <= 1e-9
    result = contact_force(forces, "C", contact.normal, 3, contact.reason)
    force, driving, balance = _newton_euler(PHI, torque, omega)
    scale = np.max(np.abs(force))
    assert np.max(np.abs(result.normal - force)) <= 1e-9 * scale
    assert np.max(np.abs(result.tangential)) <= 1e-9 * scale
    assert np.max(np.abs(forces.driving - driving)) <= 1e-9 * np.max(np.abs(driving))
    assert np.max(np.abs(balance)) <= 1e-9
    assert np.max(np.abs(forces.power_balance / forces.power_scale)) <= 1e-9
    assert result.holds.all() and (force > 0).all()


def test_a_contact_lost_over_part_of_the_cycle_is_an_interval_with_its_reason() -> None:
    """A weak return torque at a high speed: the arm's inertia would need the cam to pull it
    over part of the turn. The interval's ends are where the Newton–Euler N crosses 0."""
    from scipy.optimize import brentq

    from assur.forces.contact import contact_force, lost_intervals

    torque, omega = -2.0, 40.0
    phi = np.radians(np.arange(0.0, 360.0, 1.0))
    _, contact, forces = _replacing_forces(phi, torque, omega)
    result = contact_force(forces, "C", contact.normal, 3, contact.reason)
    force = _newton_euler(phi, torque, omega)[0]
    assert ((force < 0) == (result.reason == Reason.CONTACT_LOST)).all()
    intervals = lost_intervals(phi, result.normal)
    assert intervals and all(i.reason == Reason.CONTACT_LOST for i in intervals)

    def n_at(x: float) -> float:
        return float(_newton_euler(np.array([x]), torque, omega)[0][0])

    changes = np.flatnonzero(np.sign(force) != np.sign(np.roll(force, -1)))
    roots = sorted(brentq(n_at, phi[k], phi[k] + math.radians(1.0), xtol=1e-13)
                   % (2 * math.pi) for k in changes)
    ends = sorted([i.start for i in intervals] + [i.end for i in intervals])
    assert len(ends) == len(roots)
    assert np.max(np.abs(np.array(ends) - roots)) <= math.radians(0.01)
    for interval in intervals:
        assert interval.shortfall == pytest.approx(force[force < 0].min(), rel=1e-9)


# --- through assur.analyse ------------------------------------------------------------------

TABLES = __import__("pathlib").Path(__file__).parents[2] / "input_tables"


def test_a_tabulated_cam_through_the_analysis_against_brute_force() -> None:
    """input_tables/cam_table_roller.yaml: the roller's centre (joint K2 of the replacing
    mechanism) on the vertical line through the shaft, against the brute-force search over
    the table's profile turned with the cam."""
    import yaml

    import assur

    result = assur.analyse(TABLES / "cam_table_roller.yaml", points=36)
    table = yaml.safe_load((TABLES / "cam_table_roller.yaml").read_text())
    profile = table["geometry"]["K"]["profiles"][0]["table"]
    spline = _spline(np.array(profile["angles"], float), np.array(profile["radii"], float))
    q = result.motion.q
    want = _brute_slider(_dense(spline, q), 10.0, 0j, math.pi / 2)
    roller = values(result.motion.joints["K2"])
    assert result.existence.all_exist
    assert np.max(np.abs(roller.real)) <= 1e-9
    assert np.max(np.abs(roller.imag - want)) <= 1e-6
    follower = result.motion.sliders["C"]
    assert np.max(np.abs(values(follower.point) - roller)) <= 1e-9


def test_the_text_report_gives_the_follower_s_travel_of_the_brute_force_search() -> None:
    """``assur analyze`` prints the follower's range; its Δ is the travel of the roller's
    centre that the brute-force search over the table's profile finds."""
    import re

    import yaml

    import assur
    from synthesis.app.analysis_text import analysis_text

    result = assur.analyse(TABLES / "cam_table_roller.yaml", points=36)
    table = yaml.safe_load((TABLES / "cam_table_roller.yaml").read_text())
    profile = table["geometry"]["K"]["profiles"][0]["table"]
    spline = _spline(np.array(profile["angles"], float), np.array(profile["radii"], float))
    want = _brute_slider(_dense(spline, result.motion.q), 10.0, 0j, math.pi / 2)
    line, = [line for line in analysis_text(result).splitlines()
             if "follower 3 of higher pair K" in line]
    travel = float(re.search(r"\(Δ ([0-9.]+)\)", line).group(1))
    assert travel == pytest.approx(float(np.ptp(want)), abs=1e-3)


def test_a_geared_five_bar_through_the_analysis_against_its_closed_form() -> None:
    """input_tables/geared_five_bar.yaml: gear 2 turns at −(30/60) of gear 1; the joint E
    where the couplers' circles meet, on the sketched side of B → C."""
    import assur

    result = assur.analyse(TABLES / "geared_five_bar.yaml", points=36)
    phi = result.motion.q
    b0, c0, d, e0 = 20j, 90 + 40j, 90 + 0j, 40 + 90j
    b = b0 * np.exp(1j * phi)
    c = d + (c0 - d) * np.exp(-0.5j * phi)
    l1, l2 = abs(e0 - b0), abs(e0 - c0)
    side = np.sign(((np.conj(c0 - b0)) * (e0 - b0)).imag)
    dist = np.abs(c - b)
    u = (c - b) / dist
    along = (l1 ** 2 - l2 ** 2 + dist ** 2) / (2 * dist)
    e = b + along * u + side * np.sqrt(l1 ** 2 - along ** 2) * 1j * u
    assert result.existence.all_exist
    for name, want in (("B", b), ("C", c), ("E", e)):
        assert np.max(np.abs(values(result.motion.joints[name]) - want)) <= 1e-9
    # the replacing link stays on the line of action, touching both base circles
    n1, n2 = values(result.motion.joints["G1"]), values(result.motion.joints["G2"])
    base = math.cos(math.radians(20.0))
    assert np.max(np.abs(np.abs(n1) - 30.0 * base)) <= 1e-9
    assert np.max(np.abs(np.abs(n2 - d) - 60.0 * base)) <= 1e-9
    assert np.max(np.abs((np.conj(n2 - n1) * n1).real)) <= 1e-9
    assert np.max(np.abs((np.conj(n2 - n1) * (n2 - d)).real)) <= 1e-9
    assert np.ptp(n1) == 0 and np.ptp(n2) == 0
    # the mesh's pressure angle is its own, not that of a rod
    assert [angle.label for angle in pressure_angles(result.motion)] == ["L1(3,4)"]


def test_the_contact_force_of_a_table_with_a_higher_pair_through_the_analysis() -> None:
    """The eccentric and its rocking roller entered as a chain with a higher pair K (the
    roller 2 on its pin B, a passive degree of freedom), analysed with its forces by
    assur.analyse: the reaction of the replacing link on the arm along the normal K1 → K2 is
    the Newton–Euler contact force, and the driving torque the Newton–Euler one."""
    from assur.forces.contact import contact_force

    result = _analysed_with_a_higher_pair(-15.0, 30.0)
    assert result.forces is not None
    joints = result.motion.joints
    k1, k2 = values(joints["K1"]), values(joints["K2"])
    normal = (k2 - k1) / np.abs(k2 - k1)
    force = contact_force(result.forces, "K2", normal, 3)
    want, driving, _ = _newton_euler(result.motion.q, -15.0, 30.0)
    assert np.max(np.abs(force.normal - want)) <= 1e-9 * np.max(np.abs(want))
    assert np.max(np.abs(result.forces.driving - driving)) <= 1e-9 * np.max(np.abs(driving))
    record = result.to_dict()
    assert record["forces"]["contacts"]["K"]["lost"] == []
    assert np.allclose(record["forces"]["contacts"]["K"]["normal"], want, rtol=1e-9, atol=0)


def test_the_analysis_reports_the_follower_and_where_its_contact_is_lost() -> None:
    """The same table under a weak return torque at a high speed: the JSON of the analysis
    gives the arm's angle with its analogs (against the four-bar's closed form) and the
    interval where the contact is lost, its ends the zeros of the Newton–Euler force."""
    from scipy.optimize import brentq

    torque, omega = -2.0, 40.0
    record = _analysed_with_a_higher_pair(torque, omega).to_dict()
    phi = np.radians(record["input"]["values"])
    contact, = record["contacts"]
    psi, psi1, psi2 = _four_bar(_cam_centre_at(phi), RADIUS + ROLLER, PIVOT, ARM, 1)
    assert (contact["pair"], contact["follower"], contact["unit"]) == ("K", 3, "deg")
    got = contact["coordinate"]
    turn = np.degrees(np.angle(np.exp(1j * (np.radians(got["value"]) - psi))))
    assert np.max(np.abs(turn)) * ARM <= 1e-9
    assert np.max(np.abs(np.radians(got["d1"]) - psi1)) * ARM <= 1e-9
    assert np.max(np.abs(np.radians(got["d2"]) - psi2)) * ARM <= 1e-9
    lost = record["forces"]["contacts"]["K"]["lost"]
    assert len(lost) == 1 and lost[0]["reason"] == Reason.CONTACT_LOST
    assert lost[0]["condition"].startswith("contact lost")
    force = _newton_euler(phi, torque, omega)[0]

    def n_at(x: float) -> float:
        return float(_newton_euler(np.array([x]), torque, omega)[0][0])

    step = phi[1] - phi[0]
    roots = [math.degrees(brentq(n_at, phi[k], phi[k] + step, xtol=1e-13))
             for k in np.flatnonzero(np.sign(force) != np.sign(np.roll(force, -1)))]
    start, end = lost[0]["start"], lost[0]["end"]
    assert min(abs(start - r) for r in roots) <= 0.05
    assert min(abs(end - r) for r in roots) <= 0.05


def _analysed_with_a_higher_pair(torque: float, omega: float) -> Analysis:
    """The eccentric with its rocking roller as a table with a higher pair, analysed with
    its forces over 360 positions."""
    import assur
    from assur.io.chain_table import chain_from_dict

    centre, roller, g3 = _sketch()

    def xy(z: complex) -> list[float]:
        return [z.real, z.imag]

    chain = chain_from_dict({
        "mechanism": {"pairs": [
            {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [2, 3]},
            {"id": "D", "type": "R", "links": [3, 0]}, {"id": "K", "type": "H", "links": [1, 2]}],
            "inputs": [1]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": xy(roller)},
                     "D": {"point": xy(PIVOT)},
                     "K": {"profiles": [{"circle": {"centre": xy(centre), "radius": RADIUS}},
                                        {"circle": {"centre": xy(roller), "radius": ROLLER}}]}},
        "masses": {1: {"mass": M1, "centre": xy(G1), "inertia": I1},
                   3: {"mass": M3, "centre": xy(g3), "inertia": I3}},
        "loads": [{"link": 3, "torque": torque}], "gravity": [0, -9.81]})
    return assur.analyse(chain, points=360, forces=True, omega=omega)


def test_an_undercut_through_the_analysis_is_an_interval_with_its_excess() -> None:
    """A disc cam with a hollow (its tightest radius of curvature computed here) under a
    translating roller larger than it: the existence report gives the interval where the
    hollow passes under the roller, reason 13, and by how much the roller is too large."""
    import assur
    from assur.io.chain_table import chain_from_dict

    angles = np.arange(0.0, 360.0, 5.0)
    t = np.radians(angles)
    radii = 40.0 - 4.0 * np.exp(-((t - math.pi) / 0.2) ** 2)
    chain = chain_from_dict({"mechanism": {"pairs": [
        {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [2, 3]},
        {"id": "C", "type": "P", "links": [3, 0], "guide": 0},
        {"id": "K", "type": "H", "links": [1, 2]}], "inputs": [1]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": [0, 54]},
                     "C": {"point": [0, 90], "direction": 90},
                     "K": {"profiles": [{"table": {"centre": [0, 0], "angles": angles.tolist(),
                                                   "radii": radii.tolist()}},
                                        {"circle": {"centre": [0, 54], "radius": 14}}]}}})
    result = assur.analyse(chain, points=360)
    spline = _spline(angles, radii)
    fine = np.linspace(0.0, 2 * math.pi, 200_001)
    r, dr, ddr = spline(fine), spline(fine, 1), spline(fine, 2)
    kappa = (r * r + 2 * dr * dr - r * ddr) / (r * r + dr * dr) ** 1.5
    tightest = float(np.min(-1.0 / kappa[kappa < 0]))
    group, = result.existence.groups
    interval, = group.intervals
    assert interval.reason == Reason.UNDERCUT
    assert interval.shortfall == pytest.approx(14.0 - tightest, abs=1e-6)
    start, end = math.degrees(interval.start), math.degrees(interval.end)
    assert 240.0 < start < 270.0 < end < 300.0


def test_the_contact_force_of_a_tabulated_cam_on_its_translating_follower() -> None:
    """input_tables/cam_table_roller.yaml with a mass and a load on the follower: along its
    guide the follower is in equilibrium under the contact force N·n, its weight, the load
    and its inertia −m·s″·ω² (s″ checked against the replacing slider-crank above), so
    N = (m·s″·ω² − m·g_u − F_u)/(n·u); the power balance holds."""
    import yaml

    import assur
    from assur.forces.contact import contact_forces
    from assur.io.chain_table import chain_from_dict

    table = yaml.safe_load((TABLES / "cam_table_roller.yaml").read_text())
    mass, load, omega = 0.5, -20.0, 40.0
    table["masses"] = {3: {"mass": mass, "centre": [0, 70], "inertia": 1e-4}}
    table["loads"] = [{"link": 3, "force": [0, load], "point": [0, 70]}]
    table["gravity"] = [0, -9.81]
    result = assur.analyse(chain_from_dict(table), points=72, forces=True, omega=omega)
    assert result.forces is not None
    follower, = followers(result.motion)
    force = contact_forces(result.motion, result.forces)["K"]
    s2 = follower.coordinate.d2 * MM  # along the guide's direction, upwards
    assert follower.normal is not None
    normal = follower.normal.v
    want = (mass * s2 * omega ** 2 + mass * 9.81 - load) / normal.imag
    assert np.max(np.abs(force.normal - want)) <= 1e-9 * np.max(np.abs(want))
    assert np.max(np.abs(force.tangential)) <= 1e-9 * np.max(np.abs(want))
    power = result.forces
    assert np.max(np.abs(power.power_balance)) <= 1e-9 * np.max(np.abs(power.power_scale))


def test_the_tooth_force_of_a_gear_pair_by_hand() -> None:
    """Two gears on fixed axles (pitch radii 30, 60 mm, 20°), a torque of −6 N·m on the
    driven one, statically: the driving torque is −T·ψ′ = −(−6)·(−½) = −3 N·m, and the
    tooth force along the line of action has the moment T about the driven axle: its size
    is |T|/(60·cos 20° mm)."""
    import assur
    from assur.forces.contact import contact_forces
    from assur.io.chain_table import chain_from_dict

    chain = chain_from_dict({
        "mechanism": {"pairs": [
            {"id": "A", "type": "R", "links": [0, 1]}, {"id": "D", "type": "R", "links": [0, 2]},
            {"id": "G", "type": "H", "links": [1, 2], "gear": {"radii": [30, 60]}}],
            "inputs": [1]},
        "geometry": {"A": {"point": [0, 0]}, "D": {"point": [90, 0]},
                     "G": {"centres": [[0, 0], [90, 0]]}},
        "loads": [{"link": 2, "torque": -6.0}]})
    result = assur.analyse(chain, points=24, forces=True, omega=0.0)
    assert result.forces is not None
    assert np.max(np.abs(result.forces.driving + 3.0)) <= 1e-12
    assert np.max(np.abs(result.forces.driving_lever + 3.0)) <= 1e-12  # by the power
    force = contact_forces(result.motion, result.forces)["G"]
    size = 6.0 / (60.0 * math.cos(math.radians(20.0)) * MM)
    assert np.max(np.abs(np.abs(force.normal) - size)) <= 1e-9 * size
    assert np.max(np.abs(force.tangential)) <= 1e-9 * size


def test_the_normal_force_on_a_flat_faced_follower_by_newton_s_second_law() -> None:
    """An eccentric (centre 15 mm from the shaft, radius 40) under a flat-faced follower of
    2 kg sliding in a vertical guide, the face horizontal, under gravity, at ω = 10 rad/s:
    the follower rises as y = 15 sin φ mm, so the face pushes it with N = m (g + ÿ) =
    2 (9.81 − 0.015·ω² sin φ) N, along the face's normal, and nothing across it."""
    import yaml

    import assur
    from assur.forces.contact import contact_forces
    from assur.io.chain_table import chain_from_dict

    data = yaml.safe_load((TABLES / "cam_eccentric_flat.yaml").read_text(encoding="utf-8"))
    data["masses"] = {2: {"mass": 2.0, "centre": [0.0, 80.0], "inertia": 0.0}}
    data["gravity"] = [0, -9.81]
    chain = chain_from_dict(data)
    result = assur.analyse(chain, points=72, forces=True, omega=10.0)
    assert result.forces is not None
    q = result.motion.q
    assert np.max(np.abs(values(result.motion.joints["K1"]) - 15.0 * np.exp(1j * q))) <= 1e-9
    want = 2.0 * (9.81 - 0.015 * 10.0 ** 2 * np.sin(q))
    found = contact_forces(result.motion, result.forces)["K"]
    assert np.max(np.abs(found.normal - want)) <= 1e-9 * np.max(np.abs(want))
    assert np.max(np.abs(found.tangential)) <= 1e-9 * np.max(np.abs(want))
    record = result.to_dict()["forces"]["contacts"]["K"]
    assert record["lost"] == [] and np.allclose(record["normal"], want, rtol=1e-9, atol=0)
