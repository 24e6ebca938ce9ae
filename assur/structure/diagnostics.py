"""Structural diagnostics: stable codes, the links and pairs involved, one plain sentence.

Codes follow ``structure.md`` §5.1. The first letter is the severity: ``E`` an error that
keeps the chain from being a proper mechanism with the declared inputs, ``W`` a warning,
``I`` information. Every diagnostic carries an English and a Russian sentence.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from assur.model import LinkId, PairId, id_key

__all__ = ["CODES", "Diagnostic", "diagnostic", "format_links"]


@dataclass(frozen=True)
class Diagnostic:
    """One structural finding.

    Parameters
    ----------
    code : str
        Stable code such as ``"E_OVERCONSTRAINED"``.
    links, pairs : tuple
        The links and pairs involved, sorted.
    message, message_ru : str
        One sentence in English and in Russian.
    data : dict
        The numbers behind the sentence (``d``, ``q``, ``k``, ``p`` …).

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
    message: str
    message_ru: str
    data: dict[str, Any] = field(default_factory=dict)

    @property
    def severity(self) -> str:
        """``"error"``, ``"warning"`` or ``"info"``."""
        return {"E": "error", "W": "warning"}.get(self.code[0], "info")

    def text(self, lang: str = "en") -> str:
        """The sentence in ``lang`` (``"en"`` or ``"ru"``)."""
        return self.message_ru if lang == "ru" else self.message

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {"code": self.code, "severity": self.severity, "links": list(self.links),
                "pairs": list(self.pairs), "message": self.message,
                "message_ru": self.message_ru, **({"data": self.data} if self.data else {})}


# code -> (English template, Russian template). Placeholders: {links}/{links_ru} (a phrase
# such as "link 4" / "links {2, 3}"), {pairs}, and the keys of ``data``.
CODES: dict[str, tuple[str, str]] = {
    "E_MOBILITY_MISMATCH": (
        "W = 3·n − 2·p5 − p4 = 3·{n} − 2·{p5} − {p4} = {W}{star}, but the mechanism has {m} "
        "input(s): the mobility does not equal the number of inputs; see the local findings",
        "W = 3·n − 2·p5 − p4 = 3·{n} − 2·{p5} − {p4} = {W}{star_ru}, а входных звеньев {m}: "
        "степень подвижности не равна числу входов; см. местные замечания"),
    "E_UNDERCONSTRAINED": (
        "{links} keep {d} degree(s) of freedom after all groups were attached "
        "(3·{k} − 2·{p} = {d}); add {d} input(s){hint}",
        "{links_ru} сохраняют {d} степень(и) свободы после присоединения всех групп "
        "(3·{k} − 2·{p} = {d}): не хватает входных звеньев ({d}){hint_ru}"),
    "E_OVERCONSTRAINED": (
        "{links} with pairs {pairs}: 3·{k} − 2·{p} = {d}, so there are {q} redundant "
        "constraint(s){why}",
        "{links_ru} с парами {pairs}: 3·{k} − 2·{p} = {d}, избыточные (пассивные) связи "
        "q = {q}{why_ru}"),
    "W_IDLE_LINK": (
        "{links} hang(s) on one pair and carry no input: an idle link with its own degree of "
        "freedom (the chain is not closed there)",
        "{links_ru} присоединено одной парой и не является входным: лишняя (местная) степень "
        "свободы, кинематическая цепь здесь не замкнута"),
    "W_PASSIVE_LINK": (
        "with the given dimensions, {links} (pairs {pairs}) adds no constraint the other links "
        "do not already impose: a passive link; remove it for structural analysis{hint}",
        "при заданных размерах {links_ru} (пары {pairs}) не накладывает новых связей: "
        "пассивное звено, удалите его при структурном анализе{hint_ru}"),
    "E_PRISMATIC_LOOP": (
        "loop {links_plain} (pairs {pairs}) has only prismatic pairs: one rotational constraint "
        "is counted twice, the real mobility is higher by {r} (W* = W + {r})",
        "контур {links_plain} (пары {pairs}) образован только поступательными парами: связь по "
        "повороту учтена дважды, действительная подвижность больше на {r} (W* = W + {r})"),
    "E_RIGID_TRUSS": (
        "{links} form a rigid truss: they cannot move relative to each other "
        "(3·({k} − 1) − 2·{p} = {f}); merge them into one link",
        "{links_ru} образуют ферму: они неподвижны друг относительно друга "
        "(3·({k} − 1) − 2·{p} = {f}); объедините их в одно звено"),
    "W_GROUP_ON_ONE_LINK": (
        "group {links_plain} is attached to link {base} only: it is rigidly fixed to that link; "
        "model it as part of link {base}",
        "группа {links_plain} присоединена только к звену {base}: она неподвижна относительно "
        "него; считайте её частью звена {base}"),
    "E_UNSUPPORTED_GROUP": (
        "{links} form an Assur group of class {cls}, order {order} ({k} links): not among the "
        "supported kinds II, III and IV",
        "{links_ru} образуют группу Ассура {cls} класса {order} порядка ({k} звеньев): такие "
        "группы не поддерживаются (только II, III и IV класс)"),
    "E_INTERNAL": (
        "{links} satisfy 3·k = 2·p but their pairs ({pattern}) form no known Assur group",
        "{links_ru} удовлетворяют условию 3·k = 2·p, но их пары ({pattern}) не образуют "
        "известной группы Ассура"),
    "I_HIGH_DEGREE": (
        "{links} has {k} pairs, more than three: allowed in general, outside the DGTU program "
        "(condition 7)",
        "{links_ru} входит в {k} кинематические пары, больше трёх: допустимо, но вне программы "
        "ДГТУ (условие 7)"),
    "E_DISCONNECTED": (
        "{links} are not connected to the frame",
        "{links_ru} не связаны со стойкой"),
    "E_INPUT_NOT_ON_FRAME": (
        "input {links} shares {k} pair(s) with the frame, expected exactly one: name the driven "
        "pair explicitly ({{pair: ...}}) or use the actuator form",
        "входное {links_ru} образует со стойкой {k} пар(ы) вместо одной: укажите ведущую пару "
        "явно ({{pair: ...}}) или задайте привод парой"),
    "E_DUPLICATE_PAIR": (
        "links {a} and {b} are joined twice (pairs {pairs}): they act as one body",
        "звенья {a} и {b} соединены дважды (пары {pairs}): они ведут себя как одно тело"),
    "W_SINGULAR_POSE": (
        "group {links_plain} is in a singular (dead-centre) position at the given pose",
        "группа {links_plain} в заданном положении находится в особом (мёртвом) положении"),
}


