"""The numbers printed in the patent application RO a 2010 00677, typed from its text.

Tabel 1 gives the example for the stroke ``a = 210°`` and ``k5 = 2`` with ``k2`` from 1.6 to
2.2; the tables under figs. 4–16 add ``k2 = 1.4`` and the charts for ``k5 = 1.8`` and 2.2.
Fig. 6 (``d``) and fig. 7 (``k_d``) print no table in the text: their values come from
Tabel 1 (Etapa II and III). The example data and the design chosen in Etapa VI are kept as
the patent prints them, inconsistencies included (the report lists them).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "CHOSEN",
    "EXAMPLE",
    "K2",
    "SERIES",
    "TABLE_MM",
    "TOLERANCES",
    "UNDEFINED",
    "Series",
]

K2: tuple[float, ...] = (1.4, 1.6, 1.8, 2.0, 2.2)
"""The discrete values of ``k2 = l2/l1`` of the patent's charts."""


@dataclass(frozen=True)
class Series:
    """One printed row: a quantity against ``k2`` for a stroke and (where it matters) ``k5``.

    Attributes
    ----------
    quantity : str
        ``'b_min'``, ``'c'``, ``'d'`` (degrees) or ``'k_d'``, ``'k_i'``, ``'k_s'``, ``'k_g'``,
        ``'e'``, ``'f'``.
    k5 : float or None
        ``l5/l1``; None for the quantities of the four-bar alone.
    source : str
        Where the row is printed.
    values : dict
        ``k2`` → printed value.
    """

    quantity: str
    k5: float | None
    source: str
    values: dict[float, float]


def _row(values: tuple[float, ...], k2: tuple[float, ...] = K2) -> dict[float, float]:
    return dict(zip(k2, values, strict=True))


_TABEL1_K2 = K2[1:]

SERIES: tuple[Series, ...] = (
    Series("b_min", None, "fig. 4", _row((22.8, 26.5, 28.8, 30.5, 31.8))),
    Series("b_min", None, "Tabel 1", _row((26.5, 28.8, 30.5, 31.8), _TABEL1_K2)),
    Series("c", None, "fig. 5", _row((61.8, 59.0, 56.0, 54.5, 53.0))),
    Series("c", None, "Tabel 1", _row((59.0, 56.0, 54.5, 53.0), _TABEL1_K2)),
    Series("d", None, "Tabel 1", _row((16.5, 18.5, 20.5, 22.0), _TABEL1_K2)),
    Series("k_d", 2.0, "Tabel 1", _row((3.5, 3.7, 3.85, 4.05), _TABEL1_K2)),
    Series("k_i", 2.0, "fig. 8", _row((0.9, 0.9, 0.95, 1.05, 1.15))),
    Series("k_i", 2.0, "Tabel 1", _row((0.9, 0.95, 1.05, 1.15), _TABEL1_K2)),
    Series("k_s", 2.0, "fig. 9", _row((2.45, 2.6, 2.75, 2.8, 2.9))),
    Series("k_s", 2.0, "Tabel 1", _row((2.6, 2.75, 2.8, 2.9), _TABEL1_K2)),
    Series("k_s", 2.2, "fig. 13", _row((2.48, 2.65, 2.8, 2.95, 3.05))),
    Series("k_s", 1.8, "fig. 15", _row((2.4, 2.5, 2.59, 2.65, 2.7))),
    Series("k_g", 2.0, "fig. 12", _row((0.08, 0.14, 0.19, 0.24, 0.29))),
    Series("k_g", 2.0, "Tabel 1", _row((0.14, 0.19, 0.24, 0.29), _TABEL1_K2)),
    Series("k_g", 2.2, "fig. 14", _row((0.085, 0.15, 0.215, 0.275, 0.33))),
    Series("k_g", 1.8, "fig. 16", _row((0.075, 0.12, 0.16, 0.2, 0.24))),
    Series("e", 2.0, "fig. 10", _row((27.0, 40.0, 48.0, 33.5, 22.0))),
    Series("e", 2.0, "Tabel 1", _row((40.0, 48.0, 33.5, 22.0), _TABEL1_K2)),
    Series("f", 2.0, "fig. 11", _row((0.75, 1.7, 2.6, 3.6, 4.4))),
    Series("f", 2.0, "Tabel 1", _row((1.7, 2.6, 3.6, 4.4), _TABEL1_K2)),
)
"""Every printed row, figure tables and Tabel 1 (angles in degrees)."""

TOLERANCES: dict[str, float] = {
    "b_min": 0.1, "c": 0.5, "d": 0.3, "k_d": 0.04, "k_i": 0.04, "k_s": 0.04, "k_g": 0.005,
}
"""How closely a geometric reading must reproduce each printed quantity (chart reading
precision; angles in degrees)."""

UNDEFINED: tuple[str, ...] = ("e", "f")
"""Angles the text names but never defines (they are drawn in fig. 1, which is missing)."""

TABLE_MM: dict[str, dict[float, float]] = {
    "l2": _row((480.0, 540.0, 600.0, 660.0), _TABEL1_K2),
    "l_d": _row((1050.0, 1110.0, 1155.0, 1215.0), _TABEL1_K2),
    "l_i": _row((270.0, 285.0, 315.0, 345.0), _TABEL1_K2),
    "l_s": _row((780.0, 825.0, 840.0, 870.0), _TABEL1_K2),
    "l_g": _row((42.0, 57.0, 72.0, 87.0), _TABEL1_K2),
}
"""Tabel 1 in millimetres (``l1 = 300 mm``, ``l5 = 600 mm``)."""

EXAMPLE: dict[str, float] = {
    "stroke_deg": 210.0, "min_transmission_deg": 25.0, "actuator_stroke_mm": 1000.0,
    "l1_mm": 300.0, "min_clearance_mm": 85.0, "k5": 2.0,
}
"""The worked example's data ("Exemplu de calcul")."""

CHOSEN: dict[str, float] = {
    "k2": 2.2, "b_min": 31.5, "c": 53.0, "d": 22.0, "k5": 2.0, "e": 22.0, "f": 1.4,
    "k_d": 4.05, "k_i": 1.15, "k_s": 2.9, "k_g": 0.29, "l1": 300.0, "l2": 660.0,
    "l5": 600.0, "l_d": 1215.0, "l_i": 345.0, "l_s": 870.0, "l_g": 87.0,
}
"""The design printed in Etapa VI (angles in degrees, lengths in millimetres)."""
