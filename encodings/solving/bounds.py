"""The lower bounds of one solve, computed once (:func:`lower_bounds`) and handed to every
part that needs them: the method, the checker's metrics, the anytime planner's gaps."""

from __future__ import annotations

from dataclasses import dataclass

from asprilo.bounds import Floor, makespan_bound, mapf_bounds
from asprilo.domain import Bound, Domain
from asprilo.model import Instance


@dataclass(frozen=True)
class LowerBounds:
    """No plan is shorter than ``makespan`` (``inf``: there is no plan at all); none has a
    smaller sum of costs than ``sum_of_costs`` (M and Md; ``None``: no bound known)."""

    makespan: float
    sum_of_costs: float | None = None


def lower_bounds(instance: Instance, domain: Domain, floor: Floor | None = None) -> LowerBounds:
    """The bounds :func:`asprilo.bounds.makespan_bound` and, for M/Md, the sum of costs of
    :func:`asprilo.bounds.mapf_bounds` (one assignment gives both)."""
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        return LowerBounds(*mapf_bounds(instance, floor))
    return LowerBounds(makespan_bound(instance, domain, floor))