def format_links(links: Iterable[LinkId], lang: str = "en") -> str:
    """A phrase naming links: ``"link 4"`` / ``"links {2, 3}"`` (``"звено 4"`` in Russian)."""
    items = sorted(links, key=id_key)
    plain = _plain(items)
    if lang == "ru":
        return f"звено {plain}" if len(items) == 1 else f"звенья {plain}"
    return f"link {plain}" if len(items) == 1 else f"links {plain}"


def _plain(items: list[Any]) -> str:
    if len(items) == 1:
        return str(items[0])
    return "{" + ", ".join(str(item) for item in items) + "}"


def diagnostic(code: str, links: Iterable[LinkId] = (), pairs: Iterable[PairId] = (),
               **data: Any) -> Diagnostic:
    """Build a diagnostic from the catalogue :data:`CODES`.

    Extra keyword arguments fill the sentence and are kept in :attr:`Diagnostic.data`;
    the keys ``hint``/``hint_ru``/``why``/``why_ru``/``star``/``star_ru`` are text only.
    """
    links_t = tuple(sorted(set(links), key=id_key))
    pairs_t = tuple(sorted(set(pairs), key=id_key))
    english, russian = CODES[code]
    fill = {"hint": "", "hint_ru": "", "why": "", "why_ru": "", "star": "", "star_ru": "",
            **data, "links": format_links(links_t), "links_ru": format_links(links_t, "ru"),
            "links_plain": _plain(list(links_t)), "pairs": _plain(list(pairs_t)) or "—"}
    text_keys = {"hint", "hint_ru", "why", "why_ru", "star", "star_ru"}
    kept = {key: value for key, value in data.items() if key not in text_keys}
    return Diagnostic(code, links_t, pairs_t, english.format(**fill), russian.format(**fill),
                      kept)
