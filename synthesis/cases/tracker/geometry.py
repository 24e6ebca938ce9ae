"""Closed-form relations of the rhomboid (kite) orientation mechanism.

The kite four-bar ``A B C D`` has the base ``AD = l1``, the short rocker ``AB = l1`` (it
carries the platform), the coupler ``BC = l2`` and the long rocker ``DC = l3 = l2``;
``k2 = l2 / l1``. On its kite branch the chain is symmetric about the diagonal ``AC``, so the
transmission angle ``b`` at ``B`` (coupler to short rocker) always equals the angle ``ADC``.
The linear actuator joins the base hinge ``E`` (on the line ``D–A`` beyond ``A``,
``|DE| = l5 = k5·l1``) to the joint ``C``. The platform's support post stands at ``A``.

Over the stroke the angle ``ADC`` runs from ``b_min`` (actuator retracted) to
``180° − b_min`` (actuator extended), so the smallest transmission angle is ``b_min`` at
both ends. With ``l1 = 1`` and ``D`` at the origin, ``A = 1`` and ``C = k2·exp(i·ADC)``:

* ``c = arg(k2·e^{i·b_min} − 1)`` and ``d = arg(k2·e^{i·b_min} + 1)`` — the patent's
  ``c = arctg(k2 sin b_min / (k2 cos b_min − 1))``, ``d = arctg(k2 sin b_min /
  (k2 cos b_min + 1))`` with the quadrant kept;
* the platform stroke ``a = 2·(180° − (c + d))``;
* ``k_i = |k2·e^{i·b_min} − k5|``, ``k_d = |k2·e^{i·b_min} + k5|``, ``k_s = k_d − k_i``;
* ``k_g = k2·(k5 − 1)·sin b_min / k_d`` — the distance from ``A`` to the actuator's axis at
  full extension.

Because ``(k2 e^{ib} − 1)(k2 e^{ib} + 1) = k2² e^{2ib} − 1``, the sum ``c + d`` is
``arg(k2² e^{2ib} − 1)``, and the patent's relation can be inverted in closed form: for a
stroke ``a`` put ``s = 180° − a/2``; the point ``P = k2² e^{2ib}`` lies on the ray from 1
at the angle ``s``, ``P = 1 + t e^{is}`` with ``t = −cos s + sqrt(cos² s + k2⁴ − 1)``, and
``b_min = arg(P) / 2``.

All functions broadcast over their arguments (numpy arrays); angles are in radians.

References
----------
.. [1] I. Vișa et al., "Mecanism de orientare", patent application RO a 2010 00677
   (OSIM, 2010), Etapa I–VI and Tabel 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from assur.typing import FloatArray

__all__ = [
    "Proportions",
    "actuator_ratios",
    "check_ratios",
    "half_angles",
    "post_clearance_ratio",
    "proportions",
    "stroke",
    "transmission_for_stroke",
]

ArrayLike = npt.ArrayLike


def check_ratios(k2: ArrayLike, k5: ArrayLike | None = None) -> None:
    """Raise ``ValueError`` unless ``k2 > 1`` (and ``k5 > 1`` when given).

    ``k2 = 1`` makes the kite a rhombus that folds onto its base; ``k5 ≤ 1`` would put the
    actuator's base hinge ``E`` between ``D`` and ``A`` instead of beyond ``A``.
    """
    if np.any(np.asarray(k2, dtype=float) <= 1.0):
        raise ValueError(f"the ratio k2 = l2/l1 must be greater than 1; got {k2!r}")
    if k5 is not None and np.any(np.asarray(k5, dtype=float) <= 1.0):
        raise ValueError(f"the ratio k5 = l5/l1 must be greater than 1; got {k5!r}")


def half_angles(b_min: ArrayLike, k2: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """The patent's angles ``c`` and ``d`` (radians) for a smallest transmission angle.

    Parameters
    ----------
    b_min : array_like
        Smallest transmission angle, radians, in (0, π/2).
    k2 : array_like
        ``l2 / l1`` (> 1).

    Returns
    -------
    c, d : ndarray
        ``arg(k2 e^{i b} − 1)`` and ``arg(k2 e^{i b} + 1)``, radians.
    """
    point = np.asarray(k2, dtype=float) * np.exp(1j * np.asarray(b_min, dtype=float))
    return np.angle(point - 1.0), np.angle(point + 1.0)


def stroke(b_min: ArrayLike, k2: ArrayLike) -> FloatArray:
    """The platform's angular stroke ``a = 2·(π − (c + d))`` (radians)."""
    c, d = half_angles(b_min, k2)
    return 2.0 * (np.pi - (c + d))


