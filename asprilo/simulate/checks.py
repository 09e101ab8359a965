"""The checks on the instance itself (step 0) and on the goal (at the horizon), and the
world at step 0 as the rules read it."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass

from ..domain import Domain, Goal, Job
from ..model import Cell, Instance
from .actions import Report
from .timeline import History


@dataclass
class Start:
    """The shelves at step 0: who carries which (the smallest robot id where several
    robots carry one shelf), which rest where, and every shelf that exists."""

    holder: dict[int, int]  # shelf -> robot
    resting: dict[int, Cell]
    shelves: set[int]


def check_instance(instance: Instance, domain: Domain, report: Report) -> Start:
    """Report what is wrong with the instance; the shelves at step 0."""
    nodes = instance.cells
    carriers = _check_robots(instance, nodes, report)
    holder = {shelf: min(robots) for shelf, robots in carriers.items()}
    for shelf, robots in carriers.items():
        if len(robots) > 1:
            report("instance", "sharedShelf", shelf, 0)
    resting = {s.id: s.at for s in instance.shelves.values() if s.id not in holder}
    _check_resting(instance, nodes, resting, report)
    _check_fixed(instance, nodes, report)
    robot_cells = {r.id: r.at for r in instance.robots.values()}
    shelf_cells = dict(resting)
    shelf_cells.update({shelf: robot_cells[robot] for shelf, robot in holder.items()})
    for first, second in pairs_sharing(robot_cells):
        report("instance", "robotCollision", first, second, 0)
    for first, second in pairs_sharing(shelf_cells):
        report("instance", "shelfCollision", first, second, 0)
    _check_orders(instance, domain, set(shelf_cells), report)
    return Start(holder, resting, set(shelf_cells))


def _check_fixed(instance: Instance, nodes: set[Cell], report: Report) -> None:
    """Picking stations and destinations: on a floor node, one of each kind per node."""
    for kind, objects in (("station", instance.stations), ("destination", instance.destinations)):
        cells = {thing.id: thing.at for thing in objects.values()}
        for ident, cell in cells.items():
            if cell not in nodes:
                report("instance", f"{kind}OffFloor", ident, 0)
        for first, second in pairs_sharing(cells):
            report("instance", f"{kind}Collision", first, second, 0)


def _check_robots(instance: Instance, nodes: set[Cell], report: Report) -> dict[int, list[int]]:
    """Robots off the floor or carrying a shelf that stands elsewhere; shelf -> its carriers."""
    carriers: dict[int, list[int]] = defaultdict(list)
    for robot in sorted(instance.robots.values(), key=lambda r: r.id):
        if robot.at not in nodes:
            report("instance", "robotOffFloor", robot.id, 0)
        if robot.carries is not None:
            carriers[robot.carries].append(robot.id)
            shelf = instance.shelves.get(robot.carries)
            if shelf is not None and shelf.at != robot.at:
                report("instance", "carriedShelfElsewhere", robot.id, robot.carries, 0)
    return carriers


def _check_resting(instance: Instance, nodes: set[Cell], resting: dict[int, Cell], report: Report) -> None:
    highways = set(instance.highways.values())
    stations = {station.at for station in instance.stations.values()}
    for shelf, cell in resting.items():
        if cell not in nodes:
            report("instance", "shelfOffFloor", shelf, 0)
        if cell in highways:
            report("instance", "shelfOnHighway", shelf, 0)
        if cell in stations:
            report("instance", "shelfOnStation", shelf, 0)


def _check_orders(instance: Instance, domain: Domain, shelves: set[int], report: Report) -> None:
    for order in instance.orders.values():
        if domain.delivers:
            if order.station is None:
                report("instance", "orderStation", order.id, 0)
            elif order.station not in instance.stations:
                report("instance", "unknownStation", order.id, order.station, 0)
        for product in order.lines:
            stock = instance.products[product].stock if product in instance.products else {}
            if not any(shelf in shelves for shelf in stock):
                report("instance", "unknownProduct", order.id, product, 0)


def pairs_sharing(cells: dict[int, Cell]) -> Iterable[tuple[int, int]]:
    """Pairs ``(a, b)``, ``a < b``, of keys mapped to the same cell."""
    by_cell: dict[Cell, list[int]] = defaultdict(list)
    for key, cell in cells.items():
        by_cell[cell].append(key)
    for keys in by_cell.values():
        keys.sort()
        for i, first in enumerate(keys):
            for second in keys[i + 1:]:
                yield first, second


def check_goal(instance: Instance, domain: Domain, history: History, report: Report) -> None:
    """Labelled goals missed, destinations unoccupied (Md), order lines still open (else)."""
    horizon = history.horizon
    final = history.state(horizon)
    if instance.assignment and domain.work is Job.GOALS:
        for robot, (kind, goal) in sorted(instance.assignment.items()):
            cell = final.shelves.get(goal) if kind == "shelf" else instance.destinations[goal].at
            if cell is not None and final.robots[robot] != cell:
                report("goal", "missedAssignedGoal", robot, cell, horizon)
    if domain.goal is Goal.DESTINATIONS:
        occupied = set(final.robots.values())
        for destination in sorted(instance.destinations.values(), key=lambda d: d.id):
            if destination.at not in occupied:
                report("goal", "unoccupiedDestination", destination.id, horizon)
        return
    for (order, product), units in sorted(final.open_lines.items()):
        report("goal", "unfilledOrder", order, product, 1 if units is None else units, horizon)
