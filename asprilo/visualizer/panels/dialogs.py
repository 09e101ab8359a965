"""The viewer's dialogs: grid size, the products on a shelf, the generator's counts, the online
link, and the question before unsaved edits are dropped.

Each dialog is a plain QDialog with ``values()``; callers ``open()`` or ``exec_()`` it.
"""

from __future__ import annotations

from collections.abc import Callable

from PyQt5.QtWidgets import (
    QAbstractItemView,
    QCheckBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QMessageBox,
    QPushButton,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from ..state.document import INSTANCE, PLAN, Document

MAX_GRID = 500
MAX_COUNT = 100_000
NO_QUANTITY = "no quantity"


def spin(value: int, low: int, high: int, special: str | None = None) -> QSpinBox:
    """A spin box over ``low..high``; ``special`` is shown instead of ``low``."""
    box = QSpinBox()
    box.setRange(low, high)
    box.setValue(value)
    if special is not None:
        box.setSpecialValueText(special)
    return box


def confirm_discard(parent: QWidget, document: Document, save: Callable[[], bool] | None = None) -> bool:
    """Whether unsaved edits may go (asks when there are any).  With ``save`` the question
    offers Save as well (Save / Discard / Cancel): they may go once ``save()`` saved them."""
    if not document.modified:
        return True
    parts = [name for name, part in (("instance", INSTANCE), ("plan", PLAN)) if document.unsaved(part)]
    subject = "The instance and the plan have" if len(parts) == 2 else f"The {parts[0]} has"
    if save is None:
        answer = QMessageBox.question(parent, "asprilo viz", f"{subject} unsaved edits. Discard them?",
                                      QMessageBox.Discard | QMessageBox.Cancel, QMessageBox.Cancel)
        return answer == QMessageBox.Discard
    answer = QMessageBox.question(parent, "asprilo viz", f"{subject} unsaved edits. Save them?",
                                  QMessageBox.Save | QMessageBox.Discard | QMessageBox.Cancel, QMessageBox.Save)
    if answer == QMessageBox.Save:
        return save()
    return answer == QMessageBox.Discard


def _buttons(dialog: QDialog) -> QDialogButtonBox:
    buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel, dialog)
    buttons.accepted.connect(dialog.accept)
    buttons.rejected.connect(dialog.reject)
    return buttons


