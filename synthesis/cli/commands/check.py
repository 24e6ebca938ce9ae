"""``assur check TABLE.yaml``: structural analysis of a chain or identification table.

Prints the counts n, p5, p4 and W, the input groups and Assur groups in layering order, the
structure formula, the mechanism class, the diagnostics, the DGTU identification table and
the applicability verdict; with ``--json`` one JSON object instead. When the file carries a
filled ``structure_identification`` table, it is checked against the analysis field by field.
Exit code 0 when the analysis ran (whatever it found), 2 for an unreadable or invalid table.
"""

from __future__ import annotations

import argparse
import json

from assur import (
    AssurError,
    StructuralAnalysis,
    StructureError,
    analyse_structure,
    build_model,
    check_identification,
    identification_table,
    load_chain,
    structure_report,
)

NAME = "check"
HELP = "structural analysis of a chain table: mobility, Assur groups, formula, DGTU table"
ORDER = 10


def add_args(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``assur check``."""
    parser.add_argument("table", help="chain table or identification table (YAML)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--lang", choices=("en", "ru"), default="en",
                        help="language of the text report (default: en)")
    parser.add_argument("--plot", metavar="FILE", default=None,
                        help="draw the structural and formalised structural schemes "
                             "(FILE.svg or FILE.png)")


def run(args: argparse.Namespace) -> int:
    """Analyse the table and print the report."""
    chain = load_chain(args.table)
    analysis = analyse_structure(chain)
    if args.plot:
        from assur import save_schemes

        save_schemes(chain, analysis, args.plot, lang=args.lang)
    try:
        table = identification_table(analysis, _variants(analysis))
    except StructureError:
        table = None
    mismatches = (check_identification(analysis, chain.identification)
                  if chain.identification is not None else None)
    if args.json:
        payload = analysis.to_dict()
        payload["identification_table"] = [row.to_dict() for row in table] if table else None
        payload["identification_check"] = (
            None if mismatches is None else [m.to_dict() for m in mismatches])
        print(json.dumps(payload, ensure_ascii=False, indent=2))
    else:
        print(structure_report(analysis, lang=args.lang, table=table, mismatches=mismatches,
                               checked_rows=len(chain.identification or ())))
    return 0


def _variants(analysis: StructuralAnalysis) -> dict[tuple[object, object], int] | None:
    """Assembly sign of every dyad from the table's dimensions, if it gives valid ones.

    Problems of the dimensions are not this command's business (``assur analyze`` reports
    them); without usable dimensions the identification table shows the default variants.
    """
    chain = analysis.chain
    if not (chain.geometry or chain.group_params):
        return None
    try:
        model = build_model(analysis)
    except AssurError:
        return None
    return {(group.i, group.j): group.sigma for group in model.groups if group.j is not None}
