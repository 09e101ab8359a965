"""The order editor: one row per order line (product, units, station), editable in place.

Orders and lines are added and removed with the buttons below the table.  The orders it
edits are those of an order book: the document's (every change an undoable edit), or,
during an online session, the orders written but not sent yet (Send gives them to the
solver, Discard drops them).  A line for a product that no shelf holds, or an order for a
picking station that does not exist, is tinted red with the reason in its tooltip.
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager
from dataclasses import dataclass
from typing import Any, Protocol

from PyQt5.QtCore import QModelIndex, Qt, pyqtSignal
from PyQt5.QtWidgets import (
    QAbstractItemView,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QStyledItemDelegate,
    QTableView,
    QVBoxLayout,
    QWidget,
)

from asprilo.model import Instance
from asprilo.simulate import Violation

from ..panels.dialogs import MAX_COUNT, spin
from ..panels.tables import PROBLEM, RowsModel
from ..state import order_edits
from ..state.edits import Edit, EditRefused

PRODUCT, UNITS, STATION = 1, 2, 3


@dataclass(frozen=True)
class OrderRow:
    order: int
    product: int | None  # None: the order has no line yet
    units: int | None
    station: int | None


class OrderBook(Protocol):
    """The orders the editor edits: their instance, how an edit is made, which orders it lists."""

    @property
    def instance(self) -> Instance: ...

    def perform(self, make: Callable[[], Edit]) -> bool: ...

    def group(self, text: str) -> AbstractContextManager: ...

    def shows(self, order: int) -> bool: ...


class OrderTable(RowsModel):
    """The book's orders as rows; edits go through the book (which may refuse them)."""

    columns = ("Order", "Product", "Units", "Station")

    def __init__(self, book: OrderBook, parent=None):
        super().__init__(parent)
        self.book = book
        self.rows: list[OrderRow] = []
        self.problems: dict[tuple[int, int | None], list[str]] = {}
        self.refresh()

    def refresh(self, violations: list[Violation] = ()) -> None:
        """Rows from the book's orders; problems from the instance's violations."""
        self.beginResetModel()
        self.rows = []
        orders = [order for order in self.book.instance.orders.values() if self.book.shows(order.id)]
        for order in sorted(orders, key=lambda o: o.id):
            lines = sorted(order.lines.items()) or [(None, None)]
            self.rows += [OrderRow(order.id, product, units, order.station) for product, units in lines]
        self.problems = {}
        for violation in violations:
            if violation.module != "instance" or not violation.check.startswith(("unknown", "order")):
                continue
            order = violation.params[0]
            product = violation.params[1] if violation.check == "unknownProduct" else None
            self.problems.setdefault((order, product), []).append(violation.message.removeprefix("instance: "))
        for row in self.rows:
            if row.product is None:
                self.problems.setdefault((row.order, None), []).append(f"order {row.order} has no lines yet")
        self.endResetModel()

    def row_problems(self, row: OrderRow) -> list[str]:
        return self.problems.get((row.order, row.product), []) + \
            (self.problems.get((row.order, None), []) if row.product is not None else [])

    # --- Qt's model interface (beyond RowsModel's) ------------------------------------------

    def flags(self, index: QModelIndex):
        flags = super().flags(index)
        return flags | Qt.ItemIsEditable if index.column() != 0 else flags

    def data(self, index: QModelIndex, role=Qt.DisplayRole) -> Any:
        if not index.isValid():
            return None
        row, column = self.rows[index.row()], index.column()
        value = (row.order, row.product, row.units, row.station)[column]
        problems = self.row_problems(row)
        if role == Qt.DisplayRole:
            if column == 0:
                return f"{row.order} \u26a0" if problems else str(row.order)
            if column == STATION:
                return "" if value is None else f"PS{value}"
            if column == UNITS and row.product is not None and value is None:
                return "–"
            return "" if value is None else str(value)
        if role == Qt.EditRole:
            return value or 0
        if role == Qt.BackgroundRole and problems:
            return PROBLEM
        if role == Qt.ToolTipRole and problems:
            return "\n".join(problems)
        if role == Qt.TextAlignmentRole:
            return int(Qt.AlignRight | Qt.AlignVCenter)
        return None

    def setData(self, index: QModelIndex, value: Any, role=Qt.EditRole) -> bool:
        if role != Qt.EditRole or not index.isValid():
            return False
        row, number = self.rows[index.row()], int(value or 0)
        instance, perform = self.book.instance, self.book.perform
        if index.column() == PRODUCT:
            if not number or number == row.product:
                return False
            return perform(lambda: order_edits.set_order_line(instance, row.order, number, row.units,
                                                              replaces=row.product))
        if index.column() == UNITS:
            if row.product is None:
                return perform(_refuse("choose the line's product first"))
            return perform(lambda: order_edits.set_order_line(instance, row.order, row.product, number or None))
        if index.column() == STATION:
            return perform(lambda: order_edits.set_order_station(instance, row.order, number or None))
        return False


def _refuse(reason: str) -> Callable[[], Edit]:
    def edit() -> Edit:
        raise EditRefused(reason)
    return edit


