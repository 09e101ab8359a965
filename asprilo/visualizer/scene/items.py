"""The graphics items of the warehouse's objects: robots, shelves, stations, destinations.

Items are plain Qt shape items (their painting runs in C++, which keeps thousands of
them fast); each is centred on its cell and knows the object it shows (``kind``, ``ident``).
Outlines are dropped at coarse detail, when a cell is only a few pixels wide; id labels are
shown only when they can be read (the scene decides, per kind of object).
"""

from __future__ import annotations

from functools import cache

from PyQt5.QtCore import QPointF, Qt
from PyQt5.QtGui import QColor, QPainterPath, QPolygonF
from PyQt5.QtWidgets import QGraphicsEllipseItem, QGraphicsItem, QGraphicsPathItem, QGraphicsRectItem

from . import style
from .drawing import NO_PEN, Z_CARRIED, Z_DESTINATION, Z_MARK, Z_ROBOT, Z_SHELF, Z_STATION, Label, pen, square
from .marks import GaugeBar, GoalLook, GoalMark
from .style import CELL


class ObjectItem:
    """What every warehouse object item offers: its identity, detail level and red flag.

    Marks that most objects never need (the red flag, a selection ring, a shadow) are
    made on first use: a big warehouse has thousands of items.
    """

    kind = ""
    flag_size = 1.0
    #: the height of the id label, in cells
    label_size = 0.2

    def init_object(self, ident: int) -> None:
        self.ident = ident
        self.label: Label | None = None
        self.flag: QGraphicsItem | None = None
        self.goal: GoalMark | None = None
        self.labelled = True  # labels (and goal tags) can be read

    def set_detail(self, fine: bool) -> None:
        if self.goal is not None:
            self.goal.set_detail(fine)

    def set_label_shown(self, shown: bool) -> None:
        """Show the id label and a goal's tag (the scene says so when labels are on and large
        enough to read)."""
        self.labelled = shown
        if self.label is not None:
            self.label.setVisible(shown)
        if self.goal is not None:
            self.goal.set_tag_shown(shown)

    def set_goal(self, look: GoalLook | None) -> None:
        """Mark the object as a goal (``None``: it is none now)."""
        if look is not None and self.goal is None:
            self.goal = GoalMark(self)
            self.goal.set_tag_shown(self.labelled)
        if self.goal is not None:
            self.goal.show(look)

    def set_flagged(self, flagged: bool) -> None:
        """Mark the object red: it takes part in a rule violation."""
        if flagged and self.flag is None:
            self.flag = QGraphicsRectItem(square(self.flag_size), self)
            self.flag.setPen(pen(style.VIOLATION, 0.08 * CELL))
        if self.flag is not None:
            self.flag.setVisible(flagged)

    @property
    def flagged(self) -> bool:
        return self.flag is not None and self.flag.isVisible()


class RobotItem(QGraphicsEllipseItem, ObjectItem):
    """A robot: a disc in its own colour with its id."""

    kind = "robot"
    label_size = 0.3

    def __init__(self, ident: int, colour: QColor):
        super().__init__(square(style.ROBOT_SIZE))
        self.init_object(ident)
        self.colour = colour
        self.setBrush(colour)
        self.setZValue(Z_ROBOT)
        self.label = Label(str(ident), 0.3 * CELL, style.ROBOT_TEXT, self, 0.5 * CELL)
        self.ring: QGraphicsEllipseItem | None = None
        self.gauge: GaugeBar | None = None
        self.set_detail(True)

    def set_detail(self, fine: bool) -> None:
        super().set_detail(fine)
        self.setPen(pen(style.ROBOT_EDGE, 0.035 * CELL) if fine else NO_PEN)

    def set_flagged(self, flagged: bool) -> None:
        if flagged and self.flag is None:
            self.flag = QGraphicsEllipseItem(square(style.ROBOT_SIZE + 0.12), self)
            self.flag.setPen(pen(style.VIOLATION, 0.09 * CELL))
        super().set_flagged(flagged)

    def set_gauge(self, part: float | None, below: bool = False) -> None:
        """Show the gauge of a resource: ``part`` of the starting level left (``None``: none)."""
        if part is not None and self.gauge is None:
            self.gauge = GaugeBar(self)
        if self.gauge is not None:
            self.gauge.setVisible(part is not None)
            if part is not None:
                self.gauge.fill_to(part, below)

    def set_selected(self, selected: bool) -> None:
        """Show the selection ring (selected robots also show their paths)."""
        if selected and self.ring is None:
            self.ring = QGraphicsEllipseItem(square(style.ROBOT_SIZE + 0.22), self)
            self.ring.setPen(pen(style.SELECTION, 0.07 * CELL))
        if self.ring is not None:
            self.ring.setVisible(selected)


