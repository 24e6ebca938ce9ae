"""The help of every command and option, in the language asked for with ``--lang``.

A Russian help text is recognised by its letters (Cyrillic, and not the English text of the
same option), independently of how the program renders it; the parser's own words (usage,
the titles of the option lists) are compared with the catalogue file read by Babel.
"""

from __future__ import annotations

import argparse
import re
from collections.abc import Iterator

import pytest
from babel.messages.pofile import read_po

from assur import text
from synthesis.cli import main
from synthesis.cli.parser import build_parser, command_names

CYRILLIC = re.compile("[а-яё]", re.IGNORECASE)


def _po(lang: str, code: str) -> str:
    with (text.LOCALE / f"{lang}.po").open("rb") as stream:
        message = read_po(stream).get(code)
    assert message is not None, code
    return str(message.string)


def _parsers(parser: argparse.ArgumentParser, path: str = "assur"
             ) -> Iterator[tuple[str, argparse.ArgumentParser]]:
    """The parser and every subcommand parser under it, with the words that reach it."""
    yield path, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _parsers(sub, f"{path} {name}")


def _helps(words: list[str]) -> dict[str, str]:
    """Every help text of the parser built for ``words``: ``"assur check --json"`` → text."""
    found = {}
    for path, parser in _parsers(build_parser(words)):
        if parser.description:
            found[path] = parser.description
        for action in parser._actions:
            if action.help and action.help != argparse.SUPPRESS:
                name = action.option_strings[-1] if action.option_strings else action.dest
                found[f"{path} {name}"] = action.help
    return found


@pytest.mark.parametrize("command", command_names())
def test_every_help_text_is_in_the_language_asked_for(command: str) -> None:
    english = _helps([command])
    russian = _helps([command, "--lang", "ru"])
    assert english.keys() == russian.keys()
    assert len(english) > 5  # the command's own options are there
    not_russian = {where: help for where, help in russian.items()
                   if not CYRILLIC.search(help) or help == english[where]}
    assert not_russian == {}
    assert [where for where, help in english.items() if CYRILLIC.search(help)] == []


def test_help_is_printed_in_russian_wherever_lang_is_given(capsys) -> None:
    for words in (["check", "--help", "--lang", "ru"], ["--lang=ru", "check", "--help"],
                  ["--lang", "ru", "--help"], ["case", "impact", "--lang", "ru", "-h"]):
        with pytest.raises(SystemExit) as stop:
            main(words)
        assert stop.value.code == 0
        out = capsys.readouterr().out
        assert out.startswith(_po("ru", "help.usage")), words
        assert _po("ru", "help.options") + ":" in out and "usage:" not in out
    with pytest.raises(SystemExit):
        main(["check", "--help"])
    out = capsys.readouterr().out
    assert out.startswith("usage: assur check") and _po("en", "cli.check.table") in out


def test_lang_before_the_command_chooses_the_language_of_the_run() -> None:
    args = build_parser(["--lang", "ru", "check", "t.yaml"]).parse_args(
        ["--lang", "ru", "check", "t.yaml"])
    assert (args.command, args.table, args.lang) == ("check", "t.yaml", "ru")
    args = build_parser(["check", "t.yaml"]).parse_args(["check", "t.yaml"])
    assert args.lang == "en"
