"""Online runs without a window (asprilo/online/run.py) and their figures (metrics.py), on a
corridor whose minimal plans are unique, so every figure is derived by hand below."""

from __future__ import annotations

import json

from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.model import Action, Plan
from asprilo.online.ceiling import ceiling, earliest_steps
from asprilo.online.metrics import Latency, PlannerCall, Window, measure
from asprilo.online.planner import encodings_planner
from asprilo.online.planning import FromScratch
from asprilo.online.run import run_online
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source

#: 5x1: picking station 1 at (1,1); robot 1 at (3,1) carries shelf 1, which holds 5 units of
#: product 1.  Order 1 asks for 1 unit, order 2 for 2.  Every minimal plan is the same: two
#: moves west, then a delivery (at the station with the shelf: one deliver action per line)
CORRIDOR = """
init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). init(object(node,3),value(at,(3,1))).
init(object(node,4),value(at,(4,1))). init(object(node,5),value(at,(5,1))).
init(object(pickingStation,1),value(at,(1,1))).
init(object(robot,1),value(at,(3,1))). init(object(robot,1),value(carries,1)).
init(object(shelf,1),value(at,(3,1))). init(object(product,1),value(on,(1,5))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
init(object(order,2),value(line,(1,2))). init(object(order,2),value(pickingStation,1)).
"""
WEST = (-1, 0)


def scratch(instance):
    """The exact search from scratch, within each call's budget."""
    return FromScratch(instance, Domain.A, lambda seconds: encodings_planner(time_limit=seconds))


def corridor():
    return read_instance(Source("corridor.lp", CORRIDOR))


def test_a_planner_as_fast_as_the_world_lets_no_robot_wait():
    """Order 2 released at step 4: the robot is at the station after step 2, delivers order 1
    at step 3; asked again after step 4, it delivers order 2's 2 units at step 5."""
    run = run_online(corridor(), Domain.A, scratch(corridor()), {2: 4}, budget=60, step_seconds=1e6)
    assert sorted(run.plan.actions) == [Action(1, 1, "move", WEST), Action(2, 1, "move", WEST),
                                        Action(3, 1, "deliver", (1, 1, 1)), Action(5, 1, "deliver", (2, 1, 2))]
    assert (run.steps, run.ended, run.waiting) == (5, "every order is done", [])
    assert [call.step for call in run.calls] == [0, 4]
    metrics = measure(corridor(), run.plan, Domain.A, run.releases, run.steps, run.calls)
    # latencies: order 1 done at 3, released at 0; order 2 done at 5, released at 4
    assert metrics.latency == Latency(2, 2.0, 3, 3)
    assert (metrics.lines, metrics.lines_done, metrics.units_done, metrics.orders_open) == (2, 2, 3, 0)
    assert metrics.lines_per_100 == 40.0 and metrics.units_per_100 == 60.0


def test_robots_wait_while_the_planner_thinks_and_those_steps_are_counted():
    """Each call takes 2.5 s of a clock the test moves, a step 1 s: 2 waiting steps a call.
    Asked after step 0, robots wait at steps 1-2, move at 3-4, deliver order 1 at 5; order 2,
    released at step 6, is planned for after step 6, robots wait at 7-8, deliver at 9."""
    readings = iter([0.0, 2.5, 100.0, 102.5])
    run = run_online(corridor(), Domain.A, scratch(corridor()), {2: 6}, budget=60, clock=readings.__next__)
    assert sorted(run.plan.actions) == [Action(3, 1, "move", WEST), Action(4, 1, "move", WEST),
                                        Action(5, 1, "deliver", (1, 1, 1)), Action(9, 1, "deliver", (2, 1, 2))]
    assert (run.steps, run.waiting) == (9, [1, 2, 7, 8])
    assert run.calls == [PlannerCall(0, 2.5), PlannerCall(6, 2.5)]
    metrics = measure(corridor(), run.plan, Domain.A, run.releases, run.steps, run.calls, len(run.waiting))
    assert metrics.latency == Latency(2, 4.0, 5, 5)  # order 1: 5 - 0; order 2: 9 - 6
    assert (metrics.calls, metrics.planner_mean, metrics.planner_max, metrics.waiting_steps) == (2, 2.5, 2.5, 4)
    assert metrics.windows == [Window(1, 9, 2, 3)]


def test_a_step_limit_ends_the_run_and_what_is_not_done_stays_open():
    readings = iter([0.0, 2.5])
    run = run_online(corridor(), Domain.A, scratch(corridor()), {2: 6}, budget=60, steps=4,
                     clock=readings.__next__)
    assert (run.steps, run.ended, sorted(run.plan.actions)) == (
        4, "the step limit", [Action(3, 1, "move", WEST), Action(4, 1, "move", WEST)])
    metrics = measure(corridor(), run.plan, Domain.A, run.releases, run.steps, run.calls, len(run.waiting))
    # order 2 is released at step 6, after the run: not counted
    assert (metrics.lines, metrics.lines_done, metrics.orders_open, metrics.latency) == (1, 0, 1, Latency.of([]))


