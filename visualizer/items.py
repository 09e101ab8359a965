"""The graphics items of the warehouse: robots, shelves, stations, destinations and marks.

Items are plain Qt shape items (their painting runs in C++, which keeps thousands of
them fast); each is centred on its cell and knows the object it shows (``kind``, ``ident``).
Outlines and labels are dropped at coarse detail, when a cell is only a few pixels wide.
"""

from __future__ import annotations

import math
from functools import cache

from PyQt5.QtCore import QPointF, QRectF, Qt
from PyQt5.QtGui import QBrush, QColor, QPainterPath, QPen, QPolygonF
from PyQt5.QtWidgets import (
    QGraphicsEllipseItem,
    QGraphicsItem,
    QGraphicsPathItem,
    QGraphicsRectItem,
    QGraphicsSimpleTextItem,
)

from . import style
from .style import CELL

NO_PEN = QPen(Qt.NoPen)

# stacking order, bottom to top
Z_DESTINATION, Z_STATION, Z_CARRIED, Z_ROBOT, Z_SHELF, Z_TRAIL, Z_MARK, Z_BADGE = range(1, 9)
# (a resting shelf is drawn above robots, half see-through: a robot parked under it shows
# dimmed; a carried shelf lies below its robot, framed in the robot's colour)


def _pen(colour: QColor, width: float, style_: Qt.PenStyle = Qt.SolidLine) -> QPen:
    return QPen(_cached_pen(colour.rgba(), width, int(style_)))


@cache
def _cached_pen(rgba: int, width: float, style_: int) -> QPen:
    pen = QPen(QColor.fromRgba(rgba), width, Qt.PenStyle(style_))
    pen.setJoinStyle(Qt.RoundJoin)
    pen.setCapStyle(Qt.RoundCap)
    return pen


def _square(size: float) -> QRectF:
    half = size * CELL / 2
    return QRectF(-half, -half, 2 * half, 2 * half)


class Label(QGraphicsSimpleTextItem):
    """Centred text that shrinks to fit ``width`` scene units."""

    def __init__(self, text: str, pixel_size: float, colour: QColor, parent: QGraphicsItem,
                 width: float | None = None):
        super().__init__(text, parent)
        self.setFont(style.font(pixel_size))
        self.setBrush(colour)
        box = self.boundingRect()
        if width is not None and box.width() > width:
            self.setScale(width / box.width())
        self.centre_at(QPointF(0, 0))

    def centre_at(self, point: QPointF) -> None:
        box = self.boundingRect()
        scale = self.scale()
        self.setPos(point.x() - box.width() * scale / 2, point.y() - box.height() * scale / 2)


class ObjectItem:
    """What every warehouse object item offers: its identity, detail level and red flag.

    Marks that most objects never need (the red flag, a selection ring, a shadow) are
    made on first use: a big warehouse has thousands of items.
    """

    kind = ""
    flag_size = 1.0

    def init_object(self, ident: int) -> None:
        self.ident = ident
        self.label: Label | None = None
        self.flag: QGraphicsItem | None = None

    def set_detail(self, fine: bool) -> None:
        if self.label is not None:
            self.label.setVisible(fine)

    def set_flagged(self, flagged: bool) -> None:
        """Mark the object red: it takes part in a rule violation."""
        if flagged and self.flag is None:
            self.flag = QGraphicsRectItem(_square(self.flag_size), self)
            self.flag.setPen(_pen(style.VIOLATION, 0.08 * CELL))
        if self.flag is not None:
            self.flag.setVisible(flagged)

    @property
    def flagged(self) -> bool:
        return self.flag is not None and self.flag.isVisible()


class RobotItem(QGraphicsEllipseItem, ObjectItem):
    """A robot: a disc in its own colour with its id."""

    kind = "robot"

    def __init__(self, ident: int, colour: QColor):
        super().__init__(_square(style.ROBOT_SIZE))
        self.init_object(ident)
        self.colour = colour
        self.setBrush(colour)
        self.setZValue(Z_ROBOT)
        self.label = Label(str(ident), 0.3 * CELL, style.ROBOT_TEXT, self, 0.5 * CELL)
        self.ring: QGraphicsEllipseItem | None = None
        self.set_detail(True)

    def set_detail(self, fine: bool) -> None:
        super().set_detail(fine)
        self.setPen(_pen(style.ROBOT_EDGE, 0.035 * CELL) if fine else NO_PEN)

    def set_flagged(self, flagged: bool) -> None:
        if flagged and self.flag is None:
            self.flag = QGraphicsEllipseItem(_square(style.ROBOT_SIZE + 0.12), self)
            self.flag.setPen(_pen(style.VIOLATION, 0.09 * CELL))
        super().set_flagged(flagged)

    def set_selected(self, selected: bool) -> None:
        """Show the selection ring (selected robots also show their paths)."""
        if selected and self.ring is None:
            self.ring = QGraphicsEllipseItem(_square(style.ROBOT_SIZE + 0.22), self)
            self.ring.setPen(_pen(style.SELECTION, 0.07 * CELL))
        if self.ring is not None:
            self.ring.setVisible(selected)


