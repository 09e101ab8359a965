"""The atoms pane: instance and plan as facts, following the map, the plan edited as text
(checked on each edit, undoable)."""

from __future__ import annotations

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pytest  # noqa: E402
from helpers import OUTCOME  # noqa: E402
from helpers.viewer import shown_window  # noqa: E402
from PyQt5.QtCore import Qt  # noqa: E402
from PyQt5.QtGui import QTextCursor  # noqa: E402
from PyQt5.QtWidgets import QMessageBox  # noqa: E402

from asprilo.checker import check  # noqa: E402
from asprilo.reader import read_instance, read_plan  # noqa: E402
from asprilo.visualizer.scene import style  # noqa: E402
from asprilo.visualizer.state.atoms import about, instance_lines  # noqa: E402

pytestmark = pytest.mark.gui
FIRST = "occurs(object(robot,1),action(move,(1,0)),1)."  # robot 1 starts at (1,6) and moves right


@pytest.fixture
def window(qtbot, tmp_path_factory, monkeypatch):
    window = shown_window(qtbot, tmp_path_factory)
    monkeypatch.setattr(QMessageBox, "question", lambda *args: QMessageBox.Discard)
    window.open_files([str(OUTCOME)])
    window.docks["atoms"].show()
    window.docks["atoms"].raise_()
    qtbot.waitUntil(lambda: window.docks["atoms"].widget().isVisible())
    return window


def pane(window):
    return window.docks["atoms"].widget()


def marked(box) -> list[str]:
    """The lines of a text box that carry a mark."""
    return [selection.cursor.block().text() for selection in box.extraSelections()]


def type_over(qtbot, box, old: str, new: str) -> None:
    """Select ``old`` in the box and type ``new`` over it, key by key."""
    box.setFocus()
    start = box.toPlainText().index(old)
    cursor = box.textCursor()
    cursor.setPosition(start)
    cursor.setPosition(start + len(old), QTextCursor.KeepAnchor)
    box.setTextCursor(cursor)
    qtbot.keyClicks(box, new)


def test_lines_say_what_they_are_about():
    assert about("init(object(product,4),value(on,(2,10))).").subjects == {("product", 4), ("shelf", 2)}
    assert about("init(object(order,1),value(pickingStation,2)).").subjects == {("order", 1), ("station", 2)}
    assert about("init(object(robot,3),value(carries,1)).").subjects == {("robot", 3), ("shelf", 1)}
    assert about("assign(robot(2),destination(5)).").subjects == {("robot", 2), ("destination", 5)}
    line = about("occurs(object(robot,3),action(deliver,(1,4,1)),8).")
    assert (line.subjects, line.step) == ({("robot", 3)}, 8)
    assert about("% robots").subjects == set() and about("#program base.").step is None


def test_the_pane_shows_the_facts_and_follows_selection_and_step(window):
    atoms = pane(window)
    instance, plan = read_instance(OUTCOME), read_plan(OUTCOME)
    assert atoms.instance_box.toPlainText().splitlines() == [line.text for line in instance_lines(instance)]
    assert len(atoms.plan_box.toPlainText().splitlines()) == len(plan) == 79
    window.select_robots([3])
    assert marked(atoms.instance_box) == ["init(object(robot,3),value(at,(3,6)))."]
    window.go_to(8)
    plan_marks = marked(atoms.plan_box)
    assert plan_marks[:3] == ["occurs(object(robot,1),action(pickup,()),8).",  # the step shown
                              "occurs(object(robot,2),action(move,(1,0)),8).",
                              "occurs(object(robot,3),action(deliver,(1,4,1)),8)."]
    assert sorted(plan_marks[3:]) == sorted(f"occurs(object(robot,3),action({a.name},{_args(a)}),{a.step})."
                                            for a in plan.actions if a.robot == 3 and a.step != 8)
    window.stage.scene.clearSelection()
    window.state.selection.set([], ("shelf", 9))  # a shelf: its position and its products
    assert marked(atoms.instance_box) == ["init(object(shelf,9),value(at,(7,4))).",
                                          "init(object(product,1),value(on,(9,4)))."]


def _args(action) -> str:
    from asprilo.writer import format_value
    return format_value(action.args)


def test_clicking_facts_selects_objects_and_steps(window, qtbot):
    atoms = pane(window)
    box = atoms.plan_box
    box.setFocus()
    block = box.document().findBlockByNumber(next(n for n, line in enumerate(atoms.lines["plan"]) if line.step == 14))
    box.setTextCursor(QTextCursor(block))
    assert window.player.step == 14
    box = atoms.instance_box
    box.setFocus()
    number = atoms.instance_box.toPlainText().splitlines().index("init(object(robot,2),value(at,(2,6))).")
    box.setTextCursor(QTextCursor(box.document().findBlockByNumber(number)))
    assert window.selected == [2]


def test_editing_a_plan_atom_changes_the_animation_and_the_violations_and_undo_takes_it_back(window, qtbot):
    atoms = pane(window)
    original = read_plan(OUTCOME)
    assert not window.track.violations
    type_over(qtbot, atoms.plan_box, FIRST, "occurs(object(robot,1),action(move,(-1,0)),1).")
    qtbot.waitUntil(lambda: window.scenario.plan != original, timeout=60_000)  # a hang guard
    # robot 1 now drives left from (1,6) onto (0,6), which is no node; the ASP checker says
    # which rules that breaks, the window must say the same
    edited = window.scenario.plan
    assert [a for a in edited.actions if a.step == 1 and a.robot == 1][0].args == (-1, 0)
    expected = sorted(error.atom for error in check(read_instance(OUTCOME), edited).errors)
    assert sorted(v.atom for v in window.track.violations) == expected and expected
    window.go_to(1)
    assert style.cell_at(window.stage.scene.robots[1].pos()) == (0, 6)  # the animation follows
    assert window.docks["violations"].windowTitle() == f"Violations ({len(expected)})"
    assert f"{len(expected)} violation" in atoms.plan_note.text()
    assert window.windowTitle().startswith("*")  # the plan has unsaved edits
    qtbot.keyClick(atoms.plan_box, Qt.Key_Z, Qt.ControlModifier)  # the window's undo, from the text
    assert window.scenario.plan == original and not window.track.violations
    assert FIRST in atoms.plan_box.toPlainText().splitlines()
    assert not window.windowTitle().startswith("*")


def test_a_plan_the_reader_refuses_is_shown_as_such_and_changes_nothing(window, qtbot):
    atoms = pane(window)
    original = window.scenario.plan
    type_over(qtbot, atoms.plan_box, FIRST, "occurs(object(robot,9),action(move,(1,0)),1).")
    qtbot.waitUntil(lambda: "the plan shown stays" in atoms.plan_note.text(), timeout=60_000)  # a hang guard
    assert "the plan moves robot 9, but the instance has robots 1..3" in atoms.plan_note.text()
    assert window.scenario.plan is original and window.editor.document.history.count == 0
