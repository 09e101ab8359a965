"""Benchmark suites: which instances, which (domain, encoding, assignment) runs, which limits.

A suite is a YAML file::

    name: paper
    time_limit: 1800          # seconds per run (the command line may override)
    memory_limit: 8192        # MB per run
    makespan_time_limit: 600  # seconds to find an instance's minimal makespan (A/B/C)
    encodings:                # encodings of one's own, by name (optional)
      mine: {files: [enc/mine.lp, enc/goal.lp], constants: {lanes: 2}, options: ["--configuration=crafty"]}
      staged: {files: [enc/plan.lp], stage: [enc/assign.lp]}  # a first stage (solve --stage)
    instances:                # named sets, in report order
      small: {batch: paper-m.yml, select: 1x2x4}   # a gen batch file and the part of its output to use
      tiny:  {files: ["../examples/encodings-repo/x2_y2*.lp"]}  # or existing files (patterns)
      quick: {batch: paper-m.yml, select: 1x2x4, first: 5}  # only the first 5 files of each folder
    runs:                     # every combination of the listed values is run on every instance
      - {domain: m, encoding: [plain, split, clingcon, dl], assign: [false, true]}
      - {domain: m, encoding: mine}       # the suite's own: no assign (it would not follow one)
      - {domain: [c, b], encoding: [plain, mine], sets: [tiny]}
      - {domain: [a, m], method: anytime}   # the anytime planner for the whole time limit
      - {domain: m, variant: diagonal}      # under a rule variant: its model solution, checked by its rules

A run entry with ``sets`` runs on the instances of those sets only.  ``assign: true`` (the
task assignment computed first, the plan along it) goes with the reference encodings, which
are written to follow it: an encoding of the suite's own is refused there (nothing makes it
follow the assignment, so its row would mean nothing).  ``variant: NAME`` (a
built-in variant, or a variant file relative to the suite; a list composes them in order, as
``--variant`` repeated does) runs and checks under the varied domain (``M+diagonal``): its
minimal makespans are searched with the variant's model solution (the default encoding of
such a run), and the report names the runs after the varied domain.  ``method: anytime``
runs the anytime planner (``asprilo solve --method anytime``) instead of an encoding at the
minimal makespan: its encoding is ``anytime``, and it is reported by time to the first plan
and by the makespan it reached over its lower bound.

An encoding of ``encodings`` runs as ``asprilo solve INSTANCE --encoding FILE... -c NAME=VALUE
OPTION...`` would (its style recognised the same way: :func:`asprilo.encodings.own.own_encoding`),
at each instance's minimal makespan like the reference encodings (a program without a horizon
is solved as it is).  A run names an encoding by its name: a reference encoding of its
domain, or one of ``encodings``.  Everything is checked when the suite is read, before the
first run: an unknown name, a missing file, a file clingo cannot parse, a program for
clingcon 3, an option clingo refuses, a constant that is no term.  An encoding's ``stage``
(files) is a first stage, as ``solve --encoding FILE... --stage FILE...`` runs it: its run is
at the instance's minimal makespan too, which a plan along the stage's answer may not reach
(the record then says that there was no plan at that makespan).

Paths are relative to the suite file.  A pattern of ``files`` walks folders (``**``, or a
wildcard in a folder's name) only below the suite's folder, and ``**`` follows no symbolic
link; elsewhere only its file name may hold wildcards (``../examples/paper-m/1x2x4/*.lp``
lists one folder), so that no suite walks the file system (``/**/*.lp`` is refused).  A
pattern matches regular files only, hidden ones (``.name``) only where it says so, as
:mod:`glob` does.  Time limits are finite numbers of seconds (at most a year).
"""

from __future__ import annotations

import itertools
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import clingo

from asprilo.domain import Domain
from asprilo.encodings import Encoding, encoding_names
from asprilo.encodings.own import own_encoding
from asprilo.encodings.registry import default_encoding
from asprilo.errors import InputError
from asprilo.paths import real
from asprilo.yamlfile import YamlList, YamlMapping, line_of, load_yaml, printable, shown

from .files import existing_files, pattern_start

