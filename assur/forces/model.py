"""The inputs of a force analysis: masses, loads (constant or tabulated) and gravity.

Everything is kept in table units: points in mm (sketch points, at the sketched position),
forces in N, torques in N·m, masses in kg, moments of inertia in kg·m² about the centre of
mass, gravity in m/s². A tabulated value is a function of the input coordinate: the crank
angle in degrees from the sketched position (periodic over 360°), or the actuator length in
mm (constant beyond the ends).

Examples
--------
>>> import numpy as np
>>> table = Tabulated(nodes=(0.0, 180.0, 360.0), values=(-500.0, 0.0, -500.0))
>>> table.at(np.radians([90.0, 450.0]), periodic=True).tolist()
[-250.0, -250.0]
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from assur.model import LinkId

__all__ = ["ForceData", "Load", "Mass", "Tabulated"]

#: A value per design: a number, or an array broadcast against the positions (``(D, 1)``).
PerDesign = float | npt.NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Tabulated:
    """A value given at nodes of the input coordinate, linear between them.

    Parameters
    ----------
    nodes : tuple of float
        Strictly increasing: crank angles in degrees from the sketched position, inside
        [0, 360], or actuator lengths in mm.
    values : tuple of float or complex
        The value at each node (a force as the complex number Fx + i·Fy, N; a torque, N·m).
    """

    nodes: tuple[float, ...]
    values: tuple[complex | float, ...]

    def at(self, q: np.ndarray, *, periodic: bool) -> np.ndarray:
        """The value at input positions ``q``.

        Parameters
        ----------
        q : ndarray
            Crank rotation in radians from the sketched position (``periodic``), or actuator
            lengths in mm.
        periodic : bool
            Crank input: evaluate at φ mod 360°, the table wrapped around (a node at 360
            repeats the value at 0 and is dropped). Otherwise constant beyond the ends.

        Returns
        -------
        ndarray
            Shaped like ``q``.

        Examples
        --------
        >>> Tabulated((10.0, 20.0), (1.0, 3.0)).at(np.array([0.0, 15.0, 99.0]),
        ...                                        periodic=False).tolist()
        [1.0, 2.0, 3.0]
        """
        nodes = np.asarray(self.nodes, dtype=float)
        values = np.asarray(self.values)
        if not periodic:
            return np.asarray(np.interp(q, nodes, values))
        if nodes[-1] == 360.0 and nodes.size > 1:
            nodes, values = nodes[:-1], values[:-1]
        return np.asarray(np.interp(np.degrees(q) % 360.0, nodes, values, period=360.0))


@dataclass(frozen=True, slots=True)
class Mass:
    """Inertia data of one moving link.

    Each value is one number, or (for a batch of designs whose masses follow their
    dimensions) an array that broadcasts against the kinematics' arrays: shape ``(D, 1)``
    for D designs × positions.

    Parameters
    ----------
    mass : float or ndarray
        kg, ≥ 0.
    centre : complex or ndarray or None
        Centre of mass as a sketch point x + i·y (mm), fixed on the link (or a point of the
        link's frame, see ``ForceData.local``); None when the mass is 0.
    inertia : float or ndarray
        Moment of inertia about the centre, kg·m², ≥ 0.
    """

    mass: PerDesign
    centre: complex | npt.NDArray[np.complex128] | None = None
    inertia: PerDesign = 0.0


@dataclass(frozen=True, slots=True)
class Load:
    """An external force (at a point of the link) or torque on one moving link.

    Parameters
    ----------
    link : link id
        The loaded link.
    force : complex or Tabulated or None
        Fx + i·Fy in global axes (N); its direction does not turn with the link.
    point : complex or None
        Sketch point of the link where the force acts (mm); required with ``force``.
    torque : float or Tabulated or None
        N·m, counter-clockwise positive.
    """

    link: LinkId
    force: complex | Tabulated | None = None
    point: complex | None = None
    torque: float | Tabulated | None = None


@dataclass(frozen=True, slots=True)
class ForceData:
    """The ``masses:``, ``loads:`` and ``gravity:`` sections of a table.

    Parameters
    ----------
    masses : mapping
        Moving link → :class:`Mass`.
    loads : tuple of Load
    gravity : complex
        gx + i·gy, m/s² (0 for none).
    local : bool
        The points (centres of mass, points of forces) are given in each link's own frame
        of the kinematics (origin and axis of ``Motion.frames``, mm) rather than as sketch
        points: so they follow a design whose dimensions change (synthesis).

    Examples
    --------
    >>> data = ForceData({2: Mass(1.2, 80 + 60j, 0.004)}, (Load(3, torque=-20.0),), -9.81j)
    >>> data.weight(2)
    -11.772j
    """

    masses: Mapping[LinkId, Mass] = field(default_factory=dict)
    loads: tuple[Load, ...] = ()
    gravity: complex = 0j
    local: bool = False

    def weight(self, link: LinkId) -> complex | npt.NDArray[np.complexfloating]:
        """The weight m·g of a link, N (0 without a mass; an array for masses per design)."""
        mass = self.masses.get(link)
        return 0j if mass is None else mass.mass * self.gravity

    @property
    def links(self) -> tuple[LinkId, ...]:
        """The links that carry a mass or a load, in table order."""
        return tuple(dict.fromkeys([*self.masses, *(load.link for load in self.loads)]))
