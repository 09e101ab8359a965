"""A stop signal that comes while Python code runs that cannot raise is handled right after it.

Two such places were met: clingo's logger callback, which clingo runs in a C++ nothrow scope
(KeyboardInterrupt raised there aborted the process: "PANIC: exception in nothrow scope"), and
a destructor such as ``clingo.Control.__del__`` (the exception was printed and dropped, and the
command, its stop request lost, ran on).  A weakref finalizer would drop it in the same way;
``exits.keeping_lost_stops`` raises such a stop again after it.  The waits below are hang
guards, not measurements."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
import weakref
from pathlib import Path

import clingo
import pytest

from asprilo import clingo_logger
from asprilo.exits import cannot_raise, deferring

#: hang guard (seconds) for a put-off signal to be handled
GUARD = 5.0


@pytest.fixture
def heard():
    """SIGUSR1 handled by ``deferring``: the list of the frames' function names it was handled in."""
    calls: list[str] = []
    previous = signal.signal(signal.SIGUSR1, deferring(lambda _number, frame: calls.append(frame.f_code.co_name)))
    yield calls
    signal.signal(signal.SIGUSR1, previous)


def wait_for(calls: list[str]) -> None:
    deadline = time.monotonic() + GUARD
    while not calls and time.monotonic() < deadline:
        time.sleep(0.001)


def test_a_signal_in_a_destructor_is_handled_after_it(heard):
    during: list[list[str]] = []

    class Dropped:
        def __del__(self):
            signal.getsignal(signal.SIGUSR1)(signal.SIGUSR1, sys._getframe())
            during.append(list(heard))

    Dropped()
    wait_for(heard)
    assert during == [[]]
    assert len(heard) == 1 and heard[0] != "__del__"


def test_a_signal_in_clingos_logger_is_handled_after_it(heard):
    clingo_logger.install()
    during: list[list[str]] = []

    def logger(_code, _text):
        if not during:
            signal.getsignal(signal.SIGUSR1)(signal.SIGUSR1, sys._getframe())
        during.append(list(heard))

    control = clingo.Control(logger=logger)
    control.add("base", [], "a :- b. c :- d.")  # two atoms that occur in no head: two messages
    control.ground([("base", [])])
    wait_for(heard)
    assert during == [[], []]
    assert len(heard) == 1 and heard[0] not in ("logger", "_logger")


def test_a_stop_raised_in_a_finalizer_is_raised_again_after_it():
    """A weakref finalizer is no destructor the frame test knows: the stop raised there (as
    SIGTERM raises it during a command) is reported as unraisable, then raised again."""
    from asprilo.cli import _stops_as_interrupts

    class Owner:
        pass

    ran, interrupted = [], []
    with _stops_as_interrupts():
        owner = Owner()

        def stop_here() -> None:
            ran.append(True)
            signal.getsignal(signal.SIGTERM)(signal.SIGTERM, sys._getframe())

        weakref.finalize(owner, stop_here)
        try:
            del owner  # the finalizer runs here, and its KeyboardInterrupt is only reported
            deadline = time.monotonic() + GUARD
            while time.monotonic() < deadline:
                time.sleep(0.001)
        except KeyboardInterrupt:
            interrupted.append(True)
    assert ran == [True] and interrupted == [True]


def test_code_that_can_raise_is_told_at_once(heard):
    signal.getsignal(signal.SIGUSR1)(signal.SIGUSR1, sys._getframe())
    assert heard == ["test_code_that_can_raise_is_told_at_once"]
    assert not cannot_raise(sys._getframe())


#: clingo logs one message per atom that occurs in no rule head: many messages, grounded over
#: and over until a stop signal comes (at a random moment)
STOPPED_WHILE_LOGGING = """
import os, random, signal, sys, threading
import clingo
from asprilo import clingo_logger
from asprilo.cli import _stops_as_interrupts
clingo_logger.install()
program = "".join(f"d{i} :- e{i}.\\n" for i in range(300))
stop = getattr(signal, sys.argv[1])
threading.Timer(random.Random(sys.argv[2]).uniform(0.05, 0.3), os.kill, (os.getpid(), stop)).start()
try:
    with _stops_as_interrupts():
        while True:
            control = clingo.Control(logger=lambda code, text: None, message_limit=1000)
            control.add("base", [], program)
            control.ground([("base", [])])
except KeyboardInterrupt:
    sys.exit(130)
"""


@pytest.mark.parametrize("stop", ["SIGINT", "SIGTERM"])
def test_a_command_stopped_while_clingo_logs_ends_as_told(tmp_path: Path, stop: str):
    """Before, about one run in three ended in a PANIC or ran on; each run here is stopped at
    a moment of its own (the seed), twelve runs per signal."""
    script = tmp_path / "stopped.py"
    script.write_text(STOPPED_WHILE_LOGGING)
    ends = []
    for seed in range(12):
        run = subprocess.run([sys.executable, str(script), stop, str(seed)],
                             capture_output=True, text=True, timeout=60)
        ends.append((run.returncode, "PANIC" in run.stderr or "Exception ignored" in run.stderr))
    assert ends == [(130, False)] * 12
