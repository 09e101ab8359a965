"""The exact solver for domains M and Md: anonymous MAPF as maximum flow over time.

Yu & LaValle (2012): robots that are not tied to particular goals can be routed as units of
flow through the *time-expanded graph* — one copy of the floor per time step 0..H.  Every
cell copy is split into an ``in`` and an ``out`` node joined by an arc of capacity 1 (at most
one robot per cell and step); ``out`` of a cell at step t leads to ``in`` of the same cell at
t+1 (waiting) and, through an *edge gadget*, to ``in`` of each neighbour.  The gadget of an
edge {u, v} is a pair of nodes a -> b joined by one arc of capacity 1 that both u and v feed
and that leads to both u and v: two robots can never cross the same edge in one step, so
swaps are impossible.  A flow of value "number of robots" from the start cells at step 0 to
the goal cells at step H is a collision-free plan of makespan at most H; maximum flow is
polynomial, and trying H upwards from a lower bound gives the proven minimal makespan.

Goals are the cells of M's ordered shelves or Md's destinations
(:func:`asprilo.bounds.goal_cells`).  When there are more robots than goals, the extra
robots may end anywhere: they drain through an ``idle`` node whose capacity is the surplus,
which forces every goal cell to be covered.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from asprilo.bounds import Floor, goal_cells, mapf_bounds
from asprilo.model import Action, Cell, Instance, Plan

from .solving.status import Attempt, SolveStatus
from .solving.watch import Watch


@dataclass
class FlowAttempt(Attempt):
    """One horizon tried (``sat``: all robots reached the goals) and the size of its network."""

    nodes: int = 0
    arcs: int = 0

    @property
    def feasible(self) -> bool:
        return self.result == "sat"


@dataclass
class FlowSearch:
    """The result of :func:`flow_plan`: the plan (or ``None``), every horizon tried, and the
    status: ``found``, ``none`` (no plan at the horizon asked for, or at any horizon),
    ``limit`` (time ran out) or ``cancelled``."""

    plan: Plan | None
    horizon: int | None
    minimal: bool
    lower_bound: float
    attempts: list[FlowAttempt] = field(default_factory=list)
    status: SolveStatus = SolveStatus.NONE


#: networks up to this many nodes x robots get their maximum flow from the plain-Python
#: search below (no numpy, no scipy: importing scipy takes longer than the whole flow of a
#: small instance); larger ones from scipy's
PYTHON_FLOW = 200_000


class TimeExpandedNetwork:
    """The flow network of a floor, start cells and goal cells over ``horizon`` steps: arc
    ``k`` goes from ``tails[k]`` to ``heads[k]`` with capacity ``capacities[k]``."""

    def __init__(self, floor: Floor, starts: list[Cell], goals: list[Cell], horizon: int):
        self.floor, self.starts, self.goals, self.horizon = floor, starts, goals, horizon
        index = floor.index
        cells = len(floor.cells)
        pairs = ((index[(x, y)], index[(x + dx, y + dy)]) for x, y in floor.cells
                 for dx, dy in ((1, 0), (0, 1)) if (x + dx, y + dy) in index)
        edges = sorted((min(pair), max(pair)) for pair in pairs)
        self.layer = 2 * cells + 2 * len(edges)  # in-nodes, out-nodes, gadget a, gadget b
        self.source = (horizon + 1) * self.layer
        self.sink, self.idle = self.source + 1, self.source + 2
        self.size = self.source + 3
        tails: list[int] = []
        heads: list[int] = []
        for step in range(horizon + 1):
            now = step * self.layer
            tails += range(now + self.inlet(0), now + self.inlet(cells))  # one robot per cell and step
            heads += range(now + self.outlet(0), now + self.outlet(cells))
            if step == horizon:
                break
            after = now + self.layer
            tails += range(now + self.outlet(0), now + self.outlet(cells))  # wait
            heads += range(after + self.inlet(0), after + self.inlet(cells))
            for number, (u, v) in enumerate(edges):
                a, b = now + 2 * cells + number, now + 2 * cells + len(edges) + number
                # the edge carries one robot per step, in either direction
                tails += (now + self.outlet(u), now + self.outlet(v), a, b, b)
                heads += (a, a, b, after + self.inlet(u), after + self.inlet(v))
        tails += [self.source] * len(starts)
        heads += [self.inlet(index[cell]) for cell in starts]
        last = horizon * self.layer
        goal_set = sorted({index[cell] for cell in goals})
        tails += [last + self.outlet(g) for g in goal_set]
        heads += [self.sink] * len(goal_set)
        capacities = [1] * len(tails)
        surplus = len(starts) - len(goal_set)
        if surplus > 0:
            ending = set(goal_set)
            others = [v for v in range(cells) if v not in ending]
            tails += [last + self.outlet(v) for v in others] + [self.idle]
            heads += [self.idle] * len(others) + [self.sink]
            capacities += [1] * len(others) + [surplus]
        self.tails, self.heads, self.capacities = tails, heads, capacities
        self.arcs = len(tails)

    def inlet(self, vertex: int) -> int:
        """The node where robots enter a cell (in layer 0; add ``t * layer`` for step t)."""
        return vertex

    def outlet(self, vertex: int) -> int:
        """The node where robots leave a cell."""
        return vertex + len(self.floor.cells)

    def route(self) -> dict[int, list[Cell]] | None:
        """Each start's cells at steps 0..H, or ``None`` when not every robot gets through."""
        small = self.size * len(self.starts) <= PYTHON_FLOW
        successor = self._python_flow() if small else self._scipy_flow()
        if successor is None:
            return None
        cells = len(self.floor.cells)
        paths = {}
        for number, start in enumerate(self.starts):
            node, path = self.inlet(self.floor.index[start]), []
            while node not in (self.sink, self.idle):
                local = node % self.layer
                if local < cells:  # an in-node: the robot stands on this cell at this step
                    path.append(self.floor.cells[local])
                node = successor[node]
            paths[number] = path
        return paths

    def _scipy_flow(self) -> dict[int, int] | None:
        """Node -> the node its unit of flow goes on to (scipy's maximum flow), or ``None``
        when the flow is smaller than the robots."""
        import numpy as np
        from scipy.sparse import csr_matrix
        from scipy.sparse.csgraph import maximum_flow
        graph = csr_matrix((np.array(self.capacities, dtype=np.int32),
                            (np.array(self.tails, dtype=np.int64), np.array(self.heads, dtype=np.int64))),
                           shape=(self.size, self.size))
        result = maximum_flow(graph, self.source, self.sink)
        if result.flow_value < len(self.starts):
            return None
        flow = result.flow.tocsr()
        flow.eliminate_zeros()
        rows = np.repeat(np.arange(self.size), np.diff(flow.indptr))
        return {int(t): int(h) for t, h, amount in zip(rows, flow.indices, flow.data, strict=True)
                if amount > 0 and t not in (self.source, self.idle)}

    def _python_flow(self) -> dict[int, int] | None:
        """The same from augmenting paths found breadth-first (Edmonds and Karp), one robot's
        unit at a time: arc ``2k`` of the residual network is arc ``k``, ``2k + 1`` its reverse."""
        heads: list[int] = []
        room: list[int] = []
        leaving: list[list[int]] = [[] for _ in range(self.size)]
        for tail, head, capacity in zip(self.tails, self.heads, self.capacities, strict=True):
            leaving[tail].append(len(heads))
            heads.append(head)
            room.append(capacity)
            leaving[head].append(len(heads))
            heads.append(tail)
            room.append(0)
        for _robot in self.starts:
            reached = {self.source: -1}
            frontier = [self.source]
            while frontier and self.sink not in reached:
                following = []
                for node in frontier:
                    for arc in leaving[node]:
                        if room[arc] and heads[arc] not in reached:
                            reached[heads[arc]] = arc
                            following.append(heads[arc])
                frontier = following
            if self.sink not in reached:
                return None
            node = self.sink
            while node != self.source:
                arc = reached[node]
                room[arc] -= 1
                room[arc ^ 1] += 1
                node = heads[arc ^ 1]
        return {tail: head for number, (tail, head) in enumerate(zip(self.tails, self.heads, strict=True))
                if room[2 * number + 1] > 0 and tail not in (self.source, self.idle)}


