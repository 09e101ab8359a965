"""One step of all robots at once: priority inheritance with backtracking (PIBT, Okumura et
al., 2019) with the swap move of LaCAM* (Okumura, 2024), written here from the papers'
descriptions; :mod:`.lacam` searches with it.

In a step every robot picks its next cell, nearest to its goal first, in the order of its
priority; a robot that wants a cell where another robot stands pushes that robot (which
then picks first, and may not come to the pusher's cell: no swaps); a robot that finds no
cell stays.  Some robots may have their next cell fixed beforehand (LaCAM's constraints).

Plain PIBT cannot let two robots pass each other in a corridor: each pushes the other back.
The swap move sees this coming (the corridor ahead has no room to pass before the robots'
ways part) and, where the corridor behind leads to room, lets the robot back away from its
goal and pull the other after it, until both reach a branch where they can pass.
"""

from __future__ import annotations

import random

from asprilo.bounds import Floor
from asprilo.model import DIRECTIONS, Cell

#: the distance given to a cell a robot's aim cannot be reached from
FAR = 1 << 30


class Pibt:
    """Steps on one floor towards fixed aims (robot -> cell); ``swap``: with the swap move."""

    def __init__(self, floor: Floor, aims: dict[int, Cell], seed: int = 0, swap: bool = True):
        self.aims = aims
        self.swap = swap
        self.distance = {aim: floor.steps_from([aim]) for aim in set(aims.values())}
        self.shuffle = random.Random(seed)
        cells = set(floor.cells)
        self.neighbours = {(x, y): [(x + dx, y + dy) for dx, dy in DIRECTIONS if (x + dx, y + dy) in cells]
                           for x, y in cells}
        self.moves = {cell: around + [cell] for cell, around in self.neighbours.items()}
        self._near: dict[tuple[Cell, Cell], list[tuple[int, Cell]]] = {}

    def ranked(self, robot: int, cell: Cell, standing: dict[Cell, int]) -> list[Cell]:
        """The cells a robot on ``cell`` may be on next: nearest to its aim first, among equally
        near ones free cells first, ties drawn anew each time (fixed ties let two robots push
        each other back and forth for ever)."""
        aim = self.aims[robot]
        near = self._near.get((aim, cell))
        if near is None:
            distance = self.distance[aim]
            near = self._near[(aim, cell)] = [(4 * distance[option], option) for option in self.moves[cell]]
        draw = self.shuffle.random
        return [option for _, option in sorted([(rank + 2 * (option in standing) + draw(), option)
                                                for rank, option in near])]

    def reachable(self, starts: dict[int, Cell]) -> bool:
        """Whether every robot can reach its aim at all."""
        return all(start in self.distance[self.aims[robot]] for robot, start in starts.items())

    def to_go(self, robot: int, cell: Cell) -> int:
        return self.distance[self.aims[robot]].get(cell, FAR)

    def step(self, at: dict[int, Cell], order: list[int], fixed: dict[int, Cell]) -> dict[int, Cell] | None:
        """Where every robot of ``at`` is after one step, the robots of ``order`` picking in
        that order and those of ``fixed`` going where it says; ``None`` when the fixed moves
        leave no valid step (two robots on one cell, or a swap)."""
        step = _Step(self, at, fixed)
        if len(step.taken) < len(fixed):
            return None
        for robot in order:
            if robot not in step.after:
                step.pick(robot, None)
        after = step.after
        if len(set(after.values())) < len(after) or any(step.swaps(robot, cell) for robot, cell in after.items()):
            return None
        return after

    # --- the swap move -----------------------------------------------------------------------

    def swap_partner(self, robot: int, wanted: Cell, at: dict[int, Cell], standing: dict[Cell, int],
                     after: dict[int, Cell]) -> int | None:
        """The robot on the cell ``robot`` wants, when ``robot`` should back away and pull it
        after it: the two must pass each other and there is room behind ``robot``."""
        other = standing.get(wanted)
        if (other is None or other == robot or other in after or not self.swap
                or not self._must_pass(robot, other, at[robot], wanted, standing)):
            return None
        return other if self._room(wanted, at[robot], standing) else None

    def _must_pass(self, pusher: int, puller: int, pusher_at: Cell, puller_at: Cell,
                   standing: dict[Cell, int]) -> bool:
        """Whether ``pusher`` (going towards ``puller``) and ``puller`` must pass each other:
        pushing on along the corridor ahead brings ``pusher`` nearer its aim without meeting
        room to pass, and there ``puller``'s way leads back past ``pusher``."""
        behind, ahead = pusher_at, puller_at
        while self.to_go(pusher, ahead) < self.to_go(pusher, behind):
            onward = self._onward(ahead, behind, standing)
            if len(onward) >= 2:
                return False  # room to pass on the way
            if not onward:
                break
            behind, ahead = ahead, onward[0]
        return (self.to_go(puller, behind) < self.to_go(puller, ahead)
                and (self.to_go(pusher, behind) == 0 or self.to_go(pusher, ahead) < self.to_go(pusher, behind)))

    def _room(self, behind: Cell, ahead: Cell, standing: dict[Cell, int]) -> bool:
        """Whether the corridor from ``behind`` through ``ahead`` (away from ``behind``) leads
        to a cell with room to pass (two ways on) before a dead end or a loop back."""
        start = behind
        while ahead != start:
            onward = self._onward(ahead, behind, standing)
            if len(onward) >= 2:
                return True
            if not onward:
                return False
            behind, ahead = ahead, onward[0]
        return False

    def _onward(self, cell: Cell, came_from: Cell, standing: dict[Cell, int]) -> list[Cell]:
        """The cells on from ``cell`` other than ``came_from``, leaving out dead ends where a
        robot already stands on its aim (it need not move)."""
        onward = []
        for next_cell in self.neighbours[cell]:
            if next_cell == came_from:
                continue
            resting = standing.get(next_cell)
            if len(self.neighbours[next_cell]) == 1 and resting is not None and self.aims[resting] == next_cell:
                continue
            onward.append(next_cell)
        return onward


