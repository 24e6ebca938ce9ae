"""The title block of the coursework report: who hands it in, in which group, which variant,
and when.

The values come from a ``student:`` section of the table and from the options of
``assur report`` (``--student``, ``--group``, ``--variant``, ``--date``), an option replacing
the value of the table; the date defaults to today. A value not given is left as a blank
line on the page, to be written in by hand after printing::

    student:
      name: Ivanova A. A.
      group: MT-21
      variant: 7
      date: 2026-05-12      # optional; today when left out
"""

from __future__ import annotations

import datetime
import os
from dataclasses import dataclass, replace
from pathlib import Path

from assur.io.reader import MISSING, TableReader
from assur.text import Message, render

__all__ = ["FIELDS", "Student", "read_student"]

#: The fields of the ``student:`` section, in the order the title block shows them.
FIELDS = ("name", "group", "variant", "date")


@dataclass(frozen=True, slots=True)
class Student:
    """Who hands the report in; None where not given (a blank on the page).

    Parameters
    ----------
    name, group, variant : str or None
        As written in the table or typed as an option.
    date : str
        ISO date (``2026-05-12``); today by default.
    """

    name: str | None = None
    group: str | None = None
    variant: str | None = None
    date: str = ""

    def rows(self, lang: str) -> list[tuple[str, str | None]]:
        """The title block's lines: label in ``lang`` and value (None: blank)."""
        return [(render(f"report.student.{key}", lang), getattr(self, key)) for key in FIELDS]

    def merged(self, **typed: str | None) -> Student:
        """This student with the values typed as options (those not None) put in."""
        return replace(self, **{key: value for key, value in typed.items()
                                if value is not None})


def _text(value: object) -> Message | None:
    """The rule for a title-block value: a text or a whole number, not empty."""
    if isinstance(value, bool) or not isinstance(value, (str, int)) or str(value).strip() == "":
        return Message("rule.text_or_number")
    return None


def _date(value: object) -> Message | None:
    """The rule for the date: a calendar date, ``YYYY-MM-DD``."""
    if isinstance(value, datetime.date):
        return None
    try:
        datetime.date.fromisoformat(str(value))
    except ValueError:
        return Message("rule.iso_date")
    return None


def read_student(path: str | os.PathLike[str], *, today: datetime.date | None = None
                 ) -> Student:
    """The ``student:`` section of a table (every field optional, each checked).

    Parameters
    ----------
    path : path-like
        The table (read already by the command, so readable YAML).
    today : datetime.date, optional
        The date when the table gives none (default: today).

    Returns
    -------
    Student

    Raises
    ------
    TableError
        A field of the section that is not what it should be, named with file and section.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> table = folder / "t.yaml"
    >>> _ = table.write_text("student: {name: Ivanova A. A., variant: 7}\\n")
    >>> read_student(table, today=datetime.date(2026, 5, 12))
    Student(name='Ivanova A. A.', group=None, variant='7', date='2026-05-12')
    """
    reader = TableReader.from_path(Path(path))
    top = reader.root(allowed=None)
    node = top.child("student", allowed=FIELDS, required=False) if top.given("student") \
        else None
    values: dict[str, str | None] = {}
    if node is not None:
        for key in FIELDS:
            value = node.get(key, required=False, default=None,
                             check=_date if key == "date" else _text)
            values[key] = None if value is None or value is MISSING else str(value).strip()
    reader.raise_if_any()
    date = values.pop("date", None) or (today or datetime.date.today()).isoformat()
    return Student(**values, date=date)
