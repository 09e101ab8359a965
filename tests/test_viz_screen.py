"""The viewer on a 1366x768 screen and a projector (issue 33, item 3): windows and dialogs that
fit with their frame, violation sentences readable in full, data shown as it is (never taken
for HTML), labels that never cover goal tags, every key press a step, Save when quitting, a
verdict the status bar never cuts short.

Offscreen, Qt 5.15's screen is 800x600 whatever QT_QPA_PLATFORM says; the viewer sizes its
windows from ``QScreen.availableGeometry``, which these tests set to a laptop's 1366x768.
"""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, WRONG_OUTCOME  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5 import sip  # noqa: E402
from PyQt5.QtCore import QPoint, QRect, Qt  # noqa: E402
from PyQt5.QtGui import QScreen, QTextDocument  # noqa: E402
from PyQt5.QtWidgets import (  # noqa: E402
    QApplication,
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QMessageBox,
    QScrollArea,
    QToolTip,
)

from asprilo.reader import read_plan  # noqa: E402
from asprilo.simulate import Violation  # noqa: E402
from asprilo.visualizer.panels.dialogs import ConnectDialog, GenerateDialog, SizeDialog, StockDialog  # noqa: E402
from asprilo.visualizer.panels.screen import FRAME  # noqa: E402
from asprilo.visualizer.panels.tables import TablePanel, plain_tip  # noqa: E402
from asprilo.visualizer.panels.violation_list import ViolationsModel, sentence  # noqa: E402

pytestmark = pytest.mark.gui

LAPTOP = QRect(0, 0, 1366, 768)
TITLE_BAR = 20  # what the window manager adds above a window (the teacher's X11 desktop)


@pytest.fixture
def laptop(monkeypatch):
    """The available screen the viewer sees: 1366x768 (a test may set another)."""
    screen = {"area": LAPTOP}
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: screen["area"])
    return screen


@pytest.fixture
def window(qtbot, tmp_path_factory, laptop, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)  # the first window: the size the viewer chooses
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)  # closing at the end
    return window


def fits(size, area: QRect = LAPTOP) -> bool:
    """Whether a window of ``size`` with its frame (a 20 px title bar) fits ``area``."""
    return size.width() <= area.width() and size.height() + TITLE_BAR <= area.height()


def plain(html: str) -> str:
    document = QTextDocument()
    document.setHtml(html)
    return document.toPlainText()


def settle(qtbot) -> None:
    qtbot.wait(10)
    QApplication.processEvents()


# --- windows and dialogs fit the screen -------------------------------------------------------------


def test_the_first_window_fits_with_its_frame_and_shows_the_verdict(window, qtbot):
    assert FRAME.top() >= TITLE_BAR
    assert fits(window.size()) and window.width() == 1366  # as wide as the screen, no taller than its room
    assert fits(window.minimumSizeHint())
    assert window.open_files([str(WRONG_OUTCOME)])
    window.go_to(23)
    settle(qtbot)
    assert fits(window.size())
    bar = window.statusBar()
    assert bar.isVisible() and bar.geometry().bottom() < window.height()  # the status bar inside the window
    verdict = window.status_line.verdict
    assert "3 rule violations, 2 at step 23" in verdict.text() and verdict.isVisible()
    assert verdict.width() >= verdict.sizeHint().width()


def test_a_smaller_screen_gets_a_smaller_first_window(qtbot, tmp_path_factory, laptop):
    laptop["area"] = QRect(0, 0, 1024, 600)
    window = shown_window(qtbot, tmp_path_factory)
    assert fits(window.size(), laptop["area"])


def shortcuts(window, qtbot) -> QDialog:
    qtbot.keyClick(window, Qt.Key_F1)
    dialogs = [d for d in window.findChildren(QDialog) if d.windowTitle() == "Keyboard shortcuts" and d.isVisible()]
    assert len(dialogs) == 1
    settle(qtbot)
    return dialogs[0]


@pytest.mark.parametrize("area", [LAPTOP, QRect(0, 0, 1024, 480)])
def test_the_shortcuts_dialog_fits_and_ok_is_in_view(window, qtbot, laptop, area):
    laptop["area"] = area
    dialog = shortcuts(window, qtbot)
    assert fits(dialog.size(), area)
    ok = dialog.findChild(QDialogButtonBox).button(QDialogButtonBox.Ok)
    corner = ok.mapTo(dialog, QPoint(ok.width(), ok.height()))
    assert ok.isVisible() and dialog.rect().contains(corner)
    area_widget = dialog.findChild(QScrollArea)
    text = area_widget.widget().text()
    for command, keys in (("Step forward", "Right"), ("Play / pause", "Space"), ("Quit", "Ctrl+Q")):
        assert f"<td>{command}</td><td><b>{keys}</b></td>" in text  # every row is there ...
    if area.height() < 600:
        assert area_widget.verticalScrollBar().maximum() > 0  # ... and reached by scrolling
    ok.click()
    assert not dialog.isVisible()


