"""The order editor: one row per order line (product, units, station), editable in place.

Orders and lines are added and removed with the buttons below the table; every change is
an undoable edit of the document.  A line for a product that no shelf holds, or an order
for a picking station that does not exist, is tinted red with the reason in its tooltip.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from PyQt5.QtCore import QModelIndex, Qt
from PyQt5.QtWidgets import (
    QAbstractItemView,
    QHBoxLayout,
    QHeaderView,
    QPushButton,
    QStyledItemDelegate,
    QTableView,
    QVBoxLayout,
    QWidget,
)

from asprilo.simulate import Violation

from . import edits
from .dialogs import MAX_COUNT, spin
from .document import Document
from .edits import Edit, EditRefused
from .tables import PROBLEM, RowsModel

PRODUCT, UNITS, STATION = 1, 2, 3


@dataclass(frozen=True)
class OrderRow:
    order: int
    product: int | None  # None: the order has no line yet
    units: int | None
    station: int | None


class OrderTable(RowsModel):
    """The document's orders as rows; edits go through ``perform`` (which may refuse them)."""

    columns = ("Order", "Product", "Units", "Station")

    def __init__(self, document: Document, perform: Callable[[Callable[[], Edit]], bool], parent=None):
        super().__init__(parent)
        self.document = document
        self.perform = perform
        self.rows: list[OrderRow] = []
        self.problems: dict[tuple[int, int | None], list[str]] = {}
        self.refresh()

    def refresh(self, violations: list[Violation] = ()) -> None:
        """Rows from the document's orders; problems from the instance's violations."""
        self.beginResetModel()
        self.rows = []
        for order in sorted(self.document.instance.orders.values(), key=lambda o: o.id):
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
        instance = self.document.instance
        if index.column() == PRODUCT:
            if not number or number == row.product:
                return False
            return self.perform(lambda: edits.set_order_line(instance, row.order, number, row.units,
                                                              replaces=row.product))
        if index.column() == UNITS:
            if row.product is None:
                return self.perform(_refuse("choose the line's product first"))
            return self.perform(lambda: edits.set_order_line(instance, row.order, row.product, number or None))
        if index.column() == STATION:
            return self.perform(lambda: edits.set_order_station(instance, row.order, number or None))
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
    """The orders table with buttons to add and remove orders and lines."""

    def __init__(self, document: Document, perform: Callable[[Callable[[], Edit]], bool], parent=None):
        super().__init__(parent)
        self.document = document
        self.perform = perform
        self.model = OrderTable(document, perform, self)
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
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.setSpacing(2)
        layout.addWidget(self.table)
        layout.addLayout(buttons)

    def refresh(self, violations: list[Violation] = ()) -> None:
        self.model.refresh(violations)

    def selected_rows(self) -> list[OrderRow]:
        rows = sorted({index.row() for index in self.table.selectionModel().selectedRows()})
        return [self.model.rows[row] for row in rows]

    # --- the buttons ---------------------------------------------------------------------------

    def add_order(self) -> bool:
        """A new order for the first picking station, with a line for the first product in stock."""
        instance = self.document.instance
        station = min(instance.stations, default=None)
        product = min(instance.products, default=None)
        units = self._default_units() if product is not None else None
        return self.perform(lambda: edits.add_order(instance, product, units, station))

    def add_line(self) -> bool:
        """A line for the next product the selected order (or the last order) lacks."""
        instance = self.document.instance
        rows = self.selected_rows()
        order = rows[0].order if rows else max(instance.orders, default=None)
        if order is None:
            return self.add_order()
        have = set(instance.orders[order].lines)
        product = next((p for p in sorted(instance.products) if p not in have), max(have | set(instance.products),
                                                                                       default=0) + 1)
        return self.perform(lambda: edits.set_order_line(instance, order, product, self._default_units()))

    def remove_lines(self) -> bool:
        instance = self.document.instance
        rows = [row for row in self.selected_rows() if row.product is not None]
        return self._perform_all([lambda row=row: edits.remove_order_line(instance, row.order, row.product)
                                  for row in rows], "remove order lines")

    def remove_orders(self) -> bool:
        instance = self.document.instance
        orders = sorted({row.order for row in self.selected_rows()})
        return self._perform_all([lambda order=order: edits.remove_order(instance, order) for order in orders],
                                 "remove orders")

    def _perform_all(self, makers: list[Callable[[], Edit]], text: str) -> bool:
        if len(makers) == 1:
            return self.perform(makers[0])
        with self.document.history.group(text):
            done = [self.perform(maker) for maker in makers]
        return any(done)

    def _default_units(self) -> int | None:
        """1 when the instance counts units (domain A), else no quantity."""
        stock = [u for p in self.document.instance.products.values() for u in p.stock.values()]
        return None if stock and all(u is None for u in stock) else 1
