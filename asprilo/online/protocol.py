"""The online link's messages: what the visualizer, a solver and a simulator say over TCP.

A message is one line of text, ended by a newline: ASP facts (``atom.`` one after the
other, possibly none) and, last on the line, at most one control word ``%$NAME.`` or
``%$NAME(T).``.  To the fact language a control word is a comment.  Control words:

``%$RESET.``     forget everything: a new session starts (visualizer -> solver, simulator)
``%$done(T).``   the state after step T has been shown (visualizer -> solver, simulator)
``%$end.``       nothing more will arrive, ever (simulator -> visualizer)
``%$error.``     the last line was refused; a comment before it says why, and the server
                 closes the connection (solver, simulator -> visualizer)

The exchange (who sends what when) is described in ``asprilo/visualizer/README.md``.  Messages are
data: facts only, within the limits in force (:mod:`asprilo.limits`), never rules or
``#include``, whatever the command line allows for files; they are read by the parser all
data goes through (:mod:`asprilo.parse`), never handed to clingo as text.
"""

from __future__ import annotations

import contextlib
import re
import socket
import time
from collections.abc import Iterable
from dataclasses import dataclass, replace

from asprilo.errors import InputError
from asprilo.facts import format_action
from asprilo.facts import instance_facts as all_facts
from asprilo.limits import Limits, current
from asprilo.model import Action, Instance, Plan
from asprilo.policy import decode
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source, load_facts

from .budgets import MemoryPool, Pace, SessionBudget

RESET, DONE, END, ERROR = "RESET", "done", "end", "error"
#: a control word at the end of a line
_CONTROL = re.compile(r"%\$(?P<name>RESET|done|end|error)(?:\((?P<step>-?\d{1,9})\))?\.\s*$")
#: how long to wait for a line by default (seconds): nobody waits for ever
TIMEOUT = 30.0


@dataclass(frozen=True)
class Message:
    """One line: its facts (ASP text, possibly empty) and its control word, if any."""

    facts: str = ""
    control: str | None = None
    step: int | None = None  # T of %$done(T).

    def text(self) -> str:
        """The message as sent: one line ending with a newline."""
        control = ""
        if self.control is not None:
            control = f"%${self.control}" + (f"({self.step})" if self.step is not None else "") + "."
        return " ".join(part for part in (self.facts, control) if part) + "\n"


def parse(line: str) -> Message:
    """A received line as a :class:`Message` (facts are not checked here)."""
    line = line.rstrip("\r\n")
    match = _CONTROL.search(line)
    if match is None:
        if "%$" in line:
            raise InputError(f"unknown control word in {line.strip()[:80]!r}")
        return Message(line.strip())
    step = match.group("step")
    if (step is None) != (match.group("name") != DONE):
        raise InputError(f"malformed control word {match.group(0).strip()!r}")
    return Message(line[:match.start()].strip(), match.group("name"), None if step is None else int(step))


def reset() -> Message:
    return Message(control=RESET)


def done(step: int) -> Message:
    return Message(control=DONE, step=step)


def error(reason: str) -> Message:
    """The answer to a line that is refused: the reason as a comment, then ``%$error.``"""
    words = " ".join(reason.replace("%$", "% $").split())
    return Message(f"% {words[:500]}", ERROR)


def message_limits() -> Limits:
    """The limits messages are read within: those in force, rules never allowed."""
    return replace(current(), allow_rules=False)


def check_facts(text: str, name: str = "<online>") -> None:
    """Refuse a message whose facts are not data: parsed as every file is (:mod:`asprilo.parse`),
    rules never allowed."""
    load_facts([Source(name, text)], message_limits(), names=set())


# --- facts in one line ------------------------------------------------------------------------------

def instance_facts(instance: Instance) -> str:
    """The instance's facts on one line."""
    return " ".join(all_facts(instance))


def action_facts(actions: Iterable[Action]) -> str:
    """``occurs/3`` facts on one line."""
    return " ".join(f"{format_action(action)}." for action in actions)


def read_world(texts: Iterable[str], name: str = "<online>") -> Instance:
    """The instance the facts of several messages describe together."""
    return read_instance([Source(name, text) for text in texts if text.strip()], message_limits())


def read_actions(text: str, name: str = "<solver>") -> list[Action]:
    """The actions a message holds (none for an empty message)."""
    return list(read_plan(Source(name, text), message_limits()).actions) if text.strip() else []


def shifted(plan: Plan, steps: int) -> list[Action]:
    """The plan's actions ``steps`` time steps later."""
    return [action._replace(step=action.step + steps) for action in plan.actions]


# --- lines over a socket (servers, scripts and tests) ---------------------------------------------------

