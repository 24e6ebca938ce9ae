"""The kinds of groups: what a kind is, declared once, as plain data.

A :class:`GroupKind` holds what the program knows of one kind of group: its names in every
language (catalogue codes), the pair pattern that classification recognises, the roles of
its pairs, the parameter columns of ``method.md`` §4.3, the assembly variants and output code
of the identification table, the pairs rebuilt from an identification row and the existence
condition. Structure, identification, kinematics, existence, transmission, schemes and
reports look a kind up here; none of them tests ``kind == …``.

The registry :data:`KINDS` maps the DGTU number L (0 for the input group, 1–5 for the dyads)
to its record; :data:`HIGHER` adds, by code, the class III triad and the class IV group of
order 2.

What a kind *does* lives with the code that does it, in a table keyed by the kind's
:attr:`~GroupKind.code`: the kinematics of each kind (solver, sketch rule, shortfall,
pressure angle) in :mod:`assur.kinematics.rules`, its kinetostatics in
:data:`assur.forces.solver.EQUILIBRIA`. Those modules import this one, never the reverse.
Adding a kind is one :class:`GroupKind` entry here and one entry in each of those tables.

Examples
--------
>>> kind = KINDS[2]
>>> kind.code, kind.pairs, kind.columns[:3]
('L2', 'RRP', ('x_Hj', 'y_Hj', 'l_j'))
>>> kind.title("ru")
'двухповодковая группа 2-го вида (ВВП)'
>>> kind_of_pattern("R", ("P", "R")).number
2
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Literal

from assur.text import render

__all__ = [
    "HIGHER",
    "KINDS",
    "GroupKind",
    "KindCode",
    "kind_of",
    "kind_of_class",
    "kind_of_pattern",
]

#: The code of a kind: the DGTU kinds L0–L5, the triad III and the class IV group IV.
KindCode = Literal["L0", "L1", "L2", "L3", "L4", "L5", "III", "IV"]
#: Columns (x, y) of an external hinge H_i / H_j.
HingeColumns = tuple[str, str]
#: Columns (base x, base y, direction β, offset e or None) of an external guide.
GuideColumns = tuple[str, str, str, "str | None"]
#: The type of a pair (``"R"``/``"P"``) and its guide carrier in an identification row:
#: ``"prev"`` the known link i−1 / j−1, ``"i"``/``"j"`` the group's own link, None for R.
RowPair = tuple[str, "str | None"]


@dataclass(frozen=True, slots=True)
class GroupKind:
    """One kind of group.

    Parameters
    ----------
    number : int or None
        The DGTU number L (0 input group, 1–5 dyads); None for kinds outside the DGTU table.
    code : str
        ``"L0"`` … ``"L5"``, ``"III"``, ``"IV"``.
    pairs : str
        The pair string in English (``"RRR"``); empty where the kind has none.
    group_class : int
        Artobolevsky's class (1 for the input group).
    pattern : tuple or None
        Classification key of a dyad: (internal pair type, sorted external pair types).
    roles : tuple of (role, side)
        Role of each pair (``"H_i"``, ``"C"``, ``"P_i"`` …) and the side it comes from:
        ``"i"``/``"j"`` the external pair of link i/j, ``"c"`` the internal pair.
    columns : tuple of str
        The parameter columns, in the order of tables 2.1–2.6.
    hinges, guides : mapping
        Side → columns of its external hinge, or of its external guide.
    variants : tuple
        Allowed values of the identification table's ``variant``; ``default_variant`` is
        printed when the dimensions are not known.
    out_code : str
        The output-parameter code of table 1.6.
    condition : str
        The existence inequality, as printed in reports.
    row_pairs : tuple of three RowPair, or None
        External pair of i, internal pair, external pair of j of a group rebuilt from an
        identification row.
    j_rule : str
        How classification picks link j: ``"frame_last"``/``"frame_first"`` (the link on
        the frame, else the later/earlier link), ``"revolute"`` (the link whose external
        pair is revolute), ``"not_carrier"`` (the link that does not carry the internal
        guide).

    Examples
    --------
    >>> from assur import KINDS
    >>> KINDS[3].pairs, KINDS[3].group_class
    ('RPR', 2)
    """

    number: int | None
    code: KindCode
    pairs: str
    group_class: int
    pattern: tuple[str, str] | None = None
    roles: tuple[tuple[str, str], ...] = ()
    columns: tuple[str, ...] = ()
    hinges: Mapping[str, HingeColumns] = field(default_factory=dict)
    guides: Mapping[str, GuideColumns] = field(default_factory=dict)
    variants: tuple[int | None, ...] = (None,)
    default_variant: int | None = None
    out_code: str = ""
    condition: str = "—"
    row_pairs: tuple[RowPair, RowPair, RowPair] | None = None
    j_rule: str = ""

    @property
    def key(self) -> str:
        """The stem of this kind's catalogue codes (``"kind.l1"``)."""
        return f"kind.{self.code.lower()}"

    def title(self, lang: str = "en") -> str:
        """The course's name of the kind, e.g. ``'dyad of kind 1 (RRR)'``."""
        return render(f"{self.key}.name", lang)

    def pair_text(self, lang: str = "en") -> str:
        """The pair string in the language (``'RRR'``, ``'ВВВ'``); empty for none."""
        return render(f"{self.key}.pairs", lang) if self.pairs else ""

    def role_rule(self, lang: str = "en") -> str:
        """How the course names the links i and j of this kind."""
        return render(f"{self.key}.roles", lang)

    @property
    def is_input(self) -> bool:
        """Whether this is the input group (class I): it always assembles."""
        return self.group_class == 1

    @property
    def sided(self) -> bool:
        """Whether the kind has two assembly variants σ = ±1."""
        return self.default_variant is not None


