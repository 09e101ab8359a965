"""The editor's mouse: clicks with an edit tool, objects dragged with the pointer, highways
and walls painted in strokes, the right-click menu.

Only while editing is possible does the editor take mouse events; otherwise (and for
what the edit tools leave alone) the viewer's own mouse pans, selects and describes.
"""

from __future__ import annotations

from typing import Protocol

from PyQt5.QtCore import QEvent, QObject, QPoint, Qt
from PyQt5.QtGui import QColor, QPen
from PyQt5.QtWidgets import QGraphicsRectItem, QMenu, QToolTip

from asprilo.model import Cell

from ..scene import style
from ..scene.stage import Stage
from ..scene.view import WarehouseView
from ..state import edits
from ..state.document import Document
from ..state.edits import NAMES, TABLES, EditRefused
from ..state.viewer import ViewerState
from .palette import OBJECT_TOOLS, EditPalette


class EditingHost(Protocol):
    """What the mouse needs of the editor."""

    state: ViewerState
    stage: Stage
    document: Document
    view: WarehouseView
    palette: EditPalette
    last_message: str | None

    def add(self, kind: str, cell: Cell) -> bool: ...

    def remove(self, kind: str, ident: int) -> bool: ...

    def move(self, kind: str, ident: int, cell: Cell) -> bool: ...

    def refuse(self, reason: str) -> None: ...

    def ask_stock(self, shelf: int) -> None: ...

    def context_menu(self, cell: Cell) -> QMenu: ...


_MOUSE_EVENTS = (QEvent.MouseButtonPress, QEvent.MouseMove, QEvent.MouseButtonRelease,
                 QEvent.MouseButtonDblClick, QEvent.ContextMenu)
_STROKE_WORDS = {"storage": "storage nodes", "highway": "highways", "missing": "walls"}


class MouseEditing(QObject):
    """Filters the view's mouse events and turns those of the edit tools into edits."""

    def __init__(self, editor: EditingHost, parent: QObject | None = None):
        super().__init__(parent)
        self.editor = editor
        self.view = editor.view
        self._drag: _Drag | None = None
        self._stroke: _Stroke | None = None
        self.view.viewport().installEventFilter(self)

    def tool_changed(self, tool: str) -> None:
        pointer = tool == "pointer"
        self.view.setDragMode(self.view.ScrollHandDrag if pointer else self.view.NoDrag)
        self.view.viewport().setCursor(Qt.ArrowCursor if pointer else Qt.CrossCursor)

    def cell_at(self, position: QPoint) -> Cell:
        return style.cell_at(self.view.mapToScene(position))

    def tip(self, event) -> None:
        """Show the last refusal at the mouse."""
        if self.editor.last_message:
            QToolTip.showText(event.globalPos(), self.editor.last_message, self.view.viewport())

    def eventFilter(self, watched, event) -> bool:
        kind = event.type()
        editor = self.editor
        if kind not in _MOUSE_EVENTS or editor.document.scenario is None or editor.state.layout_lock() is not None:
            return False  # the viewer's own mouse: pan, select, hover
        if kind == QEvent.ContextMenu:
            editor.context_menu(self.cell_at(event.pos())).popup(event.globalPos())
            return True
        left = event.button() == Qt.LeftButton
        if kind == QEvent.MouseButtonDblClick and left:
            return self._double_click(event)
        if kind == QEvent.MouseButtonPress and left:
            return self._press(event)
        busy = self._drag is not None or self._stroke is not None
        if kind == QEvent.MouseMove and busy:
            self._move_to(event)
            return True
        if kind == QEvent.MouseButtonRelease and left and busy:
            self._release(event)
            return True
        return False

    def _press(self, event) -> bool:
        editor = self.editor
        cell, tool = self.cell_at(event.pos()), editor.palette.tool
        if tool == "pointer":
            here = edits.objects_at(editor.document.instance, cell)
            if not here or editor.stage.time != 0:
                return False  # pan and select as in the viewer (objects are moved in the initial state)
            self._drag = _Drag(self, *here[0], cell, event.pos())
        elif tool in OBJECT_TOOLS:
            if not editor.add(tool, cell):
                self.tip(event)
        elif tool == "erase":
            here = edits.objects_at(editor.document.instance, cell)
            if here:
                editor.remove(*here[0])
            else:
                editor.refuse(f"nothing to remove on {edits.cell_text(cell)}")
                self.tip(event)
        else:
            self._stroke = _Stroke(editor, tool, cell)
            if self._stroke.target is None:
                self._stroke = None
        return True

    def _double_click(self, event) -> bool:
        here = edits.objects_at(self.editor.document.instance, self.cell_at(event.pos()))
        shelves = [ident for kind, ident in here if kind == "shelf"]
        if self.editor.palette.tool != "pointer" or not shelves:
            return False
        self.editor.ask_stock(shelves[0])
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


class _Drag:
    """An object dragged with the pointer: it follows the mouse; dropped, it moves there."""

    def __init__(self, mouse: MouseEditing, kind: str, ident: int, cell: Cell, start: QPoint):
        self.mouse, self.kind, self.ident, self.origin, self.start = mouse, kind, ident, cell, start
        editor = mouse.editor
        scene, instance = editor.stage.scene, editor.document.instance
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
        editor = self.mouse.editor
        point = self.mouse.view.mapToScene(position)
        for item in self.items:
            item.setPos(point)
        cell = style.cell_at(point)
        try:
            edits.move_object(editor.document.instance, self.kind, self.ident, cell)
            colour, reason = style.DELIVERY, None
        except EditRefused as refusal:
            colour, reason = style.VIOLATION, str(refusal)
        self.target.setRect(style.cell_rect(cell).adjusted(3, 3, -3, -3))
        self.target.setPen(QPen(colour, 0.06 * style.CELL))
        fill = QColor(colour)
        fill.setAlpha(50)
        self.target.setBrush(fill)
        self.target.setVisible(True)
        editor.state.say(reason or f"drop {NAMES[self.kind]} {self.ident} on {edits.cell_text(cell)}", 3000)

    def drop(self, event) -> None:
        view, editor = self.mouse.view, self.mouse.editor
        editor.stage.scene.removeItem(self.target)
        if not self.moved:  # a click: select as the viewer does
            view.clicked.emit(view.objects_at(event.pos()), event.modifiers())
            return
        if not editor.move(self.kind, self.ident, self.mouse.cell_at(event.pos())):
            for item in self.items:  # refused or not moved: back to where it stands
                item.setPos(style.centre(self.origin))
            self.mouse.tip(event)


class _Stroke:
    """Highway or wall painted over cells with the mouse button held: one undoable step."""

    def __init__(self, editor: EditingHost, tool: str, cell: Cell):
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
            self.editor.document.history.begin_group(f"make {_STROKE_WORDS[self.target]}")
            self.open = True
        self.editor.document.perform(edit)

    def finish(self) -> None:
        if self.open:
            self.editor.document.history.end_group()
