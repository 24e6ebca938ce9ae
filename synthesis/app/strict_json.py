"""The one way every command prints JSON: strict JSON, never a bare ``NaN`` or ``Infinity``.

A number that is not finite (a quantity not solved at a position, a criterion of a design
that could not be assembled) is written as ``null``; the record that holds it carries its
reason beside it (``reason``, ``status``). ``allow_nan=False`` then guards the output: a value
that slipped through would be a bug, not invalid JSON on the user's screen.

Examples
--------
>>> import numpy as np
>>> strict_json({"torque": [1.5, float("nan")], "omega": np.float64("inf"), "n": np.int64(3)})
'{"torque": [1.5, null], "omega": null, "n": 3}'
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["finite", "strict_json"]


def finite(data: Any) -> Any:
    """``data`` with every non-finite number replaced by None, NumPy scalars and arrays as
    Python numbers and lists (mappings, lists and tuples walked through)."""
    if isinstance(data, Mapping):
        return {key: finite(value) for key, value in data.items()}
    if isinstance(data, list | tuple):
        return [finite(value) for value in data]
    if isinstance(data, np.ndarray):
        return finite(data.tolist())
    if isinstance(data, np.generic):
        return finite(data.item())
    if isinstance(data, float) and not math.isfinite(data):
        return None
    return data


def strict_json(data: Any, *, indent: int | None = None) -> str:
    """``data`` as strict JSON text (UTF-8 letters kept; any other object as its text).

    Parameters
    ----------
    data : object
        A JSON-ready structure (``to_dict`` of a result).
    indent : int, optional
        As for :func:`json.dumps`.

    Returns
    -------
    str
    """
    return json.dumps(finite(data), ensure_ascii=False, indent=indent, allow_nan=False,
                      default=str)
