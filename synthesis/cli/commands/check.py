"""``assur check TABLE.yaml``: structural analysis of a chain or identification table.

Prints the counts n, p5, p4 and W, the input groups and Assur groups in layering order, the
structure formula, the mechanism class, the diagnostics, the DGTU identification table and
the applicability verdict; with ``--json`` one JSON object instead. When the file carries a
filled ``structure_identification`` table, it is checked against the analysis field by field.
Exit code 0 when the analysis ran (whatever it found), 2 for an unreadable or invalid table.
"""

from __future__ import annotations

import argparse

from assur.structure.report import ORDERS
from assur.text import DEFAULT, languages, render

#: The output options, checked before the run.
OUTPUTS = {"plot": "file"}


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Arguments of ``assur check``."""
    parser.add_argument("table", help=render("cli.check.table", lang))
    parser.add_argument("--json", action="store_true", help=render("cli.check.json", lang))
    parser.add_argument("--lang", choices=languages(), default=lang,
                        help=render("cli.check.lang", lang))
    parser.add_argument("--plot", metavar="FILE", default=None, help=render("cli.check.plot", lang))
    parser.add_argument("--order", choices=ORDERS, default=ORDERS[0],
                        help=render("cli.check.order", lang))


def run(args: argparse.Namespace) -> int:
    """Analyse the table and print the report."""
    from assur.assessment import POINTS
    from synthesis.app.assess import assess
    from synthesis.app.check_report import check_text
    from synthesis.app.outputs import outputs_of
    from synthesis.app.table_warnings import print_warnings

    if args.plot:  # a format that cannot be written is refused before any work
        from assur.plot.formats import picture_format

        picture_format(args.plot)
    assessment = assess(args.table, points=POINTS)
    if args.plot:
        from assur.plot.schemes import save_schemes

        outputs_of(args).write(args.plot, lambda path: save_schemes(
            assessment.chain, assessment.analysis, path, lang=args.lang))
    warnings = assessment.chain.warnings
    if args.json:
        from synthesis.app.strict_json import strict_json

        print(strict_json(assessment.to_dict(), indent=2))
    else:
        print_warnings(warnings, args.table, args.lang)
        print(check_text(assessment, args.lang, args.order))
    return 0
