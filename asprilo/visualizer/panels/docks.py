"""The side panels in their docks: orders, the online figures, inventory, robots, plan and
violations, following the state's track, step and selection."""

from __future__ import annotations

from PyQt5.QtCore import QObject, Qt
from PyQt5.QtWidgets import QDockWidget, QMainWindow, QMenu

from asprilo.simulate import Violation

from ..state.viewer import ViewerState
from .inventory import InventoryModel
from .online_figures import OnlineFigures
from .orders import OrdersModel
from .plan_list import PlanModel
from .robot_list import RobotsModel
from .tables import TablePanel
from .violation_list import ViolationsModel

#: name -> (dock title, filter hint)
PANELS = {"orders": ("Orders", "filter orders"), "inventory": ("Inventory", "filter shelves, products"),
          "robots": ("Robots", "filter robots"), "plan": ("Plan", "filter actions"),
          "violations": ("Violations", "filter violations")}
_MODELS = {"orders": OrdersModel, "inventory": InventoryModel, "robots": RobotsModel, "plan": PlanModel,
           "violations": ViolationsModel}


class Panels(QObject):
    """One :class:`TablePanel` per kind of row, each in a dock of ``window``."""

    def __init__(self, state: ViewerState, window: QMainWindow, menu: QMenu):
        super().__init__(window)
        self.state, self.menu, self.window = state, menu, window
        self.tables = {name: TablePanel(_MODELS[name](), hint) for name, (_title, hint) in PANELS.items()}
        self.docks: dict[str, QDockWidget] = {}
        for name, (title, _hint) in PANELS.items():
            beside = {"inventory": "orders", "plan": "robots", "violations": "plan"}.get(name)
            self.add_dock(name, title, self.tables[name], self.docks[beside] if beside else None)
        self.online = OnlineFigures()
        self.add_dock("online", "Online", self.online, self.docks["orders"])
        self.docks["orders"].raise_()
        self.docks["robots"].raise_()
        self.tables["plan"].row_activated.connect(lambda action: state.seek(action.step))
        self.tables["robots"].table.selectionModel().selectionChanged.connect(self._robots_picked)
        state.shown.connect(lambda _keep: self._show_track())
        state.track_changed.connect(lambda _change: self._show_track())
        state.step_changed.connect(self._show_step)
        state.selection.changed.connect(self._show_selection)
        state.checked.connect(self._show_report)

    def add_dock(self, name: str, title: str, widget, beside: QDockWidget | None = None) -> QDockWidget:
        """Put ``widget`` in a dock on the right (a tab ``beside`` another), listed in View > Panels."""
        dock = QDockWidget(title, self.window)
        dock.setObjectName(f"dock_{name}")
        dock.setWidget(widget)
        self.window.addDockWidget(Qt.RightDockWidgetArea, dock)
        if beside is not None:
            self.window.tabifyDockWidget(beside, dock)
        self.menu.addAction(dock.toggleViewAction())
        self.docks[name] = dock
        return dock

    def __getitem__(self, name: str) -> TablePanel:
        return self.tables[name]

    def _show_track(self) -> None:
        track = self.state.track
        for panel in self.tables.values():
            panel.set_track(track)
            panel.show_step(self.state.step)
        self.online.set_track(track)
        self.online.show_step(self.state.step)
        self.docks["violations"].setWindowTitle(f"Violations ({len(track.violations)})" if track else "Violations")
        self._show_selection()

    def _show_step(self, step: int) -> None:
        for panel in self.tables.values():
            panel.show_step(step)
        self.online.show_step(step)
        plan = self.tables["plan"]
        row = plan.model.first_row(step) if self.state.track else None
        if row is not None and self.docks["plan"].isVisible():
            plan.scroll_to_source_row(row)

    def _show_report(self, violations: list[Violation]) -> None:
        """The ASP checker's violations instead of the replay's, until the next change."""
        panel = self.tables["violations"]
        panel.model.set_rows(violations)
        panel.fit_columns()
        self.docks["violations"].setWindowTitle(f"Violations — ASP checker ({len(violations)})")
        self.docks["violations"].raise_()

    # --- the robots panel and the selection ------------------------------------------------------

    def _show_selection(self) -> None:
        panel, track = self.tables["robots"], self.state.track
        selection = panel.table.selectionModel()
        selection.blockSignals(True)
        panel.table.clearSelection()
        for robot in self.state.selection.robots:
            if track is not None and robot in track.robot_index:
                index = panel.proxy.mapFromSource(panel.model.index(track.robot_index[robot], 0))
                selection.select(index, selection.Select | selection.Rows)
        selection.blockSignals(False)
        panel.table.viewport().update()

    def _robots_picked(self, *_args) -> None:
        panel = self.tables["robots"]
        rows = {index.row() for index in panel.table.selectionModel().selectedRows()}
        self.state.selection.set([panel.source_row(row) for row in sorted(rows)])
