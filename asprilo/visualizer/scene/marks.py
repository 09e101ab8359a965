"""Marks on the map that are not objects: red cells of violations, goal frames and their
tags, the pills of actions under way, the paths of selected robots, a robot's gauge (the
level of a variant's resource, its energy say)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from PyQt5.QtCore import QPointF, QRectF, Qt
from PyQt5.QtGui import QBrush, QColor, QPainterPath
from PyQt5.QtWidgets import QGraphicsItem, QGraphicsPathItem, QGraphicsRectItem

from . import style
from .drawing import NO_PEN, Z_BADGE, Z_MARK, Z_TRAIL, Label, pen, square
from .style import CELL


class CellMark(QGraphicsRectItem):
    """A red frame around a cell involved in a violation."""

    def __init__(self, rect: QRectF):
        super().__init__(rect.adjusted(2, 2, -2, -2))
        self.setPen(pen(style.VIOLATION, 0.07 * CELL, Qt.DashLine))
        self.setBrush(QColor(224, 49, 49, 40))
        self.setZValue(Z_MARK)


@dataclass(frozen=True)
class GoalLook:
    """How a goal is marked: the frame's colour, dashed (open) or solid (reached), and the
    tag's text (who serves it, where it must go, or who reached it)."""

    colour: QColor
    reached: bool
    tag: str = ""


class GoalMark(QGraphicsPathItem):
    """A frame around a goal's cell (dashed while open, solid once reached) with a small tag
    in its top right corner; a child of the object's item, so it moves with it."""

    def __init__(self, parent: QGraphicsItem):
        super().__init__(parent)
        path = QPainterPath()
        path.addRoundedRect(square(0.98), 0.14 * CELL, 0.14 * CELL)
        self.setPath(path)
        self.setBrush(QBrush(Qt.NoBrush))
        self.pill = QGraphicsPathItem(self)
        self.pill.setPen(NO_PEN)
        self.text = Label("", 0.19 * CELL, QColor("white"), self.pill)
        self.look: GoalLook | None = None
        self.fine = True
        self.tag_shown = True

    def show(self, look: GoalLook | None) -> None:
        self.setVisible(look is not None)
        if look is None or look == self.look:
            return
        self.look = look
        self._restyle()
        self.text.setText(look.tag)
        box = self.text.boundingRect()
        width, height = box.width() + 0.1 * CELL, box.height()
        pill = QPainterPath()
        pill.addRoundedRect(QRectF(-width / 2, -height / 2, width, height), height / 2, height / 2)
        self.pill.setPath(pill)
        self.pill.setBrush(look.colour)
        self.pill.setPos(0.49 * CELL - width / 2, -0.49 * CELL + height / 2)
        self.text.centre_at(QPointF(0, 0))
        self._show_tag()

    def set_detail(self, fine: bool) -> None:
        self.fine = fine
        if self.look is not None:
            self._restyle()
            self._show_tag()

    def set_tag_shown(self, shown: bool) -> None:
        """Show the tag where it can be read (as id labels)."""
        self.tag_shown = shown
        if self.look is not None:
            self._show_tag()

    def _show_tag(self) -> None:
        self.pill.setVisible(bool(self.look.tag) and self.fine and self.tag_shown)

    def _restyle(self) -> None:
        width = (0.07 if self.fine else 0.16) * CELL
        self.setPen(pen(self.look.colour, width, Qt.SolidLine if self.look.reached else Qt.DashLine))


class GaugeBar(QGraphicsRectItem):
    """A thin bar under a robot's disc: the part of its starting level left, green, orange
    when little is left, an empty red bar once the level is below the least allowed; a child
    of the robot's item, so it moves with it."""

    #: the bar's box, in cells from the robot's centre: under the disc (and its red ring), in the cell
    BOX = (-style.ROBOT_SIZE / 2, 0.41, style.ROBOT_SIZE, 0.08)

    def __init__(self, parent: QGraphicsItem):
        x, y, width, height = (value * CELL for value in self.BOX)
        super().__init__(QRectF(x, y, width, height), parent)
        self.setPen(pen(QColor("#343a40"), 0.02 * CELL))
        self.setBrush(QColor(255, 255, 255, 200))
        self.fill = QGraphicsRectItem(self)
        self.fill.setPen(NO_PEN)
        self.shown: tuple[float, bool] | None = None

    def fill_to(self, part: float, below: bool) -> None:
        """``part`` (0..1) of the starting level is left; ``below``: under the least level."""
        if self.shown == (part, below):
            return
        self.shown = (part, below)
        box = self.rect()
        part = min(max(part, 0.0), 1.0)
        self.fill.setRect(QRectF(box.left(), box.top(), box.width() * part, box.height()))
        self.fill.setBrush(style.DELIVERY if part > 0.25 else style.GOAL)
        self.setBrush(style.VIOLATION if below else QColor(255, 255, 255, 200))
        self.fill.setVisible(not below)


class Badge(QGraphicsPathItem):
    """A small pill with text that shows an action while it happens (pick up, deliver, ...)."""

    def __init__(self, text: str, colour: QColor):
        super().__init__()
        self.label = Label(text, 0.2 * CELL, QColor("white"), self)
        box = self.label.boundingRect()
        width, height = box.width() + 0.16 * CELL, box.height() + 0.04 * CELL
        path = QPainterPath()
        path.addRoundedRect(QRectF(-width / 2, -height / 2, width, height), height / 2, height / 2)
        self.setPath(path)
        self.setBrush(colour)
        self.setPen(pen(QColor("white"), 0.025 * CELL))
        self.setZValue(Z_BADGE)

    def show_progress(self, anchor: QPointF, progress: float) -> None:
        """Place the badge above ``anchor`` (below it in the top row), drifting away and fading
        in and out as ``progress`` goes 0..1."""
        away = -1 if anchor.y() > CELL else 1
        self.setPos(anchor.x(), anchor.y() + away * (0.5 + 0.25 * progress) * CELL)
        self.setOpacity(min(1.0, 3 * math.sin(math.pi * progress)))


class TrailItem(QGraphicsPathItem):
    """The path of a robot in its colour: the part still ahead solid, the part behind faint."""

    def __init__(self, colour: QColor):
        super().__init__()
        self.setPen(pen(colour, 0.1 * CELL))
        self.setBrush(QBrush(Qt.NoBrush))
        self.setZValue(Z_TRAIL)
        self.setOpacity(0.8)
        self.past = QGraphicsPathItem(self)
        faint = QColor(colour)
        faint.setAlpha(110)
        self.past.setPen(pen(faint, 0.07 * CELL, Qt.DashLine))

    def set_points(self, ahead: list[QPointF], behind: list[QPointF]) -> None:
        self.setPath(_polyline(ahead, goal=True))
        self.past.setPath(_polyline(behind, goal=False))


def _polyline(points: list[QPointF], goal: bool) -> QPainterPath:
    path = QPainterPath()
    if len(points) < 2:
        return path
    path.moveTo(points[0])
    for point in points[1:]:
        path.lineTo(point)
    if goal:
        radius = 0.14 * CELL
        path.addEllipse(points[-1], radius, radius)
    return path

