"""File > Reload on save (offscreen): the files shown are read again when saved -- in place or
renamed over -- with the step shown kept; unsaved edits are never dropped silently (a banner
offers Reload, which asks); a save that cannot be read is said in the banner."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, SMALL_A  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtWidgets import QMessageBox  # noqa: E402

from asprilo.model import Plan  # noqa: E402
from asprilo.visualizer.panels.reload_on_save import SETTING  # noqa: E402

pytestmark = pytest.mark.gui

#: milliseconds a save may take to show (a bound against hanging, not a timing)
PATIENCE = 60_000
PLAN = "".join(line + "\n" for line in OUTCOME.read_text().splitlines() if line.startswith("occurs("))


def first_steps(last: int) -> str:
    """The plan's actions up to step ``last``."""
    return "".join(line + "\n" for line in PLAN.splitlines() if int(line.rsplit(",", 1)[1].rstrip(").")) <= last)


def replace(path, text: str) -> None:
    """Save as many editors do: a new file renamed over the old one."""
    fresh = path.with_name(f".{path.name}.new")
    fresh.write_text(text)
    os.replace(fresh, path)


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    window.questions = []
    monkeypatch.setattr(QMessageBox, "question", lambda *args: window.questions.append(args[2]) or QMessageBox.Discard)
    return window


@pytest.fixture
def files(tmp_path):
    instance, plan = tmp_path / "instance.lp", tmp_path / "plan.lp"
    instance.write_text(SMALL_A.read_text())
    plan.write_text(PLAN)
    return instance, plan


def test_a_saved_plan_is_read_again_and_the_step_kept(window, qtbot, files):
    instance, plan = files
    assert window.reload_on_save.action.isChecked()            # on by default
    assert window.open_files([str(instance)], [str(plan)]) and window.track.horizon == 29
    window.go_to(10)
    plan.write_text(first_steps(20))                           # in place
    qtbot.waitUntil(lambda: window.track.horizon == 20, timeout=PATIENCE)
    assert window.player.step == 10 and not window.questions
    replace(plan, first_steps(15))                             # renamed over: watched again after it
    qtbot.waitUntil(lambda: window.track.horizon == 15, timeout=PATIENCE)
    plan.write_text(first_steps(12))
    qtbot.waitUntil(lambda: window.track.horizon == 12, timeout=PATIENCE)
    replace(instance, SMALL_A.read_text().replace("init(object(robot,1),value(at,(1,6))).",
                                                  "init(object(robot,1),value(at,(1,5)))."))
    qtbot.waitUntil(lambda: window.track.state(0).robots[1] == (1, 5), timeout=PATIENCE)
    assert window.player.step == 10 and window.track.horizon == 12
    assert window.reload_on_save.banner.isHidden()


def test_unsaved_edits_are_not_dropped_silently(window, qtbot, files):
    instance, plan = files
    window.open_files([str(instance)], [str(plan)])
    window.state.document.replace_plan(Plan(), "clear the plan")   # an unsaved edit
    assert window.state.document.modified
    plan.write_text(first_steps(20))
    banner = window.reload_on_save.banner
    qtbot.waitUntil(lambda: not banner.isHidden(), timeout=PATIENCE)
    assert "plan.lp changed on disk" in banner.text.text() and not banner.reload.isHidden()
    assert len(window.track.plan) == 0 and not window.questions    # the edit stays, nothing asked yet
    banner.reload.click()                                            # File > Reload: asks first
    assert window.questions == ["The plan has unsaved edits. Discard them?"]
    assert window.track.horizon == 20 and banner.isHidden() and not window.state.document.modified


def test_a_save_that_cannot_be_read_is_said_in_the_banner(window, qtbot, files):
    instance, plan = files
    window.open_files([str(instance)], [str(plan)])
    plan.write_text(first_steps(20) + "occurs(object(robot,1),action(move,(0,1)),21)\n")   # no "."
    banner = window.reload_on_save.banner
    qtbot.waitUntil(lambda: not banner.isHidden(), timeout=PATIENCE)
    assert "cannot be read" in banner.text.text() and "plan.lp" in banner.text.text()
    assert banner.reload.isHidden() and window.track.horizon == 29 and window.last_error is None
    plan.write_text(first_steps(20))                                # mended: read, the banner goes
    qtbot.waitUntil(lambda: window.track.horizon == 20, timeout=PATIENCE)
    assert banner.isHidden()


def test_the_viewers_own_save_reads_nothing_again(window, qtbot, files, tmp_path):
    instance, plan = files
    window.open_files([str(instance)], [str(plan)])
    window.state.document.replace_plan(Plan(), "clear the plan")
    opened = []
    window.state.document.opened.connect(opened.append)
    assert window.editor.save_plan(str(plan))
    window.reload_on_save.look()                                    # what the watcher's event leads to
    assert not opened and window.state.document.history.can_undo    # the history is kept
    assert window.reload_on_save.banner.isHidden()


def test_the_setting_off_watches_nothing_and_on_reads_what_was_saved(window, qtbot, files):
    instance, plan = files
    window.open_files([str(instance)], [str(plan)])
    watcher = window.reload_on_save.watcher
    assert str(plan) in watcher.files() and str(plan.parent) in watcher.directories()
    window.reload_on_save.action.trigger()                          # off
    assert window.settings.value(SETTING, type=bool) is False
    assert not watcher.files() and not watcher.directories()
    plan.write_text(first_steps(20))
    window.reload_on_save.look()
    assert window.track.horizon == 29                               # off: nothing read
    window.reload_on_save.action.trigger()                          # on again: the save is read now
    assert window.track.horizon == 20 and window.settings.value(SETTING, type=bool) is True
    assert window.reload_on_save.action in window.menus["file"].actions()
