"""A misspelt action is warned about, never a vote for another domain (issue 47, item 5).

The corridor: robot 1 at (1,1), a picking station at (2,1), shelf 1 with product 1 at (3,1);
order 1 asks for one unit of product 1 (M-aligned: one robot, one single-unit line).  The
plan moves east twice; with ``mvoe`` at step 1 the robot moves only once, so at the horizon
(step 2) it stands at (2,1), not under the shelf: by hand, under M, two violations -- the
unknown action and the unfulfilled order.
"""

from __future__ import annotations

from asprilo.cli import main
from asprilo.domain import Domain, detect_domain
from asprilo.model import Action, Plan
from asprilo.reader import read_instance

CORRIDOR = """\
init(object(node,1),value(at,(1,1))).
init(object(node,2),value(at,(2,1))).
init(object(node,3),value(at,(3,1))).
init(object(pickingStation,1),value(at,(2,1))).
init(object(robot,1),value(at,(1,1))).
init(object(shelf,1),value(at,(3,1))).
init(object(product,1),value(on,(1,1))).
init(object(order,1),value(line,(1,1))).
init(object(order,1),value(pickingStation,1)).
"""

TYPO_PLAN = """\
% robot 1 walks east to the shelf
occurs(object(robot,1),action(mvoe,(1,0)),1).
occurs(object(robot,1),action(move,(1,0)),2).
"""


def test_a_misspelt_move_leaves_an_m_instance_in_domain_m(tmp_path):
    instance_file = tmp_path / "corridor.lp"
    instance_file.write_text(CORRIDOR)
    instance = read_instance(instance_file)
    typo = Plan([Action(1, 1, "mvoe", (1, 0)), Action(2, 1, "move", (1, 0))])
    assert detect_domain(instance, typo) is Domain.M
    # a known action of A still makes the plan A, typo or not
    picks = Plan([Action(1, 1, "mvoe", (1, 0)), Action(2, 1, "pickup", ())])
    assert detect_domain(instance, picks) is Domain.A


def test_check_warns_about_the_typo_and_checks_the_plan_as_m(tmp_path, capsys):
    (tmp_path / "corridor.lp").write_text(CORRIDOR)
    (tmp_path / "typo.lp").write_text(TYPO_PLAN)
    code = main(["check", str(tmp_path / "corridor.lp"), str(tmp_path / "typo.lp")])
    out, err = capsys.readouterr()
    assert code == 1
    assert err.splitlines() == [
        f"warning: {tmp_path / 'typo.lp'}:2: there is no action 'mvoe': did you mean move? "
        "(the actions: deliver, move, pickup, putdown)"]
    assert out.splitlines()[:3] == [
        "step 1: robot 1 does 'mvoe', which is not an action of domain M",
        "step 2 (the horizon): order 1 is not fulfilled: no robot stands under a shelf holding product 1",
        "invalid plan: 2 violations (domain M (detected), horizon 2)",
    ]
