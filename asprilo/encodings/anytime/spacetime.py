"""Where the robots of an M/Md plan are at every step, and the fastest way for one more
robot through them, for the large-neighbourhood search of :mod:`.refine`.

A path is the list of a robot's vertices (of a :class:`~.roadmap.Roadmap`) after steps 0, 1,
... up to its last move; from then on the robot stays on its last vertex (its goal) for good.
:class:`Occupancy` holds the paths of the robots planned: ``who[t * size + v]`` is the robot
on vertex ``v`` at step ``t`` while it is still on its way, ``busy[v]`` those steps in order,
and ``parked[v]`` the step from which a robot (``parker[v]``) stays on ``v`` for good.

The search is A* over *safe intervals* (SIPP, Phillips and Likhachev 2011, written here from
the paper's idea): the steps a vertex is free fall into runs between the steps a robot is on
it, and a robot that reaches a run may stay until the run ends.  A state is "on vertex ``v``
in its ``k``-th run", reached as early as possible; waiting needs no states of its own.  The
distance to the goal never overshoots, so the first state taken on the goal's last run (no
robot comes there afterwards) is the earliest arrival; no arrival comes before that run
starts either, and among states with the same estimate those nearest to the goal go first.
"""

from __future__ import annotations

import heapq
from bisect import bisect_right, insort

from .roadmap import Roadmap

#: no robot
NONE = -1
#: "never" for a vertex no robot parks on
NEVER = 1 << 30


class Occupancy:
    """The paths of the robots planned so far, indexed by step and vertex."""

    def __init__(self, roadmap: Roadmap, steps: int = 64):
        self.roadmap, self.size = roadmap, roadmap.size
        self.steps = steps  # rows of ``who``: the steps held (grown as paths come)
        self.who = [NONE] * (steps * self.size)
        self.busy: list[list[int]] = [[] for _ in range(self.size)]
        self.parked = [NEVER] * self.size
        self.parker = [NONE] * self.size  # vertex -> the robot parked there

    def add(self, robot: int, path: list[int]) -> None:
        """Put ``robot``'s path in (nobody else is on its vertices then)."""
        if len(path) > self.steps:
            grow = max(len(path), 2 * self.steps) - self.steps
            self.who.extend([NONE] * (grow * self.size))
            self.steps += grow
        size, who, busy = self.size, self.who, self.busy
        for step, vertex in enumerate(path[:-1]):
            who[step * size + vertex] = robot
            insort(busy[vertex], step)
        self.parked[path[-1]], self.parker[path[-1]] = len(path) - 1, robot

    def remove(self, path: list[int]) -> None:
        """Take a path out (one put in with :meth:`add`)."""
        size, who, busy = self.size, self.who, self.busy
        for step, vertex in enumerate(path[:-1]):
            who[step * size + vertex] = NONE
            busy[vertex].remove(step)
        self.parked[path[-1]], self.parker[path[-1]] = NEVER, NONE

    def last_visit(self, vertex: int) -> int:
        """The last step at which a robot on its way is on ``vertex`` (-1: none)."""
        busy = self.busy[vertex]
        return busy[-1] if busy else -1


