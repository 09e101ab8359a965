"""Route one robot's errand around the fixed tracks of the others.

Python prepares a small search space (:class:`~.space.Space`): for every leg of the errand
(the way to one task) a corridor of cells along a shortest route, each cell with the steps
at which the robot can be there if it is at most ``slack`` steps late; plus the reservations
of the other robots inside the corridors.  One of two engines searches it: the Python search
of :mod:`.timed_search` (the default: no solver to start for each of thousands of calls) or
the logic program ``route.lp`` (the same search, written for clingo's grounder; both find
the same earliest arrival).  When no route fits, the corridors widen and the slack grows
(:data:`LEVELS`) before the errand is given up.
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
from .grid import Grid, widen
from .reservations import Reservations
from .space import Space
from .timed_search import search

PROGRAM = Path(__file__).resolve().parent / "route.lp"


@dataclass(frozen=True)
class Level:
    """How much room a routing attempt gives: corridor ``radius`` around one shortest route
    (``None``: every cell on a route at most ``detour`` steps longer), ``slack`` steps late."""

    radius: int | None
    slack: int
    detour: int = 0


#: the levels per engine, and how many of them a repair of the large-neighbourhood search tries
#: (it can be undone, so it gives up sooner).  Grounding costs what the windows hold, so
#: ``route.lp`` starts narrow; the Python search visits little more than one route when one
#: fits, but all of the windows when none does, so it starts wide and widens in fewer levels:
#: every cell on a way at most 8 steps longer (a corridor around one shortest way kept the
#: repairs of 200 MovingAI agents from the detours that lower the sum of costs: 1.35 against
#: 1.31 times its bound after 60 s).
LEVELS = {"asp": (Level(1, 6), Level(2, 20), Level(4, 60), Level(None, 150, 12), Level(None, 400, 10**6)),
          "python": (Level(None, 30, 8), Level(None, 60, 16), Level(None, 400, 10**6))}
QUICK = {"asp": 3, "python": 2}
#: the most (cell, step) pairs the windows of one routing call may hold: the logic program
#: grounds them all, the Python search keeps each cell's runs of free steps.  A level with
#: every cell on a way at most so much longer holds more on a long way across an open floor
#: (the ways fill the rectangle between its ends): it is tried as a corridor of radius
#: ``NARROW`` around one shortest way then.
MAX_SLOTS = {"asp": 300_000, "python": 3_000_000}
NARROW = 3
#: how many steps longer a way may get by keeping off the cells where others park
DETOUR = 0


@dataclass
class Leg:
    """The way to one task: where it starts, the cells it may use and when."""

    task: Task
    start: Cell
    earliest: int        # the step the robot could set out at, were nothing in its way
    length: int          # steps of a shortest way
    deadline: int        # the last step at which the task may be reached (``slack`` steps late)
    windows: dict[Cell, tuple[int, int]]


class Router:
    """Routes errands on one floor against one reservation table; ``stopped()`` true ends
    the widening of a search early (no route then)."""

    def __init__(self, grid: Grid, reservations: Reservations, stopped: Callable[[], bool] = lambda: False,
                 engine: str = "python"):
        if engine not in ENGINES:
            raise ValueError(f"unknown routing engine {engine!r} (known: {', '.join(ENGINES)})")
        self.grid, self.reservations, self.stopped, self.engine = grid, reservations, stopped, engine

    def route(self, robot: int, tasks: list[Task], begin: Cell, step: int = 0, quick: bool = False,
              avoid: frozenset[Cell] = frozenset()) -> tuple[list[Cell], dict[int, Task]] | None:
        """The cells of ``robot`` after steps ``step`` .. parked and the tasks it does at
        which step, on the first level that has a route; ``None`` when none has (``quick``:
        after fewer levels).  The corridors keep off the cells of ``avoid`` (where others
        will park) unless that makes a way more than :data:`DETOUR` steps longer."""
        passable = [self._passable(robot, tasks, number) for number in range(len(tasks))]
        levels = LEVELS[self.engine]
        for level in levels[:QUICK[self.engine]] if quick else levels:
            if self.stopped():
                return None
            legs = self._legs(tasks, begin, step, passable, level, avoid)
            if legs is None or _too_late(legs, self.reservations, robot):
                return None  # some task cannot be reached (in time) at all
            if _slots(legs) > MAX_SLOTS[self.engine]:
                if level.radius is not None:
                    return None
                # a long way across an open floor: the corridor around one shortest way (NARROW)
                legs = self._legs(tasks, begin, step, passable, Level(NARROW, level.slack), avoid)
                if legs is None or _slots(legs) > MAX_SLOTS[self.engine]:
                    return None
            found = self._solve(robot, legs, begin, step)
            if found is not None:
                return found
        return None

    def way(self, robot: int, tasks: list[Task], begin: Cell) -> set[Cell]:
        """The cells on or next to a shortest way through ``tasks`` (empty: there is none)."""
        passable = [self._passable(robot, tasks, number) for number in range(len(tasks))]
        legs = self._legs(tasks, begin, 0, passable, Level(1, 0), frozenset())
        return set() if legs is None else {cell for leg in legs for cell in leg.windows}

    def in_the_way(self, robot: int, tasks: list[Task], begin: Cell) -> list[int]:
        """Other robots on or next to a shortest way through ``tasks``: those parked there
        first, then those that come to the robot's start while it is still there, then
        those passing the way most often."""
        table, met = self.reservations, Counter[int]()
        for cell in self.way(robot, tasks, begin):
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
        nothing; else nowhere a shelf rests all the time, nor on its own other shelves (on the
        cells of those it lifts later, and where it puts any down)."""
        task = tasks[number]
        if not task.carrying:
            return self.grid.floor
        own = {t.shelf for t in tasks if t.shelf is not None}
        blocked = self.reservations.still_shelves(own)
        lifted = {t.shelf for t in tasks[:number] if t.name == "pickup"}  # off their own cells by now
        blocked += [self.reservations.homes[s] for s in own if s != task.shelf and s not in lifted]
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
            windows = _windows(corridor, earliest + from_start, earliest + length + level.slack - to_task)
            legs.append(Leg(task, start, earliest, length, earliest + length + level.slack, windows))
            end = min(task.cells, key=lambda cell: from_start[cell])
            start, earliest = end, earliest + length + 1
        return legs

    def _corridor(self, start: Cell, from_start: np.ndarray, to_task: np.ndarray, allowed: np.ndarray,
                  level: Level, length: int) -> np.ndarray:
        if level.radius is None:
            return allowed & (from_start + to_task <= length + level.detour)
        route = self.grid.mask(self.grid.path(start, to_task))
        return widen(route, level.radius) & allowed & (from_start < INFINITE) & (to_task < INFINITE)

    # --- the search -------------------------------------------------------------------------

    def _solve(self, robot: int, legs: list[Leg], begin: Cell, step: int
               ) -> tuple[list[Cell], dict[int, Task]] | None:
        space = Space.gather(robot, self.reservations, [leg.task for leg in legs], [leg.windows for leg in legs],
                             begin, step, lazy=self.engine == "python")
        space.estimate([leg.deadline for leg in legs], [leg.length for leg in legs])
        return ENGINES[self.engine](space)


