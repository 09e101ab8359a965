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

import contextlib
import signal
import threading
from collections.abc import Iterator

#: nothing was done: bad input, a usage error, an output that cannot be written
REFUSED = 2
#: stopped from outside (Ctrl-C, SIGTERM, SIGHUP): 128 plus SIGINT's number, as shells say it
INTERRUPTED = 130


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