def test_units_count_when_delivered_and_lines_when_done():
    """A plan by hand: order 2's 2 units in two deliveries (steps 4 and 5); windows of 2 steps."""
    plan = Plan([Action(1, 1, "move", WEST), Action(2, 1, "move", WEST), Action(3, 1, "deliver", (1, 1, 1)),
                 Action(4, 1, "deliver", (2, 1, 1)), Action(5, 1, "deliver", (2, 1, 1))])
    metrics = measure(corridor(), plan, Domain.A, {}, 5, [PlannerCall(0, 0.5), PlannerCall(2, 1.5, found=False)],
                      window=2)
    assert metrics.windows == [Window(1, 2, 0, 0), Window(3, 4, 1, 2), Window(5, 5, 1, 1)]
    assert metrics.latency == Latency(2, 4.0, 5, 5) and metrics.units_done == 3
    assert (metrics.planner_mean, metrics.planner_max) == (1.0, 1.5)


def test_the_ceiling_counts_releases_trips_and_one_delivery_a_step_at_a_station():
    """The robot carries the shelf 2 cells from the station: a line is done at step 3 at the
    earliest (2 moves and the delivery); order 2 released at step 4 at step 5 at the earliest.
    Released together, the station takes the second delivery a step after the first."""
    assert earliest_steps(corridor(), Domain.A, {2: 4}) == {(1, 1): 3.0, (2, 1): 5.0}
    assert [ceiling(corridor(), Domain.A, {2: 4}, steps).lines for steps in (2, 3, 4, 5, 9)] == [0, 1, 1, 2, 2]
    assert [ceiling(corridor(), Domain.A, {}, steps).lines for steps in (2, 3, 4)] == [0, 1, 2]
    assert ceiling(corridor(), Domain.A, {2: 4}, 5).lines_per_100 == 40.0  # the first run above meets it
    # C: one delivery may close several lines, so the station's capacity is not counted
    assert ceiling(corridor(), Domain.C, {}, 3).lines == 2
    # M: the robot stands under the shelf from the start; a line is known after step 0
    assert earliest_steps(corridor(), Domain.M, {}) == {(1, 1): 1.0, (2, 1): 1.0}


def test_the_command_writes_the_plan_the_record_and_the_figures(tmp_path, capsys):
    scenario = tmp_path / "corridor.lp"
    scenario.write_text(CORRIDOR)
    plan, record = tmp_path / "run.lp", tmp_path / "run.json"
    assert main(["online", str(scenario), "--at", "4:2", "--planner", "asp", "--budget", "60", "-o", str(plan),
                 "--record", str(record), "--json"]) == 0
    out, err = capsys.readouterr()
    figures = json.loads(out)
    # the first test's run, figures derived there
    assert (figures["lines_done"], figures["units_done"], figures["lines_per_100"], figures["latency"]) == (
        2, 3, 40.0, {"orders": 2, "mean": 2.0, "p95": 3, "max": 3})
    assert (figures["ceiling_lines"], figures["waiting_steps"], figures["planner"]["calls"]) == (2, 0, 2)
    assert read_plan(str(plan)).actions == [Action(1, 1, "move", WEST), Action(2, 1, "move", WEST),
                                            Action(3, 1, "deliver", (1, 1, 1)), Action(5, 1, "deliver", (2, 1, 2))]
    kept = json.loads(record.read_text())
    assert (kept["steps"], kept["ended"], kept["releases"], [c["step"] for c in kept["calls"]]) == (
        5, "every order is done", {"1": 0, "2": 4}, [0, 4])
    assert err.splitlines()[0] == "online run: 5 steps (every order is done); 2 planner calls, 0 waiting steps"
    assert err.splitlines()[1] == ("throughput: 40.0 order lines per 100 steps; ceiling 40.0: 100 % of it; "
                                   "60.0 units per 100 steps (2 of 2 lines done)")


def test_the_command_refuses_bad_release_steps_in_words(tmp_path, capsys):
    scenario = tmp_path / "corridor.lp"
    scenario.write_text(CORRIDOR)
    assert main(["online", str(scenario), "--at", "x:2"]) == 2
    assert capsys.readouterr().err == "error: --at x:2: expected STEP:ORDER[,ORDER...], e.g. --at 3:2\n"
    assert main(["online", str(scenario), "--at", "3:9"]) == 2
    assert capsys.readouterr().err == "error: the instance has no order 9\n"
    assert main(["online", str(scenario), "--replan", "often"]) == 2
    assert capsys.readouterr().err == "error: --replan often: expected 'arrival' or a number of steps\n"