def test_every_dialog_fits_a_laptop(qtbot, window):
    stock = StockDialog(3, {product: 5 for product in range(1, 300)}, window)  # a shelf of 299 products
    for dialog in (SizeDialog("Resize grid", 11, 6, "New cells become storage nodes. " * 5, window),
                   GenerateDialog({"robots": 3}, 1, window), ConnectDialog("127.0.0.1", 5000, 5001, window), stock):
        qtbot.addWidget(dialog)
        dialog.show()
        settle(qtbot)
        assert fits(dialog.size()), type(dialog).__name__
    window.state.report_error("x" * 50_000)  # the error dialog: a long message is shortened
    settle(qtbot)
    boxes = [box for box in window.findChildren(QMessageBox) if box.isVisible()]
    assert boxes and all(fits(box.size()) for box in boxes)


# --- violation sentences readable in full -------------------------------------------------------------


def test_a_long_violation_sentence_is_readable_in_full(qtbot, window):
    long = ("robot 1 delivers 6 units of product 4 for order 1 at picking station 2, but the order asks for "
            "only 1 more unit of product 4 there and shelf 3, which robot 1 carries, holds only 2 units of it")
    violation = Violation("deliver", "orderAmount", (1, 23), 23, f"step 23: {long}", (1,))
    assert sentence(violation) == long  # the step is in its own column: said once
    model = ViolationsModel()
    model.set_rows([violation])
    panel = TablePanel(model)
    qtbot.addWidget(panel)
    panel.resize(470, 300)
    panel.show()
    qtbot.waitExposed(panel)
    assert panel.texts() == [["23", "deliver/orderAmount", long]]
    tip = panel.proxy.index(0, 2).data(Qt.ToolTipRole)
    assert plain(tip) == long  # the whole sentence ...
    assert plain(panel.proxy.index(0, 1).data(Qt.ToolTipRole)) == "err(deliver,orderAmount,(1,23))"
    QToolTip.showText(panel.mapToGlobal(QPoint(10, 10)), tip, panel)
    qtbot.waitUntil(QToolTip.isVisible, timeout=10_000)  # a hang guard (the first tip may fade in)
    assert plain(QToolTip.text()) == long
    # the tip's label is a window of its own: the top-level widgets hold it (not every widget
    # of the session, some of which earlier tests' windows are taking down)
    label = next(w for w in QApplication.topLevelWidgets()
                 if not sip.isdeleted(w) and w.objectName() == "qtooltip_label" and w.isVisible())
    assert label.width() < 800  # ... wrapped into lines that fit the screen
    QToolTip.hideText()


def test_the_goal_at_the_horizon_says_so_without_repeating_the_step(window):
    window.open_files([str(WRONG_OUTCOME)])
    rows = window.panels["violations"].texts()
    assert [row[0] for row in rows] == ["23", "23", "29"]
    assert not any(row[2].startswith("step ") for row in rows)
    assert rows[2][2].startswith("at the horizon: order 1 still lacks")


# --- data shown as it is -----------------------------------------------------------------------------------


def test_the_atoms_pane_shows_the_readers_words_literally(window, qtbot):
    assert window.open_files([str(OUTCOME)])
    window.docks["atoms"].show()
    window.docks["atoms"].raise_()
    atoms = window.docks["atoms"].widget()
    qtbot.waitUntil(lambda: atoms.shown, timeout=10_000)  # a hang guard
    atoms.plan_box.setPlainText("occurs(object(robot,1),action(move,(1,0)),1) foo.")
    atoms.read_now()
    shown = plain(atoms.plan_note.text())
    assert "<plan atoms>:1: syntax error, unexpected <IDENTIFIER> (the plan shown stays)" in shown


