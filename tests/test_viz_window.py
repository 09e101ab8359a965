"""The viewer's main window, driven like a user would (offscreen): files, playback, panels."""

from __future__ import annotations

import os
from itertools import pairwise

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, SMALL_A, WRONG_OUTCOME  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PIL import Image  # noqa: E402
from PyQt5.QtCore import QMimeData, QPoint, Qt, QUrl  # noqa: E402
from PyQt5.QtGui import QDropEvent  # noqa: E402
from PyQt5.QtWidgets import QAction  # noqa: E402

from asprilo.simulate import simulate  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402
from asprilo.visualizer.window import MainWindow  # noqa: E402

pytestmark = pytest.mark.gui


@pytest.fixture
def window(qtbot, tmp_path_factory):
    return shown_window(qtbot, tmp_path_factory, (1366, 768))  # a laptop's screen (offscreen: 800x600)


def robot_cells(window) -> dict[int, tuple[float, float]]:
    return {r: (item.pos().x() / style.CELL + 0.5, item.pos().y() / style.CELL + 0.5)
            for r, item in window.stage.scene.robots.items()}


def test_empty_window_then_open(window):
    assert window.scenario is None and window.windowTitle() == "asprilo viz"
    assert window.open_files([str(OUTCOME)])
    assert window.windowTitle() == "outcome.txt — asprilo viz"
    assert window.track.horizon == 29
    assert window.transport.slider.maximum() == 29
    assert window.transport.label.text() == "initial state (step 0 of 29)"
    assert "domain A" in window.status_line.summary.text() and "horizon 29" in window.status_line.summary.text()
    assert "valid plan" in window.status_line.verdict.text()


def test_keyboard_playback(window, qtbot):
    window.open_files([str(OUTCOME)])
    player = window.player
    qtbot.keyClick(window, Qt.Key_End)
    assert player.time == 29 and window.transport.label.text() == "state after step 29 of 29"
    assert robot_cells(window) == simulate(window.track.instance, window.track.plan).state(29).robots
    qtbot.keyClick(window, Qt.Key_Home)
    assert player.time == 0
    qtbot.keyClick(window, Qt.Key_Right)          # glides smoothly to the next state
    assert player.moving
    qtbot.waitUntil(lambda: not player.moving and player.time == 1.0, timeout=3000)
    assert window.transport.spin.value() == 1
    qtbot.keyClick(window, Qt.Key_Left)
    qtbot.waitUntil(lambda: not player.moving and player.time == 0.0, timeout=3000)
    qtbot.keyClick(window, Qt.Key_BracketRight)
    assert player.speed == 4.0
    qtbot.keyClick(window, Qt.Key_BracketLeft)
    qtbot.keyClick(window, Qt.Key_BracketLeft)
    assert player.speed == 1.0


def test_play_to_the_end_and_loop(window, qtbot):
    window.open_files([str(OUTCOME)])
    player = window.player
    player.set_speed(64)
    seen: list[float] = []
    player.time_changed.connect(seen.append)
    qtbot.keyClick(window, Qt.Key_Space)
    assert player.playing
    qtbot.waitUntil(lambda: not player.playing, timeout=60_000)  # a hang guard
    assert player.time == 29 and seen == sorted(seen)
    assert any(0 < t < 29 and t != int(t) for t in seen)   # in-between frames were shown
    qtbot.keyClick(window, Qt.Key_L)
    assert player.loop
    seen.clear()
    qtbot.keyClick(window, Qt.Key_Space)                   # from the end: starts over
    qtbot.waitUntil(lambda: any(b < a for a, b in pairwise(seen)), timeout=60_000)  # a hang guard
    assert player.playing                                  # wrapped around, still playing
    qtbot.keyClick(window, Qt.Key_Space)
    assert not player.playing


def test_slider_and_go_to_step(window):
    window.open_files([str(OUTCOME)])
    window.transport.slider.setValue(12)
    assert window.player.step == 12 and window.transport.spin.value() == 12
    window.transport.spin.setValue(20)
    assert window.player.time == 20 and window.transport.slider.value() == 20
    state = simulate(window.track.instance, window.track.plan).state(20)
    assert robot_cells(window) == state.robots
    orders = window.panels["orders"].texts()
    assert orders[3] == ["2", "PS2", "5", "20", "15", "5", "open"]


