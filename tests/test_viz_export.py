"""Headless export (``viz ... --export``) and the ``viz`` command's handling of bad input."""

from __future__ import annotations

import io
import os
import subprocess
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy  # noqa: E402
import pytest  # noqa: E402
from helpers import OUTCOME, ROOT, SMALL_A, WRONG_OUTCOME  # noqa: E402
from PIL import Image, ImageChops  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.visualizer.export.images import animation_times  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402

pytestmark = pytest.mark.gui

# outcome.txt: an 11x6 floor; animations 48 px per cell and a quarter cell margin on each side
WIDTH, HEIGHT = 552, 312
CAPTION = 24
# pictures: 128 px per cell (for slides: the 11x6 floor at least 1200 px wide), a caption band
PICTURE_CELL = 128
PICTURE = (1472, 832 + 48)


def viz(*args: str) -> int:
    return main(["viz", *map(str, args)])


def test_png_of_a_state(qapp, tmp_path, capsys):
    out = tmp_path / "state.png"
    assert viz(OUTCOME, "--export", out, "--step", 8) == 0
    assert capsys.readouterr().err == f"wrote {out}: {PICTURE[0]}x{PICTURE[1]}\n"
    image = Image.open(out).convert("RGB")
    assert image.size == PICTURE
    # robot 1 stands on (5,3) at step 8: its colour a little left of the cell's centre
    x, y = int((5 - 0.5 + 0.25) * PICTURE_CELL) - 24, int((3 - 0.5 + 0.25) * PICTURE_CELL)
    colour = style.robot_colour(0)
    assert image.getpixel((x, y)) == pytest.approx((colour.red(), colour.green(), colour.blue()), abs=3)
    assert image.getpixel((2, 2)) == (style.BACKGROUND.red(), style.BACKGROUND.green(), style.BACKGROUND.blue())


def test_png_cell_size_and_instance_without_plan(qapp, tmp_path):
    out = tmp_path / "new" / "floor.png"  # folders are made as needed
    assert viz(SMALL_A, "--export", out, "--cell", 20) == 0
    assert Image.open(out).size == (230, 130)


def test_png_has_a_step_caption_unless_told_not_to(qapp, tmp_path):
    background = (style.BACKGROUND.red(), style.BACKGROUND.green(), style.BACKGROUND.blue())
    assert viz(OUTCOME, "--export", tmp_path / "with.png", "--step", 12) == 0
    assert viz(OUTCOME, "--export", tmp_path / "without.png", "--step", 12, "--no-caption") == 0
    captioned = Image.open(tmp_path / "with.png").convert("RGB")
    bare = Image.open(tmp_path / "without.png").convert("RGB")
    assert captioned.size == PICTURE and bare.size == (1472, 832)
    band = captioned.crop((0, 832, 1472, PICTURE[1]))  # "state after step 12 of 29" under the floor
    assert (numpy.asarray(band) != background).any(axis=2).sum() > 200
    assert ImageChops.difference(captioned.crop((0, 0, 1472, 832)), bare).getbbox() is None  # the same floor
    assert (numpy.asarray(bare.crop((0, 832 - 24, 1472, 832))) == background).all()  # below it: nothing


def test_the_caption_says_which_state(qapp):
    from asprilo.visualizer.export.images import picture_caption
    assert picture_caption(12, 29) == "state after step 12 of 29"
    assert picture_caption(0, 29) == "initial state (step 0 of 29)"


def test_default_cell_fits_slides_and_big_floors_stay_bounded(qapp, tmp_path, capsys):
    from asprilo.reader import read_instance
    assert viz(SMALL_A, "--export", tmp_path / "floor.png") == 0
    width, height = Image.open(tmp_path / "floor.png").size
    assert width >= 1200 and (width, height) == (1472, 832)  # 11x6, no plan: no caption
    big = tmp_path / "big.lp"
    nodes = " ".join(f"init(object(node,{y * 300 + x + 1}),value(at,({x + 1},{y + 1})))."
                     for y in range(4) for x in range(300))
    big.write_text(nodes + " init(object(robot,1),value(at,(1,1))).\n")
    assert read_instance(big).size == (300, 4)
    assert viz(big, "--export", tmp_path / "big.png") == 0
    assert max(Image.open(tmp_path / "big.png").size) <= 2000


