"""The lower bounds of one solve, computed once (:func:`lower_bounds`) and handed to every
part that needs them: the method, the checker's metrics, the anytime planner's gaps.  On a
large A/B/C floor the strong bound takes minutes: the anytime planner has it computed beside
its search (:func:`bounds_beside`), and what needs a bound at once takes the cheap one
(:func:`prompt_bounds`)."""

from __future__ import annotations

import signal
from dataclasses import dataclass, field
from typing import Any

from asprilo.bounds import Floor, makespan_bound, mapf_bounds
from asprilo.domain import Bound, Domain
from asprilo.model import Instance


@dataclass(frozen=True)
class LowerBounds:
    """No plan is shorter than ``makespan`` (``inf``: there is no plan at all); none has a
    smaller sum of costs than ``sum_of_costs`` (M and Md; ``None``: no bound known)."""

    makespan: float
    sum_of_costs: float | None = None


class BoundsLost(Exception):
    """The awaited bounds will never come; the message says why (``the process computing the
    lower bound ran out of memory``)."""


@dataclass(frozen=True)
class AwaitedBounds(LowerBounds):
    """Lower bounds that another process is computing (the exact search beside the anytime
    planner in method ``auto``, or the bound's own child): these (zero, or the cheap ones:
    admissible) until they arrive on ``inbox`` (the receiving end of a pipe); :meth:`arrived`
    looks for them without waiting."""

    makespan: float = 0.0
    inbox: Any = field(default=None, compare=False, repr=False)

    def arrived(self) -> LowerBounds | None:
        """The bounds, once they have come (``None`` before); :class:`BoundsLost` when they
        never will (the sender ended without them, or said why it could not compute them)."""
        try:
            if self.inbox is None or not self.inbox.poll():
                return None
            bounds = self.inbox.recv()
        except (EOFError, OSError):  # the sender is gone
            raise BoundsLost("the process computing the lower bound ended without it") from None
        if isinstance(bounds, str):  # why they cannot come, in words
            raise BoundsLost(bounds)
        return bounds if isinstance(bounds, LowerBounds) else None


def prompt_bounds(instance: Instance, domain: Domain, floor: Floor | None = None) -> LowerBounds:
    """The bounds of :func:`lower_bounds` where they come in moments (a small instance, or
    M/Md), else the cheap ones (:func:`asprilo.bounds.cheap_bounds`, milliseconds): for whoever
    must answer now (a solve whose child was stopped before it said its bounds)."""
    floor = floor or Floor(instance.cells)
    if _prompt(instance, domain, floor):
        return lower_bounds(instance, domain, floor)
    from asprilo.bounds import cheap_bounds
    return LowerBounds(*cheap_bounds(instance, domain, floor))


def _prompt(instance: Instance, domain: Domain, floor: Floor) -> bool:
    """Whether :func:`lower_bounds` answers in moments (:data:`BACKGROUND_WORK`)."""
    return domain.bound is Bound.MAPF or len(instance.robots) * len(floor.cells) < BACKGROUND_WORK


def lower_bounds(instance: Instance, domain: Domain, floor: Floor | None = None) -> LowerBounds:
    """The bounds :func:`asprilo.bounds.makespan_bound` and, for M/Md, the sum of costs of
    :func:`asprilo.bounds.mapf_bounds` (one assignment gives both)."""
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        return LowerBounds(*mapf_bounds(instance, floor))
    return LowerBounds(makespan_bound(instance, domain, floor))


#: robots x floor cells from which the anytime planner computes the A/B/C bound beside its
#: search, in a child process, instead of before it (on 100x100 with 200 robots it takes 11 s)
BACKGROUND_WORK = 20_000


#: what the bound's child says when it ran out of memory
OUT_OF_MEMORY = "the process computing the strong lower bound ran out of memory"


@dataclass(frozen=True)
class _Reports:
    """The receiving end of the bound's child, read as :class:`AwaitedBounds` reads a pipe:
    the bounds, or why they will not come (the child's words, or how it died)."""

    child: Any

    def poll(self) -> bool:
        return self.child.receiver.poll()

    def recv(self) -> LowerBounds | str | None:
        try:
            kind, payload = self.child.receiver.recv()
        except EOFError:
            raise BoundsLost(self._death()) from None
        return payload if kind == "message" else None

    def _death(self) -> str:
        """How the child ended without a word: a signal (an abort is C++ out of memory)."""
        process = self.child.process
        process.join(1.0)
        code = process.exitcode
        if code == -signal.SIGABRT:
            return OUT_OF_MEMORY + " (it aborted)"
        how = f"killed by signal {-code}" if code is not None and code < 0 else f"exit status {code}"
        return f"the process computing the strong lower bound died ({how})"


def _report_bounds(instance: Instance, domain: Domain, report: Any) -> None:
    """The bound's child: the bounds, or why there are none (a string)."""
    try:
        bounds = lower_bounds(instance, domain)
    except MemoryError:
        bounds = None
    report(OUT_OF_MEMORY if bounds is None else bounds)


def bounds_beside(instance: Instance, domain: Domain, floor: Floor) -> tuple[LowerBounds, Any]:
    """The lower bounds for a search that should not wait for them: for a large A/B/C
    instance, the cheap bounds at once and the strong ones from a child process when they
    come (an :class:`AwaitedBounds`); else the strong ones, computed here.  The second value
    is the child (its ``wait(0)`` ends it), or ``None``.  The child is a program of its own
    (standalone): it can be started from the child process a solve runs in, and its memory
    is its own."""
    if _prompt(instance, domain, floor):
        return lower_bounds(instance, domain, floor), None
    from asprilo.bounds import cheap_bounds
    from asprilo.isolation import start_isolated

    child = start_isolated(_report_bounds, (instance, domain), standalone=True)
    return AwaitedBounds(*cheap_bounds(instance, domain, floor), inbox=_Reports(child)), child
