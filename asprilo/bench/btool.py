"""Export a suite for potassco's benchmark-tool (``btool`` 2.x), which runs it on a cluster or
on one machine, and read back what ``btool eval`` makes of such runs.

``asprilo bench export-btool SUITE.yml DIR`` makes the suite's instances (like ``asprilo
bench``) and writes into DIR::

    runscripts/<suite>.xml        one <setting> per (domain, encoding, assignment); a sequential
                                  job (seq) and a Slurm job (dist); one benchmark per instance set
    programs/asprilo-<version>    the system under test: one run of ``asprilo.bench.single``
    programs/runlim               calls the runlim found on the PATH (or replace it by a binary)
    templates/asprilo.sh          the run template: runlim enforces the time and memory limits
    templates/single.dist         the Slurm script of the dist job
    resultparsers/asprilo.py      reads a run's JSON record and runlim's report for btool eval
    benchmarks/<set>/*.lp         the instances; <name>.makespans.json beside an instance caches
                                  its minimal makespans, <name>.assignments.json the assignments
                                  the searches with assignment followed (the runs follow them)
    encodings/<name>/...          the files of the suite's own encodings (and the files they
                                  #include, in the same folders relative to each other)
    encodings/<name>.json         such an encoding: its files (relative to this file), constants
                                  and options; its settings name it (``--own-encoding``)

Minimal makespans are not computed here: each run finds its instance's minimal makespan
(under the suite's makespan_time_limit) unless the cache beside the instance knows it, and
caches it (with its assignment) for the runs after it; makespans and assignments that a
local run of the suite found (``DIR/prepared/{makespans,assignments}.json``) are copied into
the caches.  Each run's record (as in
results.jsonl) is the last JSON line of its output; ``btool eval`` collects the records as
measures and ``asprilo bench report RESULTS.xml`` reads them.
"""

from __future__ import annotations

import json
import os
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path
from xml.sax.saxutils import quoteattr

from asprilo import __version__
from asprilo.encodings.program_scan import scan
from asprilo.errors import InputError
from asprilo.paths import problem, real
from asprilo.writer import write_bytes, write_text

from .btool_files import PARSER, SLURM, TEMPLATE
from .results import run_key
from .runner import ASSIGNMENTS, Runner, SuiteInstance, fact_lists, read_assignments, read_json_object, read_makespans
from .suite import OwnEncoding, RunSpec, Suite

SYSTEM = "asprilo"
#: seconds a run gets beyond its time limit and makespan search (Python start-up, checking the plan)
SLACK = 30
#: the memory limit (MB) of runs when the suite sets none
MEMORY = 20000


def setting_name(spec: RunSpec) -> str:
    return f"{spec.label}-{spec.encoding}"


def makespan_cache(instance: Path) -> Path:
    """The file beside an exported instance that caches its minimal makespans."""
    return instance.with_name(instance.name + ".makespans.json")


def assignment_cache(instance: Path) -> Path:
    """The file beside an exported instance that caches the assignments its makespans follow."""
    return instance.with_name(instance.name + ".assignments.json")


def read_makespan_cache(path: Path) -> dict[str, int | None]:
    """The minimal makespans cached beside an exported instance (domain label -> makespan, None:
    its search ran out of time); an unreadable cache is empty (the makespans are searched again)."""
    return {label: span for label, span in read_json_object(path).items() if span is None or type(span) is int}


def read_assignment_cache(path: Path) -> dict[str, list[str]]:
    """The assignments cached beside an exported instance (domain label -> facts)."""
    return fact_lists(read_json_object(path))