def test_svg_is_vector_drawing(qapp, tmp_path):
    out = tmp_path / "state.svg"
    assert viz(OUTCOME, "--export", out, "--step", 29, "--cell", 48) == 0
    text = out.read_text()
    assert text.startswith("<?xml") and "<svg" in text and f'viewBox="0 0 {WIDTH} {HEIGHT + CAPTION}"' in text
    assert "state after step 29 of 29" in text  # the caption, as text
    assert "<image" not in text  # drawn with paths, not pasted pixels


@pytest.mark.parametrize("frames, count", [(1, 30), (3, 88)])
def test_gif_has_a_frame_per_state_and_in_between_frames(qapp, tmp_path, frames, count):
    out = tmp_path / "plan.gif"
    assert viz(OUTCOME, "--export", out, "--frames", frames, "--speed", 5) == 0
    image = Image.open(out)
    assert image.n_frames == count
    assert image.size == (WIDTH, HEIGHT + CAPTION)
    assert image.info["duration"] == round(1000 / (5 * frames) / 10) * 10
    assert image.info["loop"] == 0


def test_animation_times():
    assert animation_times(2, 1) == [0.0, 1.0, 2.0]
    assert animation_times(2, 4) == [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0]
    assert animation_times(0, 4) == [0.0]


def test_mp4(qapp, tmp_path):
    av = pytest.importorskip("av")
    out = tmp_path / "plan.mp4"
    assert viz(OUTCOME, "--export", out, "--frames", 2) == 0
    with av.open(str(out)) as container:
        stream = container.streams.video[0]
        frames = sum(1 for _ in container.decode(stream))
        assert (stream.width, stream.height) == (WIDTH, HEIGHT + CAPTION)
    assert frames == 59


