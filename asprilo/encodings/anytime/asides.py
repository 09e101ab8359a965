"""Holding shelves aside: robots without work lift the resting shelves that stand on the
short way of another robot's carry and step aside with them (the ``hold`` neighbourhood of
:mod:`.improve`).

A carry goes around the resting shelves.  Where the way around a block is long, the
shortest way from a shelf to its first station may cross the cells of shelves that serve
no order; robots without work can lift those shelves first and park holding them off that
way, so the carried shelf goes through.  On seed 4603 of ``a_multiline.py``'s call with two
orders the minimal plan (16 steps, proven by the exact search) does just that: two robots
without work lift the shelves between a shelf in the back row and its station and stand
aside with them, and that shelf reaches the station in 5 moves instead of 7 around.

The jobs are kept as :attr:`.work.Work.clearings` (the shelf and the cell its robot parks
on, holding it) of robots that have no trips; :func:`held` is their errand.  Robots with
trips of their own are not asked (tried: no gain on the six missed seeds of
``a_multiline.py``).
"""

from __future__ import annotations

import heapq
import random
from typing import TYPE_CHECKING

from asprilo.bounds import INFINITE
from asprilo.model import DIRECTIONS, Cell

from .errands import Task

if TYPE_CHECKING:
    from .work import Work

#: the most a crossed shelf may add to a step when ways are drawn (a random extra cost per
#: shelf, so that repeated tries offer other ways and other shelves to hold)
JITTER = 2.0


def held(work: Work, robot: int) -> list[Task]:
    """The errand of a robot without trips that holds shelves aside: lift each, put all but
    the last down on its cell, park holding the last one (none: no such job)."""
    jobs = work.clearings.get(robot, [])
    tasks: list[Task] = []
    for number, (shelf, cell) in enumerate(jobs):
        tasks.append(Task("pickup", (work.homes[shelf],), False, shelf))
        last = number == len(jobs) - 1
        tasks.append(Task("park" if last else "putdown", (cell,), True, shelf))
    return tasks


def idle_robots(work: Work) -> list[int]:
    """Robots without trips, without a shelf and without a job of holding one."""
    return [robot for robot, state in sorted(work.instance.robots.items())
            if robot not in work.trips and state.carries is None and robot not in work.clearings]


def hold_aside(work: Work, robot: int, rng: random.Random) -> list[int]:
    """Let robots without work hold aside the shelves on a short way of one of ``robot``'s
    carries to its first station (drawn at random among the carries that a way through
    shelves serving no order makes shorter); the robots given jobs (none: no such way, or
    fewer robots without work than shelves on it)."""
    from .work import entered  # work.py imports this module for :func:`held`
    idle = idle_robots(work)
    if not idle:
        return []
    busy = {trip.shelf for trips in work.trips.values() for trip in trips}
    busy |= {state.carries for state in work.instance.robots.values() if state.carries is not None}
    busy |= {shelf for jobs in work.clearings.values() for shelf, _ in jobs}
    liftable = {work.homes[shelf]: shelf for shelf in work.homes
                if shelf not in busy and work.homes[shelf] in work.resting}
    lifted = {work.homes[shelf] for shelf in busy}  # their own robots lift them (when: the router sees)
    ways = []
    for trip in work.trips.get(robot, []):
        if not trip.deliveries:
            continue
        home, station = work.homes[trip.shelf], trip.deliveries[0][0]
        around = work.grid.distances([station], work.carrying)
        way = _way_through(work, home, station, liftable, lifted, rng)
        if way is not None and 0 < len(way[2]) <= len(idle) and way[0] < entered(around, home):
            ways.append(way)
    if not ways:
        return []
    cells, blockers = rng.choice(ways)[1:]
    return _give(work, idle, blockers, cells, liftable)


def _way_through(work: Work, home: Cell, station: Cell, liftable: dict[Cell, int], lifted: set[Cell],
                 rng: random.Random) -> tuple[int, list[Cell], list[Cell]] | None:
    """The shortest way with a shelf from ``home`` to ``station`` that may cross the cells of
    ``liftable`` shelves (each with a random extra cost of up to :data:`JITTER` steps) and of
    ``lifted`` ones: its moves, its cells, and the liftable cells it crosses."""
    extra = {cell: rng.uniform(0, JITTER) for cell in liftable}
    cost, came = {home: 0.0}, {home: home}
    queue = [(0.0, home)]
    while queue:
        steps, cell = heapq.heappop(queue)
        if cell == station:
            break
        if steps > cost[cell]:
            continue
        for dx, dy in DIRECTIONS:
            near = (cell[0] + dx, cell[1] + dy)
            if near not in work.instance.cells:
                continue
            if not work.carrying[near] and near not in liftable and near not in lifted and near != station:
                continue
            step = steps + 1 + extra.get(near, 0.0)
            if step < cost.get(near, INFINITE):
                cost[near], came[near] = step, cell
                heapq.heappush(queue, (step, near))
    if station not in came:
        return None
    way, cell = [station], station
    while cell != home:
        cell = came[cell]
        way.append(cell)
    return len(way) - 1, way, [cell for cell in reversed(way) if cell in liftable]


def _give(work: Work, idle: list[int], blockers: list[Cell], way: list[Cell], liftable: dict[Cell, int]) -> list[int]:
    """Give each shelf on ``blockers`` to the nearest robot of ``idle`` not given one yet,
    with the cell nearest it off the ``way`` where its robot parks holding it."""
    taken = set(way) | set(work.claims.values()) | work.needed_cells()
    taken |= {state.at for state in work.instance.robots.values()}
    taken |= {station.at for station in work.instance.stations.values()}
    taken |= {cell for shelf, cell in work.homes.items() if cell in work.resting and cell not in blockers}
    left, given = list(idle), []
    clearings, claims = dict(work.clearings), dict(work.claims)
    for cell in blockers:
        walk = work.grid.distances([cell])
        helper = min(left, key=lambda r: (walk[work.instance.robots[r].at], r))
        if walk[work.instance.robots[helper].at] >= INFINITE:
            return []
        away = work.grid.distances([cell], work.carrying | work.grid.mask([cell]))
        spots = [c for c in work.instance.cells if c not in taken and away[c] < INFINITE]
        if not spots:
            return []
        spot = min(spots, key=lambda c: (away[c], c))
        taken.add(spot)
        left.remove(helper)
        shelf = liftable[cell]
        clearings[helper] = [(shelf, spot)]
        claims[shelf] = spot
        given.append(helper)
    work.clearings, work.claims = clearings, claims
    return given
