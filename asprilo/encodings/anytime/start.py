"""A plan to start from, as the planner's own: tracks, and the work they follow.

:func:`tracks_of` replays a valid plan into one :class:`~.reservations.Track` per robot
(where it stands after every step, what it picks up, puts down and delivers when).
:func:`rebuild` reads the work out of the tracks -- which robot carries which shelves, in
which order, to which stations, delivering what, and where it puts each one down -- and
gives it to a :class:`~.work.Work`, so that the large-neighbourhood search can route robots
of the plan again as if it had planned them itself.  That works where the plan does what
the planner's errands do: every shelf lifted by one robot once, and every shelf lifted
delivers.  Other plans are kept as given (:func:`rebuild` says why): they bound what the
search reports, and the search improves its own plans.  In M and Md the work is the goal
cell each robot ends on.
"""

from __future__ import annotations

from typing import cast

import clingo

from asprilo.bounds import goal_cells
from asprilo.domain import Delivery, Job
from asprilo.model import Instance, Plan

from .assignment import Choice
from .errands import Line, Task, Trip
from .reservations import Track
from .work import Work


def tracks_of(plan: Plan, instance: Instance) -> dict[int, Track]:
    """The track of every robot of ``instance`` in ``plan`` (a valid plan: it is not checked
    here).  A track ends with the robot's last action; a robot that never acts stays on its
    start cell."""
    cells = {robot: [spot.at] for robot, spot in instance.robots.items()}
    done: dict[int, dict[int, Task]] = {robot: {} for robot in instance.robots}
    carried: dict[int, int] = {robot: spot.carries for robot, spot in instance.robots.items()
                               if spot.carries is not None}
    resting = {shelf.at: number for number, shelf in instance.shelves.items() if number not in carried.values()}
    for step, actions in sorted(plan.by_step().items()):
        for action in actions:
            robot = cast(int, action.robot)  # a valid plan's robots are the instance's
            path = cells[robot]
            path.extend([path[-1]] * (step - len(path)))  # waited until the step before
            here = path[-1]
            if action.name == "move":
                path.append((here[0] + action.args[0], here[1] + action.args[1]))
                continue
            path.append(here)
            if action.name == "pickup":
                carried[robot] = shelf = resting.pop(here)
                done[robot][step] = Task("pickup", (here,), False, shelf)
            elif action.name == "putdown":
                resting[here] = shelf = carried.pop(robot)
                done[robot][step] = Task("putdown", (here,), True, shelf)
            elif action.name == "deliver":
                line = tuple(action.args[:2])
                done[robot][step] = Task("deliver", (here,), True, carried[robot], tuple(action.args), (line,))
    return {robot: Track(robot, cells[robot], done[robot]) for robot in instance.robots}


def rebuild(work: Work, tracks: dict[int, Track]) -> str | None:
    """Give ``work`` the work that ``tracks`` (of a valid plan of ``work``'s domain) do; or,
    when it cannot follow them, leave it as it is and say why (a clause: ``robot 2 carries
    shelf 4 without delivering from it``)."""
    if work.domain.work is Job.GOALS:
        return _rebuild_goals(work, tracks)
    lines = _lines_closed(work, tracks)
    lifted = {spot.carries: robot for robot, spot in work.instance.robots.items() if spot.carries is not None}
    trips: dict[int, list[Trip]] = {}
    for robot, track in sorted(tracks.items()):
        found = _trips(work, robot, track, lines, lifted)
        if isinstance(found, str):
            return found
        if found:
            trips[robot] = found
    atoms = {clingo.Function("carry", [clingo.Number(robot), clingo.Number(trip.shelf)])
             for robot, trips_ in trips.items() for trip in trips_}
    atoms |= _gives(work, tracks, lines)
    # where each shelf but a robot's last is put down, when not on its own cell
    claims = {shelf: cell for robot, track in tracks.items() for shelf, (cell, _) in track.placed(work.homes).items()
              if robot in trips and shelf != trips[robot][-1].shelf}
    work.restore((Choice(atoms), trips, {}, claims, {}, frozenset()))
    return None


