"""What the makespan bounds of domains A, B and C share, and the bounds by lines and stations.

Every order line needs a shelf that holds its product at its order's picking station.  A
shelf moves only on a robot: a robot must walk to it, lift it and carry it there, and a
robot carrying a shelf cannot pass a cell where another shelf rests until that shelf has
been lifted away.  That gives each line a *release*: the earliest step its first delivery
can happen.  A station serves one robot at a time, and a robot that delivers has to leave
before the next one comes in, so deliveries of different shelves at one station are at
least two steps apart (:func:`station_bound`).  Where every shelf serves one line at most
(the paper's M-aligned instances), a scheduling relaxation in ASP also takes into account
that a robot delivers one line at a time (:func:`schedule_bound`); where shelves serve
several lines, :mod:`asprilo.bounds.trip` places the delivery actions themselves
(:func:`asprilo.bounds.makespan.delivery_bound` picks).  In A, a product ordered beyond its
stock leaves no plan at all (:func:`short_of_stock`).  Nothing here is ever more than a
valid plan needs.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

from ..domain import Delivery, Domain
from ..model import DIRECTIONS, Cell, Instance
from .floor import INFINITE, Floor

if TYPE_CHECKING:
    import numpy as np

#: the scheduling relaxation: conflicts per horizon (a deterministic budget, smaller for big
#: programs, whose conflicts cost more: at most SCHEDULE_WORK / (lines x robots x horizon))
#: and horizons tried
SCHEDULE_CONFLICTS = 20_000
SCHEDULE_WORK = 400_000_000
SCHEDULE_STEPS = 64
_PROGRAM = Path(__file__).resolve().parent / "delivery.lp"


def carry_arrivals(cells: set[Cell], starts: dict[Cell, float], free_at: dict[Cell, float]) -> dict[Cell, float]:
    """The earliest step something that can be on each cell of ``starts`` at the step given
    there (a shelf lifted there, say) can be on each cell, moving one cell per step, when a
    cell in ``free_at`` can be entered no earlier than the step given there."""
    best = dict(starts)
    queue = [(step, cell) for cell, step in best.items()]
    heapq.heapify(queue)
    while queue:
        step, (x, y) = heapq.heappop(queue)
        if step > best[(x, y)]:
            continue
        for dx, dy in DIRECTIONS:
            cell = (x + dx, y + dy)
            if cell not in cells:
                continue
            arrival = max(step + 1, free_at.get(cell, 0))
            if arrival < best.get(cell, INFINITE):
                best[cell] = arrival
                heapq.heappush(queue, (arrival, cell))
    return best


#: cells x stations from which :meth:`Deliveries.carry` searches all stations at once with
#: numpy (on 200x200 with 100 stations: 0.14 s instead of 4.5 s); below, importing numpy
#: would cost more than it saves
NUMPY_SEARCH = 1_000_000
#: shelves of lines x cells up to which :meth:`Deliveries.arrival` searches forward from each
#: shelf in plain Python (:func:`carry_arrivals`); beyond, back from all stations at once with
#: numpy (:func:`arrivals_back`; 200x200 with 761 such shelves: 75 s and 3.8 GB forward).  At
#: least :data:`asprilo.bounds.makespan.CHEAP_VISITS`: the cheap bound goes without numpy.
FORWARD_VISITS = 100_000
#: stations searched back side by side in one pass (memory: about 40 bytes per station and cell)
STATIONS_AT_ONCE = 16


def arrivals_back(floor: Floor, stations: list[Cell], starts: np.ndarray, free_at: np.ndarray) -> np.ndarray:
    """``len(stations) x len(floor.cells)``: what :func:`carry_arrivals` finds at each station
    from each cell ``C`` alone at step ``starts[C]`` (``starts`` and ``free_at`` are indexed like
    ``floor.cells``; ``free_at`` is ``-INFINITE`` where a cell can be entered at any step), by
    one search back from every station instead of one forward from every cell.

    A way of ``a`` moves from ``C`` ends on the station at step ``max(starts[C] + a, late)``,
    where ``late`` is the latest of ``free_at`` of each cell entered on the way plus the moves
    left from there.  The search goes back one move per round, and a cell keeps a way only if
    its ``late`` beats that of every shorter way kept there (a longer way pays only where it
    passes cells free earlier); a ``late`` of at most ``a`` never counts (no start is before
    step 0).  The start's own ``free_at`` is never counted: a way back through its start is
    no better than the rest of it."""
    import numpy as np
    neighbours = floor.neighbours()
    size = len(floor.cells) + 1  # with the "no node" vertex
    starts = np.append(starts, 0.0)
    free_at = np.append(free_at, -INFINITE)
    result = np.full((len(stations), size), INFINITE)
    for first in range(0, len(stations), STATIONS_AT_ONCE):
        batch = stations[first:first + STATIONS_AT_ONCE]
        count = len(batch)
        offsets = np.arange(count) * size
        kept = np.full(count * size, INFINITE)  # per station and cell: the smallest late of a way kept
        kept[offsets + size - 1] = -INFINITE  # "no node" keeps nothing
        best = np.full(count * size, INFINITE)  # per station and cell: the earliest arrival found
        frontier = np.array([floor.index[cell] + offset for cell, offset in zip(batch, offsets, strict=True)
                             if cell in floor.index], dtype=np.int64)
        late = np.full(frontier.size, -INFINITE)
        kept[frontier] = late
        best[frontier] = starts[frontier % size]
        moves = 0
        while frontier.size:
            vertex = frontier % size
            leaving = np.maximum(free_at[vertex] + moves, late)  # the frontier's cells are entered, too
            moves += 1
            leaving[leaving <= moves] = -INFINITE
            reached = (neighbours[vertex] + (frontier - vertex)[:, None]).ravel()
            leaving = np.repeat(leaving, neighbours.shape[1])
            better = leaving < kept[reached]
            reached, leaving = reached[better], leaving[better]
            order = np.lexsort((leaving, reached))  # the best way into each reached cell first
            reached, leaving = reached[order], leaving[order]
            unique = np.ones(reached.size, dtype=bool)
            unique[1:] = reached[1:] != reached[:-1]
            frontier, late = reached[unique], leaving[unique]
            kept[frontier] = late
            best[frontier] = np.minimum(best[frontier], np.maximum(starts[frontier % size] + moves, late))
        result[first:first + count] = best.reshape(count, size)
    return result[:, :-1]


@dataclass(frozen=True)
class Line:
    """An order line still to be delivered: its station cell and the shelves holding its product."""

    order: int
    product: int
    station: Cell
    holders: tuple[int, ...]
    deliveries: int  # how many deliveries it needs at least (A: quantities)


class Deliveries:
    """What the bounds of one instance share: lines, shelf positions, robot distances.

    ``carriers`` (shelf -> robot, from a task assignment) restricts who may bring a shelf.
    ``stationless`` are the lines still to be delivered whose order names no station of the
    instance, as ``(order, product)``: no plan delivers them.  ``blocking``: whether a line's
    release takes into account that a carried shelf cannot pass shelves resting on its way
    (:meth:`arrival`, a search per shelf); without, a shelf arrives after its lifting and its
    walking distance (:meth:`carry`, a search per station), which is no later.
    """

    #: whether :meth:`release` goes by :meth:`arrival` (else by :meth:`carry` alone)
    blocking = True

    def __init__(self, instance: Instance, domain: Domain, floor: Floor, carriers: dict[int, int] | None = None):
        self.instance, self.domain, self.floor = instance, domain, floor
        self.carriers = carriers or {}
        carried = {r.carries: r.at for r in instance.robots.values() if r.carries is not None}
        self.carried = carried
        self.shelves = {s.id: s.at for s in instance.shelves.values()} | carried
        self.stock = instance.shelf_stock()
        self.lines, self.stationless = self._lines()
        self.robots = sorted(instance.robots)
        nearest = floor.steps_from(instance.robots[r].at for r in self.robots)  # the nearest robot's steps
        #: shelf -> the earliest step it can be off the ground (lifted by the nearest robot)
        self.lifted = {s: 0 if s in carried else float(nearest.get(cell, INFINITE)) + 1
                       for s, cell in sorted(self.shelves.items())}
        #: station -> shelf -> :meth:`arrival`, for the stations of ``_targets`` only
        self._arrivals: dict[Cell, dict[int, float]] = {}
        self._targets = {line.station for line in self.lines}
        self._searched: set[int] = set()  # the shelves searched forward
        self._from_station: dict[Cell, dict[Cell, int]] = {}

    @cached_property
    def walk(self) -> dict[int, np.ndarray]:
        """Shelf -> the steps from each robot (in the order of ``robots``) to the shelf's cell."""
        ids = sorted(self.shelves)
        walks = self.floor.distances([self.shelves[s] for s in ids], [self.instance.robots[r].at for r in self.robots])
        return {s: walks[k] for k, s in enumerate(ids)}

    def carry(self, shelf: int, station: Cell) -> float:
        """The distance from ``shelf``'s cell to ``station`` (one search per station; on a
        large floor with many stations, one search for all of them, with numpy)."""
        if station not in self._from_station:
            stations = sorted({line.station for line in self.lines} | {station})
            if len(self.instance.cells) * len(stations) < NUMPY_SEARCH:
                self._from_station[station] = self.floor.steps_from([station])
            else:
                cells = sorted(set(self.shelves.values()))
                for at, row in zip(stations, self.floor.distances(stations, cells).tolist(), strict=True):
                    self._from_station[at] = dict(zip(cells, row, strict=True))
        return float(self._from_station[station].get(self.shelves[shelf], INFINITE))

    def _lines(self) -> tuple[list[Line], list[tuple[int, int]]]:
        lines, stationless = [], []
        for order in self.instance.orders.values():
            station = None if order.station is None else self.instance.stations.get(order.station)
            for product, units in order.lines.items():
                if units == 0:
                    continue
                stock = self.instance.products[product].stock if product in self.instance.products else {}
                holders = tuple(sorted(s for s in stock if s in self.shelves))
                if station is None:
                    stationless.append((order.id, product))
                else:
                    deliveries = self._deliveries(product, units, holders)
                    lines.append(Line(order.id, product, station.at, holders, deliveries))
        return lines, stationless

    def _deliveries(self, product: int, units: int | None, holders: tuple[int, ...]) -> int:
        """A: the fewest shelves whose stock covers the line (each shelf gives at most once)."""
        if not self.domain.counts_units or units is None:
            return 1
        stocks = sorted((self.stock[s][product] or 1 for s in holders), reverse=True)
        total = 0
        for count, stock in enumerate(stocks, 1):
            total += stock
            if total >= units:
                return count
        return 1

    def arrival(self, shelf: int, station: Cell) -> float:
        """The earliest step ``shelf`` can stand on ``station``, carried: lifted at
        ``lifted[shelf]``, entering the cell of another shelf resting there from the start no
        earlier than the step after that one's ``lifted``.  Kept for the stations of lines
        only (and any other asked for): on a small floor found by a search forward from each
        shelf asked about, else by one search back from the stations for every shelf."""
        if station not in self._targets:
            self._targets.add(station)
            self._arrivals.clear()
            self._searched.clear()
        if self._searches_back:
            if not self._arrivals:
                self._arrivals = self._arrivals_back()
        elif shelf not in self._searched:
            self._searched.add(shelf)
            free_at = {cell: self.lifted[other] + 1 for other, cell in self.shelves.items()
                       if other != shelf and other not in self.carried}
            reached = carry_arrivals(self._cells, {self.shelves[shelf]: self.lifted[shelf]}, free_at)
            for target in self._targets:
                self._arrivals.setdefault(target, {})[shelf] = reached.get(target, INFINITE)
        return self._arrivals[station][shelf]

    @cached_property
    def _searches_back(self) -> bool:
        """Whether :meth:`arrival` searches back from the stations (:data:`FORWARD_VISITS`)."""
        holders = {shelf for line in self.lines for shelf in line.holders}
        return len(holders) * len(self.floor.cells) > FORWARD_VISITS

    @cached_property
    def _cells(self) -> set[Cell]:
        return self.instance.cells

    def _arrivals_back(self) -> dict[Cell, dict[int, float]]:
        """Station -> shelf -> :meth:`arrival`, for every station of ``_targets`` and every shelf
        (:func:`arrivals_back`; a shelf off the floor arrives nowhere)."""
        import numpy as np
        size = len(self.floor.cells)
        starts, free_at = np.zeros(size), np.full(size, -INFINITE)
        placed = {shelf: self.floor.index[cell] for shelf, cell in self.shelves.items() if cell in self.floor.index}
        for shelf, vertex in placed.items():
            starts[vertex] = self.lifted[shelf]
            if shelf not in self.carried:
                free_at[vertex] = self.lifted[shelf] + 1
        targets = sorted(self._targets)
        found = arrivals_back(self.floor, targets, starts, free_at)[:, list(placed.values())].tolist()
        nowhere = dict.fromkeys(self.shelves, INFINITE)
        return {target: nowhere | dict(zip(placed, row, strict=True))
                for target, row in zip(targets, found, strict=True)}

    def release(self, line: Line) -> float:
        """The earliest step of the line's first delivery (see ``blocking``)."""
        if not self.blocking:
            return min((self.lifted[s] + self.carry(s, line.station) + 1 for s in line.holders), default=INFINITE)
        return min((self.arrival(s, line.station) + 1 for s in line.holders), default=INFINITE)


