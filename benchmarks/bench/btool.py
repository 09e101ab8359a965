"""Export a suite for potassco's benchmark-tool (``btool``), which runs it on a cluster, and
read the results of such runs back.

``asprilo bench export-btool SUITE.yml DIR`` makes the instances and their minimal
makespans here (like ``asprilo bench``), then writes into DIR::

    runscripts/<suite>.xml        one <setting> per (domain, encoding, assignment); a sequential
                                  job and a Slurm (dist) job; one benchmark folder per instance set
    programs/asprilo-<version>    the system under test: one run of ``asprilo.bench.single``
    templates/asprilo.sh          the run template (runlim enforces time and memory limits)
    resultparsers/asprilo.py      reads the run's JSON line and runlim's report
    benchmarks/<set>/...          the instances, with makespans.json beside them

Then, on the cluster: put a runlim binary (https://github.com/arminbiere/runlim) at
``DIR/programs/runlim``, ``cd DIR && btool gen runscripts/<suite>.xml`` and start the
generated script; afterwards ``asprilo bench report DIR`` reads the results.  The machine
needs this asprilo installed (the program calls ``python -m asprilo.bench.single`` with the
Python that made the export).
"""

from __future__ import annotations

import gzip
import json
import os
import re
import shutil
import sys
from pathlib import Path
from xml.sax.saxutils import quoteattr

from asprilo import __version__
from asprilo.writer import write_text

from .results import run_key
from .runner import Runner
from .suite import RunSpec, Suite

SYSTEM = "asprilo"


def setting_name(spec: RunSpec) -> str:
    return f"{spec.label}-{spec.encoding}".replace("^", "")


def export(suite: Suite, folder: str | Path, runner: Runner) -> Path:
    """Write the btool set-up for ``suite`` into ``folder``; returns the runscript's path."""
    folder = Path(folder).resolve()
    instances = runner.instances()
    makespans = runner.makespans(instances)
    for instance in instances:
        target = folder / "benchmarks" / instance.set / Path(instance.name).name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(instance.path, target)
    for instance_set in suite.sets:
        spans = {Path(i.name).name: makespans.get(i.name, {}) for i in instances if i.set == instance_set.name}
        write_text(folder / "benchmarks" / instance_set.name / "makespans.json",
                   json.dumps(spans, indent=1, sort_keys=True) + "\n")
    program = folder / "programs" / f"{SYSTEM}-{__version__}"
    write_text(program, f"#!/bin/sh\nexec {sys.executable} -m asprilo.bench.single \"$@\"\n")
    os.chmod(program, 0o755)
    write_text(folder / "templates" / "asprilo.sh", _TEMPLATE)
    write_text(folder / "resultparsers" / "asprilo.py", _PARSER)
    runscript = folder / "runscripts" / f"{suite.name}.xml"
    write_text(runscript, _runscript(suite, runner))
    return runscript


def _runscript(suite: Suite, runner: Runner) -> str:
    settings = "\n".join(
        f'    <setting name={quoteattr(setting_name(spec))} tag="all" '
        f'cmdline={quoteattr(_arguments(spec))}/>' for spec in suite.runs)
    benchmarks = "\n".join(
        f'  <benchmark name={quoteattr(s.name)}>\n    <folder path="benchmarks/{s.name}"/>\n  </benchmark>'
        for s in suite.sets)
    timeout = int(runner.time_limit)
    memory = runner.memory_limit or 20000
    projects = "\n".join(
        f'  <project name="{suite.name}-{kind}-{s.name}" job="{kind}">\n'
        f'    <runtag machine="cluster" benchmark={quoteattr(s.name)} tag="all"/>\n  </project>'
        for kind in ("seq", "dist") for s in suite.sets)
    return f"""<runscript output="output">
  <!-- made by asprilo {__version__} from {suite.path.name}; see asprilo.bench.btool -->
  <machine name="cluster" cpu="any" memory="{memory}MB"/>
  <config name="asprilo" template="templates/asprilo.sh"/>
  <system name="{SYSTEM}" version="{__version__}" measures="asprilo" config="asprilo">
{settings}
  </system>
  <seqjob name="seq" timeout="{timeout}s" memout="{memory}" runs="1" parallel="1"/>
  <distjob name="dist" timeout="{timeout}s" memout="{memory}" runs="1" script_mode="timeout"
           walltime="23h 59m 59s" cpt="1"/>
{benchmarks}
{projects}
</runscript>
"""


