"""Pictures of a mechanism that obey: a design that never assembles is drawn (the failing
group marked), the file is written in the format its name asks for, the title says from
where φ is counted, coinciding joints and paths stay readable.

Expectations come from hand calculations on the tables (law of cosines, the sketch's crank
angle) and from the files' own signatures (magic bytes), not from the drawing code.
"""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import yaml
from matplotlib.lines import Line2D

from assur.kinematics.analysis import analyse
from assur.kinematics.build import load_model
from assur.plot.formats import PictureFormatError, animation_format
from assur.plot.mechanism import (
    coinciding,
    draw_mechanism,
    failing_group,
    figure_for,
    save_animation,
    save_mechanism_picture,
)
from synthesis.cli import main

ROOT = Path(__file__).resolve().parents[2]
FAILS = ROOT / "input_tables" / "course_11_link_fails.yaml"
MAGIC = {"png": b"\x89PNG\r\n\x1a\n", "svg": b"<?xml", "pdf": b"%PDF-", "jpg": b"\xff\xd8\xff",
         "gif": b"GIF89a"}


@pytest.fixture(scope="module")
def never(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The course's 11-link table with a coupler 30 mm and a rocker 30 mm: the crank pin
    (40 mm from O1) is always at least 150 − 40 = 110 mm from the rocker pivot (150, 0),
    more than 30 + 30, so the first dyad L1(2,3) never closes, and nothing after it."""
    data = yaml.safe_load((ROOT / "input_tables" / "course_11_link_table.yaml").read_text("utf-8"))
    params = data["structure_identification"][1]["params"]
    params.update(l_i=30, l_j=30)
    path = tmp_path_factory.mktemp("never") / "never.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    return path


def test_a_design_that_never_assembles_is_drawn_with_its_failing_group(never: Path) -> None:
    motion = analyse(load_model(never), np.radians(np.arange(0.0, 360.0, 30.0)))
    assert not np.asarray(motion.exists).any()
    _, ax = figure_for(motion)
    draw_mechanism(motion, 2, ax, lang="ru")  # φ = 60°
    title = ax.get_title().replace("\n", " ")
    assert "группа L1(2,3) не собирается ни в одном положении цикла" in title
    # the rings sit on the group's outer hinges: the crank pin at 30° + 60° and the pivot
    rings = [line for line in ax.lines if line.get_gid() == "fails-L1(2,3)"]
    assert len(rings) == 1
    xy = np.column_stack(rings[0].get_data())
    pin = 40 * np.exp(1j * math.radians(90.0))
    assert np.allclose(sorted(map(tuple, xy)), sorted([(pin.real, pin.imag), (150.0, 0.0)]),
                       atol=1e-9)


def test_the_failing_interval_is_the_one_the_table_documents() -> None:
    # the table's comment: L3 (6, 7) fails over φ = 21.59°…72.58° (guide offset 72 mm
    # larger than the hinge distance); on a 1° grid that is 22°…72°
    motion = analyse(load_model(FAILS), np.radians(np.arange(0.0, 360.0, 1.0)))
    failure = failing_group(motion, 45)
    assert failure is not None and failure.label == "L3(6,7)"
    assert failure.runs == ((22, 72),)
    assert failing_group(motion, 21) is None and failing_group(motion, 73) is None


def test_commands_draw_a_design_that_never_assembles(never: Path, tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    picture = tmp_path / "never.svg"
    assert main(["analyze", str(never), "--points", "24", "--plot", str(picture)]) == 0
    assert picture.read_bytes().startswith(MAGIC["svg"])
    assert "L1(2,3) does not assemble" in picture.read_text("utf-8")
    page = tmp_path / "never.html"
    assert main(["report", str(never), "--points", "24", "--out", str(page)]) == 0
    html = page.read_text("utf-8")
    assert "group L1(2,3) does not assemble anywhere in the cycle" in html
    assert "Traceback" not in capsys.readouterr().err


@pytest.mark.parametrize("ending", ["png", "svg", "pdf", "jpg"])
def test_a_picture_is_written_in_the_format_of_its_name(ending: str, tmp_path: Path) -> None:
    motion = analyse(load_model(ROOT / "input_tables" / "four_bar.yaml"), points=12)
    path = tmp_path / f"four_bar.{ending}"
    save_mechanism_picture(motion, path, index=1, dpi=30)
    assert path.read_bytes().startswith(MAGIC[ending])


def test_unsupported_endings_are_refused_before_any_work(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]
                                                        ) -> None:
    missing = tmp_path / "no_such_table.yaml"  # never read: the ending is checked first
    assert main(["analyze", str(missing), "--plot", str(tmp_path / "a.bmp")]) == 2
    assert capsys.readouterr().err.strip() == (
        f"{tmp_path / 'a.bmp'}: a picture cannot be written as .bmp; "
        "write one of: .png, .svg, .pdf, .jpg, .jpeg")
    assert main(["analyze", str(missing), "--animate", str(tmp_path / "a.avi"),
                 "--lang", "ru"]) == 2
    assert "анимацию нельзя записать в формате .avi; допустимые форматы: .gif" in (
        capsys.readouterr().err)
    assert not list(tmp_path.iterdir())


def test_mp4_is_refused_in_both_languages_without_ffmpeg(monkeypatch: pytest.MonkeyPatch) -> None:
    from matplotlib.animation import writers

    monkeypatch.setattr(writers, "is_available", lambda name: False)
    with pytest.raises(PictureFormatError) as caught:
        animation_format("cycle.mp4")
    assert caught.value.text("en") == (
        "cycle.mp4: an MP4 animation needs the program 'ffmpeg', which is not installed; "
        "install 'ffmpeg' or write one of: .gif")
    assert "нужна программа 'ffmpeg'" in caught.value.text("ru")
    assert animation_format("cycle.GIF") == "gif"


def test_animation_formats(tmp_path: Path) -> None:
    from matplotlib.animation import writers

    motion = analyse(load_model(ROOT / "input_tables" / "four_bar.yaml"), points=6)
    gif = tmp_path / "cycle.gif"
    save_animation(motion, gif, frames=3, dpi=25)
    assert gif.read_bytes().startswith(MAGIC["gif"])
    if writers.is_available("ffmpeg"):  # where ffmpeg is installed: an ISO media file
        mp4 = tmp_path / "cycle.mp4"
        save_animation(motion, mp4, frames=3, dpi=25)
        assert mp4.read_bytes()[4:8] == b"ftyp"


@pytest.mark.skipif(shutil.which("ffprobe") is None or shutil.which("ffmpeg") is None,
                    reason="ffmpeg is not installed here")
def test_an_mp4_holds_one_frame_per_position_and_the_mechanism_moves(tmp_path: Path) -> None:
    """ffmpeg's own tools read the file back: ffprobe counts the frames, and two decoded frames
    differ (the crank has turned between them)."""
    motion = analyse(load_model(ROOT / "input_tables" / "four_bar.yaml"), points=12)
    mp4 = tmp_path / "cycle.mp4"
    save_animation(motion, mp4, frames=6, dpi=25)
    probe = subprocess.run(
        ["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
         "stream=nb_read_frames,codec_type", "-of", "csv=p=0", str(mp4)],
        capture_output=True, text=True, check=True).stdout.strip()
    assert probe == "video,6"
    decoded = subprocess.run(
        ["ffmpeg", "-v", "error", "-i", str(mp4), "-f", "rawvideo", "-pix_fmt", "gray", "-"],
        capture_output=True, check=True).stdout
    frames = np.frombuffer(decoded, np.uint8).reshape(6, -1)
    assert np.abs(frames[0].astype(int) - frames[3].astype(int)).max() > 64


def test_the_title_says_from_where_phi_is_counted() -> None:
    motion = analyse(load_model(ROOT / "input_tables" / "four_bar.yaml"), points=36)
    _, ax = figure_for(motion)
    draw_mechanism(motion, 3, ax)  # φ = 30° from the sketch
    sketch = math.degrees(math.atan2(35, 20))  # the sketch's crank A(0,0) → B(20,35)
    title = ax.get_title().replace("\n", " ")
    assert (f"crank angle φ = 30.0° from the sketched position (crank at {sketch + 30:.1f}° "
            "from the x axis)") in title


def test_coinciding_joints_share_a_label_and_coinciding_paths_a_note(tmp_path: Path) -> None:
    data = yaml.safe_load((ROOT / "input_tables" / "four_bar.yaml").read_text("utf-8"))
    data["geometry"]["tracing"] = {"K": {"link": 2, "point": [110, 80]},  # K placed on C
                                   "L": {"link": 2, "point": [110.4, 80.3]}}  # 0.5 mm off
    table = tmp_path / "traced.yaml"
    table.write_text(yaml.safe_dump(data), encoding="utf-8")
    motion = analyse(load_model(table), points=24)
    _, ax = figure_for(motion)
    draw_mechanism(motion, 5, ax, lang="ru")
    texts = [t.get_text() for t in ax.texts]
    assert "C=K=L" in texts  # within a hinge's radius (0.012 of the 110 mm span): one label
    assert not {"C", "K", "L"} & set(texts)
    note = [t for t in texts if t.startswith("совпадающие траектории")]
    assert note and "K = C" in note[0]
    # the path is drawn once: one line through every position of C
    c = np.asarray(motion.joints["C"])
    drawn = [line for line in ax.lines if isinstance(line, Line2D)
             and len(line.get_xdata()) == c.size
             and np.allclose(line.get_xdata(), c.real) and np.allclose(line.get_ydata(), c.imag)]
    assert len(drawn) == 1


def test_coinciding_is_told_apart_from_close() -> None:
    x = np.linspace(0, 1, 5)
    curves = {"a": x, "b": x + 1e-12, "c": x + 1e-3, "d": np.where(x > 0.5, np.nan, x)}
    assert coinciding(curves, 1e-9) == {"b": "a"}
