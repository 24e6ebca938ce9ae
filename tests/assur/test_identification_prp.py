"""The i/j roles of a PRP dyad (L4) neither of whose guides is on the frame.

structure.md §5.4: in an L4 row, j is the link whose guide is on the frame if exactly one
is, otherwise the smaller id. The chain and its rows are derived by hand in the header of
tests/assur/chains/x13_prp_guides_on_moving_links.yaml.
"""

from __future__ import annotations

from pathlib import Path

import yaml

from assur import analyse_structure, chain_from_dict
from assur.structure.identification import identification_table

CHAIN = Path(__file__).parent / "chains" / "x13_prp_guides_on_moving_links.yaml"


def test_prp_dyad_with_no_guide_on_the_frame_takes_the_smaller_id_as_j() -> None:
    data = yaml.safe_load(CHAIN.read_text(encoding="utf-8"))
    del data["expected"]
    analysis = analyse_structure(chain_from_dict(data))
    keys = ("L", "seq", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1", "j_plus_1")
    built = [tuple(getattr(row, k) for k in keys) for row in identification_table(analysis)]
    # L4: j = 4 (the smaller id, guided by 3), i = 5 (guided by the crank 1); a link guided
    # (not hinged) by 1 or 3 is no successor, so the only successor is 2 of the crank
    assert built == [(0, 1, 0, None, 1, None, 2, None),
                     (1, 2, 1, 0, 2, 3, None, None),
                     (4, 3, 1, 3, 5, 4, None, None)]
