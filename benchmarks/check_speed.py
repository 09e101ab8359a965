"""How fast ``check`` answers: whole commands first (interpreter start included), then the
ASP checker (``asprilo.checker.check``) and the simulator in a warm process.  Each figure is
the median wall-clock time of several runs.

Whole commands (issue 32, item 3 and the small M solve; targets in brackets):
  check small-a       check on the small A example with its outcome.txt        [<= 0.15 s]
  check small-a -B    the same with --bound strong (the strongest bound)       [none]
  check medium-a      check on the medium A example with a plan                [<= 0.3 s]
                      (the anytime planner's first plan, made once before timing)
  original checker    the issue's 1.1-1.3 s for the small A example (the original ASP
                      checker is not installed here), over check small-a      [>= 7x]
  solve small-m       asprilo solve with defaults on the paper's small M instance
                      with 11 robots (makespan 4)                              [<= 0.15 s]
  python              the interpreter alone (python -c pass), for scale
The lower bound that check shows is the cheap one unless --bound strong asks for the
strongest; the line after the table says which bound each check command showed.
--pythonpath DIR runs the commands with that folder first on the Python path (a copy of
another commit installed with ``pip install --no-deps --target DIR``), to time a version
before a change on the same machine; the commands run in an empty folder, so that the
checkout's own folders are not on the path.

Warm-process cases (targets of the checker's issue in brackets):
  outcome       the 29-step domain-A plan of the paper's example            [<= 0.5 s]
  m46           a valid 46-robot plan on the paper's large 46x15 M instance  [<= 1 s]
  b45           the 45-step domain-B plan x46_y15_..._N1.plan (invalid)     [<= 2 s]
  1000x500      1,000 robots x 500 steps of moves on a 100x100 floor        [<= 10 s]
                (valid: every robot shuttles in its own two cells)
  1000x500walk  the same as a random walk (invalid: ~31,000 collisions)

Times are of ``check(instance, plan)`` in a warm process (its programs parsed once).

Usage: python benchmarks/check_speed.py [--repeat N] [--commands | --quick] [--pythonpath DIR]
(--commands: the whole commands only; --quick leaves out the two 1000x500 cases.)
"""

from __future__ import annotations

import argparse
import heapq
import math
import os
import random
import statistics
import subprocess
import sys
import tempfile
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
SMALL_A = EXAMPLES / "asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
OUTCOME = EXAMPLES / "asprilo/dom-a/small/outcome.txt"
MEDIUM_A = EXAMPLES / "asprilo/dom-a/medium/x19_y9_n171_r6_s45_ps3_pr180_u540_o12_N1.lp"
SMALL_M = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp"
#: the original ASP checker on the small A example, as the issue measured it (not installed here)
ORIGINAL_CHECKER = (1.1, 1.3)


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


def medium_plan(folder: Path) -> Path:
    """A plan for the medium A example: the anytime planner's first checked plan."""
    from asprilo.encodings import solve
    from asprilo.writer import format_plan
    outcome = solve(read_instance(MEDIUM_A), method="anytime", time_limit=20)
    if outcome.plan is None:
        raise SystemExit(f"no plan for {MEDIUM_A.name} within 20 s: {outcome.message}")
    path = folder / "medium-plan.lp"
    path.write_text(format_plan(outcome.plan))
    return path


def _median_run(command: list[str], variables: dict, folder: str, repeat: int,
                warm_up: int) -> tuple[float, subprocess.CompletedProcess]:
    """The median wall time of ``repeat`` runs of ``command`` after ``warm_up`` runs, and the
    last run (the first that fails, if one does)."""
    runs = []
    for run in range(warm_up + repeat):
        started = time.perf_counter()
        done = subprocess.run(command, capture_output=True, text=True, env=variables, cwd=folder)
        if done.returncode not in (0, 1):
            return math.nan, done
        if run >= warm_up:
            runs.append(time.perf_counter() - started)
    return statistics.median(runs), done


