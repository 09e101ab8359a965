"""Route one robot's errand around the fixed tracks of the others, with ``route.lp``.

Python prepares a small search space, clingo searches it: for every leg of the errand (the
way to one task) a corridor of cells along a shortest route, each cell with the steps at
which the robot can be there if it is at most ``slack`` steps late; plus the reservations
of the other robots inside the corridors.  When no route fits, the corridors widen and
the slack grows (:data:`LEVELS`) before the errand is given up.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import clingo
import numpy as np

from asprilo.bounds import INFINITE
from asprilo.model import Cell

from .errands import Task
from .grid import Grid, cells_of, widen
from .reservations import FOREVER, Reservations

PROGRAM = Path(__file__).resolve().parent / "route.lp"


@dataclass(frozen=True)
class Level:
    """How much room a routing attempt gives: corridor ``radius`` around one shortest route
    (``None``: every cell on a route at most ``detour`` steps longer), ``slack`` steps late."""

    radius: int | None
    slack: int
    detour: int = 0


LEVELS = (Level(1, 6), Level(2, 20), Level(4, 60), Level(None, 150, 12), Level(None, 400, 10**6))
#: a level whose corridors hold more (cell, step) pairs than this is not tried
MAX_SLOTS = 300_000
#: how many steps longer a way may get by keeping off the cells where others park
DETOUR = 0


@dataclass
class Leg:
    """The way to one task: where it starts, the cells it may use and when."""

    task: Task
    start: Cell
    earliest: int        # the step the robot could set out at, were nothing in its way
    length: int          # steps of a shortest way
    windows: dict[Cell, tuple[int, int]]


class Router:
    """Routes errands on one floor against one reservation table; ``stopped()`` true ends
    the widening of a search early (no route then)."""

    def __init__(self, grid: Grid, reservations: Reservations, stopped: Callable[[], bool] = lambda: False):
        self.grid, self.reservations, self.stopped = grid, reservations, stopped

    def route(self, robot: int, tasks: list[Task], begin: Cell, step: int = 0,
              levels: tuple[Level, ...] = LEVELS, avoid: frozenset[Cell] = frozenset()
              ) -> tuple[list[Cell], dict[int, Task]] | None:
        """The cells of ``robot`` after steps ``step`` .. parked and the tasks it does at
        which step, on the first level that has a route; ``None`` when none has.  The
        corridors keep off the cells of ``avoid`` (where others will park) unless that
        makes a way more than :data:`DETOUR` steps longer."""
        passable = [self._passable(robot, tasks, number) for number in range(len(tasks))]
        for level in levels:
            if self.stopped():
                return None
            legs = self._legs(tasks, begin, step, passable, level, avoid)
            if legs is None or _too_late(legs, self.reservations, robot):
                return None  # some task cannot be reached (in time) at all
            if sum(last - first + 1 for leg in legs for first, last in leg.windows.values()) > MAX_SLOTS:
                return None
            found = self._solve(robot, legs, begin, step)
            if found is not None:
                return found
        return None

    def in_the_way(self, robot: int, tasks: list[Task], begin: Cell) -> list[int]:
        """Other robots on or next to a shortest way through ``tasks``: those parked there
        first, then those that come to the robot's start while it is still there, then
        those passing the way most often."""
        passable = [self._passable(robot, tasks, number) for number in range(len(tasks))]
        legs = self._legs(tasks, begin, 0, passable, Level(1, 0), frozenset())
        if legs is None:
            return []
        table, met = self.reservations, Counter[int]()
        for cell in {cell for leg in legs for cell in leg.windows}:
            for other in table.stays.get(cell, {}):
                met[other] += 1000
            for step, other in table.visits.get(cell, {}).items():
                near_start = abs(cell[0] - begin[0]) + abs(cell[1] - begin[1]) <= 1 and step <= 3
                met[other] += 100 if near_start else 1
        met.pop(robot, None)
        return [other for other, _ in met.most_common()]

    # --- the search space ------------------------------------------------------------------

    def _passable(self, robot: int, tasks: list[Task], number: int) -> np.ndarray:
        """Where the robot may be on its way to task ``number``: anywhere when it carries
        nothing; else nowhere a shelf rests all the time, nor on its own other shelves."""
        task = tasks[number]
        if not task.carrying:
            return self.grid.floor
        own = {t.shelf for t in tasks if t.shelf is not None}
        blocked = self.reservations.still_shelves(own)
        blocked += [self.reservations.homes[s] for s in own if s != task.shelf]
        blocked += [t.cells[0] for t in tasks if t.name == "putdown" and t.shelf != task.shelf]
        return self.grid.floor & ~self.grid.mask(blocked)

    def _legs(self, tasks: list[Task], begin: Cell, step: int, passable: list[np.ndarray],
              level: Level, avoid: frozenset[Cell]) -> list[Leg] | None:
        legs, start, earliest = [], begin, step
        shunned = self.grid.mask(avoid - {c for task in tasks for c in task.cells} - {begin})
        for task, allowed in zip(tasks, passable, strict=True):
            to_task = self.grid.distances(task.cells, allowed)
            if to_task[start] == INFINITE:
                return None
            kept = allowed & ~shunned
            to_task_kept = self.grid.distances(task.cells, kept)
            if to_task_kept[start] <= to_task[start] + DETOUR:
                allowed, to_task = kept, to_task_kept
            from_start = self.grid.distances([start], allowed)
            length = int(to_task[start])
            corridor = self._corridor(start, from_start, to_task, allowed, level, length)
            windows = {}
            for x, y in cells_of(corridor):
                first, last = earliest + int(from_start[x, y]), earliest + length + level.slack - int(to_task[x, y])
                if first <= last:
                    windows[(x, y)] = (first, last)
            legs.append(Leg(task, start, earliest, length, windows))
            end = min(task.cells, key=lambda cell: from_start[cell])
            start, earliest = end, earliest + length + 1
        return legs

    def _corridor(self, start: Cell, from_start: np.ndarray, to_task: np.ndarray, allowed: np.ndarray,
                  level: Level, length: int) -> np.ndarray:
        if level.radius is None:
            return allowed & (from_start + to_task <= length + level.detour)
        route = self.grid.mask(self.grid.path(start, to_task))
        return widen(route, level.radius) & allowed & (from_start < INFINITE) & (to_task < INFINITE)

    # --- the facts and the solver --------------------------------------------------------------

    def _facts(self, robot: int, legs: list[Leg], begin: Cell, step: int) -> str:
        out = [f"begin({_c(begin)},{step}).", f"last({len(legs)})."]
        spans: dict[Cell, list[int]] = {}
        for number, leg in enumerate(legs, 1):
            out.append(f"acts({number})." if leg.task.name != "park" else "")
            if leg.task.carrying:
                out.append(f"carrying({number}).")
            for cell, (first, last) in leg.windows.items():
                out.append(f"window({number},{_c(cell)},{first},{last}).")
                span = spans.setdefault(cell, [first, last])
                span[0], span[1] = min(span[0], first), max(span[1], last)
            out += self._task_cells(robot, number, leg)
        out += self._others(robot, spans)
        out += self._shelves(robot, legs)
        return "\n".join(out)

    def _task_cells(self, robot: int, number: int, leg: Leg) -> list[str]:
        out = []
        table = self.reservations
        for cell in leg.task.cells:
            if leg.task.name == "putdown" and leg.task.shelf is not None and cell != table.homes.get(leg.task.shelf):
                out.append(f"task({number},{_c(cell)}).")
                settle = table.last_loaded_visit(cell, robot) + 1
                if settle > 0:
                    out.append(f"settle({number},{min(settle, FOREVER)}).")
            elif leg.task.name != "park":
                out.append(f"task({number},{_c(cell)}).")
            elif self.reservations.stay(cell, robot) is None:
                out.append(f"task({number},{_c(cell)}).")
                last = self.reservations.last_visit(cell, robot)
                if last >= 0:
                    out.append(f"free_from({_c(cell)},{last + 1}).")
        return out

    def _others(self, robot: int, spans: dict[Cell, list[int]]) -> list[str]:
        """The other robots inside the corridors: where they are, stay and move."""
        out = []
        table = self.reservations
        for cell, (first, last) in spans.items():
            out += [f"busy({_c(cell)},{t})." for t in table.busy(cell, first, last, robot)]
            since = table.stay(cell, robot)
            if since is not None and since <= last:
                out.append(f"stays({_c(cell)},{since}).")
            out += [f"crossing({_c(source)},{_c(cell)},{t})."
                    for source, t in table.crossings(cell, first, last + 1, robot) if source in spans]
        return out

    def _shelves(self, robot: int, legs: list[Leg]) -> list[str]:
        """The shelves of other robots that rest in a carrying leg's corridor part of the time."""
        own = {leg.task.shelf for leg in legs if leg.task.shelf is not None}
        moving = self.reservations.moving_shelves(own)
        cells = {cell for leg in legs if leg.task.carrying for cell in leg.windows}
        out = []
        for shelf, cell in moving.items():
            if cell in cells:
                out += [f"rests({_c(cell)},{first},{min(last, FOREVER)})."
                        for first, last in self.reservations.resting(shelf)]
        for cell, since in self.reservations.placed(own).values():  # put down away from their cells
            if cell in cells:
                out.append(f"rests({_c(cell)},{since},{FOREVER}).")
        return out

    def _solve(self, robot: int, legs: list[Leg], begin: Cell, step: int
               ) -> tuple[list[Cell], dict[int, Task]] | None:
        # a Control of its own, not the driver's (asprilo.solver says why: hundreds of tiny calls)
        control = clingo.Control(["--warn=none"])
        control.load(str(PROGRAM))
        control.add("base", [], self._facts(robot, legs, begin, step))
        control.ground([("base", [])])
        symbols: list[clingo.Symbol] = []
        result = control.solve(on_model=lambda model: symbols.extend(model.symbols(shown=True)))
        if not result.satisfiable or not any(s.name == "arrival" for s in symbols):
            return None
        return _route(symbols, [leg.task for leg in legs], step)


def _too_late(legs: list[Leg], table: Reservations, robot: int) -> bool:
    """Whether an action's cell is taken for good by another robot before this robot
    can possibly be there."""
    for leg in legs:
        if leg.task.name != "park":
            since = table.stay(leg.task.cells[0], robot)
            if since is not None and since <= leg.earliest + leg.length + 1:
                return True
    return False


def _c(cell: Cell) -> str:
    return f"({cell[0]},{cell[1]})"


def _route(symbols: list[clingo.Symbol], tasks: list[Task], step: int) -> tuple[list[Cell], dict[int, Task]]:
    """The model's ``at/3`` atoms as cells per step and the tasks done at their steps."""
    where: dict[int, tuple[int, Cell]] = {}
    arrival = step
    for symbol in symbols:
        if symbol.name == "arrival":
            arrival = symbol.arguments[0].number
        else:
            number, cell, at = symbol.arguments
            where[at.number] = (number.number, (cell.arguments[0].number, cell.arguments[1].number))
    cells = [where[t][1] for t in range(step, arrival + 1)]
    done = {t: tasks[where[t - 1][0] - 1] for t in range(step + 1, arrival + 1) if where[t][0] != where[t - 1][0]}
    return cells, done
