"""A lesson you can present: the presentation mode (F11), the checker rule behind a
violation in the violations panel, and strips of states (``--strip``, File > Export strip)."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, WRONG_OUTCOME  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PIL import Image  # noqa: E402
from PyQt5.QtCore import Qt  # noqa: E402
from PyQt5.QtWidgets import QDockWidget, QToolBar  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.visualizer.export import strip  # noqa: E402
from asprilo.visualizer.panels.checker_rule import HINT  # noqa: E402
from asprilo.visualizer.panels.commands import shortcut_rows  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402

pytestmark = pytest.mark.gui

WAIT = 60_000  # ms: a hang guard, not a speed requirement
BACKGROUND = (style.BACKGROUND.red(), style.BACKGROUND.green(), style.BACKGROUND.blue())
WHITE = (255, 255, 255)


@pytest.fixture
def window(qtbot, tmp_path_factory):
    return shown_window(qtbot, tmp_path_factory, (1366, 768))


def shown_parts(window) -> set[str]:
    return {part.objectName() for part in (*window.findChildren(QDockWidget), *window.findChildren(QToolBar))
            if part.isVisible()}


# --- the presentation mode ------------------------------------------------------------------------

def test_presentation_mode_narrates_the_step_and_leaves_the_window_as_it_was(window, qtbot):
    window.open_files([str(WRONG_OUTCOME)])
    window.go_to(23)
    before, size = shown_parts(window), window.size()
    assert before and not window.narration.isVisible()
    qtbot.keyClick(window, Qt.Key_F11)
    assert window.presentation.active and window.commands["present"].isChecked()
    assert shown_parts(window) == set()  # every dock and tool bar hidden
    assert not window.menuBar().isVisible() and not window.statusBar().isVisible()
    assert window.isFullScreen()
    bar = window.narration
    assert bar.isVisible()
    assert bar.sentence.text() == (
        "Step 23: robot 1 delivers 6 units of product 5 at station 2 for order 2, but the order needs only 5 more "
        "and shelf 2 holds only 5; robot 2 moves left to (4,1) with shelf 3; and robot 3 moves up to (7,1) with "
        "shelf 9.")
    assert bar.verdict.text() == "invalid plan: 3 rule violations (first at step 23)"
    assert bar.rules.isVisible() and bar.rules.text().split("\n") == [
        "checker/deliver_a.lp:6 (first of 2 rules): err(deliver,orderAmount,(R,T)) :- does(R,deliver,(O,P,_),T), "
        "order(O), not line(O,P,_).",
        "checker/deliver_a.lp:10: err(deliver,shelfAmount,(R,T)) :- does(R,deliver,(_,P,N),T), carries(R,S,T-1), "
        "onShelf(P,S,Units), #sum{ M,Other,U : gives(Other,S,_,P,M,U), U < T } > Units - N."]
    assert bar.sentence.font().pixelSize() >= 24  # letters for the back row
    # the map fills the window's width, the bar below it (offscreen the "screen" is 800x600)
    qtbot.waitUntil(lambda: window.view.width() == window.width() == window.narration.width(), timeout=WAIT)
    scene = window.view.scene().sceneRect()
    fitting = min(window.view.viewport().width() / scene.width(), window.view.viewport().height() / scene.height())
    assert window.view.pixels_per_cell == pytest.approx(fitting * style.CELL, rel=0.05)

    qtbot.keyClick(window, Qt.Key_Right)  # the keys still step
    qtbot.waitUntil(lambda: not window.player.moving and window.player.step == 24, timeout=WAIT)
    assert bar.sentence.text().startswith("Step 24: robot 2 delivers 1 unit of product 4 at station 1 for order 1")
    assert not bar.rules.isVisible()  # no rule broken at step 24

    qtbot.keyClick(window, Qt.Key_Escape)  # Esc leaves, as F11 does
    assert not window.presentation.active and not window.commands["present"].isChecked()
    assert shown_parts(window) == before and not window.narration.isVisible()
    assert window.menuBar().isVisible() and window.statusBar().isVisible() and not window.isFullScreen()
    assert window.size() == size
    qtbot.keyClick(window, Qt.Key_F5, Qt.ShiftModifier)  # slide software's key
    assert window.presentation.active
    qtbot.keyClick(window, Qt.Key_F11)
    assert not window.presentation.active and shown_parts(window) == before


def test_presentation_mode_key_is_listed_and_free(window):
    rows = dict(shortcut_rows(window))
    assert rows["Presentation mode (Esc leaves it)"] == "F11, Shift+F5"
    keys = [key.strip() for text, keys in shortcut_rows(window) for key in keys.split(",")]
    assert keys.count("F11") == 1 and keys.count("Shift+F5") == 1


def test_presentation_mode_of_a_valid_plan_and_of_the_empty_window(window, qtbot):
    window.presentation.enter()
    assert window.narration.sentence.text() == "No instance open: Ctrl+O opens one."
    window.open_files([str(OUTCOME)])  # the bar follows a new scenario
    assert window.narration.sentence.text() == "Step 0: the initial state."
    assert window.narration.verdict.text() == "valid plan \u2713" and not window.narration.rules.isVisible()
    window.go_to(8)
    assert window.narration.sentence.text().startswith("Step 8: robot 3 delivers 1 unit of product 4 at station 1 "
                                                       "for order 1")
    window.close()  # leaves the mode first: the layout saved is the one with the panels
    assert not window.presentation.active


# --- the checker rule behind a violation -------------------------------------------------------------

def test_clicking_a_violation_shows_its_checker_rule(window):
    window.open_files([str(WRONG_OUTCOME)])
    note, panel = window.rule_note, window.panels["violations"]
    assert note.text() == HINT
    panel.table.clicked.emit(panel.proxy.index(1, 0))  # deliver/shelfAmount at step 23
    assert window.player.step == 23
    assert note.text() == (
        "<b>err(deliver,shelfAmount,(1,23))</b> is found by <b>checker/deliver_a.lp:10</b>:<br><code>"
        "err(deliver,shelfAmount,(R,T)) :- does(R,deliver,(_,P,N),T), carries(R,S,T-1), onShelf(P,S,Units), "
        "#sum{ M,Other,U : gives(Other,S,_,P,M,U), U &lt; T } &gt; Units - N.</code>")
    panel.table.clicked.emit(panel.proxy.index(0, 0))  # deliver/orderAmount: two rules derive it
    assert note.text().startswith("<b>err(deliver,orderAmount,(1,23))</b> is found by one of 2 rules:"
                                  "<br><b>checker/deliver_a.lp:6</b>: <code>err(deliver,orderAmount,(R,T)) :- ")
    assert "<br><b>checker/deliver_a.lp:7</b>: <code>err(deliver,orderAmount,(R,T)) :- " in note.text()
    panel.table.clicked.emit(panel.proxy.index(2, 0))
    assert "<b>checker/goal.lp:4</b>" in note.text()
    window.open_files([str(OUTCOME)])
    assert note.text() == HINT


# --- strips of states ---------------------------------------------------------------------------------

def viz(*args) -> int:
    return main(["viz", *map(str, args)])


def strip_size(cell: int, floor: tuple[int, int], panels: int, columns: int) -> tuple[int, int]:
    """By hand: a panel is the floor and a quarter-cell margin on each side at ``cell`` pixels per
    cell, over a caption band of max(18, cell // 2) pixels; panels are max(4, cell // 4) apart."""
    width, height = round((floor[0] + 0.5) * cell), round((floor[1] + 0.5) * cell) + max(18, cell // 2)
    gap, rows = max(4, cell // 4), -(-panels // columns)
    return columns * width + (columns - 1) * gap, rows * height + (rows - 1) * gap


def test_strip_of_six_states_in_two_rows(qapp, tmp_path, capsys):
    out = tmp_path / "strip.png"
    assert viz(OUTCOME, "--export", out, "--strip", "3-8") == 0
    # 11x6 floor at 48 px: panels of 552x(312+24); three fit in 2000 pixels: 3 x 2 panels
    assert strip_size(48, (11, 6), 6, 3) == (1680, 684)
    assert capsys.readouterr().err == f"wrote {out}: 1680x684, the states after steps 3 to 8\n"
    image = Image.open(out).convert("RGB")
    assert image.size == (1680, 684)
    for index in range(6):
        x, y = (index % 3) * (552 + 12), (index // 3) * (336 + 12)
        assert image.getpixel((x + 2, y + 2)) == BACKGROUND  # the panel's margin
        band = [image.getpixel((x + px, y + 312 + py)) for px in range(4, 300) for py in range(2, 22)]
        assert BACKGROUND in band and any(pixel != BACKGROUND for pixel in band)  # a caption is written there
        if index % 3 < 2:
            assert image.getpixel((x + 552 + 6, y + 100)) == WHITE  # the gap between two panels
    assert image.getpixel((100, 336 + 6)) == WHITE  # the gap between two rows


def test_strip_cell_and_columns(qapp, tmp_path):
    out = tmp_path / "strip.jpg"
    assert viz(OUTCOME, "--export", out, "--strip", "0-4", "--cell", 20, "--columns", 2) == 0
    assert strip_size(20, (11, 6), 5, 2) == (465, 454)  # 230x(130+18) panels, 5 apart, 3 rows
    assert Image.open(out).size == (465, 454)
    one = tmp_path / "one.png"
    assert viz(OUTCOME, "--export", one, "--strip", "29-29", "--cell", 10) == 0
    assert Image.open(one).size == strip_size(10, (11, 6), 1, 1) == (115, 83)


def test_strip_captions_say_which_state(qapp, monkeypatch):
    from asprilo.reader import read_instance, read_plan
    from asprilo.visualizer.scene.animator import Animator
    from asprilo.visualizer.scene.warehouse import WarehouseScene
    from asprilo.visualizer.state.track import Track
    drawn = []
    original = strip.images.render

    def spy(scene, cell_px, caption=None):
        drawn.append(caption)
        return original(scene, cell_px, caption)

    track = Track(read_instance(OUTCOME), read_plan(OUTCOME))
    animator = Animator(WarehouseScene(track.instance), track)
    animator.show(5.5)
    monkeypatch.setattr(strip.images, "render", spy)
    image = strip.render_strip(animator, [0, 1, 29], 8)
    assert drawn == ["initial state (step 0 of 29)", "state after step 1 of 29", "state after step 29 of 29"]
    assert animator.time == 5.5  # left as it was
    assert (image.width(), image.height()) == strip_size(8, (11, 6), 3, 3)


def test_a_long_strip_wraps_and_stays_within_the_pixel_budget(qapp, tmp_path, monkeypatch, capsys):
    out = tmp_path / "all.png"
    assert viz(OUTCOME, "--export", out, "--strip", "0-29") == 0  # 30 panels: 10 rows of 3
    assert Image.open(out).size == strip_size(48, (11, 6), 30, 3) == (1680, 3468)
    monkeypatch.setattr(strip, "STRIP_PIXELS", 1_000_000)
    capsys.readouterr()
    assert viz(OUTCOME, "--export", out, "--strip", "0-29") == 0  # smaller cells until it fits
    width, height = Image.open(out).size
    assert width * height <= 1_000_000
    assert viz(OUTCOME, "--export", out, "--strip", "0-29", "--cell", 48) == 2  # a cell size given: refused
    assert "more than 1,000,000 in all" in capsys.readouterr().err


@pytest.mark.parametrize("args, message", [
    (("--strip", "5-3"), "--strip 5-3: the first step comes after the last"),
    (("--strip", "3-30"), "--strip 3-30 lies beyond the plan, whose last step is 29"),
    (("--strip", "1-2", "--step", "4"), "--strip FIRST-LAST names its steps; leave out --step"),
    (("--columns", "2"), "--columns goes with --strip"),
    (("--strip", "1-2", "--columns", "0"), "--columns must be at least 1, got 0"),
])
def test_strip_refusals(qapp, tmp_path, capsys, args, message):
    assert viz(OUTCOME, "--export", tmp_path / "s.png", *args) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "s.png").exists()


def test_strip_needs_a_picture_file(qapp, tmp_path, capsys):
    assert viz(OUTCOME, "--export", tmp_path / "s.gif", "--strip", "1-2") == 2
    assert "a strip is a picture: use .png or .jpg, not '.gif'" in capsys.readouterr().err
    assert viz(OUTCOME, "--strip", "1-2") == 2
    assert "--strip goes with --export" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        viz(OUTCOME, "--export", tmp_path / "s.png", "--strip", "3")
    assert "'3' is not FIRST-LAST" in capsys.readouterr().err


def test_export_strip_from_the_window(window, tmp_path):
    window.open_files([str(OUTCOME)])
    window.go_to(12)
    out = tmp_path / "strip.png"
    assert window.strips.save(str(out), 10, 13, columns=2)
    assert Image.open(out).size == strip_size(48, (11, 6), 4, 2)
    assert window.statusBar().currentMessage() == f"saved {out}: steps 10–13, 1116x684"
    assert window.player.time == 12 and window.stage.animator.time == 12  # the window shows what it showed
    assert not window.strips.save(str(tmp_path / "strip.svg"), 10, 13)
    assert "a strip is a picture" in window.last_error
    assert window.commands["export_strip"] in window.menus["file"].actions()
