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
from dataclasses import dataclass, field, replace
from typing import Any

from assur.model import Chain, Drive, LinkId, PairId, id_key
from assur.text import Message, in_every_language

__all__ = ["CODES", "Diagnostic", "diagnostic", "link_phrase", "with_fixes"]

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
        """The sentence, not yet rendered."""
        return Message(f"diag.{self.code.lower()}", {
            **dict.fromkeys(NOTES, ""), "n": len(self.links), **self.data, **self.notes,
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


def with_fixes(chain: Chain, found: list[Diagnostic]) -> list[Diagnostic]:
    """The findings with the fix where the peeling's own words would mislead.

    * Links that hang on one pair each (``W_IDLE_LINK``) and are left over with a freedom
      (``E_UNDERCONSTRAINED``, whose advice would be to add inputs) are one finding,
      ``E_MISSING_PAIR``: a pair between them may be missing.
    * An input on a link that shares no pair with the frame, where the input on a link next
      to it that is hinged to the frame decomposes the chain, is ``E_INPUT_NOT_HINGED``
      naming that link; the redundant constraints the wrong input made appear are dropped.
    * A mobility below the inputs by the formula that the dimensions make right (a passive
      link such as the third crank of a double parallelogram: W_geom equals the inputs) is
      one finding, ``E_REDUNDANT_LINK``, naming the link the decomposition could not place
      and what to do, instead of the mismatch and the redundant constraint.

    Parameters
    ----------
    chain : Chain
    found : list of Diagnostic
        The findings of the analysis, in order.

    Returns
    -------
    list of Diagnostic

    Examples
    --------
    >>> from assur import analyse_structure, chain_from_dict
    >>> chain = chain_from_dict({"mechanism": {"pairs": [
    ...     {"id": "A", "type": "R", "links": [0, 1]}, {"id": "B", "type": "R", "links": [1, 2]},
    ...     {"id": "D", "type": "R", "links": [3, 0]}], "inputs": [1]}})
    >>> [d.text() for d in analyse_structure(chain).issues if d.code == "E_MISSING_PAIR"]
    ['links {2, 3} each hang on one pair, so the chain is not closed there: a pair between them may be missing']
    """
    return _redundant_link(_input_fixes(chain, _missing_pairs(found)))


def _redundant_link(found: list[Diagnostic]) -> list[Diagnostic]:
    mismatch = next((d for d in found if d.code == "E_MOBILITY_MISMATCH"), None)
    geom = None if mismatch is None else mismatch.notes.get("geom")
    if mismatch is None or geom is None or geom.data.get("w_geom") != mismatch.data["m"]:
        return found
    unplaced = next((d for d in found if d.code == "W_PASSIVE_LINK" and "hint" in d.notes), None)
    if unplaced is None:
        return found
    link = set(unplaced.links)
    fixed = diagnostic("E_REDUNDANT_LINK", unplaced.links, unplaced.pairs,
                       W=mismatch.data["W"], w_geom=geom.data["w_geom"])
    return [fixed if d is mismatch else d for d in found if d is not unplaced
            and not (d.code == "E_OVERCONSTRAINED" and set(d.links) == link)]


def _missing_pairs(found: list[Diagnostic]) -> list[Diagnostic]:
    idle = {link for d in found if d.code == "W_IDLE_LINK" for link in d.links}
    loose = [d for d in found if d.code == "E_UNDERCONSTRAINED" and set(d.links) <= idle]
    if not loose:
        return found
    links = [link for d in loose for link in d.links]
    pairs = [pair for d in found if d.code == "W_IDLE_LINK" and set(d.links) & set(links)
             for pair in d.pairs]
    at = found.index(loose[0])
    kept = [d for d in found if d not in loose]
    kept.insert(at, diagnostic("E_MISSING_PAIR", links, pairs))
    return kept


def _input_fixes(chain: Chain, found: list[Diagnostic]) -> list[Diagnostic]:
    from assur.structure.peeling import body_graph, peel

    off = [d for d in found if d.code == "E_INPUT_NOT_ON_FRAME" and d.data.get("k") == 0]
    for item in off:
        link = item.links[0]
        inputs = {drive.link for drive in chain.inputs}
        near = sorted({pair.other(link) for pair in chain.pairs_of(link)} - inputs, key=id_key)
        for other in near:
            if sum(chain.frame in pair.links for pair in chain.pairs_of(other)) != 1:
                continue
            drives = tuple(Drive(link=other) if drive.link == link else drive
                           for drive in chain.inputs)
            trial = peel(body_graph(replace(chain, inputs=drives)))
            if trial.issues or trial.leftover or trial.disconnected:
                continue
            fixed = diagnostic("E_INPUT_NOT_HINGED", [link], (), other=other)
            return [fixed if d is item else d for d in found
                    if d.code not in ("E_OVERCONSTRAINED", "E_UNDERCONSTRAINED")]
    return found