def test_error_dialogs_and_tooltips_take_data_as_plain_text(window, qtbot):
    window.state.report_error("<plan atoms>:3: syntax error, unexpected <b>")
    settle(qtbot)
    box = next(box for box in window.findChildren(QMessageBox) if box.isVisible())
    assert box.textFormat() == Qt.PlainText and box.text().startswith("<plan atoms>:3:")
    assert plain_tip("order 1 for <b>you</b>") != "order 1 for <b>you</b>"  # looks like HTML: escaped
    assert plain(plain_tip("order 1 for <b>you</b>")) == "order 1 for <b>you</b>"
    assert plain_tip("err(goal,unfilledOrder,(1,2,1,29))") == "err(goal,unfilledOrder,(1,2,1,29))"


# --- labels never cover tags ---------------------------------------------------------------------------------


def test_station_labels_never_cover_goal_tags(window):
    window.open_files([str(OUTCOME)])
    scene = window.stage.scene
    covered, tags = [], 0
    for step in range(window.track.horizon + 1):
        window.go_to(step)
        pills = [shelf.goal.pill.sceneBoundingRect() for shelf in scene.shelves.values()
                 if shelf.goal is not None and shelf.goal.isVisible() and shelf.goal.pill.isVisible()]
        tags += len(pills)
        for station in scene.stations.values():
            covered += [step for pill in pills if station.tag.sceneBoundingRect().intersects(pill)]
    assert tags and not covered
    window.go_to(7)  # robot 3 brought shelf 1 to PS1: `✓ PS1` beside the station's `PS1`
    assert any(shelf.goal is not None and shelf.goal.look.tag == "\u2713 PS1" for shelf in scene.shelves.values())


# --- every key press counts -------------------------------------------------------------------------------------


def test_fast_key_presses_each_advance_one_step(window, qtbot):
    window.open_files([str(OUTCOME)])
    player = window.player
    for _ in range(3):
        qtbot.keyClick(window, Qt.Key_Right)  # pressed during the glide the first press started
    assert player.moving
    qtbot.waitUntil(lambda: not player.moving, timeout=10_000)  # a hang guard
    assert player.time == 3.0 and window.transport.spin.value() == 3
    for _ in range(2):
        qtbot.keyClick(window, Qt.Key_Left)
    qtbot.waitUntil(lambda: not player.moving, timeout=10_000)
    assert player.time == 1.0


# --- Save when quitting --------------------------------------------------------------------------------------------


def test_quitting_with_an_unsaved_plan_offers_save_and_saves(window, qtbot, tmp_path, monkeypatch):
    window.open_files([str(OUTCOME)])
    plan = read_plan(OUTCOME)
    shorter = type(plan)([action for action in plan.actions if action.step <= 10])
    assert window.state.document.replace_plan(shorter, "edit the plan's atoms")
    asked, target = [], tmp_path / "plan.lp"
    monkeypatch.setattr(QFileDialog, "getSaveFileName", lambda *args, **kw: ("", ""))  # Save, then Cancel
    monkeypatch.setattr(QMessageBox, "question", lambda *args: asked.append(args[2:4]) or QMessageBox.Save)
    assert not window.close() and window.isVisible()  # the file dialog was cancelled: nothing lost
    text, buttons = asked[0]
    assert text == "The plan has unsaved edits. Save them?"
    assert buttons == QMessageBox.Save | QMessageBox.Discard | QMessageBox.Cancel
    monkeypatch.setattr(QFileDialog, "getSaveFileName", lambda *args, **kw: (str(target), ""))
    assert window.close() and not window.isVisible()
    assert read_plan(target) == shorter


# --- the verdict is never cut short ----------------------------------------------------------------------------


@pytest.mark.parametrize("width", [1366, 1024])
def test_the_verdict_is_never_elided_while_a_job_runs(window, qtbot, width):
    window.resize(width, window.height())
    window.open_files([str(WRONG_OUTCOME)])
    window.go_to(23)
    bar, verdict, summary = window.jobs.bar, window.status_line.verdict, window.status_line.summary
    bar.show()  # what a solve shows while it runs: what it does, a busy bar, Cancel
    bar.label.setText("Solve: reference encoding (plain), makespan at least 29 — horizon 31 tried: no plan; "
                      "grounding horizon 32…")
    settle(qtbot)
    assert verdict.text().endswith("3 rule violations, 2 at step 23</b></span>")
    assert verdict.width() >= verdict.sizeHint().width()
    assert window.statusBar().rect().contains(verdict.geometry())
    assert bar.label.shown().endswith("…") and bar.label.toolTip() == bar.label.text()  # the job's words give way
    if width == 1366:  # room for all three: the summary keeps its share before the job's words get theirs
        assert summary.width() >= min(summary.sizeHint().width(), 0.39 * window.statusBar().width())
