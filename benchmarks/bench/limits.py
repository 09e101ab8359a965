"""Run one benchmark job in a child process under OS-enforced wall-time and memory limits.

The child is a fresh Python process (``python -m asprilo.bench.worker``) in a session of
its own; it sets ``RLIMIT_AS`` on itself before doing anything, and the runner kills its
whole process group when the wall-clock limit passes.  A run that runs away is a time-out
or a mem-out of that run, never a crash of the runner.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass

#: seconds a child gets beyond its own time limit to stop cleanly before it is killed
GRACE = 5.0

#: process ids of the children running now (their process groups are killed on interrupt)
RUNNING: set[int] = set()


@dataclass
class Outcome:
    """What became of one child process."""

    status: str            # "done", "timeout", "memout" or "error"
    wall: float            # seconds
    report: dict           # the JSON object the worker printed last (empty if none)
    detail: str = ""       # for errors: the last line the child wrote to stderr


def run_limited(job: dict, time_limit: float, memory_mb: int | None) -> Outcome:
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
        return Outcome("timeout", time.perf_counter() - started, {})
    finally:
        RUNNING.discard(child.pid)
    wall = time.perf_counter() - started
    report = _last_json(out)
    if child.returncode == 0 and report:
        return Outcome("done", wall, report)
    if "MemoryError" in err or "bad_alloc" in err or "std::bad_alloc" in out:
        return Outcome("memout", wall, report)
    lines = [line for line in err.splitlines() if line.strip()]
    detail = lines[-1] if lines else f"exit status {child.returncode}"
    return Outcome("error", wall, report, detail)


def _kill(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


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
