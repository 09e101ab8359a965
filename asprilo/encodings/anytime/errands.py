"""What each robot has to do, in order: its errand.

An errand is a list of tasks.  A task is an action the robot does in one step standing on
one cell (``pickup``, ``putdown``, ``deliver``), or, last of all, ``park``: staying on one
of a few cells for good.  Between two tasks the robot walks (or waits); ``carrying`` says
whether it carries a shelf on the way to a task.  Routing (:mod:`.router`) turns an errand
into a timed track; this module only says what is to be done.

Before its robot fetches the next one, a shelf is put down on a free storage cell on the
way (one that no shelf starts on and no other shelf is put down on: :class:`~.work.Work`
chooses it), or else on the cell it came from; so the shelves rest on their own cells
until they are fetched, and on their new cells afterwards.  After its last delivery a robot
parks with the shelf on the shelf's own cell (or, when nobody else needs the station any
more, on the station).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from asprilo.domain import Delivery, Domain
from asprilo.model import Cell, Instance

#: a line of an order: (order, product)
Line = tuple[int, int]


@dataclass(frozen=True)
class Task:
    """One task of an errand; ``shelf`` is the shelf a pickup, putdown or delivery handles."""

    name: str                      # pickup | putdown | deliver | park
    cells: tuple[Cell, ...]
    carrying: bool = False         # the robot carries a shelf on its way here
    shelf: int | None = None
    args: tuple = ()               # the deliver action's arguments
    lines: tuple[Line, ...] = ()   # the order lines a delivery serves (domain C: maybe several)


@dataclass
class Trip:
    """One shelf brought to its stations: the deliveries at each station, in visiting order.

    ``deliveries`` holds ``(station cell, lines, args)``, one entry per deliver action.
    """

    shelf: int
    deliveries: list[tuple[Cell, tuple[Line, ...], tuple]] = field(default_factory=list)


def shelf_home(instance: Instance, shelf: int) -> Cell:
    """Where a shelf rests: its cell, or the start cell of the robot carrying it."""
    for robot in instance.robots.values():
        if robot.carries == shelf:
            return robot.at
    return instance.shelves[shelf].at


def delivery_errand(instance: Instance, robot: int, trips: list[Trip], park_cells: tuple[Cell, ...],
                    putdowns: dict[int, Cell] | None = None) -> list[Task]:
    """The tasks of a robot that brings ``trips`` (at least one) one after the other.

    Every shelf but the last is put down on its cell of ``putdowns`` (by default its own
    cell); the last one is kept and the robot parks with it on one of ``park_cells``.
    """
    putdowns = putdowns or {}
    carried = instance.robots[robot].carries
    tasks: list[Task] = []
    for number, trip in enumerate(trips):
        home = shelf_home(instance, trip.shelf)
        if trip.shelf != carried:
            tasks.append(Task("pickup", (home,), False, trip.shelf))
        for station, lines, args in trip.deliveries:
            tasks.append(Task("deliver", (station,), True, trip.shelf, args, lines))
        if number < len(trips) - 1:
            tasks.append(Task("putdown", (putdowns.get(trip.shelf, home),), True, trip.shelf))
        else:
            tasks.append(Task("park", park_cells, True, trip.shelf))
    return tasks


def goal_errand(cell: Cell) -> list[Task]:
    """The errand of a robot in domain M or Md: reach a goal cell and stay."""
    return [Task("park", (cell,))]


def shelves_of(tasks: list[Task]) -> list[int]:
    """The shelves an errand handles, in order, each once."""
    return list(dict.fromkeys(task.shelf for task in tasks if task.shelf is not None))


def _near(a: Cell, b: Cell) -> int:
    return abs(a[0] - b[0]) + abs(a[1] - b[1])


def trips(instance: Instance, domain: Domain, gives: list[tuple[int, ...]], carries: list[tuple[int, ...]],
          homes: dict[int, Cell]) -> dict[int, list[Trip]]:
    """Robot -> its trips, from an assignment: ``gives`` = (shelf, order, product, units),
    ``carries`` = (robot, shelf).  A robot fetches the nearest of its shelves next; a shelf
    visits the nearest of its stations next (a robot that starts with a shelf brings that
    one first)."""
    served: dict[int, dict[Cell, list[tuple[Line, int]]]] = {}
    for shelf, order, product, units in gives:
        station = instance.stations[instance.orders[order].station].at
        served.setdefault(shelf, {}).setdefault(station, []).append(((order, product), units))
    shelves_of_robot: dict[int, list[int]] = {}
    for robot, shelf in carries:
        shelves_of_robot.setdefault(robot, []).append(shelf)
    result = {}
    for robot, shelves in shelves_of_robot.items():
        at, ordered, left = instance.robots[robot].at, [], set(shelves)
        if instance.robots[robot].carries in left:
            ordered.append(instance.robots[robot].carries)
            left.discard(ordered[0])
        while left:
            ordered.append(min(sorted(left), key=lambda s: _near(at, homes[s])))
            left.discard(ordered[-1])
            at = homes[ordered[-1]]
        result[robot] = [_trip(shelf, homes[shelf], served.get(shelf, {}), domain) for shelf in ordered]
    return result


def _trip(shelf: int, home: Cell, stations: dict[Cell, list[tuple[Line, int]]], domain: Domain) -> Trip:
    trip, at, left = Trip(shelf), home, dict(stations)
    while left:
        station = min(sorted(left), key=lambda cell: _near(at, cell))
        lines = sorted(left.pop(station))
        if domain.delivery is Delivery.STATION:
            trip.deliveries.append((station, tuple(line for line, _ in lines), lines[0][0]))
        else:
            trip.deliveries += [(station, (line,), (*line, units) if domain.counts_units else line)
                                for line, units in lines]
        at = station
    return trip
