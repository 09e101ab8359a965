"""What the reader warns about a file the viewer reads (issue 33, item 1): a plan file with
``occur/3``, ``mvoe`` or ``occurs/2`` in it, opened from the command line, File > Open or
Open plan, reloaded or saved in an editor, is said in the atoms pane (``warning: FILE:LINE:
...``) and in the status bar, not on standard error only; another file read, or the plan
edited in the pane, ends them."""

from __future__ import annotations

import os
import warnings

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, SMALL_A  # noqa: E402

from asprilo.cli import main  # noqa: E402
from asprilo.errors import InputWarning  # noqa: E402
from asprilo.visualizer.state.loading import load_scenario, warnings_said  # noqa: E402

TITLE_BAR = 20  # what the window manager adds above a window

MISTAKES = ("% a plan with mistakes\n"
            "occur(object(robot,1),action(move,(1,0)),2).\n"
            "occurs(object(robot,1),action(mvoe,(1,0)),3).\n"
            "occurs(object(robot,2),action(move,(0,1),4)).\n")
FIXED = ("% a plan with mistakes, mended\n"
         "occurs(object(robot,1),action(move,(1,0)),2).\n"
         "occurs(object(robot,1),action(move,(1,0)),3).\n"
         "occurs(object(robot,2),action(move,(0,1)),4).\n")
#: milliseconds a save may take to be read (a bound against hanging, not a timing)
PATIENCE = 60_000


def said(path) -> list[str]:
    """The reader's three warnings on MISTAKES in ``path``, lines 2 to 4."""
    return [f"{path}:2: occur/3 is ignored: did you mean occurs/3?",
            f"{path}:3: there is no action 'mvoe': did you mean move? (the actions: deliver, move, pickup, putdown)",
            f"{path}:4: occurs/2 is ignored: occurs has 3 arguments, occurs(object(robot,R),action(Name,Args),T) "
            "(a parenthesis in the wrong place?)"]


@pytest.fixture
def mistakes(tmp_path):
    path = tmp_path / "mistakes.lp"
    path.write_text(MISTAKES)
    return path


# --- without Qt: the scenario keeps them, and they are given on as before ---------------------------------

def test_a_scenario_keeps_the_readers_warnings_and_gives_them_on(mistakes):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scenario = load_scenario([str(SMALL_A)], [str(mistakes)])
        again = load_scenario([str(SMALL_A)], [str(mistakes)])  # read again: said again
    assert scenario.read_warnings == again.read_warnings == said(mistakes)
    assert [(w.category, str(w.message)) for w in caught] == [(InputWarning, text) for text in said(mistakes) * 2]
    assert warnings_said(scenario) == "3 warnings reading mistakes.lp: see the Atoms pane"
    assert load_scenario([str(SMALL_A)], [str(OUTCOME)]).read_warnings == []
    assert warnings_said(load_scenario([str(SMALL_A)], [str(OUTCOME)])) is None


@pytest.mark.gui
def test_viz_still_prints_them_on_standard_error(qapp, mistakes, tmp_path, capsys):
    code = main(["viz", str(SMALL_A), str(mistakes), "--export", str(tmp_path / "state.png")])
    err = capsys.readouterr().err.splitlines()
    assert code == 1
    assert err[:3] == [f"warning: {text}" for text in said(mistakes)]


# --- the window ------------------------------------------------------------------------------------------

@pytest.fixture
def screen(monkeypatch):
    """The available screen the viewer sees (offscreen Qt's is 800x600): a laptop's 1366x768."""
    from PyQt5.QtCore import QRect
    from PyQt5.QtGui import QScreen
    area = {"area": QRect(0, 0, 1366, 768)}
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: area["area"])
    return area


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch, screen):
    from helpers.viewer import shown_window
    from PyQt5.QtWidgets import QMessageBox
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    return shown_window(qtbot, tmp_path_factory)  # the first window: 1366x748


def atoms_pane(window, qtbot):
    window.docks["atoms"].show()
    window.docks["atoms"].raise_()
    pane = window.docks["atoms"].widget()
    qtbot.waitUntil(lambda: pane.shown, timeout=10_000)  # a hang guard
    return pane


def note_lines(pane) -> list[str]:
    from PyQt5.QtGui import QTextDocument
    document = QTextDocument()
    document.setHtml(pane.plan_note.text())
    return document.toPlainText().splitlines()


def warned(path) -> list[str]:
    return [f"warning: {text}" for text in said(path)]


@pytest.mark.gui
def test_a_plan_file_opened_is_said_in_the_atoms_pane_and_the_status_bar(window, qtbot, mistakes, screen):
    from PyQt5.QtCore import QRect
    screen["area"] = QRect(0, 0, 1920, 1080)  # room to grow: offscreen Qt's letters are bigger than X11's
    assert window.open_files([str(SMALL_A)], [str(mistakes)])   # as File > Open, Recent files
    assert window.statusBar().currentMessage() == "3 warnings reading mistakes.lp: see the Atoms pane"
    pane = atoms_pane(window, qtbot)
    assert note_lines(pane) == ["1 action, horizon 3: 7 violations", *warned(mistakes)]
    note = pane.plan_note                                       # wrapped, all of it in view
    qtbot.waitUntil(lambda: note.height() >= note.label.heightForWidth(note.viewport().width()) > 0, timeout=10_000)
    assert note.height() > 4 * note.label.fontMetrics().lineSpacing() and note.verticalScrollBar().maximum() == 0


