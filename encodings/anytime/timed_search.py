"""The Python routing engine: ``route.lp``'s search, in Python.

It answers the same question as the logic program on the same :class:`~.space.Space`: the
earliest step at which the robot can be parked, and a route that gets it there.  Like the
grounder, it searches the states "on cell C at step T, on the way to task K" of the
time-expanded floor inside the windows, keeping for each state the one it came from; but it
goes best first (A*), so it seldom visits more than the states near one good route, and it
starts no solver for each call: on a crowded floor the first plan needs thousands of calls
(``tests/test_timed_search.py`` checks that both engines find the same arrival).
"""

from __future__ import annotations

import heapq

from asprilo.model import Cell

from .errands import Task
from .space import Space

#: a state of the search: (task number, cell, step)
State = tuple[int, Cell, int]


def search(space: Space) -> tuple[list[Cell], dict[int, Task]] | None:
    """The route of ``space``'s robot with the earliest arrival: its cells after steps
    ``space.step`` .. arrival and the tasks done at their steps; ``None`` when none fits.

    Needs :meth:`Space.estimate`: the states are visited best first, by their step plus the
    steps still to go (A*; the estimate never overshoots, so the first parked state taken
    is the earliest one); of two as good, the one at the earlier step first, as the grounder
    goes (routes that keep close to their shortest way early leave room for others)."""
    rooms = [_rooms(space, number) for number in range(1, space.last + 1)]
    if not any(max(rooms[-1][cell][0], space.free_from.get(cell, 0)) <= rooms[-1][cell][1]
               for cell in space.task_cells[-1] if cell in rooms[-1]):
        return None  # no parking cell is free within the window: no need to search
    begin: State = (1, space.begin, space.step)
    came_from: dict[State, State | None] = {begin: None}
    queue = [(space.step + rooms[0][space.begin][3], space.step, begin)]
    crossings, last = space.crossings, space.last
    while queue:
        _estimate, _later, state = heapq.heappop(queue)
        number, cell, step = state
        if number == last and cell in space.task_cells[-1] and step >= space.free_from.get(cell, step):
            return _trace(space, came_from, state)
        after, room = step + 1, rooms[number - 1]
        x, y = cell
        for target in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1), cell):
            free = room.get(target)
            if free is not None and free[0] <= after <= free[1] and after not in free[2] \
                    and (target, cell, after) not in crossings and (number, target, after) not in came_from:
                came_from[(number, target, after)] = state
                heapq.heappush(queue, (after + free[3], after, (number, target, after)))
        if number < last and cell in space.task_cells[number - 1] and space.acts(number) \
                and after >= space.settle.get(number, after):
            free = rooms[number].get(cell)
            following = (number + 1, cell, after)
            if free is not None and free[0] <= after <= free[1] and after not in free[2] and following not in came_from:
                came_from[following] = state
                heapq.heappush(queue, (after + free[3], after, following))
    return None


def _rooms(space: Space, number: int) -> dict[Cell, tuple[int, int, frozenset[int], int]]:
    """Cell -> ``(first, last, closed, to_go)`` on the way to task ``number``: the steps the
    robot may be there (``last`` cut where another robot stays for good), the steps in
    between at which it may not (another robot there, or a shelf in the way of a robot
    carrying one), and the steps at least still to go from there."""
    carrying = space.carrying(number)
    rooms = {}
    for cell, (first, last) in space.windows[number - 1].items():
        last = min(last, space.stays.get(cell, last + 1) - 1)
        closed = set(space.busy.get(cell, ()))
        if carrying:
            for since, until in space.rests.get(cell, ()):
                closed.update(range(max(first, since), min(last, until) + 1))
        rooms[cell] = (first, last, frozenset(closed), space.to_go(number, cell))
    return rooms


def _trace(space: Space, came_from: dict[State, State | None], last: State) -> tuple[list[Cell], dict[int, Task]]:
    """The route back from the parked state ``last`` to the start."""
    states: list[State] = []
    state: State | None = last
    while state is not None:
        states.append(state)
        state = came_from[state]
    states.reverse()
    cells = [cell for _number, cell, _step in states]
    done = {step: space.tasks[states[index - 1][0] - 1]
            for index, (number, _cell, step) in enumerate(states) if index and number != states[index - 1][0]}
    return cells, done
