"""The A/B/C anytime planner on big generated floors over several seeds (issue 45): the
first plan's time and makespan, the makespan at the time limit, and the lower bound, per
seed, with the median and the worst of each.

The floors are the issue's calls (``--floor 100``: ``gen -x 100 -y 100 -X 5 -Y 2 -H -p 20
-s 1000 -r 200 -P 1000 -u 3000 -o 100 --seed S -C``; ``--floor 200``: the 200x200 call with
600 robots), each solved as a user would, ``asprilo solve --domain a --method anytime
--time-limit L --json``, in a process of its own under an address-space cap (4 GB), one
after the other (``--jobs``: more at a time, and noisier times).  The ratio is the makespan
over the lower bound the solve reports (the strong one when its process finished in time,
else the cheap one).  Times are wall-clock on whatever machine runs it; its load average is
printed first.

    python benchmarks/abc_seeds.py                                  # 100x100, seeds 9201-9205, 60 s
    python benchmarks/abc_seeds.py --floor 200 --seeds 9204 --limit 180
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from statistics import median

#: the generator's calls of the issue, per floor size (the seed comes last)
FLOORS = {100: "-x 100 -y 100 -X 5 -Y 2 -H -p 20 -s 1000 -r 200 -P 1000 -u 3000 -o 100 -C",
          200: "-x 200 -y 200 -X 5 -Y 2 -H -p 40 -s 5000 -r 600 -P 5000 -u 15000 -o 500 -C"}
#: the address-space cap of every solve (MB)
CAP_MB = 4000


def generate(folder: Path, floor: int, seed: int) -> Path:
    """The issue's instance for ``floor`` and ``seed``."""
    path = folder / f"x{floor}_s{seed}.lp"
    call = ["asprilo", "gen", *FLOORS[floor].split(), "--seed", str(seed)]
    path.write_text(subprocess.run(call, check=True, capture_output=True, text=True).stdout)
    return path


def _capped() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (CAP_MB * 2**20, CAP_MB * 2**20))


def solved(instance: Path, limit: float) -> dict:
    """One solve's figures: wall time, first plan (seconds, makespan), last makespan, bound."""
    call = ["asprilo", "solve", str(instance), "--domain", "a", "--method", "anytime",
            "--time-limit", f"{limit:g}", "--json"]
    began = time.perf_counter()
    done = subprocess.run(call, capture_output=True, text=True, preexec_fn=_capped, timeout=3 * limit + 120)
    wall = time.perf_counter() - began
    try:
        report = json.loads(done.stdout)
    except json.JSONDecodeError:
        return {"wall": wall, "status": f"exit {done.returncode}: {done.stderr.strip()[-200:]}", "history": []}
    return {"wall": wall, "status": report["status"], "history": report.get("history") or [],
            "bound": report.get("lower_bound")}


def row(seed: int, run: dict) -> str:
    history, bound = run["history"], run.get("bound")
    if not history:
        return f"{seed:>6} {run['wall']:7.1f} {'-':>8} {'-':>9} {'-':>9} {bound or '-':>6} {'-':>7}  {run['status']}"
    first, last = history[0], history[-1]
    return (f"{seed:>6} {run['wall']:7.1f} {first['seconds']:8.1f} {first['makespan']:>9} {last['makespan']:>9} "
            f"{bound:>6g} {last['makespan'] / bound:7.3f}  {run['status']}")


def summary(runs: dict[int, dict]) -> list[str]:
    """Median and worst of the first plan's time, and of the ratios at the first plan and at the end."""
    found = [run for run in runs.values() if run["history"]]
    lines = [f"plans: {len(found)} of {len(runs)}"]
    if not found:
        return lines
    figures = {"first plan (s)": [run["history"][0]["seconds"] for run in found],
               "first makespan / bound": [run["history"][0]["makespan"] / run["bound"] for run in found],
               "makespan / bound at the limit": [run["history"][-1]["makespan"] / run["bound"] for run in found]}
    for name, values in figures.items():
        lines.append(f"{name:<30} median {median(values):7.3f}   worst {max(values):7.3f}")
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--floor", type=int, choices=sorted(FLOORS), default=100)
    parser.add_argument("--seeds", type=int, nargs="+", default=[9201, 9202, 9203, 9204, 9205])
    parser.add_argument("--limit", type=float, default=60.0, help="the solve's --time-limit (default 60)")
    parser.add_argument("--jobs", type=int, default=1, help="solves at a time (default 1)")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}; {args.floor}x{args.floor}, limit {args.limit:g} s", flush=True)
    print(f"{'seed':>6} {'wall':>7} {'first s':>8} {'first ms':>9} {'last ms':>9} {'bound':>6} {'ratio':>7}  status",
          flush=True)
    with tempfile.TemporaryDirectory() as folder:
        instances = {seed: generate(Path(folder), args.floor, seed) for seed in args.seeds}
        with ThreadPoolExecutor(args.jobs) as pool:
            results = dict(zip(args.seeds, pool.map(lambda seed: solved(instances[seed], args.limit), args.seeds),
                               strict=True))
    for seed, run in results.items():
        print(row(seed, run), flush=True)
    print("\n".join(summary(results)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
