"""The relaxed schedule of an assignment, the search over assignments, and the improver's
restarts from them (issue 45, domain A with orders of several lines).

The floors are corridors drawn with ``helpers.worlds.world``; every expected schedule is
derived by hand below, step by step, and the search's best is checked against a brute force
over every assignment of the tiny instances.

``TWO`` (as in test_anytime_putdowns): station (1,1), highway (2..4,1), the robot on (5,1),
shelf 1 on (2,2) with product 1, shelf 2 on (3,2) with product 2, a spare cell (5,2); one
order asks both.  Shelf 1 first: walk W W W S under nothing (4), lift (5), N W (7), deliver
(8); back to (2,2): E to (2,1), S onto the shelf's own cell (10), put down (11), E under
nothing to (3,2) (12), lift (13), N W W (16), deliver (17).  Shelf 2 first: W W S (3), lift
(4), N W W (7), deliver (8); E E S (11), put down (12), W (13), lift (14), N W (16),
deliver (17).  The spare cell is farther either way (5 steps to it with the shelf).

``QUEUE``: the same corridor without the spare cell, a second robot on (5,2) below the
first.  Robot 1 with shelf 2: W W S (3), lift (4), N W W (7), deliver (8), then it steps off
the station (9): robot 2 needs it.  Robot 2 with shelf 1: N W W W S (5), lift (6), N W (8);
the station is free from 9 (robot 1 delivered at 8): it moves in at 9 and delivers at 10.
Makespan 10, sum of finishes 9 + 10 = 19; the other split (robot
1 shelf 1: 4 + 1 + 2 = 7, deliver 8; robot 2 shelf 2: N W W S = 4, lift 5, N W W = 8,
moves in at 9, delivers 10) gives the same.

``DEAD``: shelf 2 (product 2) at the end of a dead end (3,3) behind shelf 1 (3,2, product
1); robot 1 on (5,1), robot 2 on (5,2).  Robot 1 lifts shelf 1 at 4 (W W S, lift) and
delivers at 8 (N W W, deliver), never bringing it back; robot 2 walks under it to shelf 2
((5,1), (4,1), (3,1), (3,2), (3,3): 5), lifts it at 6, when shelf 1 is away, and carries it
out through shelf 1's cell (N N W W: arrives 10, the station free since 9), delivers at 11.
Around the resting shelves shelf 2 would never get out.
"""

from __future__ import annotations

import itertools

from helpers.errands import assigned_work
from helpers.worlds import world

from asprilo.encodings.anytime import improve, relaxed
from asprilo.encodings.anytime.improve import Improver, score
from asprilo.encodings.anytime.prioritized import first_tracks
from asprilo.encodings.anytime.relaxed import Assignment, Schedules
from asprilo.encodings.anytime.reservations import Reservations
from asprilo.encodings.anytime.router import Router


def two():
    return world("P###R/ SS .", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1, 2: 1}, 1)})


def queue():
    return world("P###R/ SS R", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1, 2: 1}, 1)})


def dead():
    instance = world("P###R/  S R/  S  ", products={1: {1: 1}, 2: {2: 1}}, orders={1: ({1: 1, 2: 1}, 1)})
    instance.highways[5] = (5, 1)
    return instance


BOTH = {(1, 1): {1: 1}, (1, 2): {2: 1}}  # order 1's lines, product 1 from shelf 1, product 2 from shelf 2


def test_one_robot_brings_two_shelves_back_and_forth_as_derived_by_hand():
    schedules = Schedules(assigned_work(two()))
    assert schedules.cost(BOTH, {1: [1, 2]}) == (17, 17)
    assert schedules.cost(BOTH, {1: [2, 1]}) == (17, 17)


def test_a_robot_waits_for_the_station_and_the_first_one_steps_off_it():
    schedules = Schedules(assigned_work(queue()))
    assert schedules.cost(BOTH, {1: [2], 2: [1]}) == (10, 19)
    assert schedules.cost(BOTH, {1: [1], 2: [2]}) == (10, 19)
    # one robot with both: the two-shelf round of TWO (no spare cell changes nothing there)
    assert schedules.cost(BOTH, {1: [1, 2], 2: []}) == (17, 17)


def test_a_shelf_in_a_dead_end_comes_out_through_the_cell_of_a_shelf_lifted_before():
    schedules = Schedules(assigned_work(dead()))
    assert schedules.cost(BOTH, {1: [1], 2: [2]}) == (11, 20)


def test_a_shelf_that_cannot_get_out_yet_makes_an_assignment_very_long():
    # robot 1 lifts shelf 2 at 5 ((4,1), (3,1), (3,2), (3,3): 4 steps, lift); robot 2 lifts
    # shelf 1 at 5 too ((5,1), (4,1), (3,1), (3,2), lift): not before, so shelf 2 has no way out
    schedules = Schedules(assigned_work(dead()))
    assert schedules.cost(BOTH, {1: [2], 2: [1]})[0] >= relaxed.FAR


def _brute_force(schedules: Schedules, gives) -> tuple[int, int]:
    """The least relaxed cost over every way to split the shelves among the robots and order them."""
    shelves = sorted({shelf for portions in gives.values() for shelf in portions})
    robots = schedules.robots
    best = None
    for owners in itertools.product(robots, repeat=len(shelves)):
        for order in itertools.permutations(shelves):
            errands = {robot: [s for s in order if owners[shelves.index(s)] == robot] for robot in robots}
            cost = schedules.cost(gives, errands)
            best = cost if best is None else min(best, cost)
    return best


def test_the_search_finds_the_best_assignment_of_a_brute_force():
    # QUEUE with a third shelf (on the spare cell's place) holding product 1 too: the search
    # may serve the line of product 1 from either shelf
    instance = world("P###R/ SSSR", products={1: {1: 1, 3: 1}, 2: {2: 1}}, orders={1: ({1: 1, 2: 1}, 1)})
    schedules = Schedules(assigned_work(instance), seed=3)
    found = schedules.search(1.0)
    best = min(_brute_force(schedules, {(1, 1): {source: 1}, (1, 2): {2: 1}}) for source in (1, 3))
    assert found and schedules.kept[0][0] == best
    gives = {line: dict(portions) for line, portions in found[0].gives}
    assert schedules.cost(gives, {robot: list(shelves) for robot, shelves in found[0].errands}) == best


def test_an_adopted_assignment_is_the_work_in_the_order_given():
    work = assigned_work(queue())
    assignment = Assignment((((1, 1), ((1, 1),)), ((1, 2), ((2, 1),))), ((2, (2, 1)),))
    work.adopt(assignment.choice(), assignment.by_robot())
    assert [trip.shelf for trip in work.trips[2]] == [2, 1] and 1 not in work.trips
    assert work.choice.of("carry") == [(2, 1), (2, 2)]


def test_restarts_report_only_plans_better_than_the_best(monkeypatch):
    monkeypatch.setattr(improve, "STALL", 2)
    instance = two()
    work = assigned_work(instance)
    table = Reservations(instance, work.homes)
    router = Router(work.grid, table)
    assert first_tracks(work, router, table, lambda: False) is not None
    improver = Improver(work, router, table, seed=1)
    assert improver.restarts
    best = score(table.tracks)
    for _ in range(40):
        before = score(table.tracks)
        better = improver.step(lambda: False)
        now = score(table.tracks)
        assert better == (now < best), (before, now, best)
        best = min(best, now)
        if not improver.exploring:
            assert now == best  # back on the best plan after a restart
    assert improver.candidates is not None  # the relaxed schedule was searched
    assert best == (17, 17)