def _arguments(spec: RunSpec) -> str:
    return f"--domain {spec.domain.value} --encoding {spec.encoding}" + (" --assign" if spec.assign else "")


_TEMPLATE = """#!/bin/bash
# One asprilo benchmark run under runlim (https://github.com/arminbiere/runlim).
cd "$(dirname $0)"
if [[ ! -e .finished ]]; then
  "{root}/programs/runlim" --space-limit={memout} --real-time-limit={timeout} \\
      --output-file=runsolver.watcher \\
      "{root}/programs/{solver}" --time-limit={timeout} {args} {files} > runsolver.solver
fi
touch .finished
"""

_PARSER = r'''"""btool result parser for asprilo runs: the JSON line of asprilo.bench.single and runlim's report."""

import json
import os
import re


def asprilo(root, runspec, instance):
    timeout = runspec.project.job.timeout
    report, status, seconds = {}, None, None
    solver = os.path.join(root, "runsolver.solver")
    if os.path.isfile(solver):
        for line in open(solver, encoding="utf-8", errors="ignore"):
            if line.startswith("{"):
                report = json.loads(line)
    watcher = os.path.join(root, "runsolver.watcher")
    if os.path.isfile(watcher):
        for line in open(watcher, encoding="utf-8", errors="ignore"):
            match = re.search(r"\[runlim\] status:\s*(.*)", line)
            if match:
                status = match.group(1).strip()
            match = re.search(r"\[runlim\] real:\s*([0-9.]+)", line)
            if match:
                seconds = float(match.group(1))
    outcome = report.get("status", "error")
    timedout = outcome in ("timeout", "no-makespan") or (status or "").startswith("out of time")
    memout = (status or "").startswith("out of memory")
    solved = outcome == "solved" and not timedout and not memout
    time = report.get("time", seconds) if solved else timeout
    return [("time", "float", float(time if time is not None else timeout)),
            ("timeout", "float", int(timedout)), ("memout", "float", int(memout)),
            ("error", "float", int(outcome in ("invalid", "error"))),
            ("status", "string", outcome if not (timedout or memout) else ("memout" if memout else "timeout")),
            ("horizon", "float", float(report.get("horizon") or 0)),
            ("choices", "float", float(report.get("choices") or 0)),
            ("conflicts", "float", float(report.get("conflicts") or 0))]
'''


def read_results(folder: str | Path, time_limit: float | None = None) -> list[dict]:
    """Records (as in results.jsonl) of the runs btool made under ``folder/output``.

    A run that runlim stopped counts as a time-out (mem-out) at the limit.
    """
    folder = Path(folder)
    records = []
    for solver in sorted(folder.glob("output/*/*/results/*/*/*/*/run*/runsolver.solver*")):
        run = solver.parent
        opener = gzip.open if solver.suffix == ".gz" else open
        with opener(solver, "rt", encoding="utf-8", errors="ignore") as stream:
            lines = [line for line in stream if line.startswith("{")]
        status = _runlim_status(run)
        if lines and not status.startswith("out of"):
            records.append(json.loads(lines[-1]))
            continue
        instance, instance_set = run.parent.name, run.parent.parent.name
        setting = run.parent.parent.parent.name.split("-", 2)[-1]
        label, _, encoding = setting.partition("-")
        robots = re.search(r"_r(\d+)_", instance)
        limit = time_limit or _runlim_limit(run)
        records.append({"key": run_key(instance_set, instance, label, encoding), "set": instance_set,
                        "instance": instance, "robots": int(robots.group(1)) if robots else 0,
                        "label": label, "encoding": encoding, "time": limit, "time_limit": limit,
                        "status": "memout" if "memory" in status else "timeout", "horizon": None})
    return records


def _runlim_lines(run: Path) -> list[str]:
    for name in ("runsolver.watcher", "runsolver.watcher.gz"):
        path = run / name
        if path.exists():
            opener = gzip.open if path.suffix == ".gz" else open
            with opener(path, "rt", encoding="utf-8", errors="ignore") as stream:
                return stream.readlines()
    return []


def _runlim_status(run: Path) -> str:
    return next((line.split("status:", 1)[1].strip() for line in _runlim_lines(run) if "status:" in line), "")


def _runlim_limit(run: Path) -> float:
    for line in _runlim_lines(run):
        match = re.search(r"time limit:\s*([0-9.]+)", line)
        if match:
            return float(match.group(1))
    return 0.0
