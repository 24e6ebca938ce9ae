"""Every real assembly mode of any four-link group from its full pose system (§4 of the note).

The closed forms of :mod:`assur.kinematics.higher.groups` cover the triad and the class IV
group with revolute internal pairs. This module solves any four-link group the other way:

- the **full pose system**: each of the four links has a pose (a shift t and a rotation θ
  from the drawing, so that its drawn point z⁰ is at ``r + t + e^{iθ}(z⁰ − r)``, r a drawn
  point of the link): 12 unknowns. A revolute pair gives 2 equations (the pair's point on both
  links coincides), a prismatic pair 2 (equal rotations; the point of the sliding link on the
  guide line of the link that carries it): 12 equations.
- the **one-parameter sweep** (the method of false positions): one link with an external pair
  is turned (a revolute pair: its rotation α over a full turn) or slid (a prismatic pair: its
  slide L·tan(α/2)); two more links close as a dyad with both branches (circle–circle or
  circle–line); the last link's constraint is a scalar residual along the closed walk
  (branch +, then branch − back, joined where the dyad stops assembling). Every sign change is
  bracketed and bisected, then polished by Newton's method on the full pose system, and the
  modes are deduplicated on their joints. Only tangential roots (exact change points) can be
  missed.
- **multi-start Newton** on the full pose system as the last resort, for a group with no such
  sweep.

Everything is vectorised over designs (drawn values and known motions of shape () or (D,)).
It is an independent second method: it shares no equation with the closed forms.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import permutations
from typing import Literal

import numpy as np

__all__ = ["Joint", "Motion", "Plan", "PoseModes", "PoseSystem", "newton_modes", "sweep_modes",
           "sweep_plans"]

#: A body of a joint: a link of the group (0–3) or a known link by name.
Body = int | str
#: A polished pose is a mode when every equation is at most ACCEPT·L.
ACCEPT = 1e-9
#: Two modes are one when no joint (and no rotation, as a point at the distance L) differs by
#: more than SAME·L.
SAME = 1e-7
#: Newton iterations of the polish.
POLISH = 12


@dataclass(frozen=True)
class Joint:
    """A pair of the group as drawn.

    Attributes
    ----------
    kind : {"R", "P"}
        Revolute or prismatic.
    first, second : int or str
        Its two bodies: a link of the group (0–3) or a known link by name; the guide of a
        prismatic pair is carried by ``second``.
    point : complex or ndarray
        The drawn point of the pair (a revolute pair's centre; a point of the guide line of a
        prismatic pair, the sliding link's point drawn there).
    direction : complex or ndarray or None
        The drawn unit direction of a prismatic pair's guide.
    """

    kind: Literal["R", "P"]
    first: Body
    second: Body
    point: complex | np.ndarray
    direction: complex | np.ndarray | None = None


@dataclass(frozen=True)
class Motion:
    """A known link at one position: its drawn point z⁰ is at ``shift + turn·z⁰``."""

    shift: complex | np.ndarray
    turn: complex | np.ndarray


#: The pose of a link as (shift A, turn E): z⁰ ↦ A + E·z⁰.
Pose = tuple[np.ndarray, np.ndarray]


@dataclass(frozen=True, eq=False)
class PoseModes:
    """The real assembly modes found, per design.

    Attributes
    ----------
    x : ndarray, shape (..., M, 12)
        The poses (t_x, t_y, θ per link) of each mode; NaN rows after the last.
    count : ndarray, int
        The number of modes.
    points : ndarray, complex, shape (..., M, 6)
        Each joint's point (on its first body) in each mode.
    """

    x: np.ndarray
    count: np.ndarray
    points: np.ndarray


@dataclass(frozen=True)
class Plan:
    """A sweep's plan: link x turned or slid at its external joint ``turned``, the dyad (y, z)
    closed on x at joint p1, between them at p2 and on a known link at p3, the last link w
    with its two joints q1, q2.

    Attributes
    ----------
    x, y, z, w : int
        The links in their roles.
    turned, p1, p2, p3, q1, q2 : int
        The joints (indices into ``PoseSystem.joints``) in their roles.
    kinds : str
        The kinds of p1, p2, p3 (``"RRR"``, ``"RPR"``, …; never ``"PPP"``).
    """

    x: int
    turned: int
    y: int
    z: int
    p1: int
    p2: int
    p3: int
    w: int
    q1: int
    q2: int
    kinds: str


@dataclass(frozen=True, eq=False)
class PoseSystem:
    """The full pose system of a four-link group: 4 links, 6 joints, 12 equations.

    Parameters
    ----------
    joints : tuple of 6 Joint
        The pairs of the group, internal and external.

    Examples
    --------
    An RRR triad (base 0, leashes 1–3 hinged to the frame "K"), drawn assembled:

    >>> base = (10 + 40j, 40 + 45j, 25 + 70j)
    >>> outer = (0j, 60 + 0j, 30 + 110j)
    >>> joints = [Joint("R", 0, k + 1, base[k]) for k in range(3)]
    >>> joints += [Joint("R", k + 1, "K", outer[k]) for k in range(3)]
    >>> system = PoseSystem(tuple(joints))
    >>> float(np.abs(system.residual(np.zeros(12), {"K": Motion(0, 1)})).max())
    0.0
    """

    joints: tuple[Joint, ...]

    @property
    def size(self) -> np.ndarray:
        """L, the largest distance between the drawn joints."""
        pts = np.stack(np.broadcast_arrays(*(np.asarray(j.point, dtype=complex)
                                             for j in self.joints)), axis=-1)
        return np.asarray(np.abs(pts[..., :, None] - pts[..., None, :]).max(axis=(-2, -1)))

    def _reference(self, link: int) -> np.ndarray:
        """The drawn point r of a link about which its rotation turns it."""
        return np.asarray(next(j.point for j in self.joints if link in (j.first, j.second)))

    def poses(self, x: np.ndarray) -> list[Pose]:
        """(A, E) of the four links from the unknowns (..., 12)."""
        out = []
        for link in range(4):
            t = x[..., 3 * link] + 1j * x[..., 3 * link + 1]
            turn = np.exp(1j * x[..., 3 * link + 2])
            r = self._reference(link)
            out.append((r + t - turn * r, turn))
        return out

    def unknowns(self, poses: list[Pose]) -> np.ndarray:
        """The unknowns (..., 12) of the four links' poses (A, E)."""
        cols = []
        for link, (shift, turn) in enumerate(poses):
            r = self._reference(link)
            t = shift + turn * r - r
            cols += [t.real, t.imag, np.angle(turn)]
        return np.stack(np.broadcast_arrays(*cols), axis=-1)

    def residual(self, x: np.ndarray, known: dict[str, Motion]) -> np.ndarray:
        """The 12 equations at the unknowns x (..., 12): per revolute joint the difference of
        its point on the two bodies (x, y); per prismatic joint L times the rotations'
        difference (in (−π, π], zero only for equal rotations) and the sliding point's
        offset from the guide line."""
        return _equations(self, _bodies(self.poses(x), known))

    def jacobian(self, x: np.ndarray, known: dict[str, Motion]) -> np.ndarray:
        """∂F/∂x (..., 12, 12) by central differences (it only steers the polish)."""
        step = np.where(np.arange(12) % 3 == 2, 1e-6, 1e-6 * np.asarray(self.size)[..., None])
        cols = []
        for i in range(12):
            dx = np.zeros(np.shape(step))
            dx[..., i] = step[..., i]
            cols.append((self.residual(x + dx, known) - self.residual(x - dx, known))
                        / (2.0 * step[..., i, None]))
        return np.stack(cols, axis=-1)

    def polish(self, x: np.ndarray, known: dict[str, Motion]) -> tuple[np.ndarray, np.ndarray]:
        """Newton's method (pseudo-inverse steps, no error at a singular Jacobian); the
        iterate and the largest residual over L."""
        with np.errstate(all="ignore"):
            for _ in range(POLISH):
                f = self.residual(x, known)
                good = np.isfinite(f).all(axis=-1) & np.isfinite(x).all(axis=-1)
                jac = np.where(good[..., None, None], self.jacobian(x, known), np.eye(12))
                step = np.einsum("...ij,...j->...i", np.linalg.pinv(jac),
                                 np.where(good[..., None], f, 0.0))
                x = np.where(good[..., None], x - step, np.nan)
            return x, np.abs(self.residual(x, known)).max(axis=-1) / self.size

    def points(self, x: np.ndarray, known: dict[str, Motion]) -> np.ndarray:
        """Each joint's point on its first body, (..., 6)."""
        bodies = _bodies(self.poses(x), known)
        return np.stack(np.broadcast_arrays(*(_at(bodies[j.first], j.point)
                                              for j in self.joints)), axis=-1)


def _bodies(poses: list[Pose], known: dict[str, Motion]) -> dict[Body, Pose]:
    out: dict[Body, Pose] = {i: pose for i, pose in enumerate(poses)}
    out.update({name: (np.asarray(m.shift), np.asarray(m.turn)) for name, m in known.items()})
    return out


def _at(pose: Pose, z: complex | np.ndarray) -> np.ndarray:
    """Where the drawn point z of a body in pose (A, E) is."""
    return np.asarray(pose[0] + pose[1] * z)


def _equations(system: PoseSystem, bodies: dict[Body, Pose]) -> np.ndarray:
    size = system.size
    rows = []
    for j in system.joints:
        one, two = bodies[j.first], bodies[j.second]
        gap = _at(one, j.point) - _at(two, j.point)
        if j.kind == "R":
            rows += [gap.real, gap.imag]
        else:
            guide = np.asarray(j.direction) * two[1]
            rows += [size * np.angle(np.conj(two[1]) * one[1]), (np.conj(guide) * gap).imag]
    return np.stack(np.broadcast_arrays(*rows), axis=-1)


def sweep_plans(system: PoseSystem) -> list[Plan]:
    """The sweep plans of a group: first, one per link x, those whose dyad has two internal
    hinges (y hinged to x, z hinged to y); then, one per link x, those with a prismatic pair
    at p1 or p2 (any kinds but three prismatic pairs).

    Parameters
    ----------
    system : PoseSystem
        The group.

    Returns
    -------
    list of Plan
        Possibly empty (every link with an external pair sits beside prismatic pairs only).
    """
    joints = system.joints

    def between(a: Body, b: Body) -> list[int]:
        return [k for k, j in enumerate(joints) if {j.first, j.second} == {a, b}]

    def known(a: int) -> list[int]:
        return [k for k, j in enumerate(joints) if a in (j.first, j.second)
                and isinstance(_other(j, a), str)]

    hinged: dict[int, Plan] = {}
    other: dict[int, Plan] = {}
    for x, y, z, w in permutations(range(4)):
        for turned in known(x):
            for p1 in between(x, y):
                for p2 in between(y, z):
                    for p3 in known(z):
                        rest = [k for k in range(6) if k not in {turned, p1, p2, p3}]
                        kinds = "".join(joints[k].kind for k in (p1, p2, p3))
                        if kinds == "PPP" or len(rest) != 2 or not all(
                                w in (joints[k].first, joints[k].second) for k in rest):
                            continue
                        plans = hinged if kinds[:2] == "RR" else other
                        plans.setdefault(x, Plan(x, turned, y, z, p1, p2, p3, w, rest[0],
                                                 rest[1], kinds))
    return list(hinged.values()) + list(other.values())


def _other(j: Joint, body: Body) -> Body:
    return j.second if j.first == body else j.first


def _swept(system: PoseSystem, roles: Plan, known: dict[str, Motion], alpha: np.ndarray
           ) -> Pose:
    """The pose of x at the sweep parameter α: turned by α about its hinge, or slid by
    L·tan(α/2) along its guide (turning with the guide's link)."""
    j = system.joints[roles.turned]
    outer = known[str(_other(j, roles.x))]
    base = (np.asarray(outer.shift), np.asarray(outer.turn))
    point = np.asarray(j.point)
    if j.kind == "R":
        turn = np.exp(1j * alpha) + 0j * base[1]
        return _at(base, point) - turn * point, turn
    shift = system.size * np.tan(alpha / 2.0) * np.asarray(j.direction) * base[1]
    return base[0] + shift, base[1] + 0j * shift


def _meet(centre: np.ndarray, radius: np.ndarray, start: np.ndarray, guide: np.ndarray,
          sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """The slide s of the point ``start + s·guide`` (|guide| = 1) at the distance ``radius``
    from ``centre`` on branch σ, and the discriminant (negative: the line misses the circle)."""
    gap = start - centre
    b = (np.conj(guide) * gap).real
    height2 = b ** 2 - np.abs(gap) ** 2 + radius ** 2
    return -b + sigma * np.sqrt(np.maximum(height2, 0.0)), height2


def _cross(start: np.ndarray, guide: np.ndarray, other: np.ndarray, along: np.ndarray
           ) -> np.ndarray:
    """The slide s where the line ``start + s·guide`` meets the line ``other + t·along``."""
    return np.asarray((np.conj(along) * (other - start)).imag / (np.conj(along) * guide).imag)


def _single(slide: np.ndarray, sigma: float) -> np.ndarray:
    """The discriminant of a line–line closure: its one branch is σ = +1, assembled where the
    lines cross."""
    return np.where(np.isfinite(slide) & (sigma > 0), 1.0, -1.0)


def _dyad(system: PoseSystem, roles: Plan, known: dict[str, Motion], x_pose: Pose,
          sigma: float) -> tuple[Pose, Pose, np.ndarray]:
    """The poses of y and z closed as a dyad on x (branch σ) and whether it assembles: y
    jointed to x at p1, to z at p2, z to its known link K at p3; a prismatic pair makes its
    two links turn together. Circle–circle (R, R, R), circle–line (R, R, P; P, R, R), the
    rotation of y and z from a line's distance (R, P, R), or line–line (P, R, P; R, P, P;
    P, P, R: one branch, σ = −1 never assembles)."""
    j1, j2, j3 = (system.joints[k] for k in (roles.p1, roles.p2, roles.p3))
    p1, p2, p3 = (np.asarray(j.point) for j in (j1, j2, j3))
    outer = known[str(_other(j3, roles.z))]
    out_pose = (np.asarray(outer.shift), np.asarray(outer.turn))
    kinds = roles.kinds
    with np.errstate(all="ignore"):
        if kinds[:2] == "RR":
            centre = _at(x_pose, p1)
            reach = np.abs(p2 - p1)
            if kinds == "RRR":
                hinge = _at(out_pose, p3)
                arm = np.abs(p2 - p3)
                d = hinge - centre
                rho = np.abs(d)
                along = (reach ** 2 - arm ** 2 + rho ** 2) / (2.0 * rho)
                height2 = reach ** 2 - along ** 2
                joint = centre + (along + 1j * sigma * np.sqrt(np.maximum(height2, 0.0))) \
                    * d / rho
                z_turn = (joint - hinge) / (p2 - p3)
                z_pose = (hinge - z_turn * p3, z_turn)
            else:
                guide = np.asarray(j3.direction) * out_pose[1]
                s, height2 = _meet(centre, reach, _at(out_pose, p2), guide, sigma)
                joint = _at(out_pose, p2) + s * guide
                z_pose = (out_pose[0] + s * guide, out_pose[1] + 0j * s)
            y_turn = (joint - centre) / (p2 - p1)
            y_pose = (centre - y_turn * p1, y_turn)
        elif kinds == "RPR":
            centre, hinge = _at(x_pose, p1), _at(out_pose, p3)
            u2 = np.asarray(j2.direction)
            rho = np.abs(centre - hinge)
            ratio = (np.conj(u2) * (p1 - p3)).imag / rho
            height2 = 1.0 - ratio ** 2
            tilt = sigma * np.sqrt(np.maximum(height2, 0.0)) + 1j * ratio
            turn = (centre - hinge) / rho * np.conj(u2 * tilt)
            y_pose, z_pose = (centre - turn * p1, turn), (hinge - turn * p3, turn)
        elif kinds[0] == "P" and kinds[1] == "R":
            g1 = np.asarray(j1.direction) * x_pose[1]
            if kinds[2] == "R":
                hinge = _at(out_pose, p3)
                s, height2 = _meet(hinge, np.abs(p2 - p3), _at(x_pose, p2), g1, sigma)
                z_turn = (_at(x_pose, p2) + s * g1 - hinge) / (p2 - p3)
                z_pose = (hinge - z_turn * p3, z_turn)
            else:
                g3 = np.asarray(j3.direction) * out_pose[1]
                s = _cross(_at(x_pose, p2), g1, _at(out_pose, p2), g3)
                z_pose = (_at(x_pose, p2) + s * g1 - out_pose[1] * p2, out_pose[1] + 0j * s)
                height2 = _single(s, sigma)
            y_pose = (x_pose[0] + s * g1, x_pose[1] + 0j * s)
        else:
            g2 = np.asarray(j2.direction)
            if kinds[0] == "R":  # R, P, P: y and z turn with K
                turn = out_pose[1]
                y_pose = (_at(x_pose, p1) - turn * p1, turn)
                t = _cross(y_pose[0], g2 * turn, out_pose[0], np.asarray(j3.direction) * turn)
                z_pose = (y_pose[0] + t * g2 * turn, turn + 0j * t)
            else:  # P, P, R: y and z turn with x
                turn = x_pose[1]
                z_pose = (_at(out_pose, p3) - turn * p3, turn)
                t = _cross(x_pose[0], np.asarray(j1.direction) * turn, z_pose[0], g2 * turn)
                y_pose = (x_pose[0] + t * np.asarray(j1.direction) * turn, turn + 0j * t)
            height2 = _single(t, sigma)
    return y_pose, z_pose, np.asarray(height2 >= 0.0)


def _last(system: PoseSystem, roles: Plan, bodies: dict[Body, Pose]) -> np.ndarray:
    """The constraint left on the last link w: hinge–hinge distance minus its drawn length;
    with one prismatic joint the offset of w's drawn point there from the guide (w turning
    with the guide's link); with two, L times the two links' rotation difference."""
    q1, q2 = _ends(system, roles)
    u, v = bodies[_other(q1, roles.w)], bodies[_other(q2, roles.w)]
    p, q = np.asarray(q1.point), np.asarray(q2.point)
    if q1.kind == q2.kind == "R":
        return np.asarray(np.abs(_at(u, p) - _at(v, q)) - np.abs(p - q))
    if q1.kind == "R":
        guide = np.asarray(q2.direction) * v[1]
        point = _at(u, p) + v[1] * (q - p)
        return np.asarray((np.conj(guide) * (point - _at(v, q))).imag)
    return np.asarray(system.size * np.angle(np.conj(u[1]) * v[1]))


def _ends(system: PoseSystem, roles: Plan) -> tuple[Joint, Joint]:
    """The last link's two joints, a revolute one first."""
    q1, q2 = system.joints[roles.q1], system.joints[roles.q2]
    return (q2, q1) if q1.kind == "P" and q2.kind == "R" else (q1, q2)


def _closing(system: PoseSystem, roles: Plan, bodies: dict[Body, Pose]) -> Pose:
    """The last link's pose at a root of its residual: through its two hinges; hinged and
    turning with the guide's link; or turning with both guides' links, its drawn points on
    both guide lines."""
    q1, q2 = _ends(system, roles)
    u, v = bodies[_other(q1, roles.w)], bodies[_other(q2, roles.w)]
    p, q = np.asarray(q1.point), np.asarray(q2.point)
    with np.errstate(all="ignore"):
        if q1.kind == q2.kind == "R":
            start, end = _at(u, p), _at(v, q)
            turn = (end - start) / np.abs(end - start) * np.abs(q - p) / (q - p)
            return start - turn * p, turn
        if q1.kind == "R":
            return _at(u, p) - v[1] * p, v[1]
        turn = u[1]
        g1, g2 = _at(u, p) - turn * p, _at(v, q) - turn * q
        d1, d2 = np.asarray(q1.direction) * u[1], np.asarray(q2.direction) * v[1]
        along = (np.conj(d2) * (g2 - g1)).imag / (np.conj(d2) * d1).imag
        return g1 + along * d1, turn


def _walk(system: PoseSystem, roles: Plan, known: dict[str, Motion], alpha: np.ndarray,
          sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """The last residual and whether the dyad assembles at the sweep parameters α."""
    x_pose = _swept(system, roles, known, alpha)
    y_pose, z_pose, ok = _dyad(system, roles, known, x_pose, sigma)
    bodies = _bodies([x_pose] * 4, known)
    bodies.update({roles.x: x_pose, roles.y: y_pose, roles.z: z_pose})
    with np.errstate(all="ignore"):
        return _last(system, roles, bodies), ok


def _expand(system: PoseSystem, known: dict[str, Motion]
            ) -> tuple[PoseSystem, dict[str, Motion]]:
    """Every drawn value and known motion with a trailing axis (against the samples)."""
    def grow(v: complex | np.ndarray | None) -> np.ndarray | None:
        return None if v is None else np.asarray(v)[..., None]

    joints = tuple(Joint(j.kind, j.first, j.second, np.asarray(j.point)[..., None],
                         grow(j.direction)) for j in system.joints)
    return PoseSystem(joints), {n: Motion(np.asarray(m.shift)[..., None],
                                          np.asarray(m.turn)[..., None])
                                for n, m in known.items()}


def _brackets(system: PoseSystem, roles: Plan, known: dict[str, Motion], samples: int
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Brackets [α₀, α₁] of a sign change on a branch σ, (..., 2·samples) each, NaN where
    there is none; a change across the join of the two branches at a dyad's limit is moved
    onto the branch that carries it by locating the limit, and so is a pair of roots, one on
    each branch, between a sample and the limit."""
    revolute = system.joints[roles.turned].kind == "R"
    step = 2.0 * np.pi / samples
    alpha = -np.pi + step * (np.arange(samples) + 0.5)
    wide, grown = _expand(system, known)
    lo, hi, branch = [], [], []
    walks = {s: _walk(wide, roles, grown, alpha, s) for s in (1.0, -1.0)}
    for s, (f, ok) in walks.items():
        nxt = np.roll(np.arange(samples), -1) if revolute else np.r_[1:samples, samples - 1]
        change = ok & ok[..., nxt] & (np.sign(f) != np.sign(f[..., nxt]))
        lo.append(np.where(change, alpha, np.nan))
        hi.append(np.where(change, alpha + step, np.nan))
        branch.append(np.where(change, s, np.nan))
        for pair in _pairs(wide, roles, grown, alpha, f, ok, s, revolute):
            lo.append(pair[0])
            hi.append(pair[1])
            branch.append(np.where(np.isnan(pair[0]), np.nan, s))
    (fp, okp), (fm, _) = walks[1.0], walks[-1.0]
    for shift in (1, -1):  # the dyad stops assembling after (shift 1) or before a sample
        edge = okp & ~np.roll(okp, -shift, axis=-1)
        if not revolute:
            edge[..., -1 if shift == 1 else 0] = False
        inside, outside, plus, minus = _compress(np.where(edge, alpha, np.nan),
                                                 alpha + shift * step + 0.0 * fp, fp, fm)
        limit = _limit(wide, roles, grown, inside, outside)
        f_limit, _ = _walk(wide, roles, grown, limit, 1.0)
        ends = np.sort(np.stack([inside, limit]), axis=0)
        for s, f in ((1.0, plus), (-1.0, minus)):  # a root between the sample and the limit
            change = np.sign(f_limit) != np.sign(f)
            lo.append(np.where(change, ends[0], np.nan))
            hi.append(np.where(change, ends[1], np.nan))
            branch.append(np.where(change & ~np.isnan(inside), s, np.nan))
    if roles.kinds == "PRP":  # a root between a sample and a pole of the slides
        for near, far in _poles(wide, roles, grown, alpha, revolute):
            change = np.sign(_walk(wide, roles, grown, near, 1.0)[0]) \
                != np.sign(_walk(wide, roles, grown, far, 1.0)[0])
            lo.append(np.where(change, near, np.nan))
            hi.append(np.where(change, far, np.nan))
            branch.append(np.where(change & ~np.isnan(near), 1.0, np.nan))
    return np.concatenate(lo, axis=-1), np.concatenate(hi, axis=-1), np.concatenate(branch,
                                                                                    axis=-1)


def _parallel(system: PoseSystem, roles: Plan, known: dict[str, Motion], alpha: np.ndarray
              ) -> np.ndarray:
    """Im(conj(g₃)·g₁) of a P, R, P dyad's guides at the sweep parameters α: zero where they
    are parallel and its slides grow without bound (a pole of the last residual)."""
    turn = _swept(system, roles, known, alpha)[1]
    outer = known[str(_other(system.joints[roles.p3], roles.z))]
    g1 = np.asarray(system.joints[roles.p1].direction) * turn
    g3 = np.asarray(system.joints[roles.p3].direction) * np.asarray(outer.turn)
    return np.asarray((np.conj(g3) * g1).imag)


def _poles(system: PoseSystem, roles: Plan, known: dict[str, Motion], alpha: np.ndarray,
           revolute: bool) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """The intervals from a sample to a pole of the slides and from the pole to the next
    sample (the pole located by bisection, 60 halvings), where the guides turn parallel
    between two samples; NaN where they do not."""
    step = alpha[1] - alpha[0]
    gap = _parallel(system, roles, known, alpha)
    flip = np.sign(gap) != np.sign(np.roll(gap, -1, axis=-1))
    if not revolute:
        flip[..., -1] = False
    start, sign = _compress(np.where(flip, alpha, np.nan), np.sign(gap))
    a, b = start, start + step
    end = b
    for _ in range(60):
        mid = 0.5 * (a + b)
        left = np.sign(_parallel(system, roles, known, mid)) == sign
        a, b = np.where(left, mid, a), np.where(left, b, mid)
    return (start, a), (b, end)


def _pairs(system: PoseSystem, roles: Plan, known: dict[str, Motion], alpha: np.ndarray,
           f: np.ndarray, ok: np.ndarray, sigma: float, revolute: bool
           ) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """Brackets of two roots closer than a sample on one branch: where |f| has a local
    minimum without a sign change, the extremum of f between the neighbours (golden-section
    search, 50 steps) is located; if f changes sign there, [α_{j−1}, α*] and [α*, α_{j+1}]."""
    step = alpha[1] - alpha[0]
    before, after = np.roll(f, 1, axis=-1), np.roll(f, -1, axis=-1)
    near = ok & np.roll(ok, 1, axis=-1) & np.roll(ok, -1, axis=-1)
    if not revolute:
        near[..., 0] = near[..., -1] = False
    dip = near & (np.abs(f) < np.abs(before)) & (np.abs(f) <= np.abs(after)) \
        & (np.sign(before) == np.sign(f)) & (np.sign(after) == np.sign(f))
    a, b, sign = _compress(np.where(dip, alpha - step, np.nan), alpha + step + 0.0 * f,
                           np.sign(f))
    lo, hi = a, b
    ratio = (np.sqrt(5.0) - 1.0) / 2.0
    for _ in range(50):
        left, right = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
        f_left = sign * _walk(system, roles, known, left, sigma)[0]
        f_right = sign * _walk(system, roles, known, right, sigma)[0]
        lower = f_left < f_right
        lo, hi = np.where(lower, lo, left), np.where(lower, right, hi)
    middle = 0.5 * (lo + hi)
    crossed = sign * _walk(system, roles, known, middle, sigma)[0] < 0
    middle = np.where(crossed, middle, np.nan)
    return (np.where(crossed, a, np.nan), middle), (middle, np.where(crossed, b, np.nan))


def _limit(system: PoseSystem, roles: Plan, known: dict[str, Motion], inside: np.ndarray,
           outside: np.ndarray) -> np.ndarray:
    """The sweep parameter where the dyad stops assembling, between ``inside`` (assembled) and
    ``outside``, by bisection (60 halvings)."""
    a, b = inside, outside
    for _ in range(60):
        mid = 0.5 * (a + b)
        _, ok = _walk(system, roles, known, mid, 1.0)
        a, b = np.where(ok, mid, a), np.where(ok, b, mid)
    return a


def _bisect(system: PoseSystem, roles: Plan, known: dict[str, Motion], lo: np.ndarray,
            hi: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """The root of the last residual on branch σ between lo and hi (60 halvings)."""
    def f(alpha: np.ndarray) -> np.ndarray:
        plus, _ = _walk(system, roles, known, alpha, 1.0)
        minus, _ = _walk(system, roles, known, alpha, -1.0)
        return np.where(sigma > 0, plus, minus)

    f_lo = f(lo)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        f_mid = f(mid)
        left = np.sign(f_mid) != np.sign(f_lo)
        lo, hi = np.where(left, lo, mid), np.where(left, mid, hi)
        f_lo = np.where(left, f_lo, f_mid)
    return np.asarray(0.5 * (lo + hi))


def _assemble(system: PoseSystem, roles: Plan, known: dict[str, Motion], alpha: np.ndarray,
              sigma: np.ndarray) -> np.ndarray:
    """The full unknowns at (α, σ): x, y, z from the sweep, w from its first joint (hinge:
    turned as drawn about it, then the polish corrects it)."""
    poses: dict[Body, Pose] = {}
    x_pose = _swept(system, roles, known, alpha)
    plus = _dyad(system, roles, known, x_pose, 1.0)
    minus = _dyad(system, roles, known, x_pose, -1.0)
    pick = sigma > 0
    poses[roles.x] = x_pose
    for k, link in ((0, roles.y), (1, roles.z)):
        poses[link] = (np.where(pick, plus[k][0], minus[k][0]),
                       np.where(pick, plus[k][1], minus[k][1]))
    bodies = _bodies([x_pose] * 4, known)
    bodies.update(poses)
    poses[roles.w] = _closing(system, roles, bodies)
    return system.unknowns([poses[i] for i in range(4)])


def _distinct(wide: PoseSystem, grown: dict[str, Motion], x: np.ndarray,
              residual: np.ndarray) -> PoseModes:
    """Keep the candidates (..., K, 12) whose residual is at most ACCEPT, once each (the
    system and motions expanded by one axis)."""
    size = wide.size[..., None]
    with np.errstate(all="ignore"):
        valid = residual <= ACCEPT
        points = wide.points(x, grown)
        turns = np.stack([wide.size * np.exp(1j * x[..., 3 * i + 2]) for i in range(4)],
                         axis=-1)
        stack = np.concatenate([points, turns], axis=-1)
        apart = np.abs(stack[..., :, None, :] - stack[..., None, :, :]).max(axis=-1)
        same = (apart <= SAME * size) & valid[..., :, None]
        earlier = np.tril(np.ones(same.shape[-2:], dtype=bool), -1).T
        valid &= ~(same & earlier).any(axis=-2)
    order = np.argsort(~valid, axis=-1, kind="stable")
    valid = np.take_along_axis(valid, order, axis=-1)
    count = valid.sum(axis=-1)
    width = max(int(count.max(initial=0)), 1)
    valid = valid[..., :width]
    x = np.take_along_axis(x, order[..., None], axis=-2)[..., :width, :]
    points = np.take_along_axis(points, order[..., None], axis=-2)[..., :width, :]
    return PoseModes(x=np.where(valid[..., None], x, np.nan), count=count,
                     points=np.where(valid[..., None], points, np.nan))


def _compress(*columns: np.ndarray) -> tuple[np.ndarray, ...]:
    """The entries of the first array that are not NaN moved to the front, and the arrays cut
    to the largest such count (at least one column)."""
    columns = tuple(np.broadcast_arrays(*columns))
    keep = ~np.isnan(columns[0])
    order = np.argsort(~keep, axis=-1, kind="stable")
    width = max(int(keep.sum(axis=-1).max(initial=0)), 1)
    return tuple(np.take_along_axis(c, order, axis=-1)[..., :width] for c in columns)


def sweep_modes(system: PoseSystem, known: dict[str, Motion], samples: int = 1440,
                plans_used: int = 2, *, plans: Sequence[Plan] | None = None) -> PoseModes:
    """Every real assembly mode by the one-parameter sweep, polished on the full system.

    Parameters
    ----------
    system : PoseSystem
        The group; drawn values of shape () or (D,).
    known : dict of str to Motion
        The known links at the position.
    samples : int
        Sweep samples over the full turn (720–4096).
    plans_used : int
        How many sweeps (each turning or sliding another link) to join: a pair of roots
        closer than a sample to a dyad's limit in one sweep is away from it in another.
    plans : sequence of Plan, optional
        The sweeps to join instead of the first ``plans_used`` of :func:`sweep_plans`.

    Returns
    -------
    PoseModes

    Raises
    ------
    ValueError
        When the group has no sweep plan: every link with an external pair is joined to the
        rest through prismatic pairs only (use :func:`newton_modes`).
    """
    chosen = list(sweep_plans(system)[:plans_used] if plans is None else plans)
    if not chosen:
        kinds = ", ".join(f"{j.first}–{j.second} {j.kind}" for j in system.joints)
        raise ValueError(f"no sweep plan for the group with the pairs {kinds}: every link "
                         "with an external pair has only prismatic pairs to the next two "
                         "links; use newton_modes")
    wide, grown = _expand(system, known)
    found = []
    for roles in chosen:
        lo, hi, sigma = _compress(*_brackets(system, roles, known, samples))
        with np.errstate(all="ignore"):
            alpha = _bisect(wide, roles, grown, lo, hi, sigma)
            x = _assemble(wide, roles, grown, alpha, sigma)
            x, residual = wide.polish(x, grown)
        found.append((x, np.where(np.isnan(sigma), np.inf, residual)))
    x = np.concatenate([f[0] for f in found], axis=-2)
    residual = np.concatenate([f[1] for f in found], axis=-1)
    return _distinct(wide, grown, x, residual)


def newton_modes(system: PoseSystem, known: dict[str, Motion], starts: int = 400,
                 seed: int = 0) -> PoseModes:
    """Modes by Newton's method on the full pose system from random starts (the last resort:
    it finds modes, it cannot prove there are no more).

    Parameters
    ----------
    system : PoseSystem
        The group.
    known : dict of str to Motion
        The known links at the position.
    starts : int
        Random starts per design: rotations uniform over a turn, shifts within L.
    seed : int
        Seed of the starts.

    Returns
    -------
    PoseModes
    """
    rng = np.random.default_rng(seed)
    shape = np.shape(system.size) + (starts, 12)
    x = rng.uniform(-1.0, 1.0, shape)
    angle = np.arange(12) % 3 == 2
    x = np.where(angle, np.pi * x, x * np.asarray(system.size)[..., None, None])
    wide, grown = _expand(system, known)
    x, residual = wide.polish(x, grown)
    return _distinct(wide, grown, x, residual)
