"""The work of one instance: what every robot has to do, and how that is decided.

:class:`Work` turns an assignment (goal cells in M/Md, shelves and order lines in A/B/C)
into errands, one per robot, and re-assigns the robots a neighbourhood frees.  Robots
without work that stand where others need to be (a station, a shelf to be fetched, a goal)
are sent to park nearby.  A robot with several shelves puts each one but the last down on
the spare storage cell (one no shelf starts on) that makes its way on shortest, or on a
cleared cell: one whose shelf serves no order and another robot first carries away to a
spare cell (:meth:`Work.clear`), because putting a shelf down there saves steps.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Collection, Iterator
from itertools import pairwise

import clingo
import numpy as np

from asprilo.bounds import INFINITE
from asprilo.domain import Domain, Job
from asprilo.model import DIRECTIONS, Cell, Instance

from .asides import held
from .assignment import Choice, aims, goal_problem, shelf_problem
from .errands import Task, Trip, delivery_errand, goal_errand, shelf_home, trips
from .grid import Grid, cells_of
from .room import movers, room_task

#: the share of the time limit the first assignment may spend optimising, and its cap (s)
ASSIGN_SHARE, ASSIGN_CAP = 0.05, 2.0
#: how far from its last station a robot may park when the others' tracks are all known
PARK_RADIUS = 3
#: the cells on each side of a put-down cell within which the ways around it must join
AROUND = 2
#: how many spare cells near its last station a robot with a shelf may park on, chosen from
#: how many nearest the station
SETTLE_CELLS, SETTLE_KEPT = 4, 64


class Work:
    """Errands per robot for one instance, and the assignment they come from."""

    def __init__(self, instance: Instance, domain: Domain, grid: Grid, longest: float):
        self.instance, self.domain, self.grid = instance, domain, grid
        self.homes = {s: shelf_home(instance, s) for s in instance.shelves}
        carried = {robot.carries for robot in instance.robots.values()}
        #: the cells of the shelves that rest at the start (not those carried)
        self.resting = {cell for shelf, cell in self.homes.items() if shelf not in carried}
        self.longest = longest
        self.goals: dict[int, Cell] = {}
        self.trips: dict[int, list[Trip]] = {}
        self.choice = Choice()
        self._problem = None
        self._parking: dict[Cell, tuple[Cell, ...]] = {}
        self._settling: dict[Cell, list[Cell]] = {}  # station -> the spare cells nearest it
        self._parking_cells: frozenset[Cell] | None = None
        self._movers: list[int] | None = None
        #: the ways of robots that robots without work once blocked (:meth:`make_room`)
        self.kept_clear: set[Cell] = set()
        #: shelf -> the spare cell it is put down on after its trip (chosen with its errand)
        self.claims: dict[int, Cell] = {}
        #: robot -> the shelves serving no order it carries away first, each to its spare cell
        self.clearings: dict[int, list[tuple[int, Cell]]] = {}
        #: cells of shelves that never come back (:meth:`vacated`) offered for putting shelves down
        self.offered: frozenset[Cell] = frozenset()
        self._cells, self._storage = instance.cells, instance.storage_cells
        self._spare: list[Cell] | None = None  # storage cells no shelf starts on and none closes a way on
        self._needed: tuple[tuple, set[Cell]] | None = None  # ((trips, goals, kept clear), needed cells)
        # needed cells -> the cells taken (a mask) and the rooms offered so far
        self._taken: tuple[set[Cell], np.ndarray, dict[int, Task]] | None = None
        self._highways = grid.mask(instance.highways.values())
        self._resting = grid.mask(self.resting)
        self.carrying = grid.floor & ~self._resting  # where a robot with a shelf gets through

    # --- the first assignment ----------------------------------------------------------------

    def assign(self, budget: float, stopped: Callable[[], bool]) -> bool:
        """Compute the first assignment (optimising for ``budget`` seconds, waiting for a
        first one until ``stopped()``); whether there is one."""
        if self.domain.work is Job.TRIPS:
            return self._assign_shelves(budget, stopped)
        self._problem = goal_problem(self.instance, self.grid, self.longest)
        choice = self._problem.assigner.solve(budget=budget, stopped=stopped)
        if choice is None:
            return False
        self._take(choice)
        return True

    def _assign_shelves(self, budget: float, stopped: Callable[[], bool]) -> bool:
        nearest = 12
        while True:
            self._problem = shelf_problem(self.instance, self.grid, self.domain, self.homes, nearest)
            choice = self._problem.assigner.solve(budget=budget, stopped=stopped)
            if choice is not None:
                self._take(choice)
                return True
            if not self._problem.assigner.unsatisfiable or nearest >= len(self.instance.robots):
                return False
            nearest *= 4

    def _take(self, choice: Choice) -> None:
        self.choice, self._parking_cells, self._movers = choice, None, None
        if self.domain.work is Job.TRIPS:
            self.trips = trips(self.instance, self.domain, choice.of("give"), choice.of("carry"), self.homes)
            for robot in [robot for robot in self.clearings if robot not in self.trips]:
                self.unclear(robot)  # a robot left without trips clears nothing (it makes room)
            self._unbox()
        else:
            self.goals = aims(choice, self._problem)

    def adopt(self, choice: Choice, order: dict[int, list[int]]) -> None:
        """Take an assignment made elsewhere (:mod:`.relaxed`), each robot's shelves in ``order``;
        the old one's cleared, claimed and offered cells are dropped (another robot's now, maybe)."""
        self.clearings, self.claims, self.offered = {}, {}, frozenset()
        self._take(choice)
        self.trips = {robot: sorted(ts, key=lambda t: order[robot].index(t.shelf)) for robot, ts in self.trips.items()}

    def save(self) -> tuple:
        """The current assignment, to :meth:`restore` it later."""
        return self.choice, self.trips, self.goals, dict(self.claims), self.clearings, self.offered

    def restore(self, saved: tuple) -> None:
        self.choice, self.trips, self.goals, claims, self.clearings, self.offered = saved
        self.claims = dict(claims)
        self._parking_cells = self._movers = None

    # --- re-assigning a neighbourhood --------------------------------------------------------------

    def reassignable(self) -> bool:
        """Whether the work can go to other robots at all (not so where every robot of M/Md
        has its own goal)."""
        return self.domain.work is Job.TRIPS or len(self.instance.assigned_cells()) < len(self.instance.robots)

    def reassign(self, freed: set[int], budget: float, moved: int | None = None) -> bool:
        """Assign the work of the ``freed`` robots among them anew (others keep theirs;
        ``moved``: a shelf that must go to another robot than its own now); whether the
        assignment changed."""
        if self._problem is None:
            return False
        keep, drop = self._fixed(freed)
        if moved is not None:
            drop += [atom for atom in self.choice.atoms if atom.name == "carry" and atom.arguments[1].number == moved]
        choice = self._problem.assigner.solve(keep, drop, budget=budget)
        if choice is None or choice.atoms == self.choice.atoms:
            return False
        self._take(choice)
        return True

    def _fixed(self, freed: set[int]) -> tuple[list[clingo.Symbol], list[clingo.Symbol]]:
        """The atoms that keep the other robots' work as it is: those to hold, and those
        to be false (no other robot gets new work; a kept shelf serves what it served)."""
        atoms, offered = self.choice.atoms, self._problem.assigner.atoms
        kept = {a for a in atoms if a.name in ("aim", "carry") and a.arguments[0].number not in freed}
        shelves = {a.arguments[1].number for a in kept if a.name == "carry"}
        kept |= {a for a in atoms if a.name == "give" and a.arguments[0].number in shelves}
        drop = [a for a in offered if a not in kept and (
            (a.name in ("aim", "carry") and a.arguments[0].number not in freed)
            or (a.name == "give" and a.arguments[0].number in shelves))]
        return list(kept), drop

    # --- errands -------------------------------------------------------------------------------

    def workers(self) -> list[int]:
        """The robots that have something to do."""
        return sorted(self.trips if self.domain.work is Job.TRIPS else self.goals)

    def stations_of(self, robot: int) -> set[Cell]:
        return {cell for trip in self.trips.get(robot, []) for cell, _, _ in trip.deliveries}

    def errand(self, robot: int, routed: set[int], roomy: bool = False,
               parked: Collection[Cell] = ()) -> list[Task]:
        """What ``robot`` does.  ``roomy``: every other robot's track is known (``routed``
        holds those that are), so it may park on its last station when no other robot needs
        that station any more, or on a free cell near it; the first plan does neither
        (robots parked there would block the ones routed later).  Either may park on a
        spare storage cell near its last station (:meth:`_settle`), else it brings its last
        shelf back.  ``parked``: cells where other robots stay for good (no shelf is put
        down there, no robot parks there)."""
        if self.domain.work is Job.GOALS:
            return goal_errand(self.goals[robot]) if robot in self.goals else self._make_room(robot)
        trips_ = self.trips.get(robot, [])
        if not trips_:  # a robot without trips may hold shelves aside (:mod:`.asides`)
            return held(self, robot) or self._make_room(robot)
        last = trips_[-1].deliveries[-1][0] if trips_[-1].deliveries else None
        home = self.homes[trips_[-1].shelf]
        # a shelf carried from the start has the robot's start cell as its home: park
        # elsewhere when that is no place for a shelf (a highway, a station)
        park = (home,) if home in self._storage else self._room(robot).cells
        if last is not None and roomy:
            if all(other in routed for other in self.trips if other != robot and last in self.stations_of(other)):
                park = (last,)
            park += self._near(last)
        if last is not None:
            park += self._settle(last, set(parked))
        putdowns = self._putdowns(trips_, set(parked))
        spared = set(self.claims.values())  # a shelf put down there stays: no robot parks there with one
        park = tuple(cell for cell in park if cell not in spared) or park
        clearing = [task for shelf, cell in self.clearings.get(robot, [])
                    for task in (Task("pickup", (self.homes[shelf],), False, shelf),
                                 Task("putdown", (cell,), True, shelf))]
        return clearing + delivery_errand(self.instance, robot, trips_, park, putdowns)

    def _putdowns(self, trips_: list[Trip], parked: set[Cell]) -> dict[int, Cell]:
        """Where the shelves of ``trips_`` but the last are put down: on the spare storage cell
        (or the shelf's own cell, when that is as good) that makes the way from its last
        station to the next shelf shortest, one no other shelf is put down on, no robot
        stays on, and none that would close a way (:meth:`_closes_a_way`: a shelf next to a
        station can close its only way in); the choice is kept in :attr:`claims`."""
        mine = {trip.shelf for trip in trips_}
        taken = {cell for shelf, cell in self.claims.items() if shelf not in mine} | parked
        cleared = [cell for cell in self.cleared() if cell not in taken]
        cleared += [cell for cell in self.vacated(mine) if cell in self.offered and cell not in taken]
        putdowns = {}
        for trip, carry, walk in self._changes(trips_):
            home = self.homes[trip.shelf]
            steps = {cell: carry[cell] + walk[cell] for cell in self.spare_cells() if cell not in taken}
            # the shelf's own cell and the cleared ones are empty by then: entered from a neighbour
            # (the carrying way goes around every cell a shelf starts on, these included)
            homes = [home] if home in self._storage else []
            steps.update({cell: entered(carry, cell) + walk[cell] for cell in [*cleared, *homes]})
            reachable = [cell for cell in steps if steps[cell] < INFINITE]
            if not reachable:
                continue
            best = min(reachable, key=lambda cell: (steps[cell], cell != home))
            putdowns[trip.shelf] = best
            taken.add(best)
        for shelf in mine:
            self.claims.pop(shelf, None)
        self.claims.update({shelf: cell for shelf, cell in putdowns.items() if cell != self.homes[shelf]})
        return putdowns

    def _changes(self, trips_: list[Trip]) -> Iterator[tuple[Trip, np.ndarray, np.ndarray]]:
        """For each trip of ``trips_`` but the last: the trip, the steps from its last station
        with a shelf (around the resting shelves) and without one from the next shelf's cell."""
        for trip, following in pairwise(trips_):
            start = trip.deliveries[-1][0] if trip.deliveries else self.homes[trip.shelf]
            yield trip, self._way(start, True), self._way(self.homes[following.shelf], False)

    def spare_cells(self) -> list[Cell]:
        """The storage cells that no shelf starts on and where a shelf closes no way."""
        if self._spare is None:
            self._spare = sorted(cell for cell in self._storage - set(self.homes.values())
                                 if not self._closes_a_way(cell))
        return self._spare

    def _closes_a_way(self, cell: Cell) -> bool:
        """Whether a shelf put down on ``cell`` could cut the ways of robots with shelves:
        the cells next to it where such a robot may be are not all joined around it within
        the square of :data:`AROUND` cells on each side (a cut there may still be a detour
        further away, but the floor's own shelves made few of those)."""
        free, (x, y) = self.carrying, cell
        width, height = free.shape

        def open_(c: Cell) -> bool:
            return 0 <= c[0] < width and 0 <= c[1] < height and c != cell and bool(free[c]) \
                and abs(c[0] - x) <= AROUND and abs(c[1] - y) <= AROUND

        near = [c for c in ((x + dx, y + dy) for dx, dy in DIRECTIONS) if open_(c)]
        seen, todo = set(near[:1]), near[:1]
        while todo:
            cx, cy = todo.pop()
            for c in ((cx + dx, cy + dy) for dx, dy in DIRECTIONS):
                if c not in seen and open_(c):
                    seen.add(c)
                    todo.append(c)
        return not seen.issuperset(near)

    def vacated(self, mine: Collection[int] = ()) -> list[Cell]:
        """The storage cells that a shelf leaves for good once lifted (none of ``mine``): the
        last shelf of a robot (whose robot parks elsewhere when the cell is claimed) and a
        shelf put down elsewhere.  A robot may put a shelf down there when the cell is
        :attr:`offered` (the ``vacate`` neighbourhood of :mod:`.improve`)."""
        carried = {robot.carries for robot in self.instance.robots.values()}
        shelves = {trips_[-1].shelf for trips_ in self.trips.values() if trips_} | set(self.claims)
        return sorted({self.homes[shelf] for shelf in shelves if shelf not in carried and shelf not in mine
                       and self.claims.get(shelf) != self.homes[shelf] and self.homes[shelf] in self._storage})

    def cleared(self) -> list[Cell]:
        """The cells whose shelves robots carry away first (:attr:`clearings`)."""
        return [self.homes[shelf] for jobs in self.clearings.values() for shelf, _ in jobs]

    def clear(self, robot: int, helper: int) -> bool:
        """Let ``helper`` first carry away a shelf that serves no order, to a spare cell,
        where ``robot`` putting a shelf down instead of on its present cell makes its way
        from the station to its next shelf shorter (the shortest such way is taken); whether
        there is such a shelf."""
        trips_ = self.trips.get(robot, [])
        if helper not in self.trips or self.instance.robots[helper].carries is not None or len(trips_) < 2:
            return False
        busy = {trip.shelf for ts in self.trips.values() for trip in ts}
        busy |= {r.carries for r in self.instance.robots.values() if r.carries is not None}
        busy |= {shelf for jobs in self.clearings.values() for shelf, _ in jobs}
        idle = [shelf for shelf, cell in self.homes.items() if shelf not in busy and cell in self._storage]
        best: tuple[float, int] | None = None  # (steps saved, shelf): infinite where the way now is blocked
        for trip, carry, walk in self._changes(trips_):
            now = self.claims.get(trip.shelf, self.homes[trip.shelf])
            steps = entered(carry, now) + walk[now]
            for shelf in idle:
                cell = self.homes[shelf]
                saved = steps - (entered(carry, cell) + walk[cell])
                if saved > 0 and (best is None or saved > best[0]):
                    best = (saved, shelf)
        if best is None:
            return False
        shelf = best[1]
        mine = {trip.shelf for trip in trips_}
        taken = {cell for other, cell in self.claims.items() if other not in mine} | set(self.cleared())
        away = self._way(self.homes[shelf], True)  # out from the shelf's own cell
        spots = [cell for cell in self.spare_cells() if cell not in taken and away[cell] < INFINITE]
        if not spots:
            return False
        spot = min(spots, key=lambda cell: (away[cell], cell))
        self.clearings = {**self.clearings, helper: [*self.clearings.get(helper, []), (shelf, spot)]}
        self.claims[shelf] = spot
        return True

    def _unbox(self) -> None:
        """A shelf to fetch that cannot be carried out of its cell (resting shelves that serve
        no order stand in every way to its first station, as in a dead end): its robot first
        carries those shelves to spare cells, the one nearest the station first."""
        busy = {trip.shelf for ts in self.trips.values() for trip in ts}
        busy |= {r.carries for r in self.instance.robots.values() if r.carries is not None}
        busy |= {shelf for jobs in self.clearings.values() for shelf, _ in jobs}
        for robot, trips_ in sorted(self.trips.items()):
            for trip in trips_:
                if not trip.deliveries:
                    continue
                for shelf in self._blockers(self.homes[trip.shelf], trip.deliveries[0][0]):
                    if shelf in busy:
                        break  # a shelf with work of its own: left to the search
                    taken = set(self.claims.values()) | set(self.cleared())
                    away = self._way(self.homes[shelf], True)
                    spots = [c for c in self.spare_cells() if c not in taken and entered(away, c) < INFINITE]
                    if not spots:
                        break
                    spot = min(spots, key=lambda c: (entered(away, c), c))
                    self.clearings = {**self.clearings, robot: [*self.clearings.get(robot, []), (shelf, spot)]}
                    self.claims[shelf] = spot
                    busy.add(shelf)

    def _blockers(self, home: Cell, station: Cell) -> list[int]:
        """The resting shelves on the way from ``station`` to ``home`` that passes the fewest of
        them, nearest the station first (none when a carried shelf gets out as things stand)."""
        if entered(self._way(station, True), home) < INFINITE:
            return []
        resting = {cell: shelf for shelf, cell in self.homes.items() if cell in self.resting and cell != home}
        crossed, came = {station: 0}, {station: station}
        todo: deque[Cell] = deque([station])
        while todo:  # 0-1 breadth first: entering a resting shelf's cell costs one
            cell = todo.popleft()
            if cell == home:
                break
            for dx, dy in DIRECTIONS:
                near = (cell[0] + dx, cell[1] + dy)
                if near not in self._cells:
                    continue
                cost = crossed[cell] + (near in resting)
                if cost < crossed.get(near, cost + 1):
                    crossed[near], came[near] = cost, cell
                    (todo.append if near in resting else todo.appendleft)(near)
        if home not in came:
            return []
        way, cell = [], home
        while cell != station:
            cell = came[cell]
            way.append(cell)
        return [resting[cell] for cell in reversed(way) if cell in resting]

    def unclear(self, helper: int) -> None:
        """``helper`` clears no cells any more: the shelves put down on them go elsewhere."""
        shelves = {shelf for shelf, _ in self.clearings.get(helper, [])}
        cells = {self.homes[shelf] for shelf in shelves}
        self.clearings = {robot: jobs for robot, jobs in self.clearings.items() if robot != helper}
        self.claims = {shelf: cell for shelf, cell in self.claims.items() if shelf not in shelves and cell not in cells}

    def _way(self, cell: Cell, carrying: bool):
        """Steps from ``cell`` to every cell (``carrying``: around the resting shelves; cached)."""
        return self.grid.distances([cell], self.carrying if carrying else None)

    def _near(self, station: Cell) -> tuple[Cell, ...]:
        """Cells a few steps from a station where a robot with a shelf may park."""
        if station not in self._parking:
            distance = self.grid.distances([station], self.carrying)
            stations = {s.at for s in self.instance.stations.values()}
            self._parking[station] = tuple(sorted(
                (c for c in cells_of(distance <= PARK_RADIUS) if c not in stations),
                key=lambda c: (int(distance[c]), c)))
        return self._parking[station]

    def _settle(self, station: Cell, parked: set[Cell]) -> tuple[Cell, ...]:
        """The :data:`SETTLE_CELLS` spare storage cells nearest ``station`` (for a robot with
        a shelf) that nobody needs and no other robot stays on: parking there after the last
        delivery saves carrying the shelf back (on 100x100 floors that doubled the first
        plan's makespan), and blocks no way (:meth:`spare_cells`)."""
        if station not in self._settling:
            distance = self._way(station, True)
            near = sorted((int(distance[cell]), cell) for cell in self.spare_cells() if distance[cell] < INFINITE)
            self._settling[station] = [cell for _, cell in near[:SETTLE_KEPT]]
        needed = self.needed_cells()
        free = [cell for cell in self._settling[station] if cell not in needed and cell not in parked]
        return tuple(free[:SETTLE_CELLS])

    def parking(self) -> frozenset[Cell]:
        """Cells where robots with work park for good (goals; homes of the shelves used):
        others had better keep off them."""
        if self._parking_cells is None:
            if self.domain.work is Job.TRIPS:
                self._parking_cells = frozenset(self.homes[t.shelf] for ts in self.trips.values() for t in ts)
            else:
                self._parking_cells = frozenset(self.goals.values())
        return self._parking_cells

    def needed_cells(self) -> set[Cell]:
        """Cells robots with work must be able to use: goals, shelves to fetch, stations and
        the cells next to them (the ways in and out)."""
        if self._needed is not None:  # kept while the work is the same (it is replaced, never changed in place)
            (trips_, goals, clear), cells = self._needed
            if trips_ is self.trips and goals is self.goals and clear == len(self.kept_clear):
                return cells
        if self.domain.work is Job.GOALS:
            cells = set(self.goals.values()) | self.kept_clear
        else:
            stations = {cell for robot in self.trips for cell in self.stations_of(robot)}
            cells = stations | {(x + dx, y + dy) for x, y in stations for dx, dy in DIRECTIONS}
            cells |= {self.homes[trip.shelf] for ts in self.trips.values() for trip in ts}
            cells = (cells | self.kept_clear) & self._cells
        self._needed = ((self.trips, self.goals, len(self.kept_clear)), cells)
        return cells

    def movers(self) -> list[int]:
        """Robots without work that have to make room (see :mod:`.room`), in routing order."""
        if self._movers is None:
            self._movers = movers(self.instance, set(self.workers()), self.needed_cells())
        return self._movers

    def make_room(self, robots: list[int], way: set[Cell]) -> list[int]:
        """Send ``robots`` without work that stand still on or next to another robot's ``way``
        to park off it (they become movers; the way is needed from now on); the ones that
        were not movers yet."""
        busy = set(self.movers()) | set(self.workers())
        new = [robot for robot in robots if robot not in busy]
        self.kept_clear |= way
        self._movers = self.movers() + new
        return new

    def _make_room(self, robot: int) -> list[Task]:
        """A robot without work: stay, or, standing in the way, park nearby."""
        if robot not in self.movers():
            carried = self.instance.robots[robot].carries
            return [Task("park", (self.instance.robots[robot].at,), carried is not None, carried)]
        return [self._room(robot)]

    def _room(self, robot: int) -> Task:
        """Where a robot making room parks: cells no robot before it in :meth:`movers` was
        offered (robots crowded in one corner were offered the same few cells, and the last
        of them found all taken), kept while the needed cells stay the same."""
        needed = self.needed_cells()
        if self._taken is None or self._taken[0] is not needed:
            stations = {s.at for s in self.instance.stations.values()}
            starts = {r.at for r in self.instance.robots.values()}
            self._taken = (needed, self.grid.mask(needed | stations | starts), {})
        _, taken, rooms = self._taken
        movers = self.movers()
        for other in movers[:movers.index(robot) + 1] if robot in movers else [robot]:
            if other not in rooms:
                rooms[other] = room_task(self.instance, self.grid, other, taken, self._highways, self._resting)
                for cell in rooms[other].cells:
                    taken[cell] = True
        return rooms[robot]

    def estimate(self, robot: int) -> float:
        """Steps the robot's errand takes at least (to order robots: the longest first)."""
        if self.domain.work is Job.GOALS:
            goal = self.goals.get(robot)
            start = self.instance.robots[robot].at
            return math.inf if goal is None else abs(goal[0] - start[0]) + abs(goal[1] - start[1])
        at, steps = self.instance.robots[robot].at, 0
        for trip in self.trips.get(robot, []):
            home = self.homes[trip.shelf]
            steps += abs(home[0] - at[0]) + abs(home[1] - at[1]) + 1
            at = home
            for cell, _, _ in trip.deliveries:
                steps += abs(cell[0] - at[0]) + abs(cell[1] - at[1]) + 1
                at = cell
        return steps


def entered(carry: np.ndarray, cell: Cell) -> float:
    """Steps to ``cell`` for a robot with a shelf, ``carry`` being the steps around the
    resting shelves: a cell whose own shelf is gone by then is entered from a neighbour."""
    if carry[cell] < INFINITE:
        return float(carry[cell])
    x, y = cell
    width, height = carry.shape
    near = [carry[x + dx, y + dy] for dx, dy in DIRECTIONS if 0 <= x + dx < width and 0 <= y + dy < height]
    return float(min(near, default=INFINITE)) + 1

