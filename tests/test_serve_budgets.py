"""The servers' budgets against hostile clients (issue 34, item 5): a line must arrive whole
within ``line-seconds`` (a client's first line counted from connecting), an answer must be
taken within it, a session's facts stay within ``file-mb``; messages are data, so no client
makes the server open a path, and nothing a client sends ends the server.

Real sockets on 127.0.0.1, port 0.  Slowness is driven by setting ``line-seconds`` small
(or large, then small, while slow clients hold their places); no assertion is about how
long something took, and every wait has a generous guard (``GUARD``) against hanging."""

from __future__ import annotations

import contextlib
import errno
import os
import select
import socket
import struct
import threading
import time
from collections.abc import Callable, Iterator

import pytest
from helpers.online import TINY, served, serving, tiny

from asprilo.limits import Limits, current, parse_option, set_current, using
from asprilo.model import Action, Plan
from asprilo.online.planner import OnlinePlanner, Schedule
from asprilo.online.protocol import DONE, ERROR, Channel, Message, done, reset
from asprilo.online.serve import simulator_session, solver_session

GUARD = 60.0  # seconds any wait may take before the test counts as hung
WORLD = " ".join(line.strip() for line in TINY.strip().splitlines())
MOVE = Message("occurs(object(robot,1),action(move,(1,0)),1).")
TURNED_AWAY = Message("% the server serves 2 clients at once; try again later", ERROR)
SLOW = b"init(object(node,1),value(at,(1,1))). "  # what a slow client trickles, never a newline


def _one_move(instance, domain, cancel) -> Plan:
    return Plan([Action(1, 1, "move", (1, 0))])


def _server(session: Callable[[Channel], None], clients: int = 2):
    """A server of ``session`` on an ephemeral loopback port (idle timeout: the default hour)."""
    return serving(session, clients=clients)


@pytest.fixture
def solver() -> Iterator[int]:
    with _server(lambda channel: solver_session(channel, OnlinePlanner(_one_move))) as port:
        yield port


@pytest.fixture
def simulator() -> Iterator[int]:
    schedule = Schedule(tiny(), {2: 3})
    with _server(lambda channel: simulator_session(channel, schedule, lambda text: None)) as port:
        yield port


@pytest.fixture
def budget() -> Iterator[Callable[[float], None]]:
    """Set ``line-seconds`` while servers run (restored afterwards)."""
    before = current()
    yield lambda seconds: set_current(Limits(line_seconds=seconds))
    set_current(before)


def _connect(port: int) -> Channel:
    return Channel.connect("127.0.0.1", port, timeout=GUARD)


def _closed(channel: Channel) -> bool:
    """Whether the server has closed the connection (a reset counts: it may close with
    bytes of ours unread)."""
    try:
        return channel.receive() is None
    except ConnectionResetError:
        return True


def _refused(port: int, data: bytes) -> str:
    """Send ``data``: the error reply's text, after which the server has closed the connection."""
    channel = _connect(port)
    channel.connection.sendall(data)
    answer = channel.receive()
    assert answer is not None and answer.control == ERROR, answer
    assert _closed(channel)
    channel.close()
    return answer.facts


def _served(port: int) -> Message | None:
    """A well-behaved session with the solver: the world, then the actions of step 1."""
    channel = _connect(port)
    channel.send(reset())
    channel.send(Message(WORLD, DONE, 0))
    answer = channel.receive()
    channel.close()
    return answer


def _at_last(ask: Callable[[], Message | None]) -> Message | None:
    """``ask()``, again while the server turns us away (its places may still be taken for a
    moment; turned away, our next line may meet a closed connection)."""
    deadline = time.monotonic() + GUARD
    while True:
        try:
            answer = ask()
        except ConnectionError:
            answer = None
        if answer is not None and not answer.facts.startswith("% the server serves"):
            return answer
        assert time.monotonic() < deadline, "still turned away"
        time.sleep(0.05)


def _served_at_last(port: int) -> Message | None:
    return _at_last(lambda: _served(port))


