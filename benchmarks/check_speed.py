"""How fast the ASP checker (``asprilo.checker.check``) and the simulator are on the sizes
that matter: prints one line per case with the median wall-clock time of several runs.

Cases (targets of the checker's issue in brackets):
  outcome       the 29-step domain-A plan of the paper's example            [<= 0.5 s]
  m46           a valid 46-robot plan on the paper's large 46x15 M instance  [<= 1 s]
  b45           the 45-step domain-B plan x46_y15_..._N1.plan (invalid)     [<= 2 s]
  1000x500      1,000 robots x 500 steps of moves on a 100x100 floor        [<= 10 s]
                (valid: every robot shuttles in its own two cells)
  1000x500walk  the same as a random walk (invalid: ~31,000 collisions)

Times are of ``check(instance, plan)`` in a warm process (its programs parsed once),
plus one line for the whole ``check`` command on the outcome (interpreter start included).

Usage: python benchmarks/check_speed.py [--repeat N] [--quick]
(--quick leaves out the two 1000x500 cases.)
"""

from __future__ import annotations

import argparse
import heapq
import random
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import linear_sum_assignment

from asprilo.bounds import Floor, goal_cells
from asprilo.checker import check
from asprilo.model import DIRECTIONS, Action, Instance, Plan, Robot
from asprilo.reader import read_instance, read_plan
from asprilo.simulate import simulate

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


# --- plans to check ----------------------------------------------------------------------

def prioritized_m_plan(instance: Instance, limit: int = 300) -> Plan:
    """A collision-free M plan: robots assigned to goal cells by a minimum-cost assignment,
    then routed one after the other by space-time search around the reservations of the
    robots routed before (robots not yet routed block their start cells)."""
    floor = Floor(instance.cells)
    robots = sorted(instance.robots.values(), key=lambda r: r.id)
    goals = goal_cells(instance)
    costs = floor.distances([r.at for r in robots], goals)
    rows, columns = linear_sum_assignment(np.where(np.isfinite(costs), costs, 10**6))
    target = {robots[r].id: goals[c] for r, c in zip(rows, columns, strict=True)}
    order = sorted(target, key=lambda robot: -costs[robots.index(instance.robots[robot]), goals.index(target[robot])])
    taken: set[tuple] = set()          # (cell, t)
    crossed: set[tuple] = set()        # (from, to, t)
    parked: dict[tuple, int] = {}      # cell -> from when a routed robot stays there for good
    waiting = {r.at for r in robots}
    actions = []
    for robot in order:
        start, goal = instance.robots[robot].at, target[robot]
        waiting.discard(start)
        path = _route(floor.index, start, goal, taken, crossed, parked, waiting, limit)
        for t, (a, b) in enumerate(zip(path, path[1:], strict=False), start=1):
            taken.add((b, t))
            crossed.add((b, a, t))
            if a != b:
                actions.append(Action(t, robot, "move", (b[0] - a[0], b[1] - a[1])))
        taken.add((path[0], 0))
        parked[path[-1]] = len(path) - 1
    return Plan(actions)


def _route(cells, start, goal, taken, crossed, parked, waiting, limit):
    def free(cell, t):
        return (cell, t) not in taken and not (cell in parked and parked[cell] <= t) and cell not in waiting

    last_busy = max([t for (cell, t) in taken if cell == goal], default=-1)
    queue = [(abs(start[0] - goal[0]) + abs(start[1] - goal[1]), 0, start, None)]
    parent = {(start, 0): None}
    while queue:
        _f, t, cell, _ = heapq.heappop(queue)
        if cell == goal and t > last_busy:
            path = [(cell, t)]
            while parent[path[-1]] is not None:
                path.append(parent[path[-1]])
            return [c for c, _t in reversed(path)]
        if t >= limit:
            continue
        for dx, dy in ((0, 0), *DIRECTIONS):
            nxt = (cell[0] + dx, cell[1] + dy)
            if nxt not in cells or (nxt, t + 1) in parent or not free(nxt, t + 1) or (cell, nxt, t + 1) in crossed:
                continue
            parent[(nxt, t + 1)] = (cell, t)
            heapq.heappush(queue, (t + 1 + abs(nxt[0] - goal[0]) + abs(nxt[1] - goal[1]), t + 1, nxt, None))
    raise RuntimeError(f"no route from {start} to {goal}")


