"""Lower bounds on the makespan and the sum of costs of M/Md plans: robots matched to goal cells.

Every goal cell needs its own robot at the horizon; a robot is no sooner there than its
floor distance says (:class:`~asprilo.bounds.floor.Floor`).  The least possible longest
distance of a matching (:func:`bottleneck_assignment`) bounds the makespan, the least total
(:func:`min_cost_assignment`) the sum of costs.  Whatever the distances ignore (other robots)
only makes them smaller, so both bounds are admissible.  :func:`nearest_goal_bounds`, the
cheap pair that ``check`` shows by default, gives each goal its nearest robot instead of a
robot of its own: weaker where robots would share their nearest goal, but one breadth-first
search in plain Python (no numpy, no matching).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..model import Cell, Instance
from .floor import INFINITE, Floor

if TYPE_CHECKING:
    import numpy as np

#: matchings in Python up to this many goal x robot pairs, SciPy beyond (SciPy is faster
#: on big problems but takes longer to import than a small one needs)
_PYTHON_MATCHING = 2_500
#: goal x robot pairs up to which the bounds come from matchings; beyond (a matrix of 8 MB,
#: a matching that takes cubic time), each goal is bounded by its nearest robot alone: one
#: search from all robots at once, time and memory linear in the floor
MATCHED_PAIRS = 1_000_000
#: cell visits (breadth-first searches in plain Python, one per goal) up to which the bounds
#: need no numpy; beyond, :func:`nearest_goal_bounds` takes the Manhattan distances of robots
#: with a labelled goal (no longer than any path), :func:`mapf_bounds` numpy's search
CHEAP_VISITS = 100_000


def bottleneck_assignment(costs: np.ndarray) -> float:
    """The least ``B`` such that every row gets its own column with cost <= ``B``.

    Rows are goals, columns are robots (at least as many).  ``inf`` if impossible.
    """
    import numpy as np
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
    import numpy as np
    if allowed.size > _PYTHON_MATCHING:
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
    import numpy as np
    goals, robots = costs.shape
    if goals == 0:
        return 0.0
    if robots < goals:
        return INFINITE
    finite = costs[np.isfinite(costs)]
    penalty = (finite.max() if finite.size else 0) * (goals + 1) + 1
    padded = np.where(np.isfinite(costs), costs, penalty)
    if costs.size > _PYTHON_MATCHING:
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
    cells: set[Cell] = set()
    for order in instance.orders.values():
        for product in order.lines:
            stock = instance.products[product].stock if product in instance.products else {}
            cells.update(instance.shelves[shelf].at for shelf in stock if shelf in instance.shelves)
    return sorted(cells)


def mapf_bounds(instance: Instance, floor: Floor | None = None, total: bool = True) -> tuple[float, float]:
    """``(makespan bound, sum-of-costs bound)`` of an M/Md instance by robot-to-goal assignment
    (with ``total=False`` the second is not computed: 0).

    Robots with a labelled goal (``instance.assignment``) count their own distance to it;
    the other robots are matched to the remaining goals.  Small instances (up to
    ``_PYTHON_MATCHING`` pairs, searches within :data:`CHEAP_VISITS`) are matched in plain
    Python, without numpy; the answer is the same.
    """
    floor = floor or Floor(instance.cells)
    assigned = instance.assigned_cells()
    taken = set(assigned.values())
    goals = [cell for cell in goal_cells(instance) if cell not in taken]
    starts = [robot.at for ident, robot in sorted(instance.robots.items()) if ident not in assigned]
    if len(goals) * len(starts) > MATCHED_PAIRS:
        makespan, cost = nearest_robot_bounds(floor, goals, starts)
    elif len(goals) * len(starts) <= _PYTHON_MATCHING and len(goals) * len(floor.cells) <= CHEAP_VISITS:
        rows = [[float(walked.get(start, INFINITE)) for start in starts]
                for walked in (floor.steps_from([goal]) for goal in goals)]
        makespan, cost = _bottleneck(rows, len(starts)), _min_cost(rows, len(starts)) if total else 0.0
    else:
        costs = floor.distances(goals, starts)
        makespan, cost = bottleneck_assignment(costs), min_cost_assignment(costs) if total else 0.0
    if assigned:
        robots = sorted(assigned)
        pairs = [(instance.robots[r].at, assigned[r]) for r in robots]
        own = _own_distances(floor, pairs, exact=True)
        if own is None:
            own = floor.distances([goal for _, goal in pairs], [start for start, _ in pairs]).diagonal().tolist()
        makespan, cost = max(makespan, max(own)), cost + sum(own)
    return makespan, cost


def _bottleneck(rows: list[list[float]], columns: int) -> float:
    """:func:`bottleneck_assignment` of the costs ``rows`` (``columns`` each), in plain Python."""
    if not rows:
        return 0.0
    if columns < len(rows):
        return INFINITE
    thresholds = sorted({cost for row in rows for cost in row if math.isfinite(cost)})

    def fits(threshold: float) -> bool:
        return _augmenting_paths([[j for j, cost in enumerate(row) if cost <= threshold] for row in rows], columns)

    if not thresholds or not fits(thresholds[-1]):
        return INFINITE
    low, high = 0, len(thresholds) - 1
    while low < high:
        middle = (low + high) // 2
        if fits(thresholds[middle]):
            high = middle
        else:
            low = middle + 1
    return float(thresholds[low])


def _min_cost(rows: list[list[float]], columns: int) -> float:
    """:func:`min_cost_assignment` of the costs ``rows`` (``columns`` each), in plain Python."""
    if not rows:
        return 0.0
    if columns < len(rows):
        return INFINITE
    finite = [cost for row in rows for cost in row if math.isfinite(cost)]
    penalty = (max(finite) if finite else 0) * (len(rows) + 1) + 1
    chosen = _hungarian([[cost if math.isfinite(cost) else penalty for cost in row] for row in rows])
    total = [rows[i][j] for i, j in enumerate(chosen)]
    return float(sum(total)) if all(math.isfinite(cost) for cost in total) else INFINITE


def nearest_goal_bounds(instance: Instance, floor: Floor | None = None) -> tuple[float, float]:
    """``(makespan bound, sum-of-costs bound)`` of an M/Md instance in milliseconds, without
    numpy: every goal cell is bounded by the robot nearest to it (:func:`nearest_robot_bounds`,
    one search from all robots without a labelled goal), every robot with a labelled goal by
    its own distance to it.  No more than :func:`mapf_bounds`' pair, which matches robots."""
    floor = floor or Floor(instance.cells)
    assigned = instance.assigned_cells()
    taken = set(assigned.values())
    goals = [cell for cell in goal_cells(instance) if cell not in taken]
    starts = [robot.at for ident, robot in sorted(instance.robots.items()) if ident not in assigned]
    makespan = cost = 0.0
    if goals:
        if len(starts) < len(goals):
            return INFINITE, INFINITE
        nearest = floor.steps_from(starts)
        reach = [float(nearest.get(cell, INFINITE)) for cell in goals]
        makespan, cost = max(reach), sum(reach)
    own = _own_distances(floor, [(instance.robots[r].at, cell) for r, cell in sorted(assigned.items())]) or []
    return max([makespan, *own]), cost + sum(own)