class _NumberDelegate(QStyledItemDelegate):
    """Spin boxes for ids and units; 0 shows as “–” (no quantity, no station)."""

    def createEditor(self, parent, option, index):
        box = spin(0, 0, MAX_COUNT, "–")
        box.setParent(parent)
        return box

    def setEditorData(self, editor, index) -> None:
        editor.setValue(int(index.data(Qt.EditRole) or 0))

    def setModelData(self, editor, model, index) -> None:
        editor.interpretText()
        model.setData(index, editor.value(), Qt.EditRole)


class OrderEditor(QWidget):
    """The orders table with buttons to add and remove orders and lines (and, for orders
    written during an online session, to send or discard them)."""

    send_clicked = pyqtSignal()
    discard_clicked = pyqtSignal()

    def __init__(self, book: OrderBook, parent=None):
        super().__init__(parent)
        self.book = book
        self.model = OrderTable(book, self)
        self.table = QTableView(self)
        self.table.setModel(self.model)
        self.table.setItemDelegate(_NumberDelegate(self.table))
        self.table.setSelectionBehavior(QAbstractItemView.SelectRows)
        self.table.setEditTriggers(QAbstractItemView.DoubleClicked | QAbstractItemView.EditKeyPressed
                                   | QAbstractItemView.AnyKeyPressed)
        self.table.verticalHeader().hide()
        self.table.verticalHeader().setDefaultSectionSize(22)
        self.table.horizontalHeader().setSectionResizeMode(QHeaderView.Stretch)
        buttons = QHBoxLayout()
        self.buttons = {}
        for name, text, slot in (("add_order", "Add order", self.add_order), ("add_line", "Add line", self.add_line),
                                 ("remove_line", "Remove line", self.remove_lines),
                                 ("remove_order", "Remove order", self.remove_orders)):
            button = QPushButton(text, self)
            button.clicked.connect(slot)
            buttons.addWidget(button)
            self.buttons[name] = button
        self.live = QHBoxLayout()
        self.note = QLabel("Orders written now go to the solver when sent.", self)
        self.note.setWordWrap(True)
        self.live.addWidget(self.note, 1)
        for name, text, signal in (("send", "Send to solver", self.send_clicked),
                                   ("discard", "Discard", self.discard_clicked)):
            button = QPushButton(text, self)
            button.clicked.connect(signal.emit)
            self.live.addWidget(button)
            self.buttons[name] = button
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.setSpacing(2)
        layout.addWidget(self.table)
        layout.addLayout(buttons)
        layout.addLayout(self.live)
        self.set_book(book, live=False)

    def set_book(self, book: OrderBook, live: bool) -> None:
        """Edit ``book``'s orders from now on; ``live``: orders of an online session, to send."""
        self.book = self.model.book = book
        for widget in (self.note, self.buttons["send"], self.buttons["discard"]):
            widget.setVisible(live)
        self.refresh()

    def refresh(self, violations: list[Violation] = ()) -> None:
        self.model.refresh(violations)

    def selected_rows(self) -> list[OrderRow]:
        rows = sorted({index.row() for index in self.table.selectionModel().selectedRows()})
        return [self.model.rows[row] for row in rows]

    # --- the buttons ---------------------------------------------------------------------------

    def add_order(self) -> bool:
        """A new order for the first picking station, with a line for the first product in stock."""
        instance = self.book.instance
        station = min(instance.stations, default=None)
        product = min(instance.products, default=None)
        units = self._default_units() if product is not None else None
        return self.book.perform(lambda: order_edits.add_order(instance, product, units, station))

    def add_line(self) -> bool:
        """A line for the next product the selected order (or the last order) lacks."""
        instance = self.book.instance
        rows = self.selected_rows()
        order = rows[0].order if rows else max((o for o in instance.orders if self.book.shows(o)), default=None)
        if order is None:
            return self.add_order()
        have = set(instance.orders[order].lines)
        product = next((p for p in sorted(instance.products) if p not in have), max(have | set(instance.products),
                                                                                       default=0) + 1)
        return self.book.perform(lambda: order_edits.set_order_line(instance, order, product, self._default_units()))

    def remove_lines(self) -> bool:
        instance = self.book.instance
        rows = [row for row in self.selected_rows() if row.product is not None]
        return self._perform_all([lambda row=row: order_edits.remove_order_line(instance, row.order, row.product)
                                  for row in rows], "remove order lines")

    def remove_orders(self) -> bool:
        instance = self.book.instance
        orders = sorted({row.order for row in self.selected_rows()})
        return self._perform_all([lambda order=order: order_edits.remove_order(instance, order) for order in orders],
                                 "remove orders")

    def _perform_all(self, makers: list[Callable[[], Edit]], text: str) -> bool:
        if len(makers) == 1:
            return self.book.perform(makers[0])
        with self.book.group(text):
            done = [self.book.perform(maker) for maker in makers]
        return any(done)

    def _default_units(self) -> int | None:
        """1 when the instance counts units (domain A), else no quantity."""
        stock = [u for p in self.book.instance.products.values() for u in p.stock.values()]
        return None if stock and all(u is None for u in stock) else 1
