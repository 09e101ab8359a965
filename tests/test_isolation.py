"""asprilo.isolation: a child process under hard time and memory limits."""

from __future__ import annotations

import subprocess
import sys
import threading
import time

import pytest

from asprilo.errors import InputError
from asprilo.isolation import run_isolated


def _count(n, report):
    for i in range(n):
        report(i)
    return "finished"


def _sleep_for_ever(report):
    report("going to sleep")
    while True:
        time.sleep(1)


def _ground_for_ever(report):
    import clingo
    control = clingo.Control()
    control.add("base", [], "p(0). p(X+1) :- p(X).")
    control.ground([("base", [])])


def _bad_input(report):
    raise InputError("no such file", "missing.lp", 3)


def test_the_value_and_every_message_come_back():
    seen = []
    outcome = run_isolated(_count, (3,), time_limit=60, on_message=seen.append)
    assert (outcome.status, outcome.value, outcome.messages, seen) == ("done", "finished", [0, 1, 2], [0, 1, 2])


def test_the_deadline_stops_a_child_that_never_returns():
    outcome = run_isolated(_sleep_for_ever, time_limit=0.5)
    assert outcome.status == "timeout"  # (whether it said something by then depends on the machine)
    assert outcome.seconds >= 0.5  # it was given its time (measured by the clock that ended it)


def test_what_a_stopped_child_said_comes_back():
    cancel = threading.Event()
    # stopped once it has said something (the limit only guards against a hang)
    outcome = run_isolated(_sleep_for_ever, time_limit=120, on_message=lambda _message: cancel.set(),
                           cancel=cancel)
    assert (outcome.status, outcome.messages) == ("timeout", ["going to sleep"])


def test_the_deadline_stops_clingo_while_it_grounds():
    outcome = run_isolated(_ground_for_ever, time_limit=1)
    assert outcome.status == "timeout"


def test_the_memory_limit_stops_clingo_while_it_grounds():
    outcome = run_isolated(_ground_for_ever, time_limit=120, memory_mb=300)
    assert outcome.status == "memout"


def test_an_error_in_the_child_is_raised_in_the_parent():
    with pytest.raises(InputError) as raised:
        run_isolated(_bad_input)
    assert str(raised.value) == "missing.lp:3: no such file"


#: a child started and never waited for (as when an interrupt comes between its start and its
#: entry among the live children); it ignores SIGTERM, as every child does
UNWAITED_CHILD = """
import time
from asprilo.isolation import _start

def sleep(seconds, report):
    report("up")  # it ignores SIGTERM from now on
    time.sleep(seconds)

process, receiver = _start(sleep, (120,), None, None)
receiver.recv()
"""


def test_a_child_never_waited_for_does_not_keep_its_parent_at_exit():
    """multiprocessing's exit handler sends it SIGTERM, which it ignores, and waits for it: 120 s
    before; it is killed first now, and the parent ends at once (60 s is a hang guard)."""
    subprocess.run([sys.executable, "-c", UNWAITED_CHILD], timeout=60, check=True)
