"""Every reason code a group can report, through every consumer that renders it.

The reasons of the dyads (1–7) and of the triad and the class IV group (7–9) are one
enumeration, :class:`assur.kinematics.reasons.Reason`. Its sentences are read here straight
from the PO files (not through the program's catalogue); tables that stop assembling are then
run through every command that renders a reason (text, JSON, CSV, the mechanism picture at a
failing position, the animation, the force picture, the HTML report, batch with reports):
each ends with exit 0 and says why, in both languages.
"""

from __future__ import annotations

import html
import json
import re
from pathlib import Path

import pytest

from assur.kinematics.reasons import Reason, reason_text
from synthesis.cli import main

ROOT = Path(__file__).resolve().parents[2]
TABLES = ROOT / "input_tables"
LOCALE = ROOT / "assur" / "locale"
#: A triad whose drawn mode ends at φ ≈ 168° and 256° (code 8), and a dyad RPR that
#: fails over φ ≈ 21.6°…72.6° (code 4), with a crank angle inside each failing interval.
FAILING = {"six_bar_triad_fails.yaml": (Reason.MODE_ENDS, 200.0),
           "course_11_link_fails.yaml": (Reason.OFFSET_TOO_LARGE, 40.0)}


_CATALOGUES: dict[str, dict[str, str]] = {}


def _po(lang: str) -> dict[str, str]:
    """msgid → msgstr of the one-line entries of a PO file (read once)."""
    if lang not in _CATALOGUES:
        text = (LOCALE / f"{lang}.po").read_text(encoding="utf-8")
        _CATALOGUES[lang] = dict(re.findall(r'^msgid "(.+)"\nmsgstr "(.*)"$', text,
                                            flags=re.MULTILINE))
    return _CATALOGUES[lang]


@pytest.mark.parametrize("reason", list(Reason), ids=lambda r: r.name)
def test_every_reason_has_its_sentence_in_both_catalogues(reason: Reason) -> None:
    """``reason.<name>`` is in en.po and ru.po; the Russian one has no Latin word."""
    en, ru = _po("en"), _po("ru")
    assert reason.code == f"reason.{reason.name.lower()}"
    assert en.get(reason.code) and ru.get(reason.code)
    assert not re.search(r"[A-Za-z]{2,}", ru[reason.code])
    assert reason_text(reason, "en") == en[reason.code]
    assert reason_text(int(reason), "ru") == ru[reason.code]


def test_the_sentences_differ() -> None:
    """No two reasons read alike, in either language."""
    for lang in ("en", "ru"):
        sentences = [reason_text(r, lang) for r in Reason]
        assert len(set(sentences)) == len(sentences)


def _words(picture: Path) -> str:
    """The words of an SVG picture (its text elements, wrapped lines joined)."""
    texts = re.findall(r"<text[^>]*>([^<]*)", picture.read_text(encoding="utf-8"))
    return " ".join(" ".join(html.unescape(t) for t in texts).split())


def _run(capsys: pytest.CaptureFixture[str], *argv: object) -> tuple[str, str]:
    """Run a command that must end with exit 0; its standard output and error."""
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 0, out + err
    assert "internal error" not in out + err
    return out, err


