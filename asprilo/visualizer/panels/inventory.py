"""The inventory panel: units of each product on each shelf, now and initially."""

from __future__ import annotations

from typing import Any

from PyQt5.QtGui import QColor

from ..state.describe import units_text
from ..state.track import Track
from .tables import CHANGED, StepModel


class InventoryModel(StepModel):
    """One row per (shelf, product); rows whose stock changed are tinted."""

    columns = ("Shelf", "Product", "Now", "Initially")
    dynamic = (2,)

    def build_rows(self, track: Track) -> list[tuple[int, int, int | None]]:
        return [(shelf, product, units)
                for shelf, stock in sorted(track.instance.shelf_stock().items())
                for product, units in sorted(stock.items())]

    def now(self, row: tuple[int, int, int | None]) -> int | None:
        shelf, product, initially = row
        return self.track.state(self.step).stock.get((shelf, product), initially)

    def value(self, row: tuple[int, int, int | None], column: int) -> Any:
        shelf, product, initially = row
        return (shelf, product, self.now(row) if column == 2 else None, initially)[column]

    def text(self, row: tuple[int, int, int | None], column: int) -> str:
        return units_text(self.value(row, column)) if column >= 2 else str(row[column])

    def background(self, row: tuple[int, int, int | None]) -> QColor | None:
        return CHANGED if self.now(row) != row[2] else None
