"""Assignments of shelves to order lines and robots, judged by a relaxed schedule and
improved by local search (domains A, B and C).

The relaxed schedule ignores collisions between robots but counts everything else a robot
does: the walk to each shelf (under the resting shelves), the pickup, the carry to each of
its stations (around them), the deliveries, the carry to a cell where the shelf is put down
(its own cell or a spare one, whichever makes the way to the next shelf shortest), the
put-down; and the queue at every station: one robot on a station at a time, the next one
moving in as the last one moves out.  Its makespan is the last delivery (one step more for
a robot that must leave a station another robot uses after it).

:class:`Schedules` searches assignments with simulated annealing from the planner's own:
move a shelf to another robot or to another place in a robot's errand, swap two shelves of
two robots, serve a line from other shelves (shelves already used first: one shelf then
serves lines of several orders in one visit).  It keeps the best few distinct assignments,
from which :mod:`.improve` restarts its search.
"""

from __future__ import annotations

import heapq
import math
import random
import time
from collections.abc import Callable
from dataclasses import dataclass

import clingo
import numpy as np

from asprilo.domain import Delivery
from asprilo.model import Cell

from .assignment import Choice
from .work import Work, entered

Line = tuple[int, int]
#: how many of the best distinct assignments are kept
KEPT = 24
#: the steps counted for a way that does not exist (a shelf that cannot get out yet): so many
#: that the search leaves such assignments
FAR = 10**6
#: the annealing's temperature at the start and the end (in steps of makespan)
HOT, COLD = 2.0, 0.05


@dataclass(frozen=True)
class Assignment:
    """Which shelves serve each line with how many units (``gives``: line -> ((shelf, units),
    ...)), and which shelves each robot brings in which order (``errands``)."""

    gives: tuple[tuple[Line, tuple[tuple[int, int], ...]], ...]
    errands: tuple[tuple[int, tuple[int, ...]], ...]

    def by_robot(self) -> dict[int, list[int]]:
        """Robot -> its shelves in order."""
        return {robot: list(shelves) for robot, shelves in self.errands}

    def choice(self) -> Choice:
        """The assignment as the shelf assignment program's atoms: ``give(S,O,P,N)``, ``carry(R,S)``."""
        atoms = {clingo.Function("give", [clingo.Number(n) for n in (shelf, order, product, units)])
                 for (order, product), portions in self.gives for shelf, units in portions}
        atoms |= {clingo.Function("carry", [clingo.Number(robot), clingo.Number(shelf)])
                  for robot, shelves in self.errands for shelf in shelves}
        return Choice(atoms)


