"""``assur case impact``: impact in a four-bar with a clearance, the source's model and
Townsend–Mansour's, beside the source's Table 1."""

from __future__ import annotations

import argparse
from typing import Any

from assur.text import DEFAULT, Message, render
from synthesis.app.outputs import outputs_of
from synthesis.cases.command import add_output_args, add_table_arg, emit
from synthesis.cases.impact.data import PAPER
from synthesis.cases.impact.report import report_json, report_text
from synthesis.cases.impact.study import run_study
from synthesis.cases.impact.table import (
    impact_data_from_dict,
    impact_table_dict,
    read_impact_table,
)

NAME = "impact"
HELP = Message("cli.case.impact.help")


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Options of the case; each overrides the table (by default the source's data)."""
    add_table_arg(parser, Message("cli.case.impact.table"), lang)
    parser.add_argument("--theta2", type=float, metavar="DEG",
                        help=render("cli.case.impact.theta2", lang))
    parser.add_argument("--omega2", type=float, metavar="RAD_S",
                        help=render("cli.case.impact.omega2", lang))
    parser.add_argument("--omega4", type=float, nargs="+", metavar="RAD_S",
                        help=render("cli.case.impact.omega4", lang))
    parser.add_argument("--k", type=float, help=render("cli.case.impact.k", lang))
    parser.add_argument("--mu", type=float, help=render("cli.case.impact.mu", lang))
    parser.add_argument("--clearance", type=float, metavar="MM",
                        help=render("cli.case.impact.clearance", lang))
    parser.add_argument("--sigma", type=int, help=render("cli.case.impact.sigma", lang))
    parser.add_argument("--lever", choices=("paper", "exact"), default="paper",
                        help=render("cli.case.impact.lever", lang))
    add_output_args(parser, plot=Message("cli.case.impact.plot"), lang=lang)


def _table(args: argparse.Namespace) -> dict[str, Any]:
    data = read_impact_table(args.table) if args.table else PAPER
    table = impact_table_dict(data)
    overrides = {"k": args.k, "mu": args.mu, "clearance_mm": args.clearance,
                 "sigma": args.sigma,
                 "omega4_rad_s": list(args.omega4) if args.omega4 is not None else None}
    table.update({key: value for key, value in overrides.items() if value is not None})
    if args.theta2 is not None:
        table["crank"]["theta2_deg"] = args.theta2
    if args.omega2 is not None:
        table["crank"]["omega2_rad_s"] = args.omega2
    return table


def run(args: argparse.Namespace) -> int:
    """Solve the case, print the report, optionally draw it."""
    source = (render("cli.case.source.table_options", args.lang, table=args.table) if args.table
              else render("cli.case.source.options", args.lang))
    table = _table(args)
    study = run_study(impact_data_from_dict(table, source), lever=args.lever)
    emit(args, lambda: report_json(study), lambda lang: report_text(study, lang))
    if args.plot:
        from synthesis.cases.impact.plot import save_plot

        save_plot(study, args.plot, args.lang)
        outputs_of(args).announce(args.plot)
    return 0
