"""A fast first plan for M and Md on crowded floors: priority inheritance with backtracking
(PIBT, Okumura et al., 2019), written here from the paper's description.

Step by step, every robot picks its next cell, nearest to its goal first; a robot that wants
a cell where another robot stands pushes that robot (which then picks first, and may not
come to the pusher's cell: no swaps); a robot that finds no cell stays.  Priorities grow
with every step a robot is away from its goal and drop once it is there, so that robots
far behind get their way.  It plans all robots together in time linear in robots x steps,
where prioritized planning (:mod:`.prioritized`) can get stuck on a floor half full; the
large-neighbourhood search then improves the plan as any other.
"""

from __future__ import annotations

import random
from collections.abc import Callable

from asprilo.bounds import INFINITE, Floor
from asprilo.model import DIRECTIONS, Cell

from .reservations import Track

#: the most steps tried, as a multiple of the longest shortest way (plus the robots)
STEP_FACTOR = 4


def pibt_tracks(floor: Floor, starts: dict[int, Cell], goals: dict[int, Cell], stopped: Callable[[], bool],
                seed: int = 0) -> dict[int, Track] | None:
    """Tracks that bring every robot of ``starts`` to its cell of ``goals`` (robots without
    a goal come back to their start), all there at the same step; ``None`` when that does
    not happen within the step limit, or when ``stopped``."""
    aims = {robot: goals.get(robot, start) for robot, start in starts.items()}
    distance = _distances(floor, set(aims.values()))
    if any(distance[aim].get(start, INFINITE) >= INFINITE for aim, start in
           ((aims[r], starts[r]) for r in starts)):
        return None
    shuffle = random.Random(seed)
    tie = {robot: shuffle.random() for robot in starts}
    longest = max((distance[aims[r]][starts[r]] for r in starts), default=0)
    at, history = dict(starts), {robot: [start] for robot, start in starts.items()}
    priority = {robot: tie[robot] for robot in starts}
    for _step in range(STEP_FACTOR * (longest + len(starts)) + 1):
        if all(at[r] == aims[r] for r in at):
            return {robot: Track(robot, _trimmed(cells)) for robot, cells in history.items()}
        if stopped():
            return None
        for robot in at:
            priority[robot] = tie[robot] if at[robot] == aims[robot] else priority[robot] + 1
        at = _step_all(at, aims, distance, priority, shuffle)
        for robot, cell in at.items():
            history[robot].append(cell)
    return None


def _distances(floor: Floor, aims: set[Cell]) -> dict[Cell, dict[Cell, int]]:
    """Aim -> cell -> steps between them."""
    return {aim: floor.steps_from([aim]) for aim in aims}


def _step_all(at: dict[int, Cell], aims: dict[int, Cell], distance: dict[Cell, dict[Cell, int]],
              priority: dict[int, float], shuffle: random.Random) -> dict[int, Cell]:
    """Where every robot is after one more step."""
    standing = {cell: robot for robot, cell in at.items()}
    after: dict[int, Cell] = {}
    taken: dict[Cell, int] = {}

    def pick(robot: int, pusher: int | None) -> bool:
        """Choose ``robot``'s next cell (pushing the robot there); whether it moves as it wished."""
        x, y = at[robot]
        to_aim = distance[aims[robot]]
        options = [(x + dx, y + dy) for dx, dy in DIRECTIONS if (x + dx, y + dy) in to_aim] + [(x, y)]
        shuffle.shuffle(options)
        options.sort(key=lambda cell: to_aim[cell])
        for cell in options:
            if cell in taken or (pusher is not None and cell == at[pusher]):
                continue
            after[robot], taken[cell] = cell, robot
            other = standing.get(cell)
            if other is not None and other != robot and other not in after and not pick(other, robot):
                continue  # the robot there could not get out of the way: it took this cell itself
            return True
        after[robot] = at[robot]
        taken[at[robot]] = robot
        return False

    for robot in sorted(at, key=lambda r: -priority[r]):
        if robot not in after:
            pick(robot, None)
    return after


def _trimmed(cells: list[Cell]) -> list[Cell]:
    """The cells up to the last move (the robot stays there afterwards)."""
    last = len(cells) - 1
    while last > 0 and cells[last] == cells[last - 1]:
        last -= 1
    return cells[:last + 1]
