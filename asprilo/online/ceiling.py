"""An upper bound on the throughput of an online scenario: printed beside the measured figure,
so that a planner's throughput means something.

No plan carried out online finishes more order lines by step N than this *ceiling*:

- a line released at step r is done at step r + 1 at the earliest (its order is known after
  step r, and the first step that can serve it is the next);
- nor before the shortest trip brings a shelf holding its product to its order's station:
  for some robot, the steps to the shelf, the pick-up (none when it starts carrying that
  shelf), the steps on to the station and the delivery; in M, the steps of some robot to a
  shelf holding the product.  Steps are counted on the floor without any other object (a
  relaxation: real trips are no shorter);
- a picking station takes at most one delivery a step (one robot stands on it, and a robot
  does one action a step), and in A and B a delivery closes at most one line.  (In C one
  delivery may close several lines of a station: there the stations' capacity is not counted.)

So, station by station, the most lines done by step N is what one server of unit time does
with each line ready at its earliest step, taken in that order: the ceiling sums it.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

from asprilo.bounds import Floor
from asprilo.bounds.floor import INFINITE
from asprilo.domain import Delivery, Domain, Goal
from asprilo.model import Instance

Line = tuple[int, int]  # (order, product)


@dataclass(frozen=True)
class Ceiling:
    """At most ``lines`` order lines done in ``steps`` steps."""

    steps: int
    lines: int

    @property
    def lines_per_100(self) -> float:
        return 100 * self.lines / self.steps if self.steps else 0.0


def earliest_steps(instance: Instance, domain: Domain, releases: dict[int, int]) -> dict[Line, float]:
    """The earliest step each order line can be done (``INFINITE``: never)."""
    floor = Floor(instance.cells)
    robots = list(instance.robots.values())
    shelf_ids = sorted(instance.shelves)
    shelf_cells = [instance.shelves[shelf].at for shelf in shelf_ids]
    station_ids = sorted(instance.stations)
    station_cells = [instance.stations[station].at for station in station_ids]
    robot_to_shelf = floor.distances([robot.at for robot in robots], shelf_cells)
    robot_to_station = floor.distances([robot.at for robot in robots], station_cells)
    shelf_to_station = floor.distances(shelf_cells, station_cells)
    earliest: dict[Line, float] = {}
    for order in instance.orders.values():
        at = station_ids.index(order.station) if order.station in instance.stations else None
        for product in order.lines:
            stock = instance.products[product].stock if product in instance.products else {}
            trips = [INFINITE]
            for k, shelf in enumerate(shelf_ids):
                if shelf not in stock:
                    continue
                for r, robot in enumerate(robots):
                    if domain.goal is Goal.SHELVES:
                        trips.append(robot_to_shelf[r, k])
                    elif at is not None and robot.carries == shelf:
                        trips.append(robot_to_station[r, at] + 1)
                    elif at is not None:
                        trips.append(robot_to_shelf[r, k] + 1 + shelf_to_station[k, at] + 1)
            earliest[(order.id, product)] = float(max(releases.get(order.id, 0) + 1, min(trips)))
    return earliest


def ceiling(instance: Instance, domain: Domain, releases: dict[int, int], steps: int,
            earliest: dict[Line, float] | None = None) -> Ceiling | None:
    """The ceiling of a run of ``steps`` steps (``None`` for a domain without orders: Md);
    ``earliest``: :func:`earliest_steps`, when found already."""
    if domain.goal is Goal.DESTINATIONS:
        return None
    earliest = earliest_steps(instance, domain, releases) if earliest is None else earliest
    if domain.goal is Goal.SHELVES or domain.delivery is Delivery.STATION:
        return Ceiling(steps, sum(step <= steps for step in earliest.values()))
    by_station: dict[int | None, list[float]] = defaultdict(list)
    for (order, _product), step in earliest.items():
        by_station[instance.orders[order].station].append(step)
    done = 0
    for ready in by_station.values():
        clock = 0.0
        for step in sorted(ready):
            clock = max(clock + 1, step)
            if clock > steps:
                break
            done += 1
    return Ceiling(steps, done)
