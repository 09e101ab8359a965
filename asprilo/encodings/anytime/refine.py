"""Large-neighbourhood search for M/Md plans with fixed goals (MAPF-LNS, Li et al. 2021,
written here from the paper's description): free a few robots, plan them again one after the
other around all the others with the space-time A* of :mod:`.spacetime`, and keep the new
paths when the plan got better (makespan first, then sum of costs; no path may end later
than the makespan).

Which robots are freed together (weights that grow with their successes):

- ``late``: a robot that finishes last, with the robots in the way of its shortest path;
- ``delayed``: a robot that lost many steps against its shortest path (drawn by its loss),
  with the robots in the way of its shortest path;
- ``crossing``: robots that pass one branching vertex of the floor;
- ``random``: robots drawn at random among those that lost steps.
"""

from __future__ import annotations

import random
from collections.abc import Callable

from asprilo.model import Cell

from .reservations import Track
from .roadmap import Roadmap
from .spacetime import NONE, Occupancy, fastest_path

KINDS = ("late", "delayed", "crossing", "random")
#: the most robots one neighbourhood frees
GROUP = 8


class Refiner:
    """Improves the paths of robots ``0 .. n-1`` towards their ``aims`` one neighbourhood
    at a time; ``paths[r]`` are the vertices of robot ``r`` up to its last move."""

    def __init__(self, roadmap: Roadmap, aims: list[int], paths: list[list[int]], seed: int = 0,
                 group: int = GROUP):
        self.roadmap, self.aims, self.group = roadmap, aims, group
        self.to = roadmap.distances_to(aims)
        self.paths = [list(path) for path in paths]
        self.costs = [len(path) - 1 for path in self.paths]
        self.occupancy = Occupancy(roadmap, max(len(path) for path in self.paths) + 1)
        for robot, path in enumerate(self.paths):
            self.occupancy.add(robot, path)
        self.owner = {aim: robot for robot, aim in enumerate(aims)}  # vertex -> the robot parking there
        self.shortest = [self.to[robot][path[0]] for robot, path in enumerate(self.paths)]
        self.crossings = [v for v in range(roadmap.size) if roadmap.degree(v) >= 3]
        self.robots = list(range(len(aims)))  # the robots' numbers in the instance
        self.random = random.Random(seed)
        self.weights = dict.fromkeys(KINDS, 1.0)
        self.tried = dict.fromkeys(KINDS, 0)
        self.won = dict.fromkeys(KINDS, 0)

    @classmethod
    def of_tracks(cls, roadmap: Roadmap, tracks: dict[int, Track], goals: dict[int, Cell], seed: int = 0
                  ) -> Refiner:
        """A refiner of ``tracks`` (robot -> track, every robot with its cell of ``goals``);
        its robot ``k`` is the ``k``-th robot in the order of their numbers."""
        robots = sorted(tracks)
        paths = [[roadmap.vertex(cell) for cell in tracks[robot].cells[:tracks[robot].finish + 1]] for robot in robots]
        refiner = cls(roadmap, [roadmap.vertex(goals[robot]) for robot in robots], paths, seed)
        refiner.robots = robots
        return refiner

    def tracks(self) -> dict[int, Track]:
        """The paths as tracks of the robots (by their numbers)."""
        cells = self.roadmap.cells
        return {robot: Track(robot, [cells[vertex] for vertex in path])
                for robot, path in zip(self.robots, self.paths, strict=True)}

    def score(self) -> tuple[int, int]:
        """(makespan, sum of costs)."""
        return max(self.costs, default=0), sum(self.costs)

    def step(self, stopped: Callable[[], bool]) -> bool:
        """Try one neighbourhood; whether the plan got better."""
        kind = self.random.choices(KINDS, [self.weights[k] for k in KINDS])[0]
        group = self._neighbourhood(kind)
        self.tried[kind] += 1
        better = len(group) > 0 and self._replan(group, stopped)
        self.weights[kind] = min(10.0, self.weights[kind] * 1.3) if better else max(0.1, self.weights[kind] * 0.98)
        self.won[kind] += better
        return better

    # --- choosing a neighbourhood ---------------------------------------------------------------

    def _neighbourhood(self, kind: str) -> list[int]:
        size = self.random.randint(2, self.group)
        if kind == "late":
            makespan = max(self.costs)
            robot = self.random.choice([r for r, cost in enumerate(self.costs) if cost == makespan])
            return self._with_met(robot, size)
        if kind == "delayed":
            losses = [cost - shortest for cost, shortest in zip(self.costs, self.shortest, strict=True)]
            if not any(losses):
                return []
            robot = self.random.choices(range(len(losses)), losses)[0]
            return self._with_blockers(robot, size)
        if kind == "crossing":
            return self._passing(self.random.choice(self.crossings), size) if self.crossings else []
        delayed = [r for r, cost in enumerate(self.costs) if cost > self.shortest[r]]
        return self.random.sample(delayed, min(size, len(delayed)))

    def _with_blockers(self, robot: int, size: int) -> list[int]:
        """``robot`` and the robots on a shortest path of it (ignoring the others) at the
        steps it would pass there, or parked on it, up to ``size`` in all."""
        occupancy, to, neighbours = self.occupancy, self.to[robot], self.roadmap.neighbours
        who, width, steps, owner = occupancy.who, occupancy.size, occupancy.steps, self.owner
        group = {robot: None}
        vertex, step = self.paths[robot][0], 0
        while len(group) < size:
            for near in (step - 1, step, step + 1):
                if 0 <= near < steps and who[near * width + vertex] != NONE:
                    group.setdefault(who[near * width + vertex])
            parker = owner.get(vertex)
            if parker is not None and occupancy.parked[vertex] <= step + 1:
                group.setdefault(parker)
            if to[vertex] == 0:
                break
            vertex = self.random.choice([v for v in neighbours[vertex] if to[v] == to[vertex] - 1])
            step += 1
        return list(group)[:size]

    def _with_met(self, robot: int, size: int) -> list[int]:
        """``robot`` and the robots that come next to it on its path, those that finish
        latest first (robots going round in circles together), up to ``size`` in all."""
        occupancy, neighbours, costs = self.occupancy, self.roadmap.neighbours, self.costs
        who, width, steps = occupancy.who, occupancy.size, occupancy.steps
        met: set[int] = set()
        for step, vertex in enumerate(self.paths[robot]):
            for near in (step - 1, step, step + 1):
                if 0 <= near < steps:
                    row = near * width
                    met.update(who[row + cell] for cell in (vertex, *neighbours[vertex]))
        met -= {NONE, robot}
        ranked = sorted(met, key=lambda other: (-costs[other], self.random.random()))
        return [robot, *ranked[:size - 1]]

    def _passing(self, vertex: int, size: int) -> list[int]:
        """Robots that pass ``vertex`` or a neighbour of it, up to ``size``."""
        occupancy = self.occupancy
        who, width = occupancy.who, occupancy.size
        passing = {who[step * width + cell] for cell in (vertex, *self.roadmap.neighbours[vertex])
                   for step in range(occupancy.steps)} - {NONE}
        passing = sorted(passing)
        return self.random.sample(passing, min(size, len(passing)))

    # --- planning the neighbourhood again -------------------------------------------------------

    def _replan(self, group: list[int], stopped: Callable[[], bool]) -> bool:
        """Plan ``group`` again in a random order; keep the paths when the plan got better."""
        before = self.score()
        occupancy, paths = self.occupancy, self.paths
        old = {robot: paths[robot] for robot in group}
        for robot in group:
            occupancy.remove(paths[robot])
        order = self.random.sample(group, len(group))
        new: dict[int, list[int]] = {}
        for robot in order:
            path = None if stopped() else fastest_path(occupancy, old[robot][0], self.aims[robot], self.to[robot],
                                                       before[0])
            if path is None:
                for placed in new.values():
                    occupancy.remove(placed)
                for robot_back, path_back in old.items():
                    occupancy.add(robot_back, path_back)
                return False
            occupancy.add(robot, path)
            new[robot] = path
        for robot, path in new.items():
            paths[robot], self.costs[robot] = path, len(path) - 1
        if self.score() < before:
            return True
        for robot in group:
            occupancy.remove(paths[robot])
        for robot, path in old.items():
            occupancy.add(robot, path)
            paths[robot], self.costs[robot] = path, len(path) - 1
        return False
