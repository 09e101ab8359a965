"""One step of all robots at once: priority inheritance with backtracking (PIBT, Okumura et
al., 2019), written here from the paper's description; :mod:`.lacam` searches with it.

In a step every robot picks its next cell, nearest to its goal first, in the order of its
priority; a robot that wants a cell where another robot stands pushes that robot (which
then picks first, and may not come to the pusher's cell: no swaps); a robot that finds no
cell stays.  Some robots may have their next cell fixed beforehand (LaCAM's constraints).
"""

from __future__ import annotations

import random

from asprilo.bounds import Floor
from asprilo.model import DIRECTIONS, Cell


class Pibt:
    """Steps on one floor towards fixed aims (robot -> cell)."""

    def __init__(self, floor: Floor, aims: dict[int, Cell], seed: int = 0):
        self.aims = aims
        self.distance = {aim: floor.steps_from([aim]) for aim in set(aims.values())}
        self.shuffle = random.Random(seed)
        cells = set(floor.cells)
        self.moves = {(x, y): [(x + dx, y + dy) for dx, dy in DIRECTIONS if (x + dx, y + dy) in cells] + [(x, y)]
                      for x, y in cells}
        self._ranked: dict[tuple[Cell, Cell], list[Cell]] = {}

    def ranked(self, robot: int, cell: Cell) -> list[Cell]:
        """The cells a robot on ``cell`` may be on next, nearest to its aim first (ties in an
        order drawn once per aim and cell)."""
        aim = self.aims[robot]
        options = self._ranked.get((aim, cell))
        if options is None:
            options = self.moves[cell][:]
            self.shuffle.shuffle(options)
            options.sort(key=self.distance[aim].__getitem__)
            self._ranked[(aim, cell)] = options
        return options

    def reachable(self, starts: dict[int, Cell]) -> bool:
        """Whether every robot can reach its aim at all."""
        return all(start in self.distance[self.aims[robot]] for robot, start in starts.items())

    def to_go(self, robot: int, cell: Cell) -> int:
        return self.distance[self.aims[robot]][cell]

    def step(self, at: dict[int, Cell], order: list[int], fixed: dict[int, Cell]) -> dict[int, Cell] | None:
        """Where every robot of ``at`` is after one step, the robots of ``order`` picking in
        that order and those of ``fixed`` going where it says; ``None`` when the fixed moves
        leave no valid step (two robots on one cell, or a swap)."""
        standing = {cell: robot for robot, cell in at.items()}
        after: dict[int, Cell] = dict(fixed)
        taken = {cell: robot for robot, cell in fixed.items()}
        if len(taken) < len(fixed):
            return None

        def swaps(robot: int, cell: Cell) -> bool:
            other = standing.get(cell)
            return other is not None and other != robot and after.get(other) == at[robot]

        def pick(robot: int, pusher: int | None) -> bool:
            """Choose ``robot``'s next cell (pushing the robot there); whether it could move."""
            for cell in self.ranked(robot, at[robot]):
                if cell in taken or (pusher is not None and cell == at[pusher]) or swaps(robot, cell):
                    continue
                after[robot], taken[cell] = cell, robot
                other = standing.get(cell)
                if other is not None and other != robot and other not in after and not pick(other, robot):
                    continue  # the robot there could not get out of the way: it took this cell itself
                return True
            after[robot] = at[robot]
            taken[at[robot]] = robot
            return False

        for robot in order:
            if robot not in after:
                pick(robot, None)
        if len(set(after.values())) < len(after) or any(swaps(robot, cell) for robot, cell in after.items()):
            return None
        return after
