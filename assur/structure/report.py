"""Text report of a structural analysis, in English or Russian, in the course's own terms.

>>> from assur.io.chain_table import chain_from_dict
>>> from assur.structure.analysis import analyse_structure
>>> chain = chain_from_dict({"mechanism": {"pairs": [
...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
...     {"id": "C", "type": "R", "links": [2, 3]}, {"id": "D", "type": "R", "links": [3, 0]}],
...     "inputs": [1]}}, source="four_bar.yaml")
>>> print(structure_report(analyse_structure(chain), lang="ru").splitlines()[-1])
Метод ДГТУ применим: да
"""

from __future__ import annotations

from collections.abc import Sequence

from assur.structure.analysis import StructuralAnalysis
from assur.structure.classification import AssurGroup, roman, signature
from assur.structure.group_models import GroupModelRow
from assur.structure.identification import IdentificationRow, Mismatch
from assur.text import Message, joined, render

__all__ = ["ORDERS", "PRINTED", "group_description", "higher_pair_lines", "in_order", "models_lines",
           "structure_report", "table_lines"]

#: The orders table 1.6 is printed in: ``course`` by kind L0…L5 as the course's table 1.6
#: (groups of one kind in layering order), ``layering`` in layering order.
ORDERS = ("course", "layering")
#: The columns of table 1.6 as the course prints them (no ``seq``).
PRINTED = ("L", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1", "j_plus_1", "variant",
            "out_code")


def _external(group: AssurGroup) -> Message | str:
    parts = [Message("report.group.external", {"pair": p, "member": g, "known": k})
             for p, g, k in group.external]
    return joined(parts) if parts else "—"


def _group_head(group: AssurGroup) -> Message:
    values = {"level": group.level, "cls": group.group_class, "order": group.order,
              "name": signature(group.name)}
    if group.name == "PPP":
        return Message("report.group.ppp", values)
    if group.is_dyad:
        kind = group.group_kind
        pairs = Message(f"{kind.key}.pairs") if kind is not None else group.name
        return Message("report.group.dyad", {**values, "kind": group.kind, "pairs": pairs,
                                             "i": group.i, "j": group.j})
    if group.group_class == 3 and group.order in (2, 3):
        return Message(f"report.group.iii_order{group.order}", values)
    return Message("report.group.other", values)


def group_description(group: AssurGroup, lang: str = "en") -> str:
    """One line describing a group in the course's terms."""
    if group.group_class == 1:
        return render("report.group.input", lang, frame=group.i_minus_1, link=group.i,
                      pair=group.pair_i)
    line = render("report.group.pair" if len(group.internal) == 1 else "report.group.pairs",
                  lang, head=_group_head(group), external=_external(group),
                  internal=", ".join(map(str, group.internal)) or "—")
    if group.composite:
        line += render("report.group.composite", lang,
                       members=", ".join(map(str, group.composite)))
    return line


def _cell(value: object) -> str:
    if value is None:
        return "–"
    if isinstance(value, list):
        return ";".join(map(str, value))
    return str(value)


def in_order(rows: Sequence[IdentificationRow], order: str = "course"
             ) -> list[IdentificationRow]:
    """The rows of table 1.6 in a printed order (:data:`ORDERS`): by kind L0…L5 as the
    course prints them, or in layering order.

    >>> from assur.model import IdentificationRow
    >>> rows = [IdentificationRow(0, 1, 0, None, 1, None, 2, None, None, None),
    ...         IdentificationRow(4, 2, 3, 0, 4, 5, None, None, None, None),
    ...         IdentificationRow(3, 3, 2, 0, 6, 7, None, None, 0, None)]
    >>> [row.L for row in in_order(rows)], [row.L for row in in_order(rows, "layering")]
    ([0, 3, 4], [0, 4, 3])
    """
    if order not in ORDERS:
        raise ValueError(f"order must be one of {ORDERS}; got {order!r}")
    if order == "layering":
        return sorted(rows, key=lambda row: row.seq or 0)
    return sorted(rows, key=lambda row: (row.L, row.seq or 0))


