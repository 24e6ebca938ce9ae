"""The library's verbs: read a mechanism table, check it, analyse its motion and forces.

``assur check`` imports this module, so what only the analysis needs (the solvers, the force
analysis, the JSON record) is imported where it is used.

Each verb is what one command runs, and each result prints as a few lines and turns into
the record that the command's ``--json`` prints:

=============================  =====================  =========================================
verb                           command                result
=============================  =====================  =========================================
:func:`load`                   (every command)        :class:`~assur.model.Chain`
:func:`check`                  ``assur check``        :class:`~assur.assessment.Assessment`
:func:`analyse`                ``assur analyze``      :class:`Analysis`
=============================  =====================  =========================================

Examples
--------
>>> from pathlib import Path
>>> import assur
>>> table = Path(assur.__file__).parents[1] / "input_tables" / "four_bar.yaml"
>>> chain = assur.load(table)
>>> assur.check(chain, points=None).identification
'not given'
>>> assur.analyse(chain, points=12).motion.q.shape
(12,)
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from assur.assessment import Assessment, assess
from assur.errors import Issue, TableError
from assur.io.chain_table import load_chain
from assur.kinematics.build import build_model
from assur.model import Chain
from assur.structure.analysis import analyse_structure
from assur.text import Message

if TYPE_CHECKING:  # pragma: no cover
    from assur.forces.solver import ForceAnalysis
    from assur.kinematics.analysis import Motion
    from assur.kinematics.existence import ExistenceReport
    from assur.kinematics.model import KinematicModel

__all__ = ["MIN_POINTS", "Analysis", "analyse", "check", "load"]

#: The fewest positions an analysis takes.
MIN_POINTS = 2

#: A table file, or a chain already read.
ChainLike = Chain | str | os.PathLike[str]


@dataclass(frozen=True)
class Analysis:
    """The kinematic analysis of a mechanism over the input cycle, and its force analysis.

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
    forces : ForceAnalysis or None
        The kinetostatics at the same positions, when asked for.
    warnings : tuple of Issue
        What looks wrong in the table but did not refuse it (:attr:`Chain.warnings`).

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> table = Path(assur.__file__).parents[1] / "input_tables" / "four_bar_gravity.yaml"
    >>> result = assur.analyse(table, points=36, forces=True, omega=10.0)
    >>> for line in repr(result).splitlines()[1:]:
    ...     print(line)
      crank: 36 positions, 0…350 deg, omega=10.0
      groups: L0(1), L1(2,3)
      every group assembles: True
      forces: driving_torque, solved at 36 of 36 positions)
    >>> sorted(result.to_dict()["forces"])[:3]
    ['driving_torque', 'driving_torque_lever', 'gravity']
    """

    model: KinematicModel
    motion: Motion
    existence: ExistenceReport
    allowed_pressure: Mapping[str, float]
    omega: float | None = None
    forces: ForceAnalysis | None = None
    warnings: tuple[Issue, ...] = ()

    @property
    def crank(self) -> bool:
        """Whether the input coordinate is an angle: a crank's rotation, or the cycle
        parameter t of several inputs' laws (else a length: an actuator's, or a slider's
        displacement)."""
        return self.model.drive in ("crank", "laws")

    def index_at(self, at: float) -> int:
        """The analysed position nearest to ``at`` (crank angle in degrees, or actuator
        length in mm)."""
        q = self.motion.q
        if self.crank:
            distance = np.abs(np.angle(np.exp(1j * (q - math.radians(at)))))
        else:
            distance = np.abs(q - at)
        return int(np.argmin(distance))

    def to_dict(self) -> dict[str, Any]:
        """Every position as a JSON-ready mapping: what ``assur analyze --json`` prints
        (:func:`assur.records.analysis_record`, with ``forces``,
        :meth:`ForceAnalysis.to_dict`, when the forces were analysed)."""
        from assur.records import analysis_record

        record = analysis_record(self)
        record["warnings"] = [issue.to_dict() for issue in self.warnings]
        if self.forces is not None:
            record["forces"] = self.forces.to_dict()
        return record

    def __repr__(self) -> str:
        q = self.motion.q
        unit = "deg" if self.crank else "mm"
        span = np.degrees(q) if self.crank else q
        groups = ", ".join(group.label for group in self.model.groups)
        lines = [f"Analysis({self.model.name!r} from {self.model.source!r}",
                 (f"  {self.model.drive}: {q.size} positions, "
                  f"{span.min():g}…{span.max():g} {unit}, omega={self.omega}"),
                 f"  groups: {groups}",
                 f"  every group assembles: {self.existence.all_exist}"]
        if self.forces is not None:
            solved = int(np.count_nonzero(self.forces.reason == 0))
            lines.append(f"  forces: {self.forces.drive}, solved at {solved} of {q.size} "
                         "positions")
        return "\n".join(lines) + ")"


def load(path: str | os.PathLike[str]) -> Chain:
    """Read a mechanism table: a chain table or a DGTU identification table.

    Parameters
    ----------
    path : path-like
        The YAML file.

    Returns
    -------
    Chain

    Raises
    ------
    TableError
        Every problem of the table at once, each with its table, row and field.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> tables = Path(assur.__file__).parents[1] / "input_tables"
    >>> chain = assur.load(tables / "course_11_link_table.yaml")
    >>> chain.frame, len(chain.links), len(chain.identification)
    (0, 12, 6)
    """
    return load_chain(path)


def check(chain: ChainLike, *, points: int | None = 360) -> Assessment:
    """Check a student's table the way the course does: structure, the identification table
    (the program's and the student's), assembly variants, existence over the cycle.

    ``assur check``, ``assur batch`` and ``assur report`` all render this one result.

    Parameters
    ----------
    chain : Chain or path-like
        A chain, or the file of a chain table or an identification table.
    points : int or None
        Crank positions of the existence check (the interval ends are refined anyway);
        None leaves the existence out.

    Returns
    -------
    Assessment
        Problems of the mechanism are findings of the result, never exceptions.

    Raises
    ------
    TableError
        When the file cannot be read as a table (every problem listed).

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> tables = Path(assur.__file__).parents[1] / "input_tables"
    >>> found = assur.check(tables / "course_11_link_table.yaml", points=36)
    >>> found.identification, found.existence.all_exist
    ('matches', True)
    >>> found.to_dict()["W"]
    1
    """
    return assess(chain if isinstance(chain, Chain) else load_chain(chain), points=points)


def analyse(chain: ChainLike, points: int = 360, forces: bool = False,
            omega: float | None = None) -> Analysis:
    """The motion of a mechanism over the input cycle, and its forces when asked for.

    Parameters
    ----------
    chain : Chain or path-like
        A chain with dimensions (a ``geometry:`` sketch or rows with ``params:``), or its
        file.
    points : int
        Positions over the cycle (at least :data:`MIN_POINTS`).
    forces : bool
        Also run the force analysis (``docs/forces.md``) with the table's ``masses:``,
        ``loads:`` and ``gravity:``.
    omega : float, optional
        Input speed (rad/s of a crank, mm/s of an actuator) for velocities and
        accelerations; needed for the forces (0: the static analysis).

    Returns
    -------
    Analysis

    Raises
    ------
    TableError
        When ``points`` is too small, the table is wrong, or the forces are asked for
        without force sections or without ``omega`` (every problem listed).
    StructureError
        When the chain is not a mechanism the kinematics solves.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> tables = Path(assur.__file__).parents[1] / "input_tables"
    >>> result = assur.analyse(tables / "four_bar_gravity.yaml", points=36, forces=True,
    ...                        omega=10.0)
    >>> result.motion.q.shape, result.existence.all_exist, result.forces.drive
    ((36,), True, 'driving_torque')
    >>> len(repr(result).splitlines()) <= 20
    True
    """
    if points < MIN_POINTS:
        raise TableError("--points", [Issue("--points", Message(
            "cli.points_at_least", {"low": MIN_POINTS, "found": points}))])
    from assur.kinematics.analysis import analyse as motion_of
    from assur.kinematics.existence import check_existence

    chain = chain if isinstance(chain, Chain) else load_chain(chain)
    model = build_model(analyse_structure(chain))
    motion = motion_of(model, points=points, analogs=True)
    existence = check_existence(model, motion=motion)
    allowed = chain.general.pressure_angles(model)
    if not forces:
        return Analysis(model, motion, existence, allowed, omega, warnings=chain.warnings)
    issues = []
    if chain.forces is None:
        issues.append(Issue("--forces", Message("force.cli.no_sections", {})))
    if omega is None:
        issues.append(Issue("--omega", Message("force.cli.no_omega", {})))
    if chain.forces is None or omega is None:
        raise TableError(chain.source, issues)
    from assur.forces.solver import kinetostatics

    return Analysis(model, motion, existence, allowed, omega,
                    kinetostatics(motion, chain.forces, omega), chain.warnings)
