"""The ``assur`` command: one console script for the whole program.

Each subcommand is a module of :mod:`synthesis.cli.commands` that defines ``NAME`` (the word
typed after ``assur``), ``HELP`` (one line), ``add_args(parser)`` and ``run(args) -> int``.
The modules are found automatically, so adding a command means adding one module.

Exit codes: 0 the run finished (whatever it found), 1 a search ended without a feasible
design, 2 invalid input (the message names file, table, row and field; no traceback),
130 interrupted by Ctrl-C.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
from collections.abc import Sequence
from types import ModuleType

from assur import AssurError
from assur.text import render

__all__ = ["main"]


def _command_modules() -> list[ModuleType]:
    import synthesis.cli.commands as package

    modules = [importlib.import_module(f"{package.__name__}.{info.name}")
               for info in pkgutil.iter_modules(package.__path__) if not info.name.startswith("_")]
    return sorted(modules, key=lambda module: getattr(module, "ORDER", 100))


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every discovered subcommand."""
    parser = argparse.ArgumentParser(
        prog="assur",
        description=render("cli.description"))
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    commands.required = True
    for module in _command_modules():
        sub = commands.add_parser(module.NAME, help=module.HELP, description=module.HELP)
        module.add_args(sub)
        sub.set_defaults(handler=module.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code."""
    args = build_parser().parse_args(argv)
    try:
        return int(args.handler(args))
    except AssurError as exc:
        print(exc.text(getattr(args, "lang", "en")), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(render("cli.interrupted", getattr(args, "lang", "en")), file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
