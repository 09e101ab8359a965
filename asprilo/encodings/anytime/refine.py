"""Large-neighbourhood search for M/Md plans with fixed goals (MAPF-LNS, Li et al. 2021,
written here from the paper's description): free a few robots, plan them again one after the
other around all the others with the safe-interval A* of :mod:`.spacetime`, and keep the new
paths when the plan is no worse (makespan first, then sum of costs; no path may end later
than the makespan; a plan as good is kept too, to move on across plateaus).

It starts with a sweep: every robot alone, those that lost most steps first, planned again
around all the others (never worse: its old path is one of those it may take); on a plan of
PIBT steps, where robots were pushed around, that is the fastest gain.  Then it attempts
shorter makespans (:mod:`.deadline`: a deadline for every robot, collisions allowed and then
repaired), a step further down after each success; after an attempt of one step fails, it
tries :data:`REST` neighbourhoods before the next.  On 400 MovingAI agents (random-32-32-20)
the deadlines bring the makespan from LaCAM's 157-235 to about 60 in 9 s of processor time,
and the sum of costs with it (about 21,000), where the neighbourhoods alone stop near 100 and
24,000: they never let a robot finish later than the makespan, and in a crowd the late
robots cannot get through without others giving way first.  Repeated sweeps are left out:
with the deadlines they cost more time than they gain (400 agents: median makespan 68 with
sweeps while they gained 0.3 %, 64 with one).  Which robots a neighbourhood frees together
(weights that grow with their successes):

- ``alone``: a robot drawn by the steps it loses, alone;
- ``late``: a robot that finishes last, the robots that keep it from its goal (and those that
  keep them from theirs), the robots parked in its way, and those that come next to it on
  its way, the latest first; the late robot is planned first;
- ``tail``: a robot that finishes last with those that keep it from its goal and those that
  come next to it, only from a step some way before it finishes (the paths up to there
  stay);
- ``delayed``: a robot that lost many steps against its shortest path (drawn by its loss),
  with the robots in the way of its shortest path;
- ``crossing``: robots that pass one branching vertex of the floor;
- ``random``: robots drawn at random among those that lost steps.
"""

from __future__ import annotations

import random
from collections.abc import Callable

from asprilo.model import Cell

from .deadline import Shortener
from .reservations import Track
from .roadmap import Roadmap
from .spacetime import NEVER, NONE, Occupancy, fastest_path

KINDS = ("alone", "late", "tail", "delayed", "crossing", "random")
#: neighbourhoods tried after an attempt at a shorter makespan failed, before the next one
REST = 200
#: the most robots one neighbourhood frees
GROUP = 8
#: how many steps before the late robot's finish a ``tail`` neighbourhood starts, at most
TAIL = 30


