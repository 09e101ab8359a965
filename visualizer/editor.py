"""The layout editor inside the viewer's window: tools, mouse, right-click menu, undo, saving.

Edits always change the instance's initial state (the window shows step 0 after each);
a loaded plan stays and is replayed on the edited instance, so its violations update at
once.  Edits that would break a rule of SPEC.md §1 are refused with the reason in the
status bar and a tooltip; problems of a loaded instance are marked red like violations.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from PyQt5.QtCore import QEvent, QObject, QPoint, Qt
from PyQt5.QtGui import QColor, QKeySequence, QPen
from PyQt5.QtWidgets import QAction, QDockWidget, QFileDialog, QGraphicsRectItem, QMenu, QMessageBox, QToolTip

from asprilo.model import Cell, Destination, Instance, PickingStation, Robot, Shelf
from asprilo.sources import Source

from . import edits, style
from .dialogs import SizeDialog, StockDialog
from .edit_commands import Document
from .edits import NAMES, TABLES, Edit, EditRefused
from .loading import Scenario
from .order_editor import OrderEditor
from .tools import OBJECT_TOOLS, ToolPalette

if TYPE_CHECKING:
    from .window import MainWindow

INSTANCE_FILTER = "ASP facts (*.lp);;All files (*)"
DEFAULT_SIZE = (10, 6)
_MAKERS = {"robot": Robot, "shelf": Shelf, "station": PickingStation, "destination": Destination}

#: name -> (menu text, shortcut)
EDIT_ACTIONS: dict[str, tuple[str, str]] = {
    "new": ("&New instance…", "Ctrl+N"),
    "save": ("&Save instance", "Ctrl+S"),
    "save_as": ("Save instance &as…", "Ctrl+Shift+S"),
    "save_template": ("Save as &template (for gen -T)…", ""),
    "resize": ("&Resize grid…", "Ctrl+Shift+R"),
}


class Editor(QObject):
    """Edits the window's instance through a :class:`Document` (undo stack included)."""

    def __init__(self, window: MainWindow):
        super().__init__(window)
        self.window = window
        self.view = window.view
        self.document = Document(self)
        self.document.changed.connect(self._changed)
        self.document.modified_changed.connect(window.show_title)
        self.last_message: str | None = None  # the last refusal (tests and status bar)
        self.locked: str | None = None  # why edits are refused for now (an online session)
        self.palette = ToolPalette(window)
        self.palette.tool_changed.connect(self._tool_changed)
        self.orders = OrderEditor(self.document, self.perform)
        self.commands = self._make_actions()
        self._drag: _Drag | None = None
        self._stroke: _Stroke | None = None
        self.view.viewport().installEventFilter(self)

    def _make_actions(self) -> dict[str, QAction]:
        slots = {"new": self.ask_new, "save": self.save, "save_as": self.ask_save_as,
                 "save_template": self.ask_save_template, "resize": self.ask_resize}
        actions = {}
        for name, (text, key) in EDIT_ACTIONS.items():
            action = QAction(text, self.window)
            if key:
                action.setShortcut(QKeySequence(key))
            action.triggered.connect(lambda _checked=False, slot=slots[name]: slot())
            self.window.addAction(action)
            actions[name] = action
        actions["undo"] = self.document.stack.createUndoAction(self.window, "&Undo")
        actions["undo"].setShortcut(QKeySequence.Undo)
        actions["redo"] = self.document.stack.createRedoAction(self.window, "&Redo")
        actions["redo"].setShortcuts([QKeySequence("Ctrl+Shift+Z"), QKeySequence("Ctrl+Y")])
        for name in ("undo", "redo"):
            self.window.addAction(actions[name])
        return actions

    def install(self, menus: dict[str, QMenu], before: QAction) -> QDockWidget:
        """Put the editor's actions into the window's menus and its tools and docks in place."""
        file = menus["file"]
        file.insertAction(file.actions()[0], self.commands["new"])
        for name in ("save", "save_as", "save_template"):
            file.insertAction(before, self.commands[name])
        file.insertSeparator(before)
        edit = QMenu("&Edit", self.window)
        self.window.menuBar().insertMenu(menus["view"].menuAction(), edit)
        edit.addAction(self.commands["undo"])
        edit.addAction(self.commands["redo"])
        edit.addSeparator()
        tools = edit.addMenu("Edit &tool")
        for action in self.palette.group.actions():
            tools.addAction(action)
        edit.addAction(self.commands["resize"])
        menus["edit"] = edit
        self.window.addToolBar(Qt.LeftToolBarArea, self.palette)
        dock = QDockWidget("Order editor", self.window)
        dock.setObjectName("dock_order_editor")
        dock.setWidget(self.orders)
        edit.addAction(dock.toggleViewAction())
        return dock

    # --- following the window ------------------------------------------------------------------

    def follow(self, scenario: Scenario | None) -> None:
        """A scenario was opened (or the window emptied): edit its instance from now on."""
        self.document.reset(scenario.instance if scenario else Instance(), _own_file(scenario))
        for name in ("save", "save_as", "save_template"):
            self.commands[name].setEnabled(scenario is not None)
        self.lock(self.locked)
        self._refresh_orders()

    def lock(self, reason: str | None) -> None:
        """Refuse edits, saying ``reason``, until called with ``None``."""
        self.locked = reason
        editable = reason is None and self.window.scenario is not None
        self.palette.setEnabled(editable)
        self.commands["resize"].setEnabled(editable)
        self.orders.setEnabled(editable)
        # (the stack re-enables these as it changes; it cannot change while locked)
        self.commands["undo"].setEnabled(editable and self.document.stack.canUndo())
        self.commands["redo"].setEnabled(editable and self.document.stack.canRedo())

    def confirm_discard(self) -> bool:
        """Whether unsaved edits may go (asks when there are any)."""
        if not self.document.modified:
            return True
        answer = QMessageBox.question(self.window, "asprilo viz", "The instance has unsaved edits. Discard them?",
                                      QMessageBox.Discard | QMessageBox.Cancel, QMessageBox.Cancel)
        return answer == QMessageBox.Discard

    # --- edits -------------------------------------------------------------------------------

    def perform(self, make: Callable[[], Edit]) -> bool:
        """Make an edit of the instance and push it on the undo stack, or say why not."""
        if self.window.scenario is None:
            return False
        if self.locked is not None:
            self.refuse(self.locked)
            return False
        try:
            edit = make()
        except EditRefused as refusal:
            self.refuse(str(refusal))
            return False
        self.last_message = None
        return self.document.perform(edit)

    def refuse(self, reason: str) -> None:
        """Say why an edit was not made (the status bar; a tooltip at the mouse for mouse edits)."""
        self.last_message = reason
        self.window.statusBar().showMessage(f"Not done: {reason}", 8000)

    def add(self, kind: str, cell: Cell) -> bool:
        return self.perform(lambda: edits.add_object(self.document.instance, kind, cell))

    def remove(self, kind: str, ident: int) -> bool:
        return self.perform(lambda: edits.remove_object(self.document.instance, kind, ident))

    def move(self, kind: str, ident: int, cell: Cell) -> bool:
        return self.perform(lambda: edits.move_object(self.document.instance, kind, ident, cell))

    def set_floor(self, cell: Cell, kind: str) -> bool:
        return self.perform(lambda: edits.set_floor(self.document.instance, cell, kind))

    def set_carries(self, robot: int, shelf: int | None) -> bool:
        return self.perform(lambda: edits.set_carries(self.document.instance, robot, shelf))

    def set_stock(self, shelf: int, stock: dict[int, int | None]) -> bool:
        return self.perform(lambda: edits.set_stock(self.document.instance, shelf, stock))

    def resize(self, width: int, height: int) -> bool:
        done = self.perform(lambda: edits.resize(self.document.instance, width, height))
        if done:
            self.view.fit()
        return done

    def replace(self, instance: Instance, text: str) -> bool:
        """Replace the whole instance (e.g. by the generator's result) as one undoable edit."""
        return self.perform(lambda: edits.replace_all(self.document.instance, instance, text))

    def new_instance(self, width: int, height: int) -> None:
        """Start a new instance: a full grid of storage nodes, nothing on it."""
        self.window.show_scenario(Scenario(edits.grid(width, height)))

    def _changed(self, edit: Edit) -> None:
        """The document changed (an edit done, undone or redone): update scene and states."""
        scene, instance = self.window.scene, self.document.instance
        if {"nodes", "highways"} & edit.tables:
            scene.set_floor(instance.nodes.values(), instance.highways.values())
        for kind, table in TABLES.items():
            keys = {change.key for change in edit.changes if change.table == table}
            items = getattr(scene, table)
            for key in sorted(keys):
                if key in items:
                    scene.remove(kind, key)
                thing = getattr(instance, table).get(key)
                if thing is not None:
                    getattr(scene, f"add_{kind}")(_MAKERS[kind](thing.id, thing.at))
        self.window.show_changes(0.0)
        self._refresh_orders()
        self.window.statusBar().showMessage(edit.text, 4000)

    def _refresh_orders(self) -> None:
        track = self.window.track
        self.orders.refresh(track.violations if track is not None else [])

    # --- the mouse ---------------------------------------------------------------------------------

    def _tool_changed(self, tool: str) -> None:
        pointer = tool == "pointer"
        self.view.setDragMode(self.view.ScrollHandDrag if pointer else self.view.NoDrag)
        self.view.viewport().setCursor(Qt.ArrowCursor if pointer else Qt.CrossCursor)
        self.window.statusBar().showMessage(self.palette.group.checkedAction().statusTip(), 4000)

    def eventFilter(self, watched, event) -> bool:
        kind = event.type()
        if self.window.scenario is None or self.locked is not None or kind not in _MOUSE_EVENTS:
            return False  # the viewer's own mouse: pan, select, hover
        if kind == QEvent.ContextMenu:
            self.context_menu(self.cell_at(event.pos())).popup(event.globalPos())
            return True
        if kind == QEvent.MouseButtonDblClick and event.button() == Qt.LeftButton:
            return self._double_click(event)
        if kind == QEvent.MouseButtonPress and event.button() == Qt.LeftButton:
            return self._press(event)
        if kind == QEvent.MouseMove and (self._drag or self._stroke):
            self._move_to(event)
            return True
        if kind == QEvent.MouseButtonRelease and event.button() == Qt.LeftButton and (self._drag or self._stroke):
            self._release(event)
            return True
        return False

    def cell_at(self, position: QPoint) -> Cell:
        return style.cell_at(self.view.mapToScene(position))

    def _press(self, event) -> bool:
        cell, tool = self.cell_at(event.pos()), self.palette.tool
        if tool == "pointer":
            target = self._draggable(cell)
            if target is None or self.window.player.time != 0:
                return False  # pan and select as in the viewer (objects are moved in the initial state)
            self._drag = _Drag(self, *target, cell, event.pos())
            return True
        if tool in OBJECT_TOOLS:
            if not self.add(tool, cell):
                self._tip(event)
        elif tool == "erase":
            here = edits.objects_at(self.document.instance, cell)
            if here:
                self.remove(*here[0])
            else:
                self.refuse(f"nothing to remove on {edits.cell_text(cell)}")
                self._tip(event)
        else:
            self._stroke = _Stroke(self, tool, cell)
            if self._stroke.target is None:
                self._stroke = None
        return True

    def _tip(self, event) -> None:
        if self.last_message:
            QToolTip.showText(event.globalPos(), self.last_message, self.view.viewport())

    def _double_click(self, event) -> bool:
        here = edits.objects_at(self.document.instance, self.cell_at(event.pos()))
        shelves = [ident for kind, ident in here if kind == "shelf"]
        if self.palette.tool != "pointer" or not shelves:
            return False
        self.ask_stock(shelves[0])
        return True

    def _move_to(self, event) -> None:
        if self._drag is not None:
            self._drag.follow(event.pos())
        elif self._stroke is not None:
            self._stroke.paint(self.cell_at(event.pos()))

    def _release(self, event) -> None:
        if self._drag is not None:
            drag, self._drag = self._drag, None
            drag.drop(event)
        elif self._stroke is not None:
            stroke, self._stroke = self._stroke, None
            stroke.finish()

    def _draggable(self, cell: Cell) -> tuple[str, int] | None:
        here = edits.objects_at(self.document.instance, cell)
        return here[0] if here else None

    # --- the right-click menu -------------------------------------------------------------------------

    def context_menu(self, cell: Cell) -> QMenu:
        """What can be done on ``cell``: add objects, change the floor, edit what stands there."""
        instance = self.document.instance
        menu = QMenu(self.view)
        menu.setAttribute(Qt.WA_DeleteOnClose)
        title = menu.addAction(f"Cell {edits.cell_text(cell)}: {_floor_words(edits.floor_kind(instance, cell))}")
        title.setEnabled(False)
        here = edits.objects_at(instance, cell)
        for kind, ident in here:
            menu.addSeparator()
            if kind == "robot":
                self._robot_entries(menu, instance.robots[ident], here)
            if kind == "shelf":
                menu.addAction(f"Products on shelf {ident}…", lambda i=ident: self.ask_stock(i))
            menu.addAction(f"Remove {NAMES[kind]} {ident}", lambda k=kind, i=ident: self.remove(k, i))
        menu.addSeparator()
        for kind in OBJECT_TOOLS:
            menu.addAction(f"Add {NAMES[kind]} here", lambda k=kind: self.add(k, cell))
        menu.addSeparator()
        floor = edits.floor_kind(instance, cell)
        for kind, text in (("storage", "Make storage node"), ("highway", "Make highway"),
                           ("missing", "Remove node (wall)")):
            if kind != floor:
                label = "Restore node" if floor == "missing" and kind == "storage" else text
                menu.addAction(label, lambda k=kind: self.set_floor(cell, k))
        return menu

    def _robot_entries(self, menu: QMenu, robot: Robot, here: list[tuple[str, int]]) -> None:
        if robot.carries is not None:
            menu.addAction(f"Robot {robot.id} puts shelf {robot.carries} down",
                           lambda: self.set_carries(robot.id, None))
        for kind, shelf in here:
            if kind == "shelf" and shelf != robot.carries:
                menu.addAction(f"Robot {robot.id} starts carrying shelf {shelf}",
                               lambda s=shelf: self.set_carries(robot.id, s))

    # --- dialogs and files -------------------------------------------------------------------------

    def ask_new(self) -> None:
        if not self.confirm_discard():
            return
        width, height = self.document.instance.size if self.window.scenario else DEFAULT_SIZE
        dialog = SizeDialog("New instance", width or DEFAULT_SIZE[0], height or DEFAULT_SIZE[1],
                            parent=self.window)
        if dialog.exec_():
            self.new_instance(*dialog.values())

    def ask_resize(self) -> None:
        width, height = self.document.instance.size
        dialog = SizeDialog("Resize grid", width, height,
                            "New cells become storage nodes; what lies beyond a smaller grid is removed "
                            "(undo brings it back).", self.window)
        if dialog.exec_():
            self.resize(*dialog.values())

    def ask_stock(self, shelf: int) -> None:
        dialog = StockDialog(shelf, self.document.instance.shelf_stock().get(shelf, {}), self.window)
        if dialog.exec_():
            self.set_stock(shelf, dialog.stock())

    def save(self) -> bool:
        if self.document.path is None:
            return self.ask_save_as()
        return self.save_as(self.document.path)

    def ask_save_as(self) -> bool:
        path = self._ask_path("Save instance", self.document.instance.file_name(1))
        return bool(path) and self.save_as(path)

    def ask_save_template(self) -> bool:
        path = self._ask_path("Save as template for gen -T", "template.lp")
        return bool(path) and self.save_template(path)

    def _ask_path(self, title: str, name: str) -> str:
        folder = Path(self.window._start_folder())
        path, _ = QFileDialog.getSaveFileName(self.window, title, str(folder / name), INSTANCE_FILTER)
        if path:
            self.window.settings.setValue("last_folder", str(Path(path).parent))
        return path

    def save_as(self, path: str | Path) -> bool:
        """Save the instance's initial state in the canonical format; the window now shows that file."""
        try:
            self.document.save(path)
        except OSError as error:
            self.window.report_error(f"{path}: cannot write the instance ({error.strerror or error})")
            return False
        scenario = self.window.scenario
        if scenario is not None:
            if len(scenario.plan) and not scenario.plan_sources:
                scenario.plan_sources = scenario.instance_sources  # the plan still comes from there
            scenario.instance_sources = [Source(str(path), self.document.text())]
            self.window.remember(scenario)
        self.window.show_title()
        self.window.statusBar().showMessage(f"saved {path}", 5000)
        return True

    def save_template(self, path: str | Path) -> bool:
        try:
            self.document.save_template(path)
        except OSError as error:
            self.window.report_error(f"{path}: cannot write the template ({error.strerror or error})")
            return False
        self.window.statusBar().showMessage(f"saved template {path} (for gen -T)", 5000)
        return True


