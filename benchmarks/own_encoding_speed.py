"""What going through `asprilo solve` costs a user's own encoding, against plain clingo.

For each instance, `asprilo solve INSTANCE --encoding FILE` (the whole command, a process of
its own) is compared with what plain clingo needs for the same search: one
`python -m clingo INSTANCE FILE -c horizon=H` process per horizon that solve tried (the
lower bound up to the minimal makespan).  The overhead is

    solve's wall time - the clingo runs' wall times (their sum) - the lower-bound search

where the lower-bound search is timed in a process of its own.  What remains is reading,
style detection, the child process, the plan's check and the summary; the target is at most
0.2 s.  Each figure is the median of --repeat runs.

Run: python benchmarks/own_encoding_speed.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ENCODING = ROOT / "tests/encodings/m-single.lp"
INSTANCES = [
    ROOT / "tests/encodings/m-tiny.lp",
    ROOT / "examples/paper-m/1x2x4/x11_y6_n66_r2_s16_ps1_pr16_u16_o2_N001.lp",
    ROOT / "examples/paper-m/1x2x4/x11_y6_n66_r5_s16_ps1_pr16_u16_o5_N001.lp",
    ROOT / "examples/paper-m/1x2x4/x11_y6_n66_r8_s16_ps1_pr16_u16_o8_N001.lp",
    ROOT / "examples/paper-m/2x3x5/x19_y9_n171_r10_s60_ps3_pr60_u60_o10_N001.lp",
]
BOUND = ("import sys, time; from asprilo.reader import read_instance; from asprilo.domain import detect_domain; "
         "from asprilo.bounds import makespan_bound; i = read_instance(sys.argv[1]); t = time.perf_counter(); "
         "makespan_bound(i, detect_domain(i)); print(time.perf_counter() - t)")


def _wall(command: list[str]) -> tuple[float, subprocess.CompletedProcess]:
    started = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    return time.perf_counter() - started, done


def measure(instance: Path, repeat: int) -> dict:
    """Median wall times of solve, of the clingo runs of the same horizons, and of the bound."""
    solves, clingos, bounds, horizons = [], [], [], []
    for _ in range(repeat):
        seconds, done = _wall([sys.executable, "-m", "asprilo.cli", "solve", str(instance), "--encoding",
                               str(ENCODING), "--json"])
        report = json.loads(done.stdout)
        horizons = [attempt["horizon"] for attempt in report["horizons_tried"]]
        solves.append(seconds)
        clingos.append(sum(_wall([sys.executable, "-m", "clingo", str(instance), str(ENCODING), "-c",
                                  f"horizon={horizon}", "-q"])[0] for horizon in horizons))
        bounds.append(float(subprocess.run([sys.executable, "-c", BOUND, str(instance)], capture_output=True,
                                           text=True, check=True).stdout))
    solve, clingo, bound = (statistics.median(values) for values in (solves, clingos, bounds))
    return {"instance": instance.name, "horizons": horizons, "solve": solve, "clingo": clingo, "bound": bound,
            "overhead": solve - clingo - bound}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"{'instance':58s} {'horizons':>9s} {'solve':>7s} {'clingo':>7s} {'bound':>7s} {'overhead':>9s}")
    for instance in INSTANCES:
        row = measure(instance, args.repeat)
        spans = f"{row['horizons'][0]}-{row['horizons'][-1]}"
        print(f"{row['instance']:58s} {spans:>9s} {row['solve']:7.2f} {row['clingo']:7.2f} {row['bound']:7.3f} "
              f"{row['overhead']:9.2f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
