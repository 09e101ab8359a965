"""The viewer's main window: warehouse view, playback bar, dockable panels, menus, files."""

from __future__ import annotations

import gc
import json
from collections.abc import Iterable
from pathlib import Path

from PyQt5.QtCore import QPointF, QSettings, Qt
from PyQt5.QtGui import QKeySequence
from PyQt5.QtWidgets import (
    QAction,
    QApplication,
    QDockWidget,
    QFileDialog,
    QInputDialog,
    QLabel,
    QMainWindow,
    QMessageBox,
    QProgressDialog,
    QSizePolicy,
    QToolBar,
)

from asprilo.errors import InputError
from asprilo.model import Instance
from asprilo.simulate import Violation

from . import export, loading, style
from .animator import Animator
from .controls import TransportBar
from .describe import tooltip
from .editor import EDIT_ACTIONS, Editor
from .gui_jobs import GuiTools
from .inventory import InventoryModel
from .live import LiveControl
from .loading import Scenario
from .orders import OrdersModel
from .paths import PathMode, Trails
from .plan_list import PlanModel
from .player import Player
from .robot_list import RobotsModel
from .scene import WarehouseScene
from .tables import TablePanel
from .tools import TOOLS
from .track import Track
from .view import WarehouseView
from .violation_list import ViolationsModel

RECENT_LIMIT = 10
FILE_FILTER = "ASP facts and clingo output (*.lp *.txt *.plan *.out);;All files (*)"

#: name -> (menu text, shortcuts); the first shortcut is the one menus show.
ACTIONS: dict[str, tuple[str, tuple[str, ...]]] = {
    "open": ("&Open instance…", ("Ctrl+O",)),
    "open_plan": ("Open &plan…", ("Ctrl+Shift+O",)),
    "reload": ("&Reload", ("F5", "Ctrl+R")),
    "export_picture": ("&Export picture…", ("Ctrl+E",)),
    "export_animation": ("Export &animation…", ("Ctrl+Shift+E",)),
    "quit": ("&Quit", ("Ctrl+Q",)),
    "zoom_in": ("Zoom &in", ("Ctrl++", "+", "=")),
    "zoom_out": ("Zoom &out", ("Ctrl+-", "-")),
    "fit": ("&Fit to window", ("Ctrl+0", "0")),
    "paths": ("Show &paths of selected robots", ("T",)),
    "whole_paths": ("&Whole paths (not only what remains)", ("Shift+T",)),
    "select_all": ("Select &all robots", ("Ctrl+A",)),
    "select_none": ("&Clear selection and highlight", ("Esc",)),
    "play": ("&Play / pause", ("Space",)),
    "forward": ("Step &forward", ("Right",)),
    "back": ("Step &back", ("Left",)),
    "start": ("Go to &start", ("Home",)),
    "end": ("Go to &end", ("End",)),
    "goto": ("&Go to step…", ("Ctrl+G",)),
    "faster": ("F&aster", ("]",)),
    "slower": ("S&lower", ("[",)),
    "loop": ("&Loop", ("L",)),
    "shortcuts": ("&Keyboard shortcuts", ("F1",)),
}


