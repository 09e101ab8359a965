"""Run one benchmark job in a child process under OS-enforced wall-time and memory limits.

The child is a fresh Python process (``python -m asprilo.bench.worker``) in a session of
its own; it sets ``RLIMIT_AS`` on itself before doing anything, and the runner kills its
whole process group when the wall-clock limit passes.  A run that runs away is a time-out
or a mem-out of that run, never a crash of the runner.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass

from .results import ERROR, MEMOUT, TIMEOUT

#: the status of a child that ran to its end (its report says what it found)
DONE = "done"

#: seconds a child gets beyond its own time limit to stop cleanly before it is killed
GRACE = 5.0

#: process ids of the children running now (their process groups are killed on interrupt)
RUNNING: set[int] = set()


@dataclass
class LimitedRun:
    """What became of one child process."""

    status: str            # DONE, or the run's status: TIMEOUT, MEMOUT or ERROR
    wall: float            # seconds
    report: dict           # the JSON object the worker printed last (empty if none)
    detail: str = ""       # for errors: the last line the child wrote to stderr


def run_limited(job: dict, time_limit: float, memory_mb: int | None) -> LimitedRun:
    """Run ``asprilo.bench.worker`` on ``job`` within the limits."""

    job = {**job, "time_limit": time_limit, "memory_mb": memory_mb}
    started = time.perf_counter()
    child = subprocess.Popen([sys.executable, "-m", "asprilo.bench.worker", json.dumps(job)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             start_new_session=True)
    RUNNING.add(child.pid)
    try:
        out, err = child.communicate(timeout=time_limit + GRACE)
    except subprocess.TimeoutExpired:
        _kill(child.pid)
        child.communicate()
        return LimitedRun(TIMEOUT, time.perf_counter() - started, {})
    finally:
        RUNNING.discard(child.pid)
    wall = time.perf_counter() - started
    report = _last_json(out)
    if child.returncode == 0 and report:
        return LimitedRun(DONE, wall, report)
    if "MemoryError" in err or "bad_alloc" in err or "std::bad_alloc" in out:
        return LimitedRun(MEMOUT, wall, report)
    lines = [line for line in err.splitlines() if line.strip()]
    detail = lines[-1] if lines else f"exit status {child.returncode}"
    return LimitedRun(ERROR, wall, report, detail)


def _kill(pid: int) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.killpg(pid, signal.SIGKILL)


def kill_running() -> None:
    """Kill every child still running (when the runner is interrupted)."""
    for pid in list(RUNNING):
        _kill(pid)


def _last_json(text: str) -> dict:
    for line in reversed(text.splitlines()):
        if line.startswith("{"):
            try:
                return json.loads(line)
            except ValueError:
                return {}
    return {}
