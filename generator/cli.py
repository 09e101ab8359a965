"""Generate warehouse instances with a compartmentalised multi-shot ASP program.

Layouts: random (default; -n for a partial grid with gaps), structured (-H: storage zones
surrounded by highways) and templates (-T: populate a hand-made layout).  The flags are those
of the original asprilo generator, so the paper's calls run unchanged.

Examples:
  gen -x 19 -y 9 -X 5 -Y 2 -p 3 -s 45 -r 6 -P 180 -u 540 -o 12 -H
  gen -x 11 -y 6 -X 4 -Y 2 -p 1 -s 16 -P 16 -u 16 -H --prs 1 -r 2 -o 2 -N 30 -d small
  gen -x 20 -y 20 -n 360 -p 4 -r 8 --sc 40 -R -P 20 -u 100 -o 10 -C
  gen -T layout.lp -r 5 -s 20 -P 10 -u 40 -o 5
  gen -j benchmarks/paper-m.yml -d instances/paper-m --skip-existing

Exit status: 0 instances written, 1 no instance (unsatisfiable request or time limit),
2 bad input (inconsistent options, bad template or batch file).
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from asprilo.cli import domain_argument
from asprilo.errors import InputError
from asprilo.writer import format_instance

from .api import generate_one
from .batch import load_batch
from .config import GeneratorConfig, RunOptions, parse_values
from .options import BY_NAME, DEFAULT_SEED, OPTIONS, split_values
from .output import Progress, exists, save
from .pipeline import GenerationFailed
from .plan import Plan, make_plan
from .sampling import derive_seed

_TYPES = {"int": int, "float": float, "str": str, "domain": domain_argument}


def configure(parser: argparse.ArgumentParser) -> None:
    groups: dict[str, argparse._ArgumentGroup] = {}
    for option in OPTIONS:
        group = groups.get(option.group) or groups.setdefault(option.group, parser.add_argument_group(option.group))
        kwargs: dict[str, Any] = {"dest": option.name, "help": option.help, "default": argparse.SUPPRESS}
        if option.kind == "flag":
            kwargs["action"] = "store_true"
        elif option.kind == "paths":
            kwargs.update(nargs="+", metavar=option.metavar)
        else:
            kwargs.update(type=_TYPES[option.kind], metavar=option.metavar)
        group.add_argument(*option.flags, **kwargs)
    batch = groups["output and batches"]
    batch.add_argument("-j", "--batch", metavar="FILE",
                       help="run the configurations of a YAML batch file; options given here apply to "
                            "every run and override the file's")
    batch.add_argument("-V", "--verbose", action="store_true",
                       help="report each instance's stages (rounds and seconds) on stderr")


@dataclass
class _Job:
    """One configuration to generate: a whole command, or one run of a batch."""

    config: GeneratorConfig
    options: RunOptions
    directory: Path
    where: tuple[str | None, int | None] = (None, None)  # batch file and line, for messages


def run(args: argparse.Namespace) -> int:
    given = {name: value for name, value in vars(args).items() if name in BY_NAME}
    values = parse_values(given)
    jobs = _batch_jobs(args.batch, values) if args.batch else [_job(values)]
    plans = []
    for job in jobs:
        try:
            plans.append(make_plan(job.config))
        except InputError as error:
            raise error.at(*job.where) from None
    # a progress bar when writing files (with -C the instances themselves show the progress)
    progress = Progress(sum(job.options.count for job in jobs if not job.options.console))
    failed = 0
    for job, plan in zip(jobs, plans):
        failed += _generate(job, plan, progress, args.verbose)
    return 1 if failed else 0


def _job(values: dict[str, Any], directory: Path | None = None, where=(None, None)) -> _Job:
    config_values, run_values = split_values(values)
    options = RunOptions(**run_values)
    return _Job(GeneratorConfig(**config_values), options, directory or Path(options.directory), where)


def _batch_jobs(path: str, command_line: dict[str, Any]) -> list[_Job]:
    jobs = []
    for item in load_batch(path):
        values = {**item.values, **command_line}
        base = values.get("seed", DEFAULT_SEED)
        values["seed"] = derive_seed(base, "run", item.directory, item.index)
        directory = Path(values.get("directory", RunOptions.directory)) / item.directory
        jobs.append(_job(values, directory, (path, item.line)))
    return jobs


def _generate(job: _Job, plan: Plan, progress: Progress, verbose: bool) -> int:
    """Generate (and write or print) the instances of one job; returns the number that failed."""
    options = job.options
    command = job.config.command_line(options)
    failed = 0
    for number in range(1, options.count + 1):
        if not options.console and options.skip_existing and \
                exists(job.directory, number, options.prefix, options.instance_dir):
            progress.advance(f"{job.directory}: N{number:03d} exists")
            continue
        try:
            item = generate_one(plan, options.seed, number, command)
        except GenerationFailed as failure:
            progress.interrupt()
            print(f"error: {_place(job)}no instance {number}: {failure}", file=sys.stderr)
            failed += 1
            if not failure.timed_out:
                break  # unsatisfiable: the other instances of this configuration are too
            continue
        if options.console:
            sys.stdout.write(format_instance(item.instance, item.header) + "\n")
            label = item.file_name(options.prefix)
        else:
            label = str(save(item, job.directory, options.prefix, options.instance_dir))
        if verbose:
            stages = ", ".join(f"{stage} {rounds}x {seconds:.2f}s" for stage, (rounds, seconds) in item.stages.items())
            progress.interrupt()
            print(f"{label}: {stages}", file=sys.stderr)
        if not options.console:
            progress.advance(label)
    return failed


def _place(job: _Job) -> str:
    file, line = job.where
    if file is None:
        return ""
    return f"{file}:{line}: " if line else f"{file}: "
