"""The online targets of issue 43: the multi-shot ASP planners on the paper's 46x15 layout.

Scenario: the large paper layout (examples/paper-m/4x5x8, 46x15, 320 shelves each holding
one product, 10 picking stations) with its first 20 robots, and a stream of single-line,
single-unit orders (product and station drawn by a seeded generator), one released every
2 steps, for 1,000 steps.  Domain M (a line is done when a robot arrives under the shelf
holding its product after the release) or A (a robot brings a shelf to the order's station
and delivers; --domain a).

Measured:
  multishot  the whole run with the multi-shot planner of the domain (one clingo Control:
             asprilo.online.multishot, asprilo.online.multishot_a): wall time, planner time
             per call (mean, max), waiting steps, throughput and the ceiling
             (asprilo.online.ceiling), order latency, the process's peak memory; the plan
             carried out is checked (M: asprilo check's rules on the layout without orders,
             every move legal, the online goal being what the figures measure; A: against the
             scenario, every delivery included)
  same questions  the first --compare-steps steps again, each call that solves asked twice
             on the same state: of the multi-shot planner (which answers) and of the same
             planner on a new Control every call (the program grounded again from nothing:
             what multi-shot solving saves; it gets 60 s to answer); robots never wait here
             (planner time is free)
  scratch    (M) the first --compare-steps steps with FromScratch and the exact `asp` planner
             (a new solve of the offline reference encoding from the world after every step it
             plans from)

Targets: the whole run within 10 minutes; planner time per call <= 1 s on average;
throughput >= 80 % of the ceiling; multi-shot >= 3x less planner time per call than from
scratch.

Run: python benchmarks/online.py [--domain m|a] [--steps 1000] [--budget 1] [--compare-steps 100]
                                 [--seed 1]
"""

from __future__ import annotations

import argparse
import random
import resource
import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from asprilo.checker import check  # noqa: E402
from asprilo.domain import Domain, Goal  # noqa: E402
from asprilo.model import Instance, Order, Plan  # noqa: E402
from asprilo.online.ceiling import ceiling  # noqa: E402
from asprilo.online.metrics import Metrics, measure  # noqa: E402
from asprilo.online.planner import encodings_planner  # noqa: E402
from asprilo.online.planning import FromScratch, OnlinePlanning, multishot  # noqa: E402
from asprilo.online.run import OnlineRun, run_online, scenario_of  # noqa: E402
from asprilo.reader import read_instance  # noqa: E402

LAYOUT = ROOT / "examples/paper-m/4x5x8/x46_y15_n690_r23_s320_ps10_pr320_u320_o23_N001.lp"


def scenario(robots: int, steps: int, every: int, seed: int) -> tuple[Instance, dict[int, int]]:
    """The layout with its first ``robots`` robots and one order every ``every`` steps."""
    layout = read_instance(str(LAYOUT))
    rng = random.Random(seed)
    products, stations = sorted(layout.products), sorted(layout.stations)
    count = steps // every
    orders = {o: Order(o, {rng.choice(products): 1}, rng.choice(stations)) for o in range(1, count + 1)}
    kept = {r: layout.robots[r] for r in sorted(layout.robots)[:robots]}
    return replace(layout, robots=kept, orders=orders), {o: (o - 1) * every for o in orders}


def peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def multishot_run(instance: Instance, domain: Domain, releases: dict[int, int], steps: int,
                  budget: float) -> tuple[OnlineRun, float]:
    started = time.perf_counter()
    run = run_online(instance, domain, multishot(instance, domain), releases, budget=budget, steps=steps,
                     on_step=lambda step, _run: step % 100 or print(f"  step {step}", file=sys.stderr, flush=True))
    return run, time.perf_counter() - started


#: the time the planner on a new Control gets for each question (enough to answer it)
FRESH_SECONDS = 60.0


class Twins:
    """The multi-shot planner, answering, and the same planner on a new Control every call,
    asked the same question each time the first one solves: (seconds, seconds) per call."""

    def __init__(self, instance: Instance, domain: Domain):
        self.main = multishot(instance, domain)
        self.fresh = multishot(instance, domain, fresh=True)
        self.times: list[tuple[float, float]] = []

    def released(self, orders: list[Order], step: int) -> None:
        self.main.released(orders, step)
        self.fresh.released(orders, step)

    def carried_out(self, step: int, actions: list) -> None:
        self.main.carried_out(step, actions)
        self.fresh.carried_out(step, actions)

    def plan(self, step: int, seconds: float, cancel) -> Plan | None:
        solves, started = self.main.solves, time.perf_counter()
        plan = self.main.plan(step, seconds, cancel)
        ours = time.perf_counter() - started
        if self.main.solves > solves:
            started = time.perf_counter()
            self.fresh.plan(step, max(seconds, FRESH_SECONDS), cancel)
            self.times.append((ours, time.perf_counter() - started))
        return plan


