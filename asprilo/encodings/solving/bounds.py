"""The lower bounds of one solve, computed once (:func:`lower_bounds`) and handed to every
part that needs them: the method, the checker's metrics, the anytime planner's gaps."""

from __future__ import annotations

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


@dataclass(frozen=True)
class AwaitedBounds(LowerBounds):
    """Lower bounds that another process is computing (the exact search beside the anytime
    planner in method ``auto``): zero, which is admissible, until they arrive on ``inbox``
    (the receiving end of a pipe); :meth:`arrived` looks for them without waiting."""

    makespan: float = 0.0
    inbox: Any = field(default=None, compare=False, repr=False)

    def arrived(self) -> LowerBounds | None:
        """The bounds, once they have come (``None`` before, and when they never will)."""
        try:
            if self.inbox is not None and self.inbox.poll():
                bounds = self.inbox.recv()
                return bounds if isinstance(bounds, LowerBounds) else None
        except (EOFError, OSError):  # the sender is gone: they will not come
            return None
        return None


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


@dataclass(frozen=True)
class _Reports:
    """The receiving end of a child's reports, read as :class:`AwaitedBounds` reads a pipe."""

    child: Any

    def poll(self) -> bool:
        return self.child.receiver.poll()

    def recv(self) -> LowerBounds | None:
        kind, payload = self.child.receiver.recv()
        return payload if kind == "message" else None


def _report_bounds(instance: Instance, domain: Domain, report: Any) -> None:
    report(lower_bounds(instance, domain))


def bounds_beside(instance: Instance, domain: Domain, floor: Floor) -> tuple[LowerBounds, Any]:
    """The lower bounds for a search that should not wait for them: for a large A/B/C
    instance, the cheap bounds at once and the strong ones from a child process when they
    come (an :class:`AwaitedBounds`); else the strong ones, computed here.  The second value
    is the child (its ``wait(0)`` ends it), or ``None``."""
    if domain.bound is Bound.MAPF or len(instance.robots) * len(floor.cells) < BACKGROUND_WORK:
        return lower_bounds(instance, domain, floor), None
    from asprilo.bounds import cheap_bounds
    from asprilo.isolation import start_isolated

    child = start_isolated(_report_bounds, (instance, domain))
    return AwaitedBounds(*cheap_bounds(instance, domain, floor), inbox=_Reports(child)), child
