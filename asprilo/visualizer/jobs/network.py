"""The visualizer's side of the online link: non-blocking connections to a solver and a
simulator (QTcpSocket), and the session that plays the world they describe step by step.

Nothing here ever waits: sockets report through Qt signals, and every answer that is
expected has a deadline, after which the session stops with a message.  Whatever a server
sends, the session ends with a reason rather than the window: bytes that are not UTF-8, a
line longer than ``MAX_LINE_BYTES``, a message that is malformed or whose facts the reader
refuses.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PyQt5.QtCore import QObject, QTimer, pyqtSignal
from PyQt5.QtNetwork import QAbstractSocket, QTcpSocket

from asprilo.errors import InputError
from asprilo.model import Action, Instance
from asprilo.online.protocol import DONE, END, Message, done, instance_facts, parse, read_actions, read_world, reset

#: seconds to wait for a connection, for the simulator's and for the solver's answers
CONNECT_SECONDS, SIMULATOR_SECONDS, SOLVER_SECONDS = 10.0, 30.0, 300.0
#: the longest line a server may send (a 200x200 warehouse's world is about 2 MB)
MAX_LINE_BYTES = 32 * 2**20


class LineLink(QObject):
    """One TCP connection exchanging one-line messages; ``received`` per line that comes in."""

    connected = pyqtSignal()
    received = pyqtSignal(object)   # Message
    failed = pyqtSignal(str)

    def __init__(self, role: str, host: str, port: int, answer_seconds: float, parent: QObject | None = None):
        super().__init__(parent)
        self.role, self.host, self.port = role, host, port
        self.answer_seconds = answer_seconds
        self.waiting = 0  # answers still expected
        self.socket = QTcpSocket(self)
        self.socket.connected.connect(self._connected)
        self.socket.readyRead.connect(self._read)
        self.socket.errorOccurred.connect(self._error)
        self.deadline = QTimer(self)
        self.deadline.setSingleShot(True)
        self.deadline.timeout.connect(self._late)

    @property
    def where(self) -> str:
        return f"the {self.role} at {self.host}:{self.port}"

    def open(self) -> None:
        self.deadline.start(int(CONNECT_SECONDS * 1000))
        self.socket.connectToHost(self.host, self.port)

    def send(self, message: Message, answered: bool = False) -> None:
        """Send a message; ``answered``: one line is expected back (within the deadline)."""
        self.socket.write(message.text().encode("utf-8"))
        if answered:
            self.waiting += 1
            if not self.deadline.isActive():
                self.deadline.start(int(self.answer_seconds * 1000))

    def close(self) -> None:
        self.deadline.stop()
        self.waiting = 0
        for signal in (self.socket.connected, self.socket.readyRead, self.socket.errorOccurred):
            signal.disconnect()
        self.socket.abort()

    def _connected(self) -> None:
        self.deadline.stop()
        self.connected.emit()

    def _read(self) -> None:
        while self.socket.canReadLine():
            data = bytes(self.socket.readLine(MAX_LINE_BYTES + 2))
            if not data.endswith(b"\n"):
                self._refuse(f"a line longer than {_size(MAX_LINE_BYTES)}")
                return
            self.waiting = max(0, self.waiting - 1)
            if self.waiting:
                self.deadline.start(int(self.answer_seconds * 1000))
            else:
                self.deadline.stop()
            try:
                message = parse(data.decode("utf-8"))
            except UnicodeDecodeError as error:
                self._refuse(f"bytes that are not UTF-8 (0x{data[error.start]:02X} at byte {error.start + 1} "
                             "of a line)")
                return
            except InputError as error:
                self._refuse(f"a bad message: {error.message}")
                return
            self.received.emit(message)
        if self.socket.bytesAvailable() > MAX_LINE_BYTES:
            self._refuse(f"a line longer than {_size(MAX_LINE_BYTES)}")

    def _refuse(self, what: str) -> None:
        self.failed.emit(f"{self.where} sent {what}")

    def _error(self, _error) -> None:
        if self.socket.error() == QAbstractSocket.RemoteHostClosedError:
            self.failed.emit(f"{self.where} closed the connection")
        else:
            self.failed.emit(f"{self.where}: {self.socket.errorString()}")

    def _late(self) -> None:
        if self.socket.state() != QAbstractSocket.ConnectedState:
            self.failed.emit(f"{self.where} does not accept connections (waited {CONNECT_SECONDS:g} s)")
        else:
            self.failed.emit(f"{self.where} did not answer within {self.answer_seconds:g} s")


def _size(count: int) -> str:
    return f"{count / 2**20:g} MB" if count >= 2**20 else f"{count:,} bytes"


class LiveSession(QObject):
    """Plays a world online: the simulator (or the instance given) says what the world is and
    what arrives when, the solver what the robots do, one step at a time.

    The window reports every state it has shown through :meth:`shown`; when that is the last
    state known, the session asks for the next step: ``%$done(T).`` to the simulator, whose
    answer (the facts arriving at T) goes to the solver followed by ``%$done(T).``; the
    solver's answer holds the actions of step T+1.  Facts the window sends (orders written
    during the session, :meth:`send`) go to the solver with the next ``%$done(T).``, like
    facts from the simulator.
    """

    world_changed = pyqtSignal(object, bool)   # the Instance; whether it is the first world
    stepped = pyqtSignal(int)                  # the actions of this step arrived
    status = pyqtSignal(str)
    stopped = pyqtSignal(str)                  # why the session ended

    def __init__(self, host: str, solver_port: int, simulator_port: int | None = None,
                 instance: Instance | None = None, parent: QObject | None = None):
        super().__init__(parent)
        if (simulator_port is None) == (instance is None):
            raise ValueError("give either a simulator port or an instance")
        self.instance = instance
        self.facts: list[str] = [instance_facts(instance)] if instance is not None else []
        self.actions: list[Action] = []
        self.frontier = 0          # the last step whose actions are known
        self.asking: int | None = None  # the step being asked about
        self.outbox: list[str] = []  # facts from the window for the solver, sent with the next question
        self._sending = ""  # those facts, while their question waits for the simulator
        self.ended = simulator_port is None  # nothing more will arrive
        self.running = False
        self._pending: set[LineLink] = set()  # links not connected yet
        self.solver = LineLink("solver", host, solver_port, SOLVER_SECONDS, self)
        self.simulator = (LineLink("simulator", host, simulator_port, SIMULATOR_SECONDS, self)
                          if simulator_port is not None else None)
        self.links = [link for link in (self.solver, self.simulator) if link is not None]
        for link in self.links:
            link.connected.connect(self._connected)
            link.failed.connect(self.stop)
        self.solver.received.connect(self._from_solver)
        if self.simulator is not None:
            self.simulator.received.connect(self._from_simulator)

    def start(self) -> None:
        self.running = True
        self._pending = set(self.links)
        for link in self.links:
            link.open()
        self.status.emit("connecting to " + " and ".join(link.where for link in self.links) + "…")

    def stop(self, reason: str = "disconnected") -> None:
        """End the session (the actions received so far stay)."""
        if not self.running:
            return
        self.running = False
        for link in self.links:
            link.close()
        self.stopped.emit(reason)

    def send(self, facts: str) -> None:
        """Tell the solver these facts (new orders) with the next question."""
        self.outbox.append(facts)

    def shown(self, step: int) -> None:
        """The window shows the state after ``step``: ask for the next one if it is the last
        known (when the robots waited at the last steps, the last state the plan shows)."""
        last = max((action.step for action in self.actions), default=0)
        if not self.running or step < min(self.frontier, last) or self.asking is not None or self._pending:
            return
        self.asking = self.frontier
        self._sending, self.outbox = " ".join(self.outbox), []
        if self._sending and not self._learn(self._sending):
            return
        if self._sending:
            self.world_changed.emit(self.instance, False)
        if self.simulator is not None:
            self.simulator.send(done(self.asking), answered=True)
        else:
            self.solver.send(Message(self._sending, DONE, self.asking), answered=True)
        self.status.emit(f"asking for step {self.asking + 1}…")

    # --- answers ---------------------------------------------------------------------------------

    def _connected(self) -> None:
        self._pending.discard(self.sender())
        if self._pending:
            return
        if self.simulator is not None:
            self.simulator.send(reset(), answered=True)
        else:
            self._begin()

    def _begin(self) -> None:
        """The world at step 0 is known: tell the solver, then show it (the window's report of
        state 0 starts the steps)."""
        self.solver.send(reset())
        self.solver.send(Message(self.facts[0]))
        self.world_changed.emit(self.instance, True)

    def _from_simulator(self, message: Message) -> None:
        if not self.running:
            return
        self.ended = self.ended or message.control == END
        if self.instance is None:  # the answer to %$RESET.: the world at step 0
            if not self._learn(message.facts):
                return
            self._begin()
            return
        if self.asking is None:
            return  # not asked: ignored
        if message.facts:
            if not self._learn(message.facts):
                return
            self.world_changed.emit(self.instance, False)
            self.status.emit(f"step {self.asking}: new facts arrived, the solver re-plans…")
        facts = " ".join(part for part in (message.facts, self._sending) if part)
        self.solver.send(Message(facts, DONE, self.asking), answered=True)

    def _learn(self, facts: str) -> bool:
        world = self._read(lambda: read_world(self.facts + [facts], "<simulator>"),
                           "the simulator sent facts that are no instance")
        if world is None:
            return False
        self.facts.append(facts)
        if self.instance is None:
            self.instance = world
        else:  # grow the instance shown rather than replacing it
            self.instance.__dict__.update(world.__dict__)
        return True

    def _from_solver(self, message: Message) -> None:
        if not self.running or self.asking is None:
            return
        actions = self._read(lambda: read_actions(message.facts), "the solver sent no actions")
        if actions is None:
            return
        step, self.asking = self.asking + 1, None
        wrong = [a for a in actions if a.step != step]
        if wrong:
            self.stop(f"asked for step {step}, the solver sent an action of step {wrong[0].step}")
            return
        if not actions and self.ended and not self.outbox:
            self.stop(f"the solver has nothing more to do after step {step - 1}")
            return
        self.actions += actions
        self.frontier = step
        self.stepped.emit(step)

    def _read(self, read: Callable[[], Any], what: str) -> Any:
        """``read()``, or ``None`` when it fails: then the session stops, saying ``what`` and why."""
        try:
            return read()
        except InputError as error:
            self.stop(f"{what}: {error}")
        except Exception as error:  # whatever the reader cannot cope with ends the session, not the window
            self.stop(f"{what}: {type(error).__name__}: {error}")
        return None
