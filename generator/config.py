"""What to generate (:class:`GeneratorConfig`) and how to run it (:class:`RunOptions`).

Fields left ``None`` were not given; :func:`asprilo.generator.plan.make_plan` fills in the
defaults and checks that the options fit together.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance

from .options import DEFAULT_SEED, SHORTHANDS, convert, format_command, option_for, split_values


@dataclass(frozen=True)
class GeneratorConfig:
    """The options that decide what an instance looks like (flags in brackets)."""

    # floor and layout
    width: int | None = None            # -x
    height: int | None = None           # -y
    nodes: int | None = None            # -n
    gap_size: int | None = None         # --gs
    structured: bool = False            # -H
    zone_x: int | None = None           # -X
    zone_y: int | None = None           # -Y
    border: int | None = None           # -B
    templates: tuple[str, ...] = ()     # -T
    template: Instance | None = field(default=None, compare=False)  # API: a layout to populate
    # objects
    stations: int | None = None         # -p
    robots: int | None = None           # -r
    shelves: int | None = None          # -s
    shelf_coverage: float | None = None  # --sc
    reachable: bool = False             # -R
    # products on shelves
    products: int | None = None         # -P
    units: int | None = None            # -u
    pus_min: int | None = None          # --pusmin (--pus)
    pus_max: int | None = None          # --pusmax
    prs_min: int | None = None          # --prsmin (--prs)
    prs_max: int | None = None          # --prsmax
    spr_min: int | None = None          # --sprmin (--spr)
    spr_max: int | None = None          # --sprmax
    # orders
    orders: int | None = None           # -o
    ol_min: int | None = None           # --olmin (--ol)
    ol_max: int | None = None           # --olmax
    order_all: bool = False             # --oap
    domain: Domain | None = None        # --domain
    # solving
    threads: int | None = None          # -t
    time_limit: float | None = None     # -w
    incremental: bool = False           # -I
    split_threshold: int | None = None  # --split-threshold
    one_shot: bool = False              # --one-shot

    @classmethod
    def from_options(cls, options: Mapping[str, Any]) -> GeneratorConfig:
        """A config from ``{"-x": 11, "--prs": 1, "structured": True, ...}`` (flags or field names).

        Run options (``-N``, ``--seed``, ``-d`` ...) are rejected here; see :class:`RunOptions`.
        """
        config, run = split_values(parse_values(options))
        if run:
            names = ", ".join(option_for(name).flag for name in run)
            raise InputError(f"{names}: not a generator setting (a run option)")
        return cls(**config)

    def values(self) -> dict[str, Any]:
        """The options that were given: field name -> value (the template object aside)."""
        given = {}
        for item in fields(self):
            value = getattr(self, item.name)
            if item.name == "template" or value is None or value is False or value == ():
                continue
            given[item.name] = value
        for name in SHORTHANDS:  # write --prs 1 rather than --prsmin 1 --prsmax 1
            low, high = given.get(f"{name}_min"), given.get(f"{name}_max")
            if low is not None and low == high:
                del given[f"{name}_min"], given[f"{name}_max"]
                given[name] = low
        return given

    def command_line(self, run: RunOptions | None = None) -> str:
        """A ``gen`` command line that makes the same instances."""
        values = self.values()
        if run is not None:
            values.update(run.values())
        return format_command(values)


@dataclass(frozen=True)
class RunOptions:
    """How many instances, from which seed, and where they go."""

    count: int = 1                      # -N
    seed: int = DEFAULT_SEED            # --seed
    directory: str = "generatedInstances"  # -d
    console: bool = False               # -C
    prefix: str = ""                    # -f
    instance_dir: bool = False          # --instance-dir
    skip_existing: bool = False         # --se

    def values(self) -> dict[str, Any]:
        """Count and seed (what decides the instances; where they are written does not)."""
        return {"count": self.count, "seed": self.seed}


def parse_values(options: Mapping[str, Any]) -> dict[str, Any]:
    """Flags or field names -> checked values by field name; ``--prs N`` becomes prs_min and prs_max.

    Later layers of options (YAML presets, the command line) simply update these values.
    """
    values = {}
    for key, value in options.items():
        option = option_for(str(key))
        values[option.name] = convert(option, value)
    for name in SHORTHANDS:
        if name in values:
            both = values.pop(name)
            given = [option_for(f"{name}_{end}").flag for end in ("min", "max") if f"{name}_{end}" in values]
            if given:
                raise InputError(f"give either {option_for(name).flag} or {'/'.join(given)}, not both")
            values[f"{name}_min"] = values[f"{name}_max"] = both
    return values
