"""Where the anytime planner parks robots on A floors (issue 45: its first plans on 100x100
floors were twice the bound, and one seed needed three attempts).

``SIDING``: station (1,1), highway (2..5,1), robot 1 on (6,1) (a storage cell), shelf 1 on
(6,2) holding the product of the one order, one more storage cell (2,2).  The robot lifts
the shelf and carries it to the station: S, lift (2); N W W W W W (8), deliver (9).  The
first plan used to carry the shelf back to its own cell (E E E E E S, 15); now it parks on
the spare storage cell nearest the station, (2,2): E S (11).  The search then lets the robot
stay on the station (9, the minimum: the delivery comes at step 9 at the earliest).

``CORNER``: station (1,1), robots 1 on (2,1) and 3 on (1,2) next to it, without work;
robot 2 on (7,1) carries shelf 1 from (7,2).  Robots 1 and 3 stand where robot 2 must
deliver: they make room, each on the nearest free cells (no robot starts there, nobody
needs them), nearest first, then by x and y.  Robot 1 (first of the two) gets (2,2) and
(3,1) (1 step away), (3,2) and (4,1) (2), (4,2) and (5,1) (3); robot 3 what is left:
(5,2) (4 steps), (6,2) (5), (6,1) (6).  Both were offered robot 1's six before, and the
one routed second found none left free where many robots stood in one corner.
"""

from __future__ import annotations

from helpers.clocks import patient_anytime
from helpers.errands import assigned_work, hand
from helpers.warehouses import minimal_makespan
from helpers.worlds import world

from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings.anytime import plan_anytime, search
from asprilo.encodings.anytime.errands import Task

E, W, N, S = (1, 0), (-1, 0), (0, -1), (0, 1)


def siding():
    return world("P####R/ .   S", products={1: {1: 1}}, orders={1: ({1: 1}, 1)})


def corner():
    return world("PR....R/R.....S", products={1: {1: 1}}, orders={1: ({1: 1}, 1)})


def test_a_robot_may_park_its_last_shelf_near_the_station():
    work = assigned_work(siding())
    # its own cell, then the spare cells nearest the station: (2,2) 2 steps, (6,1) 5
    assert work.errand(1, set())[-1] == Task("park", ((6, 2), (2, 2), (6, 1)), True, 1)
    # a cell where another robot stays is not offered
    assert work.errand(1, set(), parked=[(2, 2)])[-1] == Task("park", ((6, 2), (6, 1)), True, 1)


def test_the_first_plan_parks_near_the_station_then_on_it(monkeypatch):
    instance = siding()
    assert minimal_makespan(instance, Domain.A, start=8) == 9
    monkeypatch.setattr(search, "CHECK_GAP", 0.0)  # every better plan checked and reported at once
    clock = patient_anytime(monkeypatch, stop_after=2)
    result = plan_anytime(instance, Domain.A, time_limit=120, on_improvement=clock.reported)
    way = (S, "pickup", N, W, W, W, W, W, "deliver:1,1,1")
    assert [sorted((a.step, a.name, a.args) for a in better.plan.actions) for better in result.history] == \
        [hand(*way, E, S), hand(*way)]
    assert result.minimal and check(instance, result.plan, Domain.A).valid


def test_robots_making_room_are_offered_cells_of_their_own():
    work = assigned_work(corner())
    assert work.trips.keys() == {2} and work.movers() == [1, 3]
    # asked in the other order: robot 1 still comes first
    assert work.errand(3, set()) == [Task("park", ((5, 2), (6, 2), (6, 1)))]
    assert work.errand(1, set()) == [Task("park", ((2, 2), (3, 1), (3, 2), (4, 1), (4, 2), (5, 1)))]
