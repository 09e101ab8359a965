"""The Python routing engine: ``route.lp``'s search, in Python.

It answers the same question as the logic program on the same :class:`~.space.Space`: the
earliest step at which the robot can be parked, and a route that gets it there.  The logic
program grounds every state "on cell C at step T, on the way to task K" inside the windows.
This search goes best first (A*) and, instead of single steps, over *safe intervals* (Phillips
and Likhachev's SIPP, written here from the paper's idea): the steps a cell is free for the
robot fall into runs between the steps it is not (another robot there, a shelf in the way of a
loaded robot), and a robot that reaches a run may wait there until the run ends.  So a state
is "on cell C in run R, on the way to task K", reached as early as possible; waiting needs no
states of its own, and a route that must wait long visits no more states than one that need
not (``tests/test_timed_search.py`` checks that both engines find the same arrival).
"""

from __future__ import annotations

import heapq
from bisect import bisect_right

from asprilo.model import Cell

from .errands import Task
from .space import Space

#: a state of the search: (task number, cell, run number); task number 0: parked
State = tuple[int, Cell, int]
#: the runs of steps a cell is free on the way to one task, and the steps still to go from it
Room = tuple[list[tuple[int, int]], list[int], int]


def search(space: Space) -> tuple[list[Cell], dict[int, Task]] | None:
    """The route of ``space``'s robot with the earliest arrival: its cells after steps
    ``space.step`` .. arrival and the tasks done at their steps; ``None`` when none fits.

    Needs :meth:`Space.estimate`: the states are visited best first, by their first step plus
    the steps still to go (A*; the estimate never overshoots, so the first parked state taken
    is the earliest one)."""
    rooms = [_Rooms(space, number) for number in range(1, space.last + 1)]
    parking = [(cell, rooms[-1][cell]) for cell in space.task_cells[-1] if cell in rooms[-1]]
    if not any(runs and runs[-1][1] >= space.free_from.get(cell, 0) for cell, (runs, _, _) in parking):
        return None  # no parking cell is free within the window: no need to search
    begin: State = (1, space.begin, _start_run(rooms[0][space.begin], space.step))
    to_go = rooms[0][space.begin][2]
    arrival = {begin: space.step}
    came_from: dict[State, State | None] = {begin: None}
    # of the states as promising, the one reached latest first: it is the furthest along (on an
    # open floor every cell between the ends of a way is as promising; taking the earliest first
    # visited them all, some 20,000 states a route on 200x200)
    queue = [(space.step + to_go, -space.step, begin)]
    while queue:
        _estimate, latest, state = heapq.heappop(queue)
        step = -latest
        if step > arrival[state]:
            continue  # reached earlier since
        if state[0] == 0:
            return _trace(space, came_from, arrival, state)
        for following, there in _successors(space, rooms, state, step):
            if there < arrival.get(following, there + 1):  # reached earlier than known
                number, cell, _ = following
                arrival[following], came_from[following] = there, state
                heapq.heappush(queue, (there + (rooms[number - 1][cell][2] if number else 0), -there, following))
    return None


def _successors(space: Space, rooms: list[_Rooms], state: State, step: int):
    """The states reachable from ``state`` (reached at ``step``), each with the earliest
    step it is reached at: parked there, on a neighbour, or on to the next task."""
    number, cell, run = state
    last = rooms[number - 1][cell][0][run][1]
    if number == space.last and cell in space.task_cells[-1]:
        parked = max(step, space.free_from.get(cell, step))
        if parked <= last:
            yield (0, cell, run), parked
    for target, there, target_run in _moves(space, rooms[number - 1], cell, step, last):
        yield (number, target, target_run), there
    if number < space.last and cell in space.task_cells[number - 1] and space.acts(number):
        following = rooms[number].get(cell)
        earliest = max(step + 1, space.settle.get(number, 0))
        latest = min(last + 1, space.due.get(number, last + 1))
        for index, (begins, ends) in enumerate(following[0] if following else ()):
            done = max(earliest, begins)
            if done <= min(latest, ends):
                yield (number + 1, cell, index), done
                break


