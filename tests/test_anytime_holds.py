"""Shelves held aside in the anytime planner (``hold`` neighbourhoods, :mod:`.asides`): a robot
without work lifts a shelf that serves no order and stands on the short way of another
robot's carry, and steps aside holding it.

A 3x3 floor worked out by hand (every cell a storage cell; ``P`` the station, ``a`` shelf 1
serving no order, ``b`` shelf 2 with the one line, robots ``1`` and ``2``)::

    y=1   . P .
    y=2   . a .
    y=3   2 b 1

Robot 1 brings shelf 2 to the station.  Around shelf 1 its carry takes 4 moves; through
shelf 1's cell 2.  Alone: move onto (2,3) at step 1, lift at 2, (3,3) 3, (3,2) 4, (3,1) 5,
(2,1) 6, deliver at 7.  With robot 2 holding shelf 1 aside: robot 2 moves to (1,2) at step 1,
(2,2) at 2, lifts at 3 and steps back to (1,2) at 4 (the nearest cell off the way: (1,2) and
(3,2) are one step from (2,2), (1,2) comes first); robot 1 lifts at 2, waits, follows onto
(2,2) at 4, (2,1) at 5 and delivers at 6, the proven minimum (``asprilo solve --method asp``
on this floor says 6, and the planner without holds ended at 7).
"""

from __future__ import annotations

import random

from asprilo.bounds import Floor
from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings.anytime.asides import hold_aside, idle_robots
from asprilo.encodings.anytime.errands import Task, trips
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.improve import Improver, score
from asprilo.encodings.anytime.plans import plan_of
from asprilo.encodings.anytime.prioritized import first_tracks
from asprilo.encodings.anytime.reservations import Reservations
from asprilo.encodings.anytime.router import Router
from asprilo.encodings.anytime.work import Work
from asprilo.reader import read_instance

FLOOR = """
init(object(grid,1),value(xsize,3)). init(object(grid,1),value(ysize,3)).
init(object(pickingStation,1),value(at,(2,1))).
init(object(robot,1),value(at,(3,3))). init(object(robot,2),value(at,(1,3))).
init(object(shelf,1),value(at,(2,2))). init(object(shelf,2),value(at,(2,3))).
init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,1))).
init(object(order,1),value(line,(2,1))). init(object(order,1),value(pickingStation,1)).
"""


def _planner(tmp_path, carries=((1, 2),)):
    (tmp_path / "hold.lp").write_text(FLOOR)
    instance = read_instance([tmp_path / "hold.lp"])
    grid = Grid(Floor(instance.cells))
    work = Work(instance, Domain.A, grid, 20)
    work.trips = trips(instance, Domain.A, [(2, 1, 2, 1)], list(carries), work.homes)
    table = Reservations(instance, work.homes)
    router = Router(grid, table)
    assert first_tracks(work, router, table, lambda: False) is not None
    return instance, work, table, router


def test_the_robot_without_work_holds_the_shelf_on_the_short_way_aside(tmp_path):
    _, work, _, _ = _planner(tmp_path)
    assert idle_robots(work) == [2]
    assert hold_aside(work, 1, random.Random(0)) == [2]
    assert work.clearings == {2: [(1, (1, 2))]}
    assert work.claims[1] == (1, 2)
    assert work.errand(2, set()) == [Task("pickup", ((2, 2),), False, 1), Task("park", ((1, 2),), True, 1)]
    assert idle_robots(work) == []
    assert hold_aside(work, 1, random.Random(0)) == []  # nobody left to hold a shelf


def test_holding_the_shelf_aside_gives_the_minimal_plan(tmp_path):
    instance, work, table, router = _planner(tmp_path)
    assert score(table.tracks)[0] > 6
    assert hold_aside(work, 1, random.Random(0)) == [2]
    improver = Improver(work, router, table)
    assert improver._repair([2, 1], 0, False, lambda: False, work.save()) == "better"
    assert table.tracks[1].finish == 6 and table.tracks[2].finish == 4
    assert score(table.tracks)[0] == 6
    verdict = check(instance, plan_of(table.tracks, instance, Domain.A), Domain.A)
    assert verdict.valid and verdict.metrics["horizon"] == 6


def test_no_hold_where_the_way_crosses_no_shelf_or_nobody_is_free(tmp_path):
    # robot 2 brings shelf 2 itself: no robot is without work
    _, work, _, _ = _planner(tmp_path, carries=((2, 2),))
    assert idle_robots(work) == [1]
    assert hold_aside(work, 1, random.Random(0)) == []  # robot 1 has no carry to shorten
    _, work, _, _ = _planner(tmp_path, carries=((1, 2),))
    work.clearings = {2: [(1, (3, 2))]}  # robot 2 holds shelf 1 already
    assert hold_aside(work, 1, random.Random(0)) == []
