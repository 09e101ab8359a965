"""The floor as numbered vertices for the M/Md planners (:mod:`.pibt`, :mod:`.lacam`,
:mod:`.refine`): every cell is a number, its neighbours a list of numbers, and the distances
to a goal one list indexed by vertex, computed once per goal and shared by every robot with
that goal and every later search.

The planners of M and Md step hundreds of robots thousands of times: numbers in lists are
what plain Python reads fastest (no tuples of coordinates built per step, no dictionaries of
cells).  The vertices are those of :class:`asprilo.bounds.Floor`, whose breadth-first search
computes the distances (many goals in one pass).
"""

from __future__ import annotations

from collections.abc import Iterable

from asprilo.bounds import Floor
from asprilo.model import Cell

#: the distance given to a vertex a goal cannot be reached from (larger than any path)
FAR = 1 << 30


class Roadmap:
    """The vertices of a floor (``cells[v]`` is the cell of vertex ``v``), their neighbours,
    and the distance tables of the goals asked for so far."""

    def __init__(self, floor: Floor):
        self.floor = floor
        self.cells: list[Cell] = floor.cells
        self.index: dict[Cell, int] = floor.index
        self.size = len(self.cells)
        self.neighbours: list[list[int]] = [
            [self.index[(x + dx, y + dy)] for dx, dy in ((0, 1), (1, 0), (0, -1), (-1, 0))
             if (x + dx, y + dy) in self.index]
            for x, y in self.cells]
        self._to: dict[int, list[int]] = {}

    def vertex(self, cell: Cell) -> int:
        return self.index[cell]

    def distances_to(self, goals: Iterable[int]) -> list[list[int]]:
        """The distance table of each goal (in the order given): ``table[v]`` is the number
        of steps from vertex ``v`` to the goal, :data:`FAR` where no path leads.  Tables of
        goals not asked for before are computed together."""
        goals = list(goals)
        missing = sorted({goal for goal in goals if goal not in self._to})
        if missing:
            rows = self.floor.distances([self.cells[goal] for goal in missing], self.cells)
            rows[rows > FAR] = FAR
            for goal, row in zip(missing, rows.astype(int).tolist(), strict=True):
                self._to[goal] = row
        return [self._to[goal] for goal in goals]

    def degree(self, vertex: int) -> int:
        return len(self.neighbours[vertex])
