"""What the command of every built-in case shares: the :class:`Case` protocol, the common
options and the output.

A case is a subpackage of :mod:`synthesis.cases` whose ``cli`` module is a :class:`Case`;
``assur case NAME`` finds it.  Every case reads an optional input table (``--table``) whose
values its own options override, and prints its report as text in the asked language or as
JSON (``--json``), optionally with pictures (``--plot``).  Exit codes, as for every command:
0 the case ran (its report says whether it reproduces its source), 1 a case that searches
for a design found none, 2 invalid input.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Mapping
from typing import Any, Protocol, runtime_checkable

from assur.text import DEFAULT, Message, languages, render

__all__ = ["Case", "add_output_args", "add_table_arg", "emit"]


@runtime_checkable
class Case(Protocol):
    """The command module of a built-in case (``synthesis/cases/<name>/cli.py``)."""

    NAME: str
    HELP: Message

    def add_args(self, parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
        """Add the options of the case, their help in ``lang``."""

    def run(self, args: argparse.Namespace) -> int:
        """Run the case; returns the exit code."""


def add_table_arg(parser: argparse.ArgumentParser, help: Message, lang: str = DEFAULT) -> None:
    """``--table FILE.yaml``: the input table of the case (its options override it)."""
    parser.add_argument("--table", metavar="FILE.yaml", help=help.text(lang))


def add_output_args(parser: argparse.ArgumentParser, *, plot: Message, lang: str = DEFAULT,
                    plot_metavar: str = "FILE") -> None:
    """``--json``, ``--plot`` (what it writes: ``plot``) and ``--lang``, their help in ``lang``."""
    parser.add_argument("--json", action="store_true", help=render("cli.case.json", lang))
    parser.add_argument("--plot", metavar=plot_metavar, help=plot.text(lang))
    parser.add_argument("--lang", choices=languages(), default=lang,
                        help=render("cli.case.lang", lang))


def emit(args: argparse.Namespace, as_json: Callable[[], Mapping[str, Any]],
         as_text: Callable[[str], str]) -> None:
    """Print the report: JSON with ``--json``, else the text in the language of ``--lang``.

    Examples
    --------
    >>> args = argparse.Namespace(json=False, lang="en")
    >>> emit(args, lambda: {"passed": True}, lambda lang: f"report in {lang}\\n")
    report in en
    >>> emit(argparse.Namespace(json=True, lang="en"), lambda: {"passed": True}, str)
    {
      "passed": true
    }
    """
    if args.json:
        from synthesis.app.strict_json import strict_json

        print(strict_json(as_json(), indent=2))
    else:
        sys.stdout.write(as_text(args.lang))
