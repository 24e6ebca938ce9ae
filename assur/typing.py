"""Type aliases shared by :mod:`assur` and :mod:`synthesis`.

Every module that names one of these types imports it from here, so an alias means the same
everywhere and is changed in one place.

Attributes
----------
FloatArray : type alias
    ``numpy.typing.NDArray[numpy.float64]``: real values — angles (rad), lengths (mm),
    criteria, design vectors.
ComplexArray : type alias
    ``numpy.typing.NDArray[numpy.complex128]``: points of the plane, ``x + 1j * y`` (mm).
BoolArray : type alias
    ``numpy.typing.NDArray[numpy.bool_]``: masks, e.g. where a mechanism assembles.
IntArray : type alias
    ``numpy.typing.NDArray[numpy.int_]``: indices and codes, e.g. a reason per position.
Value : type alias
    What a position solver takes and gives for one quantity: a
    :class:`~assur.kinematics.jets.Jet` (a value with its derivatives along the input), an
    ndarray over designs and positions, or a plain number (points complex, angles and
    lengths real).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from assur.kinematics.jets import Jet

__all__ = ["BoolArray", "ComplexArray", "FloatArray", "IntArray", "Value"]

FloatArray = npt.NDArray[np.float64]
ComplexArray = npt.NDArray[np.complex128]
BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int_]
Value = Jet | np.ndarray | complex | float
