"""``robot-steps`` is counted while a plan is read (issue 46, item 7): a plan beyond it is
refused at the action that passes it, before the rest of the file is read (a syntax error
further down is never reached) and long before anything is simulated."""

from __future__ import annotations

import pytest

from asprilo.cli import main
from asprilo.errors import InputError
from asprilo.limits import Limits
from asprilo.reader import read_instance_and_plan, read_plan
from asprilo.sources import Source

LIMITS = Limits(robot_steps=10)
BROKEN = "occurs(object(robot,1),action(move,(1,0)),1"  # no period: a syntax error if ever reached


def moves(robots: list[int], steps: range, fancy: bool = False) -> str:
    """One move per robot and step, in step order; ``fancy`` writes them with a comment
    inside (the token path reads them, not the regular expression)."""
    gap = " %* c *% " if fancy else ""
    return "".join(f"occurs(object(robot,{r}),{gap}action(move,(0,1)),{t}).\n" for t in steps for r in robots)


def refusal(text: str, robots: int | None = None) -> str:
    with pytest.raises(InputError) as error:
        read_plan(Source("plan.lp", text), LIMITS, robots)
    return str(error.value)


@pytest.mark.parametrize("fancy", [False, True])
def test_a_step_beyond_the_limit_is_refused_where_it_stands(fancy):
    text = moves([1], range(1, 12), fancy) + BROKEN  # step 11 on line 11
    assert refusal(text) == ("plan.lp:11: an action at step 11, beyond the limit robot-steps=10 "
                             "(raise it with --limit robot-steps=N)")
    assert refusal("occurs(object(robot,1),action(move,(0,1)),-11).\n" + BROKEN).startswith(
        "plan.lp:1: an action at step -11, beyond")


@pytest.mark.parametrize("fancy", [False, True])
def test_robots_seen_so_far_times_the_horizon(fancy):
    # 2 robots: steps 1..5 are 10 robot-steps; robot 1 at step 6 (line 11) makes 12
    text = moves([1, 2], range(1, 8), fancy) + BROKEN
    assert refusal(text) == ("plan.lp:11: a plan moving 2 robots up to step 6, beyond the limit "
                             "robot-steps=10 (raise it with --limit robot-steps=N)")
    # robot 3 first moves at step 4 (line 7 of this text): 3 robots up to step 4 are 12
    text = moves([1, 2], range(1, 4)) + "occurs(object(robot,3),action(move,(0,1)),4).\n" + BROKEN
    assert refusal(text).startswith("plan.lp:7: a plan moving 3 robots up to step 4, beyond")


def test_with_the_instance_known_its_robots_count_from_the_first_action():
    # 4 robots in the instance: step 3 makes 12, whichever robot moves
    text = moves([1], range(1, 5)) + BROKEN
    assert refusal(text, robots=4) == ("plan.lp:3: a plan of horizon 3 for 4 robots, beyond the limit "
                                       "robot-steps=10 (raise it with --limit robot-steps=N)")
    assert len(read_plan(Source("plan.lp", moves([1], range(1, 3))), LIMITS, robots=4).actions) == 2


def test_a_plan_at_the_limit_is_read():
    assert len(read_plan(Source("plan.lp", moves([1, 2], range(1, 6))), LIMITS).actions) == 10
    assert len(read_plan(Source("plan.lp", moves([1], range(1, 11))), LIMITS, robots=1).actions) == 10


INSTANCE = ("init(object(node,1),value(at,(1,1))). init(object(node,2),value(at,(1,2))).\n"
            "init(object(robot,1),value(at,(1,1))). init(object(robot,2),value(at,(1,2))).\n")


def test_check_refuses_while_reading(tmp_path, capsys):
    instance, plan = tmp_path / "instance.lp", tmp_path / "plan.lp"
    instance.write_text(INSTANCE)
    plan.write_text(moves([1], range(1, 7)) + BROKEN)  # 2 robots in the instance: step 6 is 12
    assert main(["check", str(instance), str(plan), "--limit", "robot-steps=10"]) == 2
    assert capsys.readouterr().err == (f"error: {plan}:6: a plan of horizon 6 for 2 robots, beyond the limit "
                                       "robot-steps=10 (raise it with --limit robot-steps=N)\n")
    with pytest.raises(InputError):
        read_instance_and_plan(Source("i.lp", INSTANCE), Source("p.lp", moves([1], range(1, 7))), LIMITS)