class Channel:
    """A connected socket that reads and writes messages within time budgets.

    Silence between lines may last ``timeout`` seconds; a line, once its first byte has come,
    must arrive whole within the ``line-seconds`` limit (with ``speaks_first``, the first line
    counts from now: a server's client must say something within it), and each line sent must
    be taken within it too.  A line longer than the ``file-mb`` limit or not UTF-8 is refused;
    a line cut off by the other side closing is no message.  A server's channel has a
    ``session`` budget (its length and lines per minute) and draws the bytes of its
    unfinished line, and those the session keeps, from a ``pool`` shared by all clients."""

    def __init__(self, connection: socket.socket, timeout: float | None = TIMEOUT, speaks_first: bool = False,
                 session: SessionBudget | None = None, pool: MemoryPool | None = None):
        self.connection = connection
        self.session = session
        self._deadline = None if session is None else session.clock() + session.seconds
        self._pace = None if session is None else Pace(session)
        self.pool = pool
        self._last = 0  # bytes of the line returned last, held from the pool until the next is read
        self._kept = 0  # bytes the session keeps (:meth:`keep`)
        self.timeout = timeout
        self.connection.settimeout(timeout)
        self._buffer = bytearray()
        #: when the line being read began (monotonic seconds); None until its first byte
        self._began: float | None = time.monotonic() if speaks_first else None
        self._first = speaks_first  # no line has come yet, and the budget counts from connecting
        #: the other side closed in the middle of a line (which was ignored)
        self.cut_off = False

    @classmethod
    def connect(cls, host: str, port: int, timeout: float | None = TIMEOUT) -> Channel:
        return cls(socket.create_connection((host, port), timeout=timeout), timeout)

    def send(self, message: Message, timeout: float | None = None) -> None:
        """Send one line; ``TimeoutError`` when the other side does not take it within the
        ``line-seconds`` limit (or ``timeout``, or the channel's timeout, if shorter)."""
        wait = _shortest(self.timeout, current().line_seconds, timeout)
        self.connection.settimeout(wait)
        try:
            self.connection.sendall(message.text().encode("utf-8"))
        except TimeoutError:
            raise TimeoutError(f"an answer not taken within {wait:g} s") from None
        finally:
            self.connection.settimeout(self.timeout)

    def receive(self) -> Message | None:
        """The next message; ``None`` when the other side closed the connection.
        Raises ``TimeoutError`` when nothing comes within the time limit and
        :class:`InputError` for a line that is too long, too slow or not text."""
        line = self._line()
        return None if line is None else parse(decode(line, "<line>"))

    def keep(self, size: int) -> None:
        """Hold ``size`` bytes from the pool for what the session keeps (until :meth:`forget`)."""
        if self.pool is not None:
            self.pool.take(size)
            self._kept += size

    def forget(self) -> None:
        """Give back what :meth:`keep` held."""
        if self.pool is not None:
            self.pool.give(self._kept)
        self._kept = 0

    def _line(self) -> bytes | None:
        limits = current()
        most = limits.file_mb * 2**20
        self._give(self._last)
        self._last = 0
        if self._deadline is not None and self.session is not None and self.session.clock() >= self._deadline:
            raise self.session.ended()
        if self._began is None and self._buffer:  # the rest of the last read begins this line
            self._began = time.monotonic()
        start = 0
        while (end := self._buffer.find(b"\n", start)) < 0:
            if len(self._buffer) > most:
                raise limits.exceeded("file_mb", f"a line of more than {limits.file_mb:,} MB")
            start = len(self._buffer)
            chunk = self._receive(current())  # read anew: the budget may change meanwhile
            if not chunk:
                self.cut_off = bool(self._buffer)
                self._give(len(self._buffer))
                self._buffer, self._began = bytearray(), None
                return None
            if self._began is None:
                self._began = time.monotonic()
            if self.pool is not None:
                self.pool.take(len(chunk))
            self._buffer += chunk
        if self._pace is not None:
            self._pace.count()
        line = bytes(self._buffer[:end + 1])
        del self._buffer[:end + 1]
        self._last = end + 1
        self._began, self._first = (time.monotonic() if self._buffer else None), False
        return line

    def _receive(self, limits: Limits) -> bytes:
        """What comes next, waiting at most the channel's timeout and never beyond the line's budget."""
        wait, budget = self.timeout, limits.line_seconds
        late = ended = False
        if self._began is not None:
            left = self._began + budget - time.monotonic()
            late = wait is None or left <= wait
            wait = left if late else wait
            if left <= 0:
                raise self._late(limits)
        if self._deadline is not None and self.session is not None:
            left = self._deadline - self.session.clock()
            if left <= 0:
                raise self.session.ended()
            if wait is None or left < wait:
                wait, late, ended = left, False, True
        self.connection.settimeout(wait)
        try:
            return self.connection.recv(1 << 16)
        except TimeoutError:
            if ended and self.session is not None:
                raise self.session.ended() from None
            if late:
                raise self._late(limits) from None
            raise TimeoutError(f"nothing received for {wait:g} s") from None
        finally:
            self.connection.settimeout(self.timeout)

    def _late(self, limits: Limits) -> InputError:
        budget = limits.line_seconds
        if self._first and not self._buffer:
            return limits.exceeded("line_seconds", f"no line within {budget:g} s of connecting")
        return limits.exceeded("line_seconds", f"a line not complete within {budget:g} s of its first byte")

    def _give(self, size: int) -> None:
        if self.pool is not None and size:
            self.pool.give(size)

    def close(self) -> None:
        """Close the connection and give back all the pool holds for it."""
        self._give(len(self._buffer) + self._last)
        self._buffer, self._last = bytearray(), 0
        self.forget()
        with contextlib.suppress(OSError):
            self.connection.close()


def _shortest(*seconds: float | None) -> float | None:
    """The shortest of these waits (``None``: no limit)."""
    given = [s for s in seconds if s is not None]
    return min(given) if given else None
