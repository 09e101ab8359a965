"""Servers against clients that are never idle and never slow (issue 46, item 6): a client
trickling short complete lines holds its place no longer than the session's length, a
flood of lines is refused beyond the lines per minute, and unfinished lines and kept facts
of all clients together stay within one memory pool (not ``file-mb`` each).

Real sockets on 127.0.0.1, port 0.  Session time runs on a clock the test moves (no
assertion depends on how fast the machine is); every real wait has a generous guard."""

from __future__ import annotations

import contextlib
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable

import pytest
from helpers.online import TINY, served, serving

from asprilo.errors import InputError
from asprilo.model import Action, Plan
from asprilo.online.budgets import MemoryPool, Pace, SessionBudget
from asprilo.online.planner import OnlinePlanner
from asprilo.online.protocol import DONE, ERROR, Channel, Message, reset
from asprilo.online.serve import solver_session

GUARD = 60.0  # seconds any wait may take before the test counts as hung
WORLD = " ".join(line.strip() for line in TINY.strip().splitlines())
MOVE = Message("occurs(object(robot,1),action(move,(1,0)),1).")
ENDED = "% the session reached its length of 10 s (serve --session-seconds); connect again to start a new one"
FLOOD = "% more than 5 lines within a minute (serve --lines-per-minute)"
FULL = ("% the server holds at most 1 MB of lines and facts for all its clients together (serve --memory-mb) "
        "and this line does not fit now")
HALF = b"p(1). " * 66_667  # 400,002 bytes, never a newline


class Clock:
    """Session time that moves only when the test says."""

    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def _one_move(instance, domain, cancel) -> Plan:
    return Plan([Action(1, 1, "move", (1, 0))])


def _solver(channel: Channel) -> None:
    solver_session(channel, OnlinePlanner(_one_move))


def _ok(channel: Channel) -> None:
    """Answers every line with ``ok.``."""
    while channel.receive() is not None:
        channel.send(Message("ok."))


def _server(session: Callable[[Channel], None], budget: SessionBudget, pool: MemoryPool, clients: int = 8):
    return serving(session, clients=clients, budget=budget, pool=pool)


def _connect(port: int) -> Channel:
    return Channel.connect("127.0.0.1", port, timeout=GUARD)


def _answer_then_closed(channel: Channel) -> Message | None:
    """The server's next line, after which it has closed the connection."""
    answer = channel.receive()
    with contextlib.suppress(ConnectionResetError):  # a reset counts: it may close with bytes of ours unread
        assert channel.receive() is None
    channel.close()
    return answer


def _until(condition: Callable[[], bool]) -> None:
    deadline = time.monotonic() + GUARD
    while not condition():
        assert time.monotonic() < deadline, "hung"
        time.sleep(0.01)


class Trickler(threading.Thread):
    """The issue's client: one short complete line (``%$RESET.``, never answered) every
    20 ms, until the server says something."""

    def __init__(self, port: int):
        super().__init__(daemon=True)
        self.channel = _connect(port)
        self.channel.send(reset())  # the server holds a place for it once this is read
        self.answer: Message | None = None
        self.start()

    def run(self) -> None:
        connection, deadline = self.channel.connection, time.monotonic() + GUARD
        with contextlib.suppress(OSError):
            while time.monotonic() < deadline:
                connection.settimeout(0.02)
                try:
                    if connection.recv(1, socket.MSG_PEEK):
                        break
                except TimeoutError:
                    connection.sendall(b"%$RESET.\n")
            connection.settimeout(GUARD)
            self.answer = _answer_then_closed(self.channel)

    def finish(self) -> Message | None:
        self.join(GUARD)
        assert not self.is_alive(), "hung"
        return self.answer


# --- a session's length and pace -----------------------------------------------------------------------

def test_tricklers_hold_their_places_no_longer_than_the_session():
    clock = Clock()
    with _server(_solver, SessionBudget(seconds=10, clock=clock), MemoryPool(), clients=2) as port:
        tricklers = [Trickler(port) for _ in range(2)]
        turned_away = _connect(port)  # both places are held: its first answer says so
        assert _answer_then_closed(turned_away) == Message("% the server serves 2 clients at once; try again later",
                                                           ERROR)
        clock.now = 10.0  # the sessions have lasted their length
        assert [t.finish() for t in tricklers] == [Message(ENDED, ERROR)] * 2
        deadline = time.monotonic() + GUARD
        while (answer := _ask(port, Message(WORLD, DONE, 0))) != MOVE:  # a place is free once they are gone
            assert time.monotonic() < deadline and answer is not None and "serves 2 clients" in answer.facts
            time.sleep(0.05)