class Trickler(threading.Thread):
    """A slow client: (optionally a whole first line, then) one byte every 50 ms, never a
    newline, until the server answers; ``answer`` is what it said, ``closed`` whether it
    then closed the connection."""

    def __init__(self, port: int, first: bytes = b""):
        super().__init__(daemon=True)
        self.channel = _connect(port)
        self.first_answer: Message | None = None
        if first:  # a line the server answers: then it surely holds a place
            self.channel.connection.sendall(first)
            self.first_answer = self.channel.receive()
        self.answer: Message | None = None
        self.closed = False
        self.start()

    def run(self) -> None:
        connection, deadline, sent = self.channel.connection, time.monotonic() + GUARD, 0
        with contextlib.suppress(OSError):
            while not select.select([connection], [], [], 0.05)[0] and time.monotonic() < deadline:
                connection.send(SLOW[sent % len(SLOW):][:1])
                sent += 1
        with contextlib.suppress(OSError):
            self.answer = self.channel.receive()
            self.closed = _closed(self.channel)
        self.channel.close()

    def finish(self) -> Message | None:
        self.join(GUARD)
        assert not self.is_alive(), "hung"
        assert self.closed
        return self.answer


def _late(seconds: str, what: str = "a line not complete within {} s of its first byte") -> Message:
    return Message(f"% {what.format(seconds)}, beyond the limit line-seconds={seconds} "
                   "(raise it with --limit line-seconds=N)", ERROR)


# --- a line within a time budget ----------------------------------------------------------------------

def test_line_seconds_is_a_limit():
    assert Limits().line_seconds == 60.0
    assert parse_option("line-seconds=0.5") == ("line_seconds", 0.5)


def test_a_slow_line_is_dropped_after_the_budget_while_others_are_served(solver, budget):
    budget(1000)
    slow = Trickler(solver)
    assert _served(solver) == MOVE  # served while the slow client trickles
    budget(0.2)
    assert slow.finish() == _late("0.2")
    assert _served(solver) == MOVE


def test_two_slow_clients_lock_a_two_client_server_no_longer_than_the_budget(simulator, budget):
    """The issue's case: two clients sending a byte now and then held a ``--clients 2``
    server for ever; now each line has ``line-seconds`` to arrive whole."""
    budget(1000)
    slow = [Trickler(simulator, first=b"%$RESET.\n") for _ in range(2)]
    assert all(s.first_answer is not None and s.first_answer.control is None for s in slow)  # the world
    assert _refused(simulator, b"") == TURNED_AWAY.facts  # both places are held
    budget(0.2)
    assert [s.finish() for s in slow] == [_late("0.2")] * 2
    answer = _at_last(lambda: _ask_world(simulator))
    assert answer is not None and "object(robot,1)" in answer.facts


def _ask_world(port: int) -> Message | None:
    channel = _connect(port)
    channel.send(reset())
    answer = channel.receive()
    channel.close()
    return answer


def test_a_client_that_never_speaks_is_let_go_after_the_budget(solver, budget):
    budget(0.2)
    assert _refused(solver, b"") == _late("0.2", "no line within {} s of connecting").facts
    with using(Limits(line_seconds=GUARD)):
        assert _served(solver) == MOVE


def test_silence_between_lines_is_the_idle_timeouts_not_the_line_budget(solver, budget):
    """The budget counts from a line's first byte: a client may think between lines."""
    budget(0.2)
    channel = _connect(solver)
    channel.send(reset())
    channel.send(Message(WORLD))
    time.sleep(0.6)  # longer than the budget (not a timing assertion: any longer pause holds too)
    channel.send(done(0))
    assert channel.receive() == MOVE
    channel.close()


def test_an_answer_not_taken_frees_the_place_after_the_budget(budget):
    """A client that asks and never reads holds its place no longer than the budget."""
    def session(channel: Channel) -> None:
        while (message := channel.receive()) is not None:
            channel.send(Message("p. " * 5_000_000 if message.facts == "big." else "small."))

    budget(0.2)
    with _server(session, clients=1) as port:
        greedy = _connect(port)
        greedy.send(Message("small."))
        assert greedy.receive() == Message("small.")  # it holds the only place
        greedy.send(Message("big."))  # 15 MB, never read
        assert _at_last(lambda: _ask(port, Message("small."))) == Message("small.")
        greedy.close()


def _ask(port: int, message: Message) -> Message | None:
    channel = _connect(port)
    channel.send(message)
    answer = channel.receive()
    channel.close()
    return answer


