"""``assur synthesize PROBLEM.yaml``: optimisation synthesis by passive LPτ search (B1–B5).

A thin caller of the library: the options are checked, :func:`synthesis.load_problem` reads
the problem, :func:`synthesis.synthesize` searches it, and the command renders the result's
:meth:`~synthesis.outcome.SynthesisResult.to_dict` (``--json`` prints it as it is, with the
names of the files written) and writes the files asked for.

Exit codes: 0 a feasible design (P1 = P2 = 0) was found, 1 the search ended without one,
2 the problem file is invalid, 130 interrupted (the best design so far is still written).
"""

from __future__ import annotations

import argparse
import sys

from assur.text import DEFAULT, languages, render

#: The options that override a search setting → its field of ``SearchSettings``.
_SETTINGS = {"budget": "budget_log2", "seed": "seed", "refine": "refine",
             "shrink": "shrink_passes", "restarts": "restarts", "time_limit": "time_limit"}
#: The output options, checked before the search starts.
OUTPUTS = {"out": "file", "trials": "file", "plot": "folder"}


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Arguments of ``assur synthesize``."""
    parser.add_argument("problem", metavar="PROBLEM.yaml",
                        help=render("cli.synthesize.problem", lang))
    parser.add_argument("--budget", type=int, metavar="M", default=None,
                        help=render("cli.synthesize.budget", lang))
    parser.add_argument("--seed", type=int, default=None, help=render("cli.synthesize.seed", lang))
    parser.add_argument("--refine", action=argparse.BooleanOptionalAction, default=None,
                        help=render("cli.synthesize.refine", lang))
    parser.add_argument("--shrink", type=int, metavar="PASSES", default=None,
                        help=render("cli.synthesize.shrink", lang))
    parser.add_argument("--restarts", type=int, metavar="R", default=None,
                        help=render("cli.synthesize.restarts", lang))
    parser.add_argument("--time-limit", type=float, metavar="SEC", default=None,
                        help=render("cli.synthesize.time_limit", lang))
    parser.add_argument("--out", metavar="RESULT", default=None,
                        help=render("cli.synthesize.out", lang))
    parser.add_argument("--trials", metavar="CSV", default=None,
                        help=render("cli.synthesize.trials", lang))
    parser.add_argument("--json", action="store_true", help=render("cli.synthesize.json", lang))
    parser.add_argument("--plot", metavar="DIR", default=None,
                        help=render("cli.synthesize.plot", lang))
    parser.add_argument("--lang", choices=languages(), default=lang,
                        help=render("cli.synthesize.lang", lang))
    parser.add_argument("--quiet", action="store_true", help=render("cli.quiet", lang))
    parser.add_argument("--scheduler", metavar="SPEC", default=None,
                        help=render("dist.option", lang))


def run(args: argparse.Namespace) -> int:
    """Read the problem, synthesise it (:func:`synthesis.synthesize`), report."""
    from synthesis.app.outputs import outputs_of
    from synthesis.app.progress import following_search
    from synthesis.cli.options import check_scheduler, check_search_options
    from synthesis.outcome import synthesize
    from synthesis.problem_table import load_problem
    from synthesis.report import text_report, write_result, write_trials

    check_search_options(args, _SETTINGS)
    check_scheduler(args.scheduler)
    problem = load_problem(args.problem)
    if not args.json:
        from synthesis.app.table_warnings import print_warnings

        print_warnings(problem.warnings, args.problem, args.lang)
    with following_search(quiet=args.quiet, lang=args.lang):
        outcome = synthesize(problem, budget=args.budget, seed=args.seed, refine=args.refine,
                             shrink=args.shrink, restarts=args.restarts,
                             time_limit=args.time_limit, scheduler=args.scheduler)
    data = outcome.to_dict()
    if problem.warnings:
        data["warnings"] = [issue.to_dict() for issue in problem.warnings]
    outputs = outputs_of(args)
    if args.out:
        outputs.write(args.out, lambda path: write_result(path, problem, outcome.search, data,
                                                           lang=args.lang))
        data["result_file"] = args.out
    if args.trials:
        data["trials_file"] = args.trials
        data["trials_written"] = outputs.write(
            args.trials, lambda path: write_trials(path, problem, outcome.search))
    if args.plot:
        from synthesis.plots import save_plots

        plots = outputs.write(args.plot, lambda path: save_plots(
            path, problem, outcome.search, outcome.analysis, lang=args.lang))
        data["plots"] = [str(p) for p in plots or ()]
    if args.json:
        from synthesis.app.strict_json import strict_json

        print(strict_json(data, indent=2))
    else:
        sys.stdout.write(text_report(data, args.lang))
    if outcome.interrupted:
        return 130
    return 0 if outcome.feasible else 1
