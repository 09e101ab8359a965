"""The online target of issue 43: the multi-shot ASP planner on the paper's 46x15 layout.

Scenario: the large paper layout (examples/paper-m/4x5x8, 46x15, 320 shelves each holding
one product, 10 picking stations) with its first 20 robots, and a stream of single-line,
single-unit orders (product and station drawn by a seeded generator), one released every
2 steps, for 1,000 steps.  Domain M (a line is done when a robot arrives under the shelf
holding its product after the release).  Domain A has no multi-shot encoding yet: not run.

Measured:
  multishot  the whole run with asprilo.online.multishot.MultiShot (one clingo Control):
             wall time, planner time per call (mean, max), waiting steps, throughput and the
             ceiling (asprilo.online.ceiling), order latency, the process's peak memory;
             the plan carried out is checked (asprilo check's rules of M on the layout
             without orders: every move legal; the online goal is what the figures measure)
  scratch    the same scenario's first --scratch-steps steps with FromScratch and the exact
             `asp` planner (a new solve from the world after every step it plans from), and
             the multi-shot run's calls over the same steps: planner time per call of both

Targets: the whole run within 10 minutes; planner time per call <= 1 s on average;
throughput >= 80 % of the ceiling; multi-shot >= 3x less planner time per call than scratch.

Run: python benchmarks/online.py [--steps 1000] [--budget 1] [--scratch-steps 100] [--seed 1]
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
from asprilo.domain import Domain  # noqa: E402
from asprilo.model import Instance, Order, Plan  # noqa: E402
from asprilo.online.ceiling import ceiling  # noqa: E402
from asprilo.online.metrics import Metrics, measure  # noqa: E402
from asprilo.online.multishot import MultiShot  # noqa: E402
from asprilo.online.planner import encodings_planner  # noqa: E402
from asprilo.online.planning import FromScratch  # noqa: E402
from asprilo.online.run import OnlineRun, run_online, scenario_of  # noqa: E402
from asprilo.reader import read_instance  # noqa: E402

#: the scenario's domain (the multi-shot planner's only one so far)
DOMAIN = Domain.parse("m")

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


def multishot_run(instance: Instance, releases: dict[int, int], steps: int, budget: float) -> tuple[OnlineRun, float]:
    started = time.perf_counter()
    planner = MultiShot(instance, DOMAIN)
    run = run_online(instance, DOMAIN, planner, releases, budget=budget, steps=steps,
                     on_step=lambda step, _run: step % 100 or print(f"  step {step}", file=sys.stderr, flush=True))
    return run, time.perf_counter() - started


def scratch_run(instance: Instance, releases: dict[int, int], steps: int, budget: float) -> OnlineRun:
    scratch = FromScratch(instance, DOMAIN, lambda seconds: encodings_planner(time_limit=seconds))
    return run_online(instance, DOMAIN, scratch, releases, budget=budget, steps=steps)


def row(name: str, metrics: Metrics, top: int | None = None) -> str:
    share = "" if not top else f"{100 * metrics.lines_done / top:5.1f} %"
    mean = "-" if metrics.planner_mean is None else f"{metrics.planner_mean:6.3f}"
    most = "-" if metrics.planner_max is None else f"{metrics.planner_max:6.2f}"
    return (f"{name:<26} {metrics.steps:>5} {metrics.calls:>5} {mean:>8} {most:>7} {metrics.waiting_steps:>5} "
            f"{metrics.lines_done:>4}/{metrics.lines:<4} {metrics.lines_per_100:>6.1f} {share:>7}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--budget", type=float, default=1.0)
    parser.add_argument("--robots", type=int, default=20)
    parser.add_argument("--every", type=int, default=2)
    parser.add_argument("--scratch-steps", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    instance, releases = scenario(args.robots, args.steps, args.every, args.seed)
    print(f"scenario: 46x15, {len(instance.robots)} robots, {len(instance.orders)} orders, one every {args.every} "
          f"steps, {args.steps} steps, budget {args.budget:g} s a call, domain M", flush=True)
    run, wall = multishot_run(instance, releases, args.steps, args.budget)
    online = scenario_of(instance, run.releases)  # the figures judge each order after its release
    metrics = measure(online, run.plan, DOMAIN, run.releases, run.steps, run.calls, len(run.waiting))
    top = ceiling(online, DOMAIN, run.releases, run.steps)
    report = check(replace(instance, orders={}), run.plan, DOMAIN, bound=None)  # the moves; M's goal is online
    print(f"multi-shot run: {wall:.0f} s wall, peak memory {peak_mb():.0f} MB, plan "
          f"{'valid' if report.valid else 'INVALID'}, ceiling {top.lines} lines "
          f"({top.lines_per_100:.1f} per 100 steps)")
    header = f"{'planner':<26} {'steps':>5} {'calls':>5} {'mean s':>8} {'max s':>7} {'wait':>5} {'lines':>9} " \
             f"{'/100':>6} {'ceiling':>7}"
    print(header)
    print(row("multishot", metrics, top.lines))
    if metrics.latency.orders:
        print(f"  latency: mean {metrics.latency.mean:.1f}, p95 {metrics.latency.p95}, max {metrics.latency.most}")
    if args.scratch_steps:
        prefix = args.scratch_steps
        early = [call for call in run.calls if call.step < prefix]
        short = measure(online, Plan([a for a in run.plan.actions if a.step <= prefix]), DOMAIN, run.releases,
                        prefix, early, sum(step <= prefix for step in run.waiting))
        scratch = scratch_run(instance, releases, prefix, args.budget)
        versus = measure(online, scratch.plan, DOMAIN, scratch.releases, scratch.steps, scratch.calls,
                         len(scratch.waiting))
        print(row(f"multishot, first {prefix}", short))
        print(row(f"scratch asp, first {prefix}", versus))
        if short.planner_mean and versus.planner_mean:
            print(f"planner time per call, scratch / multishot: {versus.planner_mean / short.planner_mean:.1f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
