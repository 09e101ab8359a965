"""What a server's clients may spend: each session's length and pace, and memory for all together.

A client that sends one short, complete line now and then is never idle and never slow, so
neither ``--idle-timeout`` nor ``line-seconds`` lets it go: a :class:`SessionBudget` does
(a session lasts at most ``seconds``, and sends at most ``lines_per_minute``).  Unfinished
lines and the facts a solver keeps for a session take memory: a :class:`MemoryPool` is one
budget of bytes that every client of a server draws from, so many clients together hold no
more than one budget (and not ``file-mb`` each).
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from asprilo.errors import InputError

SESSION_SECONDS = 3600.0  # the longest session, from connecting
LINES_PER_MINUTE = 6000  # the most lines a client may send in any 60 s
MEMORY_MB = 512  # unfinished lines and kept facts of all clients together


@dataclass(frozen=True)
class SessionBudget:
    """How long a session may last and how many lines it may send per minute."""

    seconds: float = SESSION_SECONDS
    lines_per_minute: int = LINES_PER_MINUTE
    clock: Callable[[], float] = field(default=time.monotonic, compare=False)

    def ended(self) -> InputError:
        """The refusal when a session has lasted ``seconds``."""
        return InputError(f"the session reached its length of {self.seconds:g} s (serve --session-seconds); "
                          "connect again to start a new one")


class Pace:
    """The times of a session's last lines: refuses a line beyond ``lines_per_minute``."""

    def __init__(self, budget: SessionBudget):
        self.budget = budget
        self._times: deque[float] = deque(maxlen=budget.lines_per_minute)

    def count(self) -> None:
        """Count a line now; :class:`InputError` if it is one more than the budget within 60 s."""
        now, most = self.budget.clock(), self.budget.lines_per_minute
        if len(self._times) == most and now - self._times[0] < 60.0:
            raise InputError(f"more than {most:,} lines within a minute (serve --lines-per-minute)")
        self._times.append(now)


class MemoryPool:
    """Bytes that all clients of a server hold together: lines being read, facts kept."""

    def __init__(self, megabytes: float = MEMORY_MB):
        self.megabytes = megabytes
        self.total = int(megabytes * 2**20)
        self.used = 0
        self._lock = threading.Lock()

    def take(self, size: int) -> None:
        """Hold ``size`` more bytes; :class:`InputError` (nothing held) when they do not fit."""
        with self._lock:
            if self.used + size > self.total:
                raise InputError(f"the server holds at most {self.megabytes:g} MB of lines and facts for all "
                                 "its clients together (serve --memory-mb) and this line does not fit now")
            self.used += size

    def give(self, size: int) -> None:
        """Give back ``size`` bytes taken before."""
        with self._lock:
            self.used -= size