# ----------------------------------------------------------------------------- registry

_TAIL = ("l_N", "beta_N", "l_M", "beta_M")
_HI, _HJ = ("x_Hi", "y_Hi"), ("x_Hj", "y_Hj")
_R: RowPair = ("R", None)
_P_PREV: RowPair = ("P", "prev")

#: The kinds of the DGTU method: L0 (input group) and the dyads L1–L5.
KINDS: Mapping[int, GroupKind] = {
    0: GroupKind(0, "L0", "", 1, roles=(("H_i", "i"),),
                 columns=("x_O1", "y_O1", "l_1", "phi_1_0"), out_code="0",
                 condition="s_min ≤ s ≤ s_max"),
    1: GroupKind(1, "L1", "RRR", 2, ("R", "RR"), (("H_i", "i"), ("H_j", "j"), ("C", "c")),
                 (*_HI, *_HJ, "l_i", "l_j", *_TAIL), {"i": _HI, "j": _HJ},
                 variants=(1, -1), default_variant=1, out_code="8;2",
                 condition="|l_i − l_j| ≤ |H_iH_j| ≤ l_i + l_j,  |cos ∠H_i| ≤ 1 − δ",
                 row_pairs=(_R, _R, _R), j_rule="frame_last"),
    2: GroupKind(2, "L2", "RRP", 2, ("R", "PR"), (("P_i", "i"), ("C", "c"), ("H_j", "j")),
                 (*_HJ, "l_j", "x_Ak", "y_Ak", "beta_g", "e", *_TAIL), {"j": _HJ},
                 {"i": ("x_Ak", "y_Ak", "beta_g", "e")}, variants=(1, -1), default_variant=1,
                 out_code="7;3", condition="|h| ≤ (1 − δ)·l_j",
                 row_pairs=(_P_PREV, _R, _R), j_rule="revolute"),
    3: GroupKind(3, "L3", "RPR", 2, ("P", "RR"), (("H_i", "i"), ("P_c", "c"), ("H_j", "j")),
                 (*_HI, *_HJ, "d", *_TAIL), {"i": _HI, "j": _HJ}, variants=(0, 1, -1),
                 default_variant=0, out_code="5", condition="|d| ≤ (1 − δ)·|H_iH_j|",
                 row_pairs=(_R, ("P", "i"), _R), j_rule="not_carrier"),
    4: GroupKind(4, "L4", "PRP", 2, ("R", "PP"), (("P_i", "i"), ("C", "c"), ("P_j", "j")),
                 ("x_Ak", "y_Ak", "beta_i", "e_i", "x_Bk", "y_Bk", "beta_j", "e_j", *_TAIL),
                 guides={"i": ("x_Ak", "y_Ak", "beta_i", "e_i"),
                         "j": ("x_Bk", "y_Bk", "beta_j", "e_j")},
                 out_code="4", condition="|sin(θ_j − θ_i)| ≥ δ",
                 row_pairs=(_P_PREV, _R, _P_PREV), j_rule="frame_first"),
    5: GroupKind(5, "L5", "RPP", 2, ("P", "PR"), (("P_i", "i"), ("P_c", "c"), ("H_j", "j")),
                 (*_HJ, "gamma", "x_Ak", "y_Ak", "beta_S", "e", *_TAIL), {"j": _HJ},
                 {"i": ("x_Ak", "y_Ak", "beta_S", "e")}, out_code="5",
                 condition="|sin γ| ≥ δ", row_pairs=(_P_PREV, ("P", "j"), _R),
                 j_rule="revolute"),
}

