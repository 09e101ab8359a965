"""The two sides of the online link that are not the visualizer: a planner that re-plans
when the world changes, and a simulator that releases orders over time.

Both are plain Python (no sockets; ``asprilo.online.serve`` puts them on the network).

- :class:`OnlinePlanner` knows the facts received so far and the actions it has sent.
  Asked for the actions of step T+1 (after ``%$done(T).``), it answers from its current
  plan; when new facts arrived since it last planned, it first computes the state of the
  world after step T (the instance replayed with the actions it sent) and plans from there.
- :class:`Schedule` splits an instance into the world at step 0 and the orders that
  arrive later, each at its step.
"""

from __future__ import annotations

import threading
from collections import defaultdict
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

from asprilo.domain import Domain, Goal, detect_domain
from asprilo.errors import InputError
from asprilo.model import Action, Instance, Order, Plan, Product, Robot, Shelf
from asprilo.simulate import State, simulate

from .protocol import instance_facts, read_world, shifted


def world_at(instance: Instance, state: State) -> Instance:
    """The world in ``state`` as an instance of its own: robots and shelves where they are,
    what robots carry, the stock left and the order lines still open."""
    robots = {r: Robot(r, tuple(state.robots[r]), state.carries.get(r)) for r in instance.robots}
    shelves = {s: Shelf(s, tuple(cell)) for s, cell in state.shelves.items()}
    products: dict[int, Product] = {}
    for (shelf, product), units in sorted(state.stock.items()):
        if units is None or units > 0:
            products.setdefault(product, Product(product)).stock[shelf] = units
    orders: dict[int, Order] = {}
    for (order, product), units in sorted(state.open_lines.items()):
        station = instance.orders[order].station if order in instance.orders else None
        orders.setdefault(order, Order(order, {}, station)).lines[product] = units
    return Instance(dict(instance.nodes), dict(instance.highways), robots, shelves, dict(instance.stations),
                    products, orders, dict(instance.destinations))


#: (instance, domain, cancel) -> a plan from the instance's state (steps 1..H), or None
Planner = Callable[[Instance, Domain, threading.Event], "Plan | None"]


def encodings_planner(encoding: str = "plain", time_limit: float | None = 60.0, method: str = "asp") -> Planner:
    """A planner through :func:`asprilo.encodings.solve`: the reference encodings (minimal
    makespan), or another of its methods."""
    def plan(instance: Instance, domain: Domain, cancel: threading.Event) -> Plan | None:
        from asprilo.encodings import solve
        outcome = solve(instance, domain, encoding=encoding, time_limit=time_limit, cancel=cancel, method=method)
        return outcome.plan if outcome.found else None
    return plan


def anytime_planner(time_limit: float = 60.0) -> Planner:
    """A planner through the anytime method: every (re-)planning answers after about
    ``time_limit`` seconds (a routing call being grounded finishes first) with the best plan
    found by then, sooner when a plan meets the lower bound."""
    return encodings_planner(time_limit=time_limit, method="anytime")


