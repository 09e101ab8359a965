"""Lower bounds on the makespan (and, for M/Md, the sum of costs) of every plan.

:func:`makespan_bound` is the one bound that ``check``, ``solve`` and the benchmark reports
use.  Distances are 4-connected shortest paths over the floor's nodes; whatever they ignore
(other robots, shelves that could move away) only makes them smaller, so every bound here
is admissible: no valid plan does better.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Sequence
from functools import cached_property

import numpy as np

from .domain import Bound, Domain
from .model import DIRECTIONS, Cell, Instance

INFINITE = float("inf")


#: breadth-first searches in Python up to this many source cells x nodes, SciPy beyond
#: (SciPy is faster on big floors but takes longer to import than a small search needs)
_PYTHON_SEARCH = 100_000


class Floor:
    """The floor as a graph: one vertex per node, edges between adjacent nodes."""

    def __init__(self, cells: Iterable[Cell]):
        self.cells: list[Cell] = sorted(set(cells))
        self.index = {cell: i for i, cell in enumerate(self.cells)}

    @cached_property
    def graph(self):
        """The adjacency matrix (scipy.sparse)."""
        from scipy.sparse import csr_matrix
        rows, columns = [], []
        for (x, y), i in self.index.items():
            for dx, dy in DIRECTIONS:
                j = self.index.get((x + dx, y + dy))
                if j is not None:
                    rows.append(i)
                    columns.append(j)
        size = len(self.cells)
        return csr_matrix((np.ones(len(rows)), (rows, columns)), shape=(size, size))

    def distances(self, sources: Sequence[Cell], targets: Sequence[Cell]) -> np.ndarray:
        """``len(sources) x len(targets)`` shortest-path lengths (``inf``: unreachable).

        A cell that is not a node is unreachable from and to everything.
        """
        result = np.full((len(sources), len(targets)), INFINITE)
        known = [k for k, cell in enumerate(sources) if cell in self.index]
        if not known or not targets:
            return result
        columns = [self.index.get(cell, -1) for cell in targets]
        rows = self._from_cells([self.index[sources[k]] for k in known])
        for k, row in zip(known, rows, strict=True):
            result[k] = [row[c] if c >= 0 else INFINITE for c in columns]
        return result

    def _from_cells(self, starts: list[int]) -> np.ndarray:
        """Distances from each start vertex to every vertex."""
        if len(starts) * len(self.cells) > _PYTHON_SEARCH:
            from scipy.sparse.csgraph import shortest_path
            return np.atleast_2d(shortest_path(self.graph, method="D", unweighted=True, indices=starts))
        rows = np.full((len(starts), len(self.cells)), INFINITE)
        for row, start in zip(rows, starts, strict=True):
            row[start] = 0
            queue = deque([start])
            while queue:
                vertex = queue.popleft()
                x, y = self.cells[vertex]
                for dx, dy in DIRECTIONS:
                    neighbour = self.index.get((x + dx, y + dy))
                    if neighbour is not None and row[neighbour] == INFINITE:
                        row[neighbour] = row[vertex] + 1
                        queue.append(neighbour)
        return rows


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
    if allowed.size > _PYTHON_SEARCH // 40:
        from scipy.optimize import linear_sum_assignment  # slow to import: only for big problems
        rows, columns = linear_sum_assignment(~allowed)
        return bool(allowed[rows, columns].all())
    return _augmenting_paths([list(np.flatnonzero(row)) for row in allowed], allowed.shape[1])


def _augmenting_paths(choices: list[list[int]], columns: int) -> bool:
    """Whether every row gets its own column among its ``choices`` (Kuhn's augmenting paths)."""
    owner = [-1] * columns

    def place(row: int, seen: set[int]) -> bool:
        for column in choices[row]:
            if column not in seen:
                seen.add(column)
                if owner[column] < 0 or place(owner[column], seen):
                    owner[column] = row
                    return True
        return False

    return all(place(row, set()) for row in range(len(choices)))


def min_cost_assignment(costs: np.ndarray) -> float:
    """The least total cost of giving every row (goal) its own column (robot); ``inf`` if none."""
    goals, robots = costs.shape
    if goals == 0:
        return 0.0
    if robots < goals:
        return INFINITE
    finite = costs[np.isfinite(costs)]
    penalty = (finite.max() if finite.size else 0) * (goals + 1) + 1
    padded = np.where(np.isfinite(costs), costs, penalty)
    if costs.size > _PYTHON_SEARCH // 40:
        from scipy.optimize import linear_sum_assignment  # slow to import: only for big problems
        rows, columns = linear_sum_assignment(padded)
    else:
        rows, columns = np.arange(goals), np.array(_hungarian(padded.tolist()))
    total = costs[rows, columns]
    return float(total.sum()) if np.isfinite(total).all() else INFINITE


def _hungarian(costs: list[list[float]]) -> list[int]:
    """The column of each row in an assignment of least total cost (rows <= columns): the
    Hungarian method with row and column potentials, one shortest augmenting path per row."""
    rows, columns = len(costs), len(costs[0])
    potentials = ([0.0] * (rows + 1), [0.0] * (columns + 1))  # of rows, of columns
    owner = [0] * (columns + 1)  # owner[j]: the row (1-based) that column j serves; 0: none
    for row in range(1, rows + 1):
        owner[0] = row
        previous, column = _augmenting_path(costs, potentials, owner)
        while column:  # walk the path back, shifting each column to the row before it
            owner[column] = owner[previous[column]]
            column = previous[column]
    assigned = [0] * rows
    for j in range(1, columns + 1):
        if owner[j]:
            assigned[owner[j] - 1] = j - 1
    return assigned


def _augmenting_path(costs, potentials, owner) -> tuple[list[int], int]:
    """Grow a shortest alternating path from the row in ``owner[0]`` to a free column, shifting
    the potentials; returns each column's predecessor on the path and the free column."""
    row_potential, column_potential = potentials
    columns = len(owner) - 1
    slack, previous, used = [INFINITE] * (columns + 1), [0] * (columns + 1), [False] * (columns + 1)
    column = 0
    while owner[column]:
        used[column] = True
        current, delta, nearest = owner[column], INFINITE, 0
        for j in range(1, columns + 1):
            if used[j]:
                continue
            reduced = costs[current - 1][j - 1] - row_potential[current] - column_potential[j]
            if reduced < slack[j]:
                slack[j], previous[j] = reduced, column
            if slack[j] < delta:
                delta, nearest = slack[j], j
        for j in range(columns + 1):
            if used[j]:
                row_potential[owner[j]] += delta
                column_potential[j] -= delta
            else:
                slack[j] -= delta
        column = nearest
    return previous, column


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


def mapf_bounds(instance: Instance, floor: Floor | None = None, total: bool = True) -> tuple[float, float]:
    """``(makespan bound, sum-of-costs bound)`` of an M/Md instance by robot-to-goal assignment
    (with ``total=False`` the second is not computed: 0).

    Robots with a labelled goal (``instance.assignment``) count their own distance to it;
    the other robots are matched to the remaining goals.
    """
    floor = floor or Floor(instance.cells)
    assigned = instance.assigned_cells()
    taken = set(assigned.values())
    goals = [cell for cell in goal_cells(instance) if cell not in taken]
    starts = [robot.at for ident, robot in sorted(instance.robots.items()) if ident not in assigned]
    costs = floor.distances(goals, starts)
    makespan, cost = bottleneck_assignment(costs), min_cost_assignment(costs) if total else 0.0
    if assigned:
        robots = sorted(assigned)
        own = floor.distances([assigned[r] for r in robots], [instance.robots[r].at for r in robots]).diagonal()
        makespan, cost = max(makespan, float(own.max())), cost + float(own.sum())
    return makespan, cost


def makespan_bound(instance: Instance, domain: Domain, floor: Floor | None = None) -> float:
    """A makespan no valid plan of ``domain`` beats (``inf``: no plan exists at all).

    M/Md: the bottleneck assignment of robots to goal cells.  A/B/C: the delivery bounds
    of :mod:`asprilo.delivery_bound` (order lines released no earlier than a robot can bring
    a shelf, stations serving one robot at a time, robots one line at a time).
    """
    floor = floor or Floor(instance.cells)
    if domain.bound is Bound.MAPF:
        return mapf_bounds(instance, floor, total=False)[0]
    from .delivery_bound import delivery_bound
    return delivery_bound(instance, domain, floor)
