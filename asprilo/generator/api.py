"""The generator's Python API: configurations in, instances (with their file headers) out."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace

from asprilo.isolation import run_isolated
from asprilo.limits import current
from asprilo.model import Instance
from asprilo.writer import header_lines

from .assemble import assemble
from .attributes import draw
from .config import GeneratorConfig, RunOptions
from .options import DEFAULT_SEED
from .pipeline import GenerationFailed, Generator
from .plan import GenerationPlan, make_plan
from .releases import release_orders
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


#: seconds the child process of :func:`generate_limited` gets beyond -w to stop by itself
GRACE = 2.0
#: plans whose :func:`estimated_size` is at most this are made in this process (their
#: grounding takes well under a second and a few MB: a child process would cost more)
IN_PROCESS = 20_000


def estimated_size(plan: GenerationPlan) -> int:
    """About how many atoms the generator grounds for ``plan``: the cells (times the gap
    shapes of a partial floor), the objects, the units a (product, shelf) pair may get and
    the lines of the orders."""
    cells = plan.width * plan.height
    if plan.partial_floor:  # a gap of every shape W x H <= gap_size may start at every cell
        widths = range(1, min(plan.gap_size, plan.width - 1) + 1)
        cells *= 1 + sum(min(plan.gap_size // width, plan.height - 1) for width in widths)
    _least, _target, most = plan.pairs
    units = most * max(1, plan.pus_max - plan.pus_min + 1)
    lines = len(plan.orders) * max(1, plan.ol_max) * max(1, plan.product_total)
    return (cells + plan.station_total + plan.robot_total + plan.shelf_total + plan.product_total + units
            + lines)


def generate_one(plan: GenerationPlan, seed: int, number: int = 1, command: str | None = None,
                 on_stage: Callable[[str], None] | None = None) -> Generated:
    """Generate instance ``number`` of a checked plan (raises GenerationFailed)."""
    generator = Generator(plan, instance_seed(seed, number), on_stage)
    instance = assemble(plan, generator.run())
    draw(instance, plan.attributes, instance_seed(seed, number))
    if plan.releases is not None:
        process, over, burst = plan.releases
        release_orders(instance, process, over, burst, instance_seed(seed, number))
    header = header_lines(instance, command, seed, tool=TOOL)
    header.insert(3 if command is not None else 2, f"instance: {number}")
    stages = {r.stage: (r.rounds, r.seconds) for r in generator.reports.values() if r.rounds}
    return Generated(instance, header, number, seed, stages)


def generate_limited(plan: GenerationPlan, seed: int, number: int = 1, command: str | None = None,
                     on_stage: Callable[[str], None] | None = None) -> Generated:
    """:func:`generate_one` in a child process (:func:`asprilo.isolation.run_isolated`) that is
    stopped when -w runs out, also while clingo grounds (which the time limit of the
    generator itself cannot interrupt), and cannot use more memory than the limit ``gen-mb``;
    either ends as :class:`GenerationFailed` naming the stage it was in.  ``on_stage`` is
    told each stage as it starts (for progress)."""
    if estimated_size(plan) <= IN_PROCESS:
        return generate_one(plan, seed, number, command, on_stage)
    limits = current()
    stages: list[str] = []

    def entered(stage: str) -> None:
        stages.append(stage)
        if on_stage is not None:
            on_stage(stage)

    outcome = run_isolated(_generate_in_child, (plan, seed, number, command), time_limit=plan.time_limit + GRACE,
                           memory_mb=limits.gen_mb, on_message=entered)
    stage = stages[-1] if stages else "floor"
    if outcome.status == "done":
        return outcome.value
    if outcome.status == "timeout":
        raise GenerationFailed(stage, timed_out=True)
    if outcome.status == "memout":
        raise GenerationFailed(stage, timed_out=True,
                               reason=f"more than {limits.gen_mb:,} MB of memory were needed, beyond the limit "
                                      f"gen-mb={limits.gen_mb:,} (raise it with --limit gen-mb=N)")
    raise GenerationFailed(stage, timed_out=False, reason=f"the generator's process ended ({outcome.detail})")


def _generate_in_child(plan: GenerationPlan, seed: int, number: int, command: str | None, report) -> Generated:
    return generate_one(plan, seed, number, command, on_stage=report)


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
