"""The Online menu: connect the window to a solver (and a simulator) and watch the world live.

While a session runs, the window plays each step as soon as its actions arrive and asks
for the next one when it has shown the last; new orders from the simulator appear in the
panels when they arrive.  Editing is locked meanwhile: the world belongs to the session.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

from PyQt5.QtCore import QObject, QSettings
from PyQt5.QtGui import QKeySequence
from PyQt5.QtWidgets import QAction, QMenu

from asprilo.model import Instance, Plan
from asprilo.sources import Source

from .dialogs import ConnectDialog
from .loading import Scenario
from .network import LiveSession

if TYPE_CHECKING:
    from .window import MainWindow


class LiveControl(QObject):
    """Starts, follows and ends the window's online session."""

    def __init__(self, window: MainWindow):
        super().__init__(window)
        self.window = window
        self.session: LiveSession | None = None
        self.name = ""
        self.scenario: Scenario | None = None  # what the session shows
        self.last_reason: str | None = None  # why the last session ended
        self.connect_action = QAction("&Connect to solver…", window)
        self.connect_action.setShortcut(QKeySequence("Ctrl+K"))
        self.connect_action.triggered.connect(self.ask_connect)
        self.disconnect_action = QAction("&Disconnect", window)
        self.disconnect_action.triggered.connect(self.disconnect)
        self.disconnect_action.setEnabled(False)
        for action in (self.connect_action, self.disconnect_action):
            window.addAction(action)
        window.player.step_changed.connect(self._shown)

    def install(self, menus: dict[str, QMenu]) -> None:
        menu = QMenu("&Online", self.window)
        self.window.menuBar().insertMenu(menus["help"].menuAction(), menu)
        menu.addAction(self.connect_action)
        menu.addAction(self.disconnect_action)
        menus["online"] = menu

    # --- sessions ------------------------------------------------------------------------------------

    def ask_connect(self) -> None:
        settings: QSettings = self.window.settings
        dialog = ConnectDialog(str(settings.value("online/host", "127.0.0.1")),
                               int(settings.value("online/solver", 5000)),
                               int(settings.value("online/simulator", 5001)) if self.window.scenario is None
                               else None, self.window)
        if not dialog.exec_():
            return
        host, solver, simulator = dialog.values()
        settings.setValue("online/host", host)
        settings.setValue("online/solver", solver)
        if simulator is not None:
            settings.setValue("online/simulator", simulator)
        self.connect_to(host, solver, simulator)

    def connect_to(self, host: str, solver_port: int, simulator_port: int | None = None) -> LiveSession | None:
        """Start a session; without a simulator the solver plans for the instance shown."""
        self.disconnect()
        instance: Instance | None = None
        if simulator_port is None:
            if self.window.scenario is None:
                self.window.report_error("Open or make an instance first, or connect to a simulator as well.")
                return None
            instance = copy.deepcopy(self.window.editor.document.instance)
        session = LiveSession(host, solver_port, simulator_port, instance, self)
        session.world_changed.connect(self._world)
        session.stepped.connect(self._stepped)
        session.status.connect(lambda text: self.window.statusBar().showMessage(text, 5000))
        session.stopped.connect(self._stopped)
        self.session = session
        self.name = f"online: solver {host}:{solver_port}" + (
            f", simulator {host}:{simulator_port}" if simulator_port is not None else "")
        self.window.editor.lock("an online session owns the world: disconnect to edit")
        self.disconnect_action.setEnabled(True)
        session.start()
        return session

    def disconnect(self) -> None:
        if self.session is not None:
            self.session.stop("disconnected")

    # --- following the session -----------------------------------------------------------------------

    def _world(self, instance: Instance, first: bool) -> None:
        if first:
            self.scenario = Scenario(instance, Plan(), [Source(f"<{self.name}>", "")], unfinished=True)
            self.window.show_scenario(self.scenario)
        elif self._still_shown():  # orders arrived: the instance grew in place
            self.window.show_changes(self.window.player.time)

    def _still_shown(self) -> bool:
        """Whether the window still shows the session (a file opened meanwhile ends it)."""
        if self.window.scenario is not self.scenario:
            self.session.stop("another instance was opened")
            return False
        return True

    def _stepped(self, step: int) -> None:
        if not self._still_shown():
            return
        player = self.window.player
        at_end = player.time >= player.horizon
        self.window.scenario.plan = Plan(list(self.session.actions))
        self.window.show_changes(player.time)
        if at_end:
            player.play()

    def _shown(self, step: int) -> None:
        if self.session is not None:
            self.session.shown(step)

    def _stopped(self, reason: str) -> None:
        session, self.session = self.session, None
        if session is not None:
            session.deleteLater()
        self.disconnect_action.setEnabled(False)
        self.window.editor.lock(None)
        self.window.tools.update_actions()
        if self.scenario is not None and self.window.scenario is self.scenario:
            self.scenario.unfinished = False  # the goal is checked now
            self.window.show_changes(self.window.player.time)
        track = self.window.track
        open_lines = len(track.state(track.horizon).open_lines) if track is not None else 0
        note = f"; {open_lines} order line{'s' if open_lines != 1 else ''} still open" if open_lines else ""
        self.last_reason = reason
        self.window.statusBar().showMessage(f"Online session ended: {reason}{note}", 15000)
