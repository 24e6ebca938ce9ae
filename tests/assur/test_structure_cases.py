"""Every chain of tests/assur/chains/ against the ``expected:`` block written in it.

The expected values come from structure.md §6 (files t*) or from the hand derivation written
in the file's header comment (files x*), never from running the program.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest
import yaml

from assur import analyse_structure, chain_from_dict
from assur.io.reader import normalise_id

CHAINS = sorted((Path(__file__).parent / "chains").glob("*.yaml"))


def _load(path: Path) -> tuple[Any, dict[str, Any]]:
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    expected = data.pop("expected")
    return chain_from_dict(data, source=str(path)), expected


def _check_group(group: Any, want: dict[str, Any]) -> None:
    got = group.to_dict()
    for key, value in want.items():
        if key == "external":
            found = {p: k for p, _, k in group.external}
            assert found == {normalise_id(p): k for p, k in value.items()}, group.label
        elif key == "internal":
            assert sorted(map(str, group.internal)) == sorted(map(str, value)), group.label
        else:
            assert got[key] == value, (group.label, key)


@pytest.mark.parametrize("path", CHAINS, ids=[p.stem for p in CHAINS])
def test_chain_case(path: Path) -> None:
    chain, expected = _load(path)
    analysis = analyse_structure(chain)
    for key in ("n", "p5", "p4", "W", "W_star", "formula", "mechanism_class", "applicable"):
        if key in expected:
            assert getattr(analysis, key) == expected[key], key
    if "leftover" in expected:
        assert list(analysis.leftover) == expected["leftover"]
    if "groups" in expected:
        assert len(analysis.groups) == len(expected["groups"])
        for group, want in zip(analysis.groups, expected["groups"], strict=True):
            _check_group(group, want)
    if "applicability" in expected:
        failed = [int(re.match(r"condition (\d+)", text).group(1))
                  for text in analysis.conditions("en")]
        assert failed == expected["applicability"]
    if "rank_test" in expected:
        assert analysis.rank is not None
        got = analysis.rank.to_dict()
        for key, value in expected["rank_test"].items():
            assert got[key] == value, key
    found = sorted((d.code, list(d.links)) for d in analysis.issues)
    want = sorted((d["code"], d["links"]) for d in expected["issues"])
    assert found == want
    for item in expected["issues"]:
        match = next(d for d in analysis.issues
                     if d.code == item["code"] and list(d.links) == item["links"])
        for key, value in item.get("data", {}).items():
            assert match.data[key] == value, (item["code"], key)
        if "text" in item:
            assert item["text"] in match.text("en")
        assert match.text("en") and match.text("ru") != match.text("en")