def station_bound(facts: Deliveries) -> float:
    """The latest of the stations' last deliveries, each station serving its lines in order
    of release: one delivery per step, and one more step whenever the shelf changes."""
    bound = 0.0
    for station in {line.station for line in facts.lines}:
        lines = [line for line in facts.lines if line.station == station]
        per_shelf = max(sum(1 for line in lines if s in line.holders) for line in lines for s in line.holders)
        releases = sorted((facts.release(line), line.deliveries) for line in lines)
        for k in range(len(releases)):
            rest = releases[k:]
            # a line that needs d deliveries needs d different shelves, so d visits
            visits = max(math.ceil(len(rest) / per_shelf), max(count for _, count in rest))
            if facts.domain.delivery is Delivery.STATION:
                last = rest[0][0] + 2 * (visits - 1)
            else:
                last = rest[0][0] + sum(count for _, count in rest) - 1 + visits - 1
            bound = max(bound, last)
    return bound


def schedulable(facts: Deliveries) -> bool:
    """Whether the scheduling relaxation applies: no shelf serves two lines, every line has
    a shelf and a station, and there are robots."""
    if facts.stationless:
        return False
    served: dict[int, int] = {}
    for line in facts.lines:
        if not line.holders:
            return False
        for shelf in line.holders:
            served[shelf] = served.get(shelf, 0) + 1
    return bool(facts.lines) and bool(facts.robots) and max(served.values()) == 1


