"""The command line's own mistakes in the user's language: argparse's sentences, provoked here
from a plain :class:`argparse.ArgumentParser` of this Python, are each recognised and told
again from the catalogue, with the nearest right word where there is one."""

from __future__ import annotations

import argparse
import re

import pytest

from synthesis.cli import main
from synthesis.cli.argument_errors import translated

LATIN_WORD = re.compile(r"\b[A-Za-z]{3,}\b")


def _argparse_says(argv: list[str]) -> str:
    """The sentence a plain argparse parser gives ``error()`` for ``argv``."""
    parser = argparse.ArgumentParser(exit_on_error=False)
    parser.add_argument("table")
    parser.add_argument("--points", type=int)
    parser.add_argument("--omega", type=float)
    parser.add_argument("--pair", nargs=2)
    parser.add_argument("--many", nargs="+")
    parser.add_argument("--mode", choices=["fast", "exact"])
    both = parser.add_mutually_exclusive_group()
    both.add_argument("--quiet", action="store_true")
    both.add_argument("--loud", action="store_true")
    said: list[str] = []

    def error(message: str) -> None:
        said.append(message)
        raise SystemExit(2)

    parser.error = error  # type: ignore[method-assign,assignment]
    try:
        parser.parse_args(argv)
    except argparse.ArgumentError as caught:
        said.append(str(caught))
    except SystemExit:
        pass
    assert said, argv
    return said[0]


MISTAKES = {  # argv → what the Russian sentence must show of it
    "missing table": ([], "table"),
    "unknown option": (["t", "--jsn"], "--jsn"),
    "not an integer": (["t", "--points", "abc"], "abc"),
    "not a number": (["t", "--omega", "1,5"], "1,5"),
    "value missing": (["t", "--points"], "--points"),
    "two values": (["t", "--pair", "1"], "--pair"),
    "at least one": (["t", "--many"], "--many"),
    "bad choice": (["t", "--mode", "fats"], "fats"),
    "exclusive": (["t", "--quiet", "--loud"], "--quiet"),
    "ambiguous": (["t", "--m", "x"], "--m"),
}


@pytest.mark.parametrize("name", MISTAKES)
def test_every_argparse_sentence_is_told_in_russian(name: str) -> None:
    argv, shown = MISTAKES[name]
    english = _argparse_says(argv)
    russian = translated(english, "ru", lambda: ["--json", "--points"])
    assert russian != english and shown in russian
    data = {"table", "points", "omega", "pair", "many", "mode", "fast", "exact", "fats",
            "quiet", "loud", "json", "jsn", "abc"}
    assert not [w for w in LATIN_WORD.findall(russian) if w not in data], russian


def test_a_sentence_not_recognised_is_kept_as_written() -> None:
    assert translated("something new went wrong", "ru", list) == "something new went wrong"


@pytest.mark.parametrize(("argv", "lang", "expected"), [
    (["chek", "t.yaml"], "en", "did you mean 'check'?"),
    (["--lang", "ru", "chek", "t.yaml"], "ru", "возможно, имелось в виду 'check'?"),
    (["--lang", "ru", "check", "t.yaml", "--jsn"], "ru", "имелось в виду '--json'?"),
    (["analyze", "t.yaml", "--points", "abc"], "en", "expected a whole number, found 'abc'"),
    (["--lang", "ru", "check"], "ru", "не заданы обязательные аргументы: table"),
])
def test_command_line_mistakes_exit_2_in_the_language_asked_for(
        argv: list[str], lang: str, expected: str, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as ended:
        main(argv)
    assert ended.value.code == 2
    err = capsys.readouterr().err
    assert expected in err and "Traceback" not in err
    assert ("ошибка:" in err) == (lang == "ru")
