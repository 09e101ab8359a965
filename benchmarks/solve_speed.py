"""How fast `asprilo solve` is: the paper's domain-M instances, every M style, the small A example.

Prints three tables:
1. every examples/paper-m instance solved at proven minimal makespan: the default encoding
   (plain, search from the bottleneck bound) and the max-flow solver (median of 3);
2. every M style at the minimal horizon (known from max-flow) on the paper-m instances,
   with its time relative to the plain style;
3. the small A example (and the same instance read as B and C): exact search, and with a
   task assignment (--assign), each under a time limit.

Each run is a separate process (a hard kill backs up the solver's own time limit, since
grounding cannot be interrupted).  Times are wall-clock seconds of the whole call
(reading, bounds, grounding, solving, checking the plan), except in table 2, which compares
the encodings by their ground + solve time.

Run: python benchmarks/solve_speed.py [--limit 120] [--sizes 1x2x4,2x3x5,4x5x8] [--skip-a]
"""

from __future__ import annotations

import argparse
import multiprocessing
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PAPER_M = ROOT / "examples/paper-m"
SMALL_A = ROOT / "examples/asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
STYLES = ("plain", "split", "clingcon", "dl")
SHORT = {"sat": "s", "unsat": "u", "unknown": "?"}  # how table 3 writes a horizon's result


def _run(queue, path, options):
    from asprilo.encodings import solve
    started = time.perf_counter()
    outcome = solve(path, **options)
    queue.put({"seconds": time.perf_counter() - started, "status": outcome.status.value,
               "horizon": outcome.horizon, "minimal": outcome.minimal,
               "tried": [(a.horizon, a.result) for a in outcome.horizons_tried],
               "stats": outcome.stats})


def measure(path: Path, limit: float, **options) -> dict:
    """One solve call in a child process; killed ``limit`` + 60 s after it started."""
    queue = multiprocessing.get_context("spawn").Queue()
    process = multiprocessing.get_context("spawn").Process(
        target=_run, args=(queue, str(path), dict(options, time_limit=limit)))
    started = time.perf_counter()
    process.start()
    process.join(limit + 60)
    if process.is_alive():
        process.kill()
        process.join()
        return {"seconds": time.perf_counter() - started, "status": "killed", "horizon": None,
                "minimal": False, "tried": [], "stats": {}}
    return queue.get()


def progress(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


def instances(sizes: list[str]) -> list[Path]:
    def robots(path: Path) -> int:
        return int(path.name.split("_r")[1].split("_")[0])
    return [p for size in sizes for p in sorted((PAPER_M / size).glob("*.lp"), key=robots)]


def short(path: Path) -> str:
    return f"{path.parent.name} r{path.name.split('_r')[1].split('_')[0]}"


def cell(result: dict) -> str:
    if result["status"] == "found":
        return f"{result['seconds']:.1f}"
    return f">{result['seconds']:.0f} ({result['status']})"


def paper_m(paths: list[Path], limit: float) -> dict[Path, int]:
    print("\n1. paper-m instances at proven minimal makespan (default encoding vs max-flow)\n")
    print(f"{'instance':<12} {'makespan':>8} {'plain search s':>15} {'proven':>7} {'flow s':>7} "
          f"{'ground s':>9} {'solve s':>8} {'rules':>9}")
    optimum = {}
    for path in paths:
        progress(f"paper-m {short(path)}")
        flows = [measure(path, limit, method="flow") for _ in range(3)]
        flow = statistics.median(r["seconds"] for r in flows)
        optimum[path] = flows[0]["horizon"]
        asp = measure(path, limit)
        stats = asp["stats"]
        print(f"{short(path):<12} {optimum[path]:>8} {cell(asp):>15} {str(asp['minimal']):>7} {flow:>7.2f} "
              f"{stats.get('ground_time', 0):>9.1f} {stats.get('solve_time', 0):>8.1f} {stats.get('rules', 0):>9}",
              flush=True)
    return optimum


def styles(optimum: dict[Path, int], limit: float) -> None:
    print(f"\n2. M styles at the minimal horizon: ground + solve seconds (x plain; limit {limit:g} s)\n")
    print(f"{'instance':<12} {'H':>3} " + " ".join(f"{s:>16}" for s in STYLES))
    for path, horizon in optimum.items():
        times = {}
        for style in STYLES:
            progress(f"styles {short(path)} {style}")
            times[style] = measure(path, limit, encoding=style, horizon=horizon)
        work = {style: r["stats"].get("ground_time", 0) + r["stats"].get("solve_time", 0)
                for style, r in times.items()}
        row = []
        for style in STYLES:
            if times[style]["status"] == "found":
                text = f"{work[style]:.2f} ({work[style] / max(work['plain'], 1e-3):.1f}x)"
            else:
                text = cell(times[style])
            row.append(f"{text:>16}")
        print(f"{short(path):<12} {horizon:>3} " + " ".join(row), flush=True)


def small_a(limit: float) -> None:
    print(f"\n3. the small A example (11x6, 3 robots, 3 orders; limit {limit:g} s; "
          "horizons tried: s = plan, u = no plan, ? = stopped)\n")
    print(f"{'domain':<7} {'mode':<8} {'result':>16} {'horizon':>8} {'proven':>7}  horizons tried")
    for domain in ("c", "b", "a"):
        for assign in (False, True):
            progress(f"small A as {domain}, assign={assign}")
            result = measure(SMALL_A, limit, domain=domain, assign=assign)
            tried = " ".join(f"{h}:{SHORT[r]}" for h, r in result["tried"])
            print(f"{domain.upper():<7} {'assign' if assign else 'exact':<8} {cell(result):>16} "
                  f"{str(result['horizon']):>8} {str(result['minimal']):>7}  {tried}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=float, default=120, help="seconds per run (default 120)")
    parser.add_argument("--a-limit", type=float, default=60, help="seconds per small-A run (default 60)")
    parser.add_argument("--sizes", default="1x2x4,2x3x5,4x5x8", help="paper-m folders to run")
    parser.add_argument("--skip-styles", action="store_true", help="leave out table 2")
    parser.add_argument("--skip-a", action="store_true", help="leave out table 3")
    args = parser.parse_args()
    optimum = paper_m(instances(args.sizes.split(",")), args.limit)
    if not args.skip_styles:
        styles(optimum, args.limit)
    if not args.skip_a:
        small_a(args.a_limit)


if __name__ == "__main__":
    main()