_MOUSE_EVENTS = (QEvent.MouseButtonPress, QEvent.MouseMove, QEvent.MouseButtonRelease,
                 QEvent.MouseButtonDblClick, QEvent.ContextMenu)


def _floor_words(kind: str) -> str:
    return {"storage": "storage node", "highway": "highway", "missing": "no node (wall)"}[kind]


def _own_file(scenario: Scenario | None) -> str | None:
    """The file Save writes to: the scenario's one instance file, unless it also holds the plan."""
    if scenario is None:
        return None
    instances, plans = scenario.files
    if len(scenario.instance_sources) != 1 or len(instances) != 1:
        return None
    if len(scenario.plan) and not scenario.plan_sources:
        return None  # the plan came from the instance file: saving the instance would lose it
    return instances[0]


class _Drag:
    """An object dragged with the pointer tool: it follows the mouse; dropped, it moves there."""

    def __init__(self, editor: Editor, kind: str, ident: int, cell: Cell, start: QPoint):
        self.editor, self.kind, self.ident, self.origin, self.start = editor, kind, ident, cell, start
        scene, instance = editor.window.scene, editor.document.instance
        self.items = [getattr(scene, TABLES[kind])[ident]]
        if kind == "robot" and instance.robots[ident].carries in scene.shelves:
            self.items.append(scene.shelves[instance.robots[ident].carries])
        self.target = QGraphicsRectItem(style.cell_rect(cell).adjusted(3, 3, -3, -3))
        self.target.setZValue(20)
        self.target.setVisible(False)
        scene.addItem(self.target)
        self.moved = False

    def follow(self, position: QPoint) -> None:
        if not self.moved and (position - self.start).manhattanLength() <= 4:
            return
        self.moved = True
        point = self.editor.view.mapToScene(position)
        for item in self.items:
            item.setPos(point)
        cell = style.cell_at(point)
        try:
            edits.move_object(self.editor.document.instance, self.kind, self.ident, cell)
            colour, reason = style.DELIVERY, None
        except EditRefused as refusal:
            colour, reason = style.VIOLATION, str(refusal)
        self.target.setRect(style.cell_rect(cell).adjusted(3, 3, -3, -3))
        self.target.setPen(QPen(colour, 0.06 * style.CELL))
        fill = QColor(colour)
        fill.setAlpha(50)
        self.target.setBrush(fill)
        self.target.setVisible(True)
        self.editor.window.statusBar().showMessage(reason or f"drop {NAMES[self.kind]} {self.ident} on "
                                                   f"{edits.cell_text(cell)}", 3000)

    def drop(self, event) -> None:
        self.editor.window.scene.removeItem(self.target)
        if not self.moved:  # a click: select as the viewer does
            self.editor.view.clicked.emit(self.editor.view.objects_at(event.pos()), event.modifiers())
            return
        cell = self.editor.cell_at(event.pos())
        if not self.editor.move(self.kind, self.ident, cell):
            for item in self.items:  # refused or not moved: back to where it stands
                item.setPos(style.centre(self.origin))
            self.editor._tip(event)


