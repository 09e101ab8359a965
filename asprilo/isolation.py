"""Run a function in a child process under hard limits: wall-clock time and memory.

The one engine for a child process under limits: ``solve(..., isolate=True)`` and the
reading of rules (:mod:`asprilo.sources`) run their work here, and so does the benchmark
runner (:mod:`asprilo.bench.limits`) each run.  clingo cannot be stopped while it grounds,
and a program may ground for ever; a child process can always be killed.  The child runs
``function(*args, report=report)`` where ``report(message)`` sends any picklable message to
the parent at once (progress); the parent hands each message to ``on_message`` as it
arrives and returns what the function returned, or says why there is nothing:

    outcome = run_isolated(ground_and_solve, (program,), time_limit=5, memory_mb=2048,
                           on_message=print)
    outcome.status      # "done", "timeout", "memout" or "crashed"
    outcome.value       # the function's return value when done

:func:`start_isolated` starts a child and returns at once (several children run side by
side, each waited for by its own thread: ``solve``'s method ``auto``).  An exception the
function raises is raised again in the parent (it must be picklable,
like :class:`~asprilo.errors.InputError`).  The child is started by ``fork`` where that is
safe (no other thread running in the parent) and ``spawn`` otherwise.  A *standalone*
child (``standalone=True``: a benchmark run) runs as a program of its own would: a fresh
interpreter (its peak memory is its own; it imports nothing but what the function needs),
in a session of its own that is killed as a whole (whatever it started goes with it), its
output discarded but for its last words, which say why it ended when it ended without a
result (an import that failed, say).  It imports the same package ``asprilo`` as its parent,
whatever the current folder holds.

No child outlives its parent: a child ignores the interrupts (Ctrl-C, SIGTERM, SIGHUP: the
parent decides when to stop, and kills it), and on Linux the kernel kills it when its parent
ends, whatever ended the parent (``PR_SET_PDEATHSIG``), even ``kill -9``.  A child with a time
limit also has one of its own, :data:`BACKSTOP` seconds later (``SIGALRM``, whose default
action ends it even inside clingo): should its parent be stopped (``kill -STOP``) or hang, the
child still ends.  A memory limit the child cannot start under (below what it has mapped
already: a forked child starts with its parent's mappings) is a mem-out that says so, not a crash.
"""

from __future__ import annotations

import atexit
import contextlib
import ctypes
import math
import multiprocessing
import os
import pickle
import resource
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from multiprocessing.connection import Connection
from pathlib import Path
from typing import Any

from .objects import ObjectKind, registered_kinds, restore_kind

#: how long a killed child may take to go, and how often the parent looks at the clock
_GRACE = 1.0
_TICK = 0.1
#: seconds past its time limit after which a child ends by itself (its parent kills it before)
BACKSTOP = 10.0
#: megabytes a child needs beyond what it has mapped when its memory limit is set
_HEADROOM_MB = 32


@dataclass
class Isolated:
    """What a child process did: ``status`` is ``done``, ``timeout``, ``memout`` or ``crashed``."""

    status: str
    value: Any = None
    seconds: float = 0.0
    messages: list[Any] = field(default_factory=list)
    detail: str = ""

    @property
    def done(self) -> bool:
        return self.status == "done"


class _Failure:
    """An exception raised in the child, carried back to be raised again."""

    def __init__(self, error: BaseException):
        self.error = error


class _OutOfMemory:
    pass


class _TooLittleMemory:
    """The child's memory limit is below what it has mapped already (it could not work)."""

    def __init__(self, mapped_mb: int):
        self.mapped_mb = mapped_mb


#: the signals that ask a command to stop: a child ignores them (its parent stops it)
INTERRUPTS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
#: Linux's prctl option that names the signal a process gets when its parent ends
_PR_SET_PDEATHSIG = 1


