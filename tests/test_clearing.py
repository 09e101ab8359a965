"""Cleared cells in the anytime planner (``clear`` neighbourhoods): a robot that finishes
early carries a shelf that serves no order out of the way, so that a late robot can put
its shelf down nearer its way.

The expected values are worked out by hand on the bundled small A example (11x6, three
robots; picking stations on (4,1) and (8,1)): with robot 3 bringing shelf 1 and then
shelf 9 to station (8,1), robot 1 shelf 3 and robot 2 shelf 2, the nearest spare cell on
robot 3's way from the station to shelf 9 is (9,3) (3 steps with the shelf, 3 without);
shelf 4 on (8,3) serves no order, and putting shelf 1 down there instead saves 2 steps.
"""

from __future__ import annotations

from helpers import EXAMPLES

from asprilo.bounds import Floor
from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings.anytime.errands import Task, trips
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.improve import Improver, score
from asprilo.encodings.anytime.plans import plan_of
from asprilo.encodings.anytime.prioritized import first_tracks
from asprilo.encodings.anytime.reservations import Reservations
from asprilo.encodings.anytime.router import Router
from asprilo.encodings.anytime.work import Work
from asprilo.reader import read_instance

SMALL_A = EXAMPLES / "asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
#: (shelf, order, product, units): what each shelf gives (orders 1, 2, 3 need 11+2, 1+20, 2+1)
GIVES = [(1, 2, 5, 10), (1, 3, 3, 1), (1, 2, 4, 1), (2, 1, 2, 7), (2, 1, 4, 1), (2, 2, 5, 10),
         (3, 1, 2, 4), (3, 1, 4, 1), (9, 3, 1, 2)]
#: (robot, shelf)
CARRIES = [(3, 1), (3, 9), (1, 3), (2, 2)]


def _planner():
    instance = read_instance([SMALL_A])
    grid = Grid(Floor(instance.cells))
    work = Work(instance, Domain.A, grid, 23)
    work.trips = trips(instance, Domain.A, GIVES, CARRIES, work.homes)
    table = Reservations(instance, work.homes)
    router = Router(grid, table)
    assert first_tracks(work, router, table, lambda: False) is not None
    return instance, work, table, router


def test_the_late_robots_shelf_goes_where_an_idle_shelf_is_cleared_away():
    _, work, table, _ = _planner()
    assert [trip.shelf for trip in work.trips[3]] == [1, 9]
    assert work.errand(3, set())[4] == Task("putdown", ((9, 3),), True, 1)
    assert work.clear(3, 1)
    assert work.clearings == {1: [(4, (9, 3))]}
    assert work.errand(1, set())[:2] == [Task("pickup", ((8, 3),), False, 4), Task("putdown", ((9, 3),), True, 4)]
    assert work.errand(3, set())[4] == Task("putdown", ((8, 3),), True, 1)


def test_the_cleared_cell_gives_the_late_robot_its_shortest_errand():
    # robot 3: 3 steps to shelf 1, lift, 7 to the station, 3 deliveries, 2 to (8,3), put
    # down, 2 to shelf 9 (over the cell shelf 3 left), lift, 4 to the station, deliver: 25
    instance, work, table, router = _planner()
    before = score(table.tracks)[0]
    assert before > 25
    assert work.clear(3, 1)
    improver = Improver(work, router, table)
    assert improver._repair([1, 3], 0, False, lambda: False, work.save()) == "better"
    assert table.tracks[3].finish == 25
    assert score(table.tracks)[0] == 25
    verdict = check(instance, plan_of(table.tracks, instance, Domain.A), Domain.A)
    assert verdict.valid and verdict.metrics["horizon"] == 25


def test_a_robot_that_stops_clearing_frees_the_cells_its_users_had():
    _, work, _, _ = _planner()
    assert work.clear(3, 1)
    work.errand(3, set())  # robot 3 claims the cleared cell for shelf 1
    assert work.claims[1] == (8, 3)
    work.unclear(1)
    assert work.clearings == {} and 4 not in work.claims and 1 not in work.claims
    assert work.errand(3, set())[4] == Task("putdown", ((9, 3),), True, 1)


def test_no_shelf_is_cleared_for_a_robot_that_puts_none_down():
    _, work, _, _ = _planner()
    assert not work.clear(1, 3)  # robot 1 brings one shelf and keeps it
    assert work.clearings == {}


def test_a_shelf_is_not_put_down_where_it_could_close_a_way():
    # by hand on the small A example: (6,3) joins the rows above and below the two blocks of
    # shelves (a robot with a shelf goes around it only beyond the 5x5 square); around (2,4)
    # and (9,3) the free neighbours stay joined (or there is only one)
    _, work, _, _ = _planner()
    assert work._closes_a_way((6, 3))
    assert not work._closes_a_way((2, 4))
    assert not work._closes_a_way((9, 3))
