"""A fast first plan for M and Md: LaCAM (lazy constraints addition search, Okumura 2023),
written here from the paper's description, over the steps of :mod:`.pibt`.

A plan is a sequence of configurations (where every robot is).  The search goes depth first
from the start configuration; a configuration's successor is one PIBT step of all robots,
so that the first descent is plain PIBT and usually reaches the goals at once.  Where PIBT
goes round in circles (robots taking turns in a dead end), a configuration met before is
taken up again with one more constraint ("robot R goes to cell C next"), tried lazily one at
a time, until a successor not met before comes out: every successor of every configuration
is eventually tried, so the search finds a plan whenever one exists (given the time).  The
plans are long rather than short; the large-neighbourhood search then improves them.
"""

from __future__ import annotations

from array import array
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from asprilo.bounds import Floor
from asprilo.model import Cell

from .pibt import Pibt
from .reservations import Track

#: the most configurations kept, in robot-cells (about 8 bytes each)
MAX_ROBOT_CELLS = 50_000_000


@dataclass
class _Constraint:
    """Robot ``robot`` goes to ``cell`` next, and so do those of the constraints above it."""

    parent: _Constraint | None = None
    robot: int = -1
    cell: Cell | None = None
    depth: int = 0

    def fixed(self) -> dict[int, Cell]:
        result: dict[int, Cell] = {}
        constraint: _Constraint | None = self
        while constraint is not None and constraint.cell is not None:
            result[constraint.robot] = constraint.cell
            constraint = constraint.parent
        return result


@dataclass
class _Node:
    """A configuration met: the cells (in the order of the robots), the one it came from,
    the robots' priorities there and the constraints still to try."""

    cells: tuple[Cell, ...]
    parent: _Node | None
    priority: array
    order: list[int]
    tree: deque = field(default_factory=lambda: deque([_Constraint()]))


def lacam_tracks(floor: Floor, starts: dict[int, Cell], goals: dict[int, Cell], stopped: Callable[[], bool],
                 seed: int = 0) -> dict[int, Track] | None:
    """Tracks that bring every robot of ``starts`` to its cell of ``goals`` (robots without
    a goal come back to their start), all there at the same step; ``None`` when no plan
    exists, when ``stopped``, or when the configurations met fill :data:`MAX_ROBOT_CELLS`."""
    robots = sorted(starts)
    position = {robot: index for index, robot in enumerate(robots)}
    aims = {robot: goals.get(robot, starts[robot]) for robot in robots}
    pibt = Pibt(floor, aims, seed)
    if not pibt.reachable(starts):
        return None
    goal = tuple(aims[robot] for robot in robots)
    ties = array("d", [pibt.shuffle.random() for _ in robots])
    root = _node(pibt, robots, tuple(starts[robot] for robot in robots), None, ties, ties)
    met = {root.cells: root}
    path = [root]
    while path:
        if stopped() or len(met) * len(robots) > MAX_ROBOT_CELLS:
            return None
        node = path[-1]
        if node.cells == goal:
            return _tracks(robots, node)
        if not node.tree:
            path.pop()
            continue
        constraint = node.tree.popleft()
        if constraint.depth < len(robots):
            robot = node.order[constraint.depth]
            options = pibt.moves[node.cells[position[robot]]][:]
            pibt.shuffle.shuffle(options)
            node.tree.extend(_Constraint(constraint, robot, cell, constraint.depth + 1) for cell in options)
        after = pibt.step(dict(zip(robots, node.cells, strict=True)), node.order, constraint.fixed())
        if after is None:
            continue
        cells = tuple(after[robot] for robot in robots)
        known = met.get(cells)
        if known is not None:
            path.append(known)
            continue
        child = _node(pibt, robots, cells, node, node.priority, ties)
        met[cells] = child
        path.append(child)
    return None


def _node(pibt: Pibt, robots: list[int], cells: tuple[Cell, ...], parent: _Node | None, before: array,
          ties: array) -> _Node:
    """A new configuration: a robot's priority grows with every step it is away from its aim
    and drops to its tie-breaker there; the robots pick in falling priority."""
    priority = array("d", (ties[index] if pibt.to_go(robot, cells[index]) == 0 else before[index] + 1
                           for index, robot in enumerate(robots)))
    order = [robots[index] for index in sorted(range(len(robots)), key=lambda index: -priority[index])]
    return _Node(cells, parent, priority, order)


def _tracks(robots: list[int], last: _Node) -> dict[int, Track]:
    """The tracks along the configurations from the start to ``last``."""
    steps: list[tuple[Cell, ...]] = []
    node: _Node | None = last
    while node is not None:
        steps.append(node.cells)
        node = node.parent
    steps.reverse()
    return {robot: Track(robot, _trimmed([cells[index] for cells in steps])) for index, robot in enumerate(robots)}


def _trimmed(cells: list[Cell]) -> list[Cell]:
    """The cells up to the last move (the robot stays there afterwards)."""
    last = len(cells) - 1
    while last > 0 and cells[last] == cells[last - 1]:
        last -= 1
    return cells[:last + 1]
