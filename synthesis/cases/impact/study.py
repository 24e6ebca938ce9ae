"""One run of the case: the position, both models, energies, the α-slip and Table 1 check."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from assur.typing import FloatArray
from synthesis.cases.impact.data import PAPER, TABLE_1, ImpactData
from synthesis.cases.impact.energy import AlphaSlip, EnergyBalance, alpha_slip, energy_balance
from synthesis.cases.impact.models import (
    ImpactResult,
    Lever,
    solve_paper,
    solve_townsend_mansour,
)
from synthesis.cases.impact.position import ImpactPosition, impact_position

__all__ = ["ImpactStudy", "TableCheck", "run_study"]


@dataclass(frozen=True, slots=True)
class TableCheck:
    """Table 1 of the source beside the computed one.

    Attributes
    ----------
    printed, computed, relative : dict of (str, str) to ndarray
        Per (column, model): the paper's three rows, the computed ones (same units) and the
        relative differences ``computed / printed − 1``.
    """

    printed: dict[tuple[str, str], FloatArray]
    computed: dict[tuple[str, str], FloatArray]
    relative: dict[tuple[str, str], FloatArray]

    def worst(self) -> dict[tuple[str, str], float]:
        """The largest absolute relative difference of each column."""
        return {key: float(np.max(np.abs(value))) for key, value in self.relative.items()}


@dataclass(frozen=True, slots=True)
class ImpactStudy:
    """Everything the report and the picture show.

    Attributes
    ----------
    data : ImpactData
    lever : str
        Restitution lever used (``'paper'`` as printed or ``'exact'``).
    position : ImpactPosition
        Shape ``(len(data.omega4),)``: one impact per rocker velocity.
    results, energy : dict
        Per model key (``'TM'``, ``'P'``).
    slip : AlphaSlip
    table : TableCheck or None
        Present when the data are the source's (the comparison with Table 1 applies),
        whichever restitution lever is used.
    """

    data: ImpactData
    lever: str
    position: ImpactPosition
    results: dict[str, ImpactResult]
    energy: dict[str, EnergyBalance]
    slip: AlphaSlip
    table: TableCheck | None


def run_study(data: ImpactData = PAPER, *, lever: Lever = "paper") -> ImpactStudy:
    """Solve the case for the given data (by default the source's)."""
    position = impact_position(data)
    results = {"TM": solve_townsend_mansour(data, position, lever=lever),
               "P": solve_paper(data, position, lever=lever)}
    energy = {key: energy_balance(data, position, result) for key, result in results.items()}
    table = _check_table(results) if data.same_as(PAPER) else None
    return ImpactStudy(data=data, lever=lever, position=position, results=results,
                       energy=energy, slip=alpha_slip(data, position), table=table)


def _check_table(results: dict[str, ImpactResult]) -> TableCheck:
    printed: dict[tuple[str, str], FloatArray] = {}
    computed: dict[tuple[str, str], FloatArray] = {}
    for column, models in TABLE_1.items():
        for model, values in models.items():
            printed[column, model] = np.asarray(values, dtype=float)
            computed[column, model] = results[model].paper_units()[column]
    relative = {key: computed[key] / printed[key] - 1.0 for key in printed}
    return TableCheck(printed=printed, computed=computed, relative=relative)