def test_sending_gives_up_after_the_budget():
    ours, theirs = socket.socketpair()
    try:
        with using(Limits(line_seconds=0.2)), pytest.raises(TimeoutError, match="an answer not taken within 0.2 s"):
            Channel(ours, timeout=GUARD).send(Message("p. " * 5_000_000))  # they never read
    finally:
        ours.close()
        theirs.close()


# --- cut off, closed, reset ------------------------------------------------------------------------------

def test_a_line_cut_off_by_a_close_is_no_message():
    ours, theirs = socket.socketpair()
    try:
        theirs.sendall(b"%$RESET.\n" + WORLD.encode() + b" %$done(0).")
        theirs.shutdown(socket.SHUT_WR)
        channel = Channel(ours, timeout=GUARD)
        assert channel.receive() == reset()
        assert channel.receive() is None and channel.cut_off
    finally:
        ours.close()
        theirs.close()


def test_a_client_that_goes_away_mid_line_is_let_go(solver):
    # a whole request but for its newline, then a half-close: no answer, the connection closed
    channel = _connect(solver)
    channel.connection.sendall(b"%$RESET.\n" + WORLD.encode() + b" %$done(0).")
    channel.connection.shutdown(socket.SHUT_WR)
    assert _closed(channel)
    channel.close()
    # a close, and a reset (SO_LINGER 0), in the middle of a fact
    for linger in (False, True):
        connection = socket.create_connection(("127.0.0.1", solver), timeout=GUARD)
        connection.sendall(b"%$RESET.\ninit(object(node,1),value(at,(1,")
        if linger:
            connection.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        connection.close()
    assert _served_at_last(solver) == MOVE  # once the server has seen them go
    assert _served_at_last(solver) == MOVE


# --- no path is ever opened ----------------------------------------------------------------------------

def _nobody_reads(fifo: str) -> bool:
    """Whether no process has ``fifo`` open for reading (a writer's non-blocking open fails)."""
    try:
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
    except OSError as failure:
        return failure.errno == errno.ENXIO
    return False


@pytest.mark.parametrize("allow_rules", [False, True])
def test_no_message_makes_the_server_open_a_path(solver, tmp_path, allow_rules):
    """A FIFO named in ``#include`` (plain, after a lexer error, after a comment), ``#script``
    or a string: opening it would hang the server; each line is refused (or, a string being
    data, served), and nobody ever opens the FIFO, ``--allow-rules`` in force or not."""
    fifo = str(tmp_path / "fifo")
    os.mkfifo(fifo)
    name = fifo.encode()
    include = b"% <online>:1: #include is not followed in data (give every file on the command line)"
    cases = {
        b'#include "' + name + b'". %$done(0).\n': include,
        b'%* *% #include "' + name + b'". %$done(0).\n': include,
        b"#include <incmode>. %$done(0).\n": include,
        b'p("\\q"). #include "' + name + b'". %$done(0).\n':
            b"% <online>:1: lexer error, the escape '\\q' in a string (strings know \\\", \\\\ and \\n)",
        b'#script (python) open("' + name + b'") #end. %$done(0).\n':
            b"% <online>:1: #script is not followed in data (give every file on the command line)",
        b'p :- #include "' + name + b'". %$done(0).\n': b"% <online>:1: ",
    }
    with using(Limits(allow_rules=allow_rules)):
        for line, reason in cases.items():
            assert _refused(solver, line).startswith(reason.decode()), line
            assert _nobody_reads(fifo)
        channel = _connect(solver)
        channel.send(Message(WORLD + f' p("{fifo}"). file("{fifo}").', DONE, 0))
        assert channel.receive() == MOVE
        channel.close()
    assert _nobody_reads(fifo)


# --- terms that crashed clingo, bytes that are no text, lines beyond the size budget ----------------------

DEEP = "% <online>:1: terms nested more deeply, beyond the limit depth=100 (raise it with --limit depth=N)"


@pytest.mark.parametrize("term", ["(" * 100_000 + "1" + ")" * 100_000, "f(" * 100_000 + "1" + ")" * 100_000,
                                  "(" * 100_000, "-(" * 20_000 + "1" + ")" * 20_000,
                                  "|" * 20_000 + "1" + "|" * 20_000],
                         ids=["brackets", "functions", "unclosed", "minus", "abs"])
