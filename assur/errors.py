"""Exception and warning hierarchy of the program.

Every error a user can cause by writing a table derives from :class:`AssurError`; the
command line prints such an error without a traceback and exits with status 2.
The double bases follow scikit-learn, so ``except ValueError`` still catches table errors.
"""

from __future__ import annotations

from dataclasses import dataclass

from assur.text import Message, in_every_language, render

__all__ = [
    "AssemblyError",
    "AssurError",
    "AssurWarning",
    "Issue",
    "StructureError",
    "TableError",
]


class AssurError(Exception):
    """Root of the program's exceptions."""

    def text(self, lang: str = "en") -> str:
        """The message for the user in ``lang`` (a language of :func:`assur.text.languages`;
        English where no translation)."""
        return str(self)


@dataclass(frozen=True, slots=True)
class Issue:
    """One problem found in a table.

    Parameters
    ----------
    location : str
        Where the problem is: table, row and field, e.g. ``pairs[3] (id 'D') 'guide'``.
    message : Message
        What was expected and what was found, as one sentence of the catalogue.
    """

    location: str
    message: Message

    def text(self, lang: str = "en") -> str:
        """Location and message in ``lang``."""
        message = self.message.text(lang)
        return f"{self.location}: {message}" if self.location else message

    def __str__(self) -> str:
        return self.text("en")

    def to_dict(self) -> dict[str, str]:
        """The issue in the form of the JSON answers: the catalogue code, where, and the
        sentence in every language.

        >>> from assur.io.reader import radian_look
        >>> record = Issue("geometry 'D' 'direction'", radian_look(3.1416)).to_dict()
        >>> record["code"], record["where"]
        ('table.warn_radian', "geometry 'D' 'direction'")
        >>> record["message"]
        '3.1416 looks like an angle in radians (π); angles are in degrees: did you mean 180?'
        """
        return {"code": self.message.code, "where": self.location,
                **in_every_language("message", self.message)}


class TableError(AssurError, ValueError):
    """A user table (YAML) is unreadable or invalid; lists every problem found.

    Parameters
    ----------
    source : str
        The file name (or another label of where the data came from).
    issues : list of Issue
        All problems, in the order they were found.
    """

    def __init__(self, source: str, issues: list[Issue]) -> None:
        self.source = source
        self.issues = list(issues)
        super().__init__(self.text("en"))

    def text(self, lang: str = "en") -> str:
        """Every problem, one per line under a count header, in ``lang``.

        >>> error = TableError("t.yaml", [Issue("'links'", Message("value.kind.list"))] * 2)
        >>> error.text("en").splitlines()[0], error.text("ru").splitlines()[0]
        ('2 problems in t.yaml:', 't.yaml: найдены 2 ошибки')
        """
        head = render("table.problems", lang, n=len(self.issues), source=self.source)
        return "\n".join([head, *(f"  - {issue.text(lang)}" for issue in self.issues)])


class StructureError(AssurError, ValueError):
    """The chain cannot be analysed the way a command needs (e.g. kinematics of a chain
    that is not decomposable into supported groups).

    Parameters
    ----------
    message : Message or str
        A sentence of the catalogue, or a text not yet moved into it.
    """

    def __init__(self, message: Message | str) -> None:
        self.message = message
        super().__init__(str(message))

    def text(self, lang: str = "en") -> str:
        """The message in ``lang``."""
        return self.message.text(lang) if isinstance(self.message, Message) else str(self)


class AssemblyError(AssurError, ArithmeticError):
    """Raised only by strict scalar helpers; vectorised solvers return masks instead."""


class AssurWarning(UserWarning):
    """Root of the program's warnings."""
