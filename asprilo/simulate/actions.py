"""Which actions of a plan take effect (SPEC.md §3): a robot of the instance acts at a step
>= 1, it is the robot's only action at that step, the name is an action of the domain and
the arguments have the right shape.  Every other action is reported and ignored."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable
from typing import Any

from ..domain import Domain
from ..model import Action, Instance, Plan

#: report(module, check, *params)
Report = Callable[..., None]


def _ints(args: Any, lengths: tuple[int, ...]) -> bool:
    return type(args) is tuple and len(args) in lengths and all(type(a) is int for a in args)


def well_formed(name: str, args: Any, domain: Domain) -> bool:
    """Whether ``args`` have the shape action ``name`` takes in ``domain`` (SPEC.md §3; the
    moves are the domain's: a variant may give others)."""
    if name == "move":
        return args in domain.directions and type(args[0]) is int
    if name in ("pickup", "putdown"):
        return args == ()
    if name == "deliver":
        if domain.counts_units:
            return _ints(args, (3,)) and args[2] >= 1
        return _ints(args, (2, 3))
    return False


def effective_actions(instance: Instance, plan: Plan, domain: Domain, report: Report) -> dict[int, list[Action]]:
    """Report the actions that do not take effect; return those that do, by step."""
    effective: dict[int, list[Action]] = defaultdict(list)
    actions = plan.actions
    # the plan is sorted, so the actions of one object at one step come one after another
    keys = [(a.step, a.robot, a.kind) for a in actions]
    shared = [False] + [a == b for a, b in zip(keys, keys[1:], strict=False)] + [False]
    for i, action in enumerate(actions):
        if not _acts(action, instance, report):
            continue
        alone = not (shared[i] or shared[i + 1])
        if _well_formed(action, domain, report) and alone:
            effective[action.step].append(action)
        if not alone:
            report("action", "concurrent", action.robot, action.step)
    return effective


def robot_of(action: Action) -> int:
    """The robot of an effective action: one of the instance's, whose ids are ints."""
    robot = action.robot
    assert type(robot) is int, action
    return robot


def _acts(action: Action, instance: Instance, report: Report) -> bool:
    """Whether a robot of the instance acts at a step >= 1 (else reported)."""
    if action.kind != "robot":
        report("action", "notRobot", action.kind, action.robot, action.step)
    elif action.robot not in instance.robots:
        report("action", "unknownRobot", action.robot, action.step)
    elif action.step < 1:
        report("action", "badStep", action.robot, action.step)
    else:
        return True
    return False


def _well_formed(action: Action, domain: Domain, report: Report) -> bool:
    """Whether the action is one of the domain, with the right arguments (else reported)."""
    if action.name not in domain.actions:
        report("action", "unknownAction", action.robot, action.name, action.step)
    elif not well_formed(action.name, action.args, domain):
        report("action", "badArguments", action.robot, action.name, action.step)
    else:
        return True
    return False
