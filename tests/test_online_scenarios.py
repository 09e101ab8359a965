"""Online scenarios as data (issue 43, item 1): an order's release step in the instance
(``init(object(order,O),value(release,Step))``, SPEC.md), read and written, checked by
``check`` (no delivery before the release), refused by ``solve`` (an offline search knows no
release steps), and used by ``asprilo online``."""

from __future__ import annotations

import pytest
from test_online_run import CORRIDOR, WEST

from asprilo.cli import main
from asprilo.errors import InputError
from asprilo.model import Action
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source
from asprilo.writer import format_instance

SCENARIO = CORRIDOR + "init(object(order,2),value(release,4)).\n"
#: the corridor's unique minimal plan for order 1, then order 2's delivery at step 4: one step
#: too early for a release at step 4
TOO_EARLY = ("occurs(object(robot,1),action(move,(-1,0)),1). occurs(object(robot,1),action(move,(-1,0)),2).\n"
             "occurs(object(robot,1),action(deliver,(1,1,1)),3). occurs(object(robot,1),action(deliver,(2,1,2)),4).\n")


def test_a_release_step_is_read_and_written_back():
    instance = read_instance(Source("scenario.lp", SCENARIO))
    # order 1 states no release step: an offline order (None), written back without one
    assert [(order.id, order.release) for order in instance.orders.values()] == [(1, None), (2, 4)]
    text = format_instance(instance)
    assert "init(object(order,2),value(release,4))." in text and "order,1),value(release" not in text
    assert read_instance(Source("again.lp", text)).orders == instance.orders
    instance.orders[1].release = 0  # released at step 0 (an online order from the start): said
    assert "init(object(order,1),value(release,0))." in format_instance(instance)


@pytest.mark.parametrize(("fact", "words"), [
    ("init(object(order,2),value(release,-1)).",
     "scenario.lp:9: order 2: value of 'release' must be a step (0 or more), got -1"),
    ("init(object(order,2),value(release,4)). init(object(order,2),value(release,5)).",
     "scenario.lp:9: order 2 has two release steps: 4 and 5"),
])
def test_a_bad_release_step_is_refused_in_words(fact, words):
    """The corridor's facts take lines 1-8; the fact tried is line 9."""
    with pytest.raises(InputError) as refused:
        read_instance(Source("scenario.lp", CORRIDOR + fact + "\n"))
    assert str(refused.value) == words


def test_check_refuses_a_delivery_before_the_release(tmp_path, capsys):
    scenario, plan = tmp_path / "scenario.lp", tmp_path / "plan.lp"
    scenario.write_text(SCENARIO)
    plan.write_text(TOO_EARLY)
    assert main(["check", str(scenario), str(plan)]) == 1
    assert capsys.readouterr().out.splitlines()[0] == (
        "step 4: robot 1 delivers 2 units of product 1 for order 2, but order 2 is released at step 4: "
        "it is known after that step only")
    plan.write_text(TOO_EARLY.replace(",4).", ",5)."))  # one step later: valid
    assert main(["check", str(scenario), str(plan)]) == 0


def test_solve_refuses_an_online_scenario_in_words(tmp_path, capsys):
    scenario = tmp_path / "scenario.lp"
    scenario.write_text(SCENARIO)
    assert main(["solve", str(scenario)]) == 2
    assert capsys.readouterr().err == (
        "error: the instance releases orders over time (order 2 at step 4): run it with 'asprilo online', "
        "or leave out its release facts to solve it offline\n")


def test_online_takes_the_release_steps_of_the_instance_and_writes_the_scenario(tmp_path, capsys):
    """Order 2 released at step 4 (the instance's own): the run of test_online_run's first test."""
    scenario, plan, written = tmp_path / "scenario.lp", tmp_path / "run.lp", tmp_path / "written.lp"
    scenario.write_text(SCENARIO)
    assert main(["online", str(scenario), "--planner", "asp", "--budget", "60", "-o", str(plan)]) == 0
    assert read_plan(str(plan)).actions[-1] == Action(5, 1, "deliver", (2, 1, 2))
    # --every 2 instead: order 2 released at step 2, which the written scenario says
    assert main(["online", str(scenario), "--every", "2", "--planner", "asp", "--budget", "60", "-o", str(plan),
                 "--scenario", str(written)]) == 0
    capsys.readouterr()
    assert read_instance(str(written)).orders[2].release == 2
    assert main(["check", str(written), str(plan)]) == 0
    assert read_plan(str(plan)).actions[:2] == [Action(1, 1, "move", WEST), Action(2, 1, "move", WEST)]
