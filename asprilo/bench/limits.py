"""Run one benchmark job in a child process under wall-time and memory limits.

The child process is the core's (:func:`asprilo.isolation.run_isolated`), standalone: a
fresh interpreter that runs :func:`asprilo.bench.worker.run` with its address space limited
(``RLIMIT_AS``), in a process group of its own that is killed as a whole when the wall-clock
limit passes.  A run that runs away is a time-out or a mem-out of that run, never a crash of
the runner.

No run outlives the runner: a signal to the runner's process group (``timeout``, a closed
terminal) does not reach a run's group, but the runner takes SIGTERM and SIGHUP as Ctrl-C and
kills every run in flight (:func:`kill_running`); a runner killed outright takes them with it
(the parent-death signal), and each run ends by itself shortly after its time limit
(:data:`asprilo.isolation.BACKSTOP`).
"""

from __future__ import annotations

import json
import threading
import time
import traceback
from dataclasses import dataclass

from asprilo.errors import InputError
from asprilo.isolation import run_isolated

from .results import ERROR, MEMOUT, TIMEOUT
from .worker import run

#: the status of a child that ran to its end (its report says what it found)
DONE = "done"

#: seconds a child gets beyond its own time limit to stop cleanly before it is killed
GRACE = 5.0

#: set on interrupt: the runs in flight are killed, and a run that starts afterwards (a worker
#: thread that picked its job up meanwhile) is killed at once, so that none outlives the runner
STOPPED = threading.Event()


@dataclass
class LimitedRun:
    """What became of one child process."""

    status: str            # DONE, or the run's status: TIMEOUT, MEMOUT or ERROR
    wall: float            # seconds
    report: dict           # the worker's report, as JSON has it (empty if none)
    detail: str = ""       # for errors: what went wrong (the error the worker raised)


def run_limited(job: dict, time_limit: float, memory_mb: int | None) -> LimitedRun:
    """Run :func:`asprilo.bench.worker.run` on ``job`` within the limits."""

    job = {**job, "time_limit": time_limit, "memory_mb": memory_mb}
    if STOPPED.is_set():  # the runner was interrupted: no new child
        return LimitedRun(ERROR, 0.0, {}, "interrupted")
    started = time.perf_counter()
    try:
        child = run_isolated(run, (job,), time_limit=time_limit + GRACE, memory_mb=memory_mb, cancel=STOPPED,
                             standalone=True)
    except Exception as error:  # noqa: BLE001 - the job's own error: the run failed
        return failure(error, time.perf_counter() - started)
    if child.status == DONE:
        return LimitedRun(DONE, child.seconds, json.loads(json.dumps(child.value)))
    if child.status == "timeout":
        return LimitedRun(TIMEOUT, child.seconds, {})
    if child.status == "memout":
        return LimitedRun(MEMOUT, child.seconds, {})
    return LimitedRun(ERROR, child.seconds, {}, f"the run's process ended without a result ({child.detail})")


def failure(error: Exception, wall: float) -> LimitedRun:
    """A run whose job raised ``error``: a mem-out when it ran out of memory (C++ code says
    ``bad_alloc``), else an error with its reason: bad input's sentence as it is, else the last
    line of the error's traceback."""
    if isinstance(error, InputError):
        return LimitedRun(ERROR, wall, {}, str(error))
    text = "".join(traceback.format_exception_only(type(error), error))
    if isinstance(error, MemoryError) or "bad_alloc" in text:
        return LimitedRun(MEMOUT, wall, {})
    lines = [line for line in text.splitlines() if line.strip()]
    return LimitedRun(ERROR, wall, {}, lines[-1] if lines else type(error).__name__)


def kill_running() -> None:
    """Kill every child still running, and any about to start (when the runner is interrupted)."""
    STOPPED.set()


def resume_running() -> None:
    """Let runs start again (a new run of a suite, after an interrupted one in this process)."""
    STOPPED.clear()
