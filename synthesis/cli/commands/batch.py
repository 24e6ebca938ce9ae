"""``assur batch DIR``: check every student's table in a folder, one row per entry."""

from __future__ import annotations

import argparse

from assur.text import DEFAULT, languages, render
from synthesis.app.outputs import outputs_of
from synthesis.app.progress import counting
from synthesis.cli.options import bounded_jobs, check_at_least, check_scheduler

#: The output options, checked before the run.
OUTPUTS = {"csv": "file", "reports": "folder"}


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Arguments of ``assur batch``."""
    parser.add_argument("folder", metavar="DIR", help=render("cli.batch.folder", lang))
    parser.add_argument("--csv", metavar="FILE", help=render("cli.batch.csv", lang))
    parser.add_argument("--no-bom", dest="bom", action="store_false",
                        help=render("cli.batch.no_bom", lang))
    parser.add_argument("--json", action="store_true", help=render("cli.batch.json", lang))
    parser.add_argument("--jobs", type=int, default=None, metavar="N",
                        help=render("cli.batch.jobs", lang))
    parser.add_argument("--reports", metavar="DIR", help=render("cli.batch.reports", lang))
    parser.add_argument("--lang", choices=languages(), default=lang,
                        help=render("cli.batch.lang", lang))
    parser.add_argument("--quiet", action="store_true", help=render("cli.quiet", lang))
    parser.add_argument("--scheduler", metavar="SPEC", default=None, help=render("dist.option", lang))


def run(args: argparse.Namespace) -> int:
    """Check the folder; exit 0 whatever the tables contain (the rows say it)."""
    from synthesis.app.batch import run_batch
    from synthesis.app.batch_output import csv_text, summary
    from synthesis.app.outputs import stdout_taken
    from synthesis.distributed import executor_for

    check_at_least(jobs=(args.jobs, 1))
    csv_alone = stdout_taken(args, "csv")
    check_scheduler(args.scheduler)
    jobs = bounded_jobs(args.jobs, args.lang)
    with executor_for(args.scheduler) as executor, \
            counting(0, "progress.batch", quiet=args.quiet, lang=args.lang) as bar:
        rows = run_batch(args.folder, jobs=jobs, lang=args.lang,
                         progress=lambda done, total: bar.move_to(done, total),
                         reports=args.reports, executor=executor)
    outputs = outputs_of(args)
    for row in rows:
        if row.report:
            outputs.announce(row.report)
    if args.csv:
        outputs.write_text(args.csv, csv_text(rows, bom=args.bom))
    if args.json:
        from synthesis.app.strict_json import strict_json

        print(strict_json([row.to_dict() for row in rows], indent=1))
    elif not csv_alone:
        print(summary(rows, args.lang))
    return 0
