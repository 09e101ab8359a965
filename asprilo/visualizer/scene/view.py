"""The warehouse view: zoom (wheel, keys), pan (drag), fit to window, hover details, clicks."""

from __future__ import annotations

from collections.abc import Callable

from PyQt5.QtCore import QEvent, QPoint, QPointF, Qt, pyqtSignal
from PyQt5.QtGui import QPainter
from PyQt5.QtWidgets import QGraphicsView, QToolTip

from . import style
from .items import ObjectItem
from .style import CELL

ZOOM_STEP = 1.25
MIN_PIXELS_PER_CELL, MAX_PIXELS_PER_CELL = 1.0, 400.0
_KIND_ORDER = {"robot": 0, "shelf": 1, "station": 2, "destination": 3}

#: (scene point, objects under it) -> rich text for the tooltip, or None
Describer = Callable[[QPointF, list], "str | None"]


class WarehouseView(QGraphicsView):
    """Shows a :class:`WarehouseScene`; ``clicked`` reports the objects under a click."""

    clicked = pyqtSignal(list, object)      # [(kind, ident)], Qt.KeyboardModifiers
    zoom_changed = pyqtSignal(float)        # screen pixels per cell

    def __init__(self, parent=None):
        super().__init__(parent)
        self.setRenderHints(QPainter.Antialiasing | QPainter.TextAntialiasing)
        self.setCacheMode(QGraphicsView.CacheBackground)
        self.setViewportUpdateMode(QGraphicsView.FullViewportUpdate)
        self.setOptimizationFlags(QGraphicsView.DontSavePainterState)
        self.setDragMode(QGraphicsView.ScrollHandDrag)
        self.setTransformationAnchor(QGraphicsView.AnchorUnderMouse)
        self.setResizeAnchor(QGraphicsView.AnchorViewCenter)
        self.setAcceptDrops(False)  # files dropped here go to the main window
        self.viewport().setAcceptDrops(False)
        self.describe: Describer | None = None
        self._press: QPoint | None = None
        self._fitting = True  # keep fitting to the window until the user zooms

    @property
    def pixels_per_cell(self) -> float:
        return abs(self.transform().m11()) * CELL

    # --- zoom ---------------------------------------------------------------------------

    def zoom_by(self, factor: float) -> None:
        target = min(max(self.pixels_per_cell * factor, MIN_PIXELS_PER_CELL), MAX_PIXELS_PER_CELL)
        factor = target / self.pixels_per_cell
        self._fitting = False
        self.scale(factor, factor)
        self._zoomed()

    def zoom_in(self) -> None:
        self.zoom_by(ZOOM_STEP)

    def zoom_out(self) -> None:
        self.zoom_by(1 / ZOOM_STEP)

    def fit(self) -> None:
        """Show the whole warehouse."""
        if self.scene() is None:
            return
        self._fitting = True
        self.fitInView(self.scene().sceneRect(), Qt.KeepAspectRatio)
        self._zoomed()

    def centre_on_cell(self, cell: tuple[int, int]) -> None:
        self.centerOn(style.centre(cell))

    def _zoomed(self) -> None:
        fine = self.pixels_per_cell >= style.FINE_DETAIL_PX
        self.setRenderHint(QPainter.Antialiasing, fine)
        if self.scene() is not None:
            self.scene().set_detail(fine)
        self.resetCachedContent()
        self.zoom_changed.emit(self.pixels_per_cell)

    def wheelEvent(self, event) -> None:
        steps = event.angleDelta().y() / 120.0
        if steps:
            self.zoom_by(ZOOM_STEP ** steps)

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        if self._fitting:
            self.fit()

    # --- objects under the mouse ------------------------------------------------------------

    def objects_at(self, position: QPoint) -> list[tuple[str, int]]:
        """``(kind, ident)`` of the objects under a viewport position, robots first."""
        found = []
        for item in self.items(position):
            while item.parentItem() is not None:
                item = item.parentItem()
            if isinstance(item, ObjectItem) and (item.kind, item.ident) not in found:
                found.append((item.kind, item.ident))
        return sorted(found, key=lambda object_: _KIND_ORDER[object_[0]])

    def viewportEvent(self, event) -> bool:
        if event.type() == QEvent.ToolTip and self.describe is not None:
            text = self.describe(self.mapToScene(event.pos()), self.objects_at(event.pos()))
            if text:
                QToolTip.showText(event.globalPos(), text, self.viewport())
            else:
                QToolTip.hideText()
            return True
        return super().viewportEvent(event)

    def mousePressEvent(self, event) -> None:
        self._press = event.pos() if event.button() == Qt.LeftButton else None
        super().mousePressEvent(event)

    def mouseReleaseEvent(self, event) -> None:
        super().mouseReleaseEvent(event)
        if self._press is not None and (event.pos() - self._press).manhattanLength() <= 4:
            self.clicked.emit(self.objects_at(event.pos()), event.modifiers())
        self._press = None