@dataclass
class OnlinePlanner:
    """Plans for a world that grows while its plan is carried out (see the module docstring)."""

    planner: Planner
    domain: Domain | None = None
    log: Callable[[str], None] = lambda _text: None
    cancel: threading.Event = field(default_factory=threading.Event)

    def __post_init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        """Forget the world and the plan (``%$RESET.``)."""
        self.facts: list[str] = []
        self.sent: dict[int, list[Action]] = {}
        self.planned: dict[int, list[Action]] = {}
        self.stale = False
        self.cancel.clear()

    def learn(self, facts: str) -> None:
        """New facts about the world (the instance, or orders that arrived)."""
        if facts.strip():
            self.facts.append(facts)
            self.stale = True

    def next_actions(self, step: int) -> list[Action]:
        """The actions of step ``step + 1`` (after ``%$done(step).``); they are final once given.

        Steps come in order: ``step`` is one answered before or the next (bad input otherwise).
        """
        following = max(self.sent, default=0)
        if not 0 <= step <= following:
            raise InputError(f"done({step}) asks about a step outside the plan: the next step is {following}")
        if step + 1 in self.sent:
            return self.sent[step + 1]
        if self.stale and self.facts:
            self.replan(step)
        actions = self.planned.get(step + 1, [])
        self.sent[step + 1] = actions
        return actions

    def replan(self, step: int) -> None:
        """Plan again from the state after ``step``, the actions sent so far being done."""
        self.stale = False
        instance = read_world(self.facts)
        domain = self.domain or detect_domain(instance)
        done = Plan([a for t, actions in self.sent.items() if t <= step for a in actions])
        state = simulate(instance, done, domain).state(step)
        now = world_at(instance, state)
        if domain.goal is Goal.LINES and not now.orders:
            self.planned = {}
            self.log(f"step {step}: every order is complete, nothing to plan")
            return
        self.log(f"step {step}: planning from the state after step {step} "
                 f"({len(now.robots)} robots, {sum(len(o.lines) for o in now.orders.values())} open order lines)")
        plan = self.planner(now, domain, self.cancel)
        self.planned = defaultdict(list)
        if plan is None:
            self.log(f"step {step}: no plan found; robots wait until something changes")
            return
        for action in shifted(plan, step):
            self.planned[action.step].append(action)
        self.log(f"step {step}: planned {len(plan)} actions for steps {step + 1}..{step + plan.horizon}")


class Schedule:
    """When the orders of an instance become known: ``arrivals`` maps order -> step (>= 0)."""

    def __init__(self, instance: Instance, arrivals: dict[int, int]):
        unknown = sorted(set(arrivals) - set(instance.orders))
        if unknown:
            raise InputError(f"the instance has no order {unknown[0]}")
        if any(step < 0 for step in arrivals.values()):
            raise InputError("orders arrive at step 0 or later")
        self.instance = instance
        self.arrivals = {order: arrivals.get(order, 0) for order in sorted(instance.orders)}

    @classmethod
    def every(cls, instance: Instance, steps: int, first: int = 0) -> Schedule:
        """Orders in id order, the first at step ``first``, then one every ``steps`` steps."""
        return cls(instance, {order: first + i * steps for i, order in enumerate(sorted(instance.orders))})

    def _orders(self, step: int) -> dict[int, Order]:
        return {o: order for o, order in sorted(self.instance.orders.items()) if self.arrivals[o] == step}

    def world(self) -> str:
        """The facts known at step 0: the instance without the orders that arrive later."""
        return instance_facts(replace(self.instance, orders=self._orders(0)))

    def arriving(self, step: int) -> str:
        """The facts of the orders that arrive at ``step`` (>= 1)."""
        orders = self._orders(step) if step >= 1 else {}
        return instance_facts(Instance(orders=orders)) if orders else ""

    @property
    def last(self) -> int:
        """The step of the last arrival (0: everything is known from the start)."""
        return max(self.arrivals.values(), default=0)


def parse_arrivals(texts: Sequence[str]) -> dict[int, int]:
    """``["3:1,2", "7:4"]`` (``STEP:ORDER,...``) as order -> step."""
    arrivals = {}
    for text in texts:
        step, _, orders = text.partition(":")
        try:
            numbers = [int(order) for order in orders.split(",")]
            when = int(step)
        except ValueError:
            raise InputError(f"--at {text}: expected STEP:ORDER[,ORDER...], e.g. --at 3:2") from None
        for order in numbers:
            arrivals[order] = when
    return arrivals


def release_steps(instance: Instance, every: int | None = None, at: Sequence[str] = ()) -> dict[int, int]:
    """When each order is released: one every ``every`` steps in id order, or as ``at`` says
    (``STEP:ORDER,...``), else the instance's own release steps (``value(release,Step)``; none: 0)."""
    if every:
        return Schedule.every(instance, every).arrivals
    if at:
        return Schedule(instance, parse_arrivals(at)).arrivals
    return {order.id: order.release or 0 for order in instance.orders.values()}
