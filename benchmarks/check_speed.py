"""How fast ``check`` answers: whole commands first (interpreter start included), then the
ASP checker (``asprilo.checker.check``) and the simulator in a warm process.  Each figure is
the median wall-clock time of several runs.

Whole commands (issue 32, item 3, issue 44, part 4 and the small M solve; targets in brackets):
  check small-a       the ``check`` command on the small A example with its
                      outcome.txt                                              [<= 0.15 s]
  asprilo check ...   the same as ``asprilo check`` (python -m asprilo.cli)    [<= 0.15 s]
  check small-a -B    the same with --bound strong (the strongest bound)       [none]
  check wrong-a       check on the small A example with wrong_outcome.txt
                      (3 violations, worded by the simulator)                  [none]
  check medium-a      check on the medium A example with a plan                [<= 0.3 s]
                      (the anytime planner's first plan, made once before timing)
  original checker    --original 'COMMAND {instance} {plan}': the original ASP checker
                      on the small A example, timed run for run beside check small-a;
                      without it, the issue's 1.1-1.3 s (it is not installed
                      here); the ratio over check small-a                      [>= 10x]
  solve small-m       asprilo solve with defaults on the paper's small M instance
                      with 11 robots (makespan 4)                              [<= 0.15 s]
  python              the interpreter alone (python -c pass), for scale
Each figure is the median of --runs runs (default 11), with the bytecode cached and
compiled from source.  Then where check small-a's start-up goes: ``python -X importtime``,
the least of --runs runs per module.  The lower bound that check shows is the cheap one
unless --bound strong asks for the strongest; the lines after the table say which bound each
check command showed.  --pythonpath DIR runs the commands with that folder first on the
Python path (a copy of another commit: ``git archive COMMIT | tar -x -C DIR``, the package
folder ``asprilo/`` at its top), to time a version before a change on the same machine; the
commands run in an empty folder, so that the checkout's own folders are not on the path.

Warm-process cases (targets of the checker's issue in brackets):
  outcome       the 29-step domain-A plan of the paper's example            [<= 0.5 s]
  m46           a valid 46-robot plan on the paper's large 46x15 M instance  [<= 1 s]
  b45           the 45-step domain-B plan x46_y15_..._N1.plan (invalid)     [<= 2 s]
  1000x500      1,000 robots x 500 steps of moves on a 100x100 floor        [<= 10 s]
                (valid: every robot shuttles in its own two cells)
  1000x500walk  the same as a random walk (invalid: ~31,000 collisions)

Times are of ``check(instance, plan)`` in a warm process (its programs parsed once).

Usage: python benchmarks/check_speed.py [--runs N] [--repeat N] [--commands | --quick] [--pythonpath DIR]
                                        [--original 'COMMAND {instance} {plan}']
(--commands: the whole commands only; --quick leaves out the two 1000x500 cases; --repeat:
runs per warm-process case.)
"""

from __future__ import annotations

import argparse
import heapq
import math
import os
import random
import re
import shlex
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
WRONG_OUTCOME = EXAMPLES / "asprilo/dom-a/small/wrong_outcome.txt"
MEDIUM_A = EXAMPLES / "asprilo/dom-a/medium/x19_y9_n171_r6_s45_ps3_pr180_u540_o12_N1.lp"
SMALL_M = EXAMPLES / "paper-m/1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp"
#: the original ASP checker on the small A example, as the issue measured it (not installed here)
ORIGINAL_CHECKER = (1.1, 1.3)
#: how many times faster than the original checker check small-a should be (issue 44, part 4)
ORIGINAL_RATIO = 10.0


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


