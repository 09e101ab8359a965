"""What the planners know beyond the instance: goal pairs no plan of a given length uses
(a pruning hint for the M encodings) and the bound of plans that follow a task assignment.

The makespan bound of every plan is :func:`asprilo.bounds.makespan_bound`.
"""

from __future__ import annotations

from itertools import permutations

import clingo

from asprilo.bounds import INFINITE, Floor, goal_cells
from asprilo.model import Cell, Instance


def unusable_goals(instance: Instance, horizon: int, floor: Floor | None = None) -> list[tuple[int, tuple]]:
    """``(robot, goal cell)`` pairs of an M/Md instance that no plan of length ``horizon`` uses.

    When there are as many robots as goals, every robot ends on its own goal, so the
    robots and goals within reach form a bipartite graph that must have a perfect
    matching.  An edge lies on some perfect matching exactly when it is matched or lies
    on an alternating cycle (Dulmage-Mendelsohn); every other pair can be ruled out.
    """
    import numpy as np  # slow to import, as scipy: only where the hints are wanted
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components, maximum_bipartite_matching

    floor = floor or Floor(instance.cells)
    robots = sorted(instance.robots)
    goals = goal_cells(instance)
    if len(robots) != len(goals) or not robots:
        return []
    allowed = floor.distances([instance.robots[r].at for r in robots], goals) <= horizon
    matching = maximum_bipartite_matching(csr_matrix(allowed.astype(np.int8)), perm_type="column")
    if (matching < 0).any():
        return []  # no plan at this horizon at all; the solver finds that out quickly
    n = len(robots)
    # robots 0..n-1, goals n..2n-1; robot -> goal along unmatched edges, goal -> robot along matched
    rows, columns = np.nonzero(allowed)
    unmatched = matching[rows] != columns
    tails = np.concatenate([rows[unmatched], n + matching])
    heads = np.concatenate([n + columns[unmatched], np.arange(n)])
    graph = csr_matrix((np.ones(len(tails)), (tails, heads)), shape=(2 * n, 2 * n))
    _, component = connected_components(graph, directed=True, connection="strong")
    return [(robots[r], goals[g]) for r, g in zip(rows, columns, strict=True)
            if matching[r] != g and component[r] != component[n + g]]


def assignment_bound(instance: Instance, facts: list[str], floor: Floor | None = None) -> float:
    """A makespan no plan that follows these ``assign/2,3`` facts beats.

    M/Md: every assigned robot walks to its goal.  A/B/C: every robot handles its shelves
    one after the other, in the best order: walk to the shelf, pick it up, carry it to each
    of its stations and deliver there, carry it to a free storage cell and put it down
    before the next one.  Shelves without a robot never move, so a carrying robot goes
    around them.  (Robots with more than six shelves count only their first trip.)
    """
    floor = floor or Floor(instance.cells)
    goals: dict[int, Cell] = {}
    tasks: dict[int, dict[int, list[Cell]]] = {}
    for fact in facts:
        kinds = [(term.name, term.arguments[0].number) for term in clingo.parse_term(fact).arguments]
        if len(kinds) == 2:
            (_, robot), (kind, goal) = kinds
            goals[robot] = (instance.shelves if kind == "shelf" else instance.destinations)[goal].at
        else:
            (_, robot), (_, shelf), (_, station) = kinds
            tasks.setdefault(robot, {}).setdefault(shelf, []).append(instance.stations[station].at)
    if goals:
        robots = sorted(goals)
        return float(max(floor.distances([instance.robots[r].at], [goals[r]])[0, 0] for r in robots))
    moving = {shelf for shelves in tasks.values() for shelf in shelves}
    moving |= {robot.carries for robot in instance.robots.values()}
    fixed = {s.at for s in instance.shelves.values() if s.id not in moving}
    chains = _Chains(instance, floor, Floor(instance.cells - fixed), sorted(instance.storage_cells - fixed))
    return float(max((chains.robot(robot, shelves) for robot, shelves in tasks.items()), default=0))


class _Chains:
    """Shortest task chains of single robots: walking on the floor, carrying around fixed shelves."""

    def __init__(self, instance: Instance, floor: Floor, carrying: Floor, drop_cells: list[Cell]):
        self.instance, self.floor, self.carrying, self.drops = instance, floor, carrying, drop_cells

    def robot(self, robot: int, shelves: dict[int, list[Cell]]) -> float:
        start, carried = self.instance.robots[robot].at, self.instance.robots[robot].carries
        cells = {s: start if s == carried else self.instance.shelves[s].at for s in shelves}
        stations = sorted({c for visits in shelves.values() for c in visits})
        carry = self.carrying.distances([*cells.values(), *stations], [*stations, *self.drops])
        walk = self.floor.distances([start, *self.drops], list(cells.values()))
        row = {cell: i for i, cell in enumerate([*cells.values(), *stations])}
        column = {cell: i for i, cell in enumerate([*stations, *self.drops])}
        drops = [column[d] for d in self.drops]

        def trip(shelf: int, walked: float) -> tuple[float, Cell]:
            """Steps of one shelf after ``walked`` steps to reach it: carry it along its stations."""
            best = (INFINITE, cells[shelf])
            for route in permutations(sorted(set(shelves[shelf]))):
                steps, at = walked, cells[shelf]
                for station in route:
                    steps, at = steps + carry[row[at], column[station]] + 1, station
                best = min(best, (steps, at))
            return best

        orders = permutations(sorted(shelves)) if len(shelves) <= 6 else [sorted(shelves)[:1]]
        best = INFINITE
        for order in orders:
            first = order[0]
            fetch = 0 if first == carried else walk[0, list(cells).index(first)] + 1
            total, at = trip(first, fetch)
            for shelf in order[1:]:
                # carry the last shelf to a free storage cell, put it down, walk to the next
                k = list(cells).index(shelf)
                handover = min((carry[row[at], d] + 1 + walk[1 + i, k] + 1 for i, d in enumerate(drops)),
                               default=INFINITE)
                total, at = trip(shelf, total + handover)
            best = min(best, total)
        return best
