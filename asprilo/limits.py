"""The limits that reading data stays within (README: "Reading data").

Instances, plans and online messages are data: whatever a file holds, reading it checks
these bounds before anything is built, and a file beyond one is refused with a message
that names the limit and how to raise it (``--limit NAME=N`` on every command that reads
files).  Rules in data are refused unless allowed (``--allow-rules``); then they are
grounded in a child process under ``rule-seconds`` and ``rule-mb``.  The same options set
the tools' budgets: YAML files (gen batch files, bench suites), exported pictures and
animations, and what gen makes.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, fields, replace
from typing import Any

from .errors import InputError
from .model import Instance, Plan


@dataclass(frozen=True)
class Limits:
    """Bounds on data (see the module docstring); the names are those of ``--limit``."""

    coordinate: int = 10_000  # largest |X| and |Y| of any cell, and grid xsize / ysize
    facts: int = 1_500_000  # facts of an instance (grid nodes counted) or a plan, cells of a map
    robot_steps: int = 500_000  # a plan's horizon times the robots of its instance; also the largest |T|
    depth: int = 100  # nesting of terms: f(g(h(1))) has depth 3
    string_chars: int = 100_000  # characters of one string (as written, between its quotes)
    fact_chars: int = 1_000_000  # characters of one fact or #const, constants written out
    file_mb: int = 256  # megabytes of one file or message
    line_seconds: float = 60.0  # seconds an online message may take to arrive, from its first byte
    rule_seconds: float = 10.0  # grounding time with --allow-rules
    rule_mb: int = 2048  # grounding memory (megabytes) with --allow-rules
    # the tools' budgets (README, "Reading data"): YAML files, exported pictures and animations, gen
    yaml_kb: int = 1_024  # kilobytes of a YAML file (gen -j batch files, bench suites, grading ladders)
    yaml_nodes: int = 50_000  # values, lists and mappings of a YAML file, each alias counted as what it stands for
    yaml_aliases: int = 1_000  # aliases (*name) in a YAML file
    yaml_depth: int = 50  # nesting of lists and mappings in a YAML file
    pixels: int = 40_000_000  # pixels of an exported picture, or of one frame of an animation
    frames: int = 10_000  # frames of an exported animation
    animation_pixels: int = 800_000_000  # pixels of all frames of an exported animation together
    gen_cells: int = 700_000  # cells of a floor gen makes (-x times -y)
    gen_objects: int = 100_000  # the most gen makes of anything: -p, -r, -s, -P, -u, -o, the per-shelf/order counts
    gen_mb: int = 2_048  # memory (megabytes) gen may use to make one instance
    allow_rules: bool = False  # rules in data (never #include or #script)

    def exceeded(self, name: str, what: str) -> InputError:
        """The error for data beyond limit ``name``: ``what`` says what was found."""
        value = getattr(self, name)
        option = name.replace("_", "-")
        return InputError(f"{what}, beyond the limit {option}={value:,} (raise it with --limit {option}=N)")

    def with_options(self, options: list[str], allow_rules: bool = False) -> Limits:
        """These limits changed by ``--limit NAME=N`` options and ``--allow-rules``."""
        changes: dict[str, Any] = {"allow_rules": self.allow_rules or allow_rules}  # field -> value of its type
        for option in options:
            name, value = parse_option(option)
            changes[name] = value
        return replace(self, **changes)


#: the limits ``--limit`` can change, with their types
NAMES = {field.name: field.type for field in fields(Limits) if field.name != "allow_rules"}
_CEILINGS = {"depth": 500,  # clingo recurses into terms (printing, grounding)
             "yaml_depth": 200}  # PyYAML composes and constructs nested values recursively


def parse_option(text: str) -> tuple[str, int | float]:
    """``robot-steps=5000000`` -> ``("robot_steps", 5000000)``."""
    name, equals, value = text.partition("=")
    key = name.strip().replace("-", "_")
    known = ", ".join(n.replace("_", "-") for n in NAMES)
    if not equals or key not in NAMES:
        raise InputError(f"--limit {text}: expected NAME=N with NAME one of {known}")
    try:
        number = float(value) if NAMES[key] == "float" else int(value.replace("_", ""))
    except ValueError:
        raise InputError(f"--limit {text}: {value!r} is not a number") from None
    if not number > 0 or number > _CEILINGS.get(key, float("inf")):
        ceiling = f" and at most {_CEILINGS[key]}" if key in _CEILINGS else ""
        raise InputError(f"--limit {text}: the limit must be positive{ceiling}")
    return key, number


def require_plan_fits(instance: Instance, plan: Plan, limits: Limits | None = None) -> None:
    """Refuse a plan whose horizon times the instance's robots is beyond ``robot-steps``:
    replaying and checking it takes time and memory in proportion."""
    limits = limits or current()
    horizon, robots = max(plan.horizon, 0), max(len(instance.robots), 1)
    if horizon * robots > limits.robot_steps:
        raise _too_many_steps(limits, horizon, robots)


def _too_many_steps(limits: Limits, horizon: int, robots: int, moved: bool = False) -> InputError:
    plural = "s" * (robots != 1)
    what = f"a plan moving {robots:,} robot{plural} up to step {horizon:,}" if moved else \
        f"a plan of horizon {horizon:,} for {robots:,} robot{plural}"
    return limits.exceeded("robot_steps", what)


class StepCounter:
    """``robot-steps`` counted while a plan is read, action by action (:meth:`add`): an
    action beyond step ``robot-steps`` (either sign), or a horizon so far times the robots
    is refused at once, before the rest is read.  The robots are the instance's where it is
    known (``robots``: the test :func:`require_plan_fits` makes later), else those the plan
    moved so far (never more than its instance has)."""

    __slots__ = ("limits", "robots", "horizon", "seen")

    def __init__(self, limits: Limits, robots: int | None = None):
        self.limits = limits
        self.robots = None if robots is None else max(robots, 1)
        self.horizon = 0
        self.seen: set = set()

    def add(self, kind: object, robot: object, step: int) -> None:
        """An action of ``robot`` (of object type ``kind``) at ``step`` (:class:`InputError`
        beyond the limit)."""
        if step > self.horizon:
            if step > self.limits.robot_steps:
                raise self.limits.exceeded("robot_steps", f"an action at step {step:,}")
            self.horizon = step
            self._check()
        elif step < -self.limits.robot_steps:
            raise self.limits.exceeded("robot_steps", f"an action at step {step:,}")
        if self.robots is None and kind == "robot" and robot not in self.seen:
            self.seen.add(robot)
            self._check()

    def _check(self) -> None:
        robots = self.robots or max(len(self.seen), 1)
        if self.horizon * robots > self.limits.robot_steps:
            raise _too_many_steps(self.limits, self.horizon, robots, moved=self.robots is None)


_current = Limits()


def current() -> Limits:
    """The limits in force (the command line's, or the defaults)."""
    return _current


def set_current(limits: Limits) -> None:
    """Put ``limits`` in force for the whole process (the command line does this once)."""
    global _current
    _current = limits


@contextmanager
def using(limits: Limits) -> Iterator[Limits]:
    """Put ``limits`` in force within a ``with`` block."""
    before = current()
    set_current(limits)
    try:
        yield limits
    finally:
        set_current(before)