def table_lines(rows: Sequence[IdentificationRow], lang: str = "en", order: str = "course"
                ) -> list[str]:
    """Table 1.6 as text: the course's columns, the rows in ``order``."""
    header = ["L", "i-1", "j-1", "i", "j", "i+1", "j+1", render("report.table.variant", lang),
              render("report.table.code", lang)]
    cells = [[_cell(getattr(row, key)) for key in PRINTED] for row in in_order(rows, order)]
    return _aligned(header, cells)


def models_lines(rows: Sequence[GroupModelRow], lang: str = "en") -> list[str]:
    """Table 1.5 as text, one record per group in layering order."""
    header = ["k", "L", "i", "j", render("report.models.external_i", lang),
              render("report.models.internal", lang), render("report.models.external_j", lang),
              "N", "M", "A_k", "B_k"]
    return _aligned(header, [row.cells() for row in rows])


def _aligned(header: Sequence[str], cells: Sequence[Sequence[str]]) -> list[str]:
    widths = [max(len(h), *(len(c[k]) for c in cells)) for k, h in enumerate(header)]
    lines = ["  " + "  ".join(h.rjust(w) for h, w in zip(header, widths, strict=True))]
    lines += ["  " + "  ".join(c.rjust(w) for c, w in zip(line, widths, strict=True))
              for line in cells]
    return lines


def _verdict(mismatches: Sequence[Mismatch] | None, given: int, lang: str, stem: str
             ) -> list[str]:
    """The verdict on a student's table: agrees, or every mismatch."""
    if mismatches is None:
        return []
    if mismatches:
        return ["", render(f"{stem}_differs", lang, n=len(mismatches)),
                *(f"  - {m.text(lang)}" for m in mismatches)]
    return ["", render(f"{stem}_agrees", lang, k=given)]


def higher_pair_lines(a: StructuralAnalysis, lang: str = "en") -> list[str]:
    """The passive degrees of freedom, subtracted with their reasons, and the replacing
    mechanism of a chain with higher pairs, as lines (nothing for a chain without).

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/cam_lever.yaml"
    >>> print(higher_pair_lines(assur.analyse_structure(assur.load_chain(table)))[0])
    passive degrees of freedom: 1, subtracted: W = 1
    """
    lines = []
    if a.passive:
        lines.append(render("report.structure.passive", lang, count=len(a.passive),
                            W=a.W_active))
        lines += [f"  - {dof.reason.text(lang)}" for dof in a.passive]
    if a.original is None:
        return lines
    n, p5 = len(a.chain.moving_links), len(a.chain.pairs)
    lines.append(render("report.structure.replacing", lang, n=n, p5=p5, W=3 * n - 2 * p5))
    for item in a.replacements:
        first, second = item.pairs
        lines.append("  - " + render(
            "report.structure.replaced", lang, pair=item.pair, link=item.link,
            first=first.id, type1=first.type.value, a1=first.links[0], b1=first.links[1],
            second=second.id, type2=second.type.value, a2=second.links[0], b2=second.links[1]))
    return lines