def _own_distances(floor: Floor, pairs: list[tuple[Cell, Cell]], exact: bool = False) -> list[float] | None:
    """The walking distance of each ``(start, goal)`` pair: Manhattan on a floor that fills its
    rectangle, else one search per goal within :data:`CHEAP_VISITS`; beyond, Manhattan, which
    no path undercuts (with ``exact``: ``None``, for the caller to search with numpy).
    ``INFINITE`` where a cell is not a node or no path leads."""
    goals = sorted({goal for _start, goal in pairs})
    searched = {}
    if not floor.manhattan():
        if len(goals) * len(floor.cells) > CHEAP_VISITS:
            if exact:
                return None
        else:
            searched = {goal: floor.steps_from([goal]) for goal in goals}
    distances = []
    for start, goal in pairs:
        if start not in floor.index or goal not in floor.index:
            distances.append(INFINITE)
        elif goal in searched:
            distances.append(float(searched[goal].get(start, INFINITE)))
        else:
            distances.append(float(abs(start[0] - goal[0]) + abs(start[1] - goal[1])))
    return distances


def nearest_robot_bounds(floor: Floor, goals: list[Cell], starts: list[Cell]) -> tuple[float, float]:
    """``(makespan bound, sum-of-costs bound)`` without a matching: every goal needs a robot
    of its own, which is no nearer than the nearest robot; so the largest and the sum of
    these nearest distances are admissible too (weaker than the matchings' when robots
    would have to share their nearest goal)."""
    import numpy as np
    if not goals:
        return 0.0, 0.0
    if len(starts) < len(goals):
        return INFINITE, INFINITE
    nearest = floor.plane_distances(starts)
    inside = [cell for cell in goals if 0 <= cell[0] < nearest.shape[0] and 0 <= cell[1] < nearest.shape[1]]
    if len(inside) < len(goals):
        return INFINITE, INFINITE
    reach = nearest[tuple(np.array(inside).T)]
    return float(reach.max()), float(reach.sum())