def same_questions(instance: Instance, domain: Domain, releases: dict[int, int], steps: int,
                   budget: float) -> list[tuple[float, float]]:
    twins = Twins(instance, domain)
    run_online(instance, domain, twins, releases, budget=budget, steps=steps, step_seconds=1e9)
    return twins.times


def scratch_run(instance: Instance, domain: Domain, releases: dict[int, int], steps: int, budget: float) -> OnlineRun:
    scratch: OnlinePlanning = FromScratch(instance, domain, lambda seconds: encodings_planner(time_limit=seconds))
    return run_online(instance, domain, scratch, releases, budget=budget, steps=steps)


def row(name: str, metrics: Metrics, top: int | None = None) -> str:
    share = "" if not top else f"{100 * metrics.lines_done / top:5.1f} %"
    mean = "-" if metrics.planner_mean is None else f"{metrics.planner_mean:6.3f}"
    most = "-" if metrics.planner_max is None else f"{metrics.planner_max:6.2f}"
    return (f"{name:<26} {metrics.steps:>5} {metrics.calls:>5} {mean:>8} {most:>7} {metrics.waiting_steps:>5} "
            f"{metrics.lines_done:>4}/{metrics.lines:<4} {metrics.lines_per_100:>6.1f} {share:>7}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--domain", choices=("m", "a"), default="m")
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--budget", type=float, default=1.0)
    parser.add_argument("--robots", type=int, default=20)
    parser.add_argument("--every", type=int, default=2)
    parser.add_argument("--compare-steps", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    domain = Domain.parse(args.domain)
    instance, releases = scenario(args.robots, args.steps, args.every, args.seed)
    print(f"scenario: 46x15, {len(instance.robots)} robots, {len(instance.orders)} orders, one every {args.every} "
          f"steps, {args.steps} steps, budget {args.budget:g} s a call, domain {domain.label}", flush=True)
    run, wall = multishot_run(instance, domain, releases, args.steps, args.budget)
    online = scenario_of(instance, run.releases)  # the figures judge each order after its release
    metrics = measure(online, run.plan, domain, run.releases, run.steps, run.calls, len(run.waiting))
    top = ceiling(online, domain, run.releases, run.steps)
    judged = online if domain.delivers else replace(instance, orders={})
    errors = [e for e in check(judged, run.plan, domain, bound=None).errors if e.module != "goal"]
    print(f"multi-shot run: {wall:.0f} s wall, peak memory {peak_mb():.0f} MB, plan "
          f"{'INVALID: ' + errors[0].message if errors else 'valid'}, ceiling {top.lines} lines "
          f"({top.lines_per_100:.1f} per 100 steps)")
    header = f"{'planner':<26} {'steps':>5} {'calls':>5} {'mean s':>8} {'max s':>7} {'wait':>5} {'lines':>9} " \
             f"{'/100':>6} {'ceiling':>7}"
    print(header)
    print(row("multishot", metrics, top.lines))
    if metrics.latency.orders:
        print(f"  latency: mean {metrics.latency.mean:.1f}, p95 {metrics.latency.p95}, max {metrics.latency.most}")
    if not args.compare_steps:
        return 0
    prefix = args.compare_steps
    times = same_questions(instance, domain, releases, prefix, args.budget)
    if times:
        ours, fresh = (sum(pair[k] for pair in times) / len(times) for k in (0, 1))
        print(f"same questions, first {prefix} steps, {len(times)} calls that solve: multishot {ours:.3f} s a call, "
              f"a new Control every call {fresh:.3f} s: {fresh / ours:.1f}x")
    if domain.goal is Goal.SHELVES:
        scratch = scratch_run(instance, domain, releases, prefix, args.budget)
        versus = measure(online, scratch.plan, domain, scratch.releases, scratch.steps, scratch.calls,
                         len(scratch.waiting))
        print(row(f"scratch asp, first {prefix}", versus))
    return 0


if __name__ == "__main__":
    sys.exit(main())