def _median_runs(commands: dict[str, list[str]], variables: dict, folder: str, runs: int,
                 warm_up: int) -> dict[str, tuple[float, subprocess.CompletedProcess]]:
    """For each of ``commands`` (name -> argv) the median wall time of ``runs`` runs after
    ``warm_up`` runs, the commands taking turns run by run (a load that comes and goes
    falls on all of them), and its last run (the first that fails, if one does)."""
    times: dict[str, list[float]] = {name: [] for name in commands}
    last: dict[str, subprocess.CompletedProcess] = {}
    for run in range(warm_up + runs):
        for name, command in commands.items():
            if name in last and last[name].returncode not in (0, 1):
                continue
            started = time.perf_counter()
            last[name] = subprocess.run(command, capture_output=True, text=True, env=variables, cwd=folder)
            if run >= warm_up:
                times[name].append(time.perf_counter() - started)
    return {name: (statistics.median(times[name]) if last[name].returncode in (0, 1) else math.nan, last[name])
            for name in commands}


def _environments(pythonpath: str | None, folder: str) -> tuple[dict, dict]:
    """The environments of the cached and the from-source runs."""
    environment = {key: value for key, value in os.environ.items() if key != "PYTHONDONTWRITEBYTECODE"}
    if pythonpath:
        environment["PYTHONPATH"] = pythonpath + os.pathsep + environment.get("PYTHONPATH", "")
    cached = dict(environment, PYTHONPYCACHEPREFIX=str(Path(folder) / "bytecode"))
    return cached, dict(environment, PYTHONDONTWRITEBYTECODE="1")


def _check_command() -> list[str]:
    """The ``check`` command as installed beside this interpreter (else ``python -c`` running it)."""
    script = Path(sys.executable).parent / "check"
    if script.is_file():
        return [str(script)]
    return [sys.executable, "-c", "import sys; from asprilo.cli import check_main; sys.exit(check_main())"]


def command_times(runs: int, pythonpath: str | None, original: str | None) -> None:
    """The whole commands of the module docstring, each the median of ``runs`` runs: with
    the modules' bytecode cached (as after ``pip install``, which compiles it; here in a
    folder of its own, after a first run that writes it) and compiled from source at every
    start (``PYTHONDONTWRITEBYTECODE=1`` without a cache, as in a checkout that is never
    written to); ``original``: the original checker's command line, timed beside check small-a."""
    asprilo = [sys.executable, "-m", "asprilo.cli"]
    check = _check_command()
    with tempfile.TemporaryDirectory() as folder:
        cached, uncached = _environments(pythonpath, folder)
        print("making a plan for the medium A example ...", file=sys.stderr, flush=True)
        medium = medium_plan(Path(folder))
        cases = [
            ("check small-a", 0.15, [*check, str(SMALL_A), str(OUTCOME)]),
            ("asprilo check ...", 0.15, [*asprilo, "check", str(SMALL_A), str(OUTCOME)]),
            ("check small-a -B", None, [*check, str(SMALL_A), str(OUTCOME), "--bound", "strong"]),
            ("check wrong-a", None, [*check, str(SMALL_A), str(WRONG_OUTCOME)]),
            ("check medium-a", 0.3, [*check, str(MEDIUM_A), str(medium)]),
            ("solve small-m", 0.15, [*asprilo, "solve", str(SMALL_M)]),
            ("python", None, [sys.executable, "-c", "pass"]),
        ]
        if original:
            cases.insert(1, ("original checker", None,
                             [word.format(instance=SMALL_A, plan=OUTCOME) for word in shlex.split(original)]))
        commands = {name: command for name, _target, command in cases}
        print(f"{'whole command':18s} {'cached s':>8s} {'source s':>8s} {'target':>6s}  (medians of {runs} runs)")
        measured = [_median_runs(commands, cached, folder, runs, 1),  # the first cached run writes the bytecode
                    _median_runs({name: command for name, command in commands.items() if name != "original checker"},
                                 uncached, folder, runs, 0)]  # the original checker is no Python: once is enough
        times, said = {}, {}
        for name, target, _command in cases:
            (seconds, done), (source, _) = measured[0][name], measured[1].get(name, measured[0][name])
            if done.returncode not in (0, 1):  # an older version without the option
                print(f"{name:18s} exit status {done.returncode}: {(done.stderr.strip().splitlines() or [''])[-1]}")
                continue
            times[name] = (seconds, source)
            said[name] = next((line for line in done.stdout.strip().splitlines() if line.startswith("lower bound")), "")
            shown = "-" if target is None else f"{target:.2f}"
            from_source = "-" if name == "original checker" else f"{source:.3f}"
            print(f"{name:18s} {seconds:8.3f} {from_source:>8s} {shown:>6s}", flush=True)
    _ratio_lines(times)
    for name in ("check small-a", "check small-a -B", "check medium-a"):
        if name in said:
            print(f"{name}: {said[name] or '(no bound line)'}")
    print()
    import_times([str(SMALL_A), str(OUTCOME)], runs, pythonpath)


