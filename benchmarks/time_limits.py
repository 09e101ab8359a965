"""Whether ``asprilo solve --method anytime --time-limit S`` ends at S on a big floor (issue 45).

The issue's floor: ``gen -x 200 -y 200 -X 5 -Y 2 -H -p 40 -s 5000 -r 600 -P 5000 -u 15000
-o 500 --seed 9204 -C`` (domain A, 600 robots).  Each limit is run as a user would, in a
process of its own under an address-space cap (``ulimit -v``, as in the issue: 3 GB), one
after the other; each row gives the wall time from start to exit against the limit, the
exit status, whether the plan file was written, the peak memory of the solve and of the
children it waited for (a child killed at the limit leaves its own children to the system:
their peak is not counted), and the last lines the command said.

    python benchmarks/time_limits.py                      # limits 10, 30 and 180 s
    python benchmarks/time_limits.py --limits 10 --robots 200 --size 100
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: the issue's call, but for the floor's size, the robots and the seed
GEN = "-X 5 -Y 2 -H -p 40 -s 5000 -P 5000 -u 15000 -o 500 -C"


def generate(folder: Path, size: int, robots: int, seed: int) -> Path:
    """The instance of the issue's call."""
    path = folder / f"x{size}_r{robots}_s{seed}.lp"
    call = ["asprilo", "gen", "-x", str(size), "-y", str(size), "-r", str(robots), "--seed", str(seed), *GEN.split()]
    path.write_text(subprocess.run(call, check=True, capture_output=True, text=True).stdout)
    return path


def measured(instance: Path, limit: float, cap_mb: int, folder: Path) -> dict:
    """One solve under ``limit`` and the cap, measured by a fresh process of its own (so that
    the peak memory of its children is this solve's alone)."""
    plan = folder / f"plan-{limit:g}.lp"
    call = ["asprilo", "solve", str(instance), "--method", "anytime", "--time-limit", f"{limit:g}", "-o", str(plan)]
    script = (f"import json, resource, subprocess, time\n"
              f"resource.setrlimit(resource.RLIMIT_AS, ({cap_mb * 2**20}, {cap_mb * 2**20}))\n"
              f"began = time.perf_counter()\n"
              f"done = subprocess.run({call!r}, capture_output=True, text=True, timeout={3 * limit + 120})\n"
              f"seconds = time.perf_counter() - began\n"
              f"peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024\n"
              f"print(json.dumps(dict(seconds=seconds, status=done.returncode, peak_mb=peak, said=done.stderr)))\n")
    answer = json.loads(subprocess.run([sys.executable, "-c", script], check=True, capture_output=True,
                                       text=True).stdout)
    lines = [line for line in answer.pop("said").splitlines() if line and not line.startswith("plan: makespan")]
    return {"limit": limit, **answer, "plan_written": plan.exists(), "said": lines[-3:]}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limits", type=float, nargs="+", default=[10.0, 30.0, 180.0])
    parser.add_argument("--size", type=int, default=200, help="the floor's width and height (default 200)")
    parser.add_argument("--robots", type=int, default=600)
    parser.add_argument("--seed", type=int, default=9204)
    parser.add_argument("--cap", type=int, default=2930, help="the address-space cap in MB (default: 3,000,000 kB)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        instance = generate(folder, args.size, args.robots, args.seed)
        print(f"{instance.name}, cap {args.cap} MB")
        print("| limit | wall | over | exit | plan file | peak MB | said |\n|---|---|---|---|---|---|---|")
        for limit in args.limits:
            row = measured(instance, limit, args.cap, folder)
            print(f"| {limit:g} s | {row['seconds']:.1f} s | {row['seconds'] - limit:+.1f} s | {row['status']} | "
                  f"{'yes' if row['plan_written'] else 'no'} | {row['peak_mb']:.0f} | {' / '.join(row['said'])} |",
                  flush=True)


if __name__ == "__main__":
    started = time.perf_counter()
    main()
    print(f"({time.perf_counter() - started:.0f} s in all)", file=sys.stderr)
