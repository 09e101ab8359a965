"""The floor as a boolean array: breadth-first distances, shortest paths and corridors.

Cells are ``(X,Y)`` as in the instance; the array is indexed ``[X, Y]`` with a border of
non-floor cells around it, so that a neighbour lookup never leaves the array.  Distances
are computed as a wave over the whole array at once (one numpy step per distance), which
is fast enough for a 100x100 floor and needs no graph library.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from asprilo.model import DIRECTIONS, Cell

#: the distance of a cell that cannot be reached
FAR = np.iinfo(np.int32).max // 2


class Grid:
    """The floor: which cells exist, and distances over them (or over a subset of them)."""

    def __init__(self, cells: Iterable[Cell]):
        cells = list(cells)
        width = max((x for x, _ in cells), default=0) + 2
        height = max((y for _, y in cells), default=0) + 2
        self.floor = np.zeros((width, height), dtype=bool)
        for x, y in cells:
            self.floor[x, y] = True

    def mask(self, cells: Iterable[Cell] = ()) -> np.ndarray:
        """A boolean array of the floor's shape, true on ``cells``."""
        result = np.zeros_like(self.floor)
        for x, y in cells:
            result[x, y] = True
        return result

    def distances(self, sources: Iterable[Cell], passable: np.ndarray | None = None) -> np.ndarray:
        """Steps from the nearest source to every cell, moving over ``passable`` cells only
        (default: the floor); sources count as passable; ``FAR`` where no path leads."""
        allowed = (self.floor if passable is None else passable).copy()
        result = np.full(self.floor.shape, FAR, dtype=np.int32)
        frontier = self.mask(sources)
        result[frontier] = 0
        allowed &= ~frontier
        distance = 0
        while frontier.any():
            distance += 1
            grown = _neighbours(frontier) & allowed
            allowed &= ~grown
            result[grown] = distance
            frontier = grown
        return result

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


def distance_table(grid: Grid, sources: list[Cell], targets: list[Cell]) -> np.ndarray:
    """``len(sources) x len(targets)`` walking distances over the whole floor (``FAR``:
    none).  On a floor without holes these are Manhattan distances; else one breadth-first
    search per target."""
    table = np.full((len(sources), len(targets)), FAR, dtype=np.int64)
    if not sources or not targets:
        return table
    xs, ys = np.array([c[0] for c in sources]), np.array([c[1] for c in sources])
    if grid.floor[1:-1, 1:-1].all():
        tx, ty = np.array([c[0] for c in targets]), np.array([c[1] for c in targets])
        return np.abs(xs[:, None] - tx[None, :]) + np.abs(ys[:, None] - ty[None, :])
    for column, target in enumerate(targets):
        table[:, column] = grid.distances([target])[xs, ys]
    return table
