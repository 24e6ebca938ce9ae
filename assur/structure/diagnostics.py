"""Structural diagnostics: stable codes, the links and pairs involved, the numbers behind them.

Codes follow ``structure.md`` §5.1. The first letter is the severity: ``E`` an error that
keeps the chain from being a proper mechanism with the declared inputs, ``W`` a warning,
``I`` information. The sentence of a code lives in the catalogue (:mod:`assur.text`) under
``diag.<code in lower case>``; a diagnostic holds only the code, the links, the pairs and
the numbers, and is rendered in any language.

>>> finding = diagnostic("E_DISCONNECTED", [5, 4])
>>> finding.text("en"), finding.text("ru")
('links {4, 5} are not connected to the frame', 'звенья {4, 5} не связаны со стойкой')
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from assur.model import LinkId, PairId, id_key
from assur.text import Message, in_every_language

__all__ = ["CODES", "Diagnostic", "diagnostic", "link_phrase"]

#: Every diagnostic code; the sentence of each is ``diag.<code in lower case>``.
CODES = ("E_MOBILITY_MISMATCH", "E_UNDERCONSTRAINED", "E_OVERCONSTRAINED", "W_IDLE_LINK",
         "W_PASSIVE_LINK", "E_PRISMATIC_LOOP", "E_RIGID_TRUSS", "W_GROUP_ON_ONE_LINK",
         "E_UNSUPPORTED_GROUP", "E_INTERNAL", "I_HIGH_DEGREE", "E_DISCONNECTED",
         "E_INPUT_NOT_ON_FRAME", "E_DUPLICATE_PAIR", "W_SINGULAR_POSE", "E_MISSING_PAIR",
         "E_INPUT_NOT_HINGED", "E_REDUNDANT_LINK")

#: Optional clauses a sentence may end with (each a message of its own, or nothing).
NOTES = ("geom", "hint", "star", "why")


@dataclass(frozen=True)
class Diagnostic:
    """One structural finding.

    Parameters
    ----------
    code : str
        Stable code such as ``"E_OVERCONSTRAINED"``.
    links, pairs : tuple
        The links and pairs involved, sorted.
    data : dict
        The numbers behind the sentence (``d``, ``q``, ``k``, ``p`` …).
    notes : dict of str to Message
        Optional clauses of the sentence, by name (one of :data:`NOTES`).

    Examples
    --------
    Two moving links and three lower pairs give W = 3·2 − 2·3 = 0, not the one input
    declared (a truss, not a mechanism):

    >>> from assur import analyse_structure, chain_from_dict
    >>> chain = chain_from_dict({"mechanism": {"pairs": [
    ...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
    ...     {"id": "C", "type": "R", "links": [2, 0]}],
    ...     "inputs": [1]}})
    >>> [issue.code for issue in analyse_structure(chain).issues][:1]
    ['E_MOBILITY_MISMATCH']
    """

    code: str
    links: tuple[LinkId, ...]
    pairs: tuple[PairId, ...]
    data: dict[str, Any] = field(default_factory=dict)
    notes: Mapping[str, Message] = field(default_factory=dict)

    @property
    def severity(self) -> str:
        """``"error"``, ``"warning"`` or ``"info"``."""
        return {"E": "error", "W": "warning"}.get(self.code[0], "info")

    @property
    def message(self) -> Message:
        """The sentence, not yet rendered.

        Its subject is the phrase naming the links ("links {2, 3, …}"), not a numeral, so the
        plural form follows one link or several (``n`` is 1 or 2), never the count: in Russian
        21 links named in a list are still "звенья … держатся".

        >>> from assur.text import render
        >>> many = diagnostic("E_MISSING_PAIR", range(2, 23)).message
        >>> "22} держатся каждое на одной паре" in render(many.code, "ru", **many.data)
        True
        """
        return Message(f"diag.{self.code.lower()}", {
            **dict.fromkeys(NOTES, ""), "n": min(len(self.links), 2), **self.data, **self.notes,
            "links": link_phrase(self.links), "names": _plain(self.links),
            "pairs": _plain(self.pairs) or "—"})

    def text(self, lang: str = "en") -> str:
        """The sentence in ``lang``."""
        return self.message.text(lang)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: the sentence in every language (``message`` in English, ``message_<lang>`` in the others)."""
        return {"code": self.code, "severity": self.severity, "links": list(self.links),
                "pairs": list(self.pairs), **in_every_language("message", self.message),
                **({"data": self.data} if self.data else {})}


def link_phrase(links: Iterable[LinkId]) -> Message:
    """A phrase naming links: ``"link 4"`` / ``"links {2, 3}"``.

    >>> link_phrase([3, 2]).text("ru")
    'звенья {2, 3}'
    """
    items = sorted(links, key=id_key)
    return Message("diag.link" if len(items) == 1 else "diag.links", {"names": _plain(items)})


def _plain(items: Iterable[Any]) -> str:
    items = list(items)
    if len(items) == 1:
        return str(items[0])
    return "{" + ", ".join(str(item) for item in items) + "}" if items else ""


def diagnostic(code: str, links: Iterable[LinkId] = (), pairs: Iterable[PairId] = (),
               notes: Mapping[str, Message] | None = None, **data: Any) -> Diagnostic:
    """A diagnostic of one of the :data:`CODES`, its links and pairs sorted.

    Keyword arguments are the numbers of the sentence, kept in :attr:`Diagnostic.data`;
    ``notes`` are its optional clauses.
    """
    return Diagnostic(code, tuple(sorted(set(links), key=id_key)),
                      tuple(sorted(set(pairs), key=id_key)), data, dict(notes or {}))