def _trips(work: Work, robot: int, track: Track, lines: dict[tuple[int, int], tuple[Line, ...]],
           lifted: dict[int, int]) -> list[Trip] | str:
    """The trips of one robot's track, in time order (``lifted``: shelf -> the robot that
    lifts it, filled in); or why the planner's errands cannot do what the track does."""
    first = work.instance.robots[robot].carries
    trips, trip = [], Trip(first) if first is not None else None
    for step, task in sorted(track.done.items()):
        shelf = cast(int, task.shelf)  # a pickup's, putdown's and delivery's shelf is known
        if task.name == "pickup":
            if shelf in lifted:
                return f"shelf {shelf} is lifted twice (by robot {lifted[shelf]} and robot {robot})"
            lifted[shelf] = robot
            trip = Trip(shelf)
        elif task.name == "deliver" and trip is not None:
            trip.deliveries.append((task.cells[0], lines[robot, step], task.args))
        elif task.name == "putdown" and trip is not None:
            if not trip.deliveries:
                return f"robot {robot} carries shelf {trip.shelf} without delivering from it"
            trips.append(trip)
            trip = None
    if trip is not None and trip.deliveries:
        trips.append(trip)
    elif trip is not None and trip.shelf != first:
        return f"robot {robot} carries shelf {trip.shelf} without delivering from it"
    return trips


def _lines_closed(work: Work, tracks: dict[int, Track]) -> dict[tuple[int, int], tuple[Line, ...]]:
    """(robot, step) of every delivery -> the order lines it serves: the line it names, and in
    C every other line still open of its station whose product the shelf holds."""
    instance = work.instance
    stock = instance.shelf_stock()
    open_lines = {(order.id, product) for order in instance.orders.values() for product in order.lines}
    deliveries = sorted((step, robot, task) for robot, track in tracks.items()
                        for step, task in track.done.items() if task.name == "deliver")
    closed = {}
    for step, robot, task in deliveries:
        named = task.lines[0]
        served = [named]
        if work.domain.delivery is Delivery.STATION:
            station = instance.orders[named[0]].station
            served = sorted({named} | {line for line in open_lines if instance.orders[line[0]].station == station
                                       and line[1] in stock.get(cast(int, task.shelf), {})})
        closed[robot, step] = tuple(served)
        if not work.domain.counts_units:
            open_lines -= set(served)
    return closed


def _gives(work: Work, tracks: dict[int, Track], lines: dict[tuple[int, int], tuple[Line, ...]]) -> set[clingo.Symbol]:
    """The ``give(S,O,P,N)`` atoms of the shelf assignment that the deliveries make: the
    units each shelf hands over per line (one, where units are not counted)."""
    given: dict[tuple[int, int, int], int] = {}
    for robot, track in tracks.items():
        for step, task in track.done.items():
            if task.name != "deliver":
                continue
            for order, product in lines[robot, step]:
                units = task.args[2] if work.domain.counts_units else 1
                key = (cast(int, task.shelf), order, product)
                given[key] = given.get(key, 0) + units if work.domain.counts_units else 1
    return {clingo.Function("give", [clingo.Number(n) for n in (*key, units)]) for key, units in given.items()}


def _rebuild_goals(work: Work, tracks: dict[int, Track]) -> str | None:
    """M and Md: each robot's goal is the goal cell it ends on (``aim(R,G)``, ``G`` the cell's
    number among the instance's goal cells)."""
    cells = goal_cells(work.instance)
    goals = {robot: track.cells[-1] for robot, track in tracks.items() if track.cells[-1] in cells}
    atoms = {clingo.Function("aim", [clingo.Number(robot), clingo.Number(cells.index(cell))])
             for robot, cell in goals.items()}
    work.restore((Choice(atoms), {}, goals, {}, {}, frozenset()))
    return None
