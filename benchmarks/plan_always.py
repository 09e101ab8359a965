"""A plan always, an answer at once (issue 32, items 1, 2 and 4): `asprilo solve` with its
defaults (method auto: the exact search and the anytime planner side by side) as a user runs
it, a whole process per run, timed from the outside.

Targets:
  exercise  20 generated exercise-size A instances (11x6, 3-5 robots, 3-5 orders, seeds 1-20;
            FLAGS below): a checked plan within 5 s for 20/20, proven minimal for >= 15/20 within
            60 s, every makespan within 60 s at most 1.15 x the proven minimum where it is known
            (--minima FILE adds minima established apart, e.g. by long exact searches)
  small-a   the bundled small A example: a plan within 5 s, makespan <= 25 within 60 s with its
            lower bound
  paper     the paper A/B/C sample, medium (paper-abc-sample.yml: 19x9, 5/10/15/19 robots, the
            first 5 instances each), read as A, B and C, no assignment, 60 s: a plan for 20/20
  sizes     every instance gen makes with the sizes of the README's and the docs' examples
            (SIZES below), in every domain it makes: a checked plan within 5 s
  silence   no silence longer than 5 s on a terminal in a solve, a bench and a gen run: each
            runs on a pseudo-terminal and the longest gap between two writes is measured
  turns     alternatives to auto on the exercise instances and the small A example: the exact
            search alone, the anytime planner alone, and the two in turns in one process
            (the anytime planner for --turn seconds, then the exact search with the anytime
            plan's makespan minus one as its largest horizon)

The first plan is timed from the start of the process to the line on standard error that
reports it (a pipe: one line per plan); the rest comes from --json.  Runs go one at a time
(auto uses both cores).  Prints a table per target and writes every run to OUT/runs.jsonl.

Run: python benchmarks/plan_always.py [--targets exercise,small-a,paper,sizes,silence,turns]
                                      [--time-limit 60] [--out /tmp/plan-always] [--minima FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import pty
import re
import select
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SMALL_A = ROOT / "examples/asprilo/dom-a/small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
#: the exercise-size A instances: 11x6 as the README's examples, 2 stations, 12 shelves of 8
#: products with 30 units; seed S has 3 + (S-1) % 3 robots and 3 + (S-1) // 3 % 3 orders
FLAGS = "-x 11 -y 6 -X 4 -Y 2 -H -p 2 -s 12 -P 8 -u 30 --domain a"
#: the sizes of the examples in README.md, asprilo/generator/README.md, docs/SPEC.md and the domains'
#: exercise sizes (asprilo/domain/*.py, Generation.exercise, as `asprilo demo` makes them);
#: name -> (gen flags, the domains gen makes them in)
SIZES = {
    "readme-figure-1": ("-x 19 -y 9 -X 5 -Y 2 -p 3 -s 45 -r 6 -P 180 -u 540 -o 12 -H", "abc"),
    "readme-m": ("-x 11 -y 6 -X 4 -Y 2 -H -p 1 -s 16 -r 5 -P 16 -u 16 -o 5", "abcm"),
    "gen-readme-small": ("-x 11 -y 6 -X 4 -Y 2 -p 1 -s 16 -P 16 -u 16 -H --prs 1 -r 2 -o 2", "abcm"),
    "gen-readme-random": ("-x 20 -y 20 -n 360 -p 4 -r 8 --sc 40 -R -P 20 -u 100 -o 10", "abc"),
    "spec-small-11": ("-x 11 -y 6 -X 4 -Y 2 -p 1 -s 16 -P 16 -u 16 -H --prs 1 -r 11 -o 11", "abcm"),
    "spec-medium-19": ("-x 19 -y 9 -X 5 -Y 2 -p 3 -s 60 -P 60 -u 60 -H --prs 1 -r 19 -o 19", "abcm"),
    "exercise-a": ("-x 11 -y 6 -X 4 -Y 2 -H -p 2 -r 3 -s 8 -P 4 -u 16 -o 2", "a"),
    "exercise-b": ("-x 11 -y 6 -X 4 -Y 2 -H -p 2 -r 3 -s 8 -P 4 -u 16 -o 2 --olmax 2", "b"),
    "exercise-c": ("-x 11 -y 6 -X 4 -Y 2 -H -p 2 -r 3 -s 8 -P 4 -u 16 -o 3 --olmax 2", "c"),
    "exercise-m": ("-x 19 -y 9 -X 5 -Y 2 -H -p 3 -r 10 -s 60 -P 60 -u 60 -o 10 --prs 1", "m"),
}
#: a line of `asprilo solve` (standard error a pipe) that reports a plan
PLAN_LINE = re.compile(r"^(plan: makespan (\d+)|horizon (\d+)[^:]*: sat)")


def solve_run(path: Path, options: list[str], limit: float, label: str) -> dict:
    """One `asprilo solve PATH OPTIONS --time-limit LIMIT --json`, timed from the outside."""
    command = [sys.executable, "-m", "asprilo.cli", "solve", str(path), *options, "--time-limit", f"{limit:g}",
               "--json"]
    started = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    first = None
    assert process.stderr is not None
    lines = []
    for line in process.stderr:
        lines.append(line)
        if first is None and PLAN_LINE.match(line):
            first = time.perf_counter() - started
    out = process.stdout.read() if process.stdout else ""
    process.wait()
    seconds = time.perf_counter() - started
    try:
        answer = json.loads(out)
    except json.JSONDecodeError:
        answer = {"status": "error", "message": "".join(lines[-3:])}
    return {"label": label, "instance": str(path), "options": options, "limit": limit, "seconds": round(seconds, 2),
            "first_plan": None if first is None else round(first, 2), "exit": process.returncode,
            "status": answer.get("status"), "makespan": answer.get("horizon"), "minimal": answer.get("minimal"),
            "lower_bound": answer.get("lower_bound"), "proven_bound": answer.get("proven_bound"),
            "found_by": answer.get("found_by"), "method": answer.get("method"), "history": answer.get("history"),
            "message": answer.get("message")}


def generate(flags: str, seed: int, domain: str, folder: Path) -> Path:
    """One instance of ``gen FLAGS --seed SEED --domain DOMAIN`` (made once, kept in ``folder``)."""
    target = folder / f"{re.sub(r'[^a-z0-9]+', '_', flags)}_{domain}_s{seed}"
    found = sorted(target.glob("*.lp"))
    if not found:
        subprocess.run([sys.executable, "-m", "asprilo.cli", "gen", *flags.split(), "--domain", domain,
                        "--seed", str(seed), "-N", "1", "-d", str(target)], check=True, capture_output=True)
        found = sorted(target.glob("*.lp"))
    return found[0]


def exercise_instances(folder: Path) -> list[tuple[int, Path]]:
    instances = []
    for seed in range(1, 21):
        robots, orders = 3 + (seed - 1) % 3, 3 + (seed - 1) // 3 % 3
        flags = FLAGS.replace("--domain a", "") + f" -r {robots} -o {orders}"
        instances.append((seed, generate(flags, seed, "a", folder)))
    return instances


def load(args) -> dict[str, int]:
    return json.loads(Path(args.minima).read_text()) if args.minima else {}


def record(out: Path, run: dict) -> dict:
    with (out / "runs.jsonl").open("a") as file:
        file.write(json.dumps(run) + "\n")
    return run


def ratio(run: dict, minimum: int | None) -> str:
    if run["makespan"] is None or minimum is None:
        return "-"
    return f"{run['makespan'] / minimum:.2f}"


# --- the targets ------------------------------------------------------------------------------------


def target_exercise(args, out: Path) -> None:
    minima = load(args)
    print(f"exercise: {FLAGS} -r R -o O --seed S, defaults, --time-limit {args.time_limit:g}")
    print(f"{'seed':>4} {'file':<44} {'first':>6} {'end':>6} {'makespan':>8} {'bound':>5} {'minimal':>7} "
          f"{'by':>7} {'min':>4} {'ratio':>5}")
    runs = []
    for seed, path in exercise_instances(out / "instances"):
        run = record(out, solve_run(path, [], args.time_limit, f"exercise s{seed}"))
        minimum = run["makespan"] if run["minimal"] else minima.get(f"s{seed}")
        run["minimum"] = minimum
        runs.append(run)
        print(f"{seed:>4} {path.name:<44} {run['first_plan'] or '-':>6} {run['seconds']:>6} "
              f"{run['makespan'] or '-':>8} {run['proven_bound'] or '-':>5} {str(run['minimal']):>7} "
              f"{run['found_by'] or '-':>7} {minimum or '-':>4} {ratio(run, minimum):>5}", flush=True)
    fast = sum(1 for run in runs if run["first_plan"] is not None and run["first_plan"] <= 5)
    proven = sum(1 for run in runs if run["minimal"])
    known = [run for run in runs if run["minimum"] is not None and run["makespan"] is not None]
    within = sum(1 for run in known if run["makespan"] <= 1.15 * run["minimum"])
    print(f"plan within 5 s: {fast}/{len(runs)} (target 20/20); proven minimal: {proven}/{len(runs)} "
          f"(target >= 15); makespan <= 1.15 x minimum: {within}/{len(known)} where known "
          f"(worst {max((r['makespan'] / r['minimum'] for r in known), default=0):.2f})")


def target_small_a(args, out: Path) -> None:
    run = record(out, solve_run(SMALL_A, ["--domain", "a"], args.time_limit, "small-a"))
    print(f"small A example, defaults, --time-limit {args.time_limit:g}: first plan {run['first_plan']} s "
          f"(target 5 s), makespan {run['makespan']} after {run['seconds']} s (target <= 25), lower bound "
          f"{run['lower_bound']}, proven bound {run['proven_bound']}, history "
          f"{[(h['seconds'], h['makespan']) for h in run['history'] or []]}")


def paper_instances(out: Path) -> list[Path]:
    """The medium set of paper-abc-sample.yml (generated once with its batch)."""
    from asprilo.bench.runner import Runner
    from asprilo.bench.suite import load_suite

    runner = Runner(load_suite(ROOT / "benchmarks/paper-abc-sample.yml"), out / "paper")
    return [instance.path for instance in runner.instances() if instance.set == "medium"]


def target_paper(args, out: Path) -> None:
    instances = paper_instances(out)
    for domain in args.domains:
        print(f"paper medium read as {domain.upper()}, defaults, --time-limit {args.time_limit:g}")
        runs = []
        for path in instances:
            run = record(out, solve_run(path, ["--domain", domain], args.time_limit, f"paper {domain}"))
            runs.append(run)
            print(f"  {path.name:<48} first {run['first_plan'] or '-':>6} end {run['seconds']:>6} makespan "
                  f"{run['makespan'] or '-':>4} bound {run['proven_bound'] or '-':>4} minimal {run['minimal']} "
                  f"by {run['found_by']}", flush=True)
        planned = sum(1 for run in runs if run["status"] == "found")
        proven = sum(1 for run in runs if run["minimal"])
        print(f"  {domain.upper()}: a plan for {planned}/{len(runs)} (target 20/20), proven minimal {proven}")


def target_sizes(args, out: Path) -> None:
    print("README/docs example sizes, every domain, defaults, --time-limit 30 (first plan: target 5 s)")
    for name, (flags, domains) in SIZES.items():
        for domain in domains:
            path = generate(flags, 1, domain, out / "sizes")
            run = record(out, solve_run(path, ["--domain", domain], 30, f"size {name} {domain}"))
            print(f"  {name:<18} {domain.upper():<2} first {run['first_plan'] or '-':>6} makespan "
                  f"{run['makespan'] or '-':>4} bound {run['proven_bound'] or '-':>4} minimal {str(run['minimal']):>5} "
                  f"method {run['method']}", flush=True)


def silence(command: list[str], seconds: float) -> tuple[float, float]:
    """The longest gap between two writes of ``command`` on a pseudo-terminal within
    ``seconds`` (then it is interrupted), and how long it ran."""
    master, slave = pty.openpty()
    started = time.perf_counter()
    process = subprocess.Popen(command, stdout=slave, stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    last, longest = started, 0.0
    while time.perf_counter() - started < seconds:
        ready, _, _ = select.select([master], [], [], 0.1)
        if ready:
            try:
                if not os.read(master, 65536):
                    break
            except OSError:
                break
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        elif process.poll() is not None:
            break
    process.send_signal(2)
    process.wait(60)
    os.close(master)
    return round(max(longest, time.perf_counter() - last if process.returncode is None else 0), 2), \
        round(time.perf_counter() - started, 1)


def target_silence(args, out: Path) -> None:
    suite = out / "silence-suite.yml"
    suite.write_text(f"name: silence\ntime_limit: 20\nmakespan_time_limit: 20\ninstances:\n"
                     f"  one: {{files: [{SMALL_A}]}}\nruns:\n  - {{domain: a, encoding: plain}}\n"
                     f"  - {{domain: a, method: anytime}}\n")
    commands = {
        "solve (small A, 30 s)": ([sys.executable, "-m", "asprilo.cli", "solve", str(SMALL_A), "--domain", "a",
                                   "--time-limit", "30", "-o", str(out / "plan.lp")], 40),
        "solve --assign (small A, 30 s)": ([sys.executable, "-m", "asprilo.cli", "solve", str(SMALL_A), "--domain",
                                            "a", "--assign", "--time-limit", "30", "-o", str(out / "plan.lp")], 40),
        "gen (100x100, 200 robots)": ([sys.executable, "-m", "asprilo.cli", "gen", "-x", "100", "-y", "100", "-H",
                                       "-r", "200", "-s", "1000", "-p", "20", "-P", "500", "-u", "3000", "-o", "50",
                                       "-N", "2", "--seed", "3", "-d", str(out / "gen-silence"), "--force"], 120),
        "bench (2 runs of the small A example, 20 s each)": (
            [sys.executable, "-m", "asprilo.cli", "bench", str(suite), "-o", str(out / "bench-silence"),
             "--restart"], 200),
    }
    for name, (command, seconds) in commands.items():
        gap, ran = silence(command, seconds)
        print(f"  {name:<50} longest silence {gap:>5} s in {ran} s (target <= 5 s)", flush=True)
        record(out, {"label": f"silence {name}", "longest_silence": gap, "seconds": ran})


def turns_run(path: Path, domain: str, limit: float, turn: float) -> dict:
    """The anytime planner for ``turn`` seconds, then the exact search up to its makespan
    minus one for the rest of the time (in one process, one after the other)."""
    from asprilo.encodings import solve

    started = time.perf_counter()
    first = solve(path, domain, method="anytime", time_limit=turn, isolate=True)
    first_plan = first.history[0]["seconds"] if first.history else None
    makespan, minimal = first.horizon, first.minimal
    if first.found and not first.minimal:
        left = limit - (time.perf_counter() - started)
        exact = solve(path, domain, method="asp", max_horizon=first.horizon - 1, time_limit=max(1.0, left),
                      isolate=True)
        if exact.found:
            makespan, minimal = exact.horizon, exact.minimal
        elif exact.status.value == "limit" and exact.proven_bound >= first.horizon:
            minimal = True  # every horizon below the anytime plan refuted
    return {"first_plan": first_plan, "makespan": makespan, "minimal": minimal,
            "seconds": round(time.perf_counter() - started, 2)}


def target_turns(args, out: Path) -> None:
    print(f"alternatives, --time-limit {args.time_limit:g}: first plan (s) / makespan / proven")
    instances = [(f"s{seed}", path, "a") for seed, path in exercise_instances(out / "instances")]
    instances.append(("small-a", SMALL_A, "a"))
    totals: dict[str, list[dict]] = {}
    for name, path, domain in instances:
        row = {"auto": solve_run(path, ["--domain", domain], args.time_limit, f"turns {name} auto"),
               "asp": solve_run(path, ["--domain", domain, "--method", "asp"], args.time_limit, f"turns {name} asp"),
               "anytime": solve_run(path, ["--domain", domain, "--method", "anytime"], args.time_limit,
                                    f"turns {name} anytime"),
               "turns": turns_run(path, domain, args.time_limit, args.turn)}
        for kind, run in row.items():
            totals.setdefault(kind, []).append(run)
        record(out, {"label": f"turns {name}", **{kind: {k: run.get(k) for k in ("first_plan", "makespan",
                                                                                    "minimal", "seconds")}
                                                   for kind, run in row.items()}})
        print(f"  {name:<8} " + "  ".join(f"{kind} {run.get('first_plan') or '-'}/{run.get('makespan') or '-'}/"
                                          f"{'P' if run.get('minimal') else '-'}" for kind, run in row.items()),
              flush=True)
    for kind, runs in totals.items():
        firsts = [run["first_plan"] for run in runs if run.get("first_plan") is not None]
        print(f"  {kind:<8} plans {len(firsts)}/{len(runs)}, first plan within 5 s "
              f"{sum(1 for f in firsts if f <= 5)}, proven {sum(1 for run in runs if run.get('minimal'))}, "
              f"makespans summed {sum(run.get('makespan') or 0 for run in runs)}")


TARGETS = {"exercise": target_exercise, "small-a": target_small_a, "paper": target_paper, "sizes": target_sizes,
           "silence": target_silence, "turns": target_turns}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--targets", default=",".join(TARGETS))
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--turn", type=float, default=10.0, help="turns: the anytime planner's seconds")
    parser.add_argument("--domains", default="abc", help="paper: the domains to read the instances as")
    parser.add_argument("--out", default="/tmp/plan-always")
    parser.add_argument("--minima", help="JSON {\"s7\": 21, ...}: minima of exercise instances established apart")
    args = parser.parse_args()
    args.domains = list(args.domains)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    print(f"load average at the start: {os.getloadavg()[0]:.2f} (2 cores: above 2, other jobs share them)")
    for name in args.targets.split(","):
        TARGETS[name](args, out)
    print(f"load average at the end: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
