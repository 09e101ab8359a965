"""The viewer's main window: puts the parts together and gives them menus and shortcuts.

The parts share one :class:`ViewerState` and never call each other: the stage draws the
warehouse, the panels list orders, stock, robots, actions and violations, the editor edits,
the jobs generate, solve and check, the online link plays a live world, the file actions
open files.  The window connects the clock (a :class:`Player`) to the state and answers
what only a window can: its title, dialogs, dropped files, closing.
"""

from __future__ import annotations

from PyQt5.QtCore import QSettings, Qt
from PyQt5.QtWidgets import (
    QAction,
    QInputDialog,
    QMainWindow,
    QMenu,
    QMenuBar,
    QMessageBox,
    QStatusBar,
    QToolBar,
    QVBoxLayout,
    QWidget,
)

from .editor.layout import Editor
from .export.exporting import ExportActions
from .export.strip import StripExport
from .jobs.live import LiveControl
from .jobs.runner import JobRunner
from .panels.atoms_pane import AtomsPane
from .panels.banner import SessionBanner
from .panels.checker_rule import RuleNote
from .panels.commands import Table, make_actions, show_shortcuts, submenu
from .panels.controls import TransportBar
from .panels.dialogs import confirm_discard
from .panels.docks import Panels
from .panels.files import FileActions
from .panels.legend import Legend
from .panels.presentation import NarrationBar, Presentation
from .panels.reload_on_save import ReloadOnSave
from .panels.screen import fit
from .panels.status import StatusLine
from .scene.paths import PathMode
from .scene.player import Player
from .scene.stage import Stage
from .scene.view import WarehouseView
from .state.loading import Scenario
from .state.track import Track
from .state.viewer import ViewerState

ACTIONS: Table = {
    "open": ("&Open instance…", ("Ctrl+O",)),
    "open_plan": ("Open &plan…", ("Ctrl+Shift+O",)),
    "reload": ("&Reload", ("F5", "Ctrl+R")),
    "export_picture": ("&Export picture…", ("Ctrl+E",)),
    "export_animation": ("Export &animation…", ("Ctrl+Shift+E",)),
    "export_strip": ("Export str&ip of states…", ()),
    "quit": ("&Quit", ("Ctrl+Q",)),
    "zoom_in": ("Zoom &in", ("Ctrl++", "+", "=")),
    "zoom_out": ("Zoom &out", ("Ctrl+-", "-")),
    "fit": ("&Fit to window", ("Ctrl+0", "0")),
    "goals": ("Show &goals", ("G",)),
    "labels": ("Show &ids (where they can be read)", ("I",)),
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
    "legend": ("&Legend: what the symbols mean", ("F2",)),
    "present": ("Presentation &mode (Esc leaves it)", ("F11", "Shift+F5")),
}
#: the side panels' width (pixels) in a new window
DOCK_WIDTH = 470
#: a new window's size (pixels), where the screen has room for it and its frame
FIRST_SIZE = (1366, 860)
#: the longest error message a dialog shows whole
ERROR_CHARACTERS = 600
MENUS = (("file", "&File"), ("edit", "&Edit"), ("view", "&View"), ("play", "&Play"), ("run", "&Run"),
         ("online", "&Online"), ("help", "&Help"))
_ICONS = {"play": "SP_MediaPlay", "forward": "SP_MediaSeekForward", "back": "SP_MediaSeekBackward",
          "start": "SP_MediaSkipBackward", "end": "SP_MediaSkipForward", "loop": "SP_BrowserReload"}


