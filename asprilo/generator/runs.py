"""Runs of the generator that write files: one command's configuration, or every run of a
YAML batch file, with progress, ``--skip-existing`` and one error line per failed instance.

    from asprilo.generator import generate_batch
    failed = generate_batch("benchmarks/paper-m.yml", "instances/paper-m", skip_existing=True)
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TextIO

from asprilo.errors import InputError
from asprilo.writer import format_instance

from .api import Generated, generate_limited
from .batch import load_batch
from .config import GeneratorConfig, RunOptions, parse_values
from .options import DEFAULT_SEED, split_values
from .output import WriteProgress, check_output_folder, exists, save
from .pipeline import GenerationFailed
from .plan import GenerationPlan, make_plan
from .sampling import derive_seed


@dataclass
class Job:
    """One configuration to generate: a whole command, or one run of a batch."""

    config: GeneratorConfig
    options: RunOptions
    directory: Path
    where: tuple[str | None, int | None] = (None, None)  # batch file and line, for messages


def command_job(values: dict[str, Any], directory: Path | None = None, where=(None, None)) -> Job:
    """The job of checked option values (field name -> value)."""
    config_values, run_values = split_values(values)
    options = RunOptions(**run_values)
    return Job(GeneratorConfig(**config_values), options, directory or Path(options.directory), where)


def batch_jobs(path: str | Path, overrides: dict[str, Any] | None = None) -> list[Job]:
    """The jobs of a batch file; ``overrides`` (checked option values) apply to every run."""
    jobs = []
    for item in load_batch(path):
        values = {**item.values, **(overrides or {})}
        base = values.get("seed", DEFAULT_SEED)
        values["seed"] = derive_seed(base, "run", item.directory, item.index)
        directory = Path(values.get("directory", RunOptions.directory)) / item.directory
        jobs.append(command_job(values, directory, (str(path), item.line)))
    return jobs


@dataclass
class Tally:
    """What became of the instances of some jobs."""

    written: int = 0
    kept: int = 0    # existing files kept (--skip-existing)
    failed: int = 0  # instances that could not be made

    def __add__(self, other: Tally) -> Tally:
        return Tally(self.written + other.written, self.kept + other.kept, self.failed + other.failed)


def run_jobs(jobs: list[Job], verbose: bool = False, stream: TextIO | None = None, quiet: bool = False) -> int:
    """Generate every job's instances; returns how many instances could not be made.

    Inconsistent options are reported (as :class:`InputError`, naming the batch file and
    line) before anything is generated.  Unless ``quiet``, a progress bar and a last line
    saying where the files went are written to ``stream``.
    """
    stream = stream or sys.stderr
    plans = []
    for job in jobs:
        try:
            plans.append(make_plan(job.config))
            _check_output(job.options)
        except InputError as error:
            raise error.at(*job.where) from None
    files = [job for job in jobs if not job.options.console]
    for job in files:
        check_output_folder(job.directory, "-d")
    # a progress bar when writing files (with -C the instances themselves show the progress)
    progress = WriteProgress(0 if quiet else sum(job.options.count for job in files), stream, beats=not quiet)
    try:
        tally = sum((_generate(job, plan, progress, verbose, stream) for job, plan in zip(jobs, plans, strict=True)),
                    Tally())
    finally:
        progress.close()
    if files and not quiet and (tally.written or tally.kept):
        print(_where_files_went(files, tally), file=stream)
    return tally.failed


def _where_files_went(jobs: list[Job], tally: Tally) -> str:
    folders = {job.directory for job in jobs}
    where = f"to {jobs[0].directory}" if len(folders) == 1 else \
        f"below {jobs[0].options.directory} ({len(folders)} folders)"
    line = f"wrote {tally.written} instance file{'s' if tally.written != 1 else ''} {where}"
    if tally.kept:
        line += f", kept {tally.kept} that existed"
    if tally.failed:
        line += f"; {tally.failed} could not be made"
    return line


def generate_batch(path: str | Path, directory: str | Path, skip_existing: bool = True,
                   stream: TextIO | None = None, **options: Any) -> int:
    """Write the instances of a YAML batch file below ``directory``; how many failed.

    ``options`` are further option values by field name (e.g. ``seed=3``), checked as on
    the command line, that override the file's.
    """
    overrides = parse_values({**options, "directory": str(directory), "skip_existing": skip_existing})
    return run_jobs(batch_jobs(path, overrides), stream=stream)


def _generate(job: Job, plan: GenerationPlan, progress: WriteProgress, verbose: bool, stream: TextIO) -> Tally:
    """Generate (and write or print) the instances of one job."""
    options = job.options
    command = job.config.command_line(options)
    tally = Tally()
    for number in range(options.first, options.first + options.count):
        if not options.console and options.skip_existing and \
                exists(job.directory, number, options.prefix, options.instance_dir):
            progress.advance(f"{job.directory}: N{number:03d} exists")
            tally.kept += 1
            continue
        progress.working(f"N{number:03d}" if options.console else f"{job.directory}: N{number:03d}")
        try:
            item = generate_limited(plan, options.seed, number, command, progress.stage)  # -w and gen-mb hold
        except GenerationFailed as failure:
            progress.interrupt()
            print(f"error: {_place(job)}no instance {number}: {failure}", file=stream)
            tally.failed += 1
            if not failure.timed_out:
                break  # unsatisfiable: the other instances of this configuration are too
            continue
        label = _put(job, item, progress)
        tally.written += not options.console
        if verbose:
            stages = ", ".join(f"{stage} {rounds}x {seconds:.2f}s" for stage, (rounds, seconds) in item.stages.items())
            progress.interrupt()
            print(f"{label}: {stages}", file=stream)
        if not options.console:
            progress.advance(label)
    return tally


def _put(job: Job, item: Generated, progress: WriteProgress) -> str:
    """Print an instance (-C) or write its file; its name or path, for messages."""
    options = job.options
    if options.console:
        sys.stdout.write(format_instance(item.instance, item.header) + "\n")
        return item.file_name(options.prefix)
    try:
        templates = getattr(job.config, "templates", None) or ()  # (a field mypy does not see: made at run time)
        return str(save(item, job.directory, options.prefix, options.instance_dir, options.force,
                        (*templates, job.where[0])))
    except InputError:
        progress.interrupt()
        raise


def _check_output(options: Any) -> None:
    """Refuse :class:`RunOptions` that both replace and keep existing files (``Any``: a class
    made at run time, which mypy does not see)."""
    if options.force and options.skip_existing:
        raise InputError("give either --force (replace files) or --skip-existing (keep them), not both")


def _place(job: Job) -> str:
    file, line = job.where
    if file is None:
        return ""
    return f"{file}:{line}: " if line else f"{file}: "
