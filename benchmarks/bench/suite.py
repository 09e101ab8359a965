"""Benchmark suites: which instances, which (domain, encoding, assignment) runs, which limits.

A suite is a YAML file::

    name: paper
    time_limit: 1800          # seconds per run (the command line may override)
    memory_limit: 8192        # MB per run
    makespan_time_limit: 600  # seconds to find an instance's minimal makespan (A/B/C)
    instances:                # named sets, in report order
      small: {batch: paper-m.yml, select: 1x2x4}   # a gen batch file and the part of its output to use
      tiny:  {files: ["../examples/encodings-repo/x2_y2*.lp"]}  # or existing files (globs)
      quick: {batch: paper-m.yml, select: 1x2x4, first: 5}  # only the first 5 files of each folder
    runs:                     # every combination of the listed values is run on every instance
      - {domain: m, encoding: [plain, split, clingcon, dl], assign: [false, true]}
      - {domain: [c, b, a], encoding: [plain, clingcon], assign: [false, true], sets: [tiny]}

A run entry with ``sets`` runs on the instances of those sets only.

Paths are relative to the suite file.
"""

from __future__ import annotations

import glob
import itertools
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from asprilo.domain import Domain
from asprilo.errors import InputError


@dataclass(frozen=True)
class InstanceSet:
    """A named group of instances: generated from a gen batch file, or given as files."""

    name: str
    batch: Path | None = None
    select: str = ""
    files: tuple[str, ...] = ()
    first: int | None = None  # use only the first N files (by name) of each folder

    def pick(self, paths: list[Path]) -> list[Path]:
        """``paths`` (in their order) cut to the first ``first`` of each folder."""
        if self.first is None:
            return paths
        taken: dict[Path, int] = {}
        kept = []
        for path in paths:
            taken[path.parent] = taken.get(path.parent, 0) + 1
            if taken[path.parent] <= self.first:
                kept.append(path)
        return kept


@dataclass(frozen=True)
class RunSpec:
    domain: Domain
    encoding: str
    assign: bool
    sets: tuple[str, ...] | None = None  # the instance sets it runs on (None: all)

    def runs_on(self, instance_set: str) -> bool:
        return self.sets is None or instance_set in self.sets

    @property
    def label(self) -> str:
        """``M`` / ``A^M`` style domain name with ``_a`` for task assignment."""
        return self.domain.label + ("_a" if self.assign else "")


@dataclass
class Suite:
    name: str
    path: Path
    time_limit: float = 1800.0
    memory_limit: int | None = 8192
    makespan_time_limit: float = 600.0
    sets: list[InstanceSet] = field(default_factory=list)
    runs: list[RunSpec] = field(default_factory=list)


def _listed(value: Any) -> list:
    return value if isinstance(value, list) else [value]


def load_suite(path: str | Path) -> Suite:
    """Read and check a suite file; any problem is an :class:`InputError` naming the file."""
    path = Path(path)
    if not path.is_file():
        raise InputError("no such file" if not path.exists() else "is not a file", str(path))
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or str(error)
        raise InputError(f"bad YAML: {problem}", str(path), mark.line + 1 if mark else None) from None
    if not isinstance(data, dict):
        raise InputError("a suite is a YAML mapping with 'instances' and 'runs'", str(path))

    def fail(where: str, message: str) -> InputError:
        return InputError(f"{where}: {message}", str(path))

    unknown = set(data) - {"name", "time_limit", "memory_limit", "makespan_time_limit", "instances", "runs"}
    if unknown:
        raise fail(sorted(unknown)[0], "unknown key (known: name, time_limit, memory_limit, "
                                       "makespan_time_limit, instances, runs)")
    suite = Suite(str(data.get("name", path.stem)), path)
    for key in ("time_limit", "makespan_time_limit"):
        if key in data:
            if not isinstance(data[key], (int, float)) or data[key] <= 0:
                raise fail(key, "must be a positive number of seconds")
            setattr(suite, key, float(data[key]))
    if "memory_limit" in data:
        if data["memory_limit"] is not None and (not isinstance(data["memory_limit"], int)
                                                 or data["memory_limit"] <= 0):
            raise fail("memory_limit", "must be a positive number of MB (or null for none)")
        suite.memory_limit = data["memory_limit"]
    sets = data.get("instances")
    if not isinstance(sets, dict) or not sets:
        raise fail("instances", "must map set names to {batch: FILE, select: DIR} or {files: [GLOB, ...]}")
    for name, entry in sets.items():
        if not isinstance(entry, dict) or not ({"batch", "files"} & set(entry)):
            raise fail(f"instances.{name}", "needs 'batch' (a gen batch file) or 'files' (globs)")
        first = entry.get("first")
        if first is not None and (not isinstance(first, int) or isinstance(first, bool) or first < 1):
            raise fail(f"instances.{name}.first", "must be a positive number of files per folder")
        if "batch" in entry:
            batch = (path.parent / str(entry["batch"])).resolve()
            if not batch.is_file():
                raise fail(f"instances.{name}.batch", f"no such file {batch}")
            suite.sets.append(InstanceSet(str(name), batch, str(entry.get("select", "")), first=first))
        else:
            suite.sets.append(InstanceSet(str(name), files=tuple(str(f) for f in _listed(entry["files"])),
                                          first=first))
    runs = data.get("runs")
    if not isinstance(runs, list) or not runs:
        raise fail("runs", "must be a list of {domain, encoding, assign} mappings")
    for number, entry in enumerate(runs):
        where = f"runs[{number}]"
        if not isinstance(entry, dict) or "domain" not in entry:
            raise fail(where, "needs at least 'domain'")
        try:
            domains = [Domain.parse(d) for d in _listed(entry["domain"])]
        except InputError as error:
            raise fail(f"{where}.domain", error.message) from None
        encodings = [str(e) for e in _listed(entry.get("encoding", "plain"))]
        assigns = _listed(entry.get("assign", False))
        if not all(isinstance(a, bool) for a in assigns):
            raise fail(f"{where}.assign", "must be true, false or a list of them")
        sets = None
        if "sets" in entry:
            sets = tuple(str(name) for name in _listed(entry["sets"]))
            unknown_sets = [name for name in sets if name not in {s.name for s in suite.sets}]
            if unknown_sets:
                raise fail(f"{where}.sets", f"no instance set '{unknown_sets[0]}'")
        unknown_keys = set(entry) - {"domain", "encoding", "assign", "sets"}
        if unknown_keys:
            raise fail(f"{where}.{sorted(unknown_keys)[0]}", "unknown key (known: domain, encoding, assign, sets)")
        suite.runs += [RunSpec(d, e, a, sets) for d, e, a in itertools.product(domains, encodings, assigns)]
    return suite


def existing_files(suite: Suite, instance_set: InstanceSet) -> list[Path]:
    """The files a ``files:`` set names, sorted; a glob that matches nothing is an error."""
    found: list[Path] = []
    for pattern in instance_set.files:
        matches = sorted(glob.glob(str(suite.path.parent / pattern), recursive=True))
        if not matches:
            raise InputError(f"instances.{instance_set.name}: no file matches {pattern!r}", str(suite.path))
        found += [Path(m) for m in matches]
    return found
