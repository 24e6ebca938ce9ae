"""Nothing suspicious passes in silence: decimal commas wherever YAML hides them (refused,
the field named, the number suggested), angles that look like radians (warned, exit code
unchanged), plural forms instead of "(s)", and ``--csv -`` on standard output.

The expectations are worked out here from the tables' own text: the number a decimal comma
meant, the degrees of a radian value, the line a field stands on.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from pathlib import Path

import pytest

from assur.io.chain_table import load_chain
from assur.structure.analysis import analyse_structure
from assur.text import render
from synthesis.cli import main

ROOT = Path(__file__).resolve().parent.parent
TABLES = ROOT / "input_tables"


def _table(tmp_path: Path, source: str, old: str, new: str, name: str = "t.yaml") -> Path:
    text = (TABLES / source).read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


def _run(capsys: pytest.CaptureFixture[str], *words: str) -> tuple[int, str, str]:
    code = main(list(words))
    out, err = capsys.readouterr()
    return code, out, err


# ---------------------------------------------------------------------------- decimal commas

@pytest.mark.parametrize("lang, words", [
    ("en", "found a list of 3 items; decimal comma? write {fixed} for {written}"),
    ("ru", "найдено: список из 3 элементов; десятичная запятая? пишите {fixed} вместо {written}")])
def test_a_decimal_comma_in_a_point(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                    lang: str, words: str) -> None:
    table = _table(tmp_path, "four_bar.yaml", "C: {point: [110, 80]}", "C: {point: [110, 80,5]}")
    code, _, err = _run(capsys, "--lang", lang, "analyze", str(table))
    assert code == 2
    assert "geometry 'C' 'point'" in err
    assert words.format(fixed=80.5, written="80,5") in err
    # check does not need the sketch: it prints the structure and the sketch's problem
    code, out, _ = _run(capsys, "--lang", lang, "check", str(table))
    assert code == 0 and "I(0,1) → II₁(2,3)" in out
    assert "geometry 'C' 'point'" in out and words.format(fixed=80.5, written="80,5") in out


@pytest.mark.parametrize("command", ["check", "analyze"])
def test_a_decimal_comma_in_identification_params(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str],
                                                  command: str) -> None:
    table = _table(tmp_path, "course_11_link_table.yaml", "l_1: 40, phi_1_0", "l_1: 40,5, phi_1_0")
    text = table.read_text(encoding="utf-8")
    line = text[:text.index("l_1: 40,5")].count("\n") + 1
    code, _, err = _run(capsys, command, str(table))
    assert code == 2
    assert f"line {line}, column" in err and "'l_1: 40,5' has a decimal comma? write 40.5" in err
    assert "unknown column" not in err
    code, _, err = _run(capsys, "--lang", "ru", command, str(table))
    assert code == 2 and "в 'l_1: 40,5' десятичная запятая? пишите 40.5" in err


def test_a_decimal_comma_in_a_block_mapping(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    table = _table(tmp_path, "four_bar_gravity.yaml", "  omega: 10 ", "  omega: 10,5 ")
    code, _, err = _run(capsys, "check", str(table))
    assert code == 2
    assert "'omega: 10,5' has a decimal comma? write 10.5" in err
    code, _, err = _run(capsys, "--lang", "ru", "check", str(table))
    assert "в 'omega: 10,5' десятичная запятая? пишите 10.5" in err


def test_a_decimal_comma_in_a_problem_table(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    source = "problems/class1_fourbar_rocker.yaml"
    ranged = _table(tmp_path, source, "l_1: [36, 30, 50]", "l_1: [36,5, 30, 50]", "a.yaml")
    code, _, err = _run(capsys, "synthesize", str(ranged))
    assert code == 2 and "'l_1'" in err and "(decimal comma? write 36.5 for 36,5)" in err
    fixed = _table(tmp_path, source, "x_Hj: 110,", "x_Hj: 110,5,", "b.yaml")
    code, _, err = _run(capsys, "--lang", "ru", "synthesize", str(fixed))
    assert code == 2 and "в 'x_Hj: 110,5' десятичная запятая? пишите 110.5" in err


def test_lists_written_without_spaces_are_still_read(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    table = _table(tmp_path, "four_bar.yaml", "links: [1, 2]}", "links: [1,2]}")
    assert _run(capsys, "check", str(table))[0] == 0


# ---------------------------------------------------------------------------------- radians

@pytest.mark.parametrize("value, pi", [(3.1416, "π"), (1.5708, "π/2"), (4.7124, "3π/2"),
                                       (6.2832, "2π")])
def test_a_direction_of_a_multiple_of_half_pi_is_warned(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], value: float, pi: str) -> None:
    table = _table(tmp_path, "slider_crank.yaml", "direction: 0}", f"direction: {value}}}")
    degrees = round(math.degrees(value), 2)
    code, out, err = _run(capsys, "check", str(table))
    assert code == 0 and out
    assert (f"warning: {table}: geometry 'D' 'direction': {value:g} looks like an angle in "
            f"radians ({pi}); angles are in degrees: did you mean {degrees:g}?") in err
    code, _, err = _run(capsys, "--lang", "ru", "analyze", str(table), "--points", "12")
    assert code == 0
    assert (f"предупреждение: {table}: geometry 'D' 'direction': {value:g} похоже на угол в "
            f"радианах ({pi}); углы задаются в градусах: может быть, {degrees:g}?") in err


def test_warnings_are_listed_in_json(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    table = _table(tmp_path, "slider_crank.yaml", "direction: 0}", "direction: 3.1416}")
    for command in (["check"], ["analyze", "--points", "12"]):
        code, out, err = _run(capsys, *command[:1], str(table), *command[1:], "--json")
        assert code == 0 and err == ""
        warnings = json.loads(out)["warnings"]
        assert [(w["code"], w["where"]) for w in warnings] == [
            ("table.warn_radian", "geometry 'D' 'direction'")]
        assert "180?" in warnings[0]["message"] and "180?" in warnings[0]["message_ru"]
    plain = TABLES / "slider_crank.yaml"
    code, out, _ = _run(capsys, "check", str(plain), "--json")
    assert json.loads(out)["warnings"] == []


def test_a_guide_direction_in_radians_puts_the_hinge_off_the_guide(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    written = 1.5755  # 90.27° in radians, as the issue's example
    table = _table(tmp_path, "course_11_link.yaml", "direction: 90.27}",
                   f"direction: {written}}}")
    sketch = load_chain(TABLES / "course_11_link.yaml").geometry
    assert sketch is not None
    guide, hinge = sketch.points["3-4"], sketch.points["4-5"]
    along = complex(math.cos(math.radians(written)), math.sin(math.radians(written)))
    off = abs(((hinge - guide) * along.conjugate()).imag)  # the line as the program reads it
    code, _, err = _run(capsys, "check", str(table))
    assert code == 0
    assert (f"geometry '3-4' 'direction': the hinge '4-5' of the slider '3-4' is {off:.3g} mm "
            f"off its drawn guide line; the direction 1.5755 looks like radians: "
            f"{round(math.degrees(written), 2):g}° puts the hinge on the guide") in err
    code, _, err = _run(capsys, "--lang", "ru", "check", str(table))
    assert f"шарнир '4-5' ползуна '3-4' отстоит от нарисованной направляющей на {off:.3g} мм" \
        in err


def test_all_directions_within_two_pi_are_warned_once(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    text = (TABLES / "course_11_link.yaml").read_text(encoding="utf-8")
    radians = re.sub(r"direction: ([-\d.]+)",
                     lambda m: f"direction: {math.radians(float(m.group(1))):.4f}", text)
    table = tmp_path / "t.yaml"
    table.write_text(radians, encoding="utf-8")
    code, _, err = _run(capsys, "check", str(table))
    assert code == 0
    lines = [line for line in err.splitlines() if "every direction is within 2π" in line]
    assert len(lines) == 1 and "'5-0'" not in lines[0]  # 0 is the same in both units


def test_the_shipped_tables_give_no_warning() -> None:
    for path in sorted(TABLES.glob("*.yaml")):
        try:
            chain = load_chain(path)
        except ValueError:
            continue  # the tables of other commands
        assert chain.warnings == (), path.name


# ------------------------------------------------------------------------------ plural forms

def test_no_sentence_guesses_its_plural() -> None:
    for lang in ("en", "ru"):
        text = (ROOT / "assur" / "locale" / f"{lang}.po").read_text(encoding="utf-8")
        assert not re.findall(r"\w\((?:s|es)\)", text), lang


def _russian_form(n: int) -> int:
    """The Russian plural form of ``n`` (0: 1, 21; 1: 2–4, 22; 2: 5–20, 25)."""
    if n % 10 == 1 and n % 100 != 11:
        return 0
    return 1 if 2 <= n % 10 <= 4 and not 12 <= n % 100 <= 14 else 2


@pytest.mark.parametrize("n", [1, 2, 5, 11, 21, 22])
def test_the_count_of_mismatches_agrees_with_its_noun(n: int) -> None:
    english = render("report.structure.table_differs", "en", n=n)
    assert english.endswith(f"({n} mismatch):" if n == 1 else f"({n} mismatches):")
    noun = ("расхождение", "расхождения", "расхождений")[_russian_form(n)]
    assert render("report.structure.table_differs", "ru", n=n).endswith(f"({n} {noun}):")


def test_one_loose_link_is_one_link(tmp_path: Path) -> None:
    rocker = "    - {id: 3, name: {en: rocker, ru: коромысло}}\n"
    table = _table(tmp_path, "four_bar.yaml", rocker, rocker + "    - {id: 4, name: loose}\n")
    found = [d for d in analyse_structure(load_chain(table)).issues
             if d.code == "E_DISCONNECTED"]
    assert [d.text("en") for d in found] == ["link 4 is not connected to the frame"]
    assert [d.text("ru") for d in found] == ["звено 4 не связано со стойкой"]
    two = _table(tmp_path, "four_bar.yaml", rocker, rocker + "    - {id: 4}\n    - {id: 5}\n",
                 "two.yaml")
    found = [d for d in analyse_structure(load_chain(two)).issues if d.code == "E_DISCONNECTED"]
    assert [d.text("en") for d in found] == ["links {4, 5} are not connected to the frame"]
    assert [d.text("ru") for d in found] == ["звенья {4, 5} не связаны со стойкой"]


# ------------------------------------------------------------------------------ --csv -

def test_csv_dash_is_standard_output(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                     monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    code, out, _ = _run(capsys, "analyze", str(TABLES / "four_bar.yaml"), "--points", "8",
                        "--csv", "-")
    assert code == 0 and not (tmp_path / "-").exists()
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [float(row["phi_deg"]) for row in rows] == [45.0 * k for k in range(8)]
    folder = tmp_path / "class"
    folder.mkdir()
    (folder / "a.yaml").write_bytes((TABLES / "four_bar.yaml").read_bytes())
    code, out, _ = _run(capsys, "batch", str(folder), "--csv", "-", "--quiet")
    assert code == 0 and not (tmp_path / "-").exists()
    rows = list(csv.DictReader(io.StringIO(out.lstrip("\ufeff"))))
    assert [(row["file"], row["verdict"]) for row in rows] == [("a.yaml", "correct")]
    code, out, err = _run(capsys, "analyze", str(TABLES / "four_bar.yaml"), "--csv", "-",
                          "--json")
    assert code == 2 and out == "" and "--csv -: standard output carries the --json" in err


def test_an_angle_of_identification_params_in_radians_is_warned(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    table = _table(tmp_path, "course_11_link_table.yaml", "beta_S: 90,", "beta_S: 1.5708,")
    code, _, err = _run(capsys, "check", str(table))
    assert code == 0
    assert ("'beta_S': 1.5708 looks like an angle in radians (π/2); angles are in degrees: "
            "did you mean 90?") in err
    table = _table(tmp_path, "course_11_link_table.yaml", "l_1: 40,", "l_1: 3.1416,", "l.yaml")
    assert "radians" not in _run(capsys, "check", str(table))[2]  # a length, not an angle


def test_a_decimal_comma_in_a_block_list(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    table = _table(tmp_path, "four_bar.yaml", "C: {point: [110, 80]}",
                   "C:\n    point:\n      - 110\n      - 80,25")
    text = table.read_text(encoding="utf-8")
    line = text[:text.index("80,25")].count("\n") + 1
    code, _, err = _run(capsys, "check", str(table))
    assert code == 2 and f"line {line}, column 9: '80,25' has a decimal comma? write 80.25" in err
    code, _, err = _run(capsys, "--lang", "ru", "check", str(table))
    assert code == 2 and "в '80,25' десятичная запятая? пишите 80.25" in err
