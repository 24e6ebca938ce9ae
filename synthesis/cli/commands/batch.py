"""``assur batch DIR``: check every student's table in a folder, one row per file."""

from __future__ import annotations

import argparse
import json
import sys

from assur.text import languages, render

NAME = "batch"
HELP = render("cli.batch.help")
ORDER = 60


def add_args(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``assur batch``."""
    parser.add_argument("folder", metavar="DIR", help=render("cli.batch.folder"))
    parser.add_argument("--csv", metavar="FILE", help=render("cli.batch.csv"))
    parser.add_argument("--json", action="store_true", help=render("cli.batch.json"))
    parser.add_argument("--jobs", type=int, default=None, metavar="N",
                        help=render("cli.batch.jobs"))
    parser.add_argument("--reports", metavar="DIR", help=render("cli.batch.reports"))
    parser.add_argument("--lang", choices=languages(), default="en",
                        help=render("cli.batch.lang"))
    parser.add_argument("--quiet", action="store_true", help=render("cli.batch.quiet"))
    parser.add_argument("--scheduler", metavar="SPEC", default=None, help=render("dist.option"))


def run(args: argparse.Namespace) -> int:
    """Check the folder; exit 0 whatever the tables contain (the rows say it)."""
    from synthesis.app.batch import run_batch
    from synthesis.app.batch_output import summary, write_csv
    from synthesis.distributed import executor_for

    if args.jobs is not None and args.jobs < 1:
        print(render("cli.option_positive", args.lang, option="--jobs", found=args.jobs),
              file=sys.stderr)
        return 2
    progress = None if args.quiet or args.json else _progress
    with executor_for(args.scheduler) as executor:
        rows = run_batch(args.folder, jobs=args.jobs, lang=args.lang, progress=progress,
                         reports=args.reports, executor=executor)
    if args.csv:
        write_csv(rows, args.csv)
    if args.json:
        print(json.dumps([row.to_dict() for row in rows], ensure_ascii=False, indent=1))
    else:
        print(summary(rows, args.lang))
    return 0


def _progress(done: int, total: int) -> None:
    print(f"\r{done}/{total}", end="" if done < total else "\n", file=sys.stderr, flush=True)