#: The kinds outside the DGTU table, by code: the triad (class III, order 3, with bars,
#: blocks hinged to the base or leashes sliding on the base) and the class IV group of
#: order 2 (hinges or sliders), solved by continuation of the drawn assembly mode
#: (:mod:`assur.kinematics.higher`). No identification row names them (``docs/tables.md``).
HIGHER: Mapping[str, GroupKind] = {
    "III": GroupKind(None, "III", "", 3, condition="m = |det R| / Π‖R_k‖ ≥ δ"),
    "IV": GroupKind(None, "IV", "", 4, condition="m = |det R| / Π‖R_k‖ ≥ δ"),
}
_BY_CLASS = {kind.group_class: kind for kind in HIGHER.values()}

_BY_PATTERN = {kind.pattern: kind for kind in KINDS.values() if kind.pattern is not None}


def kind_of(number: int | str) -> GroupKind:
    """The kind with DGTU number L (0–5), or the higher kind with code ``"III"``/``"IV"``.

    Parameters
    ----------
    number : int or str
        The DGTU number L of the kind (0 for the input group), or ``"III"``, ``"IV"``.

    Returns
    -------
    GroupKind
        Its registry entry.

    Raises
    ------
    KeyError
        For a number that is no kind.

    Examples
    --------
    >>> kind_of(4).pairs, kind_of("III").group_class
    ('PRP', 3)
    """
    try:
        return HIGHER[number] if isinstance(number, str) else KINDS[number]
    except KeyError:
        raise KeyError(f"no group kind {number!r}; the kinds are L0–L5, III, IV") from None


def kind_of_class(group_class: int) -> GroupKind | None:
    """The higher kind of a group of this class (3 triad, 4 class IV), None for others.

    Parameters
    ----------
    group_class : int
        Artobolevsky's class of the group.

    Returns
    -------
    GroupKind or None
        The registry entry of the triad or the class IV group.

    Examples
    --------
    >>> kind_of_class(4).code, kind_of_class(5)
    ('IV', None)
    """
    return _BY_CLASS.get(group_class)


def kind_of_pattern(internal: str, external: tuple[str, str]) -> GroupKind | None:
    """The dyad kind with this internal pair type and these external pair types, or None.

    >>> kind_of_pattern("P", ("R", "R")).code
    'L3'
    >>> kind_of_pattern("P", ("P", "P")) is None
    True
    """
    return _BY_PATTERN.get((internal, "".join(sorted(external))))
