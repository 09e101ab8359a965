"""The multi-shot ASP online planner (asprilo/online/multishot.py, asprilo/encodings/online/)
on a corridor whose shortest plans are unique, every figure derived by hand below."""

from __future__ import annotations

import json
import threading
from collections import Counter
from pathlib import Path

import clingo
import pytest

from asprilo.checker import check
from asprilo.cli import main
from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Action
from asprilo.online.metrics import Latency, PlannerCall, measure
from asprilo.online.multishot import MultiShot
from asprilo.online.planner import encodings_planner
from asprilo.online.planning import FromScratch
from asprilo.online.run import run_online, scenario_of
from asprilo.reader import read_instance
from asprilo.sources import Source

TEMPLATE = str(Path(__file__).resolve().parent.parent / "docs" / "online-template.lp")

#: 5x1, domain M: robot 1 at (1,1); shelf 1 at (3,1) holds product 1, shelf 2 at (5,1)
#: product 2.  Order 1 asks for product 1, order 2 for product 2.  A line is served when a
#: robot stands under the shelf after the order's release: every shortest plan moves east.
CORRIDOR = """
init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(2,1))). init(object(node,3),value(at,(3,1))).
init(object(node,4),value(at,(4,1))). init(object(node,5),value(at,(5,1))).
init(object(robot,1),value(at,(1,1))).
init(object(shelf,1),value(at,(3,1))). init(object(shelf,2),value(at,(5,1))).
init(object(product,1),value(on,(1,1))). init(object(product,2),value(on,(2,1))).
init(object(order,1),value(line,(1,1))). init(object(order,2),value(line,(2,1))).
"""
EAST = (1, 0)


def corridor():
    return read_instance(Source("corridor.lp", CORRIDOR))


@pytest.fixture
def parts(monkeypatch):
    """Every part grounded, as (name, arguments), by any Control."""
    grounded: list[tuple[str, tuple]] = []
    ground = clingo.Control.ground

    def counting(self, parts=(("base", ()),), context=None):
        grounded.extend((name, tuple(str(a) for a in args)) for name, args in parts)
        return ground(self, parts, context)

    monkeypatch.setattr(clingo.Control, "ground", counting)
    return grounded


def test_a_run_plans_each_release_and_grounds_every_part_once(parts):
    """After step 0 order 1 is open: the robot is 2 cells from shelf 1 (moves at 1, 2, order 1
    done at 2).  Order 2, released at step 4, is planned after step 4: 2 cells to shelf 2
    (moves at 5, 6, done at 6).  Both calls look 2 steps ahead: steps 1-2 and check(2) are
    grounded by the first and used again by the second."""
    planner = MultiShot(corridor(), Domain.M)
    run = run_online(corridor(), Domain.M, planner, {2: 4}, budget=60, step_seconds=1e6)
    assert run.plan.actions == [Action(1, 1, "move", EAST), Action(2, 1, "move", EAST),
                                Action(5, 1, "move", EAST), Action(6, 1, "move", EAST)]
    assert (run.steps, run.ended, run.waiting, [call.step for call in run.calls]) == (
        6, "every order is done", [], [0, 4])
    assert planner.done == {(1, 1): 2, (2, 2): 6}
    assert Counter(parts) == Counter([("base", ()), ("line", ("1", "1", "1", "0", "0")), ("step", ("1",)),
                                      ("step", ("2",)), ("check", ("2",)), ("line", ("2", "2", "1", "0", "4"))])
    metrics = measure(scenario_of(corridor(), run.releases), run.plan, Domain.M, run.releases, run.steps, run.calls)
    assert metrics.latency == Latency(2, 2.0, 2, 2)  # 2 - 0 and 6 - 4
    assert (metrics.lines, metrics.lines_done, metrics.orders_open) == (2, 2, 0)
    assert check(scenario_of(corridor(), run.releases), run.plan, Domain.M).valid


