"""The patent's printed numbers beside the values of the geometric reading.

Each printed value of :data:`~synthesis.cases.tracker.patent.SERIES` is recomputed from the
closed forms (:mod:`~synthesis.cases.tracker.geometry`) for the patent's stroke of 210° and
compared within the chart-reading tolerance of its quantity. The post clearance ``k_g`` is
reproduced only for ``k2 = 2.2``: for the smaller ``k2`` the printed charts do not follow
from the geometry, and the differences are reported as they are. The angles ``e`` and ``f``
are not defined by the text and are not computed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from synthesis.cases.tracker.geometry import proportions
from synthesis.cases.tracker.patent import EXAMPLE, SERIES, TABLE_MM, TOLERANCES, UNDEFINED

__all__ = ["ANGLES", "Comparison", "reproduce", "reproduce_mm"]

ANGLES: tuple[str, ...] = ("b_min", "c", "d")
"""Quantities printed in degrees."""

_K_G_CHECKED = 2.2


@dataclass(frozen=True)
class Comparison:
    """One printed value beside the computed one.

    Attributes
    ----------
    quantity : str
        Patent name (``'b_min'``, ``'k_s'``, ``'l_d'``, …).
    k2 : float
    k5 : float or None
    source : str
        ``'fig. 9'``, ``'Tabel 1'``, …
    printed : float
        The patent's value (degrees, ratio or mm).
    computed : float or None
        The geometric reading's value; None where the text gives no way to compute it.
    tolerance : float or None
        Allowed difference; None where no agreement is expected.
    """

    quantity: str
    k2: float
    k5: float | None
    source: str
    printed: float
    computed: float | None
    tolerance: float | None

    @property
    def difference(self) -> float | None:
        """Computed minus printed (None where nothing is computed)."""
        return None if self.computed is None else self.computed - self.printed

    @property
    def deviation(self) -> float:
        """|computed − printed|, NaN where nothing is computed."""
        return math.nan if self.computed is None else abs(self.computed - self.printed)

    @property
    def status(self) -> str:
        """How the row compares.

        ``'match'`` (within the tolerance), ``'MISMATCH'`` (outside it), ``'differs'`` (no
        agreement expected) or ``'not derivable'`` (nothing computed).
        """
        if self.computed is None:
            return "not derivable"
        if self.tolerance is None:
            return "differs"
        return "match" if self.deviation <= self.tolerance else "MISMATCH"


def _tolerance(quantity: str, k2: float) -> float | None:
    if quantity == "k_g" and not math.isclose(k2, _K_G_CHECKED):
        return None
    return TOLERANCES[quantity]


def reproduce() -> list[Comparison]:
    """Every printed value of the figure tables and Tabel 1 beside its computed value."""
    a = math.radians(EXAMPLE["stroke_deg"])
    rows: list[Comparison] = []
    for series in SERIES:
        k2 = np.array(list(series.values))
        printed = np.array(list(series.values.values()))
        if series.quantity in UNDEFINED:
            computed: list[float | None] = [None] * len(k2)
        else:
            values = getattr(proportions(a, k2, series.k5 or EXAMPLE["k5"]), series.quantity)
            values = np.degrees(values) if series.quantity in ANGLES else values
            computed = [float(v) for v in values]
        rows.extend(Comparison(series.quantity, float(x), series.k5, series.source, float(p),
                               c, None if c is None else _tolerance(series.quantity, x))
                    for x, p, c in zip(k2, printed, computed, strict=True))
    return rows


def reproduce_mm() -> list[Comparison]:
    """Tabel 1's millimetres beside ``l1 = 300 mm`` times the computed ratios.

    The tolerance is that of the ratio times ``l1`` (``l2`` is exact by definition).
    """
    l1, k5 = EXAMPLE["l1_mm"], EXAMPLE["k5"]
    a = math.radians(EXAMPLE["stroke_deg"])
    rows: list[Comparison] = []
    for name, printed in TABLE_MM.items():
        k2 = np.array(list(printed))
        values = proportions(a, k2, k5)
        ratio = {"l2": values.k2, "l_d": values.k_d, "l_i": values.k_i, "l_s": values.k_s,
                 "l_g": values.k_g}[name]
        tolerance = TOLERANCES.get("k" + name[1:], 1e-9)
        rows.extend(Comparison(name, float(x), k5, "Tabel 1", float(p), float(r * l1),
                               None if name == "l_g" and not math.isclose(x, _K_G_CHECKED)
                               else tolerance * l1)
                    for x, p, r in zip(k2, printed.values(), ratio, strict=True))
    return rows
