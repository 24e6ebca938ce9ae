"""The assembly variants written in a student's identification table, against the sketch.

The structure alone cannot tell the assembly variant σ of an RRR or RRP dyad (``method.md``
§3.4 rule 7 only limits it to ±1); the dimensions can. When a table gives both the
identification rows and the dimensions, every L1/L2 row's ``variant`` must be the σ in which
the dimensions assemble that group.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

__all__ = ["variant_findings"]


def variant_findings(model: Any, rows: Iterable[Mapping[str, Any]], lang: str = "en",
                     *, table: str = "structure_identification") -> list[tuple[int, str]]:
    """Rows whose ``variant`` differs from the σ of the kinematic model.

    Parameters
    ----------
    model : KinematicModel
        Built from the same table's dimensions.
    rows : iterable of mappings
        The identification rows as given (keys ``L``, ``i``, ``j``, ``variant``).
    lang : {"en", "ru"}

    Returns
    -------
    list of (row index, sentence)
    """
    sigma = {(g.i, g.j): g.sigma for g in model.groups if g.kind in (1, 2)}
    found = []
    for index, row in enumerate(rows):
        key = (row.get("i"), row.get("j"))
        given = row.get("variant")
        if key not in sigma or given not in (1, -1) or given == sigma[key]:
            continue
        where = f"{table}[{index}] (L{row.get('L')}, links {key[0]}, {key[1]}) 'variant'"
        if lang == "ru":
            found.append((index, f"{where}: по размерам группа собирается в варианте "
                                 f"{sigma[key]}, в таблице указано {given}"))
        else:
            found.append((index, f"{where}: the dimensions assemble this group in the variant "
                                 f"{sigma[key]}, the table says {given}"))
    return found
