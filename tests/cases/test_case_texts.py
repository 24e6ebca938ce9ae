"""The built-in cases word their results through the catalogue, in every language."""

from __future__ import annotations

import math

import pytest

from assur.text import languages
from synthesis.cases.fourbar_velocity_ratio import NoSolution, Request
from synthesis.cases.fourbar_velocity_ratio.report import message_dict, no_solution_text
from synthesis.cases.impact.data import PAPER
from synthesis.cases.impact.report import report_text
from synthesis.cases.impact.study import run_study


def _impossible() -> NoSolution:
    with pytest.raises(NoSolution) as caught:
        Request(n_star=2.0, psi1=math.radians(20.0), e=1.5, delta=0.05).check()
    return caught.value


def test_every_reason_of_an_impossible_request_is_told_in_the_asked_language() -> None:
    why = _impossible().message
    assert why.text("en") == (
        "no such mechanism: n* = 2 ≥ 1 on the forward stroke: the rocker of a crank-rocker "
        "always turns slower than the crank while both turn the same way (n < 1 there); a ratio "
        "of magnitude ≥ 1 exists only on the return stroke (give a negative n*); the crank of a "
        "crank-rocker is its shortest link, 0 < e < 1 (frame = 1); found e = 1.5")
    russian = no_solution_text(why, "ru")
    assert "решения нет: такого механизма нет: n* = 2 ≥ 1 на прямом ходе" in russian
    assert russian.rstrip().endswith("; кривошип кривошипно-коромыслового механизма — самое "
                                     "короткое звено, 0 < e < 1 (стойка = 1); задано e = 1.5")


def test_a_message_in_json_carries_its_code_and_every_language() -> None:
    shown = message_dict(_impossible().message)
    assert shown is not None and shown["code"] == "case.fourbar.no_such_mechanism"
    assert set(shown) == {"code", *languages()}


TITLES = {"en": "Impact in a four-bar with a clearance in the bearing B (Vjaters, Viba, Grasmanis)",
          "ru": "Удар в четырёхзвеннике с зазором в шарнире B (Вятерс, Виба, Грасманис)"}


@pytest.mark.parametrize("lang", languages())
def test_the_impact_report_names_no_code(lang: str) -> None:
    text = report_text(run_study(PAPER), lang)
    assert "case." not in text
    if lang in TITLES:
        assert text.splitlines()[0] == TITLES[lang]
