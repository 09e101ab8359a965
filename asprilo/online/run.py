"""An online run without a window: the world carried out step by step while orders are
released, a planner asked for the next actions as the world changes.

Time: the world takes one step every ``step_seconds`` of the planner's wall time.  A call of
the planner after step t that takes s seconds lets floor(s / step_seconds) steps pass in
which the robots stand still (the *waiting steps*: counted); the plan it answers is carried
out from the step after.  Standing still changes nothing, so the plan made from the state
after step t fits the state after the waiting steps.  A call may take ``budget`` seconds; one
that finds no plan is made again at once with twice the time (the planner keeps thinking
while the robots wait), up to ``most_budget``; a plan found brings the budget back.

The planner is asked after step 0 and then (``replan``): ``"arrival"`` whenever orders were
released since it last planned (the default), or an integer k: also every k steps; and
whenever a plan with actions has been carried out to its end while orders are still open (a
planner may plan part of the work at a time: domain A's multi-shot planner plans the next
step of every task).  An order
released at step r is known to the planner after step r.  The run ends after ``steps``
steps, or (``steps=None``) once every order is released and done; a run whose planner finds
no plan within ``most_budget`` while nothing else can change ends there, and says so.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

from asprilo.domain import Domain, Goal
from asprilo.model import Action, Instance, Order, Plan
from asprilo.simulate import simulate

from .metrics import PlannerCall, scenario_of
from .planning import OnlinePlanning
from .protocol import shifted

#: the longest a run goes on without a step limit (steps): a guard, said when it ends a run
MOST_STEPS = 100_000


@dataclass
class OnlineRun:
    """What a run carried out: the plan, the planner's calls, the steps robots waited, the
    release steps, its length in steps and why it ended."""

    plan: Plan
    releases: dict[int, int]
    steps: int
    calls: list[PlannerCall] = field(default_factory=list)
    waiting: list[int] = field(default_factory=list)
    ended: str = ""
    carried: list[Action] = field(default_factory=list)  # the actions carried out so far, while it runs


@dataclass
class _World:
    """The run so far: the orders released, the actions carried out, the current plan."""

    instance: Instance
    domain: Domain
    releases: dict[int, int]
    done: list[Action] = field(default_factory=list)
    ahead: dict[int, list[Action]] = field(default_factory=dict)

    def released_at(self, step: int) -> list[Order]:
        """The orders released at ``step``."""
        return [order for o, order in sorted(self.instance.orders.items()) if self.releases[o] == step]

    def finished(self, step: int) -> bool:
        """Every order known after ``step`` is done (Md: the plan carried out to its end)."""
        if self.domain.goal is Goal.DESTINATIONS:
            return not self.ahead_after(step)
        known = replace(self.instance, orders={o: order for o, order in self.instance.orders.items()
                                               if self.releases[o] <= step})
        return not simulate(known, Plan(list(self.done)), self.domain).state(step).open_lines

    def ahead_after(self, step: int) -> bool:
        return any(t > step and actions for t, actions in self.ahead.items())


def run_online(instance: Instance, domain: Domain, planner: OnlinePlanning,
               releases: dict[int, int] | None = None, *, budget: float = 1.0, most_budget: float | None = None,
               steps: int | None = None, step_seconds: float = 1.0, replan: str | int = "arrival",
               clock: Callable[[], float] = time.perf_counter, cancel: threading.Event | None = None,
               on_step: Callable[[int, OnlineRun], None] | None = None) -> OnlineRun:
    """Run ``instance`` online (see the module docstring) with ``planner`` (told of the orders
    and the actions as they come: :mod:`asprilo.online.planning`); ``releases``: order -> step
    (an order not named is known from the start);
    ``most_budget``: by default 16 times ``budget``; ``on_step(step, run)`` after every step;
    setting ``cancel`` ends the run after the step under way (what ran is kept)."""
    releases = {order: releases.get(order, 0) if releases else 0 for order in sorted(instance.orders)}
    world = _World(scenario_of(instance, releases), domain, releases)
    run = OnlineRun(Plan([]), releases, 0, carried=world.done)
    cancel = cancel or threading.Event()
    most = 16 * budget if most_budget is None else most_budget
    limit = MOST_STEPS if steps is None else steps
    step, planned_at, seconds, under_way = 0, None, budget, False
    planner.released(world.released_at(0), 0)
    while step < limit:
        ran_out = under_way and not world.ahead_after(step)
        under_way = under_way and not ran_out
        if _due(step, planned_at, releases, replan) or (ran_out and not world.finished(step)) or \
                (run.calls and not run.calls[-1].found and seconds <= most):
            planned_at = step
            found, step = _plan(world, run, planner, step, seconds, step_seconds, clock, cancel, limit)
            seconds = budget if found else 2 * seconds
            under_way = world.ahead_after(step)
            if step >= limit:
                break
        actions = world.ahead.get(step + 1, [])
        world.done += actions
        step += 1
        planner.carried_out(step, actions)
        arriving = world.released_at(step)
        if arriving:
            planner.released(arriving, step)
        run.steps = step
        if on_step is not None:
            on_step(step, run)
        if cancel.is_set():
            run.ended = "interrupted"
            break
        if steps is None and not world.ahead_after(step) and all(r <= step for r in releases.values()):
            if world.finished(step):
                run.ended = "every order is done"
                break
            if seconds > most and planned_at is not None and all(r <= planned_at for r in releases.values()):
                run.ended = f"the planner found no plan for what is left within {most:g} s"
                break
    else:
        run.ended = run.ended or ("the step limit" if steps is not None else f"the guard of {MOST_STEPS} steps")
    run.plan = Plan(list(world.done))
    return run


def _due(step: int, planned_at: int | None, releases: dict[int, int], replan: str | int) -> bool:
    """Whether the planner is asked after ``step`` (a call that found nothing aside)."""
    if planned_at is None:
        return True
    if any(planned_at < release <= step for release in releases.values()):
        return True
    return isinstance(replan, int) and step - planned_at >= replan


def _plan(world: _World, run: OnlineRun, planner: OnlinePlanning, step: int, budget: float, step_seconds: float,
          clock: Callable[[], float], cancel: threading.Event, limit: int) -> tuple[bool, int]:
    """Ask the planner after ``step``; the steps robots wait meanwhile pass (the planner is
    told of them); whether it found a plan, and the step at which its plan starts."""
    started = clock()
    plan = planner.plan(step, budget, cancel)
    seconds = clock() - started
    run.calls.append(PlannerCall(step, seconds, plan is not None))
    waited = min(math.floor(seconds / step_seconds), limit - step)
    for stood in range(step + 1, step + waited + 1):
        run.waiting.append(stood)
        planner.carried_out(stood, [])
        arriving = world.released_at(stood)
        if arriving:
            planner.released(arriving, stood)
    step += waited
    run.steps = step
    world.ahead = {}
    for action in shifted(plan, step) if plan is not None else ():
        world.ahead.setdefault(action.step, []).append(action)
    return plan is not None, step
