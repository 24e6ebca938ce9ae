"""The report a student hands in: the title block (student, group, variant, date) from the
options or the table's ``student:`` section, and no error style for a valid mechanism."""

from __future__ import annotations

import datetime
import re
from pathlib import Path

import pytest

from assur import TableError, load_chain
from assur.model import Student
from synthesis import load_problem
from synthesis.app.coursework import build_report, render_html
from synthesis.cli import main

TABLES = Path(__file__).resolve().parent.parent / "input_tables"


def _title_block(page: str) -> dict[str, str]:
    block = re.search(r'<dl class="student" id="student">(.*?)</dl>', page).group(1)
    return dict(re.findall(r"<dt>(.*?)</dt><dd[^>]*>(.*?)</dd>", block))


def _with_student(tmp_path: Path, section: str) -> Path:
    table = tmp_path / "four_bar.yaml"
    table.write_text((TABLES / "four_bar.yaml").read_text(encoding="utf-8") + section,
                     encoding="utf-8")
    return table


def test_title_block_from_the_table_and_the_options(tmp_path, capsys):
    table = _with_student(tmp_path, "student:\n  name: Ivanova A. A.\n  group: MT-21\n"
                                    "  variant: 7\n")
    out = tmp_path / "r.html"
    assert main(["report", str(table), "--points", "12", "--out", str(out), "--quiet",
                 "--variant", "12", "--date", "2026-05-12"]) == 0
    shown = _title_block(out.read_text(encoding="utf-8"))
    assert shown == {"Student": "Ivanova A. A.", "Group": "MT-21", "Variant": "12",
                     "Date": "2026-05-12"}
    # the chain itself is read as before: check and batch accept the section
    assert main(["check", str(table)]) == 0


def test_title_block_blank_lines_and_today_by_default(tmp_path):
    report = build_report(TABLES / "four_bar.yaml", points=12, lang="ru")
    shown = _title_block(render_html(report))
    assert shown == {"Студент": "", "Группа": "", "Вариант": "",
                     "Дата": datetime.date.today().isoformat()}


@pytest.mark.parametrize(("section", "field"), [
    ("student: {name: [Ivanova]}\n", "student 'name'"),
    ("student: {date: 12.05.2026}\n", "student 'date'"),
    ("student: {nmae: Ivanova}\n", "did you mean 'name'"),
])
def test_a_bad_student_section_is_reported_by_field(tmp_path, section, field):
    with pytest.raises(TableError) as info:
        load_chain(_with_student(tmp_path, section))
    assert field in str(info.value)


def test_a_date_option_that_is_not_a_date_exits_2(tmp_path, capsys):
    assert main(["report", str(TABLES / "four_bar.yaml"), "--out", str(tmp_path / "r.html"),
                 "--date", "12.05.2026"]) == 2
    assert "--date" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["six_bar_triad.yaml", "class_iv_group.yaml"])
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_a_valid_higher_group_mechanism_has_no_error_style(name, lang):
    page = render_html(build_report(TABLES / name, points=12, lang=lang))
    section = re.search(r'<section id="identification">(.*?)</section>', page).group(1)
    assert 'class="bad"' not in page  # outside the course's program is no mistake
    assert '<p class="note" id="no-dgtu-table">' in section
    assert "<th></th>" not in page  # no empty header row anywhere


def test_the_chain_reader_gives_the_student_section(tmp_path: Path) -> None:
    table = _with_student(tmp_path, "student:\n  name: ' Ivanova A. A. '\n  group: MT-21\n"
                                    "  variant: 7\n  date: 2026-05-12\n")
    # written by hand above: the name trimmed, the variant's number kept as its digits
    assert load_chain(table).student == Student(name="Ivanova A. A.", group="MT-21",
                                                variant="7", date="2026-05-12")
    assert load_chain(TABLES / "four_bar.yaml").student is None


def _problem_with_student(tmp_path: Path, section: str) -> Path:
    table = tmp_path / "problem.yaml"
    table.write_text((TABLES / "problems" / "class1_fourbar_rocker.yaml")
                     .read_text(encoding="utf-8") + section, encoding="utf-8")
    return table


def test_a_problem_gives_its_student_section_to_the_report(tmp_path: Path) -> None:
    table = _problem_with_student(tmp_path, "student: {name: Petrov B. B., variant: 3}\n")
    assert load_problem(table).student == Student(name="Petrov B. B.", variant="3")
    report = build_report(table, points=12, budget=4,
                          student={"group": "MT-22", "date": "2026-05-12", "name": None})
    shown = _title_block(render_html(report))
    assert shown == {"Student": "Petrov B. B.", "Group": "MT-22", "Variant": "3",
                     "Date": "2026-05-12"}


def test_a_bad_student_section_of_a_problem_is_reported_by_field(tmp_path: Path) -> None:
    with pytest.raises(TableError) as info:
        load_problem(_problem_with_student(tmp_path, "student: {variant: ''}\n"))
    assert "student 'variant'" in str(info.value)