def _ask(port: int, message: Message) -> Message | None:
    channel = _connect(port)
    try:
        channel.send(message)
        return channel.receive()
    except ConnectionError:
        return None
    finally:
        channel.close()


def test_a_silent_client_is_let_go_at_the_end_of_its_session():
    """The session's length counts from connecting: shorter than the line budget, it ends first."""
    with served("solver", "--session-seconds", "0.3") as server:
        channel = _connect(server.port)  # and never a word
        assert channel.receive() == Message("% the session reached its length of 0.3 s (serve --session-seconds); "
                                            "connect again to start a new one", ERROR)
        channel.close()
        assert server.process.wait(GUARD) == 0
    assert ("session: refused: the session reached its length of 0.3 s (serve --session-seconds); "
            "connect again to start a new one\n") in server.errors


def test_lines_beyond_the_pace_are_refused():
    clock = Clock()
    with _server(_ok, SessionBudget(lines_per_minute=5, clock=clock), MemoryPool()) as port:
        channel = _connect(port)
        for _ in range(5):
            channel.send(Message("p."))
            assert channel.receive() == Message("ok.")
        channel.send(Message("p."))  # the sixth within the same minute
        assert _answer_then_closed(channel) == Message(FLOOD, ERROR)
        channel = _connect(port)  # a new session, a new count
        for second in (0.0, 0.0, 0.0, 0.0, 0.0, 60.0, 60.0):  # five now, two a minute later
            clock.now = second
            channel.send(Message("p."))
            assert channel.receive() == Message("ok.")
        channel.close()


def test_the_pace_counts_the_last_minute():
    clock = Clock()
    pace = Pace(SessionBudget(lines_per_minute=2, clock=clock))
    for clock.now in (0.0, 30.0, 60.0, 90.0, 120.0):  # never more than 2 within 60 s
        pace.count()
    clock.now = 149.0  # the third since 90.0
    with pytest.raises(InputError, match=r"^more than 2 lines within a minute \(serve --lines-per-minute\)$"):
        pace.count()


# --- one memory pool for all clients -------------------------------------------------------------------

def test_half_lines_of_all_clients_share_one_pool():
    """The issue's case: every client buffered up to ``file-mb`` of an unfinished line; now
    their half-lines together stay within the pool, the client beyond it is refused, the
    others finish their lines, and all is given back."""
    pool = MemoryPool(1)  # 1,048,576 bytes
    with _server(_ok, SessionBudget(), pool) as port:
        first, second = _connect(port), _connect(port)
        first.connection.sendall(HALF)
        second.connection.sendall(HALF)
        _until(lambda: pool.used == 2 * len(HALF))
        third = _connect(port)
        with contextlib.suppress(OSError):  # the server may close before it has all
            third.connection.sendall(HALF)
        assert _answer_then_closed(third) == Message(FULL, ERROR)
        _until(lambda: pool.used == 2 * len(HALF))  # the third's part is given back
        for channel in (first, second):
            channel.connection.sendall(b"\n")
            assert channel.receive() == Message("ok.")
            channel.close()
        _until(lambda: pool.used == 0)


def test_the_facts_a_solver_keeps_are_drawn_from_the_pool():
    """A line is held while it is worked on, and its facts while the session keeps them:
    420,001 + 420,000 bytes fit 1 MB, a second such line no longer does; a reset gives back."""
    facts = "p(1). " * 70_000  # 420,000 characters
    pool = MemoryPool(1)
    with _server(_solver, SessionBudget(), pool) as port:
        channel = _connect(port)
        for _ in range(2):
            channel.send(Message(facts))
            channel.send(reset())
        channel.send(Message(facts))
        channel.send(Message(WORLD, DONE, 0))
        assert channel.receive() == MOVE
        channel.send(Message(facts))
        assert _answer_then_closed(channel) == Message(FULL, ERROR)
        _until(lambda: pool.used == 0)
        assert _ask(port, Message(WORLD, DONE, 0)) == MOVE


@pytest.mark.parametrize("option", ["--session-seconds", "--lines-per-minute", "--memory-mb"])
def test_budgets_must_be_positive(option):
    done = subprocess.run([sys.executable, "-m", "asprilo.cli", "serve", "solver", option, "0", "--port", "0"],
                          capture_output=True, text=True, timeout=GUARD)
    assert (done.returncode, done.stdout) == (2, "")
    assert done.stderr == ("error: --clients, --idle-timeout, --session-seconds, --lines-per-minute and --memory-mb "
                           "must be positive\n")
