"""``assur case NAME``: run one of the built-in cases.

Each case is a subpackage of :mod:`synthesis.cases` whose ``cli`` module is a
:class:`~synthesis.cases.command.Case` (``NAME``, ``HELP``, ``add_args(parser, lang)``,
``run(args) -> int``), listed in :func:`cases`.
"""

from __future__ import annotations

import argparse
from typing import cast

from assur.text import DEFAULT, render
from synthesis.cases.command import Case


def cases() -> tuple[Case, ...]:
    """The built-in cases, in the order of the help."""
    from synthesis.cases.fourbar_velocity_ratio import cli as fourbar_velocity_ratio
    from synthesis.cases.impact import cli as impact
    from synthesis.cases.tracker import cli as tracker

    return tuple(cast(Case, module) for module in (fourbar_velocity_ratio, impact, tracker))


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Add one sub-subcommand per built-in case, the help in ``lang``."""
    subparsers = parser.add_subparsers(dest="case", metavar="CASE")  # of the parser's class
    subparsers.required = True
    for module in cases():
        text = module.HELP.text(lang)
        sub = subparsers.add_parser(module.NAME, help=text, description=text, lang=lang)
        module.add_args(sub, lang)
        sub.add_argument("--quiet", action="store_true", help=render("cli.quiet", lang))
        sub.set_defaults(case_handler=module.run)


def run(args: argparse.Namespace) -> int:
    """Dispatch to the chosen case (a search inside it draws a progress bar)."""
    from synthesis.app.progress import following_search

    with following_search(quiet=args.quiet, lang=getattr(args, "lang", "en")):
        return int(args.case_handler(args))
