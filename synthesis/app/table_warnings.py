"""The warnings of a table (:attr:`assur.model.Chain.warnings`) as a command shows them: one
line each on standard error in text mode, a ``warnings`` list in a JSON answer.

A warning does not change the exit code: the table is read and analysed as written.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import TextIO

from assur.errors import Issue
from assur.text import in_every_language, render

__all__ = ["print_warnings", "warning_records"]


def warning_records(warnings: Iterable[Issue]) -> list[dict[str, str]]:
    """The warnings in the form of the JSON answers: the catalogue code, where, and the
    sentence in every language.

    >>> from assur.io.reader import radian_look
    >>> record = warning_records([Issue("geometry 'D' 'direction'", radian_look(3.1416))])[0]
    >>> record["code"], record["where"]
    ('table.warn_radian', "geometry 'D' 'direction'")
    >>> record["message"]
    '3.1416 looks like an angle in radians (π); angles are in degrees: did you mean 180?'
    """
    return [{"code": issue.message.code, "where": issue.location,
             **in_every_language("message", issue.message)} for issue in warnings]


def print_warnings(warnings: Iterable[Issue], source: str, lang: str,
                   stream: TextIO | None = None) -> None:
    """Print each warning on one line of ``stream`` (standard error by default)."""
    for issue in warnings:
        print(render("table.warning", lang, source=source, issue=issue.text(lang)),
              file=stream or sys.stderr)
