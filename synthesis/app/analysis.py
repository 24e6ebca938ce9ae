"""Kinematic analysis of a table over the input cycle: one function, one result.

:func:`analyse_table` reads a chain table with a ``geometry:`` sketch or an identification
table with ``params:``, solves the groups in layering order with the first and second
analogs, and checks the existence of every group; :class:`TableAnalysis` holds the model,
the motion and the existence report. ``assur analyze`` renders it as text
(:mod:`synthesis.app.analysis_text`), JSON (:mod:`synthesis.app.analysis_json`) or CSV
(:mod:`synthesis.app.analysis_csv`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from assur import (
    ExistenceReport,
    Jet,
    KinematicModel,
    Motion,
    TableError,
    analyse,
    check_existence,
)
from assur.errors import Issue
from assur.io.chain_table import load_chain
from assur.kinematics.build import build_model
from assur.model import LinkId
from assur.structure.analysis import analyse_structure
from assur.text import Message

__all__ = ["TableAnalysis", "analyse_table", "moving_links"]

#: The fewest positions an analysis takes.
MIN_POINTS = 2


@dataclass(frozen=True)
class TableAnalysis:
    """The kinematic analysis of one table.

    Attributes
    ----------
    model : KinematicModel
    motion : Motion
        Every position, with the first and second analogs.
    existence : ExistenceReport
        Existence of every group at the same positions.
    allowed_pressure : mapping
        Every group label → allowable pressure angle, degrees: the table's own
        (``general: {allowable: [...]}``, as a synthesis result keeps its problem's), else
        the program default 45°.
    omega : float or None
        Input speed (rad/s of a crank, mm/s of an actuator) for velocities and
        accelerations; None: analogs only.
    warnings : tuple of Issue
        What looks wrong in the table but did not refuse it (:attr:`Chain.warnings`).
    """

    model: KinematicModel
    motion: Motion
    existence: ExistenceReport
    allowed_pressure: Mapping[str, float]
    omega: float | None = None
    warnings: tuple[Issue, ...] = ()

    @property
    def crank(self) -> bool:
        """Whether the input is a crank (else a linear actuator)."""
        return self.model.drive == "crank"

    def index_at(self, at: float) -> int:
        """The analysed position nearest to ``at`` (crank angle in degrees, or actuator
        length in mm)."""
        q = self.motion.q
        if self.crank:
            distance = np.abs(np.angle(np.exp(1j * (q - math.radians(at)))))
        else:
            distance = np.abs(q - at)
        return int(np.argmin(distance))


def analyse_table(path: str | os.PathLike[str], *, points: int = 360,
                  omega: float | None = None) -> TableAnalysis:
    """Analyse a table's mechanism over the input cycle.

    Parameters
    ----------
    path : path-like
        A chain table with a ``geometry:`` sketch, or an identification table with
        ``params:``.
    points : int
        Positions over the cycle (at least 2).
    omega : float, optional
        Input speed (rad/s of a crank, mm/s of an actuator), kept for the renderers.

    Returns
    -------
    TableAnalysis

    Raises
    ------
    TableError
        When ``points`` is too small or the table is wrong (every problem listed).
    StructureError
        When the chain is not a class II mechanism with one input.

    Examples
    --------
    >>> from pathlib import Path
    >>> import synthesis
    >>> tables = Path(synthesis.__file__).parents[1] / "input_tables"
    >>> from synthesis.app.analysis import analyse_table
    >>> result = analyse_table(tables / "course_11_link.yaml", points=36)
    >>> result.motion.q.shape, result.existence.all_exist
    ((36,), True)
    """
    if points < MIN_POINTS:
        raise TableError("--points", [Issue("--points", Message(
            "cli.points_at_least", {"low": MIN_POINTS, "found": points}))])
    from synthesis.problem import allowed_pressure_angles

    chain = load_chain(path)
    model = build_model(analyse_structure(chain))
    motion = analyse(model, points=points, analogs=True)
    return TableAnalysis(model, motion, check_existence(model, motion=motion),
                         allowed_pressure_angles(chain.general, model), omega, chain.warnings)


def moving_links(model: KinematicModel) -> list[LinkId]:
    """The moving links in the order of their numbers (named links after numbered ones)."""
    return sorted(model.links, key=lambda link: (isinstance(link, str), str(link).zfill(6)))


def as_jet(value: Jet | np.ndarray) -> Jet:
    """A quantity of a motion as a jet (a plain array has zero analogs)."""
    return value if isinstance(value, Jet) else Jet(value, 0.0, 0.0)
