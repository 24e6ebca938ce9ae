"""``assur report TABLE.yaml``: the coursework report as one self-contained HTML page."""

from __future__ import annotations

import argparse
import json
import sys

from assur.text import languages, render

NAME = "report"
HELP = render("cli.report.help")
ORDER = 50
#: The fewest crank positions a report's diagrams take.
MIN_POINTS = 8


def add_args(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``assur report``."""
    parser.add_argument("table", metavar="TABLE.yaml", help=render("cli.report.table"))
    parser.add_argument("--out", metavar="REPORT.html", default=None,
                        help=render("cli.report.out"))
    parser.add_argument("--lang", choices=languages(), default="en",
                        help=render("cli.report.lang"))
    parser.add_argument("--points", type=int, default=360, metavar="N",
                        help=render("cli.report.points"))
    parser.add_argument("--json", action="store_true", help=render("cli.report.json"))
    parser.add_argument("--budget", type=int, default=None, metavar="M",
                        help=render("cli.report.budget"))


def run(args: argparse.Namespace) -> int:
    """Build and write the report; print where it went (or the key values as JSON)."""
    from synthesis.app.coursework import write_report

    if args.points < MIN_POINTS:
        print(render("cli.option_at_least", args.lang, option="--points", low=MIN_POINTS,
                     found=args.points), file=sys.stderr)
        return 2
    report = write_report(args.table, args.out, lang=args.lang, points=args.points,
                          budget=args.budget)
    if args.json:
        print(json.dumps({"out": str(report.out), "title": report.title, **report.facts},
                         ensure_ascii=False, indent=1, default=str))
    else:
        print(report.out)
    return 0