def test_deep_terms_are_refused_and_the_server_goes_on(solver, term):
    assert _refused(solver, f"p({term}). %$done(0).\n".encode()) == DEEP
    assert _served(solver) == MOVE


@pytest.mark.parametrize("term", ["~" * 20_000 + "1", "1+" * 20_000 + "1", "- " * 20_001 + "1",
                                  "1*" * 20_000 + "1"], ids=["tilde", "plus", "minus", "times"])
def test_20000_operators_are_evaluated_as_data(solver, term):
    channel = _connect(solver)
    channel.send(Message(f"#const c = {term}. {WORLD} p({term}). q(c).", DONE, 0))
    assert channel.receive() == MOVE
    channel.close()


@pytest.mark.parametrize("data", [b"\xed\xa0\x80", b"\xc0\xaf", b"\x80", b"\xe2\x82", b"\xff\xfe"],
                         ids=["surrogate", "overlong", "continuation", "truncated", "ff"])
def test_bytes_that_are_no_utf8_are_refused(solver, data):
    reason = _refused(solver, b"p(1). " + data + b"\n")
    assert reason.startswith("% <line>:1: not a UTF-8 text file (byte 0x"), reason
    assert _served(solver) == MOVE


@pytest.mark.parametrize("data", [b"p(\x1b[31m). %$done(0).\n", b"p(\x00). %$done(0).\n",
                                  b"\x1b]0;owned\x07 %$done(0).\n", b"p(1). %$st\x1bop.\n"])
def test_control_characters_never_come_back_raw(solver, data):
    reason = _refused(solver, data)
    assert reason.isprintable() and "\x1b" not in reason, reason
    assert _served(solver) == MOVE


def test_a_line_beyond_the_size_budget_is_refused_while_the_client_still_sends(solver):
    with using(Limits(file_mb=1)):
        channel = _connect(solver)
        sender = threading.Thread(target=_send_quietly, args=(channel.connection, b"p(1). " * 700_000), daemon=True)
        sender.start()  # 4 MB, no newline: refused once beyond 1 MB
        answer = channel.receive()
        channel.close()
        sender.join(GUARD)
    assert answer == Message("% a line of more than 1 MB, beyond the limit file-mb=1 (raise it with --limit file-mb=N)",
                             ERROR)
    assert _served(solver) == MOVE


def _send_quietly(connection: socket.socket, data: bytes) -> None:
    with contextlib.suppress(OSError):
        connection.sendall(data)


def test_the_facts_of_a_session_stay_within_the_size_budget(solver):
    """Lines each within ``file-mb`` add up in the solver's world: together they are bounded too."""
    facts = "p(1). " * 70_000  # 420 kB
    with using(Limits(file_mb=1)):
        channel = _connect(solver)
        for _ in range(2):
            channel.send(Message(facts))
        channel.send(reset())  # forgets, and the count starts again
        for _ in range(3):
            channel.send(Message(facts))
        answer = channel.receive()
        assert _closed(channel)
        channel.close()
        assert answer == Message("% facts of more than 1 MB in one session (since its last reset), beyond the limit "
                                 "file-mb=1 (raise it with --limit file-mb=N)", ERROR)
        assert _served(solver) == MOVE


def test_a_session_that_fails_ends_its_client_only():
    def session(channel: Channel) -> None:
        while (message := channel.receive()) is not None:
            if message.facts == "boom.":
                raise RuntimeError("a bug")
            channel.send(message)

    with _server(session) as port:
        assert _refused(port, b"boom.\n") == "% the server failed on this line (RuntimeError)"
        assert _ask(port, Message("ok.")) == Message("ok.")


# --- the command line ---------------------------------------------------------------------------------------

def test_serve_takes_the_line_budget_from_the_command_line():
    with served("solver", "--limit", "line-seconds=0.5") as server:
        channel = _connect(server.port)  # and never a word
        assert channel.receive() == _late("0.5", "no line within {} s of connecting")
        channel.close()
        assert server.process.wait(GUARD) == 0
    assert "session: refused: no line within 0.5 s of connecting, beyond the limit line-seconds=0.5" in server.errors