def command_times(repeat: int, pythonpath: str | None) -> None:
    """The whole commands of the module docstring, each the median of ``repeat`` runs: with
    the modules' bytecode cached (as after ``pip install``, which compiles it; here in a
    folder of its own, after a first run that writes it) and compiled from source at every
    start (``PYTHONDONTWRITEBYTECODE=1`` without a cache, as in a checkout that is never
    written to)."""
    environment = {key: value for key, value in os.environ.items() if key != "PYTHONDONTWRITEBYTECODE"}
    if pythonpath:
        environment["PYTHONPATH"] = pythonpath + os.pathsep + environment.get("PYTHONPATH", "")
    asprilo = [sys.executable, "-m", "asprilo.cli"]
    with tempfile.TemporaryDirectory() as folder:
        cached = dict(environment, PYTHONPYCACHEPREFIX=str(Path(folder) / "bytecode"))
        uncached = dict(environment, PYTHONDONTWRITEBYTECODE="1")
        print("making a plan for the medium A example ...", file=sys.stderr, flush=True)
        medium = medium_plan(Path(folder))
        cases = [
            ("check small-a", 0.15, [*asprilo, "check", str(SMALL_A), str(OUTCOME)]),
            ("check small-a -B", None, [*asprilo, "check", str(SMALL_A), str(OUTCOME), "--bound", "strong"]),
            ("check medium-a", 0.3, [*asprilo, "check", str(MEDIUM_A), str(medium)]),
            ("solve small-m", 0.15, [*asprilo, "solve", str(SMALL_M)]),
            ("python", None, [sys.executable, "-c", "pass"]),
        ]
        print(f"{'whole command':18s} {'cached s':>8s} {'source s':>8s} {'target':>6s}  (medians of {repeat} runs)")
        times, said = {}, {}
        for name, target, command in cases:
            medians = []
            for variables, warm_up in ((cached, 1), (uncached, 0)):  # the first cached run writes the bytecode
                seconds, done = _median_run(command, variables, folder, repeat, warm_up)
                if done.returncode not in (0, 1):  # an older version without the option
                    print(f"{name:18s} exit status {done.returncode}: {done.stderr.strip().splitlines()[-1]}")
                    break
                medians.append(seconds)
            if len(medians) < 2:
                continue
            times[name] = medians[0]
            lines = done.stdout.strip().splitlines()
            said[name] = next((line for line in lines if line.startswith("lower bound")), "")
            shown = "-" if target is None else f"{target:.2f}"
            print(f"{name:18s} {medians[0]:8.3f} {medians[1]:8.3f} {shown:>6s}", flush=True)
    low, high = ORIGINAL_CHECKER
    check_small = times["check small-a"]
    print(f"original checker   {low:.1f}-{high:.1f} s (the issue's figure, not measured here): "
          f"{low / check_small:.1f}-{high / check_small:.1f}x the time of check small-a, cached [>= 7x]")
    for name in ("check small-a", "check small-a -B", "check medium-a"):
        if name in said:
            print(f"{name}: {said[name] or '(no bound line)'}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per case (median reported; large cases: 3)")
    parser.add_argument("--quick", action="store_true", help="leave out the 1000x500 cases")
    parser.add_argument("--commands", action="store_true", help="the whole commands only")
    parser.add_argument("--pythonpath", metavar="DIR", help="run the commands with DIR first on the Python path")
    args = parser.parse_args(argv)

    command_times(args.repeat, args.pythonpath)
    if args.commands:
        return 0
    print()
    m46 = read_instance(EXAMPLES / "paper-m/4x5x8/x46_y15_n690_r46_s320_ps10_pr320_u320_o46_N001.lp")
    cases = [
        ("outcome", 0.5, lambda: (read_instance(SMALL_A), read_plan(OUTCOME))),
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
    return 0


if __name__ == "__main__":
    sys.exit(main())
