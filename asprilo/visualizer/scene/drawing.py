"""What the warehouse's items are drawn with: pens, cell-sized squares, centred text, and
the stacking order of everything on the map."""

from __future__ import annotations

from functools import cache

from PyQt5.QtCore import QPointF, QRectF, Qt
from PyQt5.QtGui import QColor, QPen
from PyQt5.QtWidgets import QGraphicsItem, QGraphicsSimpleTextItem

from . import style
from .style import CELL

NO_PEN = QPen(Qt.NoPen)

# stacking order, bottom to top
Z_DESTINATION, Z_STATION, Z_CARRIED, Z_ROBOT, Z_SHELF, Z_TRAIL, Z_MARK, Z_BADGE = range(1, 9)
# (a resting shelf is drawn above robots, half see-through: a robot parked under it shows
# dimmed; a carried shelf lies below its robot, framed in the robot's colour)


def pen(colour: QColor, width: float, style_: Qt.PenStyle = Qt.SolidLine) -> QPen:
    """A round-cornered pen (pens are shared: thousands of items use a few)."""
    return QPen(_cached_pen(colour.rgba(), width, int(style_)))


@cache
def _cached_pen(rgba: int, width: float, style_: int) -> QPen:
    result = QPen(QColor.fromRgba(rgba), width, Qt.PenStyle(style_))
    result.setJoinStyle(Qt.RoundJoin)
    result.setCapStyle(Qt.RoundCap)
    return result


def square(size: float) -> QRectF:
    """A square ``size`` cells wide centred on (0, 0)."""
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