def _moves(space: Space, room: _Rooms, cell: Cell, step: int, last: int):
    """The moves from ``cell`` (reached at ``step``, free until ``last``) to a neighbour:
    ``(neighbour, earliest step there, its run)`` for every run of the neighbour it can reach
    in time, without swapping cells with a robot coming the other way."""
    x, y = cell
    for target in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
        free = room.get(target)
        if free is None:
            continue
        runs, starts, _ = free
        index = max(0, bisect_right(starts, step + 1) - 1)
        while index < len(runs) and runs[index][0] <= last + 1:
            begins, ends = runs[index]
            for there in range(max(step + 1, begins), min(last + 1, ends) + 1):
                if (target, cell, there) not in space.crossings:
                    yield target, there, index
                    break
            index += 1


def _start_run(room: Room, step: int) -> int:
    """The number of the run of the start cell that holds the first ``step``.  Where none
    does (the start lies outside the window then), a run is made for it: the robot may stay
    only if the next step is free."""
    runs, starts, _ = room
    index = bisect_right(starts, step) - 1
    if index >= 0 and runs[index][1] >= step:
        return index
    index += 1
    if index < len(runs) and runs[index][0] == step + 1:
        runs[index], starts[index] = (step, runs[index][1]), step
    else:
        runs.insert(index, (step, step))
        starts.insert(index, step)
    return index


class _Rooms(dict):
    """Cell -> :data:`Room` on the way to task ``number``: the runs of steps the robot may be
    there (inside its window, cut where another robot stays for good, between the steps
    another robot is there or, for a robot carrying a shelf, another shelf rests there), and
    the steps at least still to go from there.  Each is made when first asked for: a search
    seldom looks at more than the cells near one way, and a long way's windows hold many."""

    def __init__(self, space: Space, number: int):
        super().__init__()
        self.space, self.number, self.window = space, number, space.windows[number - 1]
        self.carrying = space.carrying(number)

    def __contains__(self, cell: object) -> bool:
        return cell in self.window

    def get(self, cell: Cell, default: Room | None = None) -> Room | None:  # type: ignore[override]
        return self[cell] if cell in self.window else default

    def __missing__(self, cell: Cell) -> Room:
        space = self.space
        space.look(cell)
        first, last = self.window[cell]
        last = min(last, space.stays.get(cell, last + 1) - 1)
        closed = set(space.busy.get(cell, ()))
        if self.carrying:
            for since, until in space.rests.get(cell, ()):
                closed.update(range(max(first, since), min(last, until) + 1))
        runs, begins = [], first
        for shut in sorted(step for step in closed if first <= step <= last):
            if shut > begins:
                runs.append((begins, shut - 1))
            begins = shut + 1
        if begins <= last:
            runs.append((begins, last))
        room = self[cell] = (runs, [begins for begins, _ in runs], space.to_go(self.number, cell))
        return room


def _trace(space: Space, came_from: dict[State, State | None], arrival: dict[State, int], parked: State
           ) -> tuple[list[Cell], dict[int, Task]]:
    """The route back from the parked state to the start: the robot waits on each cell until
    it leaves it."""
    visits: list[tuple[State, int]] = []  # (state, first step there), the parked state last
    state: State | None = parked
    while state is not None:
        visits.append((state, arrival[state]))
        state = came_from[state]
    visits.reverse()
    cells: list[Cell] = []
    done: dict[int, Task] = {}
    for (state, step), (following, next_step) in zip(visits, visits[1:], strict=False):
        cells += [state[1]] * (next_step - step)
        if following[0] == state[0] + 1:
            done[next_step] = space.tasks[state[0] - 1]
    cells.append(parked[1])
    return cells, done
