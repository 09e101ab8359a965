"""One problem, three readings (issue 45): C relaxes B, B relaxes A, so the anytime planner of
B or C also makes a first plan under the stronger reading and keeps it when it is shorter.

The floor (``helpers.worlds.world``): station (1,1), highway (2,1), the robot on (3,1) (a
storage cell), shelf 1 on (2,2) under the highway, holding products 1 and 2; order 1 asks
both at the station.  Every plan derived here by hand:

- the robot fetches the shelf: W to (2,1) (1), S under the shelf (2), lift (3), N (4), W
  onto the station (5), and delivers from step 6;
- under B's reading it delivers line (1,1) at 6 and line (1,2) at 7; read as C, the
  delivery at 6 closes both lines (the shelf holds both products), so the one at 7 closes
  nothing and is left out: the robot just stands on the station at step 7;
- then, in a first plan (which never parks on a station), it takes the shelf off the station
  to a cell two moves away ((2,2), its own cell, or (3,1), the only spare storage cell): 9.

Splitting a line in A: shelves 1 and 2 hold one unit of product 1 each and the order asks
two; tracks that deliver one unit from each are, read as B, a plan whose first delivery
closes the line and whose second one is left out.
"""

from __future__ import annotations

import time

from helpers.worlds import world

from asprilo.bounds import Floor
from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings.anytime import search
from asprilo.encodings.anytime.errands import Task
from asprilo.encodings.anytime.grid import Grid
from asprilo.encodings.anytime.plans import plan_of
from asprilo.encodings.anytime.reservations import Track
from asprilo.encodings.anytime.work import Work
from asprilo.encodings.solving.bounds import LowerBounds
from asprilo.encodings.solving.watch import Watch


def one_shelf():
    return world("P#R/ S", products={1: {1: 1}, 2: {1: 1}}, orders={1: ({1: 1, 2: 1}, 1)})


def _run(instance, domain: Domain) -> search._Run:
    """A run of the planner with a generous hang guard, its own reading's work assigned."""
    run = search._Run(instance, domain, Watch(600, clock=time.perf_counter), LowerBounds(6), None)
    run.work = Work(instance, domain, Grid(Floor(instance.cells)), 6)
    assert run.work.assign(1.0, lambda: False)
    return run


def _late(robot: int, finish: int, at) -> dict[int, Track]:
    """An own first plan that does nothing useful until it moves once at step ``finish``."""
    return {robot: Track(robot, [at] * finish + [(2, 1)])}


def _deliveries(plan) -> list[tuple]:
    return sorted((a.step, a.args) for a in plan.actions if a.name == "deliver")


def test_c_takes_the_b_readings_first_plan_when_it_is_shorter():
    instance = one_shelf()
    run = _run(instance, Domain.C)
    improver = search._stronger_reading(run, Grid(Floor(instance.cells)), "python", _late(1, 99, (3, 1)), 600, 0)
    assert improver is not None and run.work.domain is Domain.B
    assert run.result.stats["reading"] == "B"
    reported = run.result.history[-1]
    assert _deliveries(reported.plan) == [(6, (1, 1))]
    assert reported.makespan == 9
    assert check(instance, reported.plan, Domain.C).valid
    assert [task.name for task in improver.table.tracks[1].done.values()] == ["pickup", "deliver", "deliver"]


def test_c_keeps_its_own_first_plan_when_the_b_reading_is_not_shorter():
    instance = one_shelf()
    run = _run(instance, Domain.C)
    own = {1: Track(1, [(3, 1), (2, 1), (2, 2), (2, 2), (2, 1), (1, 1), (1, 1), (2, 1), (2, 2)],
                    {3: Task("pickup", ((2, 2),), False, 1)})}  # finishes at 8, as C's own plan does
    assert search._stronger_reading(run, Grid(Floor(instance.cells)), "python", own, 600, 0) is None
    assert run.work.domain is Domain.C and run.result.history == [] and "reading" not in run.result.stats


def test_a_and_m_have_no_stronger_reading():
    instance = one_shelf()
    run = _run(instance, Domain.A)
    assert search._stronger_reading(run, Grid(Floor(instance.cells)), "python", _late(1, 99, (3, 1)), 600, 0) is None


def test_an_a_reading_split_line_is_a_b_plan_with_one_delivery():
    instance = world("P#R/SS", products={1: {1: 1, 2: 1}}, orders={1: ({1: 2}, 1)})
    # shelf 1 on (1,2) under the station, shelf 2 on (2,2) under the highway
    lift = Task("pickup", ((2, 2),), False, 2)
    give = Task("deliver", ((1, 1),), True, 2, (1, 1, 1), ((1, 1),))
    down = Task("putdown", ((2, 2),), True, 2)
    lift_1 = Task("pickup", ((1, 2),), False, 1)
    give_1 = Task("deliver", ((1, 1),), True, 1, (1, 1, 1), ((1, 1),))
    # W (1), S (2), lift 2 (3), N (4), W (5), deliver (6), E (7), S (8), put down (9), W under
    # shelf 1 (10), lift (11), N onto the station (12), deliver (13)
    cells = [(3, 1), (2, 1), (2, 2), (2, 2), (2, 1), (1, 1), (1, 1), (2, 1), (2, 2), (2, 2), (1, 2), (1, 2), (1, 1),
             (1, 1)]
    tracks = {1: Track(1, cells, {3: lift, 6: give, 9: down, 11: lift_1, 13: give_1})}
    as_a = plan_of(tracks, instance, Domain.A)
    assert _deliveries(as_a) == [(6, (1, 1, 1)), (13, (1, 1, 1))]
    assert check(instance, as_a, Domain.A).valid
    as_b = plan_of(tracks, instance, Domain.B)
    assert _deliveries(as_b) == [(6, (1, 1))]
    assert check(instance, as_b, Domain.B).valid
