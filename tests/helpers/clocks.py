"""Clocks for tests of searches with a time limit, so that no test depends on the machine's
speed: a limit only guards against a hang, and where a search stops depends on the search.

:class:`PatientClock` runs a hundred times slower than the wall until the search has reported
``stop_after`` results (plans of the anytime planner, horizons tried by the exact search),
then jumps past any limit: the search stops right there, on any machine, however loaded.
With ``stop_after=None`` it never jumps (a search that stops by itself at its lower bound).

:func:`patient_anytime` puts one in the anytime planner's module (for :func:`plan_anytime`
called directly: pass ``on_improvement=clock.reported``); :func:`patient_solves` gives every
``solve`` of the test (the API or a command, in this process) one of its own.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

#: how much slower than the wall a patient clock runs before it jumps
SLOWER = 100
#: where it jumps: past any limit a test sets
PAST_ANY_LIMIT = 1e6


class PatientClock:
    """A search's clock that waits for ``stop_after`` reports (and ``enough()``), then jumps."""

    def __init__(self, stop_after: int | None = 1, enough: Callable[[], bool] = lambda: True) -> None:
        self.started, self.stop_after, self.enough = time.perf_counter(), stop_after, enough
        self.reports = 0

    def perf_counter(self) -> float:
        """The time (the name of the ``time`` function it stands in for)."""
        jumped = self.stop_after is not None and self.reports >= self.stop_after and self.enough()
        return (time.perf_counter() - self.started) / SLOWER + (PAST_ANY_LIMIT if jumped else 0.0)

    __call__ = perf_counter

    def reported(self, _result: object = None) -> None:
        """Hear one report of the search."""
        self.reports += 1


def patient_anytime(monkeypatch, stop_after: int | None = 1, enough: Callable[[], bool] = lambda: True
                    ) -> PatientClock:
    """The clock of :func:`plan_anytime` calls with a watch of their own."""
    from asprilo.encodings.anytime import search

    clock = PatientClock(stop_after, enough)
    monkeypatch.setattr(search, "time", clock)
    return clock


def patient_solves(monkeypatch, *stop_after: int | None) -> list[PatientClock]:
    """A clock for each ``solve`` of the test, in order: the n-th stops after ``stop_after[n]``
    reports (the last value for every later solve; none given: 1)."""
    from asprilo.encodings.solving import front
    from asprilo.encodings.solving.watch import Listeners, Watch

    clocks: list[PatientClock] = []
    wanted = stop_after or (1,)

    def watch(time_limit=None, cancel=None, listeners=None) -> Watch:
        clock = PatientClock(wanted[min(len(clocks), len(wanted) - 1)])
        clocks.append(clock)
        listeners = listeners or Listeners()

        def progress(attempt) -> None:
            clock.reported(attempt)
            if listeners.progress is not None:
                listeners.progress(attempt)

        return Watch(time_limit, cancel, replace(listeners, progress=progress), clock=clock)

    monkeypatch.setattr(front, "Watch", watch)
    return clocks
