"""The makespan bound of every plan: the one ``check``, ``solve`` and the benchmark reports use.

:func:`makespan_bound` picks the bound that the domain's descriptor names (``domain.bound``):
robots matched to goal cells for M/Md (:mod:`asprilo.bounds.mapf`), the delivery bounds for
A/B/C (:func:`delivery_bound`).  Every bound here is admissible: no valid plan does better.
"""

from __future__ import annotations

import math

from ..domain import Bound, Domain
from ..model import Instance
from .delivery import Deliveries, schedulable, schedule_bound, short_of_stock, station_bound
from .floor import INFINITE, Floor
from .mapf import mapf_bounds
from .trip import trip_bound


def makespan_bound(instance: Instance, domain: Domain, floor: Floor | None = None) -> float:
    """A makespan no valid plan of ``domain`` beats (``INFINITE``: no plan exists at all).

    M/Md: the bottleneck assignment of robots to goal cells.  A/B/C: :func:`delivery_bound`
    (order lines released no earlier than a robot can bring a shelf, stations serving one
    robot at a time, robots one line at a time).
    """
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        return mapf_bounds(instance, floor, total=False)[0]
    return delivery_bound(instance, domain, floor)


def delivery_bound(instance: Instance, domain: Domain, floor: Floor) -> float:
    """An admissible makespan bound for A, B and C (``INFINITE``: some line can never be served):
    the stations' bound, raised by the scheduling relaxation where every shelf serves one line
    at most (:mod:`asprilo.bounds.delivery`), else by the trip relaxation (:mod:`asprilo.bounds.trip`)."""
    facts = Deliveries(instance, domain, floor)
    if not facts.lines and not facts.stationless:
        return 0.0
    if facts.stationless or not all(math.isfinite(facts.release(line)) for line in facts.lines) \
            or short_of_stock(facts):
        return INFINITE
    bound = station_bound(facts)
    if schedulable(facts):
        return schedule_bound(facts, bound)
    return trip_bound(facts, bound)
