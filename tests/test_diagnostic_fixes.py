"""Diagnostics that give the fix, in both languages: a missing pair, an input on a link not
hinged to the frame, a kind written for another kind's parameters, an assembly variant
nothing can verify, the redundant link of a double parallelogram, more than one input; and
the structure is assessed when only the sketch is inconsistent."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
import yaml

from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
TABLES = ROOT / "input_tables"
FOUR_BAR = (TABLES / "four_bar.yaml").read_text(encoding="utf-8")


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def _without(text: str, *marks: str) -> str:
    return "\n".join(line for line in text.splitlines() if not any(m in line for m in marks))


def _check(path: Path, capsys: pytest.CaptureFixture[str], lang: str = "en"
           ) -> tuple[str, dict[str, Any]]:
    assert main(["check", str(path), "--lang", lang]) == 0
    text = capsys.readouterr().out
    assert main(["check", str(path), "--json"]) == 0
    return text, json.loads(capsys.readouterr().out)


def _loose_links(path: Path) -> list[int]:
    """The moving links of a table that share one pair only (read from the YAML here)."""
    pairs = yaml.safe_load(path.read_text(encoding="utf-8"))["mechanism"]["pairs"]
    count: dict[int, int] = {}
    for pair in pairs:
        for link in pair["links"]:
            count[link] = count.get(link, 0) + 1
    return sorted(link for link, k in count.items() if k == 1 and link != 0)


@pytest.mark.parametrize("lang, words", [
    ("en", ("each hang on one pair, so the chain is not closed there: a pair between them may "
           "be missing")),
    ("ru", ("держатся каждое на одной паре, и цепь там не замкнута: возможно, между ними не "
           "хватает пары"))])
def test_links_on_one_pair_each_are_a_missing_pair(lang: str, words: str, tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path / "no_c.yaml", _without(FOUR_BAR, "{id: C, type", "  C: {point"))
    text, found = _check(path, capsys, lang)
    loose = _loose_links(path)
    assert loose == [2, 3]
    missing = [d for d in found["issues"] if d["code"] == "E_MISSING_PAIR"]
    assert [d["links"] for d in missing] == [loose]
    assert words in text
    assert not [d for d in found["issues"] if d["code"] == "E_UNDERCONSTRAINED"]  # no inputs
    assert found["verdict"] == "wrong" and found["findings"][0]["code"] == "diag.e_missing_pair"


@pytest.mark.parametrize("lang, formula, sketch", [
    ("en", "Structure formula: I(0,1)", "geometry 'C': unknown key"),
    ("ru", "I(0,1)", "geometry 'C'")])
def test_the_structure_is_printed_when_only_the_sketch_is_inconsistent(
        lang: str, formula: str, sketch: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    """Pair C deleted, its sketch line kept: the sketch names a joint the chain lacks."""
    path = _write(tmp_path / "no_c_drawn.yaml", _without(FOUR_BAR, "{id: C, type"))
    text, found = _check(path, capsys, lang)
    assert formula in text and sketch in text
    codes = [f["code"] for f in found["findings"]]
    assert codes[0] == "diag.e_missing_pair"  # the structure explains the sketch's problem
    assert any(f["where"] == "geometry 'C'" for f in found["findings"])


@pytest.mark.parametrize("lang, words", [
    ("en", ("input link 2 is not hinged to the frame; link 1 is the link hinged to the frame: "
           "did you mean '{link: 1}'?")),
    ("ru", ("входное звено 2 не соединено шарниром со стойкой; со стойкой соединено звено 1: "
           "может быть, имелось в виду '{link: 1}'?"))])
def test_an_input_off_the_frame_names_the_link_hinged_to_it(
        lang: str, words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = _write(tmp_path / "input2.yaml", FOUR_BAR.replace("- {link: 1}  ", "- {link: 2}  "))
    pairs = yaml.safe_load(path.read_text(encoding="utf-8"))["mechanism"]["pairs"]
    near = {link for p in pairs if 2 in p["links"] for link in p["links"]} - {2}
    on_frame = {link for p in pairs if 0 in p["links"] for link in p["links"]} - {0}
    assert min(near & on_frame) == 1  # the first neighbour of link 2 hinged to the frame
    text, found = _check(path, capsys, lang)
    assert words in text
    codes = [d["code"] for d in found["issues"]]
    assert codes == ["E_INPUT_NOT_HINGED"]  # no spurious redundant constraints
    assert found["issues"][0]["data"] == {"other": 1}


@pytest.mark.parametrize("lang, words", [
    ("en", "'params': these are the columns of L4, not of L5: is the row's L 4?"),
    ("ru", "'params': это столбцы L4, а не L5: может быть, L этой строки равно 4?")])
def test_a_kind_written_for_another_kinds_parameters(
        lang: str, words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The course table's row of links 4, 5 is L4 (PRP): written L5, its params are L4's."""
    source = (TABLES / "course_11_link_table.yaml").read_text(encoding="utf-8")
    path = _write(tmp_path / "l5.yaml", source.replace("{L: 4, seq: 3", "{L: 5, seq: 3"))
    text, found = _check(path, capsys, lang)
    assert words in text
    assert found["verdict"] == "wrong"
    assert found["findings"][0]["code"] == "model.params_of_kind"


