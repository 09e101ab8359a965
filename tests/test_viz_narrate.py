"""A step in one sentence (the presentation mode's words): exact sentences on small plans
whose states are derived by hand, for every action kind, several actions at a step, and
broken rules in words; the plan's verdict."""

from __future__ import annotations

import pytest
from helpers import SMALL_A, WRONG_OUTCOME
from helpers.worlds import plan, walk, world

from asprilo.domain import Domain
from asprilo.reader import read_instance, read_plan
from asprilo.visualizer.state.narrate import narrate, verdict
from asprilo.visualizer.state.track import Track


def story(track: Track) -> list[str]:
    return [narrate(track, step) for step in range(track.horizon + 1)]


def station_world(quantities: bool = True, lines: dict | None = None, stock: dict | None = None):
    """``P.B/...``: picking station 1 at (1,1), robot 1 under shelf 1 at (3,1)."""
    unit = (lambda n: n) if quantities else (lambda n: None)
    stock = stock or {1: {1: unit(3)}, 2: {1: unit(2)}}
    lines = lines or {1: ({1: unit(2)}, 1), 2: ({2: unit(1)}, 1)}
    return world("P.B/...", products=stock, orders=lines)


def test_a_valid_plan_told_step_by_step():
    # robot 1 lifts shelf 1, carries it two cells left onto the station and hands over
    # 2 units of product 1 (order 1), then 1 unit of product 2 (order 2)
    track = Track(station_world(), plan((1, 1, "pickup"), (2, 1, "W"), (3, 1, "W"), (4, 1, "deliver", (1, 1, 2)),
                                        (5, 1, "deliver", (2, 2, 1))), Domain.A)
    assert story(track) == [
        "step 0: the initial state",
        "step 1: robot 1 picks up shelf 1 at (3,1)",
        "step 2: robot 1 moves left to (2,1) with shelf 1",
        "step 3: robot 1 moves left to (1,1) with shelf 1",
        "step 4: robot 1 delivers 2 units of product 1 at station 1 for order 1",
        "step 5: robot 1 delivers 1 unit of product 2 at station 1 for order 2"]
    assert verdict(track) == "valid plan"


def test_moves_in_every_direction_with_and_without_a_shelf():
    track = Track(world("...../..B../....."), plan(*walk(1, "NSEW"), (5, 1, "pickup"), *walk(1, "ES", start=6),
                                                   (8, 1, "putdown"), *walk(1, "N", start=9)), Domain.A)
    assert story(track)[1:] == [
        "step 1: robot 1 moves up to (3,1)", "step 2: robot 1 moves down to (3,2)",
        "step 3: robot 1 moves right to (4,2)", "step 4: robot 1 moves left to (3,2)",
        "step 5: robot 1 picks up shelf 1 at (3,2)", "step 6: robot 1 moves right to (4,2) with shelf 1",
        "step 7: robot 1 moves down to (4,3) with shelf 1", "step 8: robot 1 puts down shelf 1 at (4,3)",
        "step 9: robot 1 moves up to (4,2)"]


def test_b_delivers_a_whole_line():
    steps = ((1, 1, "pickup"), (2, 1, "W"), (3, 1, "W"), (4, 1, "deliver", (1, 1)), (5, 1, "deliver", (2, 2, 7)))
    with_units = Track(station_world(), plan(*steps), Domain.B)
    assert story(with_units)[4:] == [
        "step 4: robot 1 delivers product 1 at station 1 for order 1 (the whole line: 2 units)",
        "step 5: robot 1 delivers product 2 at station 1 for order 2 (the whole line: 1 unit)"]  # B ignores 7
    without = Track(station_world(quantities=False), plan(*steps), Domain.B)
    assert story(without)[4] == "step 4: robot 1 delivers product 1 at station 1 for order 1 (the whole line)"
    assert verdict(with_units) == verdict(without) == "valid plan"


