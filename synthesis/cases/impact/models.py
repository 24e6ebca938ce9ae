"""The two impact models as small linear systems, batched over positions with numpy.

Sign conventions are the source's: the normal impulse F acts on the pin along −u(ψ) and on the
rocker along +u(ψ); the friction impulse f acts on the pin along −n(ψ) and on the rocker along
+n(ψ), with n(ψ) = i·u(ψ); r_A is the impulse on the coupler at A (the crank receives −r_A),
r_O2 the impulse of the frame on the crank at O2. Both bodies touch at the pin centre
(the source's model: the rocker's contact point is O4 + r4·u(θ4) + ξ·u(ψ)).

Friction is full slip, |f| = μF, opposing the tangential slip of the pin on the bearing before
impact; a result says whether the slip kept its direction (otherwise the pin stuck during
the impact and full slip is not the right model there).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from assur.typing import BoolArray, ComplexArray, FloatArray
from synthesis.cases.impact.data import PAPER_IMPULSE_UNIT, ImpactData
from synthesis.cases.impact.position import ImpactPosition

__all__ = [
    "LEVERS",
    "MODELS",
    "ImpactResult",
    "Lever",
    "pin_offset",
    "restitution_lever",
    "solve_paper",
    "solve_townsend_mansour",
]

Lever = Literal["paper", "exact"]

#: Model keys: the source's ("P") and Townsend–Mansour's ("TM", the source's [2]).
MODELS = ("TM", "P")

#: Rocker lever in the restitution law: as printed in (7)–(9), or as the geometry gives it.
LEVERS = ("paper", "exact")


@dataclass(frozen=True, slots=True)
class ImpactResult:
    """Velocities after impact and impulses (SI units); arrays of the positions' shape.

    Attributes
    ----------
    model : str
        ``"P"`` (the source's) or ``"TM"`` (Townsend–Mansour's).
    k, mu : float
        The coefficients of restitution and friction used.
    omega2, omega3, omega4 : ndarray
        Angular velocities after impact, rad/s.
    v3 : ndarray of complex
        Velocity of the coupler's centre of mass after impact, m/s.
    normal, friction : ndarray
        Normal impulse F and friction impulse f at the bearing B, N·s.
    r_a, r_o2 : ndarray of complex
        Impulses at A (on the coupler) and at O2 (on the crank), N·s.
    drive : ndarray
        Angular impulse the drive applies to the crank, N·m·s (zero in the source's model).
    slip_before, slip_after : ndarray
        Tangential velocity of the pin relative to the bearing along n(ψ), m/s.
    approach_before, approach_after : ndarray
        Normal velocity of the pin relative to the bearing along u(ψ), m/s (positive: the
        pin moves into the wall).
    exists : ndarray of bool
        Positions with an impact; elsewhere every result is NaN.
    """

    model: str
    k: float
    mu: float
    omega2: FloatArray
    omega3: FloatArray
    omega4: FloatArray
    v3: ComplexArray
    normal: FloatArray
    friction: FloatArray
    r_a: ComplexArray
    r_o2: ComplexArray
    drive: FloatArray
    slip_before: FloatArray
    slip_after: FloatArray
    approach_before: FloatArray
    approach_after: FloatArray
    exists: BoolArray

    @property
    def full_slip(self) -> BoolArray:
        """Whether full slip is consistent: no friction, or the slip kept its direction."""
        return (self.mu == 0.0) | (self.slip_before * self.slip_after >= 0.0)

    def paper_units(self) -> dict[str, FloatArray]:
        """The columns of Table 1: velocities in rad/s, impulse magnitudes in 1e-4 N·s."""
        return {
            "omega2": self.omega2,
            "omega3": self.omega3,
            "F": self.normal / PAPER_IMPULSE_UNIT,
            "r_A": np.abs(self.r_a) / PAPER_IMPULSE_UNIT,
            "r_O2": np.abs(self.r_o2) / PAPER_IMPULSE_UNIT,
        }


def pin_offset(data: ImpactData, position: ImpactPosition
               ) -> tuple[FloatArray, FloatArray]:
    """ρ and α of (8): the distance from O4 to the pin centre and its angle to the rocker.

    Returns
    -------
    rho, alpha : ndarray
        Of the positions' shape; ρ in metres, α in radians.
    """
    gap = position.psi - position.theta4
    xi = data.clearance
    rho = np.sqrt(data.r4 ** 2 + xi ** 2 + 2.0 * data.r4 * xi * np.cos(gap))
    return rho, np.arcsin(xi / rho * np.sin(gap))


def restitution_lever(data: ImpactData, position: ImpactPosition,
                      lever: Lever = "paper") -> FloatArray:
    """The rocker's lever in the restitution law: v_B4n = lever · θ4'.

    Parameters
    ----------
    data : ImpactData
    position : ImpactPosition
    lever : {'paper', 'exact'}
        ``'paper'``: ρ·sin(ψ − θ4 + α) as printed in (7), with ρ and α of (8);
        ``'exact'``: ρ·sin(ψ − θ4 − α) = r4·sin(ψ − θ4), the normal velocity of the rocker's
        point at the pin centre.
    """
    if lever not in LEVERS:
        raise ValueError(f"'lever' must be one of {LEVERS}; got {lever!r}")
    gap = position.psi - position.theta4
    if lever == "exact":
        return data.r4 * np.sin(gap)
    rho, alpha = pin_offset(data, position)
    return rho * np.sin(gap + alpha)


@dataclass(frozen=True, slots=True)
class _Terms:
    """Trigonometric terms shared by both models, at the positions with an impact."""

    s2: FloatArray        # sin(ψ − θ2)
    s3: FloatArray        # sin(ψ − θ3)
    c2: FloatArray        # cos(ψ − θ2)
    c3: FloatArray        # cos(ψ − θ3)
    s4: FloatArray        # sin(ψ − θ4)
    arm_f4: FloatArray    # r4·cos(ψ − θ4) + ξ: friction arm about O4
    lever4: FloatArray    # rocker lever of the restitution law
    sign: FloatArray      # direction of the friction impulse on the rocker, ±1
    slip: FloatArray      # tangential slip before impact
    approach: FloatArray  # approach before impact with the restitution lever


def _terms(data: ImpactData, position: ImpactPosition, lever: Lever) -> _Terms:
    psi = position.psi
    s2, c2 = np.sin(psi - position.theta2), np.cos(psi - position.theta2)
    s3, c3 = np.sin(psi - position.theta3), np.cos(psi - position.theta3)
    s4, c4 = np.sin(psi - position.theta4), np.cos(psi - position.theta4)
    arm_f4 = data.r4 * c4 + data.clearance
    slip = _tangential(data, position.omega2, position.omega3, position.omega4, c2, c3, arm_f4)
    lever4 = restitution_lever(data, position, lever)
    approach = (data.r2 * position.omega2 * s2 + data.r3 * position.omega3 * s3
                - lever4 * position.omega4)
    return _Terms(s2=s2, s3=s3, c2=c2, c3=c3, s4=s4, arm_f4=arm_f4, lever4=lever4,
                  sign=np.where(slip >= 0.0, 1.0, -1.0), slip=slip, approach=approach)


def _tangential(data: ImpactData, omega2: FloatArray, omega3: FloatArray,
                omega4: FloatArray, c2: FloatArray, c3: FloatArray,
                arm_f4: FloatArray) -> FloatArray:
    """Slip of the pin on the bearing along n(ψ)."""
    return data.r2 * omega2 * c2 + data.r3 * omega3 * c3 - arm_f4 * omega4


def _normal(data: ImpactData, omega2: FloatArray, omega3: FloatArray,
            omega4: FloatArray, terms: _Terms) -> FloatArray:
    """Approach of the pin to the wall along u(ψ) (exact rocker lever)."""
    return (data.r2 * omega2 * terms.s2 + data.r3 * omega3 * terms.s3
            - data.r4 * terms.s4 * omega4)


def _coupler_velocity(data: ImpactData, position: ImpactPosition, omega2: FloatArray,
                      omega3: FloatArray) -> ComplexArray:
    """Velocity of the coupler's centre of mass, equations (1)–(2)."""
    velocity: ComplexArray = (1j * data.r2 * omega2 * np.exp(1j * position.theta2)
                                        + 1j * (data.r3 / 2.0) * omega3
                                        * np.exp(1j * position.theta3))
    return velocity


def _batched_solve(rows: list[list[FloatArray]], rhs: list[FloatArray],
                   exists: BoolArray) -> FloatArray:
    """Solve the systems given row by row where there is an impact; NaN elsewhere.

    The solution's last axis holds the unknowns in the order of the columns.
    """
    matrix = np.stack([np.stack(row, axis=-1) for row in rows], axis=-2)
    right = np.stack(rhs, axis=-1)
    out = np.full(right.shape, np.nan)
    out[exists] = np.linalg.solve(matrix[exists], right[exists][..., None])[..., 0]
    return out


def solve_paper(data: ImpactData, position: ImpactPosition, *, k: float | None = None,
                mu: float | None = None, lever: Lever = "paper") -> ImpactResult:
    """The source's model: every velocity may jump, the crank's included.

    Nine linear equations (1)–(5), the restitution law (9) and f = μF in the unknowns
    θ2'+, θ3'+, θ4'+, ẋ3+, ẏ3+, r_Ax, r_Ay, F, f.

    Parameters
    ----------
    data : ImpactData
        Dimensions, masses, inertias; ``k`` and ``mu`` by default.
    position : ImpactPosition
        The mechanism at impact (:func:`~synthesis.cases.impact.position.impact_position`).
    k : float, optional
        Coefficient of restitution (0 plastic … 1 elastic); default ``data.k``.
    mu : float, optional
        Coefficient of friction (full slip); default ``data.mu``.
    lever : {'paper', 'exact'}
        The rocker's lever in the restitution law (see :func:`restitution_lever`).

    Returns
    -------
    ImpactResult
        The impulse at O2 follows from the crank's linear momentum (centre of mass at r2/2).
    """
    k = data.k if k is None else float(k)
    mu = data.mu if mu is None else float(mu)
    t = _terms(data, position, lever)
    th2, th3 = position.theta2, position.theta3
    w2, w3, w4 = position.omega2, position.omega3, position.omega4
    cp, sp = np.cos(position.psi), np.sin(position.psi)
    half = data.r3 / 2.0
    v3 = _coupler_velocity(data, position, w2, w3)
    zero, one = np.zeros(position.shape), np.ones(position.shape)
    rows = [
        # (1), (2): coupler centre velocity after impact
        [-data.r2 * np.sin(th2), -half * np.sin(th3), zero, -one, zero, zero, zero, zero, zero],
        [data.r2 * np.cos(th2), half * np.cos(th3), zero, zero, -one, zero, zero, zero, zero],
        # (3): coupler linear and angular momentum
        [zero, zero, zero, data.m3 * one, zero, -one, zero, cp, -sp],
        [zero, zero, zero, zero, data.m3 * one, zero, -one, sp, cp],
        [zero, data.inertia3 * one, zero, zero, zero, -half * np.sin(th3), half * np.cos(th3),
         half * t.s3, half * t.c3],
        # (4): crank about O2
        [data.inertia_o2 * one, zero, zero, zero, zero, -data.r2 * np.sin(th2),
         data.r2 * np.cos(th2), zero, zero],
        # (5): rocker about O4
        [zero, zero, data.inertia_o4 * one, zero, zero, zero, zero, -data.r4 * t.s4, -t.arm_f4],
        # (9): restitution
        [-data.r2 * t.s2, -data.r3 * t.s3, t.lever4, zero, zero, zero, zero, zero, zero],
        # full slip
        [zero, zero, zero, zero, zero, zero, zero, mu * t.sign, -one],
    ]
    rhs = [zero, zero, data.m3 * v3.real, data.m3 * v3.imag, data.inertia3 * w3,
           data.inertia_o2 * w2, data.inertia_o4 * w4, k * t.approach, zero]
    x = _batched_solve(rows, rhs, position.exists)
    w2p, w3p, w4p, x3p, y3p, rax, ray, normal, friction = np.moveaxis(x, -1, 0)
    r_a = rax + 1j * ray
    dv2 = 1j * (data.r2 / 2.0) * (w2p - w2) * np.exp(1j * th2)
    return _result("P", k, mu, data, position, t, w2p, w3p, w4p, x3p + 1j * y3p, normal, friction,
                   r_a, r_a + data.m2 * dv2, np.zeros(position.shape))


def solve_townsend_mansour(data: ImpactData, position: ImpactPosition, *,
                           k: float | None = None, mu: float | None = None,
                           lever: Lever = "paper") -> ImpactResult:
    """Townsend–Mansour's model [2]: the crank speed is held through the impact.

    The velocity of A does not change, so the coupler turns about A: the coupler's angular
    momentum about A, the rocker's about O4, the restitution law (9) with θ2'+ = θ2' and
    f = μF give four equations in θ3'+, θ4'+, F, f (the source's "3 equations" need the
    fourth, f = μF). The impulse at A follows from the coupler's linear momentum; the crank's
    momentum does not change, so the frame takes r_O2 = r_A and the drive supplies the angular
    impulse that keeps the crank speed.

    Parameters and return value as :func:`solve_paper`.
    """
    k = data.k if k is None else float(k)
    mu = data.mu if mu is None else float(mu)
    t = _terms(data, position, lever)
    w2, w3, w4 = position.omega2, position.omega3, position.omega4
    zero, one = np.zeros(position.shape), np.ones(position.shape)
    rows = [
        [data.inertia_a3 * one, zero, data.r3 * t.s3, data.r3 * t.c3],
        [zero, data.inertia_o4 * one, -data.r4 * t.s4, -t.arm_f4],
        [-data.r3 * t.s3, t.lever4, zero, zero],
        [zero, zero, mu * t.sign, -one],
    ]
    rhs = [data.inertia_a3 * w3, data.inertia_o4 * w4, k * t.approach + data.r2 * w2 * t.s2,
           zero]
    x = _batched_solve(rows, rhs, position.exists)
    w3p, w4p, normal, friction = np.moveaxis(x, -1, 0)
    w2p = np.where(position.exists, w2, np.nan)
    v3p = _coupler_velocity(data, position, w2p, w3p)
    u = np.exp(1j * position.psi)
    r_a = data.m3 * (v3p - _coupler_velocity(data, position, w2, w3)) + (normal + 1j * friction) * u
    th2 = position.theta2
    drive = -data.r2 * (r_a.real * np.sin(th2) - r_a.imag * np.cos(th2))
    return _result("TM", k, mu, data, position, t, w2p, w3p, w4p, v3p, normal, friction, r_a,
                   r_a, drive)


def _result(model: str, k: float, mu: float, data: ImpactData, position: ImpactPosition, t: _Terms,
            w2p: FloatArray, w3p: FloatArray, w4p: FloatArray,
            v3p: ComplexArray, normal: FloatArray,
            friction: FloatArray, r_a: ComplexArray,
            r_o2: ComplexArray, drive: FloatArray) -> ImpactResult:
    nan = np.where(position.exists, 0.0, np.nan)
    return ImpactResult(
        model=model, k=k, mu=mu, omega2=w2p, omega3=w3p, omega4=w4p, v3=v3p, normal=normal,
        friction=friction, r_a=r_a, r_o2=r_o2, drive=drive + nan,
        slip_before=t.slip + nan,
        slip_after=_tangential(data, w2p, w3p, w4p, t.c2, t.c3, t.arm_f4),
        approach_before=_normal(data, position.omega2, position.omega3, position.omega4, t) + nan,
        approach_after=_normal(data, w2p, w3p, w4p, t),
        exists=position.exists)