def plan_of_paths(robots: list[int], paths: dict[int, list[Cell]]) -> Plan:
    """The move actions that take each robot along its path (standing still = no action)."""
    actions = []
    for number, path in paths.items():
        for step in range(1, len(path)):
            (x0, y0), (x1, y1) = path[step - 1], path[step]
            if (x0, y0) != (x1, y1):
                actions.append(Action(step, robots[number], "move", (x1 - x0, y1 - y0)))
    return Plan(actions)


def flow_plan(instance: Instance, horizon: int | None = None, watch: Watch | None = None,
              on_attempt: Callable[[FlowAttempt], None] | None = None, bound: float | None = None) -> FlowSearch:
    """A plan of minimal makespan for an M/Md instance (or the plan for a fixed ``horizon``).

    Without ``horizon`` the search starts at the bottleneck-assignment lower bound (``bound``,
    when the caller has it) and goes up one step at a time; the first feasible horizon is the
    minimal makespan.  ``watch`` bounds its time and may cancel it; ``on_attempt`` hears of
    every horizon tried.
    """
    floor = Floor(instance.cells)
    robots = sorted(instance.robots)
    starts = [instance.robots[r].at for r in robots]
    goals = goal_cells(instance)
    if bound is None:
        bound = mapf_bounds(instance, floor, total=False)[0]
    search = FlowSearch(None, None, False, bound)
    if any(cell not in floor.index for cell in starts + goals) or not math.isfinite(bound):
        search.minimal = True  # some goal can be reached by no robot: no plan at any horizon
        return search
    first = last = horizon
    if horizon is None:
        first, last = int(bound), int(bound) + len(robots) + len(floor.cells)
    watch = watch or Watch()
    for current in range(first, last + 1):
        if watch.cancelled or watch.expired:
            search.status = _stopped(watch)
            break
        attempt, paths = _try(floor, starts, goals, current)
        search.attempts.append(attempt)
        if on_attempt is not None:
            on_attempt(attempt)
        if paths is not None:
            search.plan, search.horizon, search.status = plan_of_paths(robots, paths), current, SolveStatus.FOUND
            search.minimal = horizon is None or current <= bound
            break
    return search


def _stopped(watch: Watch) -> SolveStatus:
    return SolveStatus.CANCELLED if watch.cancelled else SolveStatus.LIMIT


def _try(floor: Floor, starts: list[Cell], goals: list[Cell], horizon: int
         ) -> tuple[FlowAttempt, dict[int, list[Cell]] | None]:
    """One horizon: the attempt, and each robot's path when all of them get through."""
    tried = time.perf_counter()
    network = TimeExpandedNetwork(floor, starts, goals, horizon)
    paths = network.route()
    attempt = FlowAttempt(horizon, "sat" if paths is not None else "unsat", time.perf_counter() - tried,
                          nodes=network.size, arcs=network.arcs)
    return attempt, paths