def test_violations_are_marked_and_clicking_one_jumps_there(window):
    window.open_files([str(WRONG_OUTCOME)])
    assert window.transport.slider.marks == [23, 29]
    assert window.docks["violations"].windowTitle() == "Violations (3)"
    panel = window.panels["violations"]
    panel.table.clicked.emit(panel.proxy.index(1, 0))          # deliver/shelfAmount at step 23
    assert window.player.step == 23
    assert window.stage.animator.highlighted.check == "shelfAmount"
    assert window.selected == [1]
    assert window.stage.scene.robots[1].flagged and window.stage.scene.shelves[2].flagged
    assert "3 rule violations, 2 at step 23" in window.status_line.verdict.text()
    window.go_to(5)
    assert window.stage.scene.shelves[2].flagged                     # highlighted until cleared
    window.clear_selection()
    assert not window.stage.scene.shelves[2].flagged and window.selected == []


def test_plan_panel_click_jumps_to_the_action(window):
    window.open_files([str(OUTCOME)])
    panel = window.panels["plan"]
    row = next(r for r in range(panel.proxy.rowCount()) if panel.source_row(r).step == 14)
    panel.table.clicked.emit(panel.proxy.index(row, 2))
    assert window.player.step == 14


def test_clicking_robots_selects_them_and_shows_paths(window, qtbot):
    window.open_files([str(OUTCOME)])
    view = window.view
    spot = view.mapFromScene(window.stage.scene.robots[2].pos())
    qtbot.mouseClick(view.viewport(), Qt.LeftButton, Qt.NoModifier, spot)
    assert window.selected == [2]
    assert window.stage.scene.robots[2].ring.isVisible()
    assert sorted(window.stage.trails._items) == [2]
    rows = window.panels["robots"].table.selectionModel().selectedRows()
    assert [window.panels["robots"].source_row(i.row()) for i in rows] == [2]
    spot3 = view.mapFromScene(window.stage.scene.robots[3].pos())
    qtbot.mouseClick(view.viewport(), Qt.LeftButton, Qt.ControlModifier, spot3)
    assert window.selected == [2, 3]
    qtbot.keyClick(window, Qt.Key_T)                            # paths off
    assert not window.stage.trails._items
    qtbot.keyClick(window, Qt.Key_T)
    qtbot.mouseClick(view.viewport(), Qt.LeftButton, Qt.NoModifier, QPoint(2, 2))  # empty spot
    assert window.selected == [] and not window.stage.trails._items


def test_hover_describes_what_is_under_the_mouse(window):
    window.open_files([str(OUTCOME)])
    window.go_to(8)
    view = window.view
    spot = view.mapFromScene(window.stage.scene.robots[1].pos())
    objects = view.objects_at(spot)
    assert objects == [("robot", 1), ("shelf", 2)]
    text = view.describe(view.mapToScene(spot), objects)
    assert text.startswith("<b>Robot 1</b><br>at (5,3)<br>carries shelf 2")


def test_zoom_and_level_of_detail(window, qtbot):
    window.open_files([str(OUTCOME)])
    view = window.view
    before = view.pixels_per_cell
    qtbot.keyClick(window, Qt.Key_Plus)
    assert view.pixels_per_cell == pytest.approx(before * 1.25)
    for _ in range(30):
        view.zoom_out()
    assert view.pixels_per_cell == pytest.approx(1.0)
    assert not window.stage.scene.fine and not window.stage.scene.robots[1].label.isVisible()
    qtbot.keyClick(window, Qt.Key_0, Qt.ControlModifier)
    assert view.pixels_per_cell == pytest.approx(before)
    assert window.stage.scene.fine and window.stage.scene.robots[1].label.isVisible()


def user_actions(window) -> list[QAction]:
    """The window's own actions and those of its menus, sub-menus included (not Qt's internal ones)."""
    actions, waiting = {}, [*window.actions(), *window.menuBar().actions()]
    while waiting:
        action = waiting.pop()
        if id(action) not in actions:
            actions[id(action)] = action
            if action.menu() is not None:
                waiting.extend(action.menu().actions())
    return list(actions.values())


def test_shortcuts_do_not_clash(window):
    keys = [key.toString() for action in user_actions(window) for key in action.shortcuts()]
    assert keys and len(keys) == len(set(keys))
    assert "Space" in keys and "Ctrl+G" in keys


