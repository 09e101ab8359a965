"""The editor's palette of edit tools: what a left click on the warehouse does."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from PyQt5.QtCore import QPointF, QRectF, Qt, pyqtSignal
from PyQt5.QtGui import QIcon, QKeySequence, QPainter, QPen, QPixmap
from PyQt5.QtWidgets import QAction, QActionGroup, QToolBar, QWidget

from ..scene import style


@dataclass(frozen=True)
class EditTool:
    name: str
    text: str
    key: str
    hint: str


#: the edit tools, in palette order
EDIT_TOOLS: tuple[EditTool, ...] = (
    EditTool("pointer", "&Pointer", "V", "select robots; drag robots, shelves and stations to move them"),
    EditTool("robot", "&Robot", "R", "click a node to add a robot"),
    EditTool("shelf", "&Shelf", "S", "click a storage node to add a shelf"),
    EditTool("station", "Picking s&tation", "P", "click a node to add a picking station"),
    EditTool("destination", "&Destination", "D", "click a node to add a destination (domain Md)"),
    EditTool("highway", "&Highway", "H", "click or drag over nodes to make them highways, or storage again"),
    EditTool("floor", "&Wall", "W", "click or drag over cells to remove nodes (walls, pillars), or restore them"),
    EditTool("erase", "&Erase", "X", "click an object to remove it"),
)
#: edit tools that add an object of their own kind
OBJECT_TOOLS = ("robot", "shelf", "station", "destination")


def _pointer(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.ROBOT_EDGE, 1.5))
    painter.setBrush(Qt.white)
    s = size / 32
    painter.drawPolygon(*[QPointF(x * s, y * s) for x, y in
                          ((9, 4), (9, 26), (14, 21), (18, 29), (22, 27), (18, 19), (25, 19))])


def _robot(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.ROBOT_EDGE, 1.5))
    painter.setBrush(style.robot_colour(0))
    painter.drawEllipse(box.adjusted(3, 3, -3, -3))


def _shelf(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.SHELF_EDGE, 2))
    painter.setBrush(style.SHELF)
    painter.drawRoundedRect(box, 4, 4)
    for fraction in (1 / 3, 2 / 3):
        y = box.top() + fraction * box.height()
        painter.drawLine(QPointF(box.left() + 4, y), QPointF(box.right() - 4, y))


def _station(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(Qt.NoPen)
    painter.setBrush(style.STATION)
    painter.drawRect(box)
    painter.setPen(QPen(style.STATION_STRIPES, 3))
    painter.setClipRect(box)
    for offset in range(-size, size, 8):
        painter.drawLine(QPointF(box.left() + offset, box.bottom()), QPointF(box.left() + offset + size, box.top()))


def _destination(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.DESTINATION, 2.5, Qt.DashLine))
    painter.setBrush(Qt.NoBrush)
    painter.drawEllipse(box.adjusted(2, 2, -2, -2))


def _highway(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.GRID_LINE, 1))
    painter.setBrush(style.HIGHWAY)
    painter.drawRect(box)


def _wall(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.GRID_LINE.darker(130), 1))
    painter.setBrush(style.MISSING_NODE.darker(115))
    painter.drawRect(box)


def _erase(painter: QPainter, box: QRectF, size: int) -> None:
    painter.setPen(QPen(style.VIOLATION, 3.5))
    painter.drawLine(box.topLeft() + QPointF(4, 4), box.bottomRight() - QPointF(4, 4))
    painter.drawLine(box.topRight() + QPointF(-4, 4), box.bottomLeft() + QPointF(4, -4))


_PICTURES: dict[str, Callable[[QPainter, QRectF, int], None]] = {
    "pointer": _pointer, "robot": _robot, "shelf": _shelf, "station": _station, "destination": _destination,
    "highway": _highway, "floor": _wall, "erase": _erase}


def tool_icon(name: str, size: int = 32) -> QIcon:
    """A small picture of what the edit tool puts on the floor, in the warehouse's own colours."""
    pixmap = QPixmap(size, size)
    pixmap.fill(Qt.transparent)
    painter = QPainter(pixmap)
    painter.setRenderHint(QPainter.Antialiasing)
    _PICTURES[name](painter, QRectF(3, 3, size - 6, size - 6), size)
    painter.end()
    return QIcon(pixmap)


class EditPalette(QToolBar):
    """One checkable button per edit tool; exactly one is chosen."""

    tool_changed = pyqtSignal(str)

    def __init__(self, parent: QWidget | None = None):
        super().__init__("Edit tools", parent)
        self.setObjectName("edit_tools")
        self.group = QActionGroup(self)
        self.group.setExclusive(True)
        self.actions_by_name: dict[str, QAction] = {}
        for tool in EDIT_TOOLS:
            action = QAction(tool_icon(tool.name), tool.text, self)
            action.setCheckable(True)
            action.setShortcut(QKeySequence(tool.key))
            action.setToolTip(f"{tool.text.replace('&', '')} ({tool.key}): {tool.hint}")
            action.setStatusTip(tool.hint)
            action.setData(tool.name)
            self.group.addAction(action)
            self.addAction(action)
            self.actions_by_name[tool.name] = action
        self.actions_by_name["pointer"].setChecked(True)
        self.group.triggered.connect(lambda action: self.tool_changed.emit(action.data()))

    @property
    def tool(self) -> str:
        return self.group.checkedAction().data()

    def choose(self, name: str) -> None:
        action = self.actions_by_name[name]
        if not action.isChecked():
            action.setChecked(True)
            self.tool_changed.emit(name)