_STROKE_WORDS = {"storage": "storage nodes", "highway": "highways", "missing": "walls"}


class _Stroke:
    """Highway or wall painted over cells with the mouse button held: one undoable step."""

    def __init__(self, editor: Editor, tool: str, cell: Cell):
        self.editor = editor
        kind = edits.floor_kind(editor.document.instance, cell)
        if tool == "highway":
            if kind == "missing":
                editor.refuse(f"{edits.cell_text(cell)} is not a node: restore it first (Wall tool)")
                self.target = None
                return
            self.target = "storage" if kind == "highway" else "highway"
        else:
            self.target = "storage" if kind == "missing" else "missing"
        self.cells: set[Cell] = set()
        self.open = False
        self.paint(cell)

    def paint(self, cell: Cell) -> None:
        if cell in self.cells:
            return
        self.cells.add(cell)
        try:
            edit = edits.set_floor(self.editor.document.instance, cell, self.target)
        except EditRefused as refusal:
            self.editor.refuse(str(refusal))
            return
        if edit.changes and not self.open:
            self.editor.document.stack.beginMacro(f"make {_STROKE_WORDS[self.target]}")
            self.open = True
        self.editor.document.perform(edit)

    def finish(self) -> None:
        if self.open:
            self.editor.document.stack.endMacro()