class SizeDialog(QDialog):
    """Width and height of the grid (a new instance, or resizing the current one)."""

    def __init__(self, title: str, width: int, height: int, note: str = "", parent: QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle(title)
        form = QFormLayout(self)
        self.width_box = spin(width, 1, MAX_GRID)
        self.height_box = spin(height, 1, MAX_GRID)
        form.addRow("Width (X, columns):", self.width_box)
        form.addRow("Height (Y, rows):", self.height_box)
        if note:
            label = QLabel(note)
            label.setWordWrap(True)
            form.addRow(label)
        form.addRow(_buttons(self))

    def values(self) -> tuple[int, int]:
        return self.width_box.value(), self.height_box.value()


class StockDialog(QDialog):
    """The products on one shelf and their units; rows can be added and removed."""

    def __init__(self, shelf: int, stock: dict[int, int | None], parent: QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle(f"Products on shelf {shelf}")
        layout = QVBoxLayout(self)
        self.table = QTableWidget(0, 2, self)
        self.table.setHorizontalHeaderLabels(["Product", "Units"])
        self.table.verticalHeader().hide()
        self.table.horizontalHeader().setSectionResizeMode(QHeaderView.Stretch)
        self.table.setSelectionBehavior(QAbstractItemView.SelectRows)
        for product, units in sorted(stock.items()):
            self.add_row(product, units)
        layout.addWidget(self.table)
        row = QHBoxLayout()
        add, remove = QPushButton("Add product"), QPushButton("Remove product")
        add.clicked.connect(lambda: self.add_row(max(self.stock(), default=0) + 1, 1))
        remove.clicked.connect(self.remove_selected)
        row.addWidget(add)
        row.addWidget(remove)
        row.addStretch(1)
        layout.addLayout(row)
        hint = QLabel(f"Units: 0 shows as “{NO_QUANTITY}” (a product listed without units, domains B, C, M).")
        hint.setWordWrap(True)
        layout.addWidget(hint)
        layout.addWidget(_buttons(self))
        self.resize(340, 320)

    def add_row(self, product: int, units: int | None) -> None:
        row = self.table.rowCount()
        self.table.insertRow(row)
        self.table.setCellWidget(row, 0, spin(product, 1, MAX_COUNT))
        self.table.setCellWidget(row, 1, spin(0 if units is None else units, 0, MAX_COUNT, NO_QUANTITY))
        self.table.setItem(row, 0, QTableWidgetItem())

    def remove_selected(self) -> None:
        for row in sorted({index.row() for index in self.table.selectedIndexes()}, reverse=True):
            self.table.removeRow(row)

    def stock(self) -> dict[int, int | None]:
        """Product -> units (``None``: no quantity); a product listed twice keeps its last row."""
        result = {}
        for row in range(self.table.rowCount()):
            units = self.table.cellWidget(row, 1).value()
            result[self.table.cellWidget(row, 0).value()] = units or None
        return result

    values = stock


#: the generator's counts the dialog offers: (option name, label, what the value means)
GENERATE_FIELDS = (
    ("robots", "Robots", "in total, those already placed included"),
    ("shelves", "Shelves", "in total"),
    ("stations", "Picking stations", "in total"),
    ("products", "Products", ""),
    ("units", "Product units", "in total, on all shelves"),
    ("orders", "Orders", ""),
)


class GenerateDialog(QDialog):
    """The generator's counts (totals: what the layout holds already counts) and the seed."""

    def __init__(self, counts: dict[str, int], seed: int, parent: QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle("Generate: fill this layout")
        form = QFormLayout(self)
        intro = QLabel("The generator keeps the floor and every object placed so far and adds "
                       "objects, products and orders up to these totals.")
        intro.setWordWrap(True)
        form.addRow(intro)
        self.boxes: dict[str, QSpinBox] = {}
        for name, label, tip in GENERATE_FIELDS:
            box = spin(counts.get(name, 0), 0, MAX_COUNT)
            box.setToolTip(tip)
            self.boxes[name] = box
            form.addRow(f"{label}:", box)
        self.lines = spin(1, 1, 100)
        form.addRow("Lines per order:", self.lines)
        self.reachable = QCheckBox("every shelf reachable from a highway without moving others")
        form.addRow(self.reachable)
        self.seed = spin(seed, 0, 2**31 - 1)
        form.addRow("Seed:", self.seed)
        form.addRow(_buttons(self))

    def values(self) -> dict:
        """Generator options by field name (zero counts left out), and the seed."""
        options = {name: box.value() for name, box in self.boxes.items() if box.value() > 0}
        if options.get("orders"):
            options["ol_min"] = options["ol_max"] = self.lines.value()
        if self.reachable.isChecked():
            options["reachable"] = True
        return {"options": options, "seed": self.seed.value()}


class ConnectDialog(QDialog):
    """Where the solver (and, optionally, the simulator) of the online link listen."""

    def __init__(self, host: str, solver_port: int, simulator_port: int | None,
                 parent: QWidget | None = None):
        super().__init__(parent)
        self.setWindowTitle("Connect to a solver")
        form = QFormLayout(self)
        self.host = QLineEdit(host)
        form.addRow("Host:", self.host)
        self.solver_port = spin(solver_port, 1, 65535)
        form.addRow("Solver port:", self.solver_port)
        self.use_simulator = QCheckBox("also a simulator (the world and orders arriving over time)")
        self.use_simulator.setChecked(simulator_port is not None)
        form.addRow(self.use_simulator)
        self.simulator_port = spin(simulator_port or solver_port + 1, 1, 65535)
        form.addRow("Simulator port:", self.simulator_port)
        self.use_simulator.toggled.connect(self.simulator_port.setEnabled)
        self.simulator_port.setEnabled(self.use_simulator.isChecked())
        note = QLabel("Start them with  asprilo serve solver --port N  and  "
                      "asprilo serve simulator INSTANCE --port M.  Without a simulator the solver "
                      "plans for the instance shown.")
        note.setWordWrap(True)
        form.addRow(note)
        form.addRow(_buttons(self))

    def values(self) -> tuple[str, int, int | None]:
        simulator = self.simulator_port.value() if self.use_simulator.isChecked() else None
        return self.host.text().strip() or "127.0.0.1", self.solver_port.value(), simulator
