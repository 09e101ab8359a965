"""A fast first plan for M and Md: LaCAM (lazy constraints addition search, Okumura 2023),
written here from the paper's description, over the steps of :mod:`.pibt`.

A plan is a sequence of configurations (the vertex of every robot, a tuple).  The search
goes depth first from the start configuration; a configuration's successor is one PIBT step
of all robots, so that the first descent is plain PIBT and usually reaches the goals at
once.  Where PIBT goes round in circles (robots taking turns in a dead end), a configuration
met before is taken up again with one more constraint ("robot R goes to vertex V next"),
tried lazily one at a time, until a successor not met before comes out: every successor of
every configuration is eventually tried, so the search finds a plan whenever one exists
(given the time).  The plans are long rather than short; :mod:`.refine` then shortens them.

A robot's priority grows by one with every step it is away from its goal and falls back to
its fraction there (PIBT's dynamic priorities); the fraction, which breaks ties, is larger
for robots that start farther from their goals.
"""

from __future__ import annotations

import math
import random
from collections import deque
from collections.abc import Callable

from asprilo.bounds import Floor
from asprilo.model import Cell

from .pibt import Pibt
from .reservations import Track
from .roadmap import Roadmap

#: the most configurations kept, in robot-vertices (about 8 bytes each)
MAX_ROBOT_CELLS = 50_000_000

#: a constraint: (the constraint above it, robot, vertex, depth); depth 0 is the empty one
Constraint = tuple


class _Node:
    """A configuration met: the vertices (in the order of the robots), the node it came
    from, the robots' priorities there, their order, and the constraints still to try."""

    __slots__ = ("config", "parent", "priority", "order", "tree")

    def __init__(self, config: tuple[int, ...], parent: _Node | None, priority: list[float]):
        self.config, self.parent, self.priority = config, parent, priority
        self.order = sorted(range(len(config)), key=priority.__getitem__, reverse=True)
        self.tree: deque[Constraint] = deque([(None, -1, -1, 0)])


def lacam_tracks(floor: Floor, starts: dict[int, Cell], goals: dict[int, Cell], stopped: Callable[[], bool],
                 seed: int = 0, roadmap: Roadmap | None = None) -> dict[int, Track] | None:
    """Tracks that bring every robot of ``starts`` to its cell of ``goals`` (robots without
    a goal come back to their start), all there at the same step; ``None`` when no plan
    exists, when ``stopped``, or when the configurations met fill :data:`MAX_ROBOT_CELLS`."""
    roadmap = roadmap or Roadmap(floor)
    robots = sorted(starts)
    if any(cell not in roadmap.index for robot in robots for cell in (starts[robot], goals.get(robot, starts[robot]))):
        return None
    begin = [roadmap.vertex(starts[robot]) for robot in robots]
    aims = [roadmap.vertex(goals.get(robot, starts[robot])) for robot in robots]
    configs = lacam_configs(roadmap, begin, aims, stopped, seed)
    if configs is None:
        return None
    return {robot: Track(robot, [roadmap.cells[vertex] for vertex in path])
            for robot, path in zip(robots, paths_of(configs), strict=True)}


def lacam_configs(roadmap: Roadmap, starts: list[int], aims: list[int], stopped: Callable[[], bool],
                  seed: int = 0) -> list[tuple[int, ...]] | None:
    """The configurations from ``starts`` to ``aims`` (robot number -> vertex), one a step;
    ``None`` as :func:`lacam_tracks` says."""
    pibt = Pibt(roadmap, aims, seed)
    if not pibt.reachable(starts):
        return None
    count = len(starts)
    shuffle = random.Random(seed).shuffle
    goal = tuple(aims)
    away = [pibt.to[robot][start] for robot, start in enumerate(starts)]
    root = _Node(tuple(starts), None, [distance / (max(away, default=0) + 1) for distance in away])
    met = {root.config: root}
    stack = [root]
    checked = 0
    while stack:
        checked += 1
        if (checked & 15 == 0 and stopped()) or len(met) * count > MAX_ROBOT_CELLS:
            return None
        node = stack[-1]
        if node.config == goal:
            return _configs(node)
        if not node.tree:
            stack.pop()
            continue
        constraint = node.tree.popleft()
        depth = constraint[3]
        if depth < count:
            robot = node.order[depth]
            here = node.config[robot]
            options = [here, *roadmap.neighbours[here]]
            shuffle(options)
            node.tree.extend((constraint, robot, vertex, depth + 1) for vertex in options)
        after = pibt.step(list(node.config), node.order, _fixed(constraint))
        if after is None:
            continue
        config = tuple(after)
        known = met.get(config)
        if known is not None:
            stack.append(known)
            continue
        child = _Node(config, node, _priorities(node.priority, config, aims))
        met[config] = child
        stack.append(child)
    return None


def _fixed(constraint: Constraint) -> list[tuple[int, int]]:
    """The (robot, vertex) moves of a constraint and those above it."""
    fixed = []
    while constraint[3] > 0:
        fixed.append((constraint[1], constraint[2]))
        constraint = constraint[0]
    return fixed


def _priorities(before: list[float], config: tuple[int, ...], aims: list[int]) -> list[float]:
    """A robot's priority one step on: one more away from its aim, its fraction there."""
    return [priority + 1 if vertex != aim else priority - math.floor(priority)
            for priority, vertex, aim in zip(before, config, aims, strict=True)]


def _configs(last: _Node) -> list[tuple[int, ...]]:
    """The configurations along the search tree from the start to ``last``."""
    steps: list[tuple[int, ...]] = []
    node: _Node | None = last
    while node is not None:
        steps.append(node.config)
        node = node.parent
    steps.reverse()
    return steps


def paths_of(configs: list[tuple[int, ...]]) -> list[list[int]]:
    """Each robot's vertices along the configurations, up to its last move (it stays there
    afterwards)."""
    paths = [list(path) for path in zip(*configs, strict=True)]
    for path in paths:
        last = len(path) - 1
        while last > 0 and path[last] == path[last - 1]:
            last -= 1
        del path[last + 1:]
    return paths
