"""A shorter makespan for an M/Md plan with goals of their own: every robot must be on its
goal for good by a deadline, collisions are allowed for a while and then repaired (after
MAPF-LNS2, Li et al. 2022, written here from the paper's idea, with a deadline added).

The robots that finish after the deadline are planned again first, each along the path that
meets the fewest other robots and still arrives in time (:func:`fewest_collisions`).  Then,
while some robots collide, a colliding robot and a few robots around the places where it meets
others are planned again the same way, one after the other in a random order; their new paths
are kept when they collide no more than the old ones did.  When nobody collides any more, the
plan has the deadline as its makespan at most; when :data:`PATIENCE` groups in a row gain
nothing, the attempt is given up.  Small groups do best: on 400 MovingAI agents
(random-32-32-20, seeds 1-5, 4.5 s of processor time) groups of 3 reached a median makespan
of 68, of 4 70, of 5 80, and groups of 8 stall in the 90s.

:class:`Crowd` counts the robots on each vertex at each step (``on[t, v]``) and those that
move from each vertex to each of its neighbours between two steps (``going[t, k, v]``: from
``v`` to ``Moves.sources[k, v]``) in numpy arrays, so that the search for the path that meets
the fewest robots is one pass over the steps with whole-floor array operations: the fewest
collisions on the way to each vertex at step ``t + 1`` from those at step ``t``, staying or
coming from a neighbour (passing a robot that goes the other way counts as a collision).
"""

from __future__ import annotations

import random
from collections.abc import Callable

import numpy as np

from .roadmap import Roadmap

#: a cost larger than any number of collisions (and far enough below the largest 32-bit number)
UNREACHABLE = 1 << 30
#: the most robots one repair group holds
GROUP = 3
#: groups in a row that gain nothing before an attempt is given up
PATIENCE = 60


class Moves:
    """Where a robot may come onto each vertex from: ``sources[0, v]`` is ``v`` itself (it
    stays), ``sources[k, v]`` for ``k >= 1`` its neighbours (padded with the vertex ``size``,
    which nobody reaches); :meth:`slots` gives the row ``k`` of a neighbour in ``sources``'s
    column of a vertex (``wide``, a row of its own, for staying)."""

    def __init__(self, roadmap: Roadmap):
        size = self.size = roadmap.size
        width = max((roadmap.degree(v) for v in range(size)), default=0)
        self.wide = width + 1
        self.sources = np.full((width + 1, size), size, dtype=np.int64)
        self.sources[0] = np.arange(size)
        for v in range(size):
            for k, u in enumerate(roadmap.neighbours[v], start=1):
                self.sources[k, v] = u
        self.columns: list[list[int]] = [[int(u) for u in column if u < size] for column in self.sources.T]
        #: each vertex's neighbours, and those of the vertex ``size`` (none)
        self.beside = np.vstack([self.sources[1:].T, np.full((1, width), size, dtype=np.int64)])

    def slots(self, neighbour: np.ndarray, vertex: np.ndarray) -> np.ndarray:
        """The row ``k`` of each ``neighbour`` in ``sources``'s column of its ``vertex`` (arrays
        of one shape; ``wide`` where the two are one vertex): looked up among the vertex's few
        neighbours, since a table of every pair of vertices grows with the floor's size squared."""
        row = (self.sources[1:, vertex] == neighbour).argmax(axis=0) + 1
        return np.where(neighbour == vertex, self.wide, row)


