"""The argument parser of ``assur``, built for the one command chosen.

Each subcommand is a module of :mod:`synthesis.cli.commands` named after the word typed after
``assur``; it defines ``add_args(parser)`` and ``run(args) -> int``, and may define
``OUTPUTS`` (option → ``'file'`` or ``'folder'``: the paths checked before the run).  The
modules are found without importing them, and only the chosen one is imported, so
``assur check`` does not load what ``assur synthesize`` needs.  The one-line help of every
command is the catalogue entry ``cli.<name>.help``.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
from collections.abc import Sequence
from importlib.metadata import PackageNotFoundError, version
from types import ModuleType

from assur.text import render

__all__ = ["ORDER", "build_parser", "command_module", "command_names"]

#: The commands in the order of the help (a new module is listed after them).
ORDER = ("check", "analyze", "synthesize", "case", "report", "batch")


def command_names() -> list[str]:
    """The subcommands, found as modules of :mod:`synthesis.cli.commands` (not imported)."""
    import synthesis.cli.commands as package

    found = [info.name for info in pkgutil.iter_modules(package.__path__)
             if not info.name.startswith("_")]
    return sorted(found, key=lambda name: (ORDER.index(name) if name in ORDER else len(ORDER),
                                           name))


def command_module(name: str) -> ModuleType:
    """The module of the subcommand ``name``."""
    return importlib.import_module(f"synthesis.cli.commands.{name}")


def _version() -> str:
    try:
        return version("assur")
    except PackageNotFoundError:  # pragma: no cover - a source tree that is not installed
        return "unknown"


def chosen_command(argv: Sequence[str]) -> str | None:
    """The subcommand named in ``argv`` (the first word that is not an option)."""
    names = set(command_names())
    for word in argv:
        if not word.startswith("-"):
            return word if word in names else None
    return None


def build_parser(argv: Sequence[str] = ()) -> argparse.ArgumentParser:
    """The parser of ``assur``; the command chosen in ``argv`` gets its full options.

    Parameters
    ----------
    argv : sequence of str
        The arguments to be parsed; without a command, every command is only listed.

    Returns
    -------
    argparse.ArgumentParser
        Each full subparser has ``handler`` (its ``run``) and ``module`` as defaults.

    Examples
    --------
    >>> args = build_parser(["check", "t.yaml"]).parse_args(["check", "t.yaml"])
    >>> args.command, args.table, args.debug
    ('check', 't.yaml', False)
    """
    parser = argparse.ArgumentParser(prog="assur", description=render("cli.description"))
    parser.add_argument("--version", action="version", version=f"assur {_version()}")
    parser.add_argument("--debug", action="store_true", help=render("cli.debug"))
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    commands.required = True
    chosen = chosen_command(argv)
    for name in command_names():
        text = render(f"cli.{name}.help")
        sub = commands.add_parser(name, help=text, description=text)
        if name != chosen:
            continue
        module = command_module(name)
        module.add_args(sub)
        sub.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                         help=render("cli.debug"))
        sub.set_defaults(handler=module.run, module=module)
    return parser