@cache
def _rack_path(size: float) -> QPainterPath:
    """A shelf seen from above: a rounded frame with two slats."""
    box = _square(size)
    path = QPainterPath()
    path.addRoundedRect(box, 0.12 * CELL, 0.12 * CELL)
    for fraction in (1 / 3, 2 / 3):
        y = box.top() + fraction * box.height()
        path.moveTo(box.left() + 0.12 * CELL, y)
        path.lineTo(box.right() - 0.12 * CELL, y)
    return path


@cache
def _block_path(size: float) -> QPainterPath:
    """A shelf when cells are tiny: a plain square, the cheapest shape to fill."""
    path = QPainterPath()
    path.addRect(_square(size))
    return path


class ShelfItem(QGraphicsPathItem, ObjectItem):
    """A shelf: a wooden rack; carried, it is lifted (shadow, larger) and framed in its robot's colour."""

    kind = "shelf"
    flag_size = style.SHELF_SIZE + 0.1

    def __init__(self, ident: int):
        super().__init__()
        self.init_object(ident)
        self.setZValue(Z_SHELF)
        self.shadow: QGraphicsPathItem | None = None
        self.carrier: QColor | None = None
        self.fine = True
        self._look: tuple | None = None  # (fine, carrier) the item is styled for
        self._restyle()

    def set_detail(self, fine: bool) -> None:
        self.fine = fine
        self._restyle()

    def set_carrier(self, colour: QColor | None) -> None:
        """``colour`` of the robot carrying this shelf, or ``None`` when it rests on the floor."""
        self.carrier = colour
        self.setZValue(Z_SHELF if colour is None else Z_CARRIED)
        self.setScale(1.0 if colour is None else style.CARRIED_SHELF_SIZE / style.SHELF_SIZE)
        self._restyle()

    @property
    def carried(self) -> bool:
        return self.carrier is not None

    def set_flagged(self, flagged: bool) -> None:
        super().set_flagged(flagged)
        self._restyle()

    def _restyle(self) -> None:
        carried = self.carrier is not None
        # at coarse detail resting shelves are drawn by the scene's ShelfLayer instead
        visible = self.fine or carried or self.flagged
        self.setVisible(visible)
        look = (self.fine, self.carrier.rgba() if carried else None)
        if not visible or look == self._look:
            return
        self._look = look
        self.setPath(_rack_path(style.SHELF_SIZE) if self.fine else _block_path(style.SHELF_SIZE))
        self.setBrush(style.SHELF if carried else style.RESTING_SHELF)
        if carried:
            self.setPen(_pen(self.carrier, (0.1 if self.fine else 0.2) * CELL))
        else:
            self.setPen(_pen(style.SHELF_EDGE, 0.045 * CELL) if self.fine else NO_PEN)
        if carried and self.fine and self.shadow is None:
            self.shadow = QGraphicsPathItem(self.path(), self)
            self.shadow.setFlag(QGraphicsItem.ItemStacksBehindParent)
            self.shadow.setBrush(style.SHADOW)
            self.shadow.setPen(NO_PEN)
            self.shadow.setPos(0.05 * CELL, 0.08 * CELL)
        if self.shadow is not None:
            self.shadow.setVisible(carried and self.fine)


class ShelfLayer(QGraphicsPathItem):
    """All resting shelves as one shape: how they are drawn when cells are a few pixels
    wide (drawing thousands of tiny items one by one would cost too much per frame)."""

    def __init__(self):
        super().__init__()
        self.setBrush(style.RESTING_SHELF)  # see-through, as the single shelves
        self.setPen(NO_PEN)
        self.setZValue(Z_SHELF)

    def show_shelves(self, shelves) -> None:
        """Draw the shelves among ``shelves`` (ShelfItems) that nobody carries."""
        box = _square(style.SHELF_SIZE)
        path = QPainterPath()
        path.setFillRule(Qt.WindingFill)  # two shelves on one cell (an invalid plan) stay filled
        for shelf in shelves:
            if not shelf.carried:
                path.addRect(box.translated(shelf.pos()))
        self.setPath(path)


