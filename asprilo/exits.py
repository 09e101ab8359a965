"""The exit statuses of every command (README: "Exit status"), one table for all:

- ``0``: done (a plan found, a plan valid, files written);
- ``1``: done, and the answer is no: no plan within the limits, a plan that breaks the rules,
  an encoding graded below full marks;
- ``2`` (:data:`REFUSED`): nothing done: bad input, a usage error, an output that cannot be
  written, a limit that cannot be honoured (a ``--memory-limit`` above ``ulimit -v``);
- ``130`` (:data:`INTERRUPTED`): stopped by Ctrl-C, SIGTERM or SIGHUP, whatever was kept
  (``solve``'s best plan so far, ``gen``'s instances, ``bench``'s finished runs); a server too.
"""

from __future__ import annotations

import _thread
import contextlib
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from types import CodeType, FrameType

#: nothing was done: bad input, a usage error, an output that cannot be written
REFUSED = 2
#: stopped from outside (Ctrl-C, SIGTERM, SIGHUP): 128 plus SIGINT's number, as shells say it
INTERRUPTED = 130

#: callbacks that clingo runs in a C++ nothrow scope, where an exception aborts the whole
#: process ("PANIC: exception in nothrow scope"); :mod:`asprilo.clingo_logger` adds its logger
NOTHROW_CALLBACKS: set[CodeType] = set()

Handler = Callable[[int, FrameType | None], object]


def cannot_raise(frame: FrameType | None) -> bool:
    """Whether the Python code running at ``frame`` cannot pass an exception on: a clingo
    callback in a nothrow scope, or a destructor (Python prints the exception and drops it,
    so a stop request raised there would be lost)."""
    while frame is not None:
        if frame.f_code in NOTHROW_CALLBACKS or frame.f_code.co_name == "__del__":
            return True
        frame = frame.f_back
    return False


def deferring(handler: Handler) -> Handler:
    """``handler`` for a stop signal, put off while code that cannot raise runs: the signal is
    then raised again for the main thread, and handled at its first step out of that code."""

    def handle(number: int, frame: FrameType | None) -> None:
        if cannot_raise(frame):
            # raised again by a thread of its own (a bare one: the threading module's locks may
            # be held where the signal came); raised from here, it would be handled at once,
            # inside this handler
            _thread.start_new_thread(_signal_main_thread_soon, (number,))
        else:
            handler(number, frame)

    return handle


@contextlib.contextmanager
def keeping_lost_stops() -> Iterator[None]:
    """A stop request (KeyboardInterrupt) raised where Python cannot pass it on and only
    reports it (a destructor the frame test missed, a weakref callback, a finalizer) is not
    lost meanwhile: Ctrl-C is raised again for the main thread."""
    previous = sys.unraisablehook

    def hook(unraisable) -> None:
        if isinstance(unraisable.exc_value, KeyboardInterrupt):
            _thread.start_new_thread(_signal_main_thread_soon, (signal.SIGINT,))
        else:
            previous(unraisable)

    sys.unraisablehook = hook
    try:
        yield
    finally:
        sys.unraisablehook = previous


def _signal_main_thread_soon(number: int) -> None:
    time.sleep(_RETRY_SECONDS)
    _thread.interrupt_main(signal.Signals(number))


#: how long a put-off stop signal waits before it is raised again
_RETRY_SECONDS = 0.005


@contextlib.contextmanager
def stopping_on_interrupt(cancel: threading.Event) -> Iterator[None]:
    """While a long search or run goes on, the first Ctrl-C sets ``cancel`` (it stops, keeping
    what it found; the command then exits :data:`INTERRUPTED`); the second one interrupts as
    usual."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.getsignal(signal.SIGINT)

    def stop(_signal: int, _frame: object) -> None:
        cancel.set()
        signal.signal(signal.SIGINT, previous if previous is not None else signal.SIG_DFL)

    signal.signal(signal.SIGINT, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous if previous is not None else signal.SIG_DFL)