def export(suite: Suite, folder: str | Path, runner: Runner, jobs: int = 1) -> Path:
    """Write the btool set-up for ``suite`` into ``folder``; returns the runscript's path."""
    folder = Path(folder).resolve()
    files_given = sorted({name for spec in suite.runs for name in spec.variants if Path(name).is_absolute()})
    if files_given:
        raise InputError(f"export-btool carries the built-in variants only, by name; a variant file "
                         f"({files_given[0]}) is not copied: make it a built-in one, or run the suite with "
                         "asprilo bench", str(suite.path))
    instances = runner.instances()
    known = read_makespans(runner.folder / "makespans.json", runner.stream)
    runner.assignments = read_assignments(runner.folder / ASSIGNMENTS)
    files = _copy_instances(instances, folder, known, runner)
    for own in suite.encodings.values():
        _copy_encoding(own, folder)
    program = folder / "programs" / f"{SYSTEM}-{__version__}"
    # --root: the export folder, which the settings' --own-encoding is relative to; -P (Python 3.11
    # and later): the run's folder is not put on the path, so nothing there can hide asprilo
    safe_path = " -P" if sys.version_info >= (3, 11) else ""
    write_text(program, f"#!/bin/sh\nexec {sys.executable}{safe_path} -m asprilo.bench.single "
                        f"--root \"$(dirname \"$0\")/..\" \"$@\"\n")
    runlim = folder / "programs" / "runlim"
    write_text(runlim, "#!/bin/sh\n# runlim (Debian: apt-get install runlim); replace this file by a runlim binary "
                       "if there is none on the PATH\nexec runlim \"$@\"\n")
    for path in (program, runlim):
        os.chmod(path, 0o755)
    write_text(folder / "templates" / "asprilo.sh", TEMPLATE)
    write_text(folder / "templates" / "single.dist", SLURM)
    write_text(folder / "resultparsers" / "asprilo.py", PARSER)
    runscript = folder / "runscripts" / f"{suite.name}.xml"
    write_text(runscript, _runscript(suite, runner, files, jobs))
    return runscript


def _included(files: tuple[str, ...]) -> list[Path]:
    """The files of an encoding and those they include by relative paths (each once; an
    absolute ``#include`` is found where it says, on the cluster too; a file that cannot be
    read is left out: the suite's check said so already)."""
    seen: list[Path] = []
    stack = [real(file) for file in reversed(files)]
    while stack:
        file = stack.pop()
        if file in seen or problem(file) is not None:
            continue
        seen.append(file)
        try:
            includes = scan(file).includes
        except InputError:
            continue
        stack += [real(file.parent / include.name) for include in reversed(includes)
                  if not include.system and not Path(include.name).is_absolute()]
    return seen


def own_description(name: str) -> str:
    """The file (relative to the export folder) that describes the suite's own encoding ``name``."""
    return f"encodings/{name}.json"


def _copy_encoding(own: OwnEncoding, folder: Path) -> None:
    """Copy an encoding of the suite's own to encodings/<name>/ (with the files it includes, in
    the same places relative to each other) and describe it in encodings/<name>.json (its
    files relative to that file, its constants and options: JSON, so that no word of them
    passes through a shell or btool's XML)."""
    program = _included((*own.files, *own.stage))
    root = Path(os.path.commonpath([file.parent for file in program]))
    target = folder / "encodings" / own.name
    for file in program:
        write_bytes(target / file.relative_to(root), file.read_bytes(), [file])
    files, stage = ([f"{own.name}/{Path(file).resolve().relative_to(root).as_posix()}" for file in group]
                    for group in (own.files, own.stage))
    write_text(folder / own_description(own.name),
               json.dumps({**own.job(), "files": files, "style": own.style, **({"stage": stage} if stage else {})},
                          indent=1) + "\n")


def _copy_instances(instances: list[SuiteInstance], folder: Path, known: dict,
                    runner: Runner) -> dict[str, list[str]]:
    """Copy the instances to benchmarks/<set>/ with their makespan and assignment caches;
    set -> file names."""
    files: dict[str, list[str]] = {}
    for instance in instances:
        name = Path(instance.name).name
        if name in files.setdefault(instance.set, []):
            raise InputError(f"instances.{instance.set}: two instances are named {name}; btool needs distinct "
                             f"names within a set")
        files[instance.set].append(name)
        target = folder / "benchmarks" / instance.set / name
        write_text(target, instance.path.read_text(encoding="utf-8"), [instance.path])
        cache = makespan_cache(target)
        spans = {**read_makespan_cache(cache),
                 **{label: span for label, span in known.get(instance.name, {}).items() if span is not None}}
        if spans:
            write_text(cache, json.dumps(spans, sort_keys=True) + "\n")
        facts = {**read_assignment_cache(assignment_cache(target)), **runner.assignments.get(instance.name, {})}
        if facts:
            write_text(assignment_cache(target), json.dumps(facts, sort_keys=True) + "\n")
    return files