__all__ = ["InstanceSet", "OwnEncoding", "RunSpec", "Suite", "existing_files", "load_suite", "pattern_start"]


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
class OwnEncoding:
    """An encoding of the suite's own (``encodings:``): its files (absolute, in loading order),
    ``-c`` constants and clingo options, and its style in words.  These (not the
    :class:`~asprilo.encodings.Encoding`) travel to the run's child process, which makes the
    encoding again (:meth:`encoding`)."""

    name: str
    files: tuple[str, ...]
    constants: tuple[tuple[str, str], ...] = ()
    options: tuple[str, ...] = ()
    style: str = ""
    stage: tuple[str, ...] = ()  # the files of a first stage (solve --stage), absolute

    def job(self) -> dict:
        """What a run's job carries (JSON)."""
        return {"files": list(self.files), "constants": [list(pair) for pair in self.constants],
                "options": list(self.options), **({"stage": list(self.stage)} if self.stage else {})}

    @classmethod
    def from_job(cls, name: str, job: dict) -> OwnEncoding:
        return cls(name, tuple(job["files"]), tuple((str(n), str(v)) for n, v in job.get("constants", ())),
                   tuple(job.get("options", ())), stage=tuple(job.get("stage", ())))

    def encoding(self) -> Encoding:
        """The encoding, its style recognised (bad input: :class:`InputError`)."""
        return own_encoding(self.files, self.constants, self.options)

    def stage_encoding(self) -> Encoding | None:
        """The first stage (``None``: none), with the encoding's constants."""
        from asprilo.encodings.choice import stage_encoding
        return stage_encoding(self.stage, self.constants) if self.stage else None

    def describe(self, folder: Path | None = None) -> str:
        """E.g. ``mine: /x/enc/mine.lp, /x/enc/goal.lp; single-shot with a horizon constant; -c lanes=2``;
        with ``folder`` (the suite's) the files are named relative to it (``enc/mine.lp``)."""
        def named(files: tuple[str, ...]) -> str:
            return ", ".join(file if folder is None else os.path.relpath(file, folder) for file in files)

        parts = [named(self.files), self.style, " ".join(f"-c {n}={v}" for n, v in self.constants),
                 " ".join(self.options), f"first stage {named(self.stage)}" if self.stage else ""]
        return f"{self.name}: " + "; ".join(part for part in parts if part)


@dataclass(frozen=True)
class RunSpec:
    domain: Domain
    encoding: str
    assign: bool
    sets: tuple[str, ...] | None = None  # the instance sets it runs on (None: all)
    method: str = "asp"                  # asp: an encoding at the minimal makespan; anytime
    own: OwnEncoding | None = None       # the suite's own encoding of that name (None: a reference one)
    variants: tuple[str, ...] = ()       # the rule variants (names, or absolute paths of files) of ``domain``
    base: Domain | None = None           # the domain they change (None: no variants)

    def domain_job(self) -> dict:
        """How a job names the run's domain: its name, and with variants the base and the variants
        (a fresh process makes the varied domain again from them)."""
        if not self.variants or self.base is None:
            return {"domain": self.domain.value}
        return {"domain": self.domain.value, "base": self.base.value, "variants": list(self.variants)}

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
    encodings: dict[str, OwnEncoding] = field(default_factory=dict)


SUITE_KEYS = ("name", "time_limit", "memory_limit", "makespan_time_limit", "encodings", "instances", "runs")
RUN_KEYS = ("domain", "encoding", "assign", "sets", "method", "variant")
ENCODING_KEYS = ("files", "constants", "options", "stage")
METHODS = ("asp", "anytime")
#: an encoding's name: it names runs in results, tables, file names and btool settings
ENCODING_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.+-]*")
#: a clingo constant's name
CONSTANT_NAME = re.compile(r"_*[a-z][A-Za-z0-9_']*")
#: the most seconds a time limit may be (a year; a waiting thread takes no more than about 292 years)
MOST_SECONDS = 365 * 24 * 3600


def _listed(value: Any) -> list:
    return value if isinstance(value, list) else [value]