def shuttle_floor(robots: int = 1000, steps: int = 500, size: int = 100, walk: bool = False,
                  seed: int = 1) -> tuple[Instance, Plan]:
    """``robots`` robots on a ``size`` x ``size`` floor, one move each per step: shuttling
    east and west in two cells of their own (valid) or walking at random (``walk``)."""
    instance = Instance(nodes={i: (1 + i % size, 1 + i // size) for i in range(size * size)})
    pairs = [(x, y) for y in range(1, size + 1) for x in range(1, size, 2)][:robots]
    instance.robots = {r: Robot(r, cell) for r, cell in enumerate(pairs, start=1)}
    rng = random.Random(seed)
    actions = []
    position = {r: robot.at for r, robot in instance.robots.items()}
    for t in range(1, steps + 1):
        for r in instance.robots:
            if walk:
                x, y = position[r]
                d = rng.choice([d for d in DIRECTIONS if 1 <= x + d[0] <= size and 1 <= y + d[1] <= size])
                position[r] = (x + d[0], y + d[1])
            else:
                d = (1, 0) if t % 2 else (-1, 0)
            actions.append(Action(t, r, "move", d))
    return instance, Plan(actions)


# --- measuring ---------------------------------------------------------------------------

def median_time(function, repeat: int) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeat):
        started = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - started)
    return statistics.median(times), result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per case (median reported; large cases: 3)")
    parser.add_argument("--quick", action="store_true", help="leave out the 1000x500 cases")
    args = parser.parse_args(argv)

    small = EXAMPLES / "asprilo/dom-a/small"
    m46 = read_instance(EXAMPLES / "paper-m/4x5x8/x46_y15_n690_r46_s320_ps10_pr320_u320_o46_N001.lp")
    cases = [
        ("outcome", 0.5, lambda: (read_instance(small / "x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"),
                                  read_plan(small / "outcome.txt"))),
        ("m46", 1.0, lambda: (m46, prioritized_m_plan(m46))),
        ("b45", 2.0, lambda: (read_instance(EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.lp"),
                              read_plan(EXAMPLES / "encodings-repo/x46_y15_n690_r10_s160_ps10_pr5_u10_o2_N1.plan"))),
    ]
    if not args.quick:
        cases += [("1000x500", 10.0, lambda: shuttle_floor()),
                  ("1000x500walk", 10.0, lambda: shuttle_floor(walk=True))]
    print(f"{'case':14s} {'robots':>6s} {'steps':>5s} {'actions':>7s} {'errors':>6s} "
          f"{'check s':>8s} {'target':>6s} {'ground s':>8s} {'simulate s':>10s}", flush=True)
    for name, target, build in cases:
        print(f"{name:14s} building ...", end="\r", file=sys.stderr, flush=True)
        instance, plan = build()
        repeat = args.repeat if len(plan) < 100_000 else min(args.repeat, 3)
        seconds, report = median_time(lambda instance=instance, plan=plan: check(instance, plan), repeat)
        simulated, _ = median_time(lambda instance=instance, plan=plan, domain=report.domain:
                                   simulate(instance, plan, domain), repeat)
        print(f"{name:14s} {len(instance.robots):6d} {report.horizon:5d} {len(plan):7d} {len(report.errors):6d} "
              f"{seconds:8.2f} {target:6.1f} {report.statistics['ground_time']:8.2f} {simulated:10.2f}", flush=True)
    command = [sys.executable, "-m", "asprilo.cli", "check", str(small / "x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"),
               str(small / "outcome.txt")]
    seconds, _ = median_time(lambda: subprocess.run(command, capture_output=True, check=True), args.repeat)
    print(f"the command 'asprilo check' on the outcome: {seconds:.2f} s (interpreter start included)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
