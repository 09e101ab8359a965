"""The minimal makespan of a tiny M or Md instance by breadth-first search over joint states.

An oracle for the tests (the grader's ladders, :mod:`test_grade_ladders`): it follows
SPEC.md section 4 for domains M and Md step by step and shares no code with the encodings,
the max-flow solver, the checker or the simulator.  Robots are anonymous, so a state is the
set of cells the robots stand on; one step moves every robot by at most one cell at once,
never two robots onto one cell and never two robots across one edge in opposite directions.
The goal: a robot on every goal cell (M: the shelf holding the product of an order's line;
Md: every destination).  Only for instances of a few cells and robots: the number of states
grows exponentially.
"""

from __future__ import annotations

from itertools import product

MOVES = ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1))


def goal_cells(instance, domain: str) -> frozenset:
    """The cells some robot must stand on at the horizon."""
    if domain == "md":
        return frozenset(destination.at for destination in instance.destinations.values())
    cells = set()
    for order in instance.orders.values():
        for item in order.lines:
            shelves = list(instance.products[item].stock)
            assert len(shelves) == 1, "domain M: every ordered product lies on exactly one shelf"
            cells.add(instance.shelves[shelves[0]].at)
    return frozenset(cells)


def _successors(state: tuple, cells: set) -> set:
    """Every joint state one step after ``state`` (robots anonymous: sorted positions)."""
    choices = [[(x + dx, y + dy) for dx, dy in MOVES if (x + dx, y + dy) in cells] for x, y in state]
    following = set()
    for after in product(*choices):
        if len(set(after)) < len(after):
            continue  # two robots on one cell
        moved = {(before, now) for before, now in zip(state, after, strict=True) if before != now}
        if any((now, before) in moved for before, now in moved):
            continue  # two robots swap cells
        following.add(tuple(sorted(after)))
    return following


def minimal_makespan(instance, domain: str, limit: int = 40, max_states: int = 2_000_000) -> int | None:
    """The fewest steps after which a robot stands on every goal cell (``None``: not within
    ``limit`` steps or ``max_states`` states)."""
    cells = set(instance.cells)
    goals = goal_cells(instance, domain)
    start = tuple(sorted(robot.at for robot in instance.robots.values()))
    layer, seen = {start}, {start}
    for depth in range(limit + 1):
        if any(goals <= set(state) for state in layer):
            return depth
        following = set()
        for state in layer:
            for nxt in _successors(state, cells):
                if nxt not in seen:
                    seen.add(nxt)
                    following.add(nxt)
        if not following or len(seen) > max_states:
            return None
        layer = following
    return None
