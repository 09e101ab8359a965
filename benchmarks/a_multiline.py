"""Domain A with several products per shelf and several lines per order (issue 45): the
anytime planner's makespan against the lower bound on the exercise-size call, many seeds.

Every seed runs as whole commands: ``asprilo gen CALL --seed S -C`` writes the instance,
then ``asprilo solve --domain a --method anytime --time-limit T --json`` plans it.  The best
lower bound is then sought beyond the planner's: the trip relaxation (with the lifts that
clear a carry's way, :mod:`asprilo.bounds.trip`) from the planner's bound up, with
``--bound-conflicts`` per horizon instead of the planner's 20,000 (in a process of its own; horizons below the
planner's bound are refuted already).  Prints per seed the first plan's time, the makespan,
the planner's bound, the best bound, the ratio of the makespan to the best bound and whether
the plan is proven minimal (it meets a bound), then the median and the worst ratio, how many
are within 1.3x and how many proven.  ``--jobs`` runs that many seeds side by side (the load
average is printed first: timings on a shared machine are noisy).

Run: python benchmarks/a_multiline.py [--seeds 4501-4520] [--time-limit 60] [--jobs 2]
                                      [--bound-conflicts 200000] [--keep DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from gen_seeds import CALL, seed_list  # the exercise-size call of issues 44 and 45; seeds as 4501-4520

ASPRILO = [sys.executable, "-m", "asprilo.cli"]


def run_seed(seed: int, limit: float, folder: Path, conflicts: int) -> dict:
    """Generate the instance of ``seed``, plan it, and seek a better bound; the figures."""
    instance = folder / f"s{seed}.lp"
    made = subprocess.run([*ASPRILO, "gen", *shlex.split(CALL), "--seed", str(seed), "-C", "-q"],
                          capture_output=True, text=True)
    if made.returncode != 0:
        return {"seed": seed, "error": made.stderr.strip()}
    instance.write_text(made.stdout)
    done = subprocess.run([*ASPRILO, "solve", str(instance), "--domain", "a", "--method", "anytime", "--json",
                           "--time-limit", str(limit), "-o", str(folder / f"p{seed}.lp")],
                          capture_output=True, text=True, timeout=limit + 120)
    report = json.loads(done.stdout) if done.stdout.strip() else {}
    bound = report.get("lower_bound")
    best = bound
    if conflicts > 0 and bound is not None and report.get("horizon", 0) > bound:
        sought = subprocess.run([sys.executable, __file__, "--bound-of", str(instance), "--from", str(int(bound)),
                                 "--bound-conflicts", str(conflicts)], capture_output=True, text=True)
        best = max(bound, float(sought.stdout)) if sought.returncode == 0 else bound
    return {"seed": seed, "makespan": report.get("horizon"), "bound": bound, "best": best,
            "first": report.get("stats", {}).get("first_plan_seconds")}


def best_bound(path: Path, start: int, conflicts: int) -> float:
    """The trip relaxation's bound of domain A from ``start`` up, ``conflicts`` per horizon."""
    from asprilo.bounds import Floor
    from asprilo.bounds.delivery import Deliveries
    from asprilo.bounds.trip import trip_bound
    from asprilo.domain import Domain
    from asprilo.reader import read_instance

    instance = read_instance(path)
    return trip_bound(Deliveries(instance, Domain.parse("a"), Floor(instance.cells)), start, conflicts)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", default="4501-4520")
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--bound-conflicts", type=int, default=200_000,
                        help="conflicts per horizon for the best bound (0: the planner's bound only)")
    parser.add_argument("--keep", type=Path, help="keep the instances and plans in this folder")
    parser.add_argument("--bound-of", type=Path, help=argparse.SUPPRESS)  # the best bound's own process
    parser.add_argument("--from", dest="start", type=int, default=0, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.bound_of is not None:
        print(best_bound(args.bound_of, args.start, args.bound_conflicts))
        return 0
    print(f"load average {os.getloadavg()[0]:.1f}; {CALL}; anytime, --time-limit {args.time_limit:g}", flush=True)
    with tempfile.TemporaryDirectory() as scratch:
        folder = args.keep or Path(scratch)
        folder.mkdir(parents=True, exist_ok=True)
        with ThreadPoolExecutor(args.jobs) as pool:
            rows = list(pool.map(lambda seed: run_seed(seed, args.time_limit, folder, args.bound_conflicts),
                                 seed_list(args.seeds)))
    ratios, proven = [], 0
    print(f"{'seed':>6} {'first s':>8} {'makespan':>8} {'bound':>6} {'best':>5} {'ratio':>6}  proven")
    for row in rows:
        if row.get("makespan") is None:
            print(f"{row['seed']:>6}  no plan {row.get('error', '')}")
            ratios.append(float("inf"))
            continue
        ratio = row["makespan"] / row["best"]
        ratios.append(ratio)
        proven += row["makespan"] <= row["best"]
        print(f"{row['seed']:>6} {row['first']:>8.2f} {row['makespan']:>8} {row['bound']:>6.0f} {row['best']:>5.0f}"
              f" {ratio:>6.2f}  {'yes' if row['makespan'] <= row['best'] else ''}")
    within = sum(ratio <= 1.3 for ratio in ratios)
    print(f"makespan / best bound: median {statistics.median(ratios):.2f}, worst {max(ratios):.2f}; "
          f"{within} of {len(rows)} within 1.3x; {proven} of {len(rows)} proven minimal")
    return 0


if __name__ == "__main__":
    sys.exit(main())
