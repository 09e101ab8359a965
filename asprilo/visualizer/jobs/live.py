"""The Online menu: connect the window to a solver (and a simulator) and watch the world live.

While a session runs, the window plays each step as soon as its actions arrive and asks
for the next one when it has shown the last; new orders from the simulator appear in the
panels when they arrive.  The layout cannot be edited meanwhile (the world belongs to the
session), but orders written in the order editor go to the solver when sent.
"""

from __future__ import annotations

import copy

from PyQt5.QtCore import QObject, QSettings
from PyQt5.QtWidgets import QMainWindow, QMenu

from asprilo.model import Instance, Plan
from asprilo.sources import Source

from ..panels.commands import Table, make_actions
from ..panels.dialogs import ConnectDialog
from ..scene.player import Player
from ..state.loading import Scenario
from ..state.viewer import ViewerState
from .network import LiveSession

LIVE_ACTIONS: Table = {
    "connect": ("&Connect to solver…", ("Ctrl+K",)),
    "disconnect": ("&Disconnect", ()),
}


class LiveControl(QObject):
    """Starts, follows and ends the window's online session."""

    def __init__(self, state: ViewerState, player: Player, window: QMainWindow, settings: QSettings):
        super().__init__(window)
        self.state, self.player, self.window, self.settings = state, player, window, settings
        self.session: LiveSession | None = None
        self.scenario: Scenario | None = None  # what the session shows
        self.commands = make_actions(window, LIVE_ACTIONS, {"connect": self.ask_connect,
                                                            "disconnect": self.disconnect})
        self.commands["disconnect"].setEnabled(False)
        state.step_changed.connect(self._shown)
        state.session.outgoing.connect(self._send)

    @property
    def last_reason(self) -> str | None:
        """Why the last session ended."""
        return self.state.session.last_reason

    def install(self, menu: QMenu) -> None:
        menu.addAction(self.commands["connect"])
        menu.addAction(self.commands["disconnect"])

    # --- sessions ------------------------------------------------------------------------------------

    def ask_connect(self) -> None:
        settings = self.settings
        dialog = ConnectDialog(str(settings.value("online/host", "127.0.0.1")),
                               int(settings.value("online/solver", 5000)),
                               int(settings.value("online/simulator", 5001))
                               if self.state.document.scenario is None else None, self.window)
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
            if self.state.document.scenario is None:
                self.state.report_error("Open or make an instance first, or connect to a simulator as well.")
                return None
            instance = copy.deepcopy(self.state.document.instance)
        session = LiveSession(host, solver_port, simulator_port, instance, self)
        session.world_changed.connect(self._world)
        session.stepped.connect(self._stepped)
        session.status.connect(lambda text: self.state.say(text))
        session.stopped.connect(self._stopped)
        self.session = session
        self.commands["disconnect"].setEnabled(True)
        self.state.session.start(f"online: solver {host}:{solver_port}" + (
            f", simulator {host}:{simulator_port}" if simulator_port is not None else ""))
        session.start()
        return session

    def disconnect(self) -> None:
        if self.session is not None:
            self.session.stop("disconnected")

    # --- following the session -----------------------------------------------------------------------

    def _world(self, instance: Instance, first: bool) -> None:
        if first:
            self.scenario = Scenario(instance, Plan(), [Source(f"<{self.state.session.name}>", "")],
                                     unfinished=True)
            self.state.document.open(self.scenario)
        elif self._still_shown():  # orders arrived: the instance grew in place
            self.state.document.refresh()

    def _still_shown(self) -> bool:
        """Whether the window still shows the session (a file opened meanwhile ends it)."""
        if self.state.document.scenario is not self.scenario:
            self.session.stop("another instance was opened")
            return False
        return True

    def _stepped(self, step: int) -> None:
        if not self._still_shown():
            return
        if len(self.session.actions) == len(self.state.document.plan):  # the robots waited: ask on
            self.session.shown(self.state.step)
            return
        at_end = self.player.time >= self.player.horizon
        self.state.document.grow_plan(Plan(list(self.session.actions)))
        if at_end:
            self.player.play()

    def _send(self, facts: str) -> None:
        if self.session is not None:
            self.session.send(facts)
            self.session.shown(self.state.step)

    def _shown(self, step: int) -> None:
        if self.session is not None:
            self.session.shown(step)

    def _stopped(self, reason: str) -> None:
        session, self.session = self.session, None
        if session is not None:
            session.deleteLater()
        self.commands["disconnect"].setEnabled(False)
        if self.scenario is not None and self.state.document.scenario is self.scenario:
            self.scenario.unfinished = False  # the goal is checked now
            self.state.document.refresh()
        track = self.state.track
        open_lines = len(track.state(track.horizon).open_lines) if track is not None else 0
        note = f"; {open_lines} order line{'s' if open_lines != 1 else ''} still open" if open_lines else ""
        self.state.session.end(reason, note)
        self.state.say(f"Online session ended: {reason}{note}", 15000)