def structure_report(analysis: StructuralAnalysis, *, lang: str = "en",
                     table: Sequence[IdentificationRow] | None = None,
                     mismatches: Sequence[Mismatch] | None = None,
                     checked_rows: int = 0,
                     models: Sequence[GroupModelRow] | None = None,
                     model_mismatches: Sequence[Mismatch] | None = None,
                     checked_models: int = 0, order: str = "course") -> str:
    """The text report of ``assur check``.

    Parameters
    ----------
    analysis : StructuralAnalysis
    lang : {'en', 'ru'}
    table : sequence of IdentificationRow, optional
        The identification table built from the analysis (table 1.6), printed when given.
    mismatches : sequence of Mismatch, optional
        The result of checking a user's table (None when no table was given).
    checked_rows : int
        Number of rows of the user's table.
    models : sequence of GroupModelRow, optional
        Table 1.5 built from the analysis, printed when given.
    model_mismatches : sequence of Mismatch, optional
        The result of checking a user's table 1.5 (None when none was given).
    checked_models : int
        Number of records of the user's table 1.5.
    order : {'course', 'layering'}
        The order of the rows of table 1.6 (:func:`in_order`).

    Returns
    -------
    str
        The report, lines joined by newlines.

    Examples
    --------
    >>> import pathlib, assur
    >>> table = pathlib.Path(assur.__file__).parents[1] / "input_tables/four_bar.yaml"
    >>> analysis = assur.analyse_structure(assur.load_chain(table))
    >>> print(assur.structure_report(analysis).splitlines()[2].strip())
    mobility W = 3n − 2p5 − p4 = 3·3 − 2·4 − 0 = 1
    """
    a = analysis
    chain = a.chain
    items = []
    for drive in chain.inputs:
        if drive.link is not None:
            name = chain.link_names(lang).get(drive.link)
            items.append(str(drive.link) + (f" ({name})" if name else ""))
        elif drive.pair is not None:
            pair = chain.pair(drive.pair)
            items.append(render("report.structure.input_pair", lang, pair=pair.id,
                                a=pair.links[0], b=pair.links[1]))
    lines = [render("report.structure.title", lang, name=chain.name, source=chain.source),
             "  " + render("report.structure.counts", lang, n=a.n, p5=a.p5, p4=a.p4),
             "  " + render("report.structure.mobility", lang, n=a.n, p5=a.p5, p4=a.p4, W=a.W)]
    lines += ["  " + line for line in higher_pair_lines(a, lang)]
    if a.W_star != a.W_active:
        lines.append("  " + render("report.structure.w_star", lang, W_star=a.W_star))
    lines.append("  " + render("report.structure.inputs", lang, m=a.m,
                               items=", ".join(items) or "—"))
    lines += ["", render("report.structure.groups" if a.original is None
                         else "report.structure.groups_replacing", lang)]
    groups = (*a.input_groups, *a.groups)
    width = max((len(g.label) for g in groups), default=0)
    lines += [f"  {g.label.ljust(width)}  {group_description(g, lang)}" for g in groups] or \
        ["  " + render("report.structure.no_groups", lang)]
    lines.append(render("report.structure.n_q" if a.input_groups else
                        "report.structure.n_q_no_l0", lang, n=len(groups)))
    lines += ["", render("report.structure.formula", lang, formula=a.formula or "—"),
              render("report.structure.class", lang, cls=roman(a.mechanism_class))]
    if a.leftover:
        lines.append(render("report.structure.leftover", lang,
                            links=", ".join(map(str, a.leftover))))
    if a.rank is not None:
        lines.append(render("report.structure.rank", lang, **a.rank.to_dict()))
    if a.issues:
        lines += ["", render("report.structure.findings", lang)]
        lines += [f"  {d.code}: {d.text(lang)}" for d in a.issues]
    if table is not None:
        lines += ["", render(f"report.structure.table_{order}", lang),
                  *table_lines(table, lang, order)]
        if any(row.out_code is None for row in table):
            lines.append("  " + render("report.structure.no_code", lang))
    lines += _verdict(mismatches, checked_rows, lang, "report.structure.table")
    if models is not None:
        lines += ["", render("report.structure.models", lang), *models_lines(models, lang),
                  "  " + render("report.structure.models_key", lang)]
    lines += _verdict(model_mismatches, checked_models, lang, "report.structure.models")
    lines.append("")
    lines.append(render("report.structure.applicable" if a.applicable
                        else "report.structure.not_applicable", lang))
    lines += [f"  - {text}" for text in a.conditions(lang)]
    return "\n".join(lines)
