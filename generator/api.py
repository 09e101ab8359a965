"""The generator's Python API: configurations in, instances (with their file headers) out."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field, replace

from asprilo.model import Instance
from asprilo.writer import header_lines

from .assemble import assemble
from .config import GeneratorConfig, RunOptions
from .options import DEFAULT_SEED
from .pipeline import Generator
from .plan import GenerationPlan, make_plan
from .sampling import derive_seed

TOOL = "asprilo gen"


@dataclass
class Generated:
    """One generated instance, its number in the run, its seed and its file header."""

    instance: Instance
    header: list[str]
    number: int
    seed: int
    stages: dict[str, tuple[int, float]] = field(default_factory=dict)  # stage -> (rounds, seconds)

    def file_name(self, prefix: str = "") -> str:
        return prefix + self.instance.file_name(self.number)


def instance_seed(seed: int, number: int) -> int:
    """The seed of instance ``number`` of a run with ``seed``."""
    return derive_seed(seed, "instance", number)


def generate_one(plan: GenerationPlan, seed: int, number: int = 1, command: str | None = None) -> Generated:
    """Generate instance ``number`` of a checked plan (raises GenerationFailed)."""
    generator = Generator(plan, instance_seed(seed, number))
    instance = assemble(plan, generator.run())
    header = header_lines(instance, command, seed, tool=TOOL)
    header.insert(3 if command is not None else 2, f"instance: {number}")
    stages = {r.stage: (r.rounds, r.seconds) for r in generator.reports.values() if r.rounds}
    return Generated(instance, header, number, seed, stages)


def iter_generate(config: GeneratorConfig, count: int = 1, seed: int = DEFAULT_SEED, *,
                  first: int = 1, command: str | None = None) -> Iterator[Generated]:
    """Instances ``first .. first+count-1`` of ``config``, one at a time.

    Raises :class:`~asprilo.errors.InputError` for inconsistent options (before solving) and
    :class:`GenerationFailed` when an instance cannot be made (unsatisfiable, time-out).
    """
    plan = make_plan(config)
    if command is None:
        command = config.command_line(RunOptions(count=count, seed=seed))
    for number in range(first, first + count):
        yield generate_one(plan, seed, number, command)


def generate(config: GeneratorConfig, count: int = 1, seed: int = DEFAULT_SEED, *,
             first: int = 1, command: str | None = None) -> list[Generated]:
    """A list of ``count`` instances of ``config`` (see :func:`iter_generate`)."""
    return list(iter_generate(config, count, seed, first=first, command=command))


def populate(template: Instance, config: GeneratorConfig | None = None, seed: int = DEFAULT_SEED,
             **options) -> Generated:
    """Fill a hand-made layout (e.g. the editor's) with the objects ``config``/``options`` ask for.

    Option values are totals: ``robots=5`` means five robots including the template's.
    """
    config = replace(config or GeneratorConfig(), template=template, **options)
    return generate(config, 1, seed)[0]
