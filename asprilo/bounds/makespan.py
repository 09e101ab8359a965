"""The makespan bound of every plan: the one ``check``, ``solve`` and the benchmark reports use.

:func:`makespan_bound` picks the bound that the domain's descriptor names (``domain.bound``):
robots matched to goal cells for M/Md (:mod:`asprilo.bounds.mapf`), the delivery bounds for
A/B/C (:func:`delivery_bound`).  Every bound here is admissible: no valid plan does better.

Two strengths: :func:`strong_bounds` (the makespan bound above and, for M/Md, the sum of
costs of the same matching: what ``solve`` computes once and ``check --bound strong`` shows;
on A/B/C a relaxation solved in ASP, up to seconds) and :func:`cheap_bounds` (what ``check``
shows by default: their first stage alone, in milliseconds and without numpy).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..domain import Bound, Domain
from ..model import Instance
from .floor import INFINITE, Floor

# The bounds of each family are imported where a domain of that family asks for them (A/B/C:
# delivery, and trip for the strong bound only; M/Md: mapf): ``check`` shows the cheap bound of
# one domain and loads only what that takes.
if TYPE_CHECKING:
    from .delivery import Deliveries

#: cell visits the cheap A/B/C bound may spend on a search per shelf that holds an ordered
#: product (shelves resting in the way); beyond, one search per station (Deliveries.blocking)
CHEAP_VISITS = 20_000


def makespan_bound(instance: Instance, domain: Domain, floor: Floor | None = None) -> float:
    """A makespan no valid plan of ``domain`` beats (``INFINITE``: no plan exists at all).

    M/Md: the bottleneck assignment of robots to goal cells.  A/B/C: :func:`delivery_bound`
    (order lines released no earlier than a robot can bring a shelf, stations serving one
    robot at a time, robots one line at a time).
    """
    if domain.bound is None:  # a variant that may allow shorter plans: nothing but 0 is known
        return 0.0
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        from .mapf import mapf_bounds
        return mapf_bounds(instance, floor, total=False)[0]
    return delivery_bound(instance, domain, floor)


def delivery_bound(instance: Instance, domain: Domain, floor: Floor) -> float:
    """An admissible makespan bound for A, B and C (``INFINITE``: some line can never be served):
    the stations' bound, raised by the scheduling relaxation where every shelf serves one line
    at most (:mod:`asprilo.bounds.delivery`), else by the trip relaxation (:mod:`asprilo.bounds.trip`)."""
    from .delivery import Deliveries, schedulable, schedule_bound
    facts = Deliveries(instance, domain, floor)
    bound = _first_stage(facts)
    if not facts.lines or not math.isfinite(bound):
        return bound
    if schedulable(facts):
        return schedule_bound(facts, bound)
    from .trip import trip_bound
    return trip_bound(facts, bound)


def strong_bounds(instance: Instance, domain: Domain, floor: Floor | None = None) -> tuple[float, float | None]:
    """``(makespan, sum of costs)``: :func:`makespan_bound` and, for M/Md, the sum-of-costs
    bound of the same assignment (:func:`~asprilo.bounds.mapf.mapf_bounds`; ``None`` for A/B/C).
    A domain without a bound (``domain.bound`` is ``None``): ``(0, None)``."""
    if domain.bound is None:
        return 0.0, None
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        from .mapf import mapf_bounds
        return mapf_bounds(instance, floor)
    return makespan_bound(instance, domain, floor), None


def cheap_bounds(instance: Instance, domain: Domain, floor: Floor | None = None) -> tuple[float, float | None]:
    """``(makespan, sum of costs)`` no larger than :func:`strong_bounds`' and found in
    milliseconds, without numpy.

    M/Md: each goal cell reached by its nearest robot (:func:`~asprilo.bounds.mapf.nearest_goal_bounds`,
    no matching).  A/B/C: the stations' bound (:func:`~asprilo.bounds.delivery.station_bound`:
    each line released when a robot can first bring a shelf holding its product, a station
    serving one delivery at a time), without the relaxations solved in ASP; ``None`` for the
    sum of costs; the shelves resting in a carried shelf's way are taken into account up to
    :data:`CHEAP_VISITS`).  ``INFINITE`` where no plan exists, as for the strong bound.
    """
    if domain.bound is None:
        return 0.0, None
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        from .mapf import nearest_goal_bounds
        return nearest_goal_bounds(instance, floor)
    from .delivery import Deliveries
    facts = Deliveries(instance, domain, floor)
    holders = {shelf for line in facts.lines for shelf in line.holders}
    facts.blocking = len(holders) * len(floor.cells) <= CHEAP_VISITS  # a search per shelf, else per station
    return _first_stage(facts), None


def _first_stage(facts: Deliveries) -> float:
    """The A/B/C bound before any relaxation: 0 with nothing to deliver, ``INFINITE`` when some
    line can never be served (no station, no shelf that gets there, A: too little stock),
    else the stations' bound."""
    from .delivery import short_of_stock, station_bound
    if not facts.lines and not facts.stationless:
        return 0.0
    if facts.stationless or not all(math.isfinite(facts.release(line)) for line in facts.lines) \
            or short_of_stock(facts):
        return INFINITE
    return station_bound(facts)

