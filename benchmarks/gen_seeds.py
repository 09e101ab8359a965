"""How long ``gen`` takes for each of many seeds of one call (issue 44: no seed may stall).

By default every seed runs as a whole ``gen ... --seed S -C -q`` command in a fresh process
(interpreter start, imports, generation and printing included), one after the other; with
``--api`` the seeds run in this process through :func:`asprilo.generator.generate` (no
interpreter start, ``-w`` set to the timeout).  A seed that takes longer than ``--timeout``
is stopped and counted as that long, so the median and max are then lower bounds.  Prints
the time of every seed, the min, median and max, and the seeds above the target.

Run: python benchmarks/gen_seeds.py [--seeds 1-100] [--api] [--timeout S] [--target S] [--call "GEN ARGS"]
"""

from __future__ import annotations

import argparse
import shlex
import statistics
import subprocess
import sys
import time

#: the exercise-size call of issue 44
CALL = "-x 11 -y 6 -X 4 -Y 2 -p 2 -s 16 -P 8 -u 40 -r 4 -H --prsmin 1 --prsmax 3 --olmin 1 --olmax 3 -o 4"
CHILD = "import sys; from asprilo.cli import main; sys.exit(main(['gen', *sys.argv[1:]]))"


def seed_list(text: str) -> list[int]:
    """``1-100``, ``3,9301-9310`` and the like."""
    seeds: list[int] = []
    for part in text.split(","):
        low, _, high = part.partition("-")
        seeds += range(int(low), int(high or low) + 1)
    return seeds


def run_command(arguments: list[str], seed: int, timeout: float) -> tuple[float, str]:
    """Seconds one whole command takes, and how it ended (ok, exit N, timeout)."""
    started = time.perf_counter()
    try:
        done = subprocess.run([sys.executable, "-c", CHILD, *arguments, "--seed", str(seed), "-C", "-q"],
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return timeout, "timeout"
    return time.perf_counter() - started, "ok" if done.returncode == 0 else f"exit {done.returncode}"


def api_config(arguments: list[str], timeout: float):
    """The generator configuration of ``gen`` arguments, with the time limit ``timeout``."""
    from asprilo.generator.cli import configure
    from asprilo.generator.config import parse_values
    from asprilo.generator.options import BY_NAME
    from asprilo.generator.runs import command_job

    parser = argparse.ArgumentParser(prog="gen")
    configure(parser)
    given = {name: value for name, value in vars(parser.parse_args([*arguments, "-w", str(timeout)])).items()
             if name in BY_NAME}
    return command_job(parse_values(given)).config


def run_api(config, seed: int) -> tuple[float, str]:
    """Seconds one instance takes through the API, and how it ended."""
    from asprilo.generator import GenerationFailed, generate

    started = time.perf_counter()
    try:
        generate(config, 1, seed)
    except GenerationFailed as failure:
        return time.perf_counter() - started, "timeout" if failure.timed_out else "unsatisfiable"
    return time.perf_counter() - started, "ok"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="1-100", help="seeds to run (default 1-100)")
    parser.add_argument("--call", default=CALL, help="the gen arguments (default: the issue's exercise call)")
    parser.add_argument("--api", action="store_true", help="run through the API in this process")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds after which a seed is stopped")
    parser.add_argument("--target", type=float, default=2.0, help="seconds a seed should stay within")
    args = parser.parse_args()
    arguments = shlex.split(args.call)
    config = api_config(arguments, args.timeout) if args.api else None
    print(f"gen {args.call} --seed S -C  ({'API, in this process' if args.api else 'whole commands'})")
    times: dict[int, float] = {}
    for seed in seed_list(args.seeds):
        seconds, end = run_api(config, seed) if args.api else run_command(arguments, seed, args.timeout)
        times[seed] = seconds
        print(f"seed {seed:>6}: {seconds:7.2f} s  {end}", flush=True)
    values = sorted(times.values())
    slow = [seed for seed, seconds in times.items() if seconds > args.target]
    print(f"{len(values)} seeds: min {values[0]:.2f} s, median {statistics.median(values):.2f} s, "
          f"max {values[-1]:.2f} s")
    print(f"above {args.target:g} s: {', '.join(map(str, slow)) if slow else 'none'}")


if __name__ == "__main__":
    main()
