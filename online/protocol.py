"""The online link's messages: what the visualizer, a solver and a simulator say over TCP.

A message is one line of text, ended by a newline: ASP facts (``atom.`` one after the
other, possibly none) and, last on the line, at most one control word ``%$NAME.`` or
``%$NAME(T).``.  To clingo a control word is a comment, so the facts of a message can be
given to clingo as they are.  Control words:

``%$RESET.``     forget everything: a new session starts (visualizer -> solver, simulator)
``%$done(T).``   the state after step T has been shown (visualizer -> solver, simulator)
``%$end.``       nothing more will arrive, ever (simulator -> visualizer)

The exchange (who sends what when) is described in ``visualizer/README.md``.
"""

from __future__ import annotations

import re
import socket
from collections.abc import Iterable
from dataclasses import dataclass

from asprilo.errors import InputError
from asprilo.facts import format_action
from asprilo.facts import instance_facts as all_facts
from asprilo.model import Action, Instance, Plan
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source

RESET, DONE, END = "RESET", "done", "end"
#: a control word at the end of a line
_CONTROL = re.compile(r"%\$(?P<name>RESET|done|end)(?:\((?P<step>-?\d+)\))?\.\s*$")
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


# --- facts in one line ------------------------------------------------------------------------------

def instance_facts(instance: Instance) -> str:
    """The instance's facts on one line."""
    return " ".join(all_facts(instance))


def action_facts(actions: Iterable[Action]) -> str:
    """``occurs/3`` facts on one line."""
    return " ".join(f"{format_action(action)}." for action in actions)


def read_world(texts: Iterable[str], name: str = "<online>") -> Instance:
    """The instance the facts of several messages describe together."""
    return read_instance([Source(name, text) for text in texts if text.strip()])


def read_actions(text: str, name: str = "<solver>") -> list[Action]:
    """The actions a message holds (none for an empty message)."""
    return list(read_plan(Source(name, text)).actions) if text.strip() else []


def shifted(plan: Plan, steps: int) -> list[Action]:
    """The plan's actions ``steps`` time steps later."""
    return [action._replace(step=action.step + steps) for action in plan.actions]


# --- lines over a socket (servers, scripts and tests) ---------------------------------------------------

class Channel:
    """A connected socket that reads and writes messages, each read with a time limit."""

    def __init__(self, connection: socket.socket, timeout: float | None = TIMEOUT):
        self.connection = connection
        self.connection.settimeout(timeout)
        self._reader = connection.makefile("r", encoding="utf-8", newline="\n")

    @classmethod
    def connect(cls, host: str, port: int, timeout: float | None = TIMEOUT) -> Channel:
        return cls(socket.create_connection((host, port), timeout=timeout), timeout)

    def send(self, message: Message) -> None:
        self.connection.sendall(message.text().encode("utf-8"))

    def receive(self) -> Message | None:
        """The next message; ``None`` when the other side closed the connection.
        Raises ``TimeoutError`` when nothing comes within the time limit."""
        line = self._reader.readline()
        return parse(line) if line else None

    def close(self) -> None:
        try:
            self._reader.close()
            self.connection.close()
        except OSError:
            pass