@pytest.mark.parametrize("lang, words, verdict", [
    ("en", "the table has no sketch, so nothing confirms the assembly variant -1", "not verified"),
    ("ru", "в таблице нет эскиза, и вариант сборки -1 проверить нечем", "не проверено")])
def test_a_variant_without_a_sketch_is_not_verified(
        lang: str, words: str, verdict: str, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    source = (TABLES / "course_11_link_table.yaml").read_text(encoding="utf-8")
    row = "i_plus_1: 6,    j_plus_1: null, variant: 1,"
    path = _write(tmp_path / "minus.yaml", source.replace(row, row.replace("1,", "-1,")))
    text, found = _check(path, capsys, lang)
    assert words in text and f"{verdict} (2)" in text.splitlines()[-4]  # rows of L1 and L2
    assert found["verdict"] == "not verified"
    assert {f["level"] for f in found["findings"]} == {"not verified"}


def _analyze_error(path: Path, lang: str, capsys: pytest.CaptureFixture[str]) -> str:
    assert main(["analyze", str(path), "--lang", lang]) == 2
    return capsys.readouterr().err


@pytest.mark.parametrize("lang, words", [
    ("en", ("link 4 (pairs {E, F}) only repeats a constraint the other links already impose, "
           "so W_geom = 1, the number of inputs: remove link 4 with its pairs {E, F}")),
    ("ru", ("звено 4 (пары {E, F}) лишь повторяет связь, которую уже налагают другие звенья, "
           "поэтому W_geom = 1, по числу входов: чтобы исследовать механизм, удалите звено 4 "
           "с его парами {E, F}"))])
def test_the_double_parallelogram_names_its_redundant_link(
        lang: str, words: str, capsys: pytest.CaptureFixture[str]) -> None:
    path = TABLES / "double_parallelogram.yaml"
    table = yaml.safe_load(path.read_text(encoding="utf-8"))
    point = {k: complex(*v["point"]) for k, v in table["geometry"].items()}
    # link 4 (E–F) is a copy of link 3 (C–D): the same vector, so it adds no constraint
    assert point["E"] - point["F"] == point["C"] - point["D"]
    error = _analyze_error(path, lang, capsys)
    assert words in error
    assert "local findings" not in error and "W_geom = 1, but" not in error


@pytest.mark.parametrize("lang, words", [("en", "Inputs: 2, each a law of the cycle parameter"),
                                         ("ru", "Входов: 2, координата каждого — закон")])
def test_two_inputs_are_analysed_over_one_cycle(lang: str, words: str,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["analyze", str(TABLES / "five_bar_two_inputs.yaml"), "--lang", lang])
    assert code == 0 and words in capsys.readouterr().out