class MainWindow(QMainWindow):
    """Shows one scenario (instance + plan) at a time."""

    def __init__(self, settings: QSettings | None = None):
        super().__init__()
        self.settings = settings if settings is not None else QSettings("asprilo", "viz")
        self.state = ViewerState()
        self.player = Player(self)
        self.view = WarehouseView(self)
        self.banner = SessionBanner(self.state.session, self)
        centre = QWidget(self)
        layout = QVBoxLayout(centre)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(0)
        layout.addWidget(self.banner)
        layout.addWidget(self.view, 1)
        self.setCentralWidget(centre)
        # the bars made here, not by Qt on first use: see panels/commands.submenu
        self.setMenuBar(QMenuBar(self))
        self.setStatusBar(QStatusBar(self))
        self.menus = {name: submenu(self.menuBar(), title) for name, title in MENUS}
        # the panels and the status line follow a new track before the stage moves the clock
        self.panels = Panels(self.state, self, QMenu("&Panels", self))
        self.status_line = StatusLine(self.state, self.statusBar())
        self.stage = Stage(self.state, self.view, self.player, self)
        self.files = FileActions(self.state, self.settings, self)
        self.reload_on_save = ReloadOnSave(self.state, self.files, self.settings, self)
        layout.insertWidget(layout.indexOf(self.banner) + 1, self.reload_on_save.banner)
        self.exports = ExportActions(self.state, self.stage, self.player, self.settings, self)
        self.editor = Editor(self.state, self.stage, self, self.settings)
        self.jobs = JobRunner(self.state, self.player, self, self.settings)
        self.live = LiveControl(self.state, self.player, self, self.settings)
        self.commands = self._make_actions()
        self.transport = TransportBar(self.player, self.commands, self)
        self._make_menus()
        self._connect()
        self.narration = NarrationBar(self.state, centre)  # under the map, in the presentation mode
        layout.addWidget(self.narration)
        self.presentation = Presentation(self, self.view, self.narration)
        self.presentation.toggled.connect(self.commands["present"].setChecked)
        self.strips = StripExport(self.state, self.stage, self.settings, self)
        self.rule_note = RuleNote(self.state, self.panels.tables["violations"])
        bar = QToolBar("Playback", self)
        bar.setObjectName("playback")
        bar.setMovable(False)
        bar.addWidget(self.transport)
        self.addToolBar(Qt.BottomToolBarArea, bar)
        self.setAcceptDrops(True)
        fit(self, *FIRST_SIZE)  # the screen's room less the frame: a 1366x768 laptop shows it all
        geometry, state = self.settings.value("window/geometry"), self.settings.value("window/state")
        if geometry is not None:
            self.restoreGeometry(geometry)
        if state is not None:
            self.restoreState(state)
        self.state.document.open(None)

    # --- what the parts show -----------------------------------------------------------------------

    @property
    def scenario(self) -> Scenario | None:
        return self.state.document.scenario

    @property
    def track(self) -> Track | None:
        return self.state.track

    @property
    def selected(self) -> list[int]:
        return self.state.selection.robots

    @property
    def last_error(self) -> str | None:
        return self.state.last_error

    # --- building the window ---------------------------------------------------------------

    def _make_actions(self) -> dict[str, QAction]:
        player, view, files, exports = self.player, self.view, self.files, self.exports
        actions = make_actions(self, ACTIONS, {
            "open": files.ask_open, "open_plan": files.ask_open_plan, "reload": files.reload,
            "export_picture": exports.ask_picture, "export_animation": exports.ask_animation,
            "quit": self.close, "zoom_in": view.zoom_in, "zoom_out": view.zoom_out, "fit": view.fit,
            "goals": lambda: self.stage.set_goals(self.commands["goals"].isChecked()),
            "labels": lambda: self.stage.set_labels(self.commands["labels"].isChecked()),
            "paths": self._show_paths, "whole_paths": self._show_paths,
            "select_all": lambda: self.select_robots(self.track.robot_ids if self.track else []),
            "select_none": self.clear_selection, "play": player.toggle, "forward": player.step_forward,
            "back": player.step_back, "start": player.to_start, "end": player.to_end, "goto": self.ask_go_to,
            "faster": player.faster, "slower": player.slower,
            "loop": lambda: player.set_loop(self.commands["loop"].isChecked()),
            "shortcuts": lambda: show_shortcuts(self), "legend": lambda: self._show_dock("legend"),
            "present": lambda: self.presentation.toggle(), "export_strip": lambda: self.strips.ask()})
        for name in ("goals", "labels", "paths", "whole_paths", "loop", "present"):
            actions[name].setCheckable(True)
        for name in ("goals", "labels", "paths"):
            actions[name].setChecked(True)
        for name, icon in _ICONS.items():
            actions[name].setIcon(self.style().standardIcon(getattr(self.style(), icon)))
        return actions

    def _make_menus(self) -> None:
        menus, commands, editor = self.menus, self.commands, self.editor.commands
        file = menus["file"]
        _fill(file, [editor["new"], commands["open"], commands["open_plan"], commands["reload"],
                     self.reload_on_save.action])
        self.files.install_recent(submenu(file, "Recent &files"))
        _fill(file, [None, editor["save"], editor["save_as"], editor["save_template"], editor["save_plan"], None,
                     commands["export_picture"], commands["export_animation"], commands["export_strip"], None,
                     commands["quit"]])
        _fill(menus["view"], [commands[n] if n else None for n in (
            "zoom_in", "zoom_out", "fit", None, "goals", "labels", "paths", "whole_paths", "select_all",
            "select_none", None, "present")])
        menus["view"].addMenu(self.panels.menu)
        _fill(menus["play"], [commands[n] if n else None for n in ("play", "forward", "back", "start", "end",
                                                                   "goto", None, "faster", "slower", "loop")])
        menus["help"].addAction(commands["shortcuts"])
        menus["help"].addAction(commands["legend"])
        docks = self.panels.docks
        self.editor.install(menus, self.panels)
        atoms = AtomsPane(self.state)
        docks["atoms"] = self.panels.add_dock("atoms", "Atoms", atoms, docks["violations"])
        docks["atoms"].visibilityChanged.connect(atoms.set_shown)
        docks["legend"] = self.panels.add_dock("legend", "Legend", Legend(), docks["order_editor"])
        docks["orders"].raise_()
        docks["robots"].raise_()
        self.resizeDocks([docks["orders"]], [DOCK_WIDTH], Qt.Horizontal)
        self.docks = docks
        self.jobs.install(menus["run"])
        self.live.install(menus["online"])

    def _connect(self) -> None:
        state, player = self.state, self.player
        player.step_changed.connect(state.show_step)
        player.playing_changed.connect(self._show_playing)
        state.seek_requested.connect(self.go_to)
        state.error_reported.connect(self._report_error)
        state.shown.connect(lambda _keep: self._show_track())
        state.track_changed.connect(lambda _change: self._show_track())
        state.document.modified_changed.connect(lambda _modified: self._show_title())
        state.document.saved.connect(self._saved)
        self.panels.tables["violations"].row_activated.connect(self.stage.show_violation)

    # --- following the state ------------------------------------------------------------------------

    def _show_track(self) -> None:
        track = self.state.track
        self.transport.slider.set_marks([v.step for v in track.violations] if track else [])
        self.transport.set_horizon(track.horizon if track else 0)
        self._show_title()

    def _show_title(self) -> None:
        """``name — asprilo viz``, with a ``*`` while edits are unsaved."""
        scenario = self.state.document.scenario
        if scenario is None:
            self.setWindowTitle("asprilo viz")
            return
        star = "*" if self.state.document.modified else ""
        self.setWindowTitle(f"{star}{scenario.title} — asprilo viz")

    def _saved(self) -> None:
        self.files.remember(self.state.document.scenario)
        self._show_title()

    def _show_playing(self, playing: bool) -> None:
        icon = "SP_MediaPause" if playing else "SP_MediaPlay"
        self.commands["play"].setIcon(self.style().standardIcon(getattr(self.style(), icon)))

    def _show_paths(self) -> None:
        mode = PathMode.WHOLE if self.commands["whole_paths"].isChecked() else PathMode.REMAINING
        self.stage.set_paths(self.commands["paths"].isChecked(), mode)

    def _show_dock(self, name: str) -> None:
        self.docks[name].show()
        self.docks[name].raise_()

    def _report_error(self, message: str) -> None:
        """Say what went wrong in a dialog (not blocking: the viewer stays usable)."""
        if len(message) > ERROR_CHARACTERS:  # e.g. a term thousands of levels deep: the dialog stays on screen
            half = ERROR_CHARACTERS // 2
            message = f"{message[:half]} … {message[-half:]}"
        box = QMessageBox(QMessageBox.Warning, "asprilo viz", message, QMessageBox.Ok, self)
        box.setTextFormat(Qt.TextFormat.PlainText)  # a file's or clingo's words, `<stdin>` or `<IDENTIFIER>` too
        box.setAttribute(Qt.WA_DeleteOnClose)
        box.open()

    # --- commands -------------------------------------------------------------------------------------

    def show_scenario(self, scenario: Scenario | None) -> None:
        """Show ``scenario`` (``None``: the empty window), forgetting what was shown."""
        self.state.document.open(scenario)

    def open_files(self, instance, plans=()) -> bool:
        """Show an instance (files, ``-`` or sources) and its plan; errors go to a dialog."""
        return self.files.open_files(instance, plans)

    def go_to(self, step: int) -> None:
        """Stop playing and show the state after ``step``."""
        self.player.pause()
        self.player.seek(step)

    def select_robots(self, robots: list[int]) -> None:
        """Select robots (rings, paths, rows in the robots panel)."""
        track = self.state.track
        self.state.selection.set([r for r in robots if track and r in track.robot_index])

    def clear_selection(self) -> None:
        self.presentation.leave()  # Esc ends the presentation mode too
        self.stage.clear_highlight()
        self.state.selection.set([])

    def ask_go_to(self) -> None:
        track = self.state.track
        if track is None:
            return
        step, ok = QInputDialog.getInt(self, "Go to step", f"Show the state after step (0–{track.horizon}):",
                                       self.player.step, 0, track.horizon)
        if ok:
            self.go_to(step)

    # --- dropped files, closing ------------------------------------------------------------------------

    def dragEnterEvent(self, event) -> None:
        if event.mimeData().hasUrls() and all(url.isLocalFile() for url in event.mimeData().urls()):
            event.acceptProposedAction()

    def dropEvent(self, event) -> None:
        paths = [url.toLocalFile() for url in event.mimeData().urls()]
        event.acceptProposedAction()
        self.files.open_dropped(paths)

    def closeEvent(self, event) -> None:
        if not confirm_discard(self, self.state.document, self.editor.save_unsaved):
            event.ignore()
            return
        self.presentation.leave()  # the layout saved is the one with the panels
        self.player.pause()
        self.live.disconnect()
        self.jobs.close()
        self.settings.setValue("window/geometry", self.saveGeometry())
        self.settings.setValue("window/state", self.saveState())
        super().closeEvent(event)


def _fill(menu: QMenu, actions: list) -> None:
    """Add actions to a menu, ``None`` as a separator."""
    for action in actions:
        menu.addSeparator() if action is None else menu.addAction(action)