@cache
def _rack_path(size: float) -> QPainterPath:
    """A shelf seen from above: a rounded frame with two slats."""
    box = square(size)
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
    path.addRect(square(size))
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
        super().set_detail(fine)
        self.fine = fine
        self._restyle()

    def set_label_shown(self, shown: bool) -> None:
        if shown and self.label is None:  # made on first use: a big warehouse has thousands of shelves
            self.label = Label(str(self.ident), self.label_size * CELL, style.SHELF_EDGE, self)
            box = self.label.boundingRect()
            corner = style.SHELF_SIZE * CELL / 2
            self.label.setPos(corner - box.width() - 0.06 * CELL, corner - box.height() - 0.02 * CELL)
        super().set_label_shown(shown)

    def set_goal(self, look: GoalLook | None) -> None:
        super().set_goal(look)
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
        visible = self.fine or carried or self.flagged or (self.goal is not None and self.goal.isVisible())
        self.setVisible(visible)
        look = (self.fine, self.carrier.rgba() if carried else None)
        if not visible or look == self._look:
            return
        self._look = look
        self.setPath(_rack_path(style.SHELF_SIZE) if self.fine else _block_path(style.SHELF_SIZE))
        self.setBrush(style.SHELF if carried else style.RESTING_SHELF)
        if carried:
            self.setPen(pen(self.carrier, (0.1 if self.fine else 0.2) * CELL))
        else:
            self.setPen(pen(style.SHELF_EDGE, 0.045 * CELL) if self.fine else NO_PEN)
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
        box = square(style.SHELF_SIZE)
        path = QPainterPath()
        path.setFillRule(Qt.WindingFill)  # two shelves on one cell (an invalid plan) stay filled
        for shelf in shelves:
            if not shelf.carried:
                path.addRect(box.translated(shelf.pos()))
        self.setPath(path)


@cache
def _stripes() -> QPainterPath:
    """Diagonal bands clipped to a cell: the striped look of a picking station."""
    box = square(1.0)
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
    """A picking station: a striped yellow cell with a ``PS<id>`` tag in its bottom left corner.

    The tag is an item of its own, drawn above robots and shelves, so a busy station
    still shows; it follows the station wherever the station is put.
    """

    kind = "station"

    def __init__(self, ident: int):
        super().__init__(square(0.96))
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
        self.tag.setPen(pen(style.STATION_STRIPES, 0.02 * CELL))
        self.tag.setZValue(Z_MARK)
        self.label = Label(f"PS{ident}", 0.2 * CELL, style.STATION_TEXT, self.tag)
        box = self.label.mapRectToParent(self.label.boundingRect()).adjusted(-3, -1, 3, 1)
        self.tag.setRect(box)
        # the bottom left corner: a goal's tag takes the top right one (``✓ PS1`` on the shelf
        # brought here), a shelf's id the bottom right one, a robot's the middle
        self._tag_offset = QPointF(-0.48 * CELL + box.width() / 2 + 2, 0.48 * CELL - box.height() / 2 - 2)

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

    def set_label_shown(self, shown: bool) -> None:
        super().set_label_shown(shown)
        self.tag.setVisible(shown)


class DestinationItem(QGraphicsEllipseItem, ObjectItem):
    """A destination (domain Md): a dashed target ring labelled ``D<id>``."""

    kind = "destination"
    label_size = 0.22

    def __init__(self, ident: int):
        super().__init__(square(0.8))
        self.init_object(ident)
        self.setBrush(QColor(style.DESTINATION.red(), style.DESTINATION.green(),
                             style.DESTINATION.blue(), 40))
        self.setZValue(Z_DESTINATION)
        self.label = Label(f"D{ident}", 0.22 * CELL, style.DESTINATION, self)
        self.set_detail(True)

    def set_detail(self, fine: bool) -> None:
        super().set_detail(fine)
        self.setPen(pen(style.DESTINATION, (0.05 if fine else 0.12) * CELL, Qt.DashLine))
