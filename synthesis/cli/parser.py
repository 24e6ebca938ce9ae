"""The argument parser of ``assur``, built for the one command chosen, in the user's language.

Each subcommand is a module of :mod:`synthesis.cli.commands` named after the word typed after
``assur``; it defines ``add_args(parser, lang)`` and ``run(args) -> int``, and may define
``OUTPUTS`` (option → ``'file'`` or ``'folder'``: the paths checked before the run).  The
commands are listed in :data:`ORDER` and only the chosen one is imported
(:func:`command_module`), so ``assur check`` does not load what ``assur synthesize`` needs.
The one-line help of every command is the catalogue entry ``cli.<name>.help``.

The help is written in the language the command line asks for with ``--lang`` (before or
after the command, before or after ``--help``), English by default, like every report; the
parser's own words (usage, the titles of the option lists, ``--help``, ``--version``) come
from the catalogue too (``help.*``).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from types import ModuleType
from typing import Any, NoReturn

from assur.text import DEFAULT, languages, render

__all__ = ["ORDER", "HelpFormatter", "Parser", "build_parser", "command_module", "command_names",
           "help_lang"]

#: The commands in the order of the help; a new command is a module of
#: :mod:`synthesis.cli.commands`, a name here and a branch of :func:`command_module`.
ORDER = ("check", "analyze", "synthesize", "case", "report", "batch")


class HelpFormatter(argparse.HelpFormatter):
    """The help formatter whose ``usage:`` is in ``lang``."""

    def __init__(self, prog: str, lang: str = DEFAULT) -> None:
        super().__init__(prog)
        self.lang = lang

    def add_usage(self, usage: str | None, actions: Any, groups: Any,
                  prefix: str | None = None) -> None:
        super().add_usage(usage, actions, groups,
                          render("help.usage", self.lang) if prefix is None else prefix)


class Parser(argparse.ArgumentParser):
    """An argument parser whose own words (usage, option lists, ``--help``) are in ``lang``.

    Its subcommand parsers are of the same class: ``add_parser(name, lang=lang, …)``.
    """

    def __init__(self, *args: Any, lang: str = DEFAULT, **kwargs: Any) -> None:
        kwargs.update(add_help=False, formatter_class=lambda prog: HelpFormatter(prog, lang))
        super().__init__(*args, **kwargs)
        self.lang = lang
        self._positionals.title = render("help.positionals", lang)
        self._optionals.title = render("help.options", lang)
        self.add_argument("-h", "--help", action="help", default=argparse.SUPPRESS,
                          help=render("help.help", lang))

    def _every_option(self) -> list[str]:
        """The option strings of this parser and of its built subcommands."""
        found = list(self._option_string_actions)
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                for sub in action.choices.values():
                    found += [o for o in sub._option_string_actions if o not in found]
        return found

    def error(self, message: str) -> NoReturn:
        """Exit 2 with the usage and argparse's ``message`` in the parser's language."""
        from synthesis.cli.argument_errors import translated

        self.print_usage(sys.stderr)
        text = translated(message, self.lang, self._every_option)
        self.exit(2, f"{self.prog}: {render('cli.error.prefix', self.lang)}: {text}\n")


class _Version(argparse.Action):
    """``--version``: the installed version, looked up only when asked for."""

    def __init__(self, option_strings: Sequence[str], dest: str, help: str | None = None
                 ) -> None:
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, help=help)

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        from importlib.metadata import PackageNotFoundError, version

        try:
            found = version("assur")
        except PackageNotFoundError:  # pragma: no cover - a source tree that is not installed
            found = "unknown"
        print(f"assur {found}", file=sys.stdout)
        parser.exit()


def command_names() -> list[str]:
    """The subcommands, in the order of the help (none of them imported)."""
    return list(ORDER)


def command_module(name: str) -> ModuleType:
    """The module of the subcommand ``name``: only the chosen command is imported.

    Raises
    ------
    KeyError
        When ``name`` is not one of :data:`ORDER`.
    """
    match name:
        case "check":
            from synthesis.cli.commands import check
            return check
        case "analyze":
            from synthesis.cli.commands import analyze
            return analyze
        case "synthesize":
            from synthesis.cli.commands import synthesize
            return synthesize
        case "case":
            from synthesis.cli.commands import case
            return case
        case "report":
            from synthesis.cli.commands import report
            return report
        case "batch":
            from synthesis.cli.commands import batch
            return batch
    raise KeyError(name)


def help_lang(argv: Sequence[str]) -> str:
    """The language ``argv`` asks for with ``--lang X`` or ``--lang=X``, else English.

    >>> help_lang(["check", "--help", "--lang", "ru"]), help_lang(["--lang=xx"]), help_lang([])
    ('ru', 'en', 'en')
    """
    for word, following in zip(argv, [*argv[1:], ""]):
        value = following if word == "--lang" else word.partition("=")[2] \
            if word.startswith("--lang=") else None
        if value in languages():
            return value
    return DEFAULT


def chosen_command(argv: Sequence[str]) -> str | None:
    """The subcommand named in ``argv`` (the first word that is neither an option nor the
    language of ``--lang``).

    >>> chosen_command(["--lang", "ru", "check", "t.yaml"]), chosen_command(["t.yaml"])
    ('check', None)
    """
    names = set(command_names())
    for word, previous in zip(argv, ["", *argv]):
        if not word.startswith("-") and previous != "--lang":
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
    lang = help_lang(argv)
    parser = Parser(prog="assur", description=render("cli.description", lang), lang=lang)
    parser.add_argument("--version", action=_Version, help=render("help.version", lang))
    parser.add_argument("--lang", choices=languages(), default=lang, help=render("help.lang", lang))
    parser.add_argument("--debug", action="store_true", help=render("cli.debug", lang))
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    commands.required = True
    chosen = chosen_command(argv)
    for name in command_names():
        text = render(f"cli.{name}.help", lang)
        sub = commands.add_parser(name, help=text, description=text, lang=lang)
        if name != chosen:
            continue
        module = command_module(name)
        module.add_args(sub, lang)
        sub.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                         help=render("cli.debug", lang))
        sub.set_defaults(handler=module.run, module=module)
    return parser