@cache
def _stripes() -> QPainterPath:
    """Diagonal bands clipped to a cell: the striped look of a picking station."""
    box = _square(1.0)
    bands = QPainterPath()
    step = CELL / 4
    offset = -CELL
    while offset < CELL:
        bands.addPolygon(QPolygonF([QPointF(box.left() + offset, box.bottom()),
                                    QPointF(box.left() + offset + step / 2, box.bottom()),
                                    QPointF(box.left() + offset + step / 2 + CELL, box.top()),
                                    QPointF(box.left() + offset + CELL, box.top())]))
        bands.closeSubpath()
        offset += step
    clip = QPainterPath()
    clip.addRect(box)
    return bands.intersected(clip)


class StationItem(QGraphicsRectItem, ObjectItem):
    """A picking station: a striped yellow cell with a ``PS<id>`` tag.

    The tag is an item of its own, drawn above robots and shelves, so a busy station
    still shows; it follows the station wherever the station is put.
    """

    kind = "station"

    def __init__(self, ident: int):
        super().__init__(_square(0.96))
        self.init_object(ident)
        self.setBrush(style.STATION)
        self.setPen(NO_PEN)
        self.setZValue(Z_STATION)
        self.setFlag(QGraphicsItem.ItemSendsGeometryChanges)
        stripes = QGraphicsPathItem(_stripes(), self)
        stripes.setBrush(style.STATION_STRIPES)
        stripes.setPen(NO_PEN)
        stripes.setScale(0.96)
        self.tag = QGraphicsRectItem()
        self.tag.setBrush(QColor(255, 255, 255, 225))
        self.tag.setPen(_pen(style.STATION_STRIPES, 0.02 * CELL))
        self.tag.setZValue(Z_MARK)
        self.label = Label(f"PS{ident}", 0.2 * CELL, style.STATION_TEXT, self.tag)
        box = self.label.mapRectToParent(self.label.boundingRect()).adjusted(-3, -1, 3, 1)
        self.tag.setRect(box)
        self._tag_offset = QPointF(-0.48 * CELL + box.width() / 2 + 2, -0.48 * CELL + box.height() / 2 + 2)

    def itemChange(self, change, value):
        if change == QGraphicsItem.ItemPositionHasChanged:
            self.tag.setPos(self.pos() + self._tag_offset)
        elif change == QGraphicsItem.ItemSceneHasChanged:
            if self.tag.scene() is not None and self.tag.scene() is not self.scene():
                self.tag.scene().removeItem(self.tag)
            if self.scene() is not None and self.tag.scene() is None:
                self.scene().addItem(self.tag)
                self.tag.setPos(self.pos() + self._tag_offset)
        return super().itemChange(change, value)

    def set_detail(self, fine: bool) -> None:
        self.tag.setVisible(fine)


class DestinationItem(QGraphicsEllipseItem, ObjectItem):
    """A destination (domain Md): a dashed target ring labelled ``D<id>``."""

    kind = "destination"

    def __init__(self, ident: int):
        super().__init__(_square(0.8))
        self.init_object(ident)
        self.setBrush(QColor(style.DESTINATION.red(), style.DESTINATION.green(),
                             style.DESTINATION.blue(), 40))
        self.setZValue(Z_DESTINATION)
        self.label = Label(f"D{ident}", 0.22 * CELL, style.DESTINATION, self)
        self.set_detail(True)

    def set_detail(self, fine: bool) -> None:
        super().set_detail(fine)
        self.setPen(_pen(style.DESTINATION, (0.05 if fine else 0.12) * CELL, Qt.DashLine))


class CellMark(QGraphicsRectItem):
    """A red frame around a cell involved in a violation."""

    def __init__(self, rect: QRectF):
        super().__init__(rect.adjusted(2, 2, -2, -2))
        self.setPen(_pen(style.VIOLATION, 0.07 * CELL, Qt.DashLine))
        self.setBrush(QColor(224, 49, 49, 40))
        self.setZValue(Z_MARK)


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
        self.setPen(_pen(QColor("white"), 0.025 * CELL))
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
        self.setPen(_pen(colour, 0.1 * CELL))
        self.setBrush(QBrush(Qt.NoBrush))
        self.setZValue(Z_TRAIL)
        self.setOpacity(0.8)
        self.past = QGraphicsPathItem(self)
        faint = QColor(colour)
        faint.setAlpha(110)
        self.past.setPen(_pen(faint, 0.07 * CELL, Qt.DashLine))

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
