"""The goals a state shows on the map, without Qt: what the robots are heading for, and
which of it they have reached.

- M: the shelves holding the ordered products; an order is fulfilled (its shelf reached)
  when a robot stands under such a shelf.
- Md: the destinations; reached when a robot stands on one.
- Labelled goals (``assign(robot(R),shelf(S))`` / ``destination(D)``): that robot's goal,
  reached only by that robot.
- A, B, C: the shelves an open order line needs (they hold its product, in A units of it),
  with the picking stations they must reach; reached while such a shelf stands on its station.
"""

from __future__ import annotations

from dataclasses import dataclass

from asprilo.domain import Goal as DomainGoal
from asprilo.simulate import State

from .track import Track


@dataclass(frozen=True)
class Goal:
    """An object marked as a goal at a state."""

    kind: str                        # "shelf" or "destination"
    ident: int
    reached: bool
    robot: int | None = None         # the robot whose labelled goal it is
    by: int | None = None            # the robot standing there now (reached M and Md goals)
    stations: tuple[int, ...] = ()   # A, B, C: where the shelf must go
    at: int | None = None            # A, B, C: the one of them it stands on now (reached)


def goals_at(track: Track, step: int) -> list[Goal]:
    """The goals at the state after ``step``, sorted by kind and id."""
    state = track.state(step)
    goals = _delivery_goals(track, state) if track.domain.goal is DomainGoal.LINES else _mapf_goals(track, state)
    return sorted(goals.values(), key=lambda goal: (goal.kind, goal.ident))


def _mapf_goals(track: Track, state: State) -> dict[tuple[str, int], Goal]:
    """M and Md: ordered shelves and destinations, labelled goals with their robots."""
    instance = track.instance
    standing = {tuple(cell): robot for robot, cell in sorted(state.robots.items(), reverse=True)}  # least id
    assigned = {goal: robot for robot, goal in instance.assignment.items()}
    targets = set(assigned)
    if track.domain.goal is DomainGoal.SHELVES:
        for order in instance.orders.values():
            for product in order.lines:
                holders = instance.products[product].stock if product in instance.products else {}
                targets.update(("shelf", shelf) for shelf in holders)
    else:
        targets.update(("destination", ident) for ident in instance.destinations)
    served = _served_shelves(track, state)
    goals = {}
    for kind, ident in targets:
        cell = state.shelves.get(ident) if kind == "shelf" else instance.destinations[ident].at
        by = standing.get(tuple(cell)) if cell is not None else None
        robot = assigned.get((kind, ident))
        if robot is not None and by != robot:  # a labelled goal: only its robot counts
            by = None
        reached = by is not None or (robot is None and (kind, ident) in served)
        goals[(kind, ident)] = Goal(kind, ident, reached, robot, by)
    return goals


def _served_shelves(track: Track, state: State) -> set[tuple[str, int]]:
    """Where the checker decides the goal (a variant's goal, say a visit at any step): the
    ordered shelves no open order line needs any more, reached though no robot stands there."""
    if not track.goal_checked or track.domain.goal is not DomainGoal.SHELVES:
        return set()
    instance, needed = track.instance, set[int]()
    for _order, product in state.open_lines:
        needed.update(instance.products[product].stock if product in instance.products else ())
    return {("shelf", shelf) for product in instance.products.values() for shelf in product.stock
            if shelf not in needed}


def _delivery_goals(track: Track, state: State) -> dict[tuple[str, int], Goal]:
    """A, B, C: shelves holding what an open line asks for, with the line's station."""
    instance = track.instance
    wanted: dict[int, set[int]] = {}  # shelf -> stations it must reach
    for order, product in state.open_lines:
        station = instance.orders[order].station if order in instance.orders else None
        holders = instance.products[product].stock if product in instance.products else {}
        for shelf in holders:
            units = state.stock.get((shelf, product), holders[shelf])
            if not track.domain.counts_units or units is None or units > 0:
                wanted.setdefault(shelf, set()).update({station} if station is not None else set())
    at_station = {station.at: station.id for station in instance.stations.values()}
    goals = {}
    for shelf, stations in wanted.items():
        cell = state.shelves.get(shelf)
        here = at_station.get(tuple(cell)) if cell is not None else None
        reached = here in stations
        goals[("shelf", shelf)] = Goal("shelf", shelf, reached, stations=tuple(sorted(stations)),
                                       at=here if reached else None)
    return goals