def test_bad_file_shows_a_dialog_and_keeps_what_was_open(window, tmp_path):
    window.open_files([str(OUTCOME)])
    broken = tmp_path / "broken.lp"
    broken.write_text("init(object(robot,1),value(at,(1,1))).\ninit(object(robot,1) value(at,(1,1))).\n")
    assert not window.open_files([str(broken)])
    assert window.last_error.startswith(f"{broken}:2: ")
    assert window.scenario.title == "outcome.txt"
    assert not window.open_files([str(tmp_path / "none.lp")])
    assert window.last_error == f"{tmp_path / 'none.lp'}: no such file"


def test_plan_needs_an_instance(window, tmp_path):
    plan = tmp_path / "plan.lp"
    plan.write_text("occurs(object(robot,1),action(move,(1,0)),1).\n")
    assert not window.files.open_plan_files([str(plan)])
    assert window.last_error == "Open an instance first: a plan needs its warehouse."


def drop(window, paths) -> None:
    data = QMimeData()
    data.setUrls([QUrl.fromLocalFile(str(p)) for p in paths])
    event = QDropEvent(QPoint(100, 100), Qt.CopyAction, data, Qt.LeftButton, Qt.NoModifier)
    window.dropEvent(event)


def test_drag_and_drop_instance_then_plan(window, tmp_path):
    plan = tmp_path / "plan.lp"
    plan.write_text("".join(line + "\n" for line in OUTCOME.read_text().splitlines() if line.startswith("occurs")))
    drop(window, [SMALL_A])
    assert window.track.horizon == 0 and window.scenario.title == SMALL_A.name
    drop(window, [plan])                                  # a plan for the instance shown
    assert window.track.horizon == 29 and window.scenario.title == f"{SMALL_A.name} + plan.lp"
    drop(window, [plan, SMALL_A])                         # both at once, in any order
    assert window.track.horizon == 29
    odd = tmp_path / "notes.txt"
    odd.write_text("hello.\n")
    drop(window, [odd])
    assert window.last_error == f"{odd}: holds neither instance facts (init/2) nor plan facts (occurs/3)"


def test_reload_rereads_files_and_keeps_the_step(window, tmp_path):
    instance = tmp_path / "instance.lp"
    instance.write_text(OUTCOME.read_text())
    window.open_files([str(instance)])
    window.go_to(10)
    instance.write_text(OUTCOME.read_text().replace("init(object(robot,1),value(at,(1,6))).",
                                                    "init(object(robot,1),value(at,(1,5)))."))
    qt_reload = window.commands["reload"]
    qt_reload.trigger()
    assert window.player.step == 10
    assert window.track.state(0).robots[1] == (1, 5)
    window.settings.sync()
    assert [p.name for p in tmp_path.iterdir()] == ["instance.lp"]  # nothing beside the user's file


def test_recent_files_live_in_settings(window, qtbot, tmp_path):
    window.open_files([str(SMALL_A)])
    window.open_files([str(SMALL_A)], [str(OUTCOME)])
    window.open_files([str(SMALL_A)])
    assert window.files.recent() == [{"instance": [str(SMALL_A)], "plans": []},
                               {"instance": [str(SMALL_A)], "plans": [str(OUTCOME)]}]
    window.close()
    again = MainWindow(window.settings)
    qtbot.addWidget(again)
    again.files.fill_recent()
    entries = again.files.recent_menu.actions()
    assert [a.text() for a in entries] == [SMALL_A.name, f"{SMALL_A.name} + outcome.txt"]
    entries[1].trigger()
    assert again.track.horizon == 29


def test_export_from_the_window(window, tmp_path):
    window.open_files([str(OUTCOME)])
    window.go_to(12)
    window.select_robots([1])
    assert window.exports.picture(str(tmp_path / "now.png"))
    assert Image.open(tmp_path / "now.png").size == (1472, 832 + 48)  # 128 px per cell, the caption below
    assert window.exports.animation(str(tmp_path / "all.gif"), 2)
    assert Image.open(tmp_path / "all.gif").n_frames == 59
    assert window.player.time == 12                       # the view is back where it was
    assert not window.exports.picture(str(tmp_path / "now.tiff"))
    assert "cannot export '.tiff'" in window.last_error
