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
