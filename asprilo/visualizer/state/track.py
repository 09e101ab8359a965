"""A plan's states, computed once by the simulator and kept as arrays for animation.

``Track`` answers everything the viewer asks about time: where each robot and shelf is
after step t (and in between, interpolated), who carries what, which action a robot does
at a step, how long it has been idle, the levels of the robots' resources (a variant's
energy), and which rules the plan breaks when: the simulator's findings, or the ASP
checker's where the domain has rules the simulator does not know (:mod:`.rules`).
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from asprilo.domain import Domain
from asprilo.model import Action, Cell, Instance, Plan
from asprilo.simulate import State, Violation, simulate

from . import rules
from .gauges import Gauge, measure


class Track:
    """States 0..horizon of ``plan`` on ``instance`` (state t = the state after step t).

    ``unfinished``: the plan is not complete (none yet, or still growing in an online
    session), so the goal is not checked at its last step.

    ``checked``: the violations are the ASP checker's (``checker_violations``, all of them),
    since the simulator does not know every rule of the domain; ``goal_checked``: the open
    order lines of a state are those the checker calls unfilled had the plan ended there.
    """

    def __init__(self, instance: Instance, plan: Plan, domain: Domain | None = None, unfinished: bool = False):
        self.instance = instance
        self.plan = plan
        self.timeline = simulate(instance, plan, domain)
        self.domain: Domain = self.timeline.domain
        self.horizon: int = self.timeline.horizon
        self.checked = not rules.simulator_knows(self.domain)
        self.checker_violations: list[Violation] = (rules.checker_violations(instance, plan, self.domain)
                                                    if self.checked else [])
        found = self.checker_violations if self.checked else self.timeline.violations
        self.violations: list[Violation] = [v for v in found if not (unfinished and self._goal(v))]
        self.states: list[State] = [self.timeline.state(t) for t in range(self.horizon + 1)]
        self.goal_checked = self.checked and not rules.goal_known(self.domain)
        self._lines_checked: set[int] = set()

        initial = self.states[0]
        self.robot_ids: list[int] = sorted(set(instance.robots) | set(initial.robots))
        self.shelf_ids: list[int] = sorted(set(instance.shelves) | set(initial.shelves))
        self.robot_index = {robot: i for i, robot in enumerate(self.robot_ids)}
        self.shelf_index = {shelf: i for i, shelf in enumerate(self.shelf_ids)}
        self.robot_xy = np.array([[state.robots.get(r, (0, 0)) for r in self.robot_ids] for state in self.states],
                                 dtype=np.float64).reshape(self.horizon + 1, len(self.robot_ids), 2)
        self.carrier = np.full((self.horizon + 1, len(self.shelf_ids)), -1, dtype=np.int32)
        for t, state in enumerate(self.states):
            for robot, shelf in state.carries.items():
                if shelf in self.shelf_index and robot in self.robot_index:
                    self.carrier[t, self.shelf_index[shelf]] = self.robot_index[robot]
        self.shelf_xy = self._shelf_positions()

        self._actions: dict[tuple[int, int], list[Action]] = {}
        for action in plan.actions:
            if action.kind == "robot":
                self._actions.setdefault((action.step, action.robot), []).append(action)
        self.violations_at: dict[int, list[Violation]] = {}
        for violation in self.violations:
            self.violations_at.setdefault(violation.step, []).append(violation)

    def _shelf_positions(self) -> np.ndarray:
        """(horizon+1, shelves, 2): a shelf moves only while carried, so each step looks up
        just the shelves carried before or after it."""
        xy = np.zeros((self.horizon + 1, len(self.shelf_ids), 2), dtype=np.float64)
        initial = self.states[0].shelves
        if self.shelf_ids:
            xy[0] = [initial.get(s, (0, 0)) for s in self.shelf_ids]
        for t in range(1, self.horizon + 1):
            xy[t] = xy[t - 1]
            shelves = self.states[t].shelves
            for index in np.flatnonzero((self.carrier[t - 1] >= 0) | (self.carrier[t] >= 0)).tolist():
                xy[t, index] = shelves.get(self.shelf_ids[index], xy[t - 1, index])
        return xy

    # --- time -----------------------------------------------------------------------------

    def clamp(self, time: float) -> float:
        return min(max(time, 0.0), float(self.horizon))

    def split(self, time: float) -> tuple[int, float]:
        """``(step, fraction)``: ``time`` lies ``fraction`` of the way from state ``step`` to the next."""
        time = self.clamp(time)
        step = min(int(time), self.horizon)
        return step, (time - step if step < self.horizon else 0.0)

    def robot_positions(self, time: float) -> np.ndarray:
        """Robot cells at ``time``, interpolated between states (shape (robots, 2))."""
        step, fraction = self.split(time)
        return _between(self.robot_xy, step, fraction)

    def shelf_positions(self, time: float) -> np.ndarray:
        step, fraction = self.split(time)
        return _between(self.shelf_xy, step, fraction)

    # --- questions per step -----------------------------------------------------------------

    def state(self, step: int) -> State:
        step = min(max(step, 0), self.horizon)
        state = self.states[step]
        if self.goal_checked and step not in self._lines_checked:
            self._lines_checked.add(step)
            state.open_lines = self._unfilled(step, state.open_lines)
        return state

    def _goal(self, violation: Violation) -> bool:
        """Whether ``violation`` is about the goal (the checker's, or a variant's about orders)."""
        return violation.module == "goal" or (self.checked and rules.about_orders(self.domain, violation))

    def _unfilled(self, step: int, replayed: dict[tuple[int, int], int | None]) -> dict[tuple[int, int], int | None]:
        """The order lines the checker calls unfilled had the plan ended at ``step``, with the
        units the replay says they miss (those requested where the replay has them filled)."""
        found = self.checker_violations if step >= self.horizon else \
            rules.checker_violations(self.instance, rules.plan_until(self.plan, step), self.domain)
        unfilled = rules.unfilled_lines(self.instance, self.domain, found)
        return {(order.id, product): replayed.get((order.id, product), units)
                for order in self.instance.orders.values()
                for product, units in order.lines.items() if (order.id, product) in unfilled}

    @cached_property
    def gauges(self) -> tuple[Gauge, ...]:
        """The levels of the domain's resources (a variant's energy), one gauge each."""
        carries = [state.carries for state in self.states]  # (the replay's: no check of the goal)
        return tuple(measure(resource, self.timeline, self.robot_ids, carries) for resource in self.domain.resources)

    def actions(self, robot: int, step: int) -> list[Action]:
        """What ``robot`` does at time step ``step``: nothing (it waits), one action, or
        several (an invalid plan)."""
        return self._actions.get((step, robot), [])

    def actions_at(self, step: int) -> list[Action]:
        """The plan's actions at time step ``step``."""
        return self._by_step.get(step, [])

    @cached_property
    def _by_step(self) -> dict[int, list[Action]]:
        return self.plan.by_step()

    @cached_property
    def idle(self) -> np.ndarray:
        """(horizon+1, robots): steps 1..t at which each robot did nothing."""
        busy = np.zeros((self.horizon + 1, len(self.robot_ids)), dtype=np.int32)
        for step, robot in self._actions:
            if robot in self.robot_index and 1 <= step <= self.horizon:
                busy[step, self.robot_index[robot]] = 1
        waiting = 1 - busy
        waiting[0] = 0
        return np.cumsum(waiting, axis=0)

    @cached_property
    def bounds(self) -> tuple[Cell, Cell]:
        """Top-left and bottom-right cell of everything that ever stands somewhere
        (robots of invalid plans may leave the floor)."""
        arrays = [xy.reshape(-1, 2) for xy in (self.robot_xy, self.shelf_xy) if xy.size]
        if not arrays:
            return (1, 1), (1, 1)
        low = np.min([xy.min(axis=0) for xy in arrays], axis=0).astype(int).tolist()
        high = np.max([xy.max(axis=0) for xy in arrays], axis=0).astype(int).tolist()
        return (low[0], low[1]), (high[0], high[1])

    @cached_property
    def off_floor(self) -> np.ndarray:
        """(horizon+1, robots) booleans: the robot stands on a cell that is not a node."""
        xy = self.robot_xy.astype(np.int64)
        nodes = np.array(list(self.instance.nodes.values()), dtype=np.int64).reshape(-1, 2)
        both = np.concatenate([xy.reshape(-1, 2), nodes])
        if not len(both):
            return np.zeros(xy.shape[:2], dtype=bool)
        low, high = int(both.min()), int(both.max())
        grid = np.zeros((high - low + 1, high - low + 1), dtype=bool)
        grid[nodes[:, 1] - low, nodes[:, 0] - low] = True
        return ~grid[xy[..., 1] - low, xy[..., 0] - low]


def _between(xy: np.ndarray, step: int, fraction: float) -> np.ndarray:
    if fraction == 0.0:
        return xy[step]
    return xy[step] + fraction * (xy[step + 1] - xy[step])
