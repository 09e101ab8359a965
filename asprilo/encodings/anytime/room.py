"""Making room: robots that stand in the way of others at the start.

Robots routed one after the other treat those not routed yet as standing still, so a robot
whose every way out passes another robot's start cell can only leave after that robot
left.  :func:`depths` says how deep a robot stands in a crowd (1: next to a free cell;
2: next to a robot of depth 1; ...); robots are routed shallow ones first.  A robot without
work that stands on a cell others need, or in front of a deeper robot, is sent to park on
a free cell nearby, off the highways where it can.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from asprilo.bounds import INFINITE
from asprilo.model import DIRECTIONS, Cell, Instance

from .errands import Task
from .grid import Grid

#: cells offered to a robot that has to make room
ROOM_CELLS = 6
#: the depth of a robot that no free cell can be reached from
WALLED_IN = 10**6


def depths(instance: Instance) -> dict[int, int]:
    """Robot -> how many robots' start cells lie between it and the nearest free cell, plus one."""
    cells = instance.cells
    at = {robot.at: robot.id for robot in instance.robots.values()}
    result: dict[int, int] = {}
    queue: deque[Cell] = deque()
    for cell, robot in at.items():
        if any(n in cells and n not in at for n in _around(cell)):
            result[robot] = 1
            queue.append(cell)
    while queue:
        cell = queue.popleft()
        for near in _around(cell):
            other = at.get(near)
            if other is not None and other not in result:
                result[other] = result[at[cell]] + 1
                queue.append(near)
    return {robot: result.get(robot, WALLED_IN) for robot in instance.robots}


def _around(cell: Cell) -> list[Cell]:
    return [(cell[0] + dx, cell[1] + dy) for dx, dy in DIRECTIONS]


def movers(instance: Instance, workers: set[int], needed: set[Cell]) -> list[int]:
    """Robots without work on a needed cell or next to a deeper robot, shallow ones first."""
    depth = depths(instance)
    at = {robot.at: robot.id for robot in instance.robots.values()}
    result = []
    for robot in instance.robots.values():
        if robot.id in workers:
            continue
        deeper = any(depth.get(at.get(n), 0) > depth[robot.id] for n in _around(robot.at))
        if robot.at in needed or deeper:
            result.append(robot.id)
    return sorted(result, key=lambda r: (depth[r], r))


def room_task(instance: Instance, grid: Grid, robot: int, taken: np.ndarray, highways: np.ndarray,
              shelf_cells: np.ndarray) -> Task:
    """Parking on one of the nearest free cells (no robot starts there, nobody needs it, no
    station: ``taken``), storage cells first (not ``highways``); a robot with a shelf keeps
    off the other shelves (``shelf_cells``).  The masks are boolean arrays of the grid."""
    start = instance.robots[robot].at
    carried = instance.robots[robot].carries
    passable = grid.floor & ~shelf_cells if carried is not None else grid.floor
    distance = grid.distances([start], passable)
    free = passable & (distance < INFINITE) & ~taken
    cells: list[Cell] = []
    for kind in (free & ~highways, free & highways):
        xs, ys = np.nonzero(kind)
        nearest = np.lexsort((ys, xs, distance[xs, ys]))[:ROOM_CELLS - len(cells)]
        cells += [(int(xs[k]), int(ys[k])) for k in nearest]
    return Task("park", tuple(cells) or (start,), carried is not None, carried)
