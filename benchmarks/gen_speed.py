"""How fast the generator makes the paper's instances and a large warehouse, and its peak memory.

Every case runs as a whole ``gen`` command in a fresh process (interpreter start, imports,
generation and writing the files), REPEAT times; the table shows the median wall time and
the largest peak memory (ru_maxrss of the process).  Targets from the generator's issue.

Run: python benchmarks/gen_speed.py [--repeat N] [--one-shot] [--only NAME]
  --one-shot  also time the one-shot mode (all parts grounded together, one solve) of the
              small, medium and Figure-1 calls, for comparison
"""

from __future__ import annotations

import argparse
import json
import shlex
import statistics
import subprocess
import sys
import tempfile

PAPER = {
    "small": ("-x 11 -y 6 -X 4 -Y 2 -p 1 -s 16 -P 16 -u 16 -H --prs 1", (2, 5, 8, 11)),
    "medium": ("-x 19 -y 9 -X 5 -Y 2 -p 3 -s 60 -P 60 -u 60 -H --prs 1", (5, 10, 15, 19)),
    "large": ("-x 46 -y 15 -X 8 -Y 2 -p 10 -s 320 -P 320 -u 320 -H --prs 1", (12, 23, 35, 46)),
}
FIGURE_1 = "-x 19 -y 9 -X 5 -Y 2 -p 3 -s 45 -r 6 -P 180 -u 540 -o 12 -H"
BIG = "-x 200 -y 200 -X 8 -Y 2 -H -p 20 -s 5000 -r 500 -P 1000 -u 5000 -o 500"

#: name -> (gen arguments, target seconds)
CASES: dict[str, tuple[str, float]] = {
    **{f"{size} r{r}": (f"{call} -r {r} -o {r}", 1.0) for size, (call, rs) in PAPER.items() for r in rs},
    "figure-1": (FIGURE_1, 2.0),
    "large r46 -N 30": (f"{PAPER['large'][0]} -r 46 -o 46 -N 30", 20.0),
    "200x200": (BIG, 10.0),
}
ONE_SHOT = {f"{name} --one-shot": (f"{CASES[name][0]} --one-shot", None)
            for name in ("small r11", "medium r19", "figure-1")}
MEMORY_TARGET_MB = 1024

# Runs one gen command and reports its wall time and peak memory (kilobytes on Linux).
CHILD = """
import json, resource, sys, time
started = time.perf_counter()
from asprilo.cli import main
status = main(["gen", *sys.argv[1:]])
print(json.dumps({"status": status, "seconds": time.perf_counter() - started,
                  "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def run_case(arguments: str) -> dict:
    with tempfile.TemporaryDirectory() as directory:
        started = __import__("time").perf_counter()
        done = subprocess.run([sys.executable, "-c", CHILD, *shlex.split(arguments), "-d", directory],
                              capture_output=True, text=True)
        wall = __import__("time").perf_counter() - started
    if done.returncode != 0:
        raise SystemExit(f"gen {arguments} failed:\n{done.stderr}")
    report = json.loads(done.stdout.splitlines()[-1])
    report["wall"] = wall  # including the interpreter's start
    return report


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--one-shot", action="store_true")
    parser.add_argument("--only", help="run only the cases whose name contains this")
    args = parser.parse_args()
    cases = {**CASES, **(ONE_SHOT if args.one_shot else {})}
    if args.only:
        cases = {name: case for name, case in cases.items() if args.only in name}
    print(f"{'case':<22} {'median s':>9} {'in gen s':>9} {'peak MB':>8} {'target':>8}  ok")
    failed = False
    for name, (arguments, target) in cases.items():
        reports = [run_case(arguments) for _ in range(args.repeat)]
        wall = statistics.median(r["wall"] for r in reports)
        inside = statistics.median(r["seconds"] for r in reports)
        peak = max(r["peak_mb"] for r in reports)
        ok = (target is None or wall <= target) and peak < MEMORY_TARGET_MB
        failed |= not ok
        shown = "-" if target is None else f"<= {target:g}"
        print(f"{name:<22} {wall:>9.2f} {inside:>9.2f} {peak:>8.0f} {shown:>8}  {'yes' if ok else 'NO'}",
              flush=True)
    print(f"\nmedian of {args.repeat} runs; 'median s' is the whole command (interpreter start "
          f"included), 'in gen s' the command without the start; memory target < {MEMORY_TARGET_MB} MB")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
