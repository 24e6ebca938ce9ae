"""``assur case tracker``: the rhomboid orientation mechanism of a solar tracker."""

from __future__ import annotations

import argparse

from assur import TableError
from assur.errors import Issue
from assur.text import Message
from synthesis.app.outputs import outputs_of
from synthesis.cases.command import add_output_args, add_table_arg, emit
from synthesis.cases.tracker.report import summary, to_dict
from synthesis.cases.tracker.study import run_study
from synthesis.cases.tracker.task import load_task

NAME = "tracker"
HELP = ("rhomboid orientation mechanism of a solar tracker driven by a linear actuator "
        "(patent application RO a 2010 00677): Tabel 1 reproduced, design procedure Etapa I-VI")

_OPTIONS = (
    ("--stroke", "stroke_deg", float, "DEG", "platform stroke a (default 210)"),
    ("--min-transmission", "min_transmission_deg", float, "DEG",
     "smallest allowed transmission angle b_min.ad (default 25)"),
    ("--l1", "l1_mm", float, "MM", "short rocker l1 (default 300)"),
    ("--actuator-stroke", "actuator_stroke_mm", float, "MM",
     "stroke of the available actuator (default 1000)"),
    ("--min-clearance", "min_clearance_mm", float, "MM",
     "least distance from the post to the extended actuator's axis (default 85)"),
)


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of the case; each overrides the value of the task table."""
    add_table_arg(parser, "design task table (see input_tables/case_tracker.yaml); default: the "
                          "patent's worked example")
    for flag, dest, kind, metavar, text in _OPTIONS:
        parser.add_argument(flag, dest=dest, type=kind, metavar=metavar, help=text)
    parser.add_argument("--k2", nargs="+", type=float, metavar="K2",
                        help="values of l2/l1 for the design table (default 1.4 1.6 1.8 2 2.2)")
    parser.add_argument("--k5", nargs="+", type=float, metavar="K5",
                        help="values of l5/l1 (default 2)")
    parser.add_argument("--budget", type=int, default=10, metavar="LOG2",
                        help="the B1-B5 synthesis draws 2**LOG2 LPtau trials in its first pass "
                             "(default 10); 0 skips the synthesis")
    parser.add_argument("--seed", type=int, default=0, help="seed of the synthesis (default 0)")
    add_output_args(parser, plot="write the charts and drawings here", plot_metavar="DIR")


def run(args: argparse.Namespace) -> int:
    """Run the case; returns 0 (the report says whether a design was found)."""
    names = [dest for _, dest, *_ in _OPTIONS] + ["k2", "k5"]
    overrides = {name: getattr(args, name) for name in names if getattr(args, name) is not None}
    if not 0 <= args.budget <= 20:
        raise TableError("command line", [Issue("option '--budget'", Message(
            "case.tracker.budget", {"found": args.budget}))])
    study = run_study(load_task(args.table, overrides), budget_log2=args.budget or None,
                      seed=args.seed, progress=args.budget >= 14)
    emit(args, lambda: to_dict(study), lambda lang: summary(study, lang))
    if args.plot:
        from synthesis.cases.tracker.plot import save_plots

        for path in save_plots(study, args.plot, args.lang):
            outputs_of(args).announce(path)
    return 0