@pytest.mark.parametrize("name", list(FAILING))
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_a_failing_table_through_every_consumer(name: str, lang: str, tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    """Text, JSON, CSV, picture at a failing angle, animation, report and batch: exit 0, and
    the reason's sentence where the output is text."""
    table = TABLES / name
    reason, at = FAILING[name]
    why = _po(lang)[reason.code]

    out, _ = _run(capsys, "analyze", table, "--points", 72, "--lang", lang)
    assert why in out

    out, _ = _run(capsys, "analyze", table, "--points", 72, "--json")
    record = json.loads(out)
    existence = [group["existence"] for group in record["groups"] if "existence" in group]
    assert int(reason) in {code for group in existence for code in group["reason"]}
    assert _po("en")[reason.code] in json.dumps(record, ensure_ascii=False)

    csv = tmp_path / "run.csv"
    _run(capsys, "analyze", table, "--points", 72, "--csv", csv)
    assert csv.read_text(encoding="utf-8").count("\n") == 73

    picture = tmp_path / "at.svg"
    _run(capsys, "analyze", table, "--points", 72, "--plot", picture, "--at", at,
         "--lang", lang)
    assert why in _words(picture)

    animation = tmp_path / "cycle.gif"
    _run(capsys, "analyze", table, "--points", 36, "--animate", animation, "--frames", 4,
         "--lang", lang)
    assert animation.stat().st_size > 0

    report = tmp_path / "report.html"
    _run(capsys, "report", table, "--points", 72, "--out", report, "--lang", lang)
    assert why in report.read_text(encoding="utf-8")

    folder = tmp_path / "batch"
    folder.mkdir()
    (folder / name).write_bytes(table.read_bytes())
    out, _ = _run(capsys, "batch", folder, "--reports", tmp_path / "reports", "--lang", lang,
                  "--jobs", 1)
    assert why in out
    assert why in (tmp_path / "reports" / name.replace(".yaml", ".html")).read_text(
        encoding="utf-8")


def test_forces_of_a_failing_triad(tmp_path: Path,
                                   capsys: pytest.CaptureFixture[str]) -> None:
    """The force analysis of the triad of ``six_bar_triad_forces.yaml`` with the crank pin
    of ``six_bar_triad_fails.yaml``: its text, CSV and picture at a failing angle."""
    source = (TABLES / "six_bar_triad_forces.yaml").read_text(encoding="utf-8")
    pin = "B: {point: [-17, -0.5]}"
    assert pin in source
    table = tmp_path / "forces_fails.yaml"
    table.write_text(source.replace(pin, "B: {point: [-50, -1.5]}"), encoding="utf-8")
    why = _po("en")[Reason.MODE_ENDS.code]
    csv, picture = tmp_path / "forces.csv", tmp_path / "forces.svg"
    out, _ = _run(capsys, "analyze", table, "--points", 72, "--forces", "--omega", 10,
                  "--csv", csv, "--plot", picture, "--at", 200)
    assert why in out
    rows = csv.read_text(encoding="utf-8").splitlines()
    assert len(rows) == 73 and "driving_torque" in rows[0]
    assert why in _words(picture)


def test_no_csv_left_after_a_failure_while_drawing(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str],
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    """A run that ends in an internal error (exit 3) while drawing leaves no CSV behind."""
    import assur.plot.mechanism

    def broken(*args: object, **kwargs: object) -> None:
        raise RuntimeError("drawing failed")

    monkeypatch.setattr(assur.plot.mechanism, "save_mechanism_picture", broken)
    csv = tmp_path / "run.csv"
    code = main(["analyze", str(TABLES / "six_bar_triad_fails.yaml"), "--points", "12",
                 "--csv", str(csv), "--plot", str(tmp_path / "at.png")])
    capsys.readouterr()
    assert code == 3
    assert not csv.exists()


@pytest.mark.parametrize("reason", list(Reason)[1:], ids=lambda r: r.name)
def test_every_code_through_the_sentence_builders(reason: Reason) -> None:
    """Each failing code in the picture's caption and in an existence interval's record (the
    JSON, the text, batch and the report take the interval's sentence), in both languages."""
    from assur.kinematics.analysis import analyse
    from assur.kinematics.build import load_model
    from assur.kinematics.existence import FailureInterval
    from assur.plot.mechanism import Failure, failure_text

    motion = analyse(load_model(TABLES / "six_bar_triad.yaml"), points=12)
    for lang in ("en", "ru"):
        caption = failure_text(motion, Failure("III(2,3,4,5)", int(reason), (), ((3, 5),)),
                               lang)
        assert _po(lang)[reason.code] in caption
    record = FailureInterval(0.5, 1.0, int(reason), -0.1, 0.7, 1.0, "mm").to_dict(False)
    assert record["reason"] == int(reason)
    assert record["condition"] == _po("en")[reason.code]