class Crowd:
    """The paths of all robots up to step ``horizon`` (each staying on its last vertex), one
    row of ``everyone`` a robot, and the robots on each vertex and each move at each step."""

    def __init__(self, roadmap: Roadmap, moves: Moves, paths: list[list[int]], horizon: int):
        self.roadmap, self.moves, self.horizon = roadmap, moves, horizon
        self.steps = np.arange(horizon + 1)
        self.on = np.zeros((horizon + 1, roadmap.size + 1), dtype=np.int32)
        #: robots going from each vertex to its k-th source between two steps (the last row: staying)
        self.going = np.zeros((horizon, moves.wide + 1, roadmap.size), dtype=np.int32)
        self.everyone = np.empty((len(paths), horizon + 1), dtype=np.int64)
        for robot, path in enumerate(paths):
            self.everyone[robot] = self.full(path)
            self._count(self.everyone[robot], 1)

    def full(self, path: list[int]) -> np.ndarray:
        """A path as one vertex at every step up to the horizon (cut there if longer)."""
        full = np.empty(self.horizon + 1, dtype=np.int64)
        kept = path[:self.horizon + 1]
        full[:len(kept)] = kept
        full[len(kept):] = kept[-1]
        return full

    def _count(self, full: np.ndarray, sign: int) -> None:
        self.on[self.steps, full] += sign
        here, there = full[:-1], full[1:]
        self.going[self.steps[:-1], self.moves.slots(there, here), here] += sign

    def take(self, robot: int) -> None:
        """Take ``robot``'s path out of the counts."""
        self._count(self.everyone[robot], -1)

    def put(self, robot: int, full: np.ndarray) -> None:
        """Put ``full`` in as ``robot``'s path (its old one taken out before)."""
        self.everyone[robot] = full
        self._count(full, 1)

    def _passing(self, paths: np.ndarray) -> np.ndarray:
        """For each path (one a row) and step, how many robots come the other way over the
        edge it takes into that step (0 where it stays)."""
        here, there = paths[..., :-1], paths[..., 1:]
        passing = self.going[self.steps[:-1], self.moves.slots(here, there), there]
        return np.where(here == there, 0, passing)

    def collisions(self, full: np.ndarray) -> int:
        """How many times a path (not counted in) meets a robot counted in: on a vertex at a
        step, or passing it on an edge."""
        return int(self.on[self.steps, full].sum() + self._passing(full).sum())

    def _clashes(self, paths: np.ndarray) -> np.ndarray:
        """For paths counted in (one a row), whether each meets another robot at each step."""
        clashes = self.on[self.steps, paths] > 1
        clashes[:, 1:] |= self._passing(paths) > 0
        return clashes

    def colliding(self) -> list[int]:
        """The robots that collide with some other robot."""
        return np.flatnonzero(self._clashes(self.everyone).any(axis=1)).tolist()

    def around(self, robot: int, reach: int, everywhere: bool = False) -> list[int]:
        """The robots that come within ``reach`` moves of ``robot`` (and ``reach`` steps of
        time) where it meets another robot (``everywhere``: anywhere on its path)."""
        size, mine = self.roadmap.size, self.everyone[robot]
        steps = self.steps if everywhere else np.flatnonzero(self._clashes(mine[None, :])[0])
        if len(steps) == 0:
            return []
        places = mine[steps][:, None]
        for _ in range(reach):
            places = np.concatenate([places, self.moves.beside[places].reshape(len(steps), -1)], axis=1)
        close = np.zeros((self.horizon + 1, size + 1), dtype=bool)
        for shift in range(-reach, reach + 1):
            close[np.clip(steps + shift, 0, self.horizon)[:, None], places] = True
        close[:, size] = False
        found = np.flatnonzero(close[self.steps, self.everyone].any(axis=1)).tolist()
        return [other for other in found if other != robot]


def fewest_collisions(crowd: Crowd, start: int, goal: int, deadline: int, draw: random.Random
                      ) -> tuple[list[int], int] | None:
    """The path from ``start`` (step 0) onto ``goal`` by step ``deadline`` (and staying there)
    that meets the fewest robots of ``crowd``, the earliest arrival among those, as its
    vertices up to its last move, and its collisions; ``None`` when the goal is too far.
    ``draw`` picks among equally good ways.

    The search stops at the first step where no vertex is reached with fewer collisions than
    the best arrival so far: the collisions of a path only grow, so no later arrival is
    better (a robot that can arrive without collisions is done after as many steps)."""
    size, sources, going = crowd.roadmap.size, crowd.moves.sources, crowd.going
    wide, adds = crowd.moves.wide, crowd.on[:, :size]
    staying = crowd.on[:deadline + 1, goal]
    after = (np.cumsum(staying[::-1])[::-1] - staying).tolist()  # robots on the goal after each step
    costs = np.full((deadline + 1, size + 1), UNREACHABLE, dtype=np.int32)  # fewest collisions so far
    costs[0, start] = adds[0, start]
    best, arrival = UNREACHABLE, -1
    for step in range(deadline + 1):
        total = int(costs[step, goal]) + after[step]
        if total < best:
            best, arrival = total, step
        if step == deadline or (best < UNREACHABLE and best <= costs[step].min()):
            break
        came = costs[step][sources]
        came += going[step, :wide]
        row = costs[step + 1, :size]
        np.minimum.reduce(came, axis=0, out=row)
        row += adds[step + 1]
    if best >= UNREACHABLE:
        return None
    return _backwards(adds, going, crowd.moves.columns, costs, goal, arrival, draw), best


