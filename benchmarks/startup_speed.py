"""Start-up time of the commands a user types most: whole processes, best of N runs.

Targets (issue 16): `check`, `info`, `asprilo --help` and `gen --help` on a small input at most
0.3 s each; `asprilo solve` of a small paper M instance (11x6, 11 robots) at most 0.4 s.
The best of several runs is the figure least disturbed by other work on the machine.

    python benchmarks/startup_speed.py [--runs 7]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SMALL_A = ROOT / "examples/asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
OUTCOME = ROOT / "examples/asprilo/dom-a/small/outcome.txt"
SMALL_M = ROOT / "examples/paper-m/1x2x4/x11_y6_n66_r11_s16_ps1_pr16_u16_o11_N001.lp"
ASPRILO = [sys.executable, "-m", "asprilo.cli"]

CASES = [
    ("asprilo --help", [*ASPRILO, "--help"], 0.3),
    ("gen --help", [*ASPRILO, "gen", "--help"], 0.3),
    ("info (small A)", [*ASPRILO, "info", str(SMALL_A)], 0.3),
    ("check (outcome.txt)", [*ASPRILO, "check", str(SMALL_A), str(OUTCOME)], 0.3),
    ("solve (small M, 11 robots)", [*ASPRILO, "solve", str(SMALL_M)], 0.4),
]


def best_of(command: list[str], runs: int) -> float:
    best = float("inf")
    for _ in range(runs):
        started = time.perf_counter()
        subprocess.run(command, capture_output=True, check=False)
        best = min(best, time.perf_counter() - started)
    return best


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    load = os.getloadavg()[0]
    print(f"{'command':28s} {'best s':>7s} {'target':>7s}   (load average {load:.1f}, {args.runs} runs each)")
    for name, command, target in CASES:
        seconds = best_of(command, args.runs)
        print(f"{name:28s} {seconds:7.3f} {target:7.1f}   {'ok' if seconds <= target else 'OVER'}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
