"""Which encoding the command line names: a reference encoding by name, or files of one's
own with ``-c NAME=VALUE`` constants and clingo's options -- the one reading that
``asprilo solve`` and ``asprilo grade`` share; and the first stage of a two-stage encoding
(``--stage FILE...``)."""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from asprilo.domain import Domain
from asprilo.errors import InputError

from .own import check_options, own_encoding
from .registry import Encoding, encoding_names, find_encoding


def choose_encoding(values: Sequence[str], const: Sequence[str], options: Sequence[str], domain: Domain,
                    horizon: int | None = None) -> tuple[Encoding, int | None]:
    """The encoding that ``values`` name (``--encoding`` values: one reference name, or
    files), with the ``const`` texts (``NAME=VALUE``) and clingo ``options``; and the horizon
    asked for (``horizon``, or ``-c horizon=H`` for a single-shot encoding of one's own).
    Bad input: :class:`InputError`."""
    constants = [_constant(text) for text in const]
    options = tuple(options)
    files = [value for value in values if is_encoding_file(value)]
    if not files:
        if len(values) > 1:
            raise InputError(f"name one reference encoding, not {len(values)}: {', '.join(values)}")
        if constants:
            raise InputError("-c sets constants of your own encoding; the reference encodings take none")
        reference = find_encoding(domain, values[0])
        check_options(options)
        return replace(reference, options=reference.options + options), horizon
    if len(files) < len(values):
        names = [value for value in values if value not in files]
        raise InputError(f"--encoding {names[0]}: no such file (a reference encoding is named alone; "
                         f"{', '.join(encoding_names(domain))} for domain {domain.label})")
    encoding = own_encoding(files, constants, options)
    given = dict(encoding.constants)
    if "horizon" not in given:
        return encoding, horizon
    horizon = _horizon_constant(given.pop("horizon"), horizon)
    return replace(encoding, constants=tuple(given.items())), horizon


def stage_encoding(files: Sequence[str | Path], constants: Sequence[tuple[str, str]] = ()) -> Encoding:
    """The first stage of a two-stage encoding (``solve --stage FILE...``): its files, solved
    once with the instance and ``constants`` (the encoding's ``-c`` values); its style
    recognised as an encoding's (a theory too).  Bad input: :class:`InputError` (an incremental
    program, whose parts a single solve would not run, among others)."""
    if not files:
        raise InputError("--stage names the files of the first stage (e.g. --stage assign.lp)")
    stage = own_encoding([Path(file) for file in files], [(name, value) for name, value in constants
                                                           if name != "horizon"])
    if stage.incremental:
        raise InputError("the first stage (--stage) is solved once, with the instance: it has step(t)/check(t) "
                         "parts, which only a search over horizons runs", str(stage.program))
    return replace(stage, name=f"stage {stage.name}", summary=f"first stage, solved once ({stage.summary})")


def is_encoding_file(value: str) -> bool:
    """Whether ``--encoding VALUE`` names a file (a path, a name with a suffix, or anything
    there but a reference encoding's name: a folder or a FIFO is then refused as no file)
    rather than a reference encoding."""
    path = Path(value)
    return (path.suffix != "" or len(path.parts) > 1 or path.is_file()
            or (os.path.lexists(path) and value not in encoding_names()))


def _constant(text: str) -> tuple[str, str]:
    name, equals, value = text.partition("=")
    if not equals or not name.strip() or not value.strip():
        raise InputError(f"-c {text}: expected NAME=VALUE")
    return name.strip(), value.strip()


def _horizon_constant(value: str, horizon: int | None) -> int:
    try:
        number = int(value)
    except ValueError:
        raise InputError(f"-c horizon={value}: the horizon is a number of steps") from None
    if horizon is not None and horizon != number:
        raise InputError(f"-c horizon={value} and --horizon {horizon} disagree")
    return number
