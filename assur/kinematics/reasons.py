"""Why a group does not assemble at a position: every code any group kind reports.

The dyads L1–L5 report the codes 1–7 (``docs/group_solvers.md``), the triad and the class IV
group (:mod:`assur.kinematics.higher`) 7–9, a linear input beyond its stroke 10; every consumer (text, JSON, CSV, plots, the
report, batch) turns a code into its sentence with :func:`reason_text`. The sentence of
:class:`Reason` ``R`` is the catalogue entry ``reason.<r>`` (:mod:`assur.text`).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from enum import IntEnum

from assur.text import Message, render

__all__ = ["REASONS", "Reason", "reason_message", "reason_text"]


class Reason(IntEnum):
    """Why a group does not assemble at a position (the ``reason`` of a solution)."""

    ASSEMBLES = 0
    STRETCHED = 1
    FOLDED = 2
    ROD_TOO_SHORT = 3
    OFFSET_TOO_LARGE = 4
    GUIDES_PARALLEL = 5
    COINCIDENT_HINGES = 6
    UNDEFINED_INPUT = 7
    #: A triad's or class IV group's followed assembly mode merges with another one.
    MODE_ENDS = 8
    #: The followed mode is not connected to the sketched position, or is ambiguous.
    NOT_FOLLOWED = 9
    #: A linear input (a slider, an actuator) is beyond an end of its stroke.
    STROKE_END = 10

    @property
    def code(self) -> str:
        """The catalogue code of the sentence (``reason.folded``)."""
        return f"reason.{self.name.lower()}"


def reason_text(code: int, lang: str = "en") -> str:
    """Why a group does not assemble, as a sentence in ``lang``.

    Parameters
    ----------
    code : int
        A :class:`Reason` code.
    lang : str
        A catalogue language.

    Returns
    -------
    str
        The sentence.

    Examples
    --------
    >>> reason_text(Reason.FOLDED), reason_text(Reason.FOLDED, "ru")
    ('hinges too close (folded)', 'шарниры слишком близко (цепь сложена)')
    >>> reason_text(8)
    'the assembly mode ends: it merges with another one (dead-centre position of the group)'
    """
    return render(Reason(code).code, lang)



def reason_message(code: int) -> Message:
    """Why a group does not assemble, as a catalogue message (rendered where it is shown).

    >>> reason_message(8).code
    'reason.mode_ends'
    """
    return Message(Reason(code).code)


class _Reasons(Mapping[int, tuple[str, str]]):
    """Reason code → (English sentence, Russian sentence), read from the catalogue."""

    def __getitem__(self, code: int) -> tuple[str, str]:
        if code not in set(Reason):
            raise KeyError(code)
        return reason_text(code, "en"), reason_text(code, "ru")

    def __iter__(self) -> Iterator[int]:
        return iter(int(r) for r in Reason)

    def __len__(self) -> int:
        return len(Reason)


#: Reason code → (English sentence, Russian sentence); :func:`reason_text` gives any language.
REASONS: Mapping[int, tuple[str, str]] = _Reasons()
