"""The plain-Python simulator: states after every step, effects of invalid actions, violations."""

from __future__ import annotations

import random

import pytest
from helpers import EXAMPLES, OUTCOME, SMALL_A, WRONG_OUTCOME
from helpers.worlds import plan, walk, world

from asprilo.domain import Domain
from asprilo.model import Product
from asprilo.reader import read_instance, read_plan
from asprilo.simulate import State, Violation, simulate

B_INSTANCE = EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.lp"
B_PLAN = EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan"


@pytest.fixture(scope="module")
def small_a():
    return read_instance(SMALL_A)


def test_outcome_is_valid_and_ends_with_every_order_fulfilled(small_a):
    timeline = simulate(small_a, read_plan(OUTCOME))
    assert (timeline.domain, timeline.horizon, timeline.valid, timeline.violations) == (Domain.A, 29, True, [])
    final = timeline.state(29)
    assert final.open_lines == {}
    assert final.carries == {}
    assert final.robots == {1: (7, 4), 2: (4, 3), 3: (7, 3)}
    # product 5: 10 units on each of shelves 1 and 2, order 2 took all 20
    assert final.stock[(1, 5)] == 0 and final.stock[(2, 5)] == 0
    assert final.stock[(1, 3)] == 7


def test_wrong_outcome_reports_exactly_the_over_delivery_and_the_missing_unit(small_a):
    timeline = simulate(small_a, read_plan(WRONG_OUTCOME))
    assert not timeline.valid
    assert [v.atom for v in timeline.violations] == [
        "err(deliver,orderAmount,(1,23))",
        "err(deliver,shelfAmount,(1,23))",
        "err(goal,unfilledOrder,(1,2,1,29))",
    ]
    assert [v.message for v in timeline.violations] == [
        "step 23: robot 1 delivers 6 units of product 5 for order 2, but the order needs only 5 more",
        "step 23: robot 1 delivers 6 units of product 5 for order 2, but shelf 2 holds only 5",
        "step 29 (the horizon): order 1 still lacks 1 unit of product 2",
    ]
    first = timeline.violations[0]
    assert (first.module, first.check, first.params, first.step, first.robots) == \
        ("deliver", "orderAmount", (1, 23), 23, (1,))
    # the over-delivery completes the line and empties the shelf: no further consequences
    assert timeline.state(23).open_lines.get((2, 5)) is None
    assert timeline.state(23).stock[(2, 5)] == 0


def test_b_plan_puts_shelves_down_on_highways_three_times():
    timeline = simulate(read_instance(B_INSTANCE), read_plan(B_PLAN))
    assert timeline.domain is Domain.B
    assert [v.atom for v in timeline.violations] == [
        "err(putdown,onHighway,(9,44))", "err(putdown,onHighway,(8,45))", "err(putdown,onHighway,(10,45))"]
    assert timeline.violations[0].message == "step 44: robot 9 puts shelf 148 down on the highway node (33,1)"
    # the shelf rests where it was put down, all the same
    assert timeline.state(44).shelves[148] == (33, 1)


def test_state_zero_is_the_instance_and_later_steps_repeat_the_final_state(small_a):
    timeline = simulate(small_a, read_plan(OUTCOME))
    start = timeline.state(0)
    assert start == State(0, {r.id: r.at for r in small_a.robots.values()}, {},
                          {s.id: s.at for s in small_a.shelves.values()},
                          {(s, p.id): u for p in small_a.products.values() for s, u in p.stock.items()},
                          {(o.id, p): u for o in small_a.orders.values() for p, u in o.lines.items()})
    late = timeline.state(100)
    assert late.step == 100
    final = timeline.state(29)
    assert (late.robots, late.shelves, late.stock, late.open_lines) == \
        (final.robots, final.shelves, final.stock, final.open_lines)


def test_random_access_gives_the_same_states_as_sequential_access(small_a):
    sequential = [simulate(small_a, read_plan(WRONG_OUTCOME)).state(t) for t in range(30)]
    timeline = simulate(small_a, read_plan(WRONG_OUTCOME))
    steps = list(range(30)) * 2
    random.Random(4).shuffle(steps)
    for t in steps:
        assert timeline.state(t) == sequential[t]


def test_a_carried_shelf_moves_with_its_robot_and_states_are_independent_copies():
    instance = world("B../...")
    timeline = simulate(instance, plan((1, 1, "pickup"), *walk(1, "ES", 2), (4, 1, "putdown")), Domain.A)
    assert timeline.valid
    assert [timeline.state(t).shelves[1] for t in range(5)] == [(1, 1), (1, 1), (2, 1), (2, 2), (2, 2)]
    assert [timeline.state(t).carries for t in range(5)] == [{}, {1: 1}, {1: 1}, {1: 1}, {}]
    state = timeline.state(2)
    state.carries.clear()
    assert timeline.state(2).carries == {1: 1}


def test_moves_take_effect_even_off_the_floor():
    timeline = simulate(world("R."), plan(*walk(1, "NSS")))
    assert [timeline.state(t).robots[1] for t in range(4)] == [(1, 1), (1, 0), (1, 1), (1, 2)]
    assert [v.atom for v in timeline.violations] == ["err(move,offFloor,(1,1))", "err(move,offFloor,(1,3))"]


def test_a_failed_pickup_changes_nothing():
    timeline = simulate(world("R.S"), plan((1, 1, "pickup")), Domain.A)
    assert [v.atom for v in timeline.violations] == ["err(pickup,noShelf,(1,1))"]
    assert timeline.state(1).carries == {}


def test_an_order_line_closes_in_b_and_every_matching_line_at_the_station_closes_in_c():
    instance = world("BP", products={1: {1: None}, 2: {1: None}},
                     orders={1: ({1: None}, 1), 2: ({2: None, 3: None}, 1)})
    instance.products[3] = Product(3, {9: None})  # on no shelf of the instance
    steps = plan((1, 1, "pickup"), (2, 1, "E"), (3, 1, "deliver", (1, 1)))
    b = simulate(instance, steps, Domain.B)
    assert b.state(3).open_lines == {(2, 2): None, (2, 3): None}
    c = simulate(instance, steps, Domain.C)
    assert c.state(3).open_lines == {(2, 3): None}
    assert [v.atom for v in c.violations] == ["err(instance,unknownProduct,(2,3,0))",
                                              "err(goal,unfilledOrder,(2,3,1,3))"]


def test_m_lines_are_open_until_a_robot_stands_under_the_shelf():
    instance = world("R.S", products={1: {1: 1}}, orders={1: ({1: 1}, None)})
    timeline = simulate(instance, plan(*walk(1, "EE")))
    assert timeline.domain is Domain.M and timeline.valid
    assert [timeline.state(t).open_lines for t in range(3)] == [{(1, 1): 1}, {(1, 1): 1}, {}]


def test_violations_are_sorted_and_carry_their_atom():
    timeline = simulate(world("RR"), plan((2, 1, "E"), (1, ("shelf", 4), "move", (1, 0)), (1, 7, "E")))
    atoms = [v.atom for v in timeline.violations]
    assert atoms == ["err(action,notRobot,(shelf,4,1))", "err(action,unknownRobot,(7,1))",
                     "err(collision,sameNode,(1,2,2))"]
    assert Violation("goal", "unfilledOrder", (1, 2, 3, 4), 4, "m").atom == "err(goal,unfilledOrder,(1,2,3,4))"
