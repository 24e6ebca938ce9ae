"""Checks of command-line options that the argument parser cannot state: every bad option
at once, each message naming the option, exit code 2.

The search options are checked by the very rules of the problem table's ``search:`` section
(:func:`synthesis.search.setting_problem`), so an option and a table entry can never disagree.
"""

from __future__ import annotations

import argparse
from collections.abc import Mapping

from assur.errors import AssurError
from assur.text import Message

__all__ = ["OptionError", "check_at_least", "check_search_options"]


class OptionError(AssurError):
    """Command-line options out of their range (every one at once)."""

    def __init__(self, problems: list[tuple[str, Message]]) -> None:
        self.problems = problems
        super().__init__(self.text("en"))

    def text(self, lang: str = "en") -> str:
        """One line per option, in ``lang``."""
        return "\n".join(f"{option}: {message.text(lang)}" for option, message in self.problems)


def check_at_least(**options: tuple[int | None, int]) -> None:
    """Refuse every option (``name=(value, lowest)``) below its lowest value.

    Raises
    ------
    OptionError

    Examples
    --------
    >>> check_at_least(jobs=(2, 1))
    >>> check_at_least(jobs=(0, 1), points=(3, 8))
    Traceback (most recent call last):
    ...
    synthesis.cli.options.OptionError: --jobs: expected a whole number ≥ 1; found 0
    --points: expected a whole number ≥ 8; found 3
    """
    problems = [(f"--{name.replace('_', '-')}", Message("cli.option.at_least",
                                                        {"low": low, "found": value}))
                for name, (value, low) in options.items() if value is not None and value < low]
    if problems:
        raise OptionError(problems)


def check_search_options(args: argparse.Namespace, fields: Mapping[str, str]) -> None:
    """Refuse every search option that breaks the rule of its setting.

    Parameters
    ----------
    args : argparse.Namespace
    fields : mapping
        Option destination → field of :class:`synthesis.search.SearchSettings`.

    Raises
    ------
    OptionError
    """
    from synthesis.search_settings import setting_problem

    problems = []
    for dest, name in fields.items():
        value = getattr(args, dest, None)
        message = None if value is None else setting_problem(name, value)
        if message is not None:
            problems.append((f"--{dest.replace('_', '-')}", message))
    if problems:
        raise OptionError(problems)
