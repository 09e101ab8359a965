"""Lower bounds on the makespan (and, for M/Md, the sum of costs) of every plan.

:func:`makespan_bound` is the one bound that ``check``, ``solve`` and the benchmark reports
use.  Distances are 4-connected shortest paths over the floor's nodes; whatever they ignore
(other robots, shelves that could move away) only makes them smaller, so every bound here
is admissible: no valid plan does better.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import shortest_path

from .domain import Domain
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
        for k, row in zip(known, np.atleast_2d(rows), strict=True):
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


def makespan_bound(instance: Instance, domain: Domain, floor: Floor | None = None) -> float:
    """A makespan no valid plan of ``domain`` beats (``inf``: no plan exists at all).

    M/Md: the bottleneck assignment of robots to goal cells.  A/B/C: the delivery bounds
    of :mod:`asprilo.delivery_bound` (order lines released no earlier than a robot can bring
    a shelf, stations serving one robot at a time, robots one line at a time).
    """
    floor = floor or Floor(instance.cells)
    if not domain.delivers:
        return mapf_bounds(instance, floor)[0]
    from .delivery_bound import delivery_bound
    return delivery_bound(instance, domain, floor)