class Refiner:
    """Improves the paths of robots ``0 .. n-1`` towards their ``aims`` one neighbourhood
    at a time; ``paths[r]`` are the vertices of robot ``r`` up to its last move."""

    def __init__(self, roadmap: Roadmap, aims: list[int], paths: list[list[int]], seed: int = 0,
                 group: int = GROUP):
        self.roadmap, self.aims, self.group = roadmap, aims, group
        self.to = roadmap.distances_to(aims)
        self.paths = [list(path) for path in paths]
        self.costs = [len(path) - 1 for path in self.paths]
        self.occupancy = Occupancy(roadmap, max((len(path) for path in self.paths), default=0) + 1)
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
        self.sweep: list[int] = self._sweep_order()
        self.shortener = Shortener(roadmap, aims, self.to, seed)
        self.jump, self.rest = 1, 0  # how far below the makespan the next deadline is; neighbourhoods till then
        self.tried["deadline"] = self.won["deadline"] = 0

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
        """Plan the next robot of a sweep again, or try one neighbourhood; whether the plan
        got better."""
        if self.sweep:
            return self._replan([self.sweep.pop()], stopped)
        if self.rest == 0:
            return self._shorten(stopped)
        self.rest -= 1
        kind = self.random.choices(KINDS, [self.weights[k] for k in KINDS])[0]
        group = self._neighbourhood(kind)
        self.tried[kind] += 1
        begin = 0
        if kind == "tail" and group:
            begin = max(0, self.costs[group[0]] - self.random.randint(TAIL // 2, TAIL))
            group = [robot for robot in group if self.costs[robot] > begin]
        better = len(group) > 0 and self._replan(group, stopped, first=kind in ("late", "tail"), begin=begin)
        self.weights[kind] = min(10.0, self.weights[kind] * 1.3) if better else max(0.1, self.weights[kind] * 0.98)
        self.won[kind] += better
        return better

    def _shorten(self, stopped: Callable[[], bool]) -> bool:
        """Attempt a shorter makespan (:mod:`.deadline`): :attr:`jump` steps shorter, at most
        half the way down to the longest shortest path; after a success the next jump is one
        step longer, after a failure one step (tried after :data:`REST` neighbourhoods when
        this one was one step already)."""
        makespan = max(self.costs, default=0)
        gap = makespan - max(self.shortest, default=0)
        if gap <= 0:
            self.rest = REST
            return False
        jump = max(1, min(self.jump, gap // 2))
        self.tried["deadline"] += 1
        paths = self.shortener.attempt(self.paths, makespan - jump, stopped)
        if paths is None:
            self.jump, self.rest = 1, (REST if jump == 1 else 0)
            return False
        self._install(paths)
        self.won["deadline"] += 1
        self.jump = jump + 1
        return True

    def _install(self, paths: list[list[int]]) -> None:
        """Take ``paths`` as the robots' paths."""
        self.paths, self.costs = paths, [len(path) - 1 for path in paths]
        self.occupancy = Occupancy(self.roadmap, max(self.costs, default=0) + 1)
        for robot, path in enumerate(paths):
            self.occupancy.add(robot, path)

    # --- choosing a neighbourhood ---------------------------------------------------------------

    def _sweep_order(self) -> list[int]:
        """The robots in the order of a sweep, backwards: those that lost most steps last."""
        return sorted(range(len(self.costs)), key=lambda robot: self.costs[robot] - self.shortest[robot])

    def _neighbourhood(self, kind: str) -> list[int]:
        size = self.random.randint(2, self.group)
        if kind == "alone":
            return [self._losing()] if max(self.losses()) > 0 else []
        if kind == "late":
            makespan = max(self.costs)
            robot = self.random.choice([r for r, cost in enumerate(self.costs) if cost == makespan])
            group = self._goal_keepers(robot, size)
            self._add_parkers(group, robot, size)
            self._add_met(group, robot, size)
            return list(group)
        if kind == "tail":
            makespan = max(self.costs)
            robot = self.random.choice([r for r, cost in enumerate(self.costs) if cost == makespan])
            group = self._goal_keepers(robot, size)
            self._add_met(group, robot, size)
            return list(group)
        if kind == "delayed":
            if max(self.losses()) == 0:
                return []
            robot = self._losing()
            group = {robot: None}
            self._add_blockers(group, robot, size)
            return list(group)
        if kind == "crossing":
            return self._passing(self.random.choice(self.crossings), size) if self.crossings else []
        delayed = [r for r, cost in enumerate(self.costs) if cost > self.shortest[r]]
        return self.random.sample(delayed, min(size, len(delayed)))

    def losses(self) -> list[int]:
        """The steps each robot loses against its shortest path."""
        return [cost - shortest for cost, shortest in zip(self.costs, self.shortest, strict=True)]

    def _losing(self) -> int:
        """A robot drawn by the steps it loses (some robot must lose steps)."""
        return self.random.choices(range(len(self.costs)), self.losses())[0]

    def _goal_keepers(self, robot: int, size: int) -> dict[int, None]:
        """``robot``, the robots that keep it from its goal (on the goal after it could be
        there), those that keep them from theirs, and so on, up to ``size`` in all."""
        occupancy = self.occupancy
        who, width = occupancy.who, occupancy.size
        group = {robot: None}
        for waiting in list(group):
            goal = self.aims[waiting]
            for step in occupancy.busy[goal]:
                if step >= self.shortest[waiting] and len(group) < size:
                    group.setdefault(who[step * width + goal])
        return group

    def _add_parkers(self, group: dict[int, None], robot: int, size: int) -> None:
        """Add the robots parked in the way of ``robot``: on the fastest path it would have
        if no robot were parked, from before it would pass; up to ``size`` in all."""
        occupancy = self.occupancy
        parked = occupancy.parked
        occupancy.parked = [NEVER] * occupancy.size
        occupancy.remove(self.paths[robot])
        try:
            free = fastest_path(occupancy, self.paths[robot][0], self.aims[robot], self.to[robot], max(self.costs))
        finally:
            occupancy.parked = parked
            occupancy.add(robot, self.paths[robot])
        for step, vertex in enumerate(free or ()):
            if parked[vertex] <= step and len(group) < size:
                group.setdefault(occupancy.parker[vertex])

    def _add_blockers(self, group: dict[int, None], robot: int, size: int) -> None:
        """Add the robots on a shortest path of ``robot`` (ignoring the others) at the
        steps it would pass there, or parked on it, up to ``size`` in all."""
        occupancy, to, neighbours = self.occupancy, self.to[robot], self.roadmap.neighbours
        who, width, steps, owner = occupancy.who, occupancy.size, occupancy.steps, self.owner
        vertex, step = self.paths[robot][0], 0
        while len(group) < size:
            for near in (step - 1, step, step + 1):
                if 0 <= near < steps and who[near * width + vertex] != NONE and len(group) < size:
                    group.setdefault(who[near * width + vertex])
            parker = owner.get(vertex)
            if parker is not None and occupancy.parked[vertex] <= step + 1 and len(group) < size:
                group.setdefault(parker)
            if to[vertex] == 0:
                break
            vertex = self.random.choice([v for v in neighbours[vertex] if to[v] == to[vertex] - 1])
            step += 1

    def _add_met(self, group: dict[int, None], robot: int, size: int) -> None:
        """Add the robots that come next to ``robot`` on its path, those that finish latest
        first, up to ``size`` in all."""
        occupancy, neighbours, costs = self.occupancy, self.roadmap.neighbours, self.costs
        who, width, steps = occupancy.who, occupancy.size, occupancy.steps
        met: set[int] = set()
        for step, vertex in enumerate(self.paths[robot]):
            for near in (step - 1, step, step + 1):
                if 0 <= near < steps:
                    row = near * width
                    met.update(who[row + cell] for cell in (vertex, *neighbours[vertex]))
        met -= {NONE, *group}
        for other in sorted(met, key=lambda other: (-costs[other], self.random.random()))[:size - len(group)]:
            group[other] = None

    def _passing(self, vertex: int, size: int) -> list[int]:
        """Robots that pass ``vertex`` or a neighbour of it, up to ``size``."""
        occupancy = self.occupancy
        who, width = occupancy.who, occupancy.size
        passing = sorted({who[step * width + cell] for cell in (vertex, *self.roadmap.neighbours[vertex])
                          for step in range(occupancy.steps)} - {NONE})
        return self.random.sample(passing, min(size, len(passing)))

    # --- planning the neighbourhood again -------------------------------------------------------

    def _replan(self, group: list[int], stopped: Callable[[], bool], first: bool = False, begin: int = 0) -> bool:
        """Plan ``group`` again in a random order (``first``: its first robot first); keep
        the paths when the plan got better.
        Unless the makespan may drop (no robot outside the group finishes last), each path
        must leave the group's sum of costs below the old one, counting the shortest paths
        of the robots still to plan: the search for it stops earlier."""
        before = self.score()
        occupancy, paths, costs = self.occupancy, self.paths, self.costs
        old = {robot: paths[robot] for robot in group}
        for robot in group:
            occupancy.remove(paths[robot])
        shorter = costs.count(before[0]) == sum(1 for robot in group if costs[robot] == before[0])
        budget = sum(costs[robot] - self.shortest[robot] for robot in group)  # steps the group may lose
        new: dict[int, list[int]] = {}
        order = group[:first] + self.random.sample(group[first:], len(group) - first)
        for robot in order:
            limit = before[0] if shorter else min(before[0], self.shortest[robot] + budget)
            path = None if stopped() or budget < 0 and not shorter else fastest_path(
                occupancy, old[robot][begin], self.aims[robot], self.to[robot], limit, begin)
            if path is not None:
                path = old[robot][:begin] + path  # (the robot moves after ``begin``: its path is longer)
            if path is None:
                self._put_back(old, new)
                return False
            occupancy.add(robot, path)
            new[robot] = path
            budget -= len(path) - 1 - self.shortest[robot]
        for robot, path in new.items():
            paths[robot], costs[robot] = path, len(path) - 1
        if self.score() <= before:
            return self.score() < before
        self._put_back(old, new)
        return False

    def _put_back(self, old: dict[int, list[int]], new: dict[int, list[int]]) -> None:
        """Take the ``new`` paths out and put the ``old`` ones back."""
        for path in new.values():
            self.occupancy.remove(path)
        for robot, path in old.items():
            self.occupancy.add(robot, path)
            self.paths[robot], self.costs[robot] = path, len(path) - 1
