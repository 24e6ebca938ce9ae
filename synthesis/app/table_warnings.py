"""The warnings of a table (:attr:`assur.model.Chain.warnings`) as a command shows them in
text mode: one line each on standard error (the JSON answers carry them as
:meth:`assur.errors.Issue.to_dict`).

A warning does not change the exit code: the table is read and analysed as written.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import TextIO

from assur.errors import Issue
from assur.text import render

__all__ = ["print_warnings"]


def print_warnings(warnings: Iterable[Issue], source: str, lang: str,
                   stream: TextIO | None = None) -> None:
    """Print each warning on one line of ``stream`` (standard error by default)."""
    for issue in warnings:
        print(render("table.warning", lang, source=source, issue=issue.text(lang)),
              file=stream or sys.stderr)
