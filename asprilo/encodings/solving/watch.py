"""One stop-watch for every solving method: the time budget, cancellation, the listeners,
the clingo solver to interrupt and the statistics of all solvers.

The horizon search, the max-flow solver and the anytime planner all ask the same
:class:`Watch` whether time is up (``expired``, ``out_of_time``) or the caller cancelled,
and report through it (``progress``, ``phase``).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from types import TracebackType
from typing import Any

from asprilo.solver import Solver, Statistics

from .bounds import LowerBounds
from .status import Attempt, Note, Phase, PhaseListener, Progress, Totals

#: how often the helper thread looks at the cancel event (seconds)
_POLL = 0.05


@dataclass(frozen=True)
class Listeners:
    """Who hears what a solve does: each attempt (``progress``), each phase as it begins
    (``phase``), the lower bounds once they are known (``bounds``), the statistics so far
    after each attempt (``totals``), and what went wrong beside the search (``notes``)."""

    progress: Progress | None = None
    phase: PhaseListener | None = None
    bounds: Callable[[LowerBounds], None] | None = None
    totals: Callable[[Totals], None] | None = None
    notes: Callable[[Note], None] | None = None


class Watch:
    """Time budget, cancellation, listeners and statistics of one solve.

    ``time_limit`` counts from the moment the watch is made; ``clock`` reads the time (a
    caller may pass its own, to make a search see time pass in steps).  With ``cancel``, a
    helper thread (started with the first solver attached) interrupts the attached clingo
    solver as soon as it is set; grounding is not interruptible, so a cancelled search stops
    at its next solve call.  Use it as a context manager (or call :meth:`close`) to end the
    helper thread.
    """

    def __init__(self, time_limit: float | None = None, cancel: threading.Event | None = None,
                 listeners: Listeners | None = None, clock: Callable[[], float] = time.perf_counter):
        self.clock = clock
        self.started = clock()
        self.deadline = None if time_limit is None else self.started + time_limit
        self.cancel = cancel
        self.listeners = listeners or Listeners()
        self.current: Solver | None = None
        self.solvers: list[Statistics] = []
        self.done = threading.Event()
        self._helper: threading.Thread | None = None

    def __enter__(self) -> Watch:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()

    def close(self) -> None:
        """End the helper thread."""
        self.done.set()

    def _interrupt_when_cancelled(self) -> None:
        while not self.done.is_set():
            if self.cancel.wait(_POLL):
                if self.current is not None:
                    self.current.control.interrupt()
                return

    # --- time and cancellation ---------------------------------------------------------------

    @property
    def cancelled(self) -> bool:
        return self.cancel is not None and self.cancel.is_set()

    def elapsed(self) -> float:
        """Seconds since the watch was made."""
        return self.clock() - self.started

    def remaining(self) -> float | None:
        """Seconds left (``None``: no limit)."""
        return None if self.deadline is None else max(0.0, self.deadline - self.clock())

    @property
    def expired(self) -> bool:
        return self.deadline is not None and self.clock() >= self.deadline

    def out_of_time(self, keep: float = 0.0) -> bool:
        """Cancelled, or less than ``keep`` seconds left."""
        return self.cancelled or (self.deadline is not None and self.clock() >= self.deadline - keep)

    # --- listeners -----------------------------------------------------------------------------

    def progress(self, attempt: Attempt) -> None:
        """Report ``attempt`` (the statistics so far first: a listener that stops the solve on
        hearing the attempt has them)."""
        if self.listeners.totals is not None:
            self.listeners.totals(Totals(self.totals()))
        if self.listeners.progress is not None:
            self.listeners.progress(attempt)

    def phase(self, name: str, horizon: int, conflicts: int | None = None) -> None:
        """Report the phase that begins (or, with ``conflicts``, goes on: the statistics so
        far go with it)."""
        if conflicts is not None and self.listeners.totals is not None:
            self.listeners.totals(Totals(self.totals()))
        if self.listeners.phase is not None:
            self.listeners.phase(Phase(name, horizon, conflicts))

    def lower_bounds(self, bounds: LowerBounds) -> None:
        if self.listeners.bounds is not None:
            self.listeners.bounds(bounds)

    def note(self, text: str) -> None:
        """Say what went wrong beside the search (one sentence)."""
        if self.listeners.notes is not None:
            self.listeners.notes(Note(text))

    # --- solvers and statistics ------------------------------------------------------------------

    def attach(self, solver: Solver) -> None:
        """The clingo solver that runs now: interrupted on cancel, its statistics counted."""
        self.current = solver
        self.solvers.append(solver.stats)
        if self.cancel is not None and self._helper is None:
            # started here, not with the watch: a process that solves nothing itself (its
            # children do) runs no thread of its own, so it may fork them
            self._helper = threading.Thread(target=self._interrupt_when_cancelled, daemon=True)
            self._helper.start()
        if self.cancelled:
            solver.control.interrupt()

    def count(self, stats: Statistics) -> Statistics:
        """Count the statistics of an engine that is no clingo solver (max-flow) as well."""
        self.solvers.append(stats)
        return stats

    def totals(self) -> dict[str, Any]:
        """Ground and solve time, choices and conflicts of all solvers; rules and atoms of the last."""
        total = Statistics()
        for stats in self.solvers:
            total.ground_time += stats.ground_time
            total.solve_time += stats.solve_time
            total.choices += stats.choices
            total.conflicts += stats.conflicts
        if self.solvers:
            total.rules, total.atoms = self.solvers[-1].rules, self.solvers[-1].atoms
        figures = total.as_dict()
        figures.pop("models", None)
        return figures