def test_c_delivery_closes_every_line_of_the_station_the_shelf_holds():
    # shelf 1 holds products 1, 2 and 3; orders 1 (products 1, 2) and 2 (products 2, 3) wait at
    # station 1: one delivery closes all four lines
    instance = station_world(quantities=False, stock={1: {1: None}, 2: {1: None}, 3: {1: None}},
                             lines={1: ({1: None, 2: None}, 1), 2: ({2: None, 3: None}, 1)})
    track = Track(instance, plan((1, 1, "pickup"), (2, 1, "W"), (3, 1, "W"), (4, 1, "deliver", (1, 1))), Domain.C)
    assert narrate(track, 4) == ("step 4: robot 1 delivers product 1 at station 1 for order 1, closing 4 lines: "
                                 "order 1 products 1 and 2, order 2 products 2 and 3")
    assert verdict(track) == "valid plan"


def test_a_broken_rule_of_a_named_action_is_a_clause_of_it():
    track = Track(station_world(), plan(
        (1, 1, "deliver", (1, 1, 2)),                 # no shelf, and not at order 1's station
        (2, 1, "pickup"), (3, 1, "pickup"),           # the second while carrying shelf 1
        (4, 1, "N"),                                  # off the floor, shelf and all
        (5, 1, "fly", (1, 0)),                        # no such action
        (6, 1, "E"), (6, 1, "W"),                     # two actions at once
        (7, ("shelf", 1), "E"),                       # a shelf does not act
        (8, 1, "S")), Domain.A)
    assert story(track)[1:8] == [
        "step 1: robot 1 delivers 2 units of product 1 at (3,1) for order 1, but it carries no shelf "
        "and order 1 goes to picking station 1 at (1,1)",
        "step 2: robot 1 picks up shelf 1 at (3,1)",
        "step 3: robot 1 picks up at (3,1), but it already carries shelf 1",
        "step 4: robot 1 moves up to (3,0) with shelf 1, which is not a floor node",
        "step 5: robot 1 does fly(1,0), which is not an action of domain A",
        "step 6: robot 1 does 2 actions at once (move(1,0), move(-1,0)); a robot does at most one action per step",
        "step 7: shelf 1 does move(1,0); rule broken: the plan gives shelf 1 the action move(1,0), but only "
        "robots act"]
    # the horizon: nothing delivered, so both orders lack everything
    assert narrate(track, 8) == ("step 8: robot 1 moves down to (3,1) with shelf 1; 2 rules broken: order 1 still "
                                 "lacks 2 units of product 1; order 2 still lacks 1 unit of product 2")
    assert verdict(track) == "invalid plan: 9 rule violations (first at step 1)"


def test_a_broken_rule_that_does_not_go_on_from_the_action_follows_it():
    # a highway at (1,1), robot 1 under shelf 1 at (2,1): the shelf is put down on the highway
    track = Track(world("#B"), plan((1, 1, "pickup"), (2, 1, "W"), (3, 1, "putdown")), Domain.A)
    assert narrate(track, 3) == ("step 3: robot 1 puts down shelf 1 at (1,1); rule broken: robot 1 puts shelf 1 "
                                 "down on the highway node (1,1)")