class MainWindow(QMainWindow):
    """Shows one scenario (instance + plan) at a time."""

    def __init__(self, settings: QSettings | None = None):
        super().__init__()
        self.settings = settings if settings is not None else QSettings("asprilo", "viz")
        self.scenario: Scenario | None = None
        self.track: Track | None = None
        self.scene: WarehouseScene | None = None
        self.animator: Animator | None = None
        self.trails: Trails | None = None
        self.selected: list[int] = []
        self.last_error: str | None = None
        self.player = Player(self)
        self.view = WarehouseView(self)
        self.view.describe = self._describe
        self.view.clicked.connect(self._clicked)
        self.setCentralWidget(self.view)
        self.commands = self._make_actions()
        self.editor = Editor(self)
        self.live = LiveControl(self)
        self._make_menus()
        self.transport = TransportBar(self.player, self.commands, self)
        bar = QToolBar("Playback", self)
        bar.setObjectName("playback")
        bar.setMovable(False)
        bar.addWidget(self.transport)
        self.addToolBar(Qt.BottomToolBarArea, bar)
        self.panels = {"orders": TablePanel(OrdersModel(), "filter orders"),
                       "inventory": TablePanel(InventoryModel(), "filter shelves, products"),
                       "robots": TablePanel(RobotsModel(), "filter robots"),
                       "plan": TablePanel(PlanModel(), "filter actions"),
                       "violations": TablePanel(ViolationsModel(), "filter violations")}
        self.docks = self._make_docks()
        self.docks["order_editor"] = self.editor.install(self.menus, self.commands["export_picture"])
        self.live.install(self.menus)
        self.tools = GuiTools(self)
        self.tools.install(self.menus)
        self.tabifyDockWidget(self.docks["inventory"], self.docks["order_editor"])
        self.docks["orders"].raise_()
        self.panels["plan"].row_activated.connect(lambda action: self.go_to(action.step))
        self.panels["violations"].row_activated.connect(self.show_violation)
        self.panels["robots"].table.selectionModel().selectionChanged.connect(self._robots_picked)
        self.status = QLabel(self)
        self.status.setSizePolicy(QSizePolicy.Ignored, QSizePolicy.Preferred)  # clipped, never overlapping
        self.problems = QLabel(self)
        self.statusBar().addWidget(self.status, 1)
        self.statusBar().addPermanentWidget(self.problems)
        self.player.time_changed.connect(self._show_time)
        self.player.step_changed.connect(self._show_step)
        self.player.playing_changed.connect(self._show_playing)
        self.setAcceptDrops(True)
        self.resize(1360, 860)
        geometry, state = self.settings.value("window/geometry"), self.settings.value("window/state")
        if geometry is not None:
            self.restoreGeometry(geometry)
        if state is not None:
            self.restoreState(state)
        self.show_scenario(None)

    # --- building the window ---------------------------------------------------------------

    def _make_actions(self) -> dict[str, QAction]:
        slots = {
            "open": self.ask_open, "open_plan": self.ask_open_plan, "reload": self.reload,
            "export_picture": self.ask_export_picture, "export_animation": self.ask_export_animation,
            "quit": self.close, "zoom_in": self.view.zoom_in, "zoom_out": self.view.zoom_out,
            "fit": self.view.fit, "paths": self._show_trails, "whole_paths": self._show_trails,
            "select_all": lambda: self.select_robots(self.track.robot_ids if self.track else []),
            "select_none": self.clear_selection, "play": self.player.toggle,
            "forward": self.player.step_forward, "back": self.player.step_back,
            "start": self.player.to_start, "end": self.player.to_end, "goto": self.ask_go_to,
            "faster": self.player.faster, "slower": self.player.slower,
            "loop": lambda: self.player.set_loop(self.commands["loop"].isChecked()),
            "shortcuts": self.show_shortcuts,
        }
        actions = {}
        for name, (text, keys) in ACTIONS.items():
            action = QAction(text, self)
            action.setShortcuts([QKeySequence(key) for key in keys])
            action.setToolTip(f"{text.replace('&', '').rstrip('…')} ({keys[0]})")
            action.triggered.connect(lambda _checked=False, slot=slots[name]: slot())
            self.addAction(action)
            actions[name] = action
        for name in ("paths", "whole_paths", "loop"):
            actions[name].setCheckable(True)
        actions["paths"].setChecked(True)
        icons = {"play": "SP_MediaPlay", "forward": "SP_MediaSeekForward", "back": "SP_MediaSeekBackward",
                 "start": "SP_MediaSkipBackward", "end": "SP_MediaSkipForward", "loop": "SP_BrowserReload"}
        for name, icon in icons.items():
            actions[name].setIcon(self.style().standardIcon(getattr(self.style(), icon)))
        return actions

    def _make_menus(self) -> None:
        menus = self.menuBar()
        file = menus.addMenu("&File")
        for name in ("open", "open_plan", "reload"):
            file.addAction(self.commands[name])
        self.recent_menu = file.addMenu("Recent &files")
        self.recent_menu.aboutToShow.connect(self._fill_recent)
        file.addSeparator()
        file.addAction(self.commands["export_picture"])
        file.addAction(self.commands["export_animation"])
        file.addSeparator()
        file.addAction(self.commands["quit"])
        view = menus.addMenu("&View")
        for name in ("zoom_in", "zoom_out", "fit", None, "paths", "whole_paths", "select_all", "select_none"):
            view.addSeparator() if name is None else view.addAction(self.commands[name])
        self.panels_menu = view.addMenu("&Panels")
        play = menus.addMenu("&Play")
        for name in ("play", "forward", "back", "start", "end", "goto", None, "faster", "slower", "loop"):
            play.addSeparator() if name is None else play.addAction(self.commands[name])
        help_ = menus.addMenu("&Help")
        help_.addAction(self.commands["shortcuts"])
        self.menus = {"file": file, "view": view, "play": play, "help": help_}

    def _make_docks(self) -> dict[str, QDockWidget]:
        titles = {"orders": "Orders", "inventory": "Inventory", "robots": "Robots", "plan": "Plan",
                  "violations": "Violations"}
        docks = {}
        for name, title in titles.items():
            dock = QDockWidget(title, self)
            dock.setObjectName(f"dock_{name}")
            dock.setWidget(self.panels[name])
            self.addDockWidget(Qt.RightDockWidgetArea, dock)
            self.panels_menu.addAction(dock.toggleViewAction())
            docks[name] = dock
        self.tabifyDockWidget(docks["orders"], docks["inventory"])
        self.tabifyDockWidget(docks["robots"], docks["plan"])
        docks["orders"].raise_()
        docks["robots"].raise_()
        self.resizeDocks([docks["orders"]], [560], Qt.Horizontal)
        return docks

    # --- opening files ---------------------------------------------------------------------

    def open_files(self, instance: Iterable, plans: Iterable = ()) -> bool:
        """Show an instance (files, ``-`` or sources) and its plan; errors go to a dialog."""
        return self._load(lambda: loading.load_scenario(list(instance), list(plans)))

    def open_plan_files(self, plans: Iterable) -> bool:
        """Show a plan on the instance already open."""
        if self.scenario is None:
            self.report_error("Open an instance first: a plan needs its warehouse.")
            return False
        return self._load(lambda: loading.add_plan(self.scenario, list(plans)))

    def open_dropped(self, paths: list[str]) -> bool:
        """Files dropped on the window: instances (and plans) or plans for the open instance."""
        try:
            instances, plans = loading.sort_files(paths)
        except InputError as error:
            self.report_error(str(error))
            return False
        if instances:
            return self.open_files(instances, plans)
        return self.open_plan_files(plans)

    def reload(self) -> bool:
        if self.scenario is None:
            return False
        return self._load(lambda: loading.reload(self.scenario), keep_time=True)

    def _load(self, read, keep_time: bool = False) -> bool:
        if not self.editor.confirm_discard():
            return False
        QApplication.setOverrideCursor(Qt.WaitCursor)
        try:
            scenario = read()
            self.show_scenario(scenario, keep_time)
        except InputError as error:
            self.report_error(str(error))
            return False
        finally:
            QApplication.restoreOverrideCursor()
        self.remember(scenario)
        return True

    def show_scenario(self, scenario: Scenario | None, keep_time: bool = False) -> None:
        """Build scene, states and panels for ``scenario`` (``None``: the empty window)."""
        time = self.player.time if keep_time else 0.0
        self.player.pause()
        gc.unfreeze()  # what the last scenario froze may now be collected
        self.scenario = scenario
        old_scene = self.scene
        if scenario is None:
            self.track = self.animator = self.trails = None
            self.scene = WarehouseScene(Instance(), self)
            self.scene.addText("Open an instance (Ctrl+O) or drop files here.", style.font(16, bold=False))
            self.scene.setSceneRect(self.scene.picture_rect())
            self.view.setScene(self.scene)
        else:
            self.scene = WarehouseScene(scenario.instance, self)
            self._animate(scenario)
            self.view.setScene(self.scene)
            self.view.fit()
        if old_scene is not None:
            old_scene.deleteLater()
        self.editor.follow(scenario)
        self._show_states(time)
        # Exempt the scenario's many long-lived objects from the garbage collector's full
        # passes: over a big warehouse one takes ~0.1 s and would stall the animation.
        gc.freeze()

    def show_changes(self, time: float = 0.0) -> None:
        """Compute the states again after the instance or the plan changed (an edit, a plan
        from the solver or the online link); scene, zoom and selection stay."""
        if self.scenario is None:
            return
        if self.animator is not None:
            self.animator.detach()
        if self.trails is not None:
            self.trails.show([])
        self._animate(self.scenario)
        self._show_states(time)

    def _animate(self, scenario: Scenario) -> None:
        # without a plan (yet) the goal is no problem: only the instance's own are shown
        unfinished = scenario.unfinished or not len(scenario.plan)
        self.track = Track(scenario.instance, scenario.plan, scenario.domain, unfinished)
        self.animator = Animator(self.scene, self.track)
        self.trails = Trails(self.scene, self.track)

    def _show_states(self, time: float) -> None:
        """Panels, slider, title and status for the current track, showing ``time``."""
        self.selected = [r for r in self.selected if self.track and r in self.track.robot_index]
        for panel in self.panels.values():
            panel.set_track(self.track)
        horizon = self.track.horizon if self.track else 0
        self.docks["violations"].setWindowTitle(
            f"Violations ({len(self.track.violations)})" if self.track else "Violations")
        self.transport.slider.set_marks([v.step for v in self.track.violations] if self.track else [])
        self.transport.set_horizon(horizon)
        self.player.set_horizon(horizon, time)  # shows that time on the new scene and panels
        self.select_robots(self.selected)
        self.show_title()
        self._show_summary()
        self.tools.update_actions()

    def show_title(self) -> None:
        """``name — asprilo viz``, with a ``*`` while edits are unsaved."""
        if self.scenario is None:
            self.setWindowTitle("asprilo viz")
            return
        star = "*" if self.editor.document.modified else ""
        self.setWindowTitle(f"{star}{self.scenario.title} — asprilo viz")

    # --- following the time ------------------------------------------------------------------

    def _show_time(self, time: float) -> None:
        if self.animator is not None:
            self.animator.show(time)

    def _show_step(self, step: int) -> None:
        for panel in self.panels.values():
            panel.show_step(step)
        plan = self.panels["plan"]
        row = plan.model.first_row(step) if self.track else None
        if row is not None and self.docks["plan"].isVisible():
            plan.scroll_to_source_row(row)
        self._show_trails()
        self._show_problems(step)

    def _show_playing(self, playing: bool) -> None:
        icon = "SP_MediaPause" if playing else "SP_MediaPlay"
        self.commands["play"].setIcon(self.style().standardIcon(getattr(self.style(), icon)))

    def go_to(self, step: int) -> None:
        """Stop playing and show the state after ``step``."""
        self.player.pause()
        self.player.seek(step)

    def show_violation(self, violation: Violation) -> None:
        """Jump to a violation's step, mark its objects and bring them into view."""
        self.go_to(violation.step)
        if self.animator is None:
            return
        self.animator.highlight(violation)
        items = [self.scene.robots[r] for r in violation.robots if r in self.scene.robots]
        items += [self.scene.shelves[s] for s in violation.shelves if s in self.scene.shelves]
        if items:
            self.view.ensureVisible(items[0])
        elif violation.cells:
            self.view.ensureVisible(style.cell_rect(violation.cells[0]))
        self.select_robots(list(violation.robots) or self.selected)

    # --- selection and paths ------------------------------------------------------------------

    def select_robots(self, robots: Iterable[int]) -> None:
        """Select robots (rings, paths, rows in the robots panel)."""
        self.selected = [r for r in dict.fromkeys(robots) if self.track and r in self.track.robot_index]
        if self.scene is not None and self.track is not None:
            for ident, item in self.scene.robots.items():
                item.set_selected(ident in self.selected)
        table = self.panels["robots"].table
        table.selectionModel().blockSignals(True)
        table.clearSelection()
        panel = self.panels["robots"]
        for robot in self.selected:
            index = panel.proxy.mapFromSource(panel.model.index(self.track.robot_index[robot], 0))
            table.selectionModel().select(index, table.selectionModel().Select | table.selectionModel().Rows)
        table.selectionModel().blockSignals(False)
        table.viewport().update()
        self._show_trails()

    def clear_selection(self) -> None:
        if self.animator is not None:
            self.animator.highlight(None)
        self.select_robots([])

    def _clicked(self, objects: list[tuple[str, int]], modifiers) -> None:
        robots = [ident for kind, ident in objects if kind == "robot"]
        if modifiers & (Qt.ControlModifier | Qt.ShiftModifier):
            chosen = list(self.selected)
            for robot in robots[:1]:
                chosen.remove(robot) if robot in chosen else chosen.append(robot)
            self.select_robots(chosen)
        else:
            self.select_robots(robots[:1])

    def _robots_picked(self, *_args) -> None:
        panel = self.panels["robots"]
        rows = {index.row() for index in panel.table.selectionModel().selectedRows()}
        self.select_robots([panel.source_row(row) for row in sorted(rows)])

    def _show_trails(self) -> None:
        if self.trails is None:
            return
        shown = self.selected if self.commands["paths"].isChecked() else []
        mode = PathMode.WHOLE if self.commands["whole_paths"].isChecked() else PathMode.REMAINING
        self.trails.show(shown, self.player.step, mode)

    # --- what the window says ------------------------------------------------------------------

    def _describe(self, point: QPointF, objects: list) -> str | None:
        if self.track is None:
            return None
        cell, step = style.cell_at(point), self.player.step
        resting = [("shelf", shelf) for shelf, at in self.track.state(step).shelves.items()
                   if tuple(at) == cell and ("shelf", shelf) not in objects]  # drawn as one layer when tiny
        return tooltip(self.track, step, cell, objects + resting)

    def _show_summary(self) -> None:
        if self.scenario is None:
            self.status.setText("No instance open.")
            return
        counts = self.scenario.instance.counts()
        track = self.track
        self.status.setText(
            f"{self.scenario.title}   ·   domain {track.domain.label}   ·   {counts['x']}×{counts['y']}, "
            f"{counts['robots']} robots, {counts['shelves']} shelves, {counts['orders']} orders   ·   "
            + (f"plan: {len(self.scenario.plan)} actions, horizon {track.horizon}" if len(self.scenario.plan)
               else "no plan"))

    def _show_problems(self, step: int) -> None:
        if self.track is None or not len(self.scenario.plan):
            self.problems.setText("")
            return
        total = len(self.track.violations)
        here = len(self.track.violations_at.get(step, []))
        if not total:
            verdict = "no rule broken so far" if self.scenario.unfinished else "valid plan"
            self.problems.setText(f"<span style='color:#2b8a3e'>{verdict} \u2713</span>")
            return
        text = f"\u26a0 {total} rule violation{'s' if total > 1 else ''}"
        if here:
            text += f", {here} at step {step}"
        self.problems.setText(f"<span style='color:#e03131'><b>{text}</b></span>")

    def report_error(self, message: str) -> None:
        """Say what went wrong in a dialog (not blocking: the viewer stays usable)."""
        self.last_error = message
        box = QMessageBox(QMessageBox.Warning, "asprilo viz", message, QMessageBox.Ok, self)
        box.setAttribute(Qt.WA_DeleteOnClose)
        box.open()

    def show_shortcuts(self) -> None:
        entries = list(ACTIONS.values()) + [(text, (key,)) for text, key in EDIT_ACTIONS.values() if key]
        entries += [(tool.text + " tool", (tool.key,)) for tool in TOOLS]
        entries += [("&Undo", ("Ctrl+Z",)), ("&Redo", ("Ctrl+Shift+Z", "Ctrl+Y"))]
        rows = "".join(f"<tr><td>{text.replace('&', '').rstrip('…')}</td><td><b>{', '.join(keys)}</b></td></tr>"
                       for text, keys in entries)
        box = QMessageBox(QMessageBox.Information, "Keyboard shortcuts",
                          f"<table cellspacing=4>{rows}</table>"
                          "<p>Mouse: wheel zooms, drag pans, click selects a robot "
                          "(Ctrl+click: several), hover shows details.</p>", QMessageBox.Ok, self)
        box.setAttribute(Qt.WA_DeleteOnClose)
        box.open()

    # --- dialogs -----------------------------------------------------------------------------

    def _start_folder(self) -> str:
        return str(self.settings.value("last_folder", str(Path.cwd())))

    def ask_open(self) -> None:
        paths, _ = QFileDialog.getOpenFileNames(self, "Open instance (and plan) files", self._start_folder(),
                                                FILE_FILTER)
        if paths:
            self.settings.setValue("last_folder", str(Path(paths[0]).parent))
            self.open_dropped(paths)

    def ask_open_plan(self) -> None:
        paths, _ = QFileDialog.getOpenFileNames(self, "Open plan files", self._start_folder(), FILE_FILTER)
        if paths:
            self.settings.setValue("last_folder", str(Path(paths[0]).parent))
            self.open_plan_files(paths)

    def ask_go_to(self) -> None:
        if self.track is None:
            return
        step, ok = QInputDialog.getInt(self, "Go to step", f"Show the state after step (0–{self.track.horizon}):",
                                       self.player.step, 0, self.track.horizon)
        if ok:
            self.go_to(step)

    def ask_export_picture(self) -> None:
        if self.animator is None:
            return
        path, _ = QFileDialog.getSaveFileName(self, "Export picture", self._start_folder(),
                                              "PNG image (*.png);;SVG drawing (*.svg);;JPEG image (*.jpg)")
        if path:
            self.export_picture(path)

    def ask_export_animation(self) -> None:
        if self.animator is None:
            return
        path, _ = QFileDialog.getSaveFileName(self, "Export animation", self._start_folder(),
                                              "GIF animation (*.gif);;MP4 video (*.mp4)")
        if not path:
            return
        frames, ok = QInputDialog.getInt(self, "Export animation", "Frames per step (1: only the states):",
                                         4, 1, 30)
        if ok:
            self.export_animation(path, frames)

    def export_picture(self, path: str) -> bool:
        """Save the warehouse as shown now (time, selection, paths)."""
        try:
            export.save_picture(path, self.scene)
        except InputError as error:
            self.report_error(str(error))
            return False
        self.statusBar().showMessage(f"saved {path}", 5000)
        return True

    def export_animation(self, path: str, frames_per_step: int = 4) -> bool:
        """Save every state of the plan (with in-between frames) as a GIF or MP4."""
        self.player.pause()
        progress = QProgressDialog("Rendering frames…", "", 0, 1, self)
        progress.setCancelButton(None)
        progress.setWindowModality(Qt.WindowModal)

        def advance(done: int, total: int) -> None:
            progress.setMaximum(total)
            progress.setValue(done)

        try:
            export.save_animation(path, self.animator, frames_per_step, self.player.speed, progress=advance)
        except InputError as error:
            self.report_error(str(error))
            return False
        finally:
            progress.close()
        self.statusBar().showMessage(f"saved {path}", 5000)
        return True

    # --- recent files, drag and drop, closing --------------------------------------------------

    def recent(self) -> list[dict]:
        """Recently opened files, newest first: ``{"instance": [paths], "plans": [paths]}``."""
        try:
            entries = json.loads(str(self.settings.value("recent", "[]")))
        except ValueError:
            return []
        return [e for e in entries if isinstance(e, dict) and {"instance", "plans"} <= set(e)]

    def remember(self, scenario: Scenario) -> None:
        """Put the scenario's files first in the recent files (standard input is not kept)."""
        instances, plans = scenario.files
        if not instances:
            return
        entry = {"instance": [str(Path(p).resolve()) for p in instances],
                 "plans": [str(Path(p).resolve()) for p in plans]}
        entries = [entry] + [e for e in self.recent() if e != entry]
        self.settings.setValue("recent", json.dumps(entries[:RECENT_LIMIT]))

    def _fill_recent(self) -> None:
        self.recent_menu.clear()
        for entry in self.recent():
            names = [Path(p).name for p in entry["instance"] + entry["plans"]]
            action = self.recent_menu.addAction(" + ".join(names))
            action.setToolTip("\n".join(entry["instance"] + entry["plans"]))
            action.triggered.connect(lambda _c=False, e=entry: self.open_files(e["instance"], e["plans"]))
        if not self.recent_menu.actions():
            self.recent_menu.addAction("(none yet)").setEnabled(False)

    def dragEnterEvent(self, event) -> None:
        if event.mimeData().hasUrls() and all(url.isLocalFile() for url in event.mimeData().urls()):
            event.acceptProposedAction()

    def dropEvent(self, event) -> None:
        paths = [url.toLocalFile() for url in event.mimeData().urls()]
        event.acceptProposedAction()
        self.open_dropped(paths)

    def closeEvent(self, event) -> None:
        if not self.editor.confirm_discard():
            event.ignore()
            return
        self.player.pause()
        self.live.disconnect()
        self.tools.cancel()
        self.settings.setValue("window/geometry", self.saveGeometry())
        self.settings.setValue("window/state", self.saveState())
        super().closeEvent(event)

