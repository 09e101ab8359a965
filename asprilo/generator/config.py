"""What to generate (:class:`GeneratorConfig`) and how to run it (:class:`RunOptions`).

Both classes are made from the options table (:mod:`.options`): one field per option.  Fields
of GeneratorConfig left ``None`` were not given; :func:`asprilo.generator.plan.make_plan` fills
in the defaults and checks that the options fit together.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import field, fields, make_dataclass
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.model import Instance

from .options import ALWAYS_ON, OPTIONS, SHORTHANDS, Option, convert, format_command, option_for, split_values

_TYPES = {"int": int, "float": float, "str": str, "flag": bool, "paths": tuple[str, ...], "domain": Domain}


class _ConfigMethods:
    """The methods of GeneratorConfig (its fields come from the options table)."""

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


class _RunMethods:
    def values(self) -> dict[str, Any]:
        """Count, seed and first number (what decides the instances; where they are written does not)."""
        first = {"first": self.first} if self.first != 1 else {}
        return {"count": self.count, "seed": self.seed, **first}


def _config_field(option: Option) -> tuple[str, Any, Any]:
    """A GeneratorConfig field: flags default to False, paths to (), values to None (not given)."""
    if option.kind == "flag":
        return option.name, bool, field(default=False)
    if option.kind == "paths":
        return option.name, tuple[str, ...], field(default=())
    return option.name, _TYPES[option.kind] | None, field(default=None)


def _run_field(option: Option) -> tuple[str, Any, Any]:
    default = False if option.kind == "flag" else option.default
    return option.name, _TYPES[option.kind], field(default=default)


def _doc(summary: str, options: list[Option]) -> str:
    lines = [f"    {option.name} ({option.flag}): {option.help_text}" for option in options]
    return summary + "\n\nFields (flags in brackets):\n\n" + "\n".join(lines)


_CONFIG_OPTIONS = [o for o in OPTIONS if not o.run and o.name not in SHORTHANDS]
_RUN_OPTIONS = [o for o in OPTIONS if o.run]

#: The options that decide what an instance looks like; ``template`` is an Instance to populate (API only).
GeneratorConfig = make_dataclass(
    "GeneratorConfig",
    [*map(_config_field, _CONFIG_OPTIONS), ("template", Instance | None, field(default=None, compare=False))],
    bases=(_ConfigMethods,), frozen=True)
GeneratorConfig.__module__ = __name__
GeneratorConfig.__doc__ = _doc("The options that decide what an instance looks like.", _CONFIG_OPTIONS)

#: How many instances, from which seed, and where they go.
RunOptions = make_dataclass("RunOptions", [*map(_run_field, _RUN_OPTIONS)], bases=(_RunMethods,), frozen=True)
RunOptions.__module__ = __name__
RunOptions.__doc__ = _doc("How many instances, from which seed, and where they go.", _RUN_OPTIONS)


def parse_values(options: Mapping[str, Any]) -> dict[str, Any]:
    """Flags or field names -> checked values by field name; ``--prs N`` becomes prs_min and prs_max.

    Later layers of options (YAML presets, the command line) simply update these values.
    """
    values = {}
    for key, value in options.items():
        if key in ALWAYS_ON:
            continue
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


def given_flags(config: GeneratorConfig, *names: str) -> list[str]:
    """The flags of those of ``names`` that ``config`` gives (for messages)."""
    return [option_for(name).flag for name in names if getattr(config, name) not in (None, False)]


def value_of(config: GeneratorConfig, name: str) -> Any:
    """The value ``config`` gives for option ``name``, or the option's default."""
    value = getattr(config, name)
    return option_for(name).default if value is None else value


def check_given(config: GeneratorConfig) -> None:
    """Check every given value against its option's range (values made through the API, too)."""
    for option in _CONFIG_OPTIONS:
        value = getattr(config, option.name)
        if value is not None:
            option.check(value)
