"""The anytime planner at warehouse scale (issue 36): time and memory against the work.

Targets:
  movingai  MovingAI random-32-32-20, scenario random-1, labelled agents (Md): 200 agents a
            first plan within 5 s, 400 within 30 s; for 200, the sum of costs after 60 s at
            most 1.3 x the sum of shortest paths (the planner's sum-of-costs bound)
  g100      A, 100x100, 200 robots, 1,000 shelves: a first plan within 30 s, peak <= 1 GB
  g200      A, 200x200, 1,000 robots, 5,000 shelves: a first plan within 120 s, peak <= 2 GB
  paper     the large paper-style instances (46x15; the bundled four, or --count N per robot
            count generated from paper-m.yml) as A, B and C, 30 s each, in one process: A,
            then B starting from A's plan, then C from B's (readings.plan_readings), so that
            C <= B <= A by construction (B and C report the plan before them first): a first
            plan within 10 s, at most 1.2 x the lower bound at the end, the three readings
            within 5%
  scale     A on floors growing with the robots (10 .. 1,000 robots, 50 cells and 5 shelves
            per robot): seconds and MB to the first plan, per robot

Every run is a process of its own (spawned: its peak memory, Linux's VmHWM, is its own);
runs go --jobs at a time, so on a small machine the times include the other job's load.
Prints one table per target, writes the runs to OUT/scale-runs.jsonl and the plot of time
and memory per robot against the robots to --plot.

Run: python benchmarks/warehouse_scale.py [--targets movingai,g100,g200,paper,scale] [--jobs 1]
                                          [--count 0] [--out /tmp/warehouse-scale] [--plot FILE.png]
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from statistics import mean

ROOT = Path(__file__).resolve().parent.parent
MOVINGAI = ROOT / "examples/movingai"
PAPER_LARGE = ROOT / "examples/paper-m/4x5x8"
SCALE = (10, 30, 100, 300, 1000)


def floor_options(robots: int, side: int | None = None) -> dict:
    """Generator options of an A instance for ``robots``: a square floor of about 50 cells per
    robot (or ``side``), 5 shelves and products per robot, a station per 10 robots; the
    structured layout (highways, robots below the storage) where the robots fit below it."""
    side = side or round(math.sqrt(50 * robots))
    layout = {"-X": 5, "-Y": 2, "-H": True} if robots <= 2 * side else {}
    return {"-x": side, "-y": side, **layout, "-p": max(1, robots // 10), "-s": 5 * robots, "-r": robots,
            "-P": 5 * robots, "-u": 15 * robots, "-o": max(1, robots // 2)}


def run_one(job: dict) -> dict:
    """One anytime run in its own process: the plans it reported and its peak memory.
    ``first_only``: stop at the first plan; ``readings``: the domain and its stronger readings
    in turn (:func:`run_readings`)."""
    from asprilo.domain import Domain
    from asprilo.encodings.anytime import plan_anytime
    from asprilo.isolation import peak_memory_mb
    from asprilo.reader import read_instance

    instance = read_instance(job["path"])
    if job.get("readings"):
        return run_readings(job, instance)
    found = threading.Event()
    started = time.perf_counter()
    result = plan_anytime(instance, Domain.parse(job["domain"]), time_limit=job["limit"], cancel=found,
                          on_improvement=(lambda _: found.set()) if job.get("first_only") else None)
    return {**job, "seconds": time.perf_counter() - started, "status": str(result.status), "bound": result.bound,
            "soc_bound": result.sum_of_costs_bound, "robots": len(instance.robots),
            "cells": len(instance.cells), "history": [better.figures() for better in result.history],
            "peak_mb": peak_memory_mb()}


def run_readings(job: dict, instance) -> dict:
    """The readings of one instance, the strongest first, each starting from the plan before:
    one entry per reading under ``readings`` (its seconds counted from its own start)."""
    from asprilo.domain import Domain
    from asprilo.encodings.anytime.readings import plan_readings
    from asprilo.isolation import peak_memory_mb

    started = time.perf_counter()
    results = plan_readings(instance, Domain.parse(job["domain"]), job["limit"])
    return {**job, "seconds": time.perf_counter() - started, "robots": len(instance.robots),
            "cells": len(instance.cells), "peak_mb": peak_memory_mb(),
            "readings": {label.lower(): {"status": str(result.status), "bound": result.bound,
                                         "soc_bound": result.sum_of_costs_bound, "start": result.stats.get("start"),
                                         "history": [better.figures() for better in result.history]}
                         for label, result in results.items()}}


def one_per_reading(run: dict) -> list[dict]:
    """A run of several readings as one run per reading (the rows of the tables)."""
    if "readings" not in run:
        return [run]
    shared = {key: value for key, value in run.items() if key not in ("readings", "domain")}
    return [{**shared, **figures, "domain": label} for label, figures in run["readings"].items()]


# --- instances ---------------------------------------------------------------------------------

def generated(out: Path, name: str, options: dict) -> Path:
    from asprilo.generator import GeneratorConfig, generate
    from asprilo.writer import format_instance, write_text
    path = out / f"{name}.lp"
    if not path.exists():
        print(f"generating {name}", file=sys.stderr)
        item = generate(GeneratorConfig.from_options(options), count=1, seed=1)[0]
        write_text(path, format_instance(item.instance))
    return path


def movingai(out: Path, agents: int) -> Path:
    from asprilo.interop.convert import scenario_to_instance
    from asprilo.interop.movingai import parse_map, parse_scenario
    from asprilo.sources import Source
    from asprilo.writer import format_instance, write_text
    path = out / f"random-32-32-20-labelled-{agents}.lp"
    if not path.exists():
        grid = parse_map(Source.from_path(MOVINGAI / "random-32-32-20.map"))
        tasks = parse_scenario(Source.from_path(MOVINGAI / "random-32-32-20-random-1.scen"))
        write_text(path, format_instance(scenario_to_instance(grid, tasks, agents, labelled=True)))
    return path


def paper_large(out: Path, count: int) -> list[Path]:
    if not count:
        return sorted(PAPER_LARGE.glob("*.lp"))
    from asprilo.generator import generate_batch
    folder = out / "paper-m"
    generate_batch(ROOT / "benchmarks/paper-m.yml", folder, count=count)
    return sorted(folder.glob("4x5x8/*/*.lp"))


def jobs(targets: list[str], out: Path, count: int) -> list[dict]:
    found = []
    if "movingai" in targets:
        found += [{"target": "movingai", "set": f"{agents} agents", "path": str(movingai(out, agents)), "domain": "md",
                   "limit": 60} for agents in (200, 400)]
    if "g100" in targets:
        found.append({"target": "g100", "set": "100x100", "domain": "a", "limit": 60,
                      "path": str(generated(out, "g100", floor_options(200, 100)))})
    if "g200" in targets:
        found.append({"target": "g200", "set": "200x200", "domain": "a", "limit": 180, "first_only": True,
                      "path": str(generated(out, "g200", floor_options(1000, 200)))})
    if "paper" in targets:  # C and its stronger readings, B and A, in turn
        found += [{"target": "paper", "set": path.stem, "path": str(path), "domain": "c", "readings": True,
                   "limit": 30} for path in paper_large(out, count)]
    if "scale" in targets:
        found += [{"target": "scale", "set": f"{robots} robots", "domain": "a", "limit": 300, "first_only": True,
                   "path": str(generated(out, f"scale-{robots}", floor_options(robots)))} for robots in SCALE]
    return found


# --- tables and the plot -----------------------------------------------------------------------

def first(run: dict) -> float | None:
    return run["history"][0]["seconds"] if run["history"] else None


def table(runs: list[dict]) -> str:
    lines = [f"{'target':<9}{'set':<44}{'dom':<4}{'robots':>7}{'first s':>9}{'makespan':>9}{'/bound':>8}"
             f"{'SOC/bound':>10}{'peak MB':>9}"]
    for run in runs:
        last = run["history"][-1] if run["history"] else None
        ratio = last["makespan"] / run["bound"] if last and run["bound"] else float("nan")
        soc = last["sum_of_costs"] / run["soc_bound"] if last and run["soc_bound"] else float("nan")
        lines.append(f"{run['target']:<9}{run['set'][:43]:<44}{run['domain']:<4}{run['robots']:>7}"
                     f"{first(run) or float('nan'):>9.2f}{last['makespan'] if last else '-':>9}{ratio:>8.3f}"
                     f"{soc:>10.3f}{run['peak_mb']:>9.0f}")
    return "\n".join(lines)


def readings(runs: list[dict]) -> str:
    """Per paper instance: the final makespans as A, B and C and how far apart they are (B
    starts from A's plan and C from B's: C <= B <= A)."""
    lines = []
    for name in sorted({r["set"] for r in runs if r["target"] == "paper"}):
        spans = {r["domain"]: r["history"][-1]["makespan"] for r in runs
                 if r["target"] == "paper" and r["set"] == name and r["history"]}
        if len(spans) == 3:
            apart = max(spans.values()) / min(spans.values()) - 1
            lines.append(f"{name}: A {spans['a']}, B {spans['b']}, C {spans['c']}: {100 * apart:.1f}% apart")
    return "\n".join(lines)


def plot(runs: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    points = sorted((r["robots"], first(r), r["peak_mb"]) for r in runs if r["target"] == "scale" and first(r))
    if not points:
        return
    robots, seconds, memory = zip(*points, strict=True)
    figure, (left, right) = plt.subplots(1, 2, figsize=(9, 3.6))
    left.plot(robots, [s / n * 1000 for s, n in zip(seconds, robots, strict=True)], marker="o")
    left.set(xscale="log", xlabel="robots", ylabel="ms per robot", title="time to the first plan")
    right.plot(robots, [m / n for m, n in zip(memory, robots, strict=True)], marker="o", color="tab:orange")
    right.set(xscale="log", yscale="log", xlabel="robots", ylabel="MB per robot", title="peak memory")
    figure.suptitle("anytime planner, domain A, 50 cells and 5 shelves per robot")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print(f"wrote {path}", file=sys.stderr)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--targets", default="movingai,g100,g200,paper,scale")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--count", type=int, default=0, help="paper instances per robot count (0: the bundled four)")
    parser.add_argument("--out", type=Path, default=Path("/tmp/warehouse-scale"))
    parser.add_argument("--plot", type=Path, default=ROOT / "benchmarks/pictures/warehouse-scale.png")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    todo = jobs(args.targets.split(","), args.out, args.count)
    print(f"{len(todo)} runs, {args.jobs} at a time", file=sys.stderr)
    runs = []
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(args.jobs, mp_context=context, max_tasks_per_child=1) as pool, \
            open(args.out / "scale-runs.jsonl", "w") as log:
        for number, run in enumerate(pool.map(run_one, todo), 1):
            log.write(json.dumps(run) + "\n")
            for row in one_per_reading(run):
                print(f"[{number}/{len(todo)}] {row['target']} {row['set']} {row['domain']}: first plan "
                      f"{first(row) if first(row) is not None else '-'} s, peak {row['peak_mb']:.0f} MB",
                      file=sys.stderr)
                runs.append(row)
    print(table(runs))
    if any(r["target"] == "paper" for r in runs):
        print(readings(runs))
        ends = [r["history"][-1]["makespan"] / r["bound"] for r in runs if r["target"] == "paper" and r["history"]]
        print(f"paper: mean makespan / bound at the end {mean(ends):.3f}, worst {max(ends):.3f}")
    plot(runs, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
