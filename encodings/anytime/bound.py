"""The lower bounds the anytime search measures its plans against (the one place that
says which bound function is used)."""

from __future__ import annotations

from asprilo import bounds
from asprilo.bounds import Floor, mapf_bounds
from asprilo.domain import Bound, Domain
from asprilo.model import Instance


def makespan_bound(instance: Instance, domain: Domain, floor: Floor | None = None) -> float:
    """No plan of ``domain`` is shorter (``INFINITE``: there is no plan at all)."""
    return bounds.makespan_bound(instance, domain, floor)


def sum_of_costs_bound(instance: Instance, domain: Domain) -> float | None:
    """No plan has a smaller sum of costs (M and Md; ``None``: no bound known)."""
    return mapf_bounds(instance)[1] if domain.bound is Bound.MAPF else None
