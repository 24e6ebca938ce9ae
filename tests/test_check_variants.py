"""The identification table built by ``assur check`` takes assembly variants from the sketch.

Expected rows are table 1.6 of the course as printed (``docs/method.md`` §3.3), reordered
into layering order; the variants 1 (L1), 0 (L3) and −1 (L2) are the source's values. The
output-parameter codes of the course's table (0, 8;2, 7;3, 5, 4, 5) are not expected: what
they mean is lost from the text and a chain table names no output, so the program writes none.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from synthesis.cli import main

TABLE_1_6 = [  # L, i-1, j-1, i, j, i+1, j+1, variant, out_code (none derivable)
    (0, 0, None, 1, None, 2, None, None, None),
    (1, 1, 0, 2, 3, 6, None, 1, None),
    (4, 3, 0, 4, 5, None, None, None, None),
    (3, 2, 0, 6, 7, 8, None, 0, None),
    (2, 0, 6, 9, 8, None, 10, -1, None),
    (5, 0, 8, 11, 10, None, None, None, None),
]
FIELDS = ("L", "i_minus_1", "j_minus_1", "i", "j", "i_plus_1", "j_plus_1", "variant", "out_code")


def test_course_example_table_matches_table_1_6_with_variants(
        tables_dir: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", str(tables_dir / "course_11_link.yaml"), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["identification_table"]
    assert [tuple(row[f] for f in FIELDS) for row in rows] == TABLE_1_6


def test_mirrored_sketch_flips_the_rrr_variant(tables_dir: Path, tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    """Mirroring every joint about the x-axis puts C on the other side of H_i→H_j."""
    import yaml

    data = yaml.safe_load((tables_dir / "course_11_link.yaml").read_text(encoding="utf-8"))
    for entry in data["geometry"].values():
        if isinstance(entry, dict) and "point" in entry:
            x, y = entry["point"]
            entry["point"] = [x, -y]
            if "direction" in entry and isinstance(entry["direction"], (int, float)):
                entry["direction"] = -entry["direction"]
            elif "direction" in entry and isinstance(entry["direction"], list):
                dx, dy = entry["direction"]
                entry["direction"] = [dx, -dy]
    mirrored = tmp_path / "mirrored.yaml"
    mirrored.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    assert main(["check", str(mirrored), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["identification_table"]
    assert rows[1]["L"] == 1 and rows[1]["variant"] == -1
