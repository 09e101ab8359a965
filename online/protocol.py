"""The online link's messages: what the visualizer, a solver and a simulator say over TCP.

A message is one line of text, ended by a newline: ASP facts (``atom.`` one after the
other, possibly none) and, last on the line, at most one control word ``%$NAME.`` or
``%$NAME(T).``.  To the fact language a control word is a comment.  Control words:

``%$RESET.``     forget everything: a new session starts (visualizer -> solver, simulator)
``%$done(T).``   the state after step T has been shown (visualizer -> solver, simulator)
``%$end.``       nothing more will arrive, ever (simulator -> visualizer)
``%$error.``     the last line was refused; a comment before it says why, and the server
                 closes the connection (solver, simulator -> visualizer)

The exchange (who sends what when) is described in ``visualizer/README.md``.  Messages are
data: facts only, within the limits in force (:mod:`asprilo.limits`), never rules or
``#include``, whatever the command line allows for files; they are read by the parser all
data goes through (:mod:`asprilo.parse`), never handed to clingo as text.
"""

from __future__ import annotations

import contextlib
import re
import socket
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
    """A connected socket that reads and writes messages, each read and write with a time
    limit; a line longer than the ``file-mb`` limit or not UTF-8 is refused."""

    def __init__(self, connection: socket.socket, timeout: float | None = TIMEOUT):
        self.connection = connection
        self.connection.settimeout(timeout)
        self._buffer = bytearray()

    @classmethod
    def connect(cls, host: str, port: int, timeout: float | None = TIMEOUT) -> Channel:
        return cls(socket.create_connection((host, port), timeout=timeout), timeout)

    def send(self, message: Message) -> None:
        self.connection.sendall(message.text().encode("utf-8"))

    def receive(self) -> Message | None:
        """The next message; ``None`` when the other side closed the connection.
        Raises ``TimeoutError`` when nothing comes within the time limit and
        :class:`InputError` for a line that is too long or not text."""
        line = self._line()
        return None if line is None else parse(decode(line, "<line>"))

    def _line(self) -> bytes | None:
        limits = current()
        most = limits.file_mb * 2**20
        start = 0
        while (end := self._buffer.find(b"\n", start)) < 0:
            if len(self._buffer) > most:
                raise limits.exceeded("file_mb", f"a line of more than {limits.file_mb:,} MB")
            start = len(self._buffer)
            chunk = self.connection.recv(1 << 16)
            if not chunk:
                line, self._buffer = bytes(self._buffer), bytearray()
                return line or None
            self._buffer += chunk
        line = bytes(self._buffer[:end + 1])
        del self._buffer[:end + 1]
        return line

    def close(self) -> None:
        with contextlib.suppress(OSError):
            self.connection.close()
