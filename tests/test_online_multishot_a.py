"""Domain A's multi-shot online planner (asprilo/online/multishot_a.py, tasks.py and
asprilo/encodings/online/a*.lp), every figure derived by hand below."""

from __future__ import annotations

import threading
from pathlib import Path

import pytest

from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Action
from asprilo.online.metrics import measure
from asprilo.online.multishot_a import MultiShotA
from asprilo.online.planning import multishot
from asprilo.online.run import run_online, scenario_of
from asprilo.online.tasks import Floor, Task, assign_tasks
from asprilo.reader import read_instance
from asprilo.sources import Source

EXAMPLE = Path(__file__).resolve().parent.parent / "examples/asprilo/dom-a/small" / \
    "x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"

#: 5x1, domain A: robot 1 at (1,1), shelf 1 at (3,1) with 2 units of product 1, picking
#: station 1 at (5,1).  Order 1 asks for 1 unit of product 1 at station 1 (released at 0),
#: order 2 for 1 more (released at 2).
CORRIDOR = """
init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). init(object(node,3),value(at,(3,1))).
init(object(node,4),value(at,(4,1))). init(object(node,5),value(at,(5,1))).
init(object(pickingStation,1),value(at,(5,1))).
init(object(robot,1),value(at,(1,1))).
init(object(shelf,1),value(at,(3,1))).
init(object(product,1),value(on,(1,2))).
init(object(order,1),value(line,(1,1))). init(object(order,1),value(pickingStation,1)).
init(object(order,2),value(line,(1,1))). init(object(order,2),value(pickingStation,1)).
"""
EAST, WEST = (1, 0), (-1, 0)


def corridor():
    return read_instance(Source("corridor.lp", CORRIDOR))


def test_a_task_is_carried_out_step_by_step():
    """Order 1 alone.  The robot walks 2 cells to the shelf (steps 1, 2), picks it up (3),
    carries it 2 cells to the station (4, 5), delivers (6): the line is done at step 6,
    latency 6.  The first call aims at the pickup (3 steps away: within the window) and plans
    3 + SLACK = 7 steps; its first model follows the hints, so step 7 heads back west.  When
    that plan has been carried out every order is done: the run asks nothing more (the shelf
    stays on the robot)."""
    instance = corridor()
    instance.orders.pop(2)
    run = run_online(instance, Domain.A, MultiShotA(instance, Domain.A), {1: 0}, budget=60, steps=10)
    assert run.plan.actions == [
        Action(1, 1, "move", EAST), Action(2, 1, "move", EAST), Action(3, 1, "pickup", ()),
        Action(4, 1, "move", EAST), Action(5, 1, "move", EAST), Action(6, 1, "deliver", (1, 1, 1)),
        Action(7, 1, "move", WEST)]
    assert [call.step for call in run.calls] == [0]
    assert run.waiting == []
    metrics = measure(scenario_of(instance, run.releases), run.plan, Domain.A, run.releases, run.steps, run.calls, 0)
    assert (metrics.lines_done, metrics.latency.mean, metrics.latency.most) == (1, 6, 6)
    assert check(instance, run.plan, Domain.A, bound=None).valid


def test_a_release_while_every_robot_is_busy_answers_the_plan_under_way_without_solving():
    """Order 2 comes after step 2, while the only robot works for order 1: no task can be
    given, so the call answers what is left of the plan (steps 3-7 of the first one, moved
    to 1-5) without a solve call."""
    instance = corridor()
    planner = MultiShotA(instance, Domain.A)
    planner.released([instance.orders[1]], 0)
    first = planner.plan(0, 60, threading.Event())
    solves = planner.solves
    for step in (1, 2):
        planner.carried_out(step, [a._replace(step=step) for a in first.actions if a.step == step])
    planner.released([instance.orders[2]], 2)
    rest = planner.plan(2, 60, threading.Event())
    assert planner.solves == solves
    assert rest.actions == [a._replace(step=a.step - 2) for a in first.actions if a.step > 2]


def test_the_run_serves_the_second_order_after_the_shelf_is_back():
    """Both orders: the robot delivers order 1 at step 6 (as above; the call after step 2
    keeps that plan).  Order 2 being open when the plan runs out after step 7, the run asks
    again: one cell west (8), the put-down on the shelf's own cell (9).  The call after step 9
    gives the robot order 2 (1 unit left on the shelf it stands under): pickup (10), two cells
    east (11, 12), delivery (13).  Order 2 was released at step 2: latency 11; order 1's 6."""
    instance = corridor()
    run = run_online(instance, Domain.A, MultiShotA(instance, Domain.A), {1: 0, 2: 2}, budget=60)
    delivered = [(a.step, a.args) for a in run.plan.actions if a.name == "deliver"]
    assert delivered == [(6, (1, 1, 1)), (13, (2, 1, 1))]
    metrics = measure(scenario_of(instance, run.releases), run.plan, Domain.A, run.releases, run.steps, run.calls, 0)
    assert (metrics.lines_done, metrics.latency.mean, metrics.latency.most) == (2, 8.5, 11)
    assert check(scenario_of(instance, run.releases), run.plan, Domain.A, bound=None).valid


def test_tasks_go_to_the_free_robot_and_shelf_that_bring_the_product_soonest():
    """A 6x2 floor, station at (6,1); shelf 1 at (2,2) holds 2 units of product 7, shelf 2 at
    (4,2) 5 units.  Line (1,7) asks for 3 units, line (2,7) for 1.  Robot 1 on (1,1): shelf 1
    costs 2 + 5 (walk to it, carry it to the station along row 1), shelf 2 4 + 3; robot 2 on
    (5,1): shelf 1 4 + 5, shelf 2 2 + 3.  So line (1,7) goes to robot 2 with shelf 2 (3
    units: it holds 5); line (2,7), next, to robot 1 with shelf 1 (1 unit)."""
    cells = {(x, y) for x in range(1, 7) for y in (1, 2)}
    floor = Floor(cells, {(2, 2), (4, 2)})
    tasks = assign_tasks({1: (1, 1), 2: (5, 1)}, [((1, 7), (6, 1), 3), ((2, 7), (6, 1), 1)],
                         {1: (2, 2), 2: (4, 2)}, {(1, 7): 2, (2, 7): 5}, floor)
    assert tasks == [Task(2, 2, (4, 2), (6, 1), (1, 7), 3), Task(1, 1, (2, 2), (6, 1), (2, 7), 1)]


@pytest.mark.parametrize("label", ["B", "C", "Md"])
def test_other_domains_are_refused_in_words(label):
    with pytest.raises(InputError, match=f"does not plan domain {label}"):
        multishot(corridor(), Domain.parse(label))


def test_the_command_runs_an_example_of_the_original_distribution(tmp_path, capsys):
    """The small domain-A example (3 orders, quantities, several lines), one order every 3
    steps: the plan carried out passes the checker against the scenario it ran, every order
    fulfilled."""
    scenario, plan = tmp_path / "scenario.lp", tmp_path / "plan.lp"
    assert main(["online", str(EXAMPLE), "--every", "3", "--planner", "multishot", "--scenario", str(scenario),
                 "-o", str(plan)]) == 0
    assert "every order is done" in capsys.readouterr().err
    assert main(["check", str(scenario), str(plan)]) == 0
    assert "orders fulfilled: 3 of 3" in capsys.readouterr().out
