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
      - {domain: [a, m], method: anytime}   # the anytime planner for the whole time limit

A run entry with ``sets`` runs on the instances of those sets only.  ``method: anytime``
runs the anytime planner (``asprilo solve --method anytime``) instead of an encoding at the
minimal makespan: its encoding is ``anytime``, and it is reported by time to the first plan
and by the makespan it reached over its lower bound.

Paths are relative to the suite file.
"""

from __future__ import annotations

import glob
import itertools
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from asprilo.domain import Domain
from asprilo.errors import InputError
from asprilo.yamlfile import YamlList, YamlMapping, line_of, load_yaml


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
    method: str = "asp"                  # asp: an encoding at the minimal makespan; anytime

    @property
    def anytime(self) -> bool:
        return self.method == "anytime"

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


SUITE_KEYS = ("name", "time_limit", "memory_limit", "makespan_time_limit", "instances", "runs")
RUN_KEYS = ("domain", "encoding", "assign", "sets", "method")
METHODS = ("asp", "anytime")


def _listed(value: Any) -> list:
    return value if isinstance(value, list) else [value]


class _SuiteFile:
    """Reads one suite file; every problem is an InputError naming the file, the line and the key."""

    def __init__(self, path: Path):
        self.path = path

    def fail(self, where: str, message: str, line: int | None) -> InputError:
        return InputError(f"{where}: {message}", str(self.path), line)

    def suite(self, data: Any) -> Suite:
        if not isinstance(data, YamlMapping):
            raise InputError("a suite is a YAML mapping with 'instances' and 'runs'", str(self.path), line_of(data, 1))
        self.known_keys(data, "", SUITE_KEYS)
        suite = Suite(str(data.get("name", self.path.stem)), self.path)
        self.limits(data, suite)
        suite.sets = self.instance_sets(data)
        suite.runs = self.run_specs(data, {s.name for s in suite.sets})
        return suite

    def known_keys(self, data: YamlMapping, where: str, known: tuple[str, ...]) -> None:
        unknown = [key for key in data if key not in known]
        if unknown:
            raise self.fail(f"{where}{unknown[0]}", f"unknown key (known: {', '.join(known)})",
                            data.line_of(unknown[0]))

    def limits(self, data: YamlMapping, suite: Suite) -> None:
        for key in ("time_limit", "makespan_time_limit"):
            if key in data:
                value = data[key]
                if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
                    raise self.fail(key, "must be a positive number of seconds", data.line_of(key))
                setattr(suite, key, float(value))
        if "memory_limit" in data:
            value = data["memory_limit"]
            if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value <= 0):
                raise self.fail("memory_limit", "must be a positive number of MB (or null for none)",
                                data.line_of("memory_limit"))
            suite.memory_limit = value

    def instance_sets(self, data: YamlMapping) -> list[InstanceSet]:
        sets = data.get("instances")
        if not isinstance(sets, YamlMapping) or not sets:
            raise self.fail("instances", "must map set names to {batch: FILE, select: DIR} or {files: [GLOB, ...]}",
                            data.line_of("instances"))
        return [self.instance_set(str(name), entry, sets.line_of(name)) for name, entry in sets.items()]

    def instance_set(self, name: str, entry: Any, line: int) -> InstanceSet:
        where = f"instances.{name}"
        if not isinstance(entry, YamlMapping) or not ({"batch", "files"} & set(entry)):
            raise self.fail(where, "needs 'batch' (a gen batch file) or 'files' (globs)", line)
        self.known_keys(entry, f"{where}.", ("batch", "select", "files", "first"))
        first = entry.get("first")
        if first is not None and (not isinstance(first, int) or isinstance(first, bool) or first < 1):
            raise self.fail(f"{where}.first", "must be a positive number of files per folder", entry.line_of("first"))
        if "batch" not in entry:
            return InstanceSet(name, files=tuple(str(f) for f in _listed(entry["files"])), first=first)
        batch = (self.path.parent / str(entry["batch"])).resolve()
        if not batch.is_file():
            raise self.fail(f"{where}.batch", f"no such file {batch}", entry.line_of("batch"))
        return InstanceSet(name, batch, str(entry.get("select", "")), first=first)

    def run_specs(self, data: YamlMapping, set_names: set[str]) -> list[RunSpec]:
        runs = data.get("runs")
        if not isinstance(runs, YamlList) or not runs:
            raise self.fail("runs", "must be a list of {domain, encoding, assign} mappings", data.line_of("runs"))
        specs: list[RunSpec] = []
        for number, (entry, line) in enumerate(zip(runs, runs.item_lines, strict=True)):
            specs += self.run_entry(f"runs[{number}]", entry, line, set_names)
        return specs

    def run_entry(self, where: str, entry: Any, line: int, set_names: set[str]) -> list[RunSpec]:
        if not isinstance(entry, YamlMapping) or "domain" not in entry:
            raise self.fail(where, "needs at least 'domain'", line)
        self.known_keys(entry, f"{where}.", RUN_KEYS)
        try:
            domains = [Domain.parse(d) for d in _listed(entry["domain"])]
        except InputError as error:
            raise self.fail(f"{where}.domain", error.message, entry.line_of("domain")) from None
        encodings = [str(e) for e in _listed(entry.get("encoding", "plain"))]
        assigns = _listed(entry.get("assign", False))
        if not all(isinstance(a, bool) for a in assigns):
            raise self.fail(f"{where}.assign", "must be true, false or a list of them", entry.line_of("assign"))
        sets = None
        if "sets" in entry:
            sets = tuple(str(name) for name in _listed(entry["sets"]))
            unknown = [name for name in sets if name not in set_names]
            if unknown:
                raise self.fail(f"{where}.sets", f"no instance set '{unknown[0]}'", entry.line_of("sets"))
        method = str(entry.get("method", "asp"))
        if method not in METHODS:
            raise self.fail(f"{where}.method", f"unknown method '{method}' (choose {' or '.join(METHODS)})",
                            entry.line_of("method"))
        if method == "anytime":
            if "encoding" in entry or True in assigns:
                raise self.fail(where, "method anytime takes no encoding and no assignment", line)
            encodings = ["anytime"]
        return [RunSpec(d, e, a, sets, method) for d, e, a in itertools.product(domains, encodings, assigns)]


def load_suite(path: str | Path) -> Suite:
    """Read and check a suite file; any problem is an :class:`InputError` naming the file and line."""
    path = Path(path)
    return _SuiteFile(path).suite(load_yaml(path))


def existing_files(suite: Suite, instance_set: InstanceSet) -> list[Path]:
    """The files a ``files:`` set names, sorted; a glob that matches nothing is an error."""
    found: list[Path] = []
    for pattern in instance_set.files:
        matches = sorted(glob.glob(str(suite.path.parent / pattern), recursive=True))
        if not matches:
            raise InputError(f"instances.{instance_set.name}: no file matches {pattern!r}", str(suite.path))
        found += [Path(m) for m in matches]
    return found
