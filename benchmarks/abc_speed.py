"""The A/B/C targets of issue 13, measured as a user meets them: whole `asprilo solve` runs.

1. The small A example (examples/asprilo/dom-a/small): minimal makespan found and proven as
   A (target 30 s), B and C (5 s each).
2. The 8x8 instance of examples/encodings-repo in C and B, and the small A example in C and
   B, at their minimal makespans (the original encodings took 0.51 s / 0.96 s in C there,
   measured in issue 13 as whole processes on a quiet machine).
3. Grounding a 40x40 domain-A instance with 60 robots and 200 shelves at its lower bound
   (target 30 s and 2 GB): made by the generator with a fixed seed, grounded in a child
   process that reports its own time and peak memory.
4. `--time-limit 5` on that instance ends within 7 s (the limit holds while clingo grounds).

    python benchmarks/abc_speed.py [--skip-big]

Every figure is wall-clock time on whatever machine runs it; the load average is printed
first (the development machine has 2 cores, often shared).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SMALL_A = ROOT / "examples/asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
EIGHT = ROOT / "examples/encodings-repo/x8_y8_n64_r4_s10_ps2_pr3_u16_o4_N1.lp"
ASPRILO = [sys.executable, "-m", "asprilo.cli"]
BIG = ["-x", "40", "-y", "40", "-X", "5", "-Y", "2", "-H", "-p", "8", "-s", "200", "-r", "60",
       "-P", "200", "-u", "600", "-o", "40", "-N", "1", "--seed", "1"]

GROUND = r"""
import json, resource, sys, time
from asprilo.bounds import makespan_bound
from asprilo.domain import Domain
from asprilo.encodings.solving import ground
from asprilo.reader import read_instance
instance = read_instance(sys.argv[1])
horizon = int(makespan_bound(instance, Domain.parse("a")))
started = time.perf_counter()
solver = ground(instance, "a", horizon)
print(json.dumps({"horizon": horizon, "seconds": time.perf_counter() - started,
                  "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "atoms": len(solver.control.symbolic_atoms)}))
"""


def solve(instance: Path, domain: str, *options: str, limit: float = 300) -> dict:
    """One whole `asprilo solve ... --json` run: its report and wall time."""
    started = time.perf_counter()
    done = subprocess.run([*ASPRILO, "solve", str(instance), "--domain", domain, "--json",
                           "--time-limit", str(limit), *options], capture_output=True, text=True)
    seconds = time.perf_counter() - started
    report = json.loads(done.stdout) if done.stdout.strip() else {"status": "error", "message": done.stderr}
    return {**report, "wall": seconds}


def row(name: str, report: dict, target: float | None = None) -> None:
    proven = "proven" if report.get("minimal") else "not proven"
    found = f"horizon {report['horizon']} ({proven})" if report.get("horizon") else \
        f"{report['status']}: refuted {report.get('refuted')}, no plan below {report.get('proven_bound')}"
    verdict = "" if target is None else ("  ok" if report.get("minimal") and report["wall"] <= target else "  MISSED")
    shown = f"{target:>6.0f}" if target is not None else "      "
    print(f"{name:40s} {report['wall']:7.2f} s {shown}   {found}{verdict}", flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--skip-big", action="store_true", help="skip the 40x40 instance (3 and 4)")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}; {'case':32s} {'wall':>9s} {'target':>6s}   result")
    print("1. the small A example, minimal makespan found and proven")
    for domain, target, limit in (("c", 5, 60), ("b", 5, 60), ("a", 30, 120)):
        row(f"   read as {domain.upper()}", solve(SMALL_A, domain, limit=limit), target)
    print("2. at the minimal makespan (whole process; the originals in C: 0.51 s, 0.96 s)")
    for instance, horizons in ((SMALL_A, {"c": 15, "b": 16}), (EIGHT, {"c": 15, "b": 16})):
        for domain, horizon in horizons.items():
            report = solve(instance, domain, "--horizon", str(horizon))
            row(f"   {instance.name[:16]} {domain.upper()} at {horizon}", report)
    if args.skip_big:
        return 0
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([*ASPRILO, "gen", *BIG, "-d", folder, "-q"], check=True)
        big = next(Path(folder).glob("*.lp"))
        print(f"3. grounding {big.name} (domain A) at its lower bound")
        done = subprocess.run([sys.executable, "-c", GROUND, str(big)], capture_output=True, text=True)
        figures = json.loads(done.stdout)
        print(f"   horizon {figures['horizon']}: {figures['seconds']:.1f} s (target 30), "
              f"peak {figures['peak_mb']:.0f} MB (target 2048), {figures['atoms']:,} atoms")
        print("4. the time limit while grounding")
        report = solve(big, "a", limit=5)
        print(f"   --time-limit 5: {report['wall']:.1f} s wall (target 7), status {report['status']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
