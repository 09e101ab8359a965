"""Memory limits of child processes: the default, and the values a process can honour.

A user's encoding runs in a child process whose address space is limited (``RLIMIT_AS``).
Without ``--memory-limit`` it gets :func:`default_memory_mb`: half the machine's memory or
:data:`MOST_DEFAULT_MB`, whichever is less, and never more than the limit this process has
already (``ulimit -v``).  :func:`check_memory_limit` refuses, in words, a value that cannot be
honoured: above the hard limit this process has (a child may not raise it), or below
:data:`LEAST_MB`, what a solver process needs to start at all.
"""

from __future__ import annotations

import os
import resource

from .errors import InputError

#: the default memory limit never exceeds this many megabytes
MOST_DEFAULT_MB = 8192
#: the least memory limit a solver process can start under: a fresh interpreter that has loaded
#: clingo and numpy and solved a tiny instance maps 110-175 MB (measured on Linux, Python 3.11);
#: a forked child starts with its parent's mappings (see :func:`asprilo.isolation`)
LEAST_MB = 256


def _megabytes(limit: int) -> int | None:
    """A resource limit in whole megabytes (``None``: unlimited)."""
    return None if limit == resource.RLIM_INFINITY else limit // 2**20


def process_limits_mb() -> tuple[int | None, int | None]:
    """The address-space limit this process has: (soft, hard) in MB, ``None`` for none."""
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    return _megabytes(soft), _megabytes(hard)


def machine_memory_mb() -> int | None:
    """The machine's physical memory in MB (``None`` where the system does not say)."""
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") // 2**20
    except (ValueError, OSError, AttributeError):
        return None


def default_memory_mb() -> int:
    """The memory limit of a user's encoding unless told otherwise: half the machine's memory
    or :data:`MOST_DEFAULT_MB`, whichever is less, and never above this process's own limit."""
    candidates = [MOST_DEFAULT_MB]
    machine = machine_memory_mb()
    if machine:
        candidates.append(machine // 2)
    soft, _hard = process_limits_mb()
    if soft is not None:
        candidates.append(soft)
    return max(1, min(candidates))


def check_memory_limit(megabytes: int) -> None:
    """Refuse a memory limit this process cannot honour (one sentence, :class:`InputError`)."""
    _soft, hard = process_limits_mb()
    if hard is not None and megabytes > hard:
        raise InputError(f"{megabytes} MB is above the memory limit this process has ({hard} MB, ulimit -v): "
                         "a child process cannot be given more")
    if megabytes < LEAST_MB:
        raise InputError(f"{megabytes} MB is too small: a solver process needs at least {LEAST_MB} MB to start")


def usable_memory_mb(megabytes: int | None) -> tuple[int | None, str]:
    """A memory limit lowered to what this process may have (its ``ulimit -v``), and the
    sentence that says so (empty when it stands as given)."""
    _soft, hard = process_limits_mb()
    if megabytes is None or hard is None or megabytes <= hard:
        return megabytes, ""
    return hard, (f"the memory limit {megabytes} MB is lowered to {hard} MB, the limit this process has "
                  "(ulimit -v)")
