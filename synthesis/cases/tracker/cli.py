"""``assur case tracker``: the rhomboid orientation mechanism of a solar tracker."""

from __future__ import annotations

import argparse

from assur import TableError
from assur.errors import Issue
from assur.text import DEFAULT, Message, render
from synthesis.app.outputs import outputs_of
from synthesis.cases.command import add_output_args, add_table_arg, emit
from synthesis.cases.tracker.report import summary, to_dict
from synthesis.cases.tracker.study import run_study
from synthesis.cases.tracker.task import load_task

NAME = "tracker"
HELP = Message("cli.case.tracker.help")

_OPTIONS = (
    ("--stroke", "stroke_deg", float, "DEG", Message("cli.case.tracker.stroke")),
    ("--min-transmission", "min_transmission_deg", float, "DEG",
     Message("cli.case.tracker.min_transmission")),
    ("--l1", "l1_mm", float, "MM", Message("cli.case.tracker.l1")),
    ("--actuator-stroke", "actuator_stroke_mm", float, "MM",
     Message("cli.case.tracker.actuator_stroke")),
    ("--min-clearance", "min_clearance_mm", float, "MM",
     Message("cli.case.tracker.min_clearance")),
)


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Options of the case; each overrides the value of the task table."""
    add_table_arg(parser, Message("cli.case.tracker.table"), lang)
    for flag, dest, kind, metavar, text in _OPTIONS:
        parser.add_argument(flag, dest=dest, type=kind, metavar=metavar, help=text.text(lang))
    parser.add_argument("--k2", nargs="+", type=float, metavar="K2",
                        help=render("cli.case.tracker.k2", lang))
    parser.add_argument("--k5", nargs="+", type=float, metavar="K5",
                        help=render("cli.case.tracker.k5", lang))
    parser.add_argument("--budget", type=int, default=10, metavar="LOG2",
                        help=render("cli.case.tracker.budget", lang))
    parser.add_argument("--seed", type=int, default=0, help=render("cli.case.tracker.seed", lang))
    add_output_args(parser, plot=Message("cli.case.tracker.plot"), lang=lang, plot_metavar="DIR")


def run(args: argparse.Namespace) -> int:
    """Run the case; returns 0 (the report says whether a design was found)."""
    names = [dest for _, dest, *_ in _OPTIONS] + ["k2", "k5"]
    overrides = {name: getattr(args, name) for name in names if getattr(args, name) is not None}
    if not 0 <= args.budget <= 20:
        raise TableError(render("cli.case.source.command_line", args.lang), [Issue("option '--budget'", Message(
            "case.tracker.budget", {"found": args.budget}))])
    study = run_study(load_task(args.table, overrides), budget_log2=args.budget or None,
                      seed=args.seed, progress=args.budget >= 14)
    emit(args, lambda: to_dict(study), lambda lang: summary(study, lang))
    if args.plot:
        from synthesis.cases.tracker.plot import save_plots

        for path in save_plots(study, args.plot, args.lang):
            outputs_of(args).announce(path)
    return 0
