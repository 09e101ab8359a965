"""The orders panel: per order line, units requested, delivered and still open; in an online
scenario, lines of orders not yet released say when they come (and are greyed)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from PyQt5.QtGui import QColor

from ..state.describe import units_text
from ..state.track import Track
from .tables import DONE, StepModel

#: the background of lines whose order is not released yet
TO_COME = QColor("#eeeeee")


@dataclass(frozen=True)
class OrderLine:
    order: int
    station: int | None
    product: int
    requested: int | None
    release: int = 0


class OrdersModel(StepModel):
    """One row per order line; finished lines and finished orders are marked."""

    columns = ("Order", "Station", "Product", "Requested", "Delivered", "Open", "Status")
    dynamic = (0, 4, 5, 6)

    def __init__(self, parent=None):
        super().__init__(parent)
        self._finished: tuple[int, set[int]] | None = None

    def build_rows(self, track: Track) -> list[OrderLine]:
        self._finished = None
        return [OrderLine(order.id, order.station, product, units, order.release or 0)
                for order in sorted(track.instance.orders.values(), key=lambda o: o.id)
                for product, units in sorted(order.lines.items())]

    def to_come(self, row: OrderLine) -> bool:
        """Whether the line's order is not released yet after the step shown (known after its release step)."""
        return self.step < row.release

    def line_done(self, row: OrderLine) -> bool:
        return (row.order, row.product) not in self.track.state(self.step).open_lines

    def missing(self, row: OrderLine) -> int | None:
        """Units still missing (0 when done; ``None`` for an open line without quantities)."""
        open_lines = self.track.state(self.step).open_lines
        return open_lines.get((row.order, row.product), 0)

    def order_done(self, order: int) -> bool:
        if self._finished is None or self._finished[0] != self.step:
            open_orders = {o for o, _p in self.track.state(self.step).open_lines}
            self._finished = (self.step, {row.order for row in self.rows} - open_orders)
        return order in self._finished[1]

    def value(self, row: OrderLine, column: int) -> Any:
        if column == 0:
            return row.order
        if column == 1:
            return row.station
        if column == 2:
            return row.product
        if column == 3:
            return row.requested
        missing = self.missing(row)
        if column == 4:
            if row.requested is None or missing is None:
                return None
            return row.requested - missing
        if column == 5:
            return missing
        if self.to_come(row):
            return f"released at {row.release}"
        return "done" if self.line_done(row) else "open"

    def text(self, row: OrderLine, column: int) -> str:
        if column == 0:
            return f"{row.order} \u2713" if self.order_done(row.order) else str(row.order)
        if column == 1:
            return "" if row.station is None else f"PS{row.station}"
        if column in (3, 4, 5):
            if column != 3 and row.requested is None:
                done = self.line_done(row)
                return ("\u2713" if done else "") if column == 4 else ("" if done else "open")
            return units_text(self.value(row, column))
        return super().text(row, column)

    def background(self, row: OrderLine) -> QColor | None:
        if self.to_come(row):
            return TO_COME
        if self.order_done(row.order):
            return DONE
        return DONE.lighter(104) if self.line_done(row) else None

    def bold(self, row: OrderLine) -> bool:
        return self.order_done(row.order)
