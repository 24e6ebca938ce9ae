"""The checks of a force analysis (``docs/forces.md`` §5).

:func:`lever_torque` is the driving torque by the principle of virtual power (Zhukovsky's
lever in analytic form): the sum of the powers of every load and inertia force per unit
input speed; reactions do no work and drop out. :func:`link_residuals` sums, from the
reported reactions alone, the forces and moments on every moving link.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np

from assur.forces.groups import cross
from assur.model import LinkId

__all__ = ["LinkResidual", "Power", "lever_torque", "link_residuals"]


@dataclass(frozen=True, slots=True)
class LinkResidual:
    """The Newton–Euler residual of one link, relative to its largest term.

    ``force`` = |Σ F| / max |force term|, ``moment`` = |Σ M| / max |moment term| (moments
    about the link's frame origin; the size of the moment of a force R at arm r is |r|·|R|);
    0 where every term is 0, NaN where not solved.
    """

    force: np.ndarray
    moment: np.ndarray


@dataclass(frozen=True, slots=True)
class Power:
    """The power of the known loads per unit input speed and the sum of its magnitudes.

    ``total`` = Σ f·P′ + Σ T·θ′ (loads, weights, inertia forces and torques; N·m per rad or N),
    ``scale`` = Σ |each term|.
    """

    total: np.ndarray
    scale: np.ndarray


def lever_torque(power: Power, rate: float | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The driving torque (or force) from the power balance, and its round-off scale.

    Parameters
    ----------
    power : Power
        The power of every known load per unit input speed.
    rate : float or ndarray
        θ_in′, the derivative of the input link's angle with respect to the input coordinate
        (±1 for a crank; 1 for an actuator, whose force works along its own length; per
        position when the input follows a law of the cycle parameter).

    Returns
    -------
    driving, scale : ndarray
        M_d with M_d·θ_in′ + Σ power = 0, and Σ |terms| / |θ_in′|.

    Examples
    --------
    >>> t, s = lever_torque(Power(np.array([2.0]), np.array([3.0])), -1.0)
    >>> t.tolist(), s.tolist()
    ([2.0], [3.0])
    """
    return -power.total / rate, power.scale / abs(rate)


def link_residuals(known: Mapping[LinkId, tuple[np.ndarray, np.ndarray]],
                   origins: Mapping[LinkId, np.ndarray],
                   reactions: Iterable[tuple[tuple[LinkId, LinkId], np.ndarray, np.ndarray,
                                             np.ndarray | None]]) -> dict[LinkId, LinkResidual]:
    """Σ F and Σ M on every moving link from its known loads and the reported reactions.

    Parameters
    ----------
    known : mapping
        Link → (resultant known force, N; its moment about the link's origin, N·m).
    origins : mapping
        Link → its origin (m, complex).
    reactions : iterable
        ((a, b), force of a on b (N, complex), its point (m), couple of a on b about that
        point (N·m) or None) for every pair, and the drive in the same form (the frame's
        driving torque on the crank, or the actuator's force on its sliding member).

    Returns
    -------
    dict
        Link → :class:`LinkResidual`.

    Examples
    --------
    A link pushed by 5 N at its origin and held by a pair with the frame:

    >>> z = np.zeros(1)
    >>> out = link_residuals({1: (z + 5, z)}, {1: z + 0j}, [((0, 1), z - 5 + 0j, z + 0j, None)])
    >>> float(out[1].force[0]), float(out[1].moment[0])
    (0.0, 0.0)
    """
    out = {}
    for link, (force, moment) in known.items():
        origin = origins[link]
        forces = [(force, np.abs(force))]
        moments = [(moment, np.abs(moment))]
        for (a, b), r, point, couple in reactions:
            if link not in (a, b):
                continue
            sign = 1.0 if link == b else -1.0
            size = np.abs(r)
            arm = point - origin
            forces.append((sign * r, size))
            moments.append((sign * cross(arm, r), np.abs(arm) * size))
            if couple is not None:
                moments.append((sign * couple, np.abs(couple)))
        out[link] = LinkResidual(_relative(forces), _relative(moments))
    return out


def _relative(terms: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """|Σ terms| / the largest term's size (0 where every term vanishes)."""
    total = np.abs(sum((t for t, _ in terms[1:]), terms[0][0]))
    largest = np.maximum.reduce([size for _, size in terms])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.asarray(np.where(largest > 0, total / largest, total))