class _SuiteFile:
    """Reads one suite file; every problem is an InputError naming the file, the line and the key."""

    def __init__(self, path: Path):
        self.path = path

    def fail(self, where: str, message: str, line: int | None) -> InputError:
        return InputError(printable(f"{where}: {message}"), str(self.path), line)  # keys may hold any character

    def suite(self, data: Any) -> Suite:
        if not isinstance(data, YamlMapping):
            raise InputError("a suite is a YAML mapping with 'instances' and 'runs'", str(self.path), line_of(data, 1))
        self.known_keys(data, "", SUITE_KEYS)
        suite = Suite(str(data.get("name", self.path.stem)), self.path)
        self.limits(data, suite)
        suite.encodings = self.own_encodings(data)
        suite.sets = self.instance_sets(data)
        suite.runs = self.run_specs(data, {s.name for s in suite.sets}, suite.encodings)
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
                if not math.isfinite(value) or value > MOST_SECONDS:
                    raise self.fail(key, f"must be a finite number of seconds, at most {MOST_SECONDS:,} (a year), "
                                         f"got {shown(value)}", data.line_of(key))
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
            patterns = tuple(str(f) for f in _listed(entry["files"]))
            for pattern in patterns:
                try:
                    pattern_start(self.path.parent, pattern)
                except InputError as error:
                    raise self.fail(f"{where}.files", error.message, entry.line_of("files")) from None
            return InstanceSet(name, files=patterns, first=first)
        batch = (self.path.parent / str(entry["batch"])).resolve()
        if not batch.is_file():
            raise self.fail(f"{where}.batch", f"no such file {batch}", entry.line_of("batch"))
        return InstanceSet(name, batch, str(entry.get("select", "")), first=first)

    # --- encodings of one's own --------------------------------------------------------

    def own_encodings(self, data: YamlMapping) -> dict[str, OwnEncoding]:
        if "encodings" not in data:
            return {}
        entries = data["encodings"]
        if not isinstance(entries, YamlMapping):
            raise self.fail("encodings", "must map names to {files: [FILE, ...], constants: {NAME: VALUE}, "
                                         "options: [OPTION, ...]}", data.line_of("encodings"))
        return {str(name): self.own_encoding(str(name), entry, entries.line_of(name))
                for name, entry in entries.items()}

    def own_encoding(self, name: str, entry: Any, line: int) -> OwnEncoding:
        where = f"encodings.{name}"
        if not ENCODING_NAME.fullmatch(name):
            raise self.fail(where, "an encoding's name is letters, digits and _ . + - (it names its runs in "
                                   "results, tables and files)", line)
        if name in encoding_names() or name == "anytime":
            raise self.fail(where, f"'{name}' is the name of a reference encoding; give yours another name", line)
        if not isinstance(entry, YamlMapping) or "files" not in entry:
            raise self.fail(where, "needs 'files': the encoding's files, relative to the suite", line)
        self.known_keys(entry, f"{where}.", ENCODING_KEYS)
        files = self.encoding_files(where, entry)
        constants = self.constants(where, entry)
        options = self.options(where, entry)
        try:
            encoding = own_encoding([path for path, _line in files], constants, options)
        except InputError as error:
            raise self.refused(where, error, entry, files) from None
        stage = self.encoding_files(where, entry, "stage") if "stage" in entry else []
        own = OwnEncoding(name, tuple(str(path.absolute()) for path, _line in files), constants, options,
                          encoding.summary, tuple(str(path.absolute()) for path, _line in stage))
        try:
            own.stage_encoding()
        except InputError as error:
            raise self.refused(where, error, entry, stage, "stage") from None
        return own

    def encoding_files(self, where: str, entry: YamlMapping, key: str = "files") -> list[tuple[Path, int]]:
        """The files (relative to the suite) of ``key``, each with its line."""
        value = entry[key]
        items = value if isinstance(value, YamlList) else [value]
        lines = value.item_lines if isinstance(value, YamlList) else [entry.line_of(key)]
        if not items or not all(isinstance(item, str) and item for item in items):
            raise self.fail(f"{where}.{key}", "must be a file or a list of files", entry.line_of(key))
        return [(self.path.parent / item, line) for item, line in zip(items, lines, strict=True)]

    def constants(self, where: str, entry: YamlMapping) -> tuple[tuple[str, str], ...]:
        if "constants" not in entry:
            return ()
        value = entry["constants"]
        if not isinstance(value, YamlMapping):
            raise self.fail(f"{where}.constants", "must map names to values, e.g. {lanes: 2}",
                            entry.line_of("constants"))
        constants = []
        for name, given in value.items():
            place, line = f"{where}.constants.{name}", value.line_of(name)
            if not isinstance(name, str) or not CONSTANT_NAME.fullmatch(name):
                raise self.fail(place, "a constant's name starts with a lower-case letter", line)
            if name == "horizon":
                raise self.fail(place, "the runs are at each instance's minimal makespan: a suite sets no horizon",
                                line)
            if isinstance(given, bool):
                given = str(given).lower()
            if not isinstance(given, (int, str)):
                raise self.fail(place, "must be a number or a term", line)
            try:
                clingo.parse_term(str(given))
            except RuntimeError:
                raise self.fail(place, f"clingo cannot read {str(given)!r} as a term", line) from None
            constants.append((name, str(given)))
        return tuple(constants)

    def options(self, where: str, entry: YamlMapping) -> tuple[str, ...]:
        if "options" not in entry:
            return ()
        value = entry["options"]
        items = value if isinstance(value, list) else [value]
        if not all(isinstance(item, str) and item for item in items):
            raise self.fail(f"{where}.options", "must be clingo options, e.g. [\"--configuration=crafty\"]",
                            entry.line_of("options"))
        return tuple(items)

    def refused(self, where: str, error: InputError, entry: YamlMapping,
                files: list[tuple[Path, int]], key: str = "files") -> InputError:
        """What :func:`own_encoding` refused, at the line of the entry at fault: the file it
        names (its item of ``files``, or of ``stage``), the options (no file named), else ``files``."""
        if error.file is not None:
            for number, (path, line) in enumerate(files):
                if real(error.file) == real(path):
                    return self.fail(f"{where}.{key}[{number}]", str(error), line)
            return self.fail(f"{where}.{key}", str(error), entry.line_of(key))
        if key == "stage":
            return self.fail(f"{where}.stage", str(error), entry.line_of("stage"))
        if "options" in entry:
            return self.fail(f"{where}.options", str(error), entry.line_of("options"))
        return self.fail(where, str(error), entry.line)

    # --- runs ----------------------------------------------------------------------------

    def run_specs(self, data: YamlMapping, set_names: set[str], own: dict[str, OwnEncoding]) -> list[RunSpec]:
        runs = data.get("runs")
        if not isinstance(runs, YamlList) or not runs:
            raise self.fail("runs", "must be a list of {domain, encoding, assign} mappings", data.line_of("runs"))
        specs: list[RunSpec] = []
        for number, (entry, line) in enumerate(zip(runs, runs.item_lines, strict=True)):
            specs += self.run_entry(f"runs[{number}]", entry, line, set_names, own)
        return specs

    def run_entry(self, where: str, entry: Any, line: int, set_names: set[str],
                  own: dict[str, OwnEncoding]) -> list[RunSpec]:
        if not isinstance(entry, YamlMapping) or "domain" not in entry:
            raise self.fail(where, "needs at least 'domain'", line)
        self.known_keys(entry, f"{where}.", RUN_KEYS)
        try:
            bases = [Domain.parse(d) for d in _listed(entry["domain"])]
        except InputError as error:
            raise self.fail(f"{where}.domain", error.message, entry.line_of("domain")) from None
        variants = self.variants(where, entry)
        domains = [self.varied(where, entry, base, variants) for base in bases]
        assigns = _listed(entry.get("assign", False))
        if not all(isinstance(a, bool) for a in assigns):
            raise self.fail(f"{where}.assign", "must be true, false or a list of them", entry.line_of("assign"))
        sets = self.run_sets(where, entry, set_names)
        method = str(entry.get("method", "asp"))
        if method not in METHODS:
            raise self.fail(f"{where}.method", f"unknown method '{method}' (choose {' or '.join(METHODS)})",
                            entry.line_of("method"))
        chosen = dict(zip(domains, bases, strict=True)) if variants else {}
        if method == "anytime":
            if "encoding" in entry or True in assigns:
                raise self.fail(where, "method anytime takes no encoding and no assignment", line)
            if variants:
                raise self.fail(f"{where}.variant", "the anytime planner knows only SPEC.md's rules, not a "
                                                    "variant's: run the variant's model solution (method asp)",
                                entry.line_of("variant"))
            return [RunSpec(d, "anytime", False, sets, method) for d in domains]
        if "encoding" in entry:
            named = [str(e) for e in _listed(entry["encoding"])]
            self.known_encodings(f"{where}.encoding", entry, domains, named, own)
            pairs = [(d, e) for d in domains for e in named]
        else:  # each domain's default: plain, or a variant's model solution
            pairs = [(d, default_encoding(d).name) for d in domains]
        mine = sorted({e for _d, e in pairs if e in own})
        if True in assigns and mine:
            raise self.fail(f"{where}.assign", f"assign: true hands a task assignment to the reference encodings, "
                                               f"which are written to follow it; '{mine[0]}' is the suite's own "
                                               f"encoding, which nothing makes follow it, so its row would mean "
                                               f"nothing: run '{mine[0]}' in an entry without assign",
                            entry.line_of("assign"))
        return [RunSpec(d, e, a, sets, method, own.get(e), variants, chosen.get(d))
                for (d, e), a in itertools.product(pairs, assigns)]

    def run_sets(self, where: str, entry: YamlMapping, set_names: set[str]) -> tuple[str, ...] | None:
        """The instance sets a run entry names (``None``: all)."""
        if "sets" not in entry:
            return None
        sets = tuple(str(name) for name in _listed(entry["sets"]))
        unknown = [name for name in sets if name not in set_names]
        if unknown:
            raise self.fail(f"{where}.sets", f"no instance set '{unknown[0]}'", entry.line_of("sets"))
        return sets

    def variants(self, where: str, entry: YamlMapping) -> tuple[str, ...]:
        """The variants of a run (built-in names, or files relative to the suite made absolute),
        each loaded once here: their declared attributes are data from now on."""
        if "variant" not in entry:
            return ()
        from asprilo.domain.variants import load_variant

        names = []
        for name in _listed(entry["variant"]):
            if not isinstance(name, str) or not name:
                raise self.fail(f"{where}.variant", "names a built-in variant or a variant file (NAME.yml), or a "
                                                    "list of them", entry.line_of("variant"))
            given = self.path.parent / name if Path(name).suffix or len(Path(name).parts) > 1 else None
            value = str(given.resolve()) if given is not None else name
            try:
                load_variant(value)
            except InputError as error:
                raise self.fail(f"{where}.variant", error.message, entry.line_of("variant")) from None
            names.append(value)
        return tuple(names)

    def varied(self, where: str, entry: YamlMapping, base: Domain, variants: tuple[str, ...]) -> Domain:
        """``base`` changed by ``variants`` (registered); a variant that does not fit it, or a
        varied domain whose minimal makespans no model solution can search, is refused."""
        if not variants:
            return base
        from asprilo.domain.variants import with_variants

        try:
            domain = with_variants(base, variants)
            default_encoding(domain)  # the makespans are searched with it
        except InputError as error:
            raise self.fail(f"{where}.variant", error.message, entry.line_of("variant")) from None
        return domain

    def known_encodings(self, where: str, entry: YamlMapping, domains: list[Domain], encodings: list[str],
                        own: dict[str, OwnEncoding]) -> None:
        """Every name a reference encoding of every domain of the entry, or one of the suite's."""
        value = entry["encoding"]
        lines = value.item_lines if isinstance(value, YamlList) else [entry.line_of("encoding")] * len(encodings)
        for name, line in zip(encodings, lines, strict=True):
            if name in own:
                continue
            for domain in domains:
                references = encoding_names(domain)
                if name not in references:
                    yours = f"the suite's encodings: {', '.join(own)}" if own else "no encodings of the suite's own"
                    raise self.fail(where, f"no encoding '{name}' for domain {domain.label} (reference encodings: "
                                           f"{', '.join(references)}; {yours})", line)


def load_suite(path: str | Path) -> Suite:
    """Read and check a suite file; any problem is an :class:`InputError` naming the file and line."""
    path = Path(path)
    return _SuiteFile(path).suite(load_yaml(path))
