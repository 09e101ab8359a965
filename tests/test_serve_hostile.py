"""The servers and bad clients: invalid bytes, an idle client, rules, huge lines, steps
outside the plan, too many clients.  Each bad line gets an error reply (``%$error.``), its
connection closes, and the server goes on serving others."""

from __future__ import annotations

import socket
import threading

import pytest
from helpers.online import TINY, WAIT, tiny

from asprilo.limits import Limits, using
from asprilo.model import Action, Plan
from asprilo.online.planner import OnlinePlanner, Schedule
from asprilo.online.protocol import DONE, ERROR, Channel, Message, done, reset
from asprilo.online.serve import listen, serve, simulator_session, solver_session

WORLD = " ".join(line.strip() for line in TINY.strip().splitlines())


def _one_move(instance, domain, cancel) -> Plan:
    return Plan([Action(1, 1, "move", (1, 0))])


@pytest.fixture
def solver():
    """A solver (each client with a planner of its own) on an ephemeral loopback port,
    serving at most two clients at once."""
    stop = threading.Event()
    listener = listen("127.0.0.1", 0)
    thread = threading.Thread(target=serve, args=(listener, lambda c: solver_session(c, OnlinePlanner(_one_move))),
                              kwargs={"stop": stop, "clients": 2}, daemon=True)
    thread.start()
    yield listener.getsockname()[1]
    stop.set()
    thread.join(WAIT)
    listener.close()


@pytest.fixture
def simulator():
    stop = threading.Event()
    listener = listen("127.0.0.1", 0)
    schedule = Schedule(tiny(), {2: 3})
    thread = threading.Thread(target=serve, args=(listener, lambda c: simulator_session(c, schedule, print)),
                              kwargs={"stop": stop}, daemon=True)
    thread.start()
    yield listener.getsockname()[1]
    stop.set()
    thread.join(WAIT)
    listener.close()


def _raw(port: int, data: bytes) -> socket.socket:
    connection = socket.create_connection(("127.0.0.1", port), timeout=WAIT)
    connection.sendall(data)
    return connection


def _refused(port: int, data: bytes) -> str:
    """Send ``data``; the error reply's reason, after which the server has closed the line."""
    channel = Channel(_raw(port, data), timeout=WAIT)
    answer = channel.receive()
    assert answer is not None and answer.control == ERROR, answer
    assert channel.receive() is None  # closed by the server
    channel.close()
    return answer.facts


def _served(port: int) -> list:
    """A well-behaved session: the world, then the actions of step 1."""
    channel = Channel.connect("127.0.0.1", port, timeout=WAIT)
    channel.send(reset())
    channel.send(Message(WORLD, DONE, 0))
    answer = channel.receive()
    channel.close()
    return answer


def test_invalid_bytes_are_refused_and_the_server_goes_on(solver):
    reason = _refused(solver, b"init(object(node,1),value(at,(1,1))). \xff\xfe %$done(0).\n")
    assert reason == "% <line>:1: not a UTF-8 text file (byte 0xff cannot be read)"
    assert _served(solver) == Message("occurs(object(robot,1),action(move,(1,0)),1).")


def test_an_idle_client_does_not_keep_others_waiting(solver):
    idle = _raw(solver, b"")
    try:
        assert _served(solver) == Message("occurs(object(robot,1),action(move,(1,0)),1).")
    finally:
        idle.close()


def test_rules_are_refused_before_grounding(solver):
    reason = _refused(solver, b"p(0). p(X+1) :- p(X). %$done(0).\n")
    assert reason == ("% <online>:1: 'p(X+1) :- p(X).' is a rule; data holds only facts, #const and "
                      "'#program base.' (rules need --allow-rules)")
    assert _refused(solver, b'#include "/etc/passwd". %$done(0).\n').startswith(
        "% <online>:1: #include is not followed in data")
    assert _served(solver) == Message("occurs(object(robot,1),action(move,(1,0)),1).")


def test_a_line_beyond_the_size_limit_is_refused(solver):
    with using(Limits(file_mb=1)):
        reason = _refused(solver, b"p. " * (2**20 // 3 + 10))
    assert reason == "% a line of more than 1 MB, beyond the limit file-mb=1 (raise it with --limit file-mb=N)"


def test_steps_outside_the_plan_are_refused(solver, simulator):
    assert _refused(solver, b"%$RESET.\n%$done(-5).\n") == (
        "% done(-5) asks about a step outside the plan: the next step is 0")
    channel = Channel.connect("127.0.0.1", solver, timeout=WAIT)
    channel.send(Message(WORLD, DONE, 0))
    assert channel.receive() == Message("occurs(object(robot,1),action(move,(1,0)),1).")
    channel.send(done(5))
    answer = channel.receive()
    assert answer == Message("% done(5) asks about a step outside the plan: the next step is 1", ERROR)
    assert channel.receive() is None
    channel.close()
    assert _refused(simulator, b"%$done(-1).\n") == "% done(-1): steps start at 0"


def test_clients_beyond_the_limit_are_turned_away(solver):
    first, second = _raw(solver, b""), _raw(solver, b"")
    try:
        assert _refused(solver, b"") == "% the server serves 2 clients at once; try again later"
    finally:
        first.close()
        second.close()


def test_a_line_of_20000_operators_is_read_by_the_parser_and_the_server_goes_on(solver):
    """One line with 20,000 operators in a row killed the server (clingo segfaulted on it):
    messages are parsed, and clingo sees only terms."""
    reason = _refused(solver, b"p(" + b"2**" * 20_000 + b"2). %$done(0).\n")
    assert reason == ("% <online>:1: 2**65536 is out of range (clingo's numbers are 32-bit: -2147483648..2147483647; "
                      "clingo would wrap it around)")
    assert _refused(solver, b'p("\\q"). #include "/etc/passwd". %$done(0).\n').startswith(
        "% <online>:1: lexer error, the escape '\\q' in a string")
    channel = Channel.connect("127.0.0.1", solver, timeout=WAIT)
    channel.send(Message(WORLD + " p(" + "- " * 20_000 + "1).", DONE, 0))
    assert channel.receive() == Message("occurs(object(robot,1),action(move,(1,0)),1).")
    channel.close()
    assert _served(solver) == Message("occurs(object(robot,1),action(move,(1,0)),1).")