def test_robots_wait_while_the_planner_thinks():
    """Each call takes 2.5 s of a clock the test moves, a step 1 s: robots wait at steps 1-2,
    move at 3-4 (order 1 done at 4); order 2, released at step 6, is planned after step 6,
    robots wait at 7-8, move at 9-10 (done at 10)."""
    readings = iter([0.0, 2.5, 100.0, 102.5])
    run = run_online(corridor(), Domain.M, MultiShot(corridor(), Domain.M), {2: 6}, budget=60,
                     clock=readings.__next__)
    assert run.plan.actions == [Action(3, 1, "move", EAST), Action(4, 1, "move", EAST),
                                Action(9, 1, "move", EAST), Action(10, 1, "move", EAST)]
    assert (run.steps, run.waiting, run.calls) == (10, [1, 2, 7, 8], [PlannerCall(0, 2.5), PlannerCall(6, 2.5)])
    metrics = measure(scenario_of(corridor(), run.releases), run.plan, Domain.M, run.releases, run.steps, run.calls,
                      len(run.waiting))
    assert metrics.latency == Latency(2, 4.0, 4, 4)  # 4 - 0 and 10 - 6
    assert (metrics.waiting_steps, metrics.planner_mean) == (4, 2.5)


def test_the_same_plan_as_planning_from_scratch():
    """Both planners are exact here, and the shortest plans are unique."""
    scratch = FromScratch(corridor(), Domain.M, lambda seconds: encodings_planner(time_limit=seconds))
    ours = run_online(corridor(), Domain.M, MultiShot(corridor(), Domain.M), {2: 4}, budget=60, step_seconds=1e6)
    theirs = run_online(corridor(), Domain.M, scratch, {2: 4}, budget=60, step_seconds=1e6)
    assert ours.plan.actions == theirs.plan.actions
    assert ours.steps == theirs.steps == 6


def test_a_call_searches_the_shortest_horizon_from_where_the_robots_stand():
    """Both orders at step 0: the robot serves product 1 on its way to product 2 (4 steps);
    after step 1 (the robot at (2,1)) 3 steps are left; line 1 is done at step 2 (under
    shelf 1), line 2 at step 4, and then there is nothing to plan."""
    planner = MultiShot(corridor(), Domain.M)
    planner.released(list(corridor().orders.values()), 0)
    assert planner.lower_bound() == 4
    assert len(planner.plan(0, 60, threading.Event()).actions) == 4
    planner.carried_out(1, [Action(1, 1, "move", EAST)])
    assert planner.plan(1, 60, threading.Event()).actions == [Action(k, 1, "move", EAST) for k in (1, 2, 3)]
    for step in (2, 3, 4):
        planner.carried_out(step, [Action(step, 1, "move", EAST)])
    assert planner.done == {(1, 1): 2, (2, 2): 4} and planner.plan(4, 60, threading.Event()).actions == []


def test_a_cancelled_call_answers_nothing():
    planner = MultiShot(corridor(), Domain.M)
    planner.released(list(corridor().orders.values()), 0)
    cancel = threading.Event()
    cancel.set()
    assert planner.plan(0, 60, cancel) is None


def test_only_domain_m(tmp_path):
    with pytest.raises(InputError, match="the multi-shot planner of domain M does not plan domain A"):
        MultiShot(corridor(), Domain.A)


@pytest.mark.parametrize("encoding", [[], ["--encoding", TEMPLATE]])
def test_the_command_runs_the_reference_encoding_and_the_template(tmp_path, capsys, encoding):
    scenario = tmp_path / "corridor.lp"
    scenario.write_text(CORRIDOR)
    plan = tmp_path / "run.lp"
    assert main(["online", str(scenario), "--at", "4:2", "--domain", "m", "--planner", "multishot", "--budget", "60",
                 "-o", str(plan), "--json", *encoding]) == 0
    figures = json.loads(capsys.readouterr().out)
    # the first test's run
    assert (figures["lines_done"], figures["latency"], figures["waiting_steps"]) == (
        2, {"orders": 2, "mean": 2.0, "p95": 2, "max": 2}, 0)
    assert "occurs(object(robot,1),action(move,(1,0)),6)." in plan.read_text()


def test_an_encoding_needs_the_multishot_planner(tmp_path, capsys):
    scenario = tmp_path / "corridor.lp"
    scenario.write_text(CORRIDOR)
    assert main(["online", str(scenario), "--planner", "asp", "--encoding", TEMPLATE]) == 2
    assert capsys.readouterr().err == "error: --encoding goes with --planner multishot\n"
