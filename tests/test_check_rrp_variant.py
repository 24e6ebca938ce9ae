"""``assur check`` and ``assur batch`` compare the assembly variant of an RRP dyad (L2) in
the student's table with the sketch.

The slider-crank: crank A–B of 50 mm drawn upright, B = (0, 50); rod B–C of 130 mm; slider C
on a frame guide along the x-axis (direction 0°, so u = (1, 0)). The rod reaches the guide
at x = ±√(130² − 50²) = ±120. ``method.md`` §2.2: σ = +1 when C lies on the +u side of the
foot of the perpendicular from H_j = B onto the path of C, here (0, 0). So C drawn at
(120, 0) is the variant +1 and C drawn at (−120, 0) the variant −1. The roles: i = 3 (the
slider, its external pair is prismatic), j = 2 (the rod).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from synthesis.cli import main

#: x of the joint C in the sketch -> the variant σ derived above.
SIGMA = {120.0: 1, -120.0: -1}


def _slider_crank(folder: Path, x_c: float, variant: int) -> Path:
    """The table with its sketch and the student's rows stating ``variant`` for the L2 row."""
    table = {
        "mechanism": {"name": "slider-crank", "inputs": [1], "pairs": [
            {"id": "A", "type": "R", "links": [0, 1]},
            {"id": "B", "type": "R", "links": [1, 2]},
            {"id": "C", "type": "R", "links": [2, 3]},
            {"id": "D", "type": "P", "links": [3, 0], "guide": 0}]},
        "geometry": {"A": {"point": [0, 0]}, "B": {"point": [0, 50]},
                     "C": {"point": [x_c, 0]}, "D": {"point": [x_c, 0], "direction": 0},
                     "input": {"rotation": "ccw"}},
        "structure_identification": [
            {"L": 0, "seq": 1, "i_minus_1": 0, "j_minus_1": None, "i": 1, "j": None,
             "i_plus_1": 2, "j_plus_1": None, "variant": None},
            {"L": 2, "seq": 2, "i_minus_1": 0, "j_minus_1": 1, "i": 3, "j": 2,
             "i_plus_1": None, "j_plus_1": None, "variant": variant}]}
    path = folder / f"slider_crank_{x_c:+.0f}_{variant:+d}.yaml"
    path.write_text(yaml.safe_dump(table), encoding="utf-8")
    return path


@pytest.mark.parametrize("x_c", sorted(SIGMA))
def test_check_flags_an_rrp_variant_the_sketch_contradicts(
        x_c: float, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    sigma = SIGMA[x_c]
    assert main(["check", str(_slider_crank(tmp_path, x_c, sigma)), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["identification_check"] == []
    assert main(["check", str(_slider_crank(tmp_path, x_c, -sigma)), "--json"]) == 0
    (finding,) = json.loads(capsys.readouterr().out)["identification_check"]
    assert (finding["row"], finding["field"], finding["expected"], finding["found"]) == \
        (1, "variant", sigma, -sigma)


def test_batch_flags_an_rrp_variant_the_sketch_contradicts(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    expected = {}
    for x_c, sigma in SIGMA.items():
        for variant in (sigma, -sigma):
            name = _slider_crank(tmp_path, x_c, variant).name
            expected[name] = "matches" if variant == sigma else "differs"
    assert main(["batch", str(tmp_path), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert {row["file"]: row["identification"] for row in rows} == expected
    for row in rows:
        assert (row["verdict"] == "wrong") == (expected[row["file"]] == "differs")
        if row["verdict"] == "wrong":
            assert "'variant'" in row["problem"]
