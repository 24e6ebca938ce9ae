"""The title block of the coursework report: who hands it in, in which group, which variant,
and when.

The values come from the ``student:`` section of the table, read with the rest of the table
(:attr:`assur.model.Chain.student`, :attr:`synthesis.problem.Problem.student`), and from the
options of ``assur report`` (``--student``, ``--group``, ``--variant``, ``--date``), an option
replacing the value of the table; the date defaults to today. A value not given is left as a
blank line on the page, to be written in by hand after printing::

    student:
      name: Ivanova A. A.
      group: MT-21
      variant: 7
      date: 2026-05-12      # optional; today when left out
"""

from __future__ import annotations

import datetime
from dataclasses import fields

from assur.model import Student
from assur.text import render

__all__ = ["title_rows", "title_student"]


def title_student(read: Student | None, typed: dict[str, str | None] | None = None, *,
                today: datetime.date | None = None) -> Student:
    """The title block: the table's section with the values typed as options put in.

    Parameters
    ----------
    read : Student or None
        The table's ``student:`` section, as its reader gave it (None: the table has none).
    typed : dict, optional
        Values typed as options (``name``, ``group``, ``variant``, ``date``; None: not typed).
    today : datetime.date, optional
        The date when neither the table nor the options give one (default: today).

    Returns
    -------
    Student
        With a date always.

    Examples
    --------
    >>> title_student(Student(name="Ivanova A. A.", variant="7"), {"variant": "12"},
    ...             today=datetime.date(2026, 5, 12))
    Student(name='Ivanova A. A.', group=None, variant='12', date='2026-05-12')
    """
    student = (read or Student()).merged(**(typed or {}))
    return student.merged(date=student.date or (today or datetime.date.today()).isoformat())


def title_rows(student: Student, lang: str) -> list[tuple[str, str | None]]:
    """The title block's lines: label in ``lang`` and value (None: a blank line).

    Examples
    --------
    >>> title_rows(Student(name="Ivanova A. A.", date="2026-05-12"), "en")
    [('Student', 'Ivanova A. A.'), ('Group', None), ('Variant', None), ('Date', '2026-05-12')]
    """
    return [(render(f"report.student.{item.name}", lang), getattr(student, item.name))
            for item in fields(student)]