def test_many_actions_the_most_relevant_named_and_the_others_counted():
    # four robots in a row (1,1)..(4,1); a shelf at (3,2)
    track = Track(world("RRRR/..S./...."), plan(
        (1, 1, "S"), (1, 2, "S"), (1, 3, "pickup"), (1, 4, "putdown"),   # 3 and 4 break rules
        (2, 1, "S"), (2, 2, "S"), (2, 3, "E"), (2, 4, "W"),              # 3 and 4 swap
        (3, 1, "N")), Domain.A)
    assert story(track)[1:] == [
        "step 1: robot 3 picks up at (3,1), but no shelf rests there; robot 4 puts down at (4,1), but it carries "
        "no shelf; and 2 more moves",
        "step 2: robot 3 moves right to (4,1), robot 4 moves left to (3,1) and 2 more moves; rule broken: robots 3 "
        "and 4 swap nodes (3,1) and (4,1)",
        "step 3: robot 1 moves up to (1,2)"]
    # no rule broken: deliveries, pickups and putdowns come before moves, lower ids first
    pickups = Track(world("BBRB/..../...."), plan((1, 1, "pickup"), (1, 2, "pickup"), (1, 3, "S"), (1, 4, "pickup")),
                    Domain.A)
    assert narrate(pickups, 1) == ("step 1: robot 1 picks up shelf 1 at (1,1), robot 2 picks up shelf 2 at (2,1) "
                                   "and 2 more actions")
    three = Track(world("RRR/..."), plan(*[(1, robot, "S") for robot in (1, 2, 3)]), Domain.A)
    assert narrate(three, 1) == ("step 1: robot 1 moves down to (1,2), robot 2 moves down to (2,2) and robot 3 "
                                 "moves down to (3,2)")
    four = Track(world("RRRR/...."), plan(*[(1, robot, "S") for robot in (1, 2, 3, 4)]), Domain.A)
    assert narrate(four, 1) == "step 1: robot 1 moves down to (1,2), robot 2 moves down to (2,2) and 2 more moves"


def test_waiting_steps_and_the_initial_state():
    track = Track(world("R.."), plan((1, 1, "E"), (3, 1, "E")), Domain.M)
    assert story(track) == ["step 0: the initial state", "step 1: robot 1 moves right to (2,1)",
                            "step 2: every robot waits", "step 3: robot 1 moves right to (3,1)"]
    assert narrate(track, 7) == narrate(track, 3) and narrate(track, -1) == narrate(track, 0)  # clamped
    assert verdict(track) == "valid plan"  # M without orders: nothing to do


def test_the_instances_problems_at_step_0_and_verdicts_without_a_plan():
    instance = world("S#/R.")
    instance.shelves[1].at = (2, 1)  # a shelf resting on the highway
    track = Track(instance, plan(), Domain.B)
    assert narrate(track, 0) == "step 0: the initial state; rule broken: shelf 1 rests on the highway node (2,1)"
    assert verdict(track) == "no plan; the instance breaks 1 rule"
    assert verdict(Track(read_instance(SMALL_A), plan(), unfinished=True)) == "no plan"


def test_more_broken_rules_than_are_said():
    # three robots end on their own cells, but three lines are open: three goal violations
    instance = world("P.B", products={1: {1: 1}, 2: {1: 1}, 3: {1: 1}},
                     orders={1: ({1: 1, 2: 1, 3: 1}, 1)})
    track = Track(instance, plan((1, 1, "W")), Domain.A)
    assert narrate(track, 1) == ("step 1: robot 1 moves left to (2,1); 3 rules broken: order 1 still lacks 1 unit of "
                                 "product 1; order 1 still lacks 1 unit of product 2; and 1 more")


def test_an_unfinished_plan_so_far():
    instance = station_world()
    track = Track(instance, plan((1, 1, "pickup")), Domain.A, unfinished=True)  # online: the goal is not judged
    assert verdict(track, unfinished=True) == "no rule broken so far"


@pytest.mark.parametrize("step, sentence", [
    (8, "step 8: robot 3 delivers 1 unit of product 4 at station 1 for order 1, robot 1 picks up shelf 2 at (5,3) "
        "and robot 2 moves right to (6,4)"),
    (23, "step 23: robot 1 delivers 6 units of product 5 at station 2 for order 2, but the order needs only 5 more "
         "and shelf 2 holds only 5; robot 2 moves left to (4,1) with shelf 3; and robot 3 moves up to (7,1) with "
         "shelf 9"),
    (29, "step 29: robot 1 puts down shelf 2 at (7,4), robot 2 puts down shelf 3 at (4,3) and robot 3 puts down "
         "shelf 9 at (7,3); rule broken: order 1 still lacks 1 unit of product 2"),
])
def test_the_wrong_outcome_example(step, sentence):
    track = Track(read_instance(WRONG_OUTCOME), read_plan(WRONG_OUTCOME))
    assert narrate(track, step) == sentence
    assert verdict(track) == "invalid plan: 3 rule violations (first at step 23)"
