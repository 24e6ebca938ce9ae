"""``assur case impact``: impact in a four-bar with a clearance, the source's model and
Townsend–Mansour's, beside the source's Table 1."""

from __future__ import annotations

import argparse
from typing import Any

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
HELP = ("impact in a four-bar with a clearance in a bearing: the source's model and "
        "Townsend–Mansour's against Table 1 (Vjaters, Viba, Grasmanis)")


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of the case; each overrides the table (by default the source's data)."""
    add_table_arg(parser, "input table (default: the source's data, as in "
                          "input_tables/case_impact.yaml)")
    parser.add_argument("--theta2", type=float, metavar="DEG", help="crank angle at impact")
    parser.add_argument("--omega2", type=float, metavar="RAD_S", help="crank speed before impact")
    parser.add_argument("--omega4", type=float, nargs="+", metavar="RAD_S",
                        help="rocker speed(s) before impact, one impact each")
    parser.add_argument("--k", type=float, help="coefficient of restitution, 0 … 1")
    parser.add_argument("--mu", type=float, help="coefficient of friction (full slip)")
    parser.add_argument("--clearance", type=float, metavar="MM", help="clearance ξ in mm")
    parser.add_argument("--sigma", type=int, help="assembly: 1 (the source's) or -1")
    parser.add_argument("--lever", choices=("paper", "exact"), default="paper",
                        help="rocker lever in the restitution law: as printed in (7)-(8) "
                             "(default) or exact")
    add_output_args(parser, plot="draw the mechanism and the model comparison (PNG, SVG, PDF)")


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
    source = f"{args.table} with command-line options" if args.table else "command-line options"
    table = _table(args)
    study = run_study(impact_data_from_dict(table, source), lever=args.lever)
    emit(args, lambda: report_json(study), lambda lang: report_text(study, lang))
    if args.plot:
        from synthesis.cases.impact.plot import save_plot

        save_plot(study, args.plot, args.lang)
        outputs_of(args).announce(args.plot)
    return 0