def fastest_path(occupancy: Occupancy, start: int, goal: int, to_goal: list[int], limit: int, begin: int = 0
                 ) -> list[int] | None:
    """The path from ``start`` at step ``begin`` that parks on ``goal`` earliest among the
    paths through the robots of ``occupancy`` (no vertex shared at a step, no two robots
    swapping vertices, nobody coming onto the goal afterwards), arriving at step ``limit`` at
    the latest, as its vertices from step ``begin`` on; ``None`` when there is none.
    ``to_goal``: the goal's distance table."""
    busy, parked, size = occupancy.busy, occupancy.parked, occupancy.size
    run = bisect_right(busy[start], begin)
    if parked[goal] != NEVER or (run and busy[start][run - 1] == begin) or parked[start] <= begin:
        return None  # somebody else parks on the goal, or stands on the start
    free_from = busy[goal][-1] + 1 if busy[goal] else 0
    if begin + to_goal[start] > limit or free_from > limit:
        return None
    neighbours, arrived = occupancy.roadmap.neighbours, len(busy[goal]) * size + goal  # the goal's last run
    # a state is run * size + vertex: the vertex in its run-th free run (after run busy steps)
    search = _Search(occupancy, to_goal, limit, free_from)
    first = run * size + start
    search.reached[first] = (begin, NONE)
    frontier = search.frontier
    frontier.append((max(begin + to_goal[start], free_from), to_goal[start], begin, first))
    done = set()
    while frontier:
        _, _, arrival, state = heapq.heappop(frontier)
        if state in done:
            continue
        done.add(state)
        if state == arrived:
            return _path(search.reached, state, size)
        vertex, run = state % size, state // size
        taken = busy[vertex]
        leave_by = taken[run] if run < len(taken) else NEVER  # the next busy step: leave before it
        leave_by = min(leave_by, parked[vertex])
        for onto in neighbours[vertex]:
            search.enter(state, arrival, leave_by, onto)
    return None


class _Search:
    """The states reached (state -> arrival step and the state before) and the frontier
    of :func:`fastest_path`."""

    def __init__(self, occupancy: Occupancy, to_goal: list[int], limit: int, free_from: int):
        self.occupancy, self.to_goal, self.limit, self.free_from = occupancy, to_goal, limit, free_from
        self.reached: dict[int, tuple[int, int]] = {}
        self.frontier: list[tuple[int, int, int, int]] = []

    def enter(self, state: int, arrival: int, leave_by: int, onto: int) -> None:
        """The earliest arrival in each free run of ``onto`` from ``state`` (reached at
        step ``arrival``, left at step ``leave_by`` at the latest), each a state to visit."""
        occupancy, to_go = self.occupancy, self.to_goal[onto]
        last = self.limit - to_go  # the latest arrival
        last = leave_by if leave_by < last else last
        parked = occupancy.parked[onto] - 1
        last = parked if parked < last else last
        later = arrival + 1
        times, who, size, free_from = occupancy.busy[onto], occupancy.who, occupancy.size, self.free_from
        index, count, edge = bisect_right(times, arrival), len(times), occupancy.steps * size
        while later <= last:
            while index < count and times[index] == later:  # on a busy step: the next one
                later, index = later + 1, index + 1
            if later > last:
                return
            before = (later - 1) * size + onto  # who is on ``onto`` the step before
            if before < edge and who[before] != NONE and self._swaps(state % size, onto, later):
                later += 1  # the robot there comes over meanwhile: one step later
                continue
            key = index * size + onto
            known = self.reached.get(key)
            if known is None or later < known[0]:
                self.reached[key] = (later, state)
                estimate = later + to_go
                heapq.heappush(self.frontier, (estimate if estimate > free_from else free_from, to_go, later, key))
            if index >= count:
                return
            later, index = times[index] + 1, index + 1  # the next free run of ``onto``

    def _swaps(self, vertex: int, onto: int, later: int) -> bool:
        """Whether the robot on ``onto`` at step ``later - 1`` is on ``vertex`` at ``later``."""
        occupancy = self.occupancy
        size, steps, who = occupancy.size, occupancy.steps, occupancy.who
        other = who[(later - 1) * size + onto] if later <= steps else NONE
        if other == NONE:
            return False
        return ((later < steps and who[later * size + vertex] == other)
                or (occupancy.parked[vertex] == later and occupancy.parker[vertex] == other))


def _path(reached: dict[int, tuple[int, int]], state: int, size: int) -> list[int]:
    """The vertices after each step from the start to ``state``, waiting where a state was
    left later than it was reached."""
    path: list[int] = []
    arrival, before = reached[state]
    while before != NONE:
        previous, earlier = reached[before]
        path.extend([state % size] + [before % size] * (arrival - previous - 1))
        state, arrival, before = before, previous, earlier
    path.append(state % size)
    path.reverse()
    return path