def asp_search(space: Space) -> tuple[list[Cell], dict[int, Task]] | None:
    """``route.lp`` on ``space``: the route with the earliest arrival, or ``None``."""
    # a Control of its own, not the driver's (asprilo.solver says why: hundreds of tiny calls)
    control = clingo.Control(["--warn=none"])
    control.load(str(PROGRAM))
    control.add("base", [], space.facts())
    control.ground([("base", [])])
    symbols: list[clingo.Symbol] = []
    result = control.solve(on_model=lambda model: symbols.extend(model.symbols(shown=True)))
    if not result.satisfiable or not any(s.name == "arrival" for s in symbols):
        return None
    return _route(symbols, space.tasks, space.step)


def _windows(corridor: np.ndarray, first: np.ndarray, last: np.ndarray) -> dict[Cell, tuple[int, int]]:
    """Cell -> (first, last) step of the cells of ``corridor`` where the first comes no
    later than the last (arrays of the grid's shape; computed for all cells at once)."""
    xs, ys = np.nonzero(corridor & (first <= last))
    firsts, lasts = first[xs, ys].astype(np.int64).tolist(), last[xs, ys].astype(np.int64).tolist()
    return dict(zip(zip(xs.tolist(), ys.tolist(), strict=True), zip(firsts, lasts, strict=True), strict=True))


def _slots(legs: list[Leg]) -> int:
    """The (cell, step) pairs the legs' windows hold."""
    return sum(last - first + 1 for leg in legs for first, last in leg.windows.values())


def _too_late(legs: list[Leg], table: Reservations, robot: int) -> bool:
    """Whether an action's cell is taken for good by another robot before this robot
    can possibly be there."""
    for leg in legs:
        if leg.task.name != "park":
            since = table.stay(leg.task.cells[0], robot)
            if since is not None and since <= leg.earliest + leg.length + 1:
                return True
    return False


#: the routing engines: the Python search (:mod:`.timed_search`) and the logic program ``route.lp``
ENGINES = {"python": search, "asp": asp_search}


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
