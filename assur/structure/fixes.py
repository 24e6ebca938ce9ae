"""The findings of a structural analysis with the fix where the peeling's own words would
mislead (a missing pair, an input on the wrong link, a redundant link): the findings of
:mod:`assur.structure.diagnostics` re-read against trial decompositions of
:mod:`assur.structure.peeling`.
"""

from __future__ import annotations

from dataclasses import replace

from assur.model import Chain, Drive, id_key
from assur.structure.diagnostics import Diagnostic, diagnostic
from assur.structure.peeling import body_graph, peel

__all__ = ["with_fixes"]


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
