"""The warehouse scene: the floor as one background, and an item per robot, shelf,
station and destination, built from an :class:`Instance`.

The floor (nodes, highways, missing nodes) is painted by the scene's background, not by
thousands of items; views cache it.  Objects can be added and removed one by one, so
the scene can back an editor as well as the viewer.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator

import numpy as np
from PyQt5.QtCore import QRectF, Qt
from PyQt5.QtGui import QImage, QPainter
from PyQt5.QtWidgets import QGraphicsScene

from asprilo.model import Cell, Destination, Instance, PickingStation, Robot, Shelf

from . import style
from .items import DestinationItem, ObjectItem, RobotItem, ShelfItem, ShelfLayer, StationItem
from .style import CELL

MISSING, STORAGE, HIGHWAY = 0, 1, 2
#: id labels smaller than this many screen pixels are hidden (they could not be read)
MIN_LABEL_PX = 7.0
_ITEMS = {"robot": RobotItem, "shelf": ShelfItem, "station": StationItem, "destination": DestinationItem}


class FloorPicture:
    """The floor drawn as the scene's background: its cells by kind (missing, storage,
    highway) over its bounding box, as tiles or, when cells are tiny, one pixel each."""

    def __init__(self, nodes: Iterable[Cell], highways: Iterable[Cell]):
        nodes, highways = _cells(nodes), _cells(highways)
        both = np.concatenate([nodes, highways])
        width, height = (both.max(axis=0).tolist() if len(both) else (0, 0))
        self.kinds = np.full((height, width), MISSING, dtype=np.uint8)
        self.kinds[nodes[:, 1] - 1, nodes[:, 0] - 1] = STORAGE
        self.kinds[highways[:, 1] - 1, highways[:, 0] - 1] = HIGHWAY
        self.rect = QRectF(0, 0, width * CELL, height * CELL)
        self.image = self._image()

    @property
    def size(self) -> Cell:
        height, width = self.kinds.shape
        return width, height

    def _image(self) -> QImage:
        """One pixel per cell, for drawing the floor when cells are tiny."""
        palette = np.array([style.MISSING_NODE.rgba(), style.STORAGE.rgba(), style.HIGHWAY.rgba()],
                           dtype=np.uint32)
        pixels = np.ascontiguousarray(palette[self.kinds])
        height, width = self.kinds.shape
        if not pixels.size:
            return QImage()
        return QImage(pixels.data, width, height, 4 * width, QImage.Format_ARGB32).copy()

    def paint(self, painter: QPainter, exposed: QRectF) -> None:
        """Paint the part of the floor inside ``exposed`` (scene coordinates)."""
        if self.rect.isEmpty():
            return
        pixels_per_cell = abs(painter.worldTransform().m11()) * CELL
        if pixels_per_cell < style.FINE_DETAIL_PX:
            painter.drawImage(self.rect, self.image)
            return
        width, height = self.size
        x0, x1 = max(0, math.floor(exposed.left() / CELL)), min(width, math.ceil(exposed.right() / CELL))
        y0, y1 = max(0, math.floor(exposed.top() / CELL)), min(height, math.ceil(exposed.bottom() / CELL))
        if x0 >= x1 or y0 >= y1:
            return
        painter.save()
        painter.setPen(Qt.NoPen)
        painter.fillRect(QRectF(x0 * CELL, y0 * CELL, (x1 - x0) * CELL, (y1 - y0) * CELL), style.GRID_LINE)
        window = self.kinds[y0:y1, x0:x1]
        gap = 0.035 * CELL
        for kind, colour, inset in ((MISSING, style.MISSING_NODE, 0.0), (STORAGE, style.STORAGE, gap),
                                    (HIGHWAY, style.HIGHWAY, gap)):
            ys, xs = np.nonzero(window == kind)
            if not len(xs):
                continue
            size = CELL - 2 * inset
            painter.setBrush(colour)
            painter.drawRects([QRectF((x0 + x) * CELL + inset, (y0 + y) * CELL + inset, size, size)
                               for x, y in zip(xs.tolist(), ys.tolist(), strict=True)])
        painter.restore()


def _cells(cells: Iterable[Cell]) -> np.ndarray:
    """Cells as an (n, 2) array, those with coordinates below 1 left out (not drawable)."""
    array = np.array(list(cells), dtype=np.int64).reshape(-1, 2)
    return array[(array >= 1).all(axis=1)]


class WarehouseScene(QGraphicsScene):
    """Floor, robots, shelves, picking stations and destinations of one instance."""

    def __init__(self, instance: Instance, parent=None):
        super().__init__(parent)
        self.setItemIndexMethod(QGraphicsScene.NoIndex)  # many items move every frame
        self.setBackgroundBrush(style.BACKGROUND)
        self.robots: dict[int, RobotItem] = {}
        self.shelves: dict[int, ShelfItem] = {}
        self.stations: dict[int, StationItem] = {}
        self.destinations: dict[int, DestinationItem] = {}
        self.fine = True
        self.labels_on = True
        self.label_cell_px = math.inf  # the cell size in pixels the labels are shown for
        self._labels_shown = {"robot": True, "shelf": False, "station": True, "destination": True}
        self.shelf_layer = ShelfLayer()  # resting shelves at coarse detail
        self.shelf_layer.setVisible(False)
        self.addItem(self.shelf_layer)
        self._extra_cells: set[Cell] = set()
        self.set_floor(instance.nodes.values(), instance.highways.values())
        for station in instance.stations.values():
            self.add_station(station)
        for destination in instance.destinations.values():
            self.add_destination(destination)
        for shelf in instance.shelves.values():
            self.add_shelf(shelf)
        for robot in instance.robots.values():
            self.add_robot(robot)

    # --- the floor ----------------------------------------------------------------------

    def set_floor(self, nodes: Iterable[Cell], highways: Iterable[Cell]) -> None:
        self.floor = FloorPicture(nodes, highways)
        self._update_rect()
        self.invalidate(self.sceneRect(), QGraphicsScene.BackgroundLayer)

    def drawBackground(self, painter: QPainter, rect: QRectF) -> None:
        painter.fillRect(rect, style.BACKGROUND)
        self.floor.paint(painter, rect)

    def include_cells(self, cells: Iterable[Cell]) -> None:
        """Make room for objects off the floor (robots of invalid plans drive there)."""
        self._extra_cells.update(cells)
        self._update_rect()

    def picture_rect(self, margin: float = 0.25) -> QRectF:  # images.PICTURE_MARGIN
        """The floor and every object position, with ``margin`` cells around: what exports show."""
        width, height = self.floor.size
        if not width and not self._extra_cells:  # no floor: whatever is drawn
            bounds = self.itemsBoundingRect()
            return bounds.adjusted(-margin * CELL, -margin * CELL, margin * CELL, margin * CELL)
        xs = [1, width] + [x for x, _ in self._extra_cells]
        ys = [1, height] + [y for _, y in self._extra_cells]
        left, top = (min(xs) - 1 - margin) * CELL, (min(ys) - 1 - margin) * CELL
        return QRectF(left, top, (max(xs) + margin) * CELL - left, (max(ys) + margin) * CELL - top)

    def _update_rect(self) -> None:
        self.setSceneRect(self.picture_rect(margin=0.5))

    # --- objects ------------------------------------------------------------------------

    def add_robot(self, robot: Robot) -> RobotItem:
        item = RobotItem(robot.id, style.robot_colour(robot.id - 1))
        return self._place(self.robots, item, robot.at)

    def add_shelf(self, shelf: Shelf) -> ShelfItem:
        item = self._place(self.shelves, ShelfItem(shelf.id), shelf.at)
        self.refresh_shelf_layer()
        return item

    def add_station(self, station: PickingStation) -> StationItem:
        return self._place(self.stations, StationItem(station.id), station.at)

    def add_destination(self, destination: Destination) -> DestinationItem:
        return self._place(self.destinations, DestinationItem(destination.id), destination.at)

    def _place(self, table: dict, item, cell: Cell):
        if item.ident in table:
            self.removeItem(table.pop(item.ident))
        if not self.fine:
            item.set_detail(False)
        item.set_label_shown(self._labels_shown[item.kind])
        item.setPos(style.centre(cell))
        table[item.ident] = item
        self.addItem(item)
        return item

    def table(self, kind: str) -> dict[int, ObjectItem]:
        """The items of one kind of object (robot, shelf, station, destination) by id."""
        return {"robot": self.robots, "shelf": self.shelves, "station": self.stations,
                "destination": self.destinations}[kind]

    def remove(self, kind: str, ident: int) -> None:
        """Remove the item of an object (``kind``: robot, shelf, station, destination)."""
        self.removeItem(self.table(kind).pop(ident))
        if kind == "shelf":
            self.refresh_shelf_layer()

    def objects(self) -> Iterator[ObjectItem]:
        for table in (self.stations, self.destinations, self.shelves, self.robots):
            yield from table.values()

    def show_labels(self, on: bool, cell_px: float) -> None:
        """Show the id labels (``on``) of the kinds of objects whose labels can be read when
        cells are ``cell_px`` screen pixels wide."""
        self.labels_on, self.label_cell_px = on, cell_px
        for kind, item_class in _ITEMS.items():
            shown = on and item_class.label_size * cell_px >= MIN_LABEL_PX
            if shown != self._labels_shown[kind]:
                self._labels_shown[kind] = shown
                for item in self.table(kind).values():
                    item.set_label_shown(shown)

    def set_detail(self, fine: bool) -> None:
        """Full look (outlines) or the cheap one for tiny cells."""
        if fine == self.fine:
            return
        self.fine = fine
        for item in self.objects():
            item.set_detail(fine)
        self.shelf_layer.setVisible(not fine)
        self.refresh_shelf_layer()

    def refresh_shelf_layer(self) -> None:
        """Redraw the resting shelves' layer (after shelves were picked up or put down)."""
        if not self.fine:
            self.shelf_layer.show_shelves(self.shelves.values())
