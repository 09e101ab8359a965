"""Geometry and colours of the warehouse picture: one place to restyle the viewer.

Scene coordinates: a cell is ``CELL`` units wide; cell ``(X,Y)`` covers
``[(X-1)*CELL, X*CELL] x [(Y-1)*CELL, Y*CELL]``, so ``(1,1)`` is the top-left and Y grows
downwards, as in SPEC.md.
"""

from __future__ import annotations

from functools import cache

from PyQt5.QtCore import QPointF, QRectF
from PyQt5.QtGui import QColor, QFont

from asprilo.model import Cell

#: Scene units per cell.
CELL = 64.0

#: Below this many screen pixels per cell items drop outlines and labels (cheap to draw).
FINE_DETAIL_PX = 12.0

# the floor
BACKGROUND = QColor("#dfe3e8")      # around the floor and where nodes are missing
MISSING_NODE = QColor("#c9ced6")
STORAGE = QColor("#fbfbfc")
HIGHWAY = QColor("#d8cdf2")         # the paper's purple highways, softened
GRID_LINE = QColor("#c3c8d0")

# objects
STATION = QColor("#f7c948")
STATION_STRIPES = QColor("#d99a00")
STATION_TEXT = QColor("#5c4300")
SHELF = QColor("#d9a86c")
RESTING_SHELF = QColor(217, 168, 108, 150)  # see-through: shows a robot parked below
SHELF_EDGE = QColor("#8a5a2b")
SHADOW = QColor(0, 0, 0, 70)
ROBOT_EDGE = QColor("#22262b")
ROBOT_TEXT = QColor("#ffffff")
DESTINATION = QColor("#2f6f4f")
SELECTION = QColor("#1b1f24")
VIOLATION = QColor("#e03131")
DELIVERY = QColor("#2b8a3e")        # deliveries, reached goals
GOAL = QColor("#f76707")            # open goals (without a robot of their own)
CAPTION = QColor("#343a40")

# relative sizes (fractions of a cell)
ROBOT_SIZE = 0.62
SHELF_SIZE = 0.84
CARRIED_SHELF_SIZE = 0.9


def robot_colour(index: int) -> QColor:
    """A distinct, saturated colour for the ``index``-th robot (golden-angle hues)."""
    hue = (0.58 + index * 0.618033988749895) % 1.0
    return QColor.fromHsvF(hue, 0.68, 0.84)


def centre(cell: Cell | tuple[float, float]) -> QPointF:
    """Scene point at the centre of a (possibly fractional) cell position."""
    return QPointF((cell[0] - 0.5) * CELL, (cell[1] - 0.5) * CELL)


def cell_rect(cell: Cell) -> QRectF:
    """Scene rectangle covered by a cell."""
    return QRectF((cell[0] - 1) * CELL, (cell[1] - 1) * CELL, CELL, CELL)


def cell_at(point: QPointF) -> Cell:
    """The cell containing a scene point."""
    return (int(point.x() // CELL) + 1, int(point.y() // CELL) + 1)


def font(pixel_size: float, bold: bool = True) -> QFont:
    """A UI font with an integer pixel size (PyQt5 rejects floats)."""
    return QFont(_font(max(1, int(round(pixel_size))), bold))


@cache
def _font(pixel_size: int, bold: bool) -> QFont:
    result = QFont("DejaVu Sans")
    result.setPixelSize(pixel_size)
    result.setBold(bold)
    return result