def _ratio_lines(times: dict[str, tuple[float, float]]) -> None:
    """How many times faster than the original checker check small-a is, cached and from source."""
    if "check small-a" not in times:
        return
    cached, source = times["check small-a"]
    if "original checker" in times:
        original = times["original checker"][0]
        print(f"original checker   {original:.3f} s measured beside it: check small-a takes {cached:.3f} s cached, "
              f"{original / cached:.1f}x faster ({original / source:.1f}x from source) [>= {ORIGINAL_RATIO:g}x]")
        return
    low, high = ORIGINAL_CHECKER
    print(f"original checker   {low:.1f}-{high:.1f} s (the issue's figure, not measured here; --original to measure): "
          f"check small-a takes {cached:.3f} s cached, {low / cached:.1f}-{high / cached:.1f}x faster "
          f"({low / source:.1f}-{high / source:.1f}x from source) [>= {ORIGINAL_RATIO:g}x]")


_IMPORT_TIME = re.compile(r"import time:\s+(\d+) \|\s+(\d+) \|( *)(\S+)")


def import_times(arguments: list[str], runs: int, pythonpath: str | None, shown: int = 12) -> None:
    """Where the start-up of ``check ARGUMENTS`` goes: ``python -X importtime``, cached, the least time
    of ``runs`` runs per module; the modules imported at the top (with what they import) and
    asprilo's own."""
    program = "import sys; from asprilo.cli import check_main; sys.argv[0] = 'check'; sys.exit(check_main())"
    least: dict[str, tuple[int, int, int]] = {}  # module -> (self us, cumulative us, depth)
    with tempfile.TemporaryDirectory() as folder:
        cached, _ = _environments(pythonpath, folder)
        for _ in range(runs + 1):  # the first writes the bytecode
            done = subprocess.run([sys.executable, "-X", "importtime", "-c", program, *arguments],
                                  capture_output=True, text=True, env=cached, cwd=folder)
            for match in _IMPORT_TIME.finditer(done.stderr):
                module, own, total, depth = match[4], int(match[1]), int(match[2]), len(match[3]) // 2
                old = least.get(module, (own, total, depth))
                least[module] = (min(old[0], own), min(old[1], total), depth)
    top = sorted(((total, module) for module, (_own, total, depth) in least.items() if depth == 0), reverse=True)
    ours = sum(own for module, (own, _total, _depth) in least.items() if module.split(".")[0] == "asprilo")
    print(f"imports of check small-a, cached (python -X importtime, least of {runs} runs): "
          f"{sum(own for own, _total, _depth in least.values()) / 1000:.1f} ms in {len(least)} modules, "
          f"asprilo's own {ours / 1000:.1f} ms")
    print("  at the top: " + ", ".join(f"{module} {total / 1000:.1f}" for total, module in top[:shown]))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=11, help="runs per whole command (median reported)")
    parser.add_argument("--repeat", type=int, default=5,
                        help="runs per warm-process case (median reported; large cases: 3)")
    parser.add_argument("--quick", action="store_true", help="leave out the 1000x500 cases")
    parser.add_argument("--commands", action="store_true", help="the whole commands only")
    parser.add_argument("--pythonpath", metavar="DIR", help="run the commands with DIR first on the Python path")
    parser.add_argument("--original", metavar="COMMAND",
                        help="the original checker's command line, {instance} and {plan} in it: timed beside check")
    args = parser.parse_args(argv)

    command_times(args.runs, args.pythonpath, args.original)
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
