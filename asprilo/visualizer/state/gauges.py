"""Robot resources over time, without Qt: a variant's energy, say, after every step.

A resource (:class:`asprilo.domain.Resource`: an attribute, the costs of actions, the least
level allowed) starts at the value the instance gives each robot
(``init(object(robot,R),value(energy,E))``, kept in ``Instance.attributes``) and drops by
the cost of every action of the robot that takes effect (the checker's ``does/4``: a robot
of the instance, at a step >= 1, its only action there, an action of the domain with the
right arguments); a move while carrying a shelf costs what ``carrying move`` says.  A step
at which the level falls below the least one is where the robot runs out, the step the
checker's variant reports.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from asprilo.domain import Resource
from asprilo.simulate import Timeline, well_formed


@dataclass(frozen=True)
class Gauge:
    """One resource of every robot: ``levels[t, i]`` after step ``t`` of the robot at index
    ``i`` (``known[i]``: the instance gives it a starting level; else its levels are 0 and
    say nothing), ``drops[robot]`` the steps at which its level falls below ``least``."""

    resource: Resource
    levels: np.ndarray
    known: np.ndarray
    drops: dict[int, list[int]]

    @property
    def name(self) -> str:
        """The attribute, as a column's title: ``Energy``."""
        return self.resource.attribute.replace("_", " ").capitalize()

    def level(self, index: int, step: int) -> int | None:
        """The level of the robot at ``index`` after ``step`` (``None``: not known)."""
        return int(self.levels[step, index]) if self.known[index] else None

    def below(self, index: int, step: int) -> bool:
        """Whether the robot at ``index`` is below the least level after ``step``."""
        return bool(self.known[index] and self.levels[step, index] < self.resource.least)

    def ran_out(self, robot: int, step: int) -> int | None:
        """The step at which ``robot`` last fell below the least level, up to ``step``."""
        return max((drop for drop in self.drops.get(robot, ()) if drop <= step), default=None)


def measure(resource: Resource, timeline: Timeline, robots: Sequence[int],
            carries: Sequence[Mapping[int, int]]) -> Gauge:
    """The levels of ``resource`` after every step of ``timeline`` (a replayed plan) for
    ``robots`` in this order, ``carries[t]`` saying who carries a shelf after step ``t``."""
    instance, domain, horizon = timeline.instance, timeline.domain, timeline.horizon
    start = np.zeros(len(robots), dtype=np.int64)
    known = np.zeros(len(robots), dtype=bool)
    for i, robot in enumerate(robots):
        value = instance.attributes.get(("robot", robot), {}).get(resource.attribute)
        if type(value) is int:
            start[i], known[i] = value, True
    costs = np.zeros((horizon + 1, len(robots)), dtype=np.int64)
    for step in range(1, horizon + 1):
        for i, robot in enumerate(robots):
            actions = timeline.actions_of(robot, step)
            if len(actions) != 1 or robot not in instance.robots:
                continue
            action = actions[0]
            if action.name in domain.actions and well_formed(action.name, action.args, domain):
                costs[step, i] = resource.cost(action.name, robot in carries[step - 1])
    levels = start - np.cumsum(costs, axis=0)
    under = levels < resource.least
    falls = under[1:] & ~under[:-1]
    drops: dict[int, list[int]] = {}
    for step, i in zip(*np.nonzero(falls), strict=True):
        if known[i]:
            drops.setdefault(robots[i], []).append(int(step) + 1)
    return Gauge(resource, levels, known, drops)
