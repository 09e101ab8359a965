"""Exercises of ``asprilo grade``: the instances graded against a model solution, and the
exercise file that bundles them with the rules and the reference encoding.

An exercise file (``exercise.yml``; docs/GRADING.md) names paths relative to itself::

    exercise: visit-two                 # its name (default: the file's folder)
    summary: visit every ordered shelf, in any order
    domain: m                           # the base domain: a|b|c|m|md
    variants: [visit-anytime]           # rule variants: built-in names or variant files
    reference: teacher.lp               # the model solution: a file, a list of files, or a
                                        # reference encoding's name (default: the variant's own)
    instances: instances                # a folder (its .lp files, by name) or a list of files
    time-limit: 10                      # seconds per instance, for each search (default 20)
    probes: [...]                       # illegal plans the student's encoding must refuse
                                        # (as in a ladder.yml: asprilo/encodings/probes.py)

Only ``domain`` and ``instances`` are required.  Every mistake is :class:`InputError` with
the file and the line.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.yamlfile import YamlMapping, load_yaml, shown

from .ladder import Ladder, Rung
from .probes import Probe, read_probes

#: the keys of an exercise file, in the order docs/GRADING.md explains them
KEYS = ("exercise", "summary", "domain", "variants", "reference", "instances", "time-limit", "probes")
_NAME = re.compile(r"[a-z][a-z0-9-]*\Z")


@dataclass(frozen=True)
class Exercise:
    """An exercise as its file says it: ``variants`` and ``reference`` as ``--variant`` and
    ``--reference`` take them (paths made absolute; ``reference`` empty: the domain's model
    solution), ``instances`` the instance files in grading order."""

    path: Path
    name: str
    domain: Domain
    variants: tuple[str, ...]
    reference: tuple[str, ...]
    instances: tuple[Path, ...]
    time_limit: float | None = None
    summary: str = ""
    probes: tuple[Probe, ...] = ()


def read_exercise(path: str | Path) -> Exercise:
    """The exercise of the file ``path`` (bad input: :class:`InputError` ``FILE:LINE``)."""
    path = Path(path)
    data = load_yaml(path)
    where = str(path)
    if not isinstance(data, YamlMapping):
        raise InputError("an exercise file is a mapping (domain: ..., instances: ...; see docs/GRADING.md)", where, 1)
    unknown = [key for key in data if key not in KEYS]
    if unknown:
        raise InputError(f"unknown key {shown(unknown[0])} (the keys: {', '.join(KEYS)})", where,
                         data.line_of(unknown[0]))
    for key in ("domain", "instances"):
        if key not in data:
            raise InputError(f"'{key}:' is missing", where, data.line or 1)
    folder = path.parent
    name = _text(data, "exercise", where) if "exercise" in data else folder.name
    if "exercise" in data and not _NAME.match(name):
        raise InputError(f"the exercise's name {shown(name)} is not a name (lower-case letters, digits and '-', "
                         "a letter first)", where, data.line_of("exercise"))
    try:
        domain = Domain.parse(_text(data, "domain", where))
    except InputError as error:
        raise InputError(error.message, where, data.line_of("domain")) from None
    if domain.variants:
        raise InputError("'domain:' is a built-in domain (a|b|c|m|md); name the rule variants under 'variants:'",
                         where, data.line_of("domain"))
    line = data.line_of("instances")
    try:
        instances = instance_files(_texts(data, "instances", where), folder)
    except InputError as error:
        raise InputError(error.message, where, line) from None
    return Exercise(path, name, domain, tuple(_variant(value, folder) for value in _texts(data, "variants", where)),
                    tuple(_reference(value, folder) for value in _texts(data, "reference", where)), tuple(instances),
                    _seconds(data, where), _text(data, "summary", where) if "summary" in data else "",
                    read_probes(path, data["probes"], data.line_of("probes")) if "probes" in data else ())


def _text(data: YamlMapping, key: str, where: str) -> str:
    value = data[key]
    if not isinstance(value, str) or not value.strip():
        raise InputError(f"'{key}:' must be a text, got {shown(value)}", where, data.line_of(key))
    return value.strip()


def _texts(data: YamlMapping, key: str, where: str) -> list[str]:
    """A text or a list of texts (none when the key is missing)."""
    value = data.get(key, [])
    values = [value] if isinstance(value, str) else value
    if not isinstance(values, list) or not all(isinstance(item, str) and item.strip() for item in values):
        raise InputError(f"'{key}:' must be a text or a list of texts, got {shown(value)}", where, data.line_of(key))
    return [item.strip() for item in values]


def _seconds(data: YamlMapping, where: str) -> float | None:
    value = data.get("time-limit")
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value <= 0:
        raise InputError(f"'time-limit:' must be a positive number of seconds, got {shown(value)}", where,
                         data.line_of("time-limit"))
    return float(value)


def _variant(value: str, folder: Path) -> str:
    """A built-in variant's name as it is; a variant file relative to the exercise file."""
    path = Path(value)
    return value if path.suffix == "" and len(path.parts) == 1 else str(folder / path)


def _reference(value: str, folder: Path) -> str:
    """A reference encoding's name as it is; a file relative to the exercise file."""
    path = folder / value
    return str(path) if Path(value).suffix or len(Path(value).parts) > 1 or path.is_file() else value


def instance_files(values: Sequence[str | Path], folder: Path | None = None) -> list[Path]:
    """The instance files ``values`` name, in order (relative to ``folder`` if given): a file
    as it is, a folder as its ``.lp`` files sorted by name."""
    if not values:
        raise InputError("no instances named (a folder of instance files, or files)")
    files: list[Path] = []
    for value in values:
        path = Path(value) if folder is None else folder / value
        if path.is_dir():
            found = sorted(path.glob("*.lp"))
            if not found:
                raise InputError(f"the folder {path} holds no instance files (*.lp)")
            files.extend(found)
        elif path.is_file():
            files.append(path)
        else:
            raise InputError(f"no such instance file or folder: {path}")
    return files


def instance_ladder(domain: Domain, files: Sequence[Path], manifest: Path, title: str, established: str) -> Ladder:
    """The instances ``files`` as a ladder whose minima are still unknown (a reference
    computes them; ``established`` says which)."""
    return Ladder(domain, manifest, tuple(Rung(file, None, established) for file in files), title=title)