@pytest.mark.gui
def test_the_window_with_warnings_still_fits_a_small_screen(qtbot, tmp_path_factory, mistakes, screen):
    from helpers.viewer import shown_window
    from PyQt5.QtCore import QRect
    screen["area"] = QRect(0, 0, 1024, 600)
    window = shown_window(qtbot, tmp_path_factory)
    assert window.open_files([str(SMALL_A)], [str(mistakes)])
    pane = atoms_pane(window, qtbot)
    note = pane.plan_note                                       # as tall as the screen leaves room for, scrolled
    qtbot.waitUntil(lambda: note.height() > 0 and note.verticalScrollBar().maximum() > 0, timeout=10_000)
    assert len(note_lines(pane)) == 4
    assert window.minimumSizeHint().height() + TITLE_BAR <= 600 and window.height() + TITLE_BAR <= 600


@pytest.mark.gui
def test_files_of_the_command_line_are_said_once_the_window_shows(qtbot, tmp_path_factory, mistakes):
    from PyQt5.QtCore import QSettings

    from asprilo.visualizer.window import MainWindow
    window = MainWindow(QSettings(str(tmp_path_factory.mktemp("settings") / "viz.ini"), QSettings.IniFormat))
    qtbot.addWidget(window)
    window.show_scenario(load_scenario([str(SMALL_A)], [str(mistakes)]))  # as viz INSTANCE PLAN does
    window.show()
    qtbot.waitUntil(window.status_line.summary.isHidden, timeout=10_000)  # under the message, not drawn over it
    assert window.statusBar().currentMessage() == "3 warnings reading mistakes.lp: see the Atoms pane"


@pytest.mark.gui
def test_a_plan_opened_on_the_instance_shown_and_another_file_after_it(window, qtbot, mistakes):
    pane = atoms_pane(window, qtbot)
    assert window.open_files([str(SMALL_A)])
    assert note_lines(pane) == ["0 actions, horizon 0: no violation"]  # no plan
    assert window.files.open_plan_files([str(mistakes)])       # File > Open plan
    assert note_lines(pane)[1:] == warned(mistakes)
    assert window.statusBar().currentMessage() == "3 warnings reading mistakes.lp: see the Atoms pane"
    assert window.files.open_plan_files([str(OUTCOME)])        # another file: they are gone
    assert note_lines(pane) == ["79 actions, horizon 29: no violation"]
    assert window.statusBar().currentMessage() == ""


@pytest.mark.gui
def test_reload_says_them_again_and_no_more_once_the_file_is_mended(window, qtbot, mistakes):
    assert window.open_files([str(SMALL_A)], [str(mistakes)])
    pane = atoms_pane(window, qtbot)
    window.reload_on_save.action.setChecked(False)              # File > Reload only, here
    assert window.files.reload()                                # the same file: the same words
    assert note_lines(pane)[1:] == warned(mistakes)
    mistakes.write_text(FIXED)
    assert window.files.reload()
    assert note_lines(pane) == ["3 actions, horizon 4: 10 violations"]
    assert window.statusBar().currentMessage() == ""


@pytest.mark.gui
def test_a_plan_saved_with_mistakes_is_said_when_read_again_on_save(window, qtbot, mistakes):
    mistakes.write_text(FIXED)
    assert window.reload_on_save.action.isChecked()
    assert window.open_files([str(SMALL_A)], [str(mistakes)])
    pane = atoms_pane(window, qtbot)
    assert note_lines(pane) == ["3 actions, horizon 4: 10 violations"]
    mistakes.write_text(MISTAKES)                               # saved in an editor
    qtbot.waitUntil(lambda: len(note_lines(pane)) == 4, timeout=PATIENCE)
    assert note_lines(pane)[1:] == warned(mistakes)
    assert window.statusBar().currentMessage() == ("mistakes.lp saved: read again; "
                                                   "3 warnings reading mistakes.lp: see the Atoms pane")
    mistakes.write_text(FIXED)
    qtbot.waitUntil(lambda: len(note_lines(pane)) == 1, timeout=PATIENCE)


@pytest.mark.gui
def test_the_plan_edited_in_the_pane_has_the_panes_own_warnings(window, qtbot, mistakes):
    assert window.open_files([str(SMALL_A)], [str(mistakes)])
    pane = atoms_pane(window, qtbot)
    pane.plan_box.setPlainText("occurs(object(robot,1),action(move,(1,0)),1).\n"
                               "occur(object(robot,2),action(move,(1,0)),1).")
    pane.read_now()
    assert note_lines(pane)[1:] == ["warning: <plan atoms>:2: occur/3 is ignored: did you mean occurs/3?"]
    window.state.document.history.undo()                       # the plan read from the file: its words again
    assert note_lines(pane)[1:] == warned(mistakes)
    pane.plan_box.setPlainText(pane.plan_box.toPlainText())     # read, the same plan: the pane's own words
    pane.read_now()
    assert note_lines(pane) == ["1 action, horizon 3: 7 violations",
                                "warning: <plan atoms>:1: there is no action 'mvoe': did you mean move? "
                                "(the actions: deliver, move, pickup, putdown)"]


@pytest.mark.gui
def test_the_plan_saved_from_the_viewer_is_no_longer_warned_about(window, qtbot, mistakes, tmp_path):
    assert window.open_files([str(SMALL_A)], [str(mistakes)])
    pane = atoms_pane(window, qtbot)
    window.reload_on_save.action.setChecked(False)
    window.state.document.save_plan(tmp_path / "saved.lp")
    assert note_lines(pane) == ["1 action, horizon 3: 7 violations"]