def _runscript(suite: Suite, runner: Runner, files: dict[str, list[str]], jobs: int) -> str:
    limits = f"--time-limit {runner.time_limit:g} --makespan-time-limit {suite.makespan_time_limit:g}"
    tags = {name: f"set{number}" for number, name in enumerate(files)}  # a setting runs on the sets it is tagged with
    settings = "\n".join(
        f'    <setting name={quoteattr(setting_name(spec))} '
        f'tag="{" ".join(tag for name, tag in tags.items() if spec.runs_on(name))}" '
        f'cmdline={quoteattr(_arguments(spec))} '
        f'dist_template="templates/single.dist"/>' for spec in suite.runs)
    benchmarks = "\n".join(
        f'  <benchmark name={quoteattr(name)}>\n    <files path="benchmarks">\n'
        + "".join(f'      <add file={quoteattr(f"{name}/{file}")}/>\n' for file in names)
        + "    </files>\n  </benchmark>" for name, names in files.items())
    timeout = int(runner.time_limit + suite.makespan_time_limit + SLACK)
    memory = runner.memory_limit or MEMORY
    projects = "\n".join(
        f'  <project name="{suite.name}-{kind}" job="{kind}">\n'
        + "".join(f'    <runtag machine="cluster" benchmark={quoteattr(name)} tag="{tags[name]}"/>\n'
                  for name in files)
        + "  </project>" for kind in ("seq", "dist"))
    return f"""<runscript output="output">
  <!-- made by asprilo {__version__} from {suite.path.name}; see asprilo.bench.btool -->
  <machine name="cluster" cpu="any" memory="{memory}MB"/>
  <config name="asprilo" template="templates/asprilo.sh"/>
  <system name="{SYSTEM}" version="{__version__}" measures="asprilo" config="asprilo" cmdline="{limits}">
{settings}
  </system>
  <seqjob name="seq" timeout="{timeout}s" memout="{memory}" runs="1" parallel="{jobs}"/>
  <distjob name="dist" timeout="{timeout}s" memout="{memory}" runs="1" script_mode="timeout"
           walltime="23h 59m 59s" cpt="1" partition="all"/>
{benchmarks}
{projects}
</runscript>
"""


def _arguments(spec: RunSpec) -> str:
    """A setting's arguments (an encoding of the suite's own: with the file that describes it)."""
    if spec.anytime:
        return f"--domain {spec.domain.value} --method anytime"
    own = f" --own-encoding {own_description(spec.encoding)}" if spec.own is not None else ""
    domain = spec.domain.value
    if spec.variants and spec.base is not None:  # built-in variants by name (export refuses variant files)
        domain = spec.base.value + "".join(f" --variant {name}" for name in spec.variants)
    return f"--domain {domain} --encoding {spec.encoding}{own}" + (" --assign" if spec.assign else "")


# --- reading btool eval's output ---------------------------------------------------------

#: record fields that btool's measures carry as text
_TEXT = ("set", "instance", "domain", "label", "encoding", "status", "method", "error")
#: record fields that btool's measures carry as numbers, and their Python types
_NUMBERS = {"robots": int, "horizon": int, "time": float, "time_limit": float, "memory_mb": float, "assign": bool,
            "ground_time": float, "solve_time": float, "rules": int, "atoms": int, "choices": int,
            "conflicts": int, "lower_bound": float}


def read_results(path: str | Path) -> list[dict]:
    """The run records in the XML that ``btool eval`` printed (measures of our result parser)."""
    path = Path(path)
    try:
        root = ElementTree.parse(path).getroot()
    except ElementTree.ParseError as error:
        raise InputError(f"not btool eval output: {error}", str(path)) from None
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror}", str(path)) from None
    if root.tag != "result":
        raise InputError("not btool eval output (no <result> element)", str(path))
    records: dict[str, dict] = {}
    for run in root.iter("run"):
        measures = {m.get("name"): m.get("val") for m in run.iter("measure")}
        if "key" in measures:  # runs that did not run have no measures
            record = _record(measures)
            records.setdefault(record["key"], record)
    return list(records.values())


def _record(measures: dict[str, str]) -> dict:
    record: dict = {name: measures[name] for name in _TEXT if name in measures}
    for name, kind in _NUMBERS.items():
        if name in measures:
            record[name] = float(measures[name]) if kind is float else kind(float(measures[name]))
    record.setdefault("horizon", None)
    record["key"] = run_key(record["set"], record["instance"], record["label"], record["encoding"])
    return record