def _backwards(adds: np.ndarray, going: np.ndarray, sources: list[list[int]], costs: np.ndarray, goal: int,
               arrival: int, draw: random.Random) -> list[int]:
    """The path that reaches ``goal`` at step ``arrival`` at the cost ``costs`` says, up to
    its last move, found backwards from there (one of the equally good ways at random);
    ``adds``, ``going``: the robots on each vertex and each move at each step."""
    cost, add, move = costs.item, adds.item, going.item
    path, vertex = [goal], goal
    for step in range(arrival, 0, -1):
        before = cost(step, vertex) - add(step, vertex)
        ways = [u for k, u in enumerate(sources[vertex]) if cost(step - 1, u) + move(step - 1, k, vertex) == before]
        vertex = ways[0] if len(ways) == 1 else draw.choice(ways)
        path.append(vertex)
    path.reverse()
    return _trimmed(path)


class Shortener:
    """Attempts to bring a plan (robot -> vertices up to its last move) to a makespan of a
    given deadline; ``to``: the robots' distance tables."""

    def __init__(self, roadmap: Roadmap, aims: list[int], to: list[list[int]], seed: int = 0):
        self.roadmap, self.aims = roadmap, aims
        self.to = to
        self.moves = Moves(roadmap)
        self.random = random.Random(seed)

    def attempt(self, paths: list[list[int]], deadline: int, stopped: Callable[[], bool]) -> list[list[int]] | None:
        """Paths of every robot on its goal by ``deadline`` without collisions, or ``None``."""
        if any(self.to[robot][path[0]] > deadline for robot, path in enumerate(paths)):
            return None
        crowd = Crowd(self.roadmap, self.moves, paths, deadline)
        late = [robot for robot, path in enumerate(paths) if len(path) - 1 > deadline]
        for robot in late:
            crowd.take(robot)
        self.random.shuffle(late)
        for robot in late:
            self._plan(crowd, robot)
        colliding, idle = crowd.colliding(), 0
        while colliding and idle < PATIENCE and not stopped():
            group = self._group(crowd, colliding)
            old = {robot: crowd.everyone[robot].copy() for robot in group}
            before = self._collisions(crowd, group)
            for robot in group:
                self._plan(crowd, robot)
            after = self._collisions(crowd, group)
            for robot in group:
                crowd.put(robot, old[robot] if after > before else crowd.everyone[robot])
            idle = idle + 1 if after >= before else 0
            colliding = crowd.colliding()
        return None if colliding else [_trimmed(full.tolist()) for full in crowd.everyone]

    def _plan(self, crowd: Crowd, robot: int) -> None:
        """Plan ``robot`` (taken out of ``crowd``) again and put it in."""
        found = fewest_collisions(crowd, int(crowd.everyone[robot][0]), self.aims[robot], crowd.horizon, self.random)
        assert found is not None  # (the deadline is no shorter than any robot's way)
        crowd.put(robot, crowd.full(found[0]))

    def _group(self, crowd: Crowd, colliding: list[int]) -> list[int]:
        """A colliding robot, robots around the places where it meets others, and robots
        that come next to its path, in a random order."""
        robot = self.random.choice(colliding)
        group = {robot: None}
        for others in (crowd.around(robot, 2), crowd.around(robot, 1, everywhere=True)):
            self.random.shuffle(others)
            for other in others[:GROUP - len(group)]:
                group[other] = None
        members = list(group)
        self.random.shuffle(members)
        return members

    def _collisions(self, crowd: Crowd, group: list[int]) -> int:
        """The collisions of ``group``'s paths with everyone (those between two of the group
        counted once); the group is left out of ``crowd`` afterwards."""
        for robot in group:
            crowd.take(robot)
        total = 0
        for robot in group:
            total += crowd.collisions(crowd.everyone[robot])
            crowd.put(robot, crowd.everyone[robot])
        for robot in group:
            crowd.take(robot)
        return total


def _trimmed(path: list[int]) -> list[int]:
    """A path without the steps it stays on its last vertex at the end."""
    last = len(path)
    while last > 1 and path[last - 1] == path[last - 2]:
        last -= 1
    return path[:last]
