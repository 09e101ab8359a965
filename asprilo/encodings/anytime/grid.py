"""The floor as boolean arrays for the planner: masks, distances, shortest paths and corridors.

Cells are ``(X,Y)`` as in the instance; the arrays are indexed ``[X, Y]`` with a border of
non-floor cells around them, so that a neighbour lookup never leaves the array.  Distances
come from the core's one distance engine (:class:`asprilo.bounds.Floor`, its array view);
a cell that cannot be reached is :data:`~asprilo.bounds.INFINITE` away.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Iterable

import numpy as np

from asprilo.bounds import Floor
from asprilo.model import DIRECTIONS, Cell

#: the bytes of distance arrays a grid keeps for reuse (the router asks for the same ones
#: again and again: from a robot's start, to its goal, over the same passable cells)
CACHE_BYTES = 64_000_000


class Grid:
    """The floor (the engine's graph) as arrays: which cells exist (``floor``, a boolean array),
    and distances over them (or over a subset of them), the latest ones kept for reuse."""

    def __init__(self, engine: Floor):
        self.engine = engine
        self.floor = engine.plane()
        self._distances: OrderedDict[tuple, np.ndarray] = OrderedDict()
        self._keep = max(16, CACHE_BYTES // (self.floor.size * 16))

    def mask(self, cells: Iterable[Cell] = ()) -> np.ndarray:
        """A boolean array of the floor's shape, true on ``cells``."""
        result = np.zeros_like(self.floor)
        for x, y in cells:
            result[x, y] = True
        return result

    def distances(self, sources: Iterable[Cell], passable: np.ndarray | None = None) -> np.ndarray:
        """Steps from the nearest source to every cell, moving over ``passable`` cells only
        (default: the floor); sources count as passable; ``INFINITE`` where no path leads.
        The array is shared with later calls with the same question: it cannot be written."""
        key = (frozenset(sources), None if passable is None else passable.tobytes())
        found = self._distances.get(key)
        if found is not None:
            self._distances.move_to_end(key)
            return found
        found = self.engine.plane_distances(key[0], passable)
        found.flags.writeable = False
        self._distances[key] = found
        if len(self._distances) > self._keep:
            self._distances.popitem(last=False)
        return found

    def table(self, sources: list[Cell], targets: list[Cell]) -> np.ndarray:
        """``len(sources) x len(targets)`` walking distances over the whole floor (``INFINITE``: none)."""
        return self.engine.distances(sources, targets)

    def path(self, start: Cell, to_goal: np.ndarray) -> list[Cell]:
        """A shortest path from ``start`` down the distances ``to_goal`` (start included);
        among equal next cells it keeps the direction it is going, to avoid zigzags."""
        path = [start]
        x, y = start
        heading = None
        while to_goal[x, y] > 0:
            steps = [d for d in DIRECTIONS if to_goal[x + d[0], y + d[1]] == to_goal[x, y] - 1]
            heading = heading if heading in steps else steps[0]
            x, y = x + heading[0], y + heading[1]
            path.append((x, y))
        return path


def _neighbours(cells: np.ndarray) -> np.ndarray:
    """The cells next to any true cell of ``cells`` (the border of the array is never set)."""
    grown = np.zeros_like(cells)
    grown[1:, :] |= cells[:-1, :]
    grown[:-1, :] |= cells[1:, :]
    grown[:, 1:] |= cells[:, :-1]
    grown[:, :-1] |= cells[:, 1:]
    return grown


def widen(cells: np.ndarray, radius: int) -> np.ndarray:
    """``cells`` and every cell within ``radius`` steps of them (ignoring the floor)."""
    result = cells.copy()
    for _ in range(radius):
        result |= _neighbours(result)
    return result


def cells_of(mask: np.ndarray) -> list[Cell]:
    """The true cells of a mask, as ``(X,Y)``."""
    xs, ys = np.nonzero(mask)
    return list(zip(xs.tolist(), ys.tolist(), strict=True))
