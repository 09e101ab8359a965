"""How the anytime planner (`asprilo solve --method anytime`) meets its targets (issue 14):
time to the first checked plan, and makespan over the lower bound as time goes on.

Targets:
  paper     every instance of paper-sample.yml (paper-m.yml, first 5 per robot count) read as
            A, B and C: a checked plan within 30 s; after 60 s the large ones' makespan is on
            average at most 1.3 x the lower bound (small and medium run 10 s, large 60 s)
  m         the same instances as M and Md: after 10 s within 1.1 x the flow optimum
  movingai  random-32-32-20 with 200 labelled agents (Md): a plan within 60 s
  g40       40x40, 60 robots, 200 shelves (A; the generator call below): a plan within 60 s
  g100      100x100, 200 robots, 1000 shelves (A): a plan within 5 minutes
  and in every run a peak memory of at most 4 GB.

Every run is a process of its own (its peak memory is its own); runs go --jobs at a time,
so on a small machine the times include the other job's load.  Prints one table per target
and writes the runs (with their histories) to OUT/anytime-runs.jsonl and a plot of
makespan / lower bound against time to --plot.

Run: python benchmarks/anytime_speed.py [--targets paper,m,movingai,g40,g100] [--jobs 2]
                                        [--out /tmp/anytime-speed] [--plot FILE.png]
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import resource
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from statistics import mean

ROOT = Path(__file__).resolve().parent.parent
MOVINGAI = ROOT / "examples/movingai"
G40 = {"-x": 40, "-y": 40, "-X": 5, "-Y": 2, "-H": True, "-p": 8, "-s": 200, "-r": 60, "-P": 200, "-u": 600, "-o": 40}
G100 = {"-x": 100, "-y": 100, "-X": 5, "-Y": 2, "-H": True, "-p": 20, "-s": 1000, "-r": 200, "-P": 1000, "-u": 3000,
        "-o": 100}
SIZES = {"1x2x4": "small", "2x3x5": "medium", "4x5x8": "large"}
SAMPLES = (1, 2, 5, 10, 20, 30, 60, 120, 300)  # seconds at which the plot and tables sample the makespan


def run_one(job: dict) -> dict:
    """One anytime run (in its own process): the history and the process's peak memory."""
    from asprilo.domain import Domain, Goal
    from asprilo.encodings import solve
    from asprilo.encodings.anytime import plan_anytime
    from asprilo.interop.convert import m_to_md
    from asprilo.reader import read_instance

    instance = read_instance(job["path"])
    domain = Domain.parse(job["domain"])
    if domain.goal is Goal.DESTINATIONS and not instance.destinations:
        instance = m_to_md(instance)
    optimum = None
    if job.get("flow"):
        optimum = solve(instance, domain, method="flow", time_limit=600).horizon
    started = time.perf_counter()
    result = plan_anytime(instance, domain, time_limit=job["limit"])
    return {**job, "seconds": time.perf_counter() - started, "status": result.status, "bound": result.bound,
            "minimal": result.minimal, "optimum": optimum, "valid": result.check.valid if result.check else None,
            "history": [better.figures() for better in result.history],
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def makespan_at(run: dict, seconds: float) -> int | None:
    """The makespan of the best plan reported by ``seconds`` (None: none yet)."""
    spans = [h["makespan"] for h in run["history"] if h["seconds"] <= seconds]
    return spans[-1] if spans else None


# --- instances -------------------------------------------------------------------------------

def paper_instances(out: Path) -> list[tuple[str, Path]]:
    from asprilo.generator import generate_batch
    folder = out / "paper-m"
    generate_batch(ROOT / "benchmarks/paper-m.yml", folder, count=5)
    return [(SIZES[path.parent.parent.name], path) for path in sorted(folder.glob("*/*/*.lp"))]


def generated(out: Path, name: str, options: dict) -> Path:
    from asprilo.generator import GeneratorConfig, generate
    from asprilo.writer import format_instance, write_text
    path = out / f"{name}.lp"
    if not path.exists():
        item = generate(GeneratorConfig.from_options(options), count=1, seed=1)[0]
        write_text(path, format_instance(item.instance))
    return path


def movingai(out: Path) -> Path:
    from asprilo.interop.convert import scenario_to_instance
    from asprilo.interop.movingai import parse_map, parse_scenario
    from asprilo.sources import Source
    from asprilo.writer import format_instance, write_text
    path = out / "random-32-32-20-labelled-200.lp"
    if not path.exists():
        grid = parse_map(Source.from_path(MOVINGAI / "random-32-32-20.map"))
        tasks = parse_scenario(Source.from_path(MOVINGAI / "random-32-32-20-random-1.scen"))
        write_text(path, format_instance(scenario_to_instance(grid, tasks, 200, labelled=True)))
    return path


def jobs(targets: list[str], out: Path) -> list[dict]:
    found = []
    if "paper" in targets or "m" in targets:
        papers = paper_instances(out)
    if "paper" in targets:
        found += [{"target": "paper", "set": size, "path": str(path), "domain": d,
                   "limit": 60 if size == "large" else 10}
                  for size, path in papers for d in "abc"]
    if "m" in targets:
        found += [{"target": "m", "set": size, "path": str(path), "domain": d, "limit": 10, "flow": True}
                  for size, path in papers for d in ("m", "md")]
    if "movingai" in targets:
        found.append({"target": "movingai", "set": "200 agents", "path": str(movingai(out)), "domain": "md",
                      "limit": 60})
    if "g40" in targets:
        found.append({"target": "g40", "set": "40x40", "path": str(generated(out, "g40", G40)), "domain": "a",
                      "limit": 60})
    if "g100" in targets:
        found.append({"target": "g100", "set": "100x100", "path": str(generated(out, "g100", G100)), "domain": "a",
                      "limit": 300})
    return found


# --- tables and the plot ---------------------------------------------------------------------

def table(runs: list[dict]) -> str:
    """Per target, set and domain: plans found, time to the first plan (mean, max), makespan
    over the bound at the end (and over the flow optimum for M/Md), peak memory."""
    lines = [f"{'target':<9}{'set':<11}{'dom':<4}{'plans':>7}{'first mean':>11}{'first max':>10}"
             f"{'end/bound':>10}{'end/opt':>9}{'peak MB':>9}"]
    keys = sorted({(r["target"], r["set"], r["domain"]) for r in runs}, key=lambda k: (k[0], list(SIZES.values())
                  .index(k[1]) if k[1] in SIZES.values() else 9, k[2]))
    for target, name, domain in keys:
        group = [r for r in runs if (r["target"], r["set"], r["domain"]) == (target, name, domain)]
        found = [r for r in group if r["history"]]
        firsts = [r["history"][0]["seconds"] for r in found]
        ratio = [r["history"][-1]["makespan"] / r["bound"] for r in found if r["bound"]]
        optimum = [r["history"][-1]["makespan"] / r["optimum"] for r in found if r.get("optimum")]
        lines.append(f"{target:<9}{name:<11}{domain:<4}{len(found):>4}/{len(group):<2}"
                     f"{mean(firsts) if firsts else float('nan'):>11.2f}{max(firsts, default=float('nan')):>10.2f}"
                     f"{mean(ratio) if ratio else float('nan'):>10.3f}"
                     f"{mean(optimum) if optimum else float('nan'):>9.3f}{max(r['peak_mb'] for r in group):>9.0f}")
    return "\n".join(lines)


def curves(runs: list[dict]) -> dict[str, list[tuple[float, float]]]:
    """Mean makespan / bound over time, per (target set, domain), sampled at SAMPLES."""
    result = {}
    for key in sorted({(r["target"], r["set"], r["domain"]) for r in runs}):
        group = [r for r in runs if (r["target"], r["set"], r["domain"]) == key and r["bound"]]
        if key[0] in ("paper", "m") and key[1] != "large":
            continue
        points = []
        for seconds in SAMPLES:
            if seconds > max(r["limit"] for r in group):
                break
            spans = [makespan_at(r, seconds) for r in group]
            if all(span is not None for span in spans):
                points.append((seconds, mean(span / r["bound"] for span, r in zip(spans, group, strict=True))))
        label = f"{key[1]} {key[2].upper() if key[2] != 'md' else 'Md'}"
        result[label] = points
    return result


def plot(runs: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axis = plt.subplots(figsize=(7, 4.2))
    for label, points in curves(runs).items():
        if points:
            axis.plot(*zip(*points, strict=True), marker="o", markersize=3, label=label)
    axis.set(xscale="log", xlabel="time (s)", ylabel="makespan / lower bound",
             title="anytime planner: best makespan over the lower bound (means)")
    axis.axhline(1.0, color="grey", linewidth=0.8)
    axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    print(f"wrote {path}", file=sys.stderr)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--targets", default="paper,m,movingai,g40,g100")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", type=Path, default=Path("/tmp/anytime-speed"))
    parser.add_argument("--plot", type=Path, default=ROOT / "benchmarks/pictures/anytime-makespan.png")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    todo = jobs(args.targets.split(","), args.out)
    print(f"{len(todo)} runs, {args.jobs} at a time", file=sys.stderr)
    context = multiprocessing.get_context("spawn")
    runs = []
    with ProcessPoolExecutor(args.jobs, mp_context=context, max_tasks_per_child=1) as pool, \
            open(args.out / "anytime-runs.jsonl", "w") as log:
        for run in pool.map(run_one, todo):
            runs.append(run)
            log.write(json.dumps(run) + "\n")
            log.flush()
            print(f"{run['target']} {Path(run['path']).name} {run['domain']}: {run['status']}, "
                  f"first {run['history'][0]['seconds'] if run['history'] else '-'} s, "
                  f"makespan {makespan_at(run, 1e9)} (bound {run['bound']:g})", file=sys.stderr, flush=True)
    print(table(runs))
    plot(runs, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
