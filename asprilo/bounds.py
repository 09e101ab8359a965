"""Shortest paths on the floor and the assignment lower bounds of anonymous MAPF (M, Md).

Distances are 4-connected shortest paths over the floor's nodes, ignoring all other
robots and shelves, so every bound here is admissible: no valid plan does better.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import shortest_path

from .model import DIRECTIONS, Cell, Instance

INFINITE = float("inf")


class Floor:
    """The floor as a graph: one vertex per node, edges between adjacent nodes."""

    def __init__(self, cells: Iterable[Cell]):
        self.cells: list[Cell] = sorted(set(cells))
        self.index = {cell: i for i, cell in enumerate(self.cells)}
        rows, columns = [], []
        for (x, y), i in self.index.items():
            for dx, dy in DIRECTIONS:
                j = self.index.get((x + dx, y + dy))
                if j is not None:
                    rows.append(i)
                    columns.append(j)
        size = len(self.cells)
        self.graph = csr_matrix((np.ones(len(rows)), (rows, columns)), shape=(size, size))

    def distances(self, sources: Sequence[Cell], targets: Sequence[Cell]) -> np.ndarray:
        """``len(sources) x len(targets)`` shortest-path lengths (``inf``: unreachable).

        A cell that is not a node is unreachable from and to everything.
        """
        result = np.full((len(sources), len(targets)), INFINITE)
        known = [k for k, cell in enumerate(sources) if cell in self.index]
        if not known or not targets:
            return result
        rows = shortest_path(self.graph, method="D", unweighted=True,
                             indices=[self.index[sources[k]] for k in known])
        columns = [self.index.get(cell, -1) for cell in targets]
        for k, row in zip(known, np.atleast_2d(rows)):
            result[k] = [row[c] if c >= 0 else INFINITE for c in columns]
        return result


def bottleneck_assignment(costs: np.ndarray) -> float:
    """The least ``B`` such that every row gets its own column with cost <= ``B``.

    Rows are goals, columns are robots (at least as many).  ``inf`` if impossible.
    """
    goals, robots = costs.shape
    if goals == 0:
        return 0.0
    if robots < goals:
        return INFINITE
    thresholds = np.unique(costs[np.isfinite(costs)])
    low, high = 0, len(thresholds) - 1
    if high < 0 or not _matches_all(costs <= thresholds[high]):
        return INFINITE
    while low < high:
        middle = (low + high) // 2
        if _matches_all(costs <= thresholds[middle]):
            high = middle
        else:
            low = middle + 1
    return float(thresholds[low])


def _matches_all(allowed: np.ndarray) -> bool:
    """Whether every row can get its own allowed column (an assignment of cost 0 exists)."""
    from scipy.optimize import linear_sum_assignment  # imported when needed: it is slow to import
    rows, columns = linear_sum_assignment(~allowed)
    return bool(allowed[rows, columns].all())


def min_cost_assignment(costs: np.ndarray) -> float:
    """The least total cost of giving every row (goal) its own column (robot); ``inf`` if none."""
    goals, robots = costs.shape
    if goals == 0:
        return 0.0
    if robots < goals:
        return INFINITE
    finite = costs[np.isfinite(costs)]
    penalty = (finite.max() if finite.size else 0) * (goals + 1) + 1
    from scipy.optimize import linear_sum_assignment
    rows, columns = linear_sum_assignment(np.where(np.isfinite(costs), costs, penalty))
    total = costs[rows, columns]
    return float(total.sum()) if np.isfinite(total).all() else INFINITE


def goal_cells(instance: Instance) -> list[Cell]:
    """Cells some robot must occupy at the horizon: destinations (Md), else the cells of
    the shelves holding ordered products (M); each cell once."""
    if instance.destinations:
        return sorted({d.at for d in instance.destinations.values()})
    cells = set()
    for order in instance.orders.values():
        for product in order.lines:
            stock = instance.products[product].stock if product in instance.products else {}
            cells.update(instance.shelves[shelf].at for shelf in stock if shelf in instance.shelves)
    return sorted(cells)


def mapf_bounds(instance: Instance, floor: Floor | None = None) -> tuple[float, float]:
    """``(makespan bound, sum-of-costs bound)`` of an M/Md instance by robot-to-goal assignment.

    Robots with a labelled goal (``instance.assignment``) count their own distance to it;
    the other robots are matched to the remaining goals.
    """
    floor = floor or Floor(instance.cells)
    assigned = instance.assigned_cells()
    taken = set(assigned.values())
    goals = [cell for cell in goal_cells(instance) if cell not in taken]
    starts = [robot.at for ident, robot in sorted(instance.robots.items()) if ident not in assigned]
    costs = floor.distances(goals, starts)
    makespan, total = bottleneck_assignment(costs), min_cost_assignment(costs)
    if assigned:
        robots = sorted(assigned)
        own = floor.distances([assigned[r] for r in robots], [instance.robots[r].at for r in robots]).diagonal()
        makespan, total = max(makespan, float(own.max())), total + float(own.sum())
    return makespan, total


def delivery_makespan_bound(instance: Instance, floor: Floor | None = None) -> float:
    """An admissible makespan bound for A, B and C: the largest, over open order lines, of
    the fewest steps any robot needs to bring a shelf holding the product to the order's
    picking station (reach the shelf, pick it up, carry it there, deliver); ``inf`` when
    some line cannot be served at all, 0 when there is nothing to deliver.

    Every line needs one delivery at least, and the shelf it comes from has to travel
    from where it starts to the station after a robot reached and lifted it (a shelf a
    robot starts with needs no pickup); other robots and shelves are ignored.
    """
    floor = floor or Floor(instance.cells)
    carried = {r.carries: r.at for r in instance.robots.values() if r.carries is not None}
    shelf_cells = {s.id: s.at for s in instance.shelves.values()}
    shelf_cells.update(carried)
    robot_cells = [r.at for r in instance.robots.values()]
    lines = [(order, product) for order in instance.orders.values()
             for product, units in order.lines.items() if units is None or units > 0]
    if not lines:
        return 0.0
    shelves = sorted({shelf for _order, product in lines if product in instance.products
                      for shelf in instance.products[product].stock if shelf in shelf_cells})
    stations = sorted({s.at for s in instance.stations.values()})
    column = {cell: i for i, cell in enumerate(stations)}
    sources = [shelf_cells[s] for s in shelves]
    to_stations = floor.distances(sources, stations)
    to_robots = floor.distances(sources, robot_cells).min(axis=1, initial=INFINITE)
    row = {shelf: i for i, shelf in enumerate(shelves)}
    bound = 0.0
    for order, product in lines:
        station = instance.stations.get(order.station)
        best = INFINITE
        if station is not None and station.at in column and product in instance.products:
            for shelf in instance.products[product].stock:
                if shelf not in row:
                    continue
                fetch = 0.0 if shelf in carried else to_robots[row[shelf]] + 1
                best = min(best, fetch + to_stations[row[shelf], column[station.at]] + 1)
        bound = max(bound, best)
    return float(bound)
