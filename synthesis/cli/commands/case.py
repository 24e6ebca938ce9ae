"""``assur case NAME``: run one of the built-in cases.

Each case is a subpackage of :mod:`synthesis.cases` whose ``cli`` module is a
:class:`~synthesis.cases.command.Case` (``NAME``, ``HELP``, ``add_args(parser, lang)``,
``run(args) -> int``); they are found automatically.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import pkgutil
from typing import cast

from assur.text import DEFAULT, render
from synthesis.cases.command import Case
from synthesis.cli.parser import Parser


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Add one sub-subcommand per built-in case, the help in ``lang``."""
    import synthesis.cases as package

    cases = parser.add_subparsers(dest="case", metavar="CASE", parser_class=Parser)
    cases.required = True
    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name):
        name = f"{package.__name__}.{info.name}.cli"
        if not info.ispkg or info.name.startswith("_") or importlib.util.find_spec(name) is None:
            continue
        module = cast(Case, importlib.import_module(name))
        text = module.HELP.text(lang)
        sub = cases.add_parser(module.NAME, help=text, description=text, lang=lang)
        module.add_args(sub, lang)
        sub.add_argument("--quiet", action="store_true", help=render("cli.quiet", lang))
        sub.set_defaults(case_handler=module.run)


def run(args: argparse.Namespace) -> int:
    """Dispatch to the chosen case (a search inside it draws a progress bar)."""
    from synthesis.app.progress import following_search

    with following_search(quiet=args.quiet, lang=getattr(args, "lang", "en")):
        return int(args.case_handler(args))