def transmission_for_stroke(a: ArrayLike, k2: ArrayLike) -> FloatArray:
    """Smallest transmission angle ``b_min`` that gives the stroke ``a`` (closed form).

    Parameters
    ----------
    a : array_like
        Platform stroke, radians, in (0, 2π).
    k2 : array_like
        ``l2 / l1`` (> 1).

    Returns
    -------
    ndarray
        ``b_min`` in radians, in (0, π/2); it inverts :func:`stroke` exactly.

    Examples
    --------
    >>> round(float(np.degrees(transmission_for_stroke(np.radians(210.0), 2.2))), 2)
    31.74
    """
    a = np.asarray(a, dtype=float)
    if np.any((a <= 0.0) | (a >= 2.0 * np.pi)):
        raise ValueError("the stroke a must lie strictly between 0° and 360°")
    check_ratios(k2)
    s = np.pi - 0.5 * a
    k4 = np.asarray(k2, dtype=float) ** 4
    t = -np.cos(s) + np.sqrt(np.cos(s) ** 2 + k4 - 1.0)
    half: FloatArray = 0.5 * np.angle(1.0 + t * np.exp(1j * s))
    return half


def actuator_ratios(b_min: ArrayLike, k2: ArrayLike, k5: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Extended and retracted actuator lengths over ``l1``: ``(k_d, k_i)``.

    The actuator length ``|EC|`` grows monotonically with the angle ``ADC``; it is shortest
    at ``ADC = b_min`` and longest at ``ADC = π − b_min``.
    """
    point = np.asarray(k2, dtype=float) * np.exp(1j * np.asarray(b_min, dtype=float))
    k5 = np.asarray(k5, dtype=float)
    return np.abs(point + k5), np.abs(point - k5)


def post_clearance_ratio(b_min: ArrayLike, k2: ArrayLike, k5: ArrayLike) -> FloatArray:
    """``k_g = l_g / l1``: distance from the post at ``A`` to the extended actuator's axis."""
    k_d, _ = actuator_ratios(b_min, k2, k5)
    k2 = np.asarray(k2, dtype=float)
    return k2 * (np.asarray(k5, dtype=float) - 1.0) * np.sin(b_min) / k_d


@dataclass(frozen=True)
class Proportions:
    """The patent's quantities for one or many ``(k2, k5)`` (arrays broadcast together).

    Angles in radians; ratios are lengths over ``l1``.

    Attributes
    ----------
    a, k2, k5 : ndarray
        Stroke and the two proportions the quantities were computed for.
    b_min, c, d : ndarray
        Smallest transmission angle and the patent's angles ``c``, ``d``.
    k_d, k_i, k_s, k_g : ndarray
        Actuator extended, retracted, stroke; post clearance.
    """

    a: FloatArray
    k2: FloatArray
    k5: FloatArray
    b_min: FloatArray
    c: FloatArray
    d: FloatArray
    k_d: FloatArray
    k_i: FloatArray
    k_s: FloatArray
    k_g: FloatArray


def proportions(a: ArrayLike, k2: ArrayLike, k5: ArrayLike) -> Proportions:
    """Every closed-form quantity of the patent for a stroke and the proportions.

    Parameters
    ----------
    a : array_like
        Platform stroke, radians.
    k2, k5 : array_like
        ``l2/l1`` and ``l5/l1``; e.g. ``k2`` of shape ``(K2, 1)`` and ``k5`` of shape
        ``(K5,)`` give ``(K2, K5)`` tables.

    Returns
    -------
    Proportions
    """
    check_ratios(k2, k5)
    a, k2, k5 = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (a, k2, k5)))
    b_min = transmission_for_stroke(a, k2)
    c, d = half_angles(b_min, k2)
    k_d, k_i = actuator_ratios(b_min, k2, k5)
    return Proportions(a=a, k2=k2, k5=k5, b_min=b_min, c=c, d=d, k_d=k_d, k_i=k_i,
                       k_s=k_d - k_i, k_g=post_clearance_ratio(b_min, k2, k5))
