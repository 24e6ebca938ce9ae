"""``assur report TABLE.yaml``: the coursework report as one self-contained HTML page."""

from __future__ import annotations

import argparse
import datetime
from pathlib import Path

from assur.errors import Issue, TableError
from assur.io.reader import describe
from assur.structure.report import ORDERS
from assur.text import DEFAULT, Message, languages, render
from synthesis.app.outputs import outputs_of
from synthesis.app.progress import following_search
from synthesis.app.strict_json import strict_json
from synthesis.cli.options import check_ranges, check_search_options, points_range

#: The output options, checked before the run.
OUTPUTS = {"out": "file"}
#: The fewest crank positions a report's diagrams take.
MIN_POINTS = 8


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Arguments of ``assur report``."""
    parser.add_argument("table", metavar="TABLE.yaml", help=render("cli.report.table", lang))
    parser.add_argument("--out", metavar="REPORT.html", default=None,
                        help=render("cli.report.out", lang))
    parser.add_argument("--lang", choices=languages(), default=lang,
                        help=render("cli.report.lang", lang))
    parser.add_argument("--points", type=int, default=360, metavar="N",
                        help=render("cli.report.points", lang))
    parser.add_argument("--json", action="store_true", help=render("cli.report.json", lang))
    parser.add_argument("--budget", type=int, default=None, metavar="M",
                        help=render("cli.report.budget", lang))
    parser.add_argument("--quiet", action="store_true", help=render("cli.quiet", lang))
    parser.add_argument("--order", choices=ORDERS, default=ORDERS[0],
                        help=render("cli.check.order", lang))
    parser.add_argument("--student", metavar="NAME", help=render("cli.report.student", lang))
    parser.add_argument("--group", metavar="GROUP", help=render("cli.report.group", lang))
    parser.add_argument("--variant", metavar="N", help=render("cli.report.variant", lang))
    parser.add_argument("--date", metavar="YYYY-MM-DD", help=render("cli.report.date", lang))


def _typed_student(args: argparse.Namespace) -> dict[str, str | None]:
    """The title-block values typed as options; a date that is not one is refused."""
    if args.date is not None:
        try:
            datetime.date.fromisoformat(args.date)
        except ValueError:
            raise TableError(render("cli.case.source.command_line", args.lang), [Issue(
                "--date", Message("table.rule_broken", {
                    "rule": Message("rule.iso_date"), "found": describe(args.date)}))]
                             ) from None
    return {"name": args.student, "group": args.group, "variant": args.variant,
            "date": args.date}


def run(args: argparse.Namespace) -> int:
    """Build and write the report; print where it went (or the key values as JSON)."""
    from synthesis.app.coursework import build_report, render_html

    check_ranges(args, {"points": points_range(MIN_POINTS)})
    check_search_options(args, {"budget": "budget_log2"})
    with following_search(quiet=args.quiet, lang=args.lang):
        report = build_report(args.table, lang=args.lang, points=args.points,
                              budget=args.budget, student=_typed_student(args),
                              order=args.order)
    out = Path(args.out) if args.out else Path(args.table).with_suffix(".html")
    outputs = outputs_of(args)
    outputs.write_text(out, render_html(report))
    report.out = outputs.written[-1] if outputs.written else None
    if args.json:
        print(strict_json({"out": None if report.out is None else str(report.out),
                           "title": report.title, **report.facts}, indent=1))
    return 0
