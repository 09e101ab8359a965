"""The figures of an online run: throughput, order latency, planner time and waiting steps.

An online run carries out a plan step by step while orders are released (an order released
at step r is known after step r; the first step that can serve it is r + 1).  From the plan
that was carried out, the release steps and the planner's calls:

- **throughput**: order lines and units done per 100 steps, over the whole run and in
  windows of ``window`` steps (throughput over time);
- **order latency**: for each order done, the step its last line was done minus its
  release step; the mean, the 95th percentile (nearest rank: the smallest latency that at
  least 95 % of the orders do not exceed) and the maximum;
- **planner time per call**: the mean and the maximum wall time of a call;
- **waiting steps**: the steps robots stood still because no plan was ready.

A line is done at the step its last missing unit is delivered (domain A) or the step a
delivery closes it (B, C); a unit counts at the step it is delivered.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from asprilo.domain import Domain
from asprilo.model import Instance, Plan
from asprilo.simulate import simulate
from asprilo.simulate.timeline import Timeline

#: the steps of one window of the throughput over time
WINDOW = 100

Line = tuple[int, int]  # (order, product)


@dataclass(frozen=True)
class PlannerCall:
    """One call of the planner: after ``step`` (it planned from that state), its wall time,
    and whether it answered with a plan."""

    step: int
    seconds: float
    found: bool = True


@dataclass(frozen=True)
class Window:
    """Lines and units done in steps ``first`` .. ``last``."""

    first: int
    last: int
    lines: int
    units: int


@dataclass(frozen=True)
class Latency:
    """Release-to-done steps of the orders done (``None`` when no order was done)."""

    orders: int
    mean: float | None
    p95: int | None
    most: int | None

    @classmethod
    def of(cls, latencies: list[int]) -> Latency:
        if not latencies:
            return cls(0, None, None, None)
        ordered = sorted(latencies)
        rank = math.ceil(0.95 * len(ordered))  # nearest rank, 1-based
        return cls(len(ordered), sum(ordered) / len(ordered), ordered[rank - 1], ordered[-1])


@dataclass(frozen=True)
class Metrics:
    """What :func:`measure` found (see the module docstring)."""

    steps: int
    lines: int            # order lines released within the run
    lines_done: int
    units_done: int
    orders_open: int      # orders released within the run and not done by its end
    latency: Latency
    calls: int
    planner_mean: float | None
    planner_max: float | None
    waiting_steps: int
    windows: list[Window] = field(default_factory=list)

    @property
    def lines_per_100(self) -> float:
        return 100 * self.lines_done / self.steps if self.steps else 0.0

    @property
    def units_per_100(self) -> float:
        return 100 * self.units_done / self.steps if self.steps else 0.0


def scenario_of(instance: Instance, releases: dict[int, int]) -> Instance:
    """``instance`` as an online scenario: every order with its release step (an order not
    named: step 0), so that the simulator and the checker judge it as released (in M, a goal
    once reached stays reached)."""
    return replace(instance, orders={o: replace(order, release=releases.get(o, 0))
                                     for o, order in instance.orders.items()})


def deliveries(instance: Instance, plan: Plan, domain: Domain, steps: int,
               timeline: Timeline | None = None) -> tuple[dict[Line, int], dict[int, int]]:
    """When each order line was done (line -> step) and how many units were delivered at
    each step (step -> units), over steps 1 .. ``steps`` of ``plan`` (``timeline``: its
    replay, when made already)."""
    timeline = timeline or simulate(instance, plan, domain)
    done: dict[Line, int] = {}
    units: dict[int, int] = {}
    before = timeline.state(0).open_lines
    for step in range(1, min(steps, plan.horizon) + 1):
        now = timeline.state(step).open_lines
        delivered = 0
        for line, missing in before.items():
            left = now.get(line)
            if left is None or (domain.counts_units and left == 0):
                done[line] = step
                delivered += _units(missing, instance, line)
            elif domain.counts_units and missing is not None and left < missing:
                delivered += missing - left
        if delivered:
            units[step] = delivered
        before = now
    return done, units


def _units(missing: int | None, instance: Instance, line: Line) -> int:
    """The units a line closed with: what it still missed (A), or what it asked for (B, C;
    a line without a quantity counts one)."""
    if missing is not None:
        return missing
    order, product = line
    asked = instance.orders[order].lines.get(product)
    return 1 if asked is None else asked


def measure(instance: Instance, plan: Plan, domain: Domain, releases: dict[int, int], steps: int,
            calls: Sequence[PlannerCall] = (), waiting_steps: int = 0, window: int = WINDOW) -> Metrics:
    """The figures of a run of ``steps`` steps that carried out ``plan`` on ``instance``,
    its orders released at ``releases`` (order -> step; an order not named: step 0) and judged
    so (:func:`scenario_of`)."""
    scenario = scenario_of(instance, releases)
    return figures(scenario, releases, deliveries(scenario, plan, domain, steps), steps, calls, waiting_steps, window)


def figures(instance: Instance, releases: dict[int, int], delivered: tuple[dict[Line, int], dict[int, int]],
            steps: int, calls: Sequence[PlannerCall] = (), waiting_steps: int = 0, window: int = WINDOW) -> Metrics:
    """:func:`measure`'s figures from what :func:`deliveries` found (made once for a plan,
    the figures after any step of it: the viewer's)."""
    done = {line: step for line, step in delivered[0].items() if step <= steps}
    units = {step: count for step, count in delivered[1].items() if step <= steps}
    released = [order for order in instance.orders if releases.get(order, 0) < steps]
    lines = [(order, product) for order in released for product in instance.orders[order].lines]
    latencies, open_orders = [], 0
    for order in released:
        finished = [done[(order, product)] for product in instance.orders[order].lines if (order, product) in done]
        if finished and len(finished) == len(instance.orders[order].lines):
            latencies.append(max(finished) - releases.get(order, 0))
        else:
            open_orders += 1
    windows = [Window(first, min(first + window - 1, steps),
                      sum(first <= step < first + window for step in done.values()),
                      sum(count for step, count in units.items() if first <= step < first + window))
               for first in range(1, steps + 1, window)]
    seconds = [call.seconds for call in calls]
    return Metrics(steps, len(lines), sum(step <= steps for step in done.values()), sum(units.values()),
                   open_orders, Latency.of(latencies), len(seconds),
                   sum(seconds) / len(seconds) if seconds else None, max(seconds, default=None),
                   waiting_steps, windows)


def counted(number: int, word: str) -> str:
    """``1 call``, ``2 calls``: a count in words."""
    return f"{number} {word}{'' if number == 1 else 's'}"