class Schedules:
    """The relaxed schedule of one instance's work, and the search over its assignments."""

    def __init__(self, work: Work, seed: int = 0):
        self.work, self.random = work, random.Random(seed)
        instance, domain = work.instance, work.domain
        self.units = domain.counts_units
        self.per_station = domain.delivery is Delivery.STATION  # one deliver serves all a shelf's lines there
        stock = instance.shelf_stock()
        self.lines: dict[Line, int] = {(o.id, p): (q or 1) if self.units else 1
                                       for o in instance.orders.values() for p, q in o.lines.items()}
        self.station: dict[int, Cell] = {o.id: instance.stations[o.station].at for o in instance.orders.values()
                                          if o.station is not None}
        self.holders: dict[int, list[int]] = {}
        self.stock: dict[tuple[int, int], float] = {}
        for shelf, held in stock.items():
            for product, units in held.items():
                self.holders.setdefault(product, []).append(shelf)
                self.stock[(shelf, product)] = (units or 1) if self.units else math.inf
        carried = {robot.carries: robot.id for robot in instance.robots.values() if robot.carries is not None}
        #: shelf -> the robot that starts with it (and brings it first, or not at all)
        self.carried = carried
        self.robots = sorted(robot.id for robot in instance.robots.values())
        self.free = [robot for robot in self.robots if instance.robots[robot].carries is None]
        self._carry: dict[tuple[Cell, frozenset[Cell]], np.ndarray] = {}
        self._walk: dict[int, np.ndarray] = {}
        self._spare: dict[tuple[Cell, int], int] = {}
        self.kept: list[tuple[tuple[int, int], Assignment]] = []

    # --- distances ---------------------------------------------------------------------------

    def carry(self, source: Cell, target: Cell, lifted: frozenset[Cell] = frozenset()) -> int:
        """Steps from ``source`` to ``target`` with a shelf, around the resting shelves but
        through the cells of ``lifted`` (whose shelves are away then)."""
        key = (source, lifted)
        if key not in self._carry:
            passable = self.work.carrying | self.work.grid.mask(lifted) if lifted else self.work.carrying
            self._carry[key] = self.work.grid.distances([source], passable)
        return int(min(entered(self._carry[key], target), FAR))

    def walk(self, cell: Cell, shelf: int) -> int:
        """Steps from ``cell`` to ``shelf``'s cell without a shelf."""
        if shelf not in self._walk:
            self._walk[shelf] = self.work.grid.distances([self.work.homes[shelf]])
        return int(min(self._walk[shelf][cell], FAR))

    def between(self, station: Cell, shelf: int, following: int, lifted: frozenset[Cell],
                vacated: list[Cell]) -> tuple[int, Cell | None]:
        """Steps from the last delivery of ``shelf`` at ``station`` to the pickup of
        ``following`` (carry to a cell, put down, walk: the best of the shelf's own cell, the
        spare cells and the ``vacated`` cells of shelves that never come back), and the
        vacated cell taken (``None``: the shelf's own cell or a spare one)."""
        home = self.work.homes[shelf]
        own = self.carry(station, home, lifted) + 1 + self.walk(home, following)
        spare = (station, following)
        if spare not in self._spare:
            self._spare[spare] = min((self.carry(station, cell) + 1 + self.walk(cell, following)
                                      for cell in self.work.spare_cells()), default=FAR)
        best, taken = min(own, self._spare[spare]), None
        for cell in vacated:
            steps = self.carry(station, cell, lifted) + 1 + self.walk(cell, following)
            if steps < best:
                best, taken = steps, cell
        return best, taken

    # --- the relaxed schedule ------------------------------------------------------------------

    def stops(self, gives: dict[Line, dict[int, int]]) -> dict[int, list[tuple[Cell, int]]]:
        """Shelf -> its (station, deliver actions) in visiting order (the nearest station next)."""
        calls: dict[int, dict[Cell, set]] = {}
        for line, portions in gives.items():
            for shelf in portions:
                calls.setdefault(shelf, {}).setdefault(self.station[line[0]], set()).add(line)
        result = {}
        for shelf, stations in calls.items():
            at, left, visits = self.work.homes[shelf], dict(stations), []
            while left:
                station = min(sorted(left), key=lambda c: abs(c[0] - at[0]) + abs(c[1] - at[1]))
                served = left.pop(station)
                visits.append((station, 1 if self.per_station else len(served)))
                at = station
            result[shelf] = visits
        return result

    def cost(self, gives: dict[Line, dict[int, int]], errands: dict[int, list[int]]) -> tuple[int, int]:
        """(makespan, sum of the robots' finishes) of the relaxed schedule."""
        stops = self.stops(gives)
        homes = self.work.homes
        away: dict[int, list[float]] = {}  # shelf -> [lifted, back on its own cell] (steps)
        finals = {shelves[-1] for shelves in errands.values() if shelves}
        claimed: set[Cell] = set()  # vacated cells a shelf was put down on

        def lifted(step: int) -> frozenset[Cell]:
            """The cells whose shelves are away at ``step``."""
            return frozenset(homes[shelf] for shelf, (up, back) in away.items() if up < step < back)

        queue = self._starts(errands, stops, away, lifted)
        free: dict[Cell, int] = {}
        last: dict[Cell, tuple[int, int]] = {}  # station -> (last delivery, robot)
        finish: dict[int, tuple[int, Cell]] = {}
        while queue:
            arrival, robot, index, stop = heapq.heappop(queue)
            shelf = errands[robot][index]
            station, calls = stops[shelf][stop]
            end = max(arrival, free.get(station, 0)) + calls
            free[station] = end + 1
            last[station] = max(last.get(station, (0, 0)), (end, robot))
            if stop + 1 < len(stops[shelf]):
                heapq.heappush(queue, (end + self.carry(station, stops[shelf][stop + 1][0]), robot, index, stop + 1))
            elif index + 1 < len(errands[robot]):
                following = errands[robot][index + 1]
                vacated = [homes[other] for other in finals if other in away and away[other][0] < end
                           and homes[other] not in claimed and self.carried.get(other) is None]
                steps, taken = self.between(station, shelf, following, lifted(end), vacated)
                fetched = end + steps + 1
                if taken is not None:
                    claimed.add(taken)
                else:  # back on its own cell (or on a spare one: the cell counts as closed again)
                    away[shelf][1] = fetched - 1 - self.walk(homes[shelf], following)
                away[following] = [fetched, math.inf]
                heapq.heappush(queue, (fetched + self.carry(homes[following], stops[following][0][0], lifted(fetched)),
                                       robot, index + 1, 0))
            else:
                finish[robot] = (end, station)
        ends = [end + (last[station][1] != robot) for robot, (end, station) in finish.items()]
        return max(ends, default=0), sum(ends)

    def _starts(self, errands: dict[int, list[int]], stops: dict[int, list[tuple[Cell, int]]],
                away: dict[int, list[float]], lifted: Callable[[int], frozenset[Cell]]
                ) -> list[tuple[int, int, int, int]]:
        """The first arrivals at a station, a heap of (step, robot, 0, 0); the first shelves'
        lifts go into ``away``."""
        robots = self.work.instance.robots
        for robot, shelves in errands.items():
            if shelves:
                first = shelves[0]
                away[first] = [0 if self.carried.get(first) == robot else self.walk(robots[robot].at, first) + 1,
                               math.inf]
        queue = []
        for robot, shelves in errands.items():
            if shelves:
                fetched = int(away[shelves[0]][0])
                queue.append((fetched + self.carry(self.work.homes[shelves[0]], stops[shelves[0]][0][0],
                                                   lifted(fetched)), robot, 0, 0))
        heapq.heapify(queue)
        return queue

    # --- the search ------------------------------------------------------------------------------

    def current(self) -> tuple[dict[Line, dict[int, int]], dict[int, list[int]]]:
        """The work's assignment: line -> {shelf: units}, robot -> shelves in order."""
        gives: dict[Line, dict[int, int]] = {line: {} for line in self.lines}
        for shelf, order, product, units in self.work.choice.of("give"):
            gives.setdefault((order, product), {})[shelf] = units
        errands = {robot: [trip.shelf for trip in trips] for robot, trips in self.work.trips.items()}
        return gives, errands

    def search(self, seconds: float, stopped: Callable[[], bool] = lambda: False) -> list[Assignment]:
        """Anneal from the work's assignment for ``seconds``; the best few distinct
        assignments found, best first (the work's own among them when it is one)."""
        gives, errands = self.current()
        if any(not portions for portions in gives.values()):
            return []
        errands = {robot: errands.get(robot, []) for robot in self.robots}
        score = self.cost(gives, errands)
        self._keep(score, gives, errands)
        began, steps = time.perf_counter(), 0
        while True:
            steps += 1
            spent = (time.perf_counter() - began) / seconds
            if spent >= 1 or (steps % 64 == 0 and stopped()):
                break
            temperature = HOT * (COLD / HOT) ** spent
            moved = self._neighbour(gives, errands)
            if moved is None:
                continue
            new = self.cost(*moved)
            worse = _scalar(new) - _scalar(score)
            if worse <= 0 or self.random.random() < math.exp(-worse / temperature):
                (gives, errands), score = moved, new
                self._keep(score, gives, errands)
        return [assignment for _, assignment in sorted(self.kept, key=lambda kept: kept[0])]

    def _keep(self, score: tuple[int, int], gives: dict[Line, dict[int, int]], errands: dict[int, list[int]]) -> None:
        assignment = Assignment(tuple(sorted((line, tuple(sorted(p.items()))) for line, p in gives.items())),
                                tuple(sorted((robot, tuple(shelves)) for robot, shelves in errands.items() if shelves)))
        if any(kept == assignment for _, kept in self.kept):
            return
        if len(self.kept) < KEPT or score < max(self.kept, key=lambda kept: kept[0])[0]:
            self.kept.append((score, assignment))
            self.kept.sort(key=lambda kept: kept[0])
            del self.kept[KEPT:]

    def _neighbour(self, gives: dict[Line, dict[int, int]], errands: dict[int, list[int]]
                   ) -> tuple[dict[Line, dict[int, int]], dict[int, list[int]]] | None:
        """A changed copy of the assignment, or ``None`` when the drawn move does not apply."""
        gives, errands = dict(gives), {robot: list(shelves) for robot, shelves in errands.items()}
        move = self.random.random()
        if move < 0.25:
            return (gives, errands) if self._reserve(gives, errands) else None
        loose = [(robot, i) for robot, shelves in errands.items() for i, shelf in enumerate(shelves)
                 if shelf not in self.carried]
        if not loose:
            return None
        robot, i = self.random.choice(loose)
        if move < 0.55:  # to another robot (or another place of the same robot's errand)
            shelf = errands[robot].pop(i)
            other = self.random.choice(self.free)
            errands[other].insert(self.random.randint(0, len(errands[other])), shelf)
            return self._settled(gives, errands)
        if move < 0.8:  # swap with a shelf of another robot
            other, j = self.random.choice(loose)
            if other == robot:
                return None
            errands[robot][i], errands[other][j] = errands[other][j], errands[robot][i]
            return self._settled(gives, errands)
        shelves = errands[robot]  # another place in the same errand
        j = self.random.randrange(len(shelves))
        shelves.insert(j, shelves.pop(i))
        return self._settled(gives, errands)

    def _settled(self, gives, errands):
        """The assignment, with every robot's carried shelf first."""
        for robot, shelves in errands.items():
            mine = [shelf for shelf in shelves if self.carried.get(shelf) == robot]
            if mine and shelves[0] != mine[0]:
                shelves.remove(mine[0])
                shelves.insert(0, mine[0])
        return gives, errands

    def _reserve(self, gives: dict[Line, dict[int, int]], errands: dict[int, list[int]]) -> bool:
        """Serve a line drawn at random from other shelves (in place: ``gives`` is replaced
        by a changed copy through the caller's dict); whether that changed anything."""
        line = self.random.choice(list(self.lines))
        product, wanted = line[1], self.lines[line]
        used = {shelf for portions in gives.values() for shelf in portions}
        left = {shelf: self.stock[(shelf, product)] - sum(p.get(shelf, 0) for other, p in gives.items()
                                                          if other != line and other[1] == product)
                for shelf in self.holders.get(product, [])}
        candidates = list(left)
        self.random.shuffle(candidates)
        if self.random.random() < 0.5:
            candidates.sort(key=lambda shelf: shelf not in used)
        portions: dict[int, int] = {}
        for shelf in candidates:
            if wanted <= 0:
                break
            given = int(min(wanted, left[shelf]))
            if given > 0:
                portions[shelf] = given
                wanted -= given
        if wanted > 0 or portions == gives[line]:
            return False
        changed = {**gives, line: portions}
        still = {shelf for p in changed.values() for shelf in p}
        for shelves in errands.values():
            shelves[:] = [shelf for shelf in shelves if shelf in still]
        for shelf in still - used:
            robot = self.carried.get(shelf) or self.random.choice(self.free)
            errands[robot].insert(0 if shelf in self.carried else self.random.randint(0, len(errands[robot])), shelf)
        gives.clear()
        gives.update(changed)
        return True


def _scalar(score: tuple[int, int]) -> float:
    """The annealing's one number: the makespan, the sum of finishes breaking ties."""
    return score[0] + score[1] / 1000
