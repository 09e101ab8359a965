"""The layout editor in the window, driven with the mouse (offscreen): tools, drag and drop,
right-click menu, orders table, undo/redo, saving."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME, SMALL_A  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtCore import QEvent, QPointF, Qt  # noqa: E402
from PyQt5.QtGui import QMouseEvent  # noqa: E402
from PyQt5.QtWidgets import QApplication, QMessageBox  # noqa: E402

from asprilo.reader import read_instance, read_plan  # noqa: E402
from asprilo.visualizer.panels.dialogs import GenerateDialog, SizeDialog, StockDialog  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402
from asprilo.writer import format_instance  # noqa: E402

pytestmark = pytest.mark.gui


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    # closing the window at the end must not ask "discard unsaved edits?"
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    return window


def body(path) -> list[str]:
    """The facts of a saved file (its header left out)."""
    return [line for line in path.read_text().splitlines() if line.startswith("init(")]


def point(window, cell):
    return window.view.mapFromScene(style.centre(cell))


def click(qtbot, window, tool: str, cell, button=Qt.LeftButton) -> None:
    window.editor.palette.choose(tool)
    qtbot.mouseClick(window.view.viewport(), button, pos=point(window, cell))


def drag(qtbot, window, start, end) -> None:
    """Press on ``start``, move over the cell half-way and onto ``end``, release there."""
    viewport = window.view.viewport()
    qtbot.mousePress(viewport, Qt.LeftButton, pos=point(window, start))
    for cell in (((start[0] + end[0]) / 2, (start[1] + end[1]) / 2), end):
        # QTest's mouseMove carries no button; send the event a dragging mouse sends
        move = QMouseEvent(QEvent.MouseMove, QPointF(point(window, cell)), Qt.NoButton, Qt.LeftButton,
                           Qt.NoModifier)
        QApplication.sendEvent(viewport, move)
    qtbot.mouseRelease(viewport, Qt.LeftButton, pos=point(window, end))


def test_mouse_edits_give_exactly_these_facts_and_undo_takes_them_back(window, qtbot, tmp_path):
    window.editor.new_instance(4, 3)
    assert window.windowTitle() == "untitled — asprilo viz"
    click(qtbot, window, "highway", (2, 1))
    click(qtbot, window, "floor", (4, 3))
    click(qtbot, window, "robot", (1, 3))
    click(qtbot, window, "shelf", (3, 2))
    click(qtbot, window, "station", (4, 1))
    assert window.windowTitle() == "*untitled — asprilo viz"
    window.editor.set_stock(1, {2: 5})
    window.editor.orders.add_order()
    assert window.editor.save_as(tmp_path / "edited.lp")
    assert window.windowTitle() == "edited.lp — asprilo viz"
    nodes = [f"init(object(node,{(y - 1) * 4 + x}),value(at,({x},{y})))." for y in (1, 2, 3) for x in (1, 2, 3, 4)
             if (x, y) != (4, 3)]
    assert body(tmp_path / "edited.lp") == nodes + [
        "init(object(highway,2),value(at,(2,1))).",
        "init(object(pickingStation,1),value(at,(4,1))).",
        "init(object(robot,1),value(at,(1,3))).",
        "init(object(shelf,1),value(at,(3,2))).",
        "init(object(product,2),value(on,(1,5))).",
        "init(object(order,1),value(line,(2,1))).",
        "init(object(order,1),value(pickingStation,1)).",
    ]
    assert read_instance(tmp_path / "edited.lp") == window.editor.document.instance
    history = window.editor.document.history
    assert history.count == 7 and history.undo_text == "add order 1"
    while history.can_undo:
        window.editor.commands["undo"].trigger()
    window.editor.save_as(tmp_path / "undone.lp")
    assert body(tmp_path / "undone.lp") == [f"init(object(node,{(y - 1) * 4 + x}),value(at,({x},{y})))."
                                            for y in (1, 2, 3) for x in (1, 2, 3, 4)]
    assert not window.stage.scene.robots and not window.stage.scene.shelves and not window.stage.scene.stations
    window.editor.commands["redo"].trigger()
    assert window.stage.scene.floor.kinds.tolist() == [[1, 2, 1, 1], [1, 1, 1, 1], [1, 1, 1, 1]]


def test_refused_edits_say_why_and_change_nothing(window, qtbot):
    window.editor.new_instance(3, 2)
    click(qtbot, window, "highway", (2, 2))
    click(qtbot, window, "shelf", (2, 2))
    assert window.editor.last_message == "(2,2) is a highway: shelves may not rest there"
    assert "Not done: (2,2) is a highway" in window.statusBar().currentMessage()
    click(qtbot, window, "robot", (1, 1))
    click(qtbot, window, "robot", (1, 1))
    assert window.editor.last_message == "robot 1 already stands on (1,1): two robots may not share a node"
    click(qtbot, window, "floor", (1, 1))
    assert window.editor.last_message == "robot 1 stands on (1,1): remove it first"
    assert window.editor.document.history.count == 2 and list(window.stage.scene.robots) == [1]


def test_painting_highways_is_one_undo_step(window, qtbot):
    window.editor.new_instance(5, 2)
    window.editor.palette.choose("highway")
    drag(qtbot, window, (1, 1), (5, 1))
    assert sorted(window.editor.document.instance.highways.values()) == [(1, 1), (3, 1), (5, 1)]
    drag(qtbot, window, (2, 1), (2, 1))
    assert window.editor.document.history.count == 2
    assert window.editor.document.history.undo_text == "make highways"
    window.editor.document.history.undo()
    window.editor.document.history.undo()
    assert not window.editor.document.instance.highways


def test_drag_and_drop_moves_objects_and_refuses_bad_drops(window, qtbot):
    window.editor.new_instance(4, 2)
    for kind, cell in (("robot", (1, 1)), ("shelf", (1, 1)), ("shelf", (3, 2)), ("station", (4, 1))):
        window.editor.add(kind, cell)
    window.editor.set_carries(1, 1)
    window.editor.palette.choose("pointer")
    drag(qtbot, window, (1, 1), (2, 2))
    instance = window.editor.document.instance
    assert instance.robots[1].at == (2, 2) and instance.shelves[1].at == (2, 2)  # the carried shelf came along
    assert window.stage.scene.robots[1].pos() == style.centre((2, 2))
    drag(qtbot, window, (2, 2), (3, 2))
    assert window.editor.last_message == "shelf 2 rests on (3,2): a robot carrying shelf 1 cannot go under it"
    assert instance.robots[1].at == (2, 2) and window.stage.scene.robots[1].pos() == style.centre((2, 2))
    drag(qtbot, window, (4, 1), (1, 1))
    assert instance.stations[1].at == (1, 1) and window.stage.scene.stations[1].pos() == style.centre((1, 1))
    assert window.editor.document.history.undo_text == "move picking station 1 to (1,1)"


def test_right_click_menu_edits_what_stands_on_a_cell(window, qtbot):
    window.editor.new_instance(3, 3)
    window.editor.add("robot", (2, 2))
    window.editor.add("shelf", (2, 2))
    menu = window.editor.context_menu((2, 2))
    texts = [action.text() for action in menu.actions() if action.text()]
    assert texts == ["Cell (2,2): storage node", "Robot 1 starts carrying shelf 1", "Remove robot 1",
                     "Products on shelf 1…", "Remove shelf 1", "Add robot here", "Add shelf here",
                     "Add picking station here", "Add destination here", "Make highway", "Remove node (wall)"]
    next(a for a in menu.actions() if a.text() == "Robot 1 starts carrying shelf 1").trigger()
    assert window.editor.document.instance.robots[1].carries == 1
    assert window.track.state(0).carries == {1: 1} and window.stage.scene.shelves[1].carried
    menu = window.editor.context_menu((3, 3))
    next(a for a in menu.actions() if a.text() == "Remove node (wall)").trigger()
    menu = window.editor.context_menu((3, 3))
    assert [a.text() for a in menu.actions() if a.text()][-2:] == ["Restore node", "Make highway"]


def test_order_table_edits_and_flags_products_nowhere_in_stock(window, qtbot):
    window.editor.new_instance(3, 2)
    window.editor.add("shelf", (1, 1))
    window.editor.add("station", (3, 1))
    window.editor.set_stock(1, {1: 4})
    orders = window.editor.orders
    assert orders.add_order()
    model = orders.model
    assert [model.index(0, c).data() for c in range(4)] == ["1", "1", "1", "PS1"]
    assert model.setData(model.index(0, 2), 3)
    assert model.setData(model.index(0, 1), 7)
    assert window.editor.document.instance.orders[1].lines == {7: 3}
    assert model.index(0, 0).data() == "1 \u26a0"
    assert model.index(0, 1).data(Qt.ToolTipRole) == "order 1 asks for product 7, which no shelf holds"
    assert model.index(0, 1).data(Qt.BackgroundRole) is not None
    assert model.setData(model.index(0, 3), 0)  # no station
    assert "order 1 names no picking station" in model.index(0, 2).data(Qt.ToolTipRole)
    orders.table.selectRow(0)
    assert orders.add_line()
    assert window.editor.document.instance.orders[1].lines == {1: 1, 7: 3}
    orders.table.selectRow(0)
    orders.table.selectRow(1)
    orders.table.selectAll()
    assert orders.remove_lines()
    assert window.editor.document.instance.orders[1].lines == {}
    assert model.index(0, 0).data(Qt.ToolTipRole) == "order 1 names no picking station\norder 1 has no lines yet"
    window.editor.document.history.undo()  # the two lines removed at once come back at once
    assert window.editor.document.instance.orders[1].lines == {1: 1, 7: 3}


def test_loaded_invalid_instance_is_flagged_in_place(window, qtbot, write):
    path = write("bad.lp", format_instance(read_instance(SMALL_A)).replace(
        "init(object(shelf,1),value(at,(3,3))).", "init(object(shelf,1),value(at,(1,1)))."))
    assert window.open_files([str(path)])
    assert window.stage.scene.shelves[1].flagged
    assert "shelf 1 rests on the highway node (1,1)" in [r[2] for r in window.panels["violations"].texts()]
    window.editor.move("shelf", 1, (3, 3))
    assert not window.stage.scene.shelves[1].flagged


def test_edits_keep_the_plan_and_replay_it(window, qtbot):
    window.open_files([str(OUTCOME)])
    window.go_to(10)
    assert window.track.horizon == 29 and not window.track.violations
    assert window.editor.add("robot", (11, 6))
    assert window.player.time == 0 and window.track.horizon == 29
    window.editor.commands["undo"].trigger()
    window.editor.move("robot", 1, (4, 6))
    assert window.track.violations and window.transport.slider.marks
    window.editor.commands["undo"].trigger()
    assert not window.track.violations
    assert window.editor.document.path is None  # outcome.txt holds the plan too: Save asks for a name


def test_resize_and_template(window, qtbot, tmp_path):
    window.open_files([str(SMALL_A)])
    assert str(window.editor.document.path) == str(SMALL_A)
    assert window.editor.resize(6, 4)
    assert window.editor.document.instance.size == (6, 4) and window.stage.scene.floor.size == (6, 4)
    assert window.editor.save_template(tmp_path / "template.lp")
    saved = read_instance(tmp_path / "template.lp")
    assert not saved.products and not saved.orders
    assert saved.shelves == window.editor.document.instance.shelves
    assert "gen -T template.lp" in (tmp_path / "template.lp").read_text()
    window.editor.commands["undo"].trigger()
    assert format_instance(window.editor.document.instance) == format_instance(read_instance(SMALL_A))
    assert window.windowTitle() == "x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp — asprilo viz"


def test_dialogs_return_what_was_entered(qtbot):
    size = SizeDialog("Resize grid", 11, 6)
    qtbot.addWidget(size)
    assert size.values() == (11, 6)
    size.width_box.setValue(20)
    assert size.values() == (20, 6)
    stock = StockDialog(3, {1: 4, 2: None})
    qtbot.addWidget(stock)
    assert stock.stock() == {1: 4, 2: None}
    stock.add_row(5, 2)
    stock.table.selectRow(0)
    stock.remove_selected()
    assert stock.stock() == {2: None, 5: 2}
    generate = GenerateDialog({"robots": 2, "shelves": 4, "orders": 3}, 7)
    qtbot.addWidget(generate)
    generate.lines.setValue(2)
    assert generate.values() == {"options": {"robots": 2, "shelves": 4, "orders": 3, "ol_min": 2, "ol_max": 2},
                                 "seed": 7}


def test_unsaved_edits_are_not_dropped_without_asking(window, monkeypatch):
    window.editor.new_instance(2, 2)
    window.editor.add("robot", (1, 1))
    asked = []
    monkeypatch.setattr(QMessageBox, "question", lambda *args: asked.append(args[2]) or QMessageBox.Cancel)
    assert not window.open_files([str(SMALL_A)])
    assert asked == ["The instance has unsaved edits. Discard them?"]
    assert list(window.editor.document.instance.robots) == [1]
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    assert window.open_files([str(SMALL_A)])


def test_saving_mid_animation_writes_the_initial_state(window, qtbot, tmp_path):
    window.open_files([str(OUTCOME)])
    window.player.set_speed(64)
    window.player.play()
    qtbot.waitUntil(lambda: window.player.time > 10, timeout=60_000)  # a hang guard
    assert window.editor.save_as(tmp_path / "saved.lp")
    assert window.player.time > 10  # saving does not stop the animation
    assert read_instance(tmp_path / "saved.lp") == read_instance(OUTCOME)
    text = (tmp_path / "saved.lp").read_text()
    assert text.startswith("%" * 60 + "\n% asprilo viz ") and "occurs(" not in text
    assert window.windowTitle() == "saved.lp + outcome.txt — asprilo viz"  # the plan still comes from there
    assert window.files.reload() and len(window.scenario.plan) == len(read_plan(OUTCOME))


def test_the_pointer_selects_robots_while_a_plan_plays(window, qtbot):
    window.open_files([str(OUTCOME)])
    window.go_to(5)
    cell = tuple(int(v) for v in window.track.state(5).robots[2])
    window.editor.palette.choose("pointer")
    qtbot.mouseClick(window.view.viewport(), Qt.LeftButton, pos=point(window, cell))
    assert window.selected == [2] and window.player.time == 5  # no rewind, nothing moved
    assert window.editor.document.history.count == 0
