"""Every built-in case is a Case with the shared options; ``assur case`` lists each."""

from __future__ import annotations

import argparse
import importlib
import pkgutil

import pytest

from assur.text import languages
from synthesis import cases
from synthesis.cases.command import Case
from synthesis.cli.parser import build_parser

MODULES = [importlib.import_module(f"synthesis.cases.{info.name}.cli")
           for info in pkgutil.iter_modules(cases.__path__) if info.ispkg]


def test_there_are_three_cases() -> None:
    assert sorted(m.NAME for m in MODULES) == ["fourbar-velocity-ratio", "impact", "tracker"]


@pytest.mark.parametrize("module", MODULES, ids=[m.NAME for m in MODULES])
def test_each_case_is_a_case_with_the_shared_options(module: Case) -> None:
    assert isinstance(module, Case)
    parser = argparse.ArgumentParser()
    module.add_args(parser)
    args = parser.parse_args(["--table", "t.yaml", "--json", "--plot", "out", "--lang", "ru"])
    assert (args.table, args.json, args.plot, args.lang) == ("t.yaml", True, "out", "ru")
    language = next(a for a in parser._actions if a.dest == "lang")
    assert tuple(language.choices) == languages()
    # the command line reaches the case by its name
    words = ["case", module.NAME]
    assert build_parser(words).parse_args(words).case_handler is module.run