def test_mp4_without_pyav_says_what_to_install(qapp, tmp_path, monkeypatch, capsys):
    from asprilo.visualizer.export import images as export
    real = export.importlib.util.find_spec
    monkeypatch.setattr(export.importlib.util, "find_spec", lambda name: None if name == "av" else real(name))
    assert viz(OUTCOME, "--export", tmp_path / "plan.mp4") == 2
    assert capsys.readouterr().err == (f"error: {tmp_path / 'plan.mp4'}: MP4 export needs PyAV "
                                       "(pip install av); .gif works without it\n")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("args, message", [
    (["missing.lp", "--export", "{tmp}/x.png"], "error: missing.lp: no such file\n"),
    ([OUTCOME, "--export", "{tmp}/x.bmp"],
     "error: {tmp}/x.bmp: cannot export '.bmp': use .png, .jpg, .svg, .gif or .mp4\n"),
    ([OUTCOME, "--export", "{tmp}/x.png", "--step", "30"],
     "error: --step 30 lies beyond the plan, whose last step is 29\n"),
    ([OUTCOME, "--export", "{tmp}/x.gif", "--frames", "0"], "error: --frames must be at least 1, got 0\n"),
    ([SMALL_A, "{tmp}/bad.lp", "--export", "{tmp}/x.png"],
     "error: {tmp}/bad.lp:1: a '.' is missing at the end of this line? (syntax error, unexpected EOF)\n"),
    ([SMALL_A, "{tmp}/other.lp", "--export", "{tmp}/x.png"],
     "error: {tmp}/other.lp:1: the plan moves robot 9, but the instance has robots 1..3 "
     "(plan and instance do not fit)\n"),
])
def test_bad_input_is_one_clear_message_and_exit_2(qapp, tmp_path, capsys, args, message):
    (tmp_path / "bad.lp").write_text("occurs(object(robot,1),action(move,(1,0)),1)\n")
    (tmp_path / "other.lp").write_text("occurs(object(robot,9),action(move,(1,0)),1).\n")
    assert viz(*[str(a).format(tmp=tmp_path) for a in args]) == 2
    assert capsys.readouterr().err == message.format(tmp=tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.lp", "other.lp"]  # nothing written


def test_headless_command_reads_piped_input_without_a_screen(tmp_path):
    """The console command on its own: no display, clingo-style output piped in."""
    out = tmp_path / "piped.png"
    text = OUTCOME.read_text().replace("\n", " ")
    piped = f"clingo version 5.8.0\nReading from stdin\nSolving...\nAnswer: 1\n{text}\nSATISFIABLE\n"
    env = {key: value for key, value in os.environ.items() if key not in ("QT_QPA_PLATFORM", "DISPLAY")}
    result = subprocess.run([sys.executable, "-m", "asprilo.cli", "viz", "--export", str(out), "--step", "29",
                             "--cell", "48"],
                            input=piped, capture_output=True, text=True, env=env, cwd=ROOT, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stderr.endswith(f"wrote {out}: {WIDTH}x{HEIGHT + CAPTION}\n")
    assert Image.open(out).size == (WIDTH, HEIGHT + CAPTION)


def test_plan_from_standard_input(qapp, tmp_path, monkeypatch, capsys):
    plan = "".join(line + " " for line in OUTCOME.read_text().splitlines() if line.startswith("occurs"))
    monkeypatch.setattr(sys, "stdin", io.StringIO(f"Answer: 1\n{plan}\nSATISFIABLE\n"))
    out = tmp_path / "end.png"
    assert viz(SMALL_A, "-", "--export", out, "--step", 29, "--cell", 48, "--no-caption") == 0
    assert capsys.readouterr().err == f"wrote {out}: {WIDTH}x{HEIGHT}\n"


def test_window_mode_checks_its_options_before_showing(qapp, monkeypatch, capsys, tmp_path):
    from PyQt5.QtCore import QSettings, QStandardPaths
    from PyQt5.QtWidgets import QApplication
    default = QStandardPaths.writableLocation(QStandardPaths.GenericConfigLocation)
    QSettings.setPath(QSettings.NativeFormat, QSettings.UserScope, str(tmp_path))  # not the user's
    shown = []
    monkeypatch.setattr(QApplication, "exec_", lambda self: shown.append(True) or 0)
    assert viz(OUTCOME, "--step", 40) == 2
    assert capsys.readouterr().err == "error: --step 40 lies beyond the plan, whose last step is 29\n"
    try:
        assert viz(OUTCOME, "--step", 5) == 0 and shown == [True]
    finally:
        QSettings.setPath(QSettings.NativeFormat, QSettings.UserScope, default)
    assert "outcome.txt" in (tmp_path / "asprilo" / "viz.conf").read_text()  # remembered there


def test_wrong_outcome_exports_despite_violations(qapp, tmp_path, capsys):
    out = tmp_path / "wrong.png"
    assert viz(WRONG_OUTCOME, "--export", out, "--step", 23, "--cell", 48) == 1  # as check: an invalid plan
    assert capsys.readouterr().err.splitlines()[-1] == (
        "invalid plan: 3 violations (domain A (detected), horizon 29); check INSTANCE PLAN lists them")
    image = Image.open(out).convert("RGB")
    # robot 1 is flagged at step 23: a red ring around it on (8,1)
    x, y = int((8 - 0.5 + 0.25) * 48), int((1 - 0.5 + 0.25) * 48)
    ring = [image.getpixel((x + dx, y)) for dx in range(-22, -14)]
    red = (style.VIOLATION.red(), style.VIOLATION.green(), style.VIOLATION.blue())
    assert any(pixel == pytest.approx(red, abs=12) for pixel in ring)
