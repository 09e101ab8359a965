"""Domain A with several products per shelf and several lines per order (issue 45): the
anytime planner's makespan against the lower bound on the exercise-size call, many seeds.

Every seed runs as whole commands: ``asprilo gen CALL --seed S -C`` writes the instance,
then ``asprilo solve --domain a --method anytime --time-limit T --json`` plans it.  Prints
per seed the first plan's time, the makespan, the bound, their ratio and whether the plan is
proven minimal (it meets the bound), then the median and the worst ratio and how many are
proven.  ``--jobs`` runs that many seeds side by side (the load average is printed first:
timings on a shared machine are noisy).

Run: python benchmarks/a_multiline.py [--seeds 4501-4520] [--time-limit 60] [--jobs 2] [--keep DIR]
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

#: the exercise-size call of issue 45 (multi-line orders, up to 3 products per shelf)
CALL = "-x 11 -y 6 -X 4 -Y 2 -p 2 -s 16 -P 8 -u 40 -r 4 -H --prsmin 1 --prsmax 3 --olmin 1 --olmax 3 -o 4"
ASPRILO = [sys.executable, "-m", "asprilo.cli"]


def seed_list(text: str) -> list[int]:
    """``4501-4520``, ``3,9301-9310`` and the like."""
    seeds: list[int] = []
    for part in text.split(","):
        low, _, high = part.partition("-")
        seeds += range(int(low), int(high or low) + 1)
    return seeds


def run_seed(seed: int, limit: float, folder: Path) -> dict:
    """Generate the instance of ``seed`` and plan it; the solve report's figures."""
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
    return {"seed": seed, "makespan": report.get("horizon"), "bound": report.get("lower_bound"),
            "minimal": bool(report.get("minimal")), "first": report.get("stats", {}).get("first_plan_seconds")}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", default="4501-4520")
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--keep", type=Path, help="keep the instances and plans in this folder")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}; {CALL}; anytime, --time-limit {args.time_limit:g}", flush=True)
    with tempfile.TemporaryDirectory() as scratch:
        folder = args.keep or Path(scratch)
        folder.mkdir(parents=True, exist_ok=True)
        with ThreadPoolExecutor(args.jobs) as pool:
            rows = list(pool.map(lambda seed: run_seed(seed, args.time_limit, folder), seed_list(args.seeds)))
    ratios = []
    print(f"{'seed':>6} {'first s':>8} {'makespan':>8} {'bound':>6} {'ratio':>6}  proven")
    for row in rows:
        if row.get("makespan") is None:
            print(f"{row['seed']:>6}  no plan {row.get('error', '')}")
            ratios.append(float("inf"))
            continue
        ratio = row["makespan"] / row["bound"]
        ratios.append(ratio)
        print(f"{row['seed']:>6} {row['first']:>8.2f} {row['makespan']:>8} {row['bound']:>6.0f} {ratio:>6.2f}"
              f"  {'yes' if row['minimal'] else ''}")
    proven = sum(row.get("minimal", False) for row in rows)
    print(f"makespan / bound: median {statistics.median(ratios):.2f}, worst {max(ratios):.2f}; "
          f"{proven} of {len(rows)} proven minimal")
    return 0


if __name__ == "__main__":
    sys.exit(main())
