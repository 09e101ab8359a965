"""Dockable side panels: tables that follow the step shown.

Each panel is a :class:`StepModel` (what the rows and columns say at a step) shown by a
:class:`TablePanel` (filter box, sortable table).  Changing the step only tells the
table that some columns changed: the view asks for the rows it shows, so panels stay
fast with thousands of rows.
"""

from __future__ import annotations

import textwrap
from html import escape
from typing import Any

from PyQt5.QtCore import QAbstractTableModel, QModelIndex, QSortFilterProxyModel, Qt, pyqtSignal
from PyQt5.QtGui import QColor, QFont
from PyQt5.QtWidgets import QAbstractItemView, QHeaderView, QLineEdit, QTableView, QVBoxLayout, QWidget

from ..state.track import Track

SORT_ROLE = Qt.UserRole
DONE = QColor("#d3f9d8")       # finished order lines, orders
CURRENT = QColor("#d0ebff")    # the step shown
CHANGED = QColor("#fff3bf")    # stock that differs from the initial one
PROBLEM = QColor("#ffe3e3")    # violations
FADED = QColor("#868e96")      # what lies in the past
_TOP = QModelIndex()           # the parent of a table's rows
MAX_COLUMN = 150               # pixels
TIP_CHARACTERS = 72            # the longest line of a wrapped tooltip


def plain_tip(text: str) -> str:
    """``text`` shown as it is in a tooltip: Qt takes text that looks like HTML (an ``&lt;`` or a
    tag such as ``<b>`` in its first line) for rich text and would drop the tags, so such
    text is escaped."""
    if not Qt.mightBeRichText(text):  # type: ignore[attr-defined]  # not in PyQt5's stubs
        return text
    return "<p style='white-space:pre-wrap'>" + escape(text) + "</p>"


def wrapped_tip(text: str, width: int = TIP_CHARACTERS) -> str:
    """``text`` as a tooltip of lines of at most ``width`` characters (a long sentence stays
    on the screen: Qt shows a plain tooltip on one line however long it is)."""
    return plain_tip("\n".join(textwrap.wrap(text, width, break_long_words=False, break_on_hyphens=False)))


class RowsModel(QAbstractTableModel):
    """A table of ``self.rows`` under the headers ``columns``."""

    columns: tuple[str, ...] = ()
    rows: list[Any]

    def rowCount(self, parent: QModelIndex = _TOP) -> int:
        return 0 if parent.isValid() else len(self.rows)

    def columnCount(self, parent: QModelIndex = _TOP) -> int:
        return 0 if parent.isValid() else len(self.columns)

    def headerData(self, section: int, orientation, role=Qt.DisplayRole):
        if orientation == Qt.Horizontal and role == Qt.DisplayRole:
            return self.columns[section]
        return None


class StepModel(RowsModel):
    """Rows of one kind of object; ``value``/``text`` say what a cell shows at ``self.step``."""

    #: columns whose contents depend on the step
    dynamic: tuple[int, ...] = ()
    #: column -> width in pixels, for columns whose texts change with the step
    widths: dict[int, int] = {}
    #: ``tooltip`` gives rich text (escaped where it shows data); otherwise tooltips are plain text
    rich_tooltips = False

    def __init__(self, parent=None):
        super().__init__(parent)
        self.track: Track | None = None
        self.step = 0
        self.rows: list[Any] = []

    def set_track(self, track: Track | None) -> None:
        self.beginResetModel()
        self.track = track
        self.step = 0
        self.rows = self.build_rows(track) if track is not None else []
        self.endResetModel()

    def show_step(self, step: int) -> None:
        self.step = step
        if self.rows:
            first = min(self.dynamic, default=0)
            self.dataChanged.emit(self.index(0, first), self.index(len(self.rows) - 1, len(self.columns) - 1))

    # --- what subclasses define -------------------------------------------------------------

    def build_rows(self, track: Track) -> list[Any]:
        raise NotImplementedError

    def value(self, row: Any, column: int) -> Any:
        """The cell's value (sorts by it); ``None`` shows as empty."""
        raise NotImplementedError

    def text(self, row: Any, column: int) -> str:
        value = self.value(row, column)
        return "" if value is None else str(value)

    def background(self, row: Any) -> QColor | None:
        return None

    def foreground(self, row: Any) -> QColor | None:
        return None

    def bold(self, row: Any) -> bool:
        return False

    def tooltip(self, row: Any, column: int) -> str | None:
        return None

    # --- Qt's model interface (beyond RowsModel's) ------------------------------------------

    def data(self, index: QModelIndex, role=Qt.DisplayRole):
        if not index.isValid():
            return None
        row = self.rows[index.row()]
        if role == Qt.DisplayRole:
            return self.text(row, index.column())
        if role == SORT_ROLE:
            value = self.value(row, index.column())
            return -1 if value is None else value
        if role == Qt.BackgroundRole:
            return self.background(row)
        if role == Qt.ForegroundRole:
            return self.foreground(row)
        if role == Qt.FontRole and self.bold(row):
            font = QFont()
            font.setBold(True)
            return font
        if role == Qt.ToolTipRole:
            tip = self.tooltip(row, index.column()) or self.text(row, index.column()) or None
            return tip if tip is None or self.rich_tooltips else plain_tip(tip)
        if role == Qt.TextAlignmentRole and isinstance(self.value(row, index.column()), int):
            return int(Qt.AlignRight | Qt.AlignVCenter)
        return None