def _die_with_parent(parent: int) -> None:
    """Have the kernel kill this process when its parent ends (Linux); a parent that ended
    already (before this was asked) ends this process now."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):  # not Linux: the parent's cleanup alone ends its children
        return
    if os.getppid() != parent:
        os._exit(1)


def _bound_to_parent(parent: int | None, backstop: float | None) -> None:
    """A child's ties to its parent: it ignores the interrupts (the parent decides when to
    stop), ends when the parent ends, and (``backstop``) after that many seconds."""
    for interrupt in INTERRUPTS:
        signal.signal(interrupt, signal.SIG_IGN)
    if parent is not None:
        _die_with_parent(parent)
    if backstop is not None:  # a time limit of its own: SIGALRM's default action ends the process
        signal.signal(signal.SIGALRM, signal.SIG_DFL)
        signal.alarm(max(1, math.ceil(backstop)))


def _child(connection, function: Callable, args: tuple, memory_mb: int | None,
           kinds: Sequence[ObjectKind] = (), parent: int | None = None, backstop: float | None = None) -> None:
    _bound_to_parent(parent, backstop)
    for kind in kinds:  # object kinds the parent registered at run time (a fresh interpreter lacks them)
        restore_kind(kind)
    if memory_mb:
        mapped = _mapped_mb()
        if mapped is not None and memory_mb < mapped + _HEADROOM_MB:
            connection.send(("result", _TooLittleMemory(mapped + _HEADROOM_MB)))
            return
        _limit_memory(memory_mb)

    def report(message: Any) -> None:
        connection.send(("message", message))

    try:
        result: Any = function(*args, report=report)
    except MemoryError:
        result = _OutOfMemory()
    except BaseException as error:  # noqa: BLE001 - everything goes back to the parent
        try:
            connection.send(("result", _Failure(error)))
        except Exception:  # noqa: BLE001 - an error that cannot be pickled
            connection.send(("result", _Failure(RuntimeError(f"{type(error).__name__}: {error}"))))
        return
    connection.send(("result", result))


def _limit_memory(memory_mb: int) -> None:
    """Limit this process's address space to ``memory_mb`` (never above the hard limit it has:
    that cannot be raised; the command line refuses such a value before any child starts)."""
    size = memory_mb * 2**20
    _soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    if hard != resource.RLIM_INFINITY:
        size = min(size, hard)
    resource.setrlimit(resource.RLIMIT_AS, (size, size))


def _mapped_mb() -> int | None:
    """The megabytes of address space this process has mapped now (Linux's VmSize)."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) // 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def peak_memory_mb() -> float:
    """This process's peak resident memory in MB: Linux's VmHWM, the peak of the program
    running now (``ru_maxrss`` keeps the peak of the process it was forked from, carried
    across exec: a child of a big parent would seem as big); ``ru_maxrss`` elsewhere."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _context() -> multiprocessing.context.ForkContext | multiprocessing.context.SpawnContext:
    """``fork`` when this process runs no other thread (fast, nothing to import again)."""
    if threading.active_count() == 1 and "fork" in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context("spawn")


def _start(function: Callable, args: tuple, memory_mb: int | None, backstop: float | None):
    """A child process that runs :func:`_child`, and the end of the pipe it answers on."""
    context = _context()
    receiver, sender = context.Pipe(duplex=False)
    process = context.Process(target=_child, daemon=True,
                              args=(sender, function, args, memory_mb, registered_kinds(), os.getpid(), backstop))
    process.start()
    sender.close()
    return process, receiver


class _Standalone:
    """A standalone child: ``python -c`` in a session of its own, told what to run on its
    standard input (a pickle), answering on a pipe as :func:`_child` does; a fresh
    interpreter imports nothing of the parent's (not even its main module).  Its standard
    error goes to a temporary file, whose last line says why a child that ended without a
    result ended."""

    def __init__(self, function: Callable, args: tuple, memory_mb: int | None, backstop: float | None):
        reading, writing = os.pipe()
        self.stderr = tempfile.TemporaryFile()  # noqa: SIM115 - closed with the child (close)
        try:
            self.popen = subprocess.Popen(
                [sys.executable, "-c", _standalone_command()],
                stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=self.stderr,
                pass_fds=(writing,), start_new_session=True)
        except BaseException:
            os.close(reading)
            self.stderr.close()
            raise
        finally:
            os.close(writing)
        self.receiver = Connection(reading, writable=False)
        self.pid = self.popen.pid
        stdin = self.popen.stdin
        assert stdin is not None  # stdin=PIPE
        with contextlib.suppress(OSError):  # a child that died at once says so through the pipe
            stdin.write(pickle.dumps((writing, function, args, memory_mb, registered_kinds(), os.getpid(),
                                      backstop)))
        with contextlib.suppress(OSError):
            stdin.close()

    def last_words(self) -> str:
        """The last line the child wrote on its standard error (e.g. the exception that ended
        it), at most 300 characters of it; empty if it wrote nothing."""
        self.stderr.seek(0, os.SEEK_END)
        self.stderr.seek(max(0, self.stderr.tell() - 4096))
        lines = [line.strip() for line in self.stderr.read().decode("utf-8", "replace").splitlines()]
        last = next((line for line in reversed(lines) if line), "")
        return last if len(last) <= 300 else last[:297] + "..."

    @property
    def exitcode(self) -> int | None:
        return self.popen.poll()

    def is_alive(self) -> bool:
        return self.popen.poll() is None

    def kill(self) -> None:
        """Kill the child's whole process group: whatever it started goes with it (a group
        whose leader has ended but is not yet reaped keeps its id, so no other group is hit)."""
        with contextlib.suppress(OSError):
            os.killpg(self.pid, signal.SIGKILL)

    def join(self, timeout: float | None = None) -> None:
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.popen.wait(timeout)

    def close(self) -> None:
        self.stderr.close()


def _standalone_command() -> str:
    """The standalone child's program: the folder the parent's ``asprilo`` came from goes
    first on its path in place of the current folder (which ``python -c`` puts there, and
    which may hold another ``asprilo``: a checkout's, say), then :func:`_standalone_main`."""
    home = str(Path(__file__).resolve().parent.parent)
    return (f"import sys; del sys.path[0]; home = {home!r}\n"
            "if home not in sys.path: sys.path.insert(0, home)\n"
            "from asprilo.isolation import _standalone_main; _standalone_main()")


def _standalone_main() -> None:
    """The standalone child's side: read what to run, run it as :func:`_child` does."""
    pipe, function, args, memory_mb, kinds, parent, backstop = pickle.load(sys.stdin.buffer)
    _child(Connection(pipe, readable=False), function, args, memory_mb, kinds, parent, backstop)


def run_isolated(function: Callable[..., Any], args: tuple = (), time_limit: float | None = None,
                 memory_mb: int | None = None, on_message: Callable[[Any], None] | None = None,
                 cancel: threading.Event | None = None, on_tick: Callable[[float], None] | None = None,
                 standalone: bool = False) -> Isolated:
    """Run ``function(*args, report=...)`` in a child process; see the module docstring.

    ``time_limit`` (seconds) and ``memory_mb`` are hard: the child is killed at the
    deadline and cannot allocate beyond the limit.  Setting ``cancel`` kills it too (status
    ``timeout``).  ``on_tick(elapsed)`` is called about ten times a second while waiting.
    ``standalone``: the child runs as a program of its own (see the module docstring).
    """
    child = start_isolated(function, args, memory_mb, standalone, time_limit=time_limit)
    return child.wait(time_limit, on_message, cancel, on_tick)


def start_isolated(function: Callable[..., Any], args: tuple = (), memory_mb: int | None = None,
                   standalone: bool = False, time_limit: float | None = None) -> Child:
    """Start ``function(*args, report=...)`` in a child process and return at once; its
    :meth:`Child.wait` does the rest of :func:`run_isolated`.  Several children started
    one after the other from a process that runs no other thread are all forked (fast),
    also when threads that wait for them start afterwards.  ``time_limit``: the child ends by
    itself :data:`BACKSTOP` seconds after it (the parent's :meth:`Child.wait` stops it first)."""
    return Child(function, args, memory_mb, standalone, time_limit)


class Child:
    """A child process started by :func:`start_isolated`, until :meth:`wait` has ended it."""

    def __init__(self, function: Callable[..., Any], args: tuple, memory_mb: int | None, standalone: bool,
                 time_limit: float | None = None):
        self.started = time.perf_counter()
        self.memory_mb, self.standalone = memory_mb, standalone
        backstop = None if time_limit is None else time_limit + BACKSTOP
        if standalone:
            self.process: Any = _Standalone(function, args, memory_mb, backstop)
            self.receiver = self.process.receiver
        else:
            self.process, self.receiver = _start(function, args, memory_mb, backstop)
        _LIVE.add(self.process)

    def wait(self, time_limit: float | None = None, on_message: Callable[[Any], None] | None = None,
             cancel: threading.Event | None = None, on_tick: Callable[[float], None] | None = None) -> Isolated:
        """Wait for the child under ``time_limit`` (counted from its start) and ``cancel``,
        as :func:`run_isolated` does; the child is gone afterwards."""
        process, receiver = self.process, self.receiver
        outcome = Isolated("crashed")
        try:
            outcome = _wait(process, receiver, self.started, time_limit, on_message, cancel, on_tick)
            outcome = _blame_memory(outcome, self.memory_mb)
        finally:
            _LIVE.discard(process)
            if self.standalone or process.is_alive():  # standalone: nothing it started outlives it either
                process.kill()
            process.join(_GRACE)
            receiver.close()
            if self.standalone:
                if outcome.status == "crashed" and process.last_words():
                    outcome.detail += f": {process.last_words()}"
                process.close()
        outcome.seconds = time.perf_counter() - self.started
        if isinstance(outcome.value, _Failure):
            raise outcome.value.error
        return outcome


#: the children started and not yet waited for: killed when this process exits (an interrupt
#: that skipped a wait; multiprocessing's own exit handler would wait for a child that ignores
#: its SIGTERM until the child's time ran out)
_LIVE: set[Any] = set()


@atexit.register
def _kill_live_children() -> None:
    # multiprocessing's children too: an interrupt between a child's start and its entry in
    # _LIVE (seen once, a SIGTERM as the child appeared) would leave one behind
    for process in [*_LIVE, *multiprocessing.active_children()]:
        with contextlib.suppress(OSError, ValueError, AttributeError):
            process.kill()


def _wait(process, receiver, started: float, time_limit: float | None, on_message, cancel,
          on_tick) -> Isolated:
    messages: list[Any] = []
    deadline = None if time_limit is None else started + time_limit
    while True:
        now = time.perf_counter()
        if (deadline is not None and now >= deadline) or (cancel is not None and cancel.is_set()):
            return Isolated("timeout", messages=messages)
        wait = _TICK if deadline is None else max(0.0, min(_TICK, deadline - now))
        if receiver.poll(wait):
            try:
                kind, payload = receiver.recv()
            except EOFError:  # the child died without a word
                process.join(_GRACE)
                return _died(process, messages)
            if kind == "message":
                messages.append(payload)
                if on_message is not None:
                    on_message(payload)
                continue
            return _answer(payload, messages)
        if on_tick is not None:
            on_tick(time.perf_counter() - started)
        if not process.is_alive() and not receiver.poll():
            return _died(process, messages)


def _answer(payload: Any, messages: list[Any]) -> Isolated:
    """What the child's result says."""
    if isinstance(payload, _OutOfMemory):
        return Isolated("memout", messages=messages, detail="out of memory")
    if isinstance(payload, _TooLittleMemory):
        return Isolated("memout", messages=messages,
                        detail=f"too little memory to start: it needs at least {payload.mapped_mb} MB")
    return Isolated("done", payload, messages=messages)


def _died(process, messages: list[Any]) -> Isolated:
    code = process.exitcode
    if code == -signal.SIGALRM:  # its own time limit ended it (the parent did not in time)
        return Isolated("timeout", messages=messages, detail="its own time limit")
    detail = f"killed by signal {-code}" if code is not None and code < 0 else f"exit status {code}"
    return Isolated("crashed", messages=messages, detail=detail)


#: how a child that ran out of its address space ends: C++ code that cannot allocate aborts
#: (std::bad_alloc: SIGABRT).  Other signals are crashes of their own: a SIGSEGV (a term nested
#: too deep overflows clingo's parser's stack), a SIGKILL from outside.
_OUT_OF_MEMORY = f"killed by signal {signal.SIGABRT.value}"


def _blame_memory(outcome: Isolated, memory_mb: int | None) -> Isolated:
    """A child under a memory limit that aborted ran out of memory (:data:`_OUT_OF_MEMORY`)."""
    if memory_mb and outcome.status == "crashed" and outcome.detail.split(":")[0] == _OUT_OF_MEMORY:
        outcome.status = "memout"
    return outcome