class _Step:
    """One step in the making: where the robots stand, where those decided go next."""

    def __init__(self, pibt: Pibt, at: dict[int, Cell], fixed: dict[int, Cell]):
        self.pibt, self.at = pibt, at
        self.standing = {cell: robot for robot, cell in at.items()}
        self.after: dict[int, Cell] = dict(fixed)
        self.taken = {cell: robot for robot, cell in fixed.items()}

    def swaps(self, robot: int, cell: Cell) -> bool:
        """Whether ``robot`` going to ``cell`` swaps cells with the robot standing there."""
        other = self.standing.get(cell)
        return other is not None and other != robot and self.after.get(other) == self.at[robot]

    def pick(self, robot: int, pusher: int | None) -> bool:
        """Choose ``robot``'s next cell (pushing the robot there); whether it could move."""
        at, after, taken = self.at, self.after, self.taken
        if pusher is None and at[robot] == self.pibt.aims[robot] and at[robot] not in taken:
            after[robot], taken[at[robot]] = at[robot], robot  # at its goal: staying ranks first
            return True
        options = self.pibt.ranked(robot, at[robot], self.standing)
        partner = self.pibt.swap_partner(robot, options[0], at, self.standing, after)
        if partner is not None:
            options = options[::-1]  # back away from the goal first
        for cell in options:
            if cell in taken or (pusher is not None and cell == at[pusher]) or self.swaps(robot, cell):
                continue
            after[robot], taken[cell] = cell, robot
            other = self.standing.get(cell)
            if other is not None and other != robot and other not in after and not self.pick(other, robot):
                continue  # the robot there could not get out of the way: it took this cell itself
            if partner is not None and cell == options[0] and partner not in after and at[robot] not in taken:
                after[partner], taken[at[robot]] = at[robot], partner  # pulled into the cell left
            return True
        after[robot] = at[robot]
        taken[at[robot]] = robot
        return False