def schedule_bound(facts: Deliveries, start: float) -> float:
    """The first horizon from ``start`` on that the scheduling relaxation does not refute."""
    text = _schedule_facts(facts)
    horizon = int(start)
    for _ in range(SCHEDULE_STEPS):
        if _relaxed_schedule(text, horizon, _conflicts(facts, horizon)) != "unsat":
            return float(horizon)
        horizon += 1
    return float(horizon)


def _conflicts(facts: Deliveries, horizon: int) -> int:
    """The conflict budget of the relaxation at ``horizon``."""
    size = max(1, len(facts.lines) * len(facts.robots) * horizon)
    return max(1, min(SCHEDULE_CONFLICTS, SCHEDULE_WORK // size))


def _relaxed_schedule(text: str, horizon: int, conflicts: int) -> list | str:
    """A model of the relaxation at ``horizon`` (its deliver/3 atoms), or "unsat" / "unknown"
    (no answer within ``conflicts`` conflicts)."""
    from ..solver import Solver, Status

    solver = Solver(options=["--warn=none"], constants={"horizon": horizon})
    solver.load(_PROGRAM)
    solver.add(text)
    solver.ground()
    result = solver.solve(conflicts=conflicts)
    if result.status is Status.UNSAT:
        return "unsat"
    return result.symbols if result.satisfiable else "unknown"


def assigned_bound(instance: Instance, domain: Domain, floor: Floor, carriers: dict[int, int], start: float) -> float:
    """A makespan bound of the plans in which each shelf in ``carriers`` is brought by its robot
    (a task assignment): the scheduling relaxation with those robots, from ``start`` on."""
    facts = Deliveries(instance, domain, floor, carriers)
    if not facts.lines or not schedulable(facts):
        return start
    return schedule_bound(facts, start)


def delivery_schedule(instance: Instance, domain: Domain, floor: Floor, horizon: int,
                      carriers: dict[int, int] | None = None) -> list[tuple[int, int, int]]:
    """``(order, product, step)`` of every line in a schedule of the relaxation at ``horizon``:
    a guess of when each line is delivered, for search heuristics (empty when the relaxation
    does not apply or has no schedule).  ``carriers``: shelf -> robot, as for :class:`Deliveries`."""
    facts = Deliveries(instance, domain, floor, carriers)
    if not facts.lines or not schedulable(facts):
        return []
    model = _relaxed_schedule(_schedule_facts(facts), horizon, _conflicts(facts, horizon))
    if isinstance(model, str):
        return []
    steps = []
    for atom in model:
        line, _robot, step = (argument.number for argument in atom.arguments)
        steps.append((facts.lines[line].order, facts.lines[line].product, step))
    return sorted(steps)


def _schedule_facts(facts: Deliveries) -> str:
    stations = {cell: k for k, cell in enumerate(sorted({line.station for line in facts.lines}))}
    out = []
    for index, line in enumerate(facts.lines):
        out.append(f"line({index}). station_of({index},{stations[line.station]}).")
        for position, robot in enumerate(facts.robots):
            shelves = [s for s in line.holders if facts.carriers.get(s, robot) == robot]
            release = min((robot_release(facts, robot, position, s, line.station) for s in shelves), default=INFINITE)
            if math.isfinite(release):
                out.append(f"release({index},{robot},{int(release)}).")
    out.append(f"gap({int(min(_cycle(facts), 10**6))}).")
    return "\n".join(out)


def robot_release(facts: Deliveries, robot: int, position: int, shelf: int, station: Cell) -> float:
    """When ``robot`` can deliver from ``shelf`` at ``station`` first: after walking to it,
    lifting it and carrying it there (and no earlier than any robot could)."""
    carrier = facts.instance.robots[robot].carries
    walk = 0.0 if carrier == shelf else float(facts.walk[shelf][position]) + 1
    carry = facts.carry(shelf, station)
    return max(facts.arrival(shelf, station), walk + carry) + 1


def _cycle(facts: Deliveries) -> float:
    """The fewest steps between two deliveries of one robot from different shelves: carry
    the first shelf to a storage cell (not the one where the next shelf stands), put it
    down, walk to the next, lift it, bring it, deliver."""
    storage = sorted(facts.instance.storage_cells)
    if not storage:
        return INFINITE
    stations = sorted({line.station for line in facts.lines})
    shelves = sorted({s for line in facts.lines for s in line.holders})
    import numpy as np
    to_storage = facts.floor.distances(stations, storage).min(axis=0)  # nearest station per cell
    via = (storage_to_shelves(facts, storage, shelves) + to_storage[:, np.newaxis]).min(axis=0)
    best = INFINITE
    for line in facts.lines:
        for shelf in line.holders:
            k = shelves.index(shelf)
            best = min(best, 3 + via[k] + facts.carry(shelf, line.station))
    return best


def short_of_stock(facts: Deliveries) -> bool:
    """A: whether some product is ordered more often than the shelves hold it (no plan at all)."""
    if not facts.domain.counts_units:
        return False
    ordered: dict[int, int] = {}
    for order in facts.instance.orders.values():
        for product, units in order.lines.items():
            ordered[product] = ordered.get(product, 0) + (1 if units is None else units)
    for product, units in ordered.items():
        stock = facts.instance.products[product].stock if product in facts.instance.products else {}
        if units > sum(1 if held is None else held for shelf, held in stock.items() if shelf in facts.shelves):
            return True
    return False


def storage_to_shelves(facts: Deliveries, storage: list, shelves: list[int]) -> np.ndarray:
    """``len(storage) x len(shelves)`` distances from each storage cell to where each shelf
    started, except from the cell of a shelf resting there (infinite: nothing is put down
    there while it stands there; a shelf carried from the start may be set down under its
    robot and lifted again)."""
    cells = [facts.shelves[s] for s in shelves]
    distances = facts.floor.distances(cells, storage).T.copy()  # fewer searches: one per shelf
    row = {cell: i for i, cell in enumerate(storage)}
    for k, (shelf, cell) in enumerate(zip(shelves, cells, strict=True)):
        if cell in row and shelf not in facts.carried:
            distances[row[cell], k] = INFINITE
    return distances
