"""The floor as a graph, and the one search for distances over it.

Cells are ``(X,Y)``; a robot moves to one of the four neighbours a step (``DIRECTIONS``).
Every walking distance in asprilo comes from :class:`Floor`: the admissible bounds of this
package, the distance facts of the task assignment, the anytime planner's routes.  They all
use one breadth-first search (:meth:`Floor._search`), in numpy: the frontier of one step is
grown to the next at once, for several starting points side by side; a floor that fills its
bounding rectangle has Manhattan distances and needs no search.

**Unreachable** is :data:`INFINITE` (``math.inf``) in both views the floor offers: the
matrices of :meth:`Floor.distances` (sources x targets, for the bounds and the assignment)
and the arrays of :meth:`Floor.plane_distances` (indexed ``[X, Y]`` like the instance, for
the anytime planner's masks and corridors).  Both are float arrays; a distance that is not
``INFINITE`` is a whole number of steps.  A bound that no plan can meet is ``INFINITE`` too.

numpy is imported when a matrix or an array is first asked for, not before: the cheap bounds
that ``check`` shows at once (:func:`asprilo.bounds.makespan.cheap_bounds`) walk the floor with
:meth:`Floor.steps_from`, the same breadth-first search in plain Python over the same
neighbours, for a few starting points at a time; importing numpy takes longer (about 0.1 s)
than such a search on any floor of the paper.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable, Sequence
from functools import cached_property
from typing import TYPE_CHECKING

from ..model import DIRECTIONS, Cell

if TYPE_CHECKING:
    import numpy as np

#: no path leads there; no plan can do it (see the module docstring)
INFINITE = math.inf

#: starting points searched side by side in one pass (their arrays stay in the processor's cache)
_BATCH = 16


class Floor:
    """The floor as a graph: one vertex per node, edges between adjacent nodes.

    ``cells`` (sorted) and ``index`` (cell -> vertex) name the vertices; ``graph`` is the
    adjacency matrix for graph algorithms (scipy.sparse)."""

    def __init__(self, cells: Iterable[Cell]):
        self.cells: list[Cell] = sorted(set(cells))
        self.index = {cell: i for i, cell in enumerate(self.cells)}
        size = len(self.cells)
        self._full = False
        if size:
            xs, ys = [x for x, _ in self.cells], [y for _, y in self.cells]
            self._full = size == (max(xs) - min(xs) + 1) * (max(ys) - min(ys) + 1)

    @cached_property
    def _arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The vertices' X and Y, each vertex's neighbours in ``DIRECTIONS`` order (vertex
        ``size`` stands for "no node") and which vertices are open (all but that one)."""
        import numpy as np
        size = len(self.cells)
        xs = np.array([x for x, _ in self.cells], dtype=np.int64)
        ys = np.array([y for _, y in self.cells], dtype=np.int64)
        following = np.full((size + 1, len(DIRECTIONS)), size, dtype=np.int64)
        if size:
            low_x, low_y = int(xs.min()), int(ys.min())
            column = int(ys.max()) - low_y + 2  # one key more per column than it has cells: no wrapping
            keys = (xs - low_x) * column + (ys - low_y)  # ascending, as the cells are
            for k, (dx, dy) in enumerate(DIRECTIONS):
                wanted = keys + dx * column + dy
                found = np.minimum(np.searchsorted(keys, wanted), size - 1)
                following[:size, k] = np.where(keys[found] == wanted, found, size)
        opened = np.ones(size + 1, dtype=bool)
        opened[size] = False
        return xs, ys, following, opened

    @property
    def _xs(self) -> np.ndarray:
        return self._arrays[0]

    @property
    def _ys(self) -> np.ndarray:
        return self._arrays[1]

    @property
    def _next(self) -> np.ndarray:
        return self._arrays[2]

    @property
    def _open(self) -> np.ndarray:
        return self._arrays[3]

    def neighbours(self) -> np.ndarray:
        """``(len(cells) + 1) x 4``: each vertex's neighbours in ``DIRECTIONS`` order, where
        ``len(cells)`` stands for "no node" (its own row holds nothing else): for searches of
        their own over the floor (:func:`asprilo.bounds.delivery.arrivals_back`)."""
        return self._next

    @cached_property
    def graph(self):
        """The adjacency matrix (scipy.sparse)."""
        import numpy as np
        from scipy.sparse import csr_matrix
        size = len(self.cells)
        rows = np.repeat(np.arange(size), len(DIRECTIONS))
        columns = self._next[:size].ravel()
        edge = columns < size
        return csr_matrix((np.ones(int(edge.sum())), (rows[edge], columns[edge])), shape=(size, size))

    # --- the sources x targets view --------------------------------------------------------

    def distances(self, sources: Sequence[Cell], targets: Sequence[Cell]) -> np.ndarray:
        """``len(sources) x len(targets)`` shortest-path lengths (``INFINITE``: unreachable).

        A cell that is not a node is unreachable from and to everything.
        """
        import numpy as np
        result = np.full((len(sources), len(targets)), INFINITE)
        rows = [k for k, cell in enumerate(sources) if cell in self.index]
        columns = [k for k, cell in enumerate(targets) if cell in self.index]
        if not rows or not columns:
            return result
        starts = np.array([self.index[sources[k]] for k in rows])
        ends = np.array([self.index[targets[k]] for k in columns])
        if self._full:
            block = (np.abs(self._xs[starts][:, None] - self._xs[ends][None, :])
                     + np.abs(self._ys[starts][:, None] - self._ys[ends][None, :])).astype(float)
        elif len(np.unique(starts)) <= len(np.unique(ends)):  # the graph is undirected: search from fewer
            block = self._from_each(starts, ends)
        else:
            block = self._from_each(ends, starts).T
        result[np.ix_(rows, columns)] = block
        return result

    def _from_each(self, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
        """Distances from each vertex of ``starts`` to each of ``ends`` (one search per distinct start)."""
        import numpy as np
        distinct, back = np.unique(starts, return_inverse=True)
        block = np.empty((len(distinct), len(ends)))
        for first in range(0, len(distinct), _BATCH):
            batch = distinct[first:first + _BATCH]
            block[first:first + len(batch)] = self._search([[v] for v in batch], self._open)[:, ends]
        return block[back.ravel()]

    # --- the array view --------------------------------------------------------------------

    @cached_property
    def shape(self) -> tuple[int, int]:
        """The shape of :meth:`plane`: one row and column beyond the largest X and Y."""
        return (int(self._xs.max(initial=0)) + 2, int(self._ys.max(initial=0)) + 2)

    def plane(self) -> np.ndarray:
        """The floor as a boolean array indexed ``[X, Y]``, true on its cells, with a border
        that is never floor beyond the largest X and Y (and at 0, since asprilo's cells start
        at 1; the array view needs cells with X, Y >= 0)."""
        import numpy as np
        result = np.zeros(self.shape, dtype=bool)
        result[self._xs, self._ys] = True
        return result

    def plane_distances(self, sources: Iterable[Cell], passable: np.ndarray | None = None) -> np.ndarray:
        """Steps from the nearest of ``sources`` to every cell, as an array shaped like
        :meth:`plane`, moving over the ``passable`` cells only (a boolean array of that shape;
        default: the floor); sources count as passable; ``INFINITE`` where no path leads."""
        import numpy as np
        opened = self._open if passable is None else np.append(passable[self._xs, self._ys], False)
        starts = [self.index[cell] for cell in sources if cell in self.index]
        result = np.full(self.shape, INFINITE)
        if starts:
            result[self._xs, self._ys] = self._search([starts], opened)[0]
        return result

    # --- without numpy ---------------------------------------------------------------------

    def steps_from(self, sources: Iterable[Cell]) -> dict[Cell, int]:
        """Steps from the nearest of ``sources`` to every node a path leads to (a node missing
        from the answer: unreachable, ``INFINITE``; sources that are not nodes are left out).

        The breadth-first search of :meth:`_search` in plain Python: for the cheap bounds,
        which must not wait for numpy (the module docstring)."""
        steps = {cell: 0 for cell in sources if cell in self.index}
        frontier = deque(steps)
        while frontier:
            x, y = cell = frontier.popleft()
            step = steps[cell] + 1
            for dx, dy in DIRECTIONS:
                reached = (x + dx, y + dy)
                if reached in self.index and reached not in steps:
                    steps[reached] = step
                    frontier.append(reached)
        return steps

    def manhattan(self) -> bool:
        """Whether distances are Manhattan distances: the floor fills its bounding rectangle."""
        return self._full

    # --- the search ------------------------------------------------------------------------

    def _search(self, groups: list[list[int]], opened: np.ndarray) -> np.ndarray:
        """``len(groups) x len(cells)``: row ``k`` holds the steps from the nearest vertex of
        ``groups[k]`` over the ``opened`` vertices (``INFINITE``: none leads there).

        Breadth-first, all rows at once: vertex ``v`` of row ``k`` is ``k * size + v`` in
        flat arrays, and each step replaces the frontier by its neighbours not reached yet.
        """
        import numpy as np
        size = len(self.cells) + 1  # with the "no node" vertex, which is never open
        count = len(groups)
        unseen = np.tile(opened, count)
        steps = np.full(count * size, INFINITE)
        frontier = np.unique(np.concatenate([np.asarray(group, dtype=np.int64) + k * size
                                             for k, group in enumerate(groups)]))
        steps[frontier] = 0
        unseen[frontier] = False
        latest = np.empty(count * size, dtype=np.int64)
        step = 0
        while frontier.size:
            step += 1
            vertex = frontier % size
            reached = (self._next[vertex] + (frontier - vertex)[:, None]).ravel()
            reached = reached[unseen[reached]]
            # a vertex reached from two sides is kept once: the last write of its position wins
            order = np.arange(reached.size)
            latest[reached] = order
            reached = reached[latest[reached] == order]
            unseen[reached] = False
            steps[reached] = step
            frontier = reached
        return steps.reshape(count, size)[:, :-1]