class TablePanel(QWidget):
    """A filter box over a sortable table of a :class:`StepModel`; reports activated rows."""

    row_activated = pyqtSignal(object)     # the model's row object

    def __init__(self, model: StepModel, filter_hint: str = "filter", parent=None):
        super().__init__(parent)
        self.model = model
        self.proxy = QSortFilterProxyModel(self)
        self.proxy.setSourceModel(model)
        self.proxy.setSortRole(SORT_ROLE)
        self.proxy.setFilterKeyColumn(-1)
        self.proxy.setFilterCaseSensitivity(Qt.CaseInsensitive)
        self.proxy.setDynamicSortFilter(False)
        self.filter = QLineEdit(self)
        self.filter.setPlaceholderText(filter_hint)
        self.filter.setClearButtonEnabled(True)
        self.filter.textChanged.connect(self.proxy.setFilterFixedString)
        self.table = QTableView(self)
        self.table.setModel(self.proxy)
        self.table.setSortingEnabled(True)
        self.table.sortByColumn(-1, Qt.AscendingOrder)
        self.table.setSelectionBehavior(QAbstractItemView.SelectRows)
        self.table.setEditTriggers(QAbstractItemView.NoEditTriggers)
        self.table.setAlternatingRowColors(False)
        self.table.setWordWrap(False)
        self.table.verticalHeader().hide()
        self.table.verticalHeader().setDefaultSectionSize(22)
        self.table.horizontalHeader().setSectionResizeMode(QHeaderView.Interactive)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.horizontalHeader().setResizeContentsPrecision(20)  # size columns by the first rows only
        self.table.clicked.connect(self._activated)
        self.table.activated.connect(self._activated)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.setSpacing(2)
        layout.addWidget(self.filter)
        layout.addWidget(self.table)

    def set_track(self, track: Track | None) -> None:
        self.model.set_track(track)
        self.fit_columns()

    def fit_columns(self) -> None:
        """Columns as wide as their contents and title (not the sort mark), at most
        ``MAX_COLUMN`` pixels: longer texts are cut short, the tooltip shows them whole."""
        header, metrics = self.table.horizontalHeader(), self.table.horizontalHeader().fontMetrics()
        fixed = self.model.widths
        for column, title in enumerate(self.model.columns):
            width = max(self.table.sizeHintForColumn(column), metrics.horizontalAdvance(title) + 14)
            header.resizeSection(column, fixed.get(column, min(width, MAX_COLUMN)))

    def show_step(self, step: int) -> None:
        self.model.show_step(step)
        self.table.viewport().update()

    def source_row(self, proxy_row: int) -> Any:
        return self.model.rows[self.proxy.mapToSource(self.proxy.index(proxy_row, 0)).row()]

    def texts(self) -> list[list[str]]:
        """What the table shows, row by row (in its current order and filter)."""
        return [[self.proxy.index(r, c).data() for c in range(self.proxy.columnCount())]
                for r in range(self.proxy.rowCount())]

    def scroll_to_source_row(self, row: int) -> None:
        index = self.proxy.mapFromSource(self.model.index(row, 0))
        if index.isValid():
            self.table.scrollTo(index, QAbstractItemView.PositionAtCenter)

    def _activated(self, index) -> None:
        if index.isValid():
            self.row_activated.emit(self.source_row(index.row()))
