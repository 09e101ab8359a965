"""Domain A online: the tasks of the robots, and who gets which.

A task is one delivery: a robot picks up a shelf where it rests, carries it to the picking
station of an order line, delivers some units of the line's product and puts the shelf back
down where it took it (so a shelf's own cell is always free for it).  The multi-shot planner
(:mod:`.multishot_a`) plans the steps of the tasks; this module chooses them, greedily: every
line not fully served yet, oldest first, goes to the free robot and the resting shelf that
bring the product to its station soonest (the walk to the shelf and the carry from it, on the
floor without other robots).
"""

from __future__ import annotations

from dataclasses import dataclass

from asprilo.model import Cell

from .lookahead import distances, neighbours

Line = tuple[int, int]  # (order, product)

#: what a task needs next
PICKUP, DELIVER, PUTDOWN = "pickup", "deliver", "putdown"


@dataclass
class Task:
    """Robot ``robot`` brings shelf ``shelf`` (resting on ``home``) to ``station`` for ``units``
    of ``line``; ``next`` is what it does next.  A task without a line only puts the shelf down
    on ``home`` (a robot that starts carrying a shelf)."""

    robot: int
    shelf: int
    home: Cell
    station: Cell
    line: Line | None
    units: int
    next: str = PICKUP


class Floor:
    """The floor as the planner's hints see it: distances walked, and carried (a robot with a
    shelf keeps off the cells where shelves rest: every shelf's own cell but the target)."""

    def __init__(self, cells: set[Cell], shelf_cells: set[Cell]):
        self.cells, self.shelf_cells = cells, shelf_cells
        self._walks: dict[Cell, dict[Cell, int]] = {}
        self._carries: dict[Cell, dict[Cell, int]] = {}

    def walk(self, target: Cell) -> dict[Cell, int]:
        """Steps from every cell to ``target`` for a robot without a shelf."""
        if target not in self._walks:
            self._walks[target] = distances(self.cells, [target])
        return self._walks[target]

    def carry(self, target: Cell) -> dict[Cell, int]:
        """Steps from every cell to ``target`` for a robot with a shelf."""
        if target not in self._carries:
            self._carries[target] = distances((self.cells - self.shelf_cells) | {target}, [target])
        return self._carries[target]

    @staticmethod
    def steps(cell: Cell, field: dict[Cell, int]) -> int | None:
        """Steps from ``cell`` down ``field`` (a cell off the field: through its best neighbour)."""
        if cell in field:
            return field[cell]
        near = [field[n] for n in neighbours(cell) if n in field]
        return min(near) + 1 if near else None


def assign_tasks(free: dict[int, Cell], lines: list[tuple[Line, Cell, int]], shelves: dict[int, Cell],
                 stock: dict[tuple[int, int], int], floor: Floor) -> list[Task]:
    """New tasks: ``free`` robots (robot -> cell), ``lines`` still to serve, oldest first
    ((order, product), its station's cell, the units not in a task yet), ``shelves`` resting
    and not in a task (shelf -> cell), ``stock``: (shelf, product) -> units on it."""
    tasks = []
    free, shelves = dict(free), dict(shelves)
    for line, station, units in lines:
        if not free:
            break
        carry = floor.carry(station)
        best = None
        for shelf, home in sorted(shelves.items()):
            held = stock.get((shelf, line[1]), 0)
            to_station = floor.steps(home, carry)
            if held <= 0 or to_station is None:
                continue
            walk = floor.walk(home)
            for robot, cell in sorted(free.items()):
                to_shelf = floor.steps(cell, walk)
                if to_shelf is None:
                    continue
                cost = to_shelf + to_station
                if best is None or cost < best[0]:
                    best = (cost, robot, shelf, home, min(units, held))
        if best is not None:
            _cost, robot, shelf, home, given = best
            tasks.append(Task(robot, shelf, home, station, line, given))
            del free[robot], shelves[shelf]
    return tasks
