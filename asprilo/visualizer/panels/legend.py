"""The legend: every symbol of the map, drawn by the same items the map uses, with what it means."""

from __future__ import annotations

from collections.abc import Callable

from PyQt5.QtCore import QPointF, QRectF, Qt
from PyQt5.QtGui import QColor, QPainter, QPixmap
from PyQt5.QtWidgets import QGraphicsRectItem, QGraphicsScene, QGridLayout, QLabel, QScrollArea, QWidget

from ..scene import style
from ..scene.drawing import NO_PEN
from ..scene.items import DestinationItem, RobotItem, ShelfItem, StationItem
from ..scene.marks import Badge, CellMark, GoalLook, TrailItem
from ..scene.style import CELL

ICON_PX = 44
_ROBOT = style.robot_colour(2)


def _floor(scene: QGraphicsScene, colour: QColor, cells: int = 1) -> None:
    for x in range(cells):
        tile = QGraphicsRectItem(QRectF(x * CELL - CELL / 2 + 2, -CELL / 2 + 2, CELL - 4, CELL - 4))
        tile.setBrush(colour)
        tile.setPen(NO_PEN)
        scene.addItem(tile)


def _robot(scene: QGraphicsScene, x: float = 0.0) -> RobotItem:
    robot = RobotItem(3, _ROBOT)
    robot.setPos(x, 0)
    scene.addItem(robot)
    return robot


def _shelf(scene: QGraphicsScene, goal: GoalLook | None = None) -> ShelfItem:
    shelf = ShelfItem(7)
    shelf.set_label_shown(True)
    shelf.set_goal(goal)
    scene.addItem(shelf)
    return shelf


def _carried(scene: QGraphicsScene) -> None:
    _shelf(scene).set_carrier(_ROBOT)
    _robot(scene)


def _under(scene: QGraphicsScene) -> None:
    _robot(scene)
    _shelf(scene)


def _station(scene: QGraphicsScene) -> None:
    scene.addItem(StationItem(1))


def _destination(scene: QGraphicsScene) -> None:
    scene.addItem(DestinationItem(1))


def _reached(scene: QGraphicsScene) -> None:
    _robot(scene)
    _shelf(scene, GoalLook(QColor(style.DELIVERY), True, "\u2713 R3"))


def _violation(scene: QGraphicsScene) -> None:
    scene.addItem(CellMark(QRectF(-CELL / 2, -CELL / 2, CELL, CELL)))
    _robot(scene).set_flagged(True)


def _path(scene: QGraphicsScene) -> None:
    _floor(scene, style.STORAGE, 2)
    trail = TrailItem(_ROBOT)
    trail.set_points([QPointF(0, 0), QPointF(CELL, 0)], [])
    scene.addItem(trail)
    _robot(scene)


def _pill(scene: QGraphicsScene) -> None:
    _robot(scene)
    badge = Badge("\u2191 pick up", _ROBOT.darker(130))
    badge.setPos(0, -0.32 * CELL)
    scene.addItem(badge)


#: (how to draw the symbol on a storage node, what it means)
ENTRIES: list[tuple[Callable[[QGraphicsScene], object] | QColor, str]] = [
    (style.STORAGE, "storage node: shelves may rest here"),
    (style.HIGHWAY, "highway: for driving only, no shelf may be put down"),
    (style.MISSING_NODE, "no node (a wall, a pillar)"),
    (lambda scene: _robot(scene), "robot 3, in a colour of its own"),
    (lambda scene: _shelf(scene), "shelf 7 resting on the floor (see-through: a robot under it shows)"),
    (_under, "robot 3 parked under a resting shelf"),
    (_carried, "robot 3 carrying shelf 7 (framed in the robot's colour)"),
    (_station, "picking station 1, where orders are delivered"),
    (_destination, "destination 1 (domain Md)"),
    (lambda scene: _shelf(scene, GoalLook(QColor(style.GOAL), False, "")),
     "goal still open: a shelf an order asks for (M), a destination (Md)"),
    (lambda scene: _shelf(scene, GoalLook(_ROBOT, False, "R3")), "robot 3's labelled goal (assign/2), in its colour"),
    (lambda scene: _shelf(scene, GoalLook(QColor(style.GOAL), False, "\u2192PS1")),
     "a shelf an open order line needs, and the station it must reach (A, B, C)"),
    (_reached, "goal reached (by robot 3; in A, B, C: the shelf is at its station)"),
    (_violation, "red: takes part in a rule violation at the state shown"),
    (_path, "the path of a selected robot (dashed: the part already driven)"),
    (_pill, "an action under way: pick up, put down, deliver"),
    (lambda scene: _robot(scene).set_gauge(0.5),
     "a variant's resource (--variant energy): the part of robot 3's starting level left; an empty red bar "
     "once it is below the least allowed"),
]


def icon(draw: Callable[[QGraphicsScene], object] | QColor) -> QPixmap:
    """The symbol on one cell (two for a path), as a picture ICON_PX high."""
    scene = QGraphicsScene()
    scene.setBackgroundBrush(style.BACKGROUND)
    if isinstance(draw, QColor):
        _floor(scene, draw)
    else:
        _floor(scene, style.STORAGE)
        draw(scene)
    source = QRectF(-CELL / 2, -CELL / 2, CELL, CELL).united(scene.itemsBoundingRect())
    source = source.intersected(QRectF(-CELL / 2, -0.75 * CELL, 2 * CELL, 1.5 * CELL))
    width = round(ICON_PX * source.width() / source.height())
    picture = QPixmap(width, ICON_PX)
    picture.fill(style.BACKGROUND)
    painter = QPainter(picture)
    painter.setRenderHints(QPainter.Antialiasing | QPainter.TextAntialiasing)
    scene.render(painter, QRectF(0, 0, width, ICON_PX), source, Qt.KeepAspectRatio)
    painter.end()
    return picture


class Legend(QScrollArea):
    """Symbols and their meaning, one per row."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        body = QWidget(self)
        grid = QGridLayout(body)
        grid.setColumnStretch(1, 1)
        self.rows: list[str] = []
        for row, (draw, meaning) in enumerate(ENTRIES):
            picture = QLabel(body)
            picture.setPixmap(icon(draw))
            text = QLabel(meaning, body)
            text.setWordWrap(True)
            grid.addWidget(picture, row, 0)
            grid.addWidget(text, row, 1)
            self.rows.append(meaning)
        self.setWidget(body)
        self.setWidgetResizable(True)
