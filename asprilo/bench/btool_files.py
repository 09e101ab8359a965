"""The files that ``asprilo bench export-btool`` writes for potassco's benchmark-tool (btool 2.x):
the run template, the Slurm template and the result parser.

btool fills a run template with ``str.format``: ``{root}`` (the export folder, relative to
the run's folder), ``{solver}`` (system name-version), ``{sys_cmd}`` and ``{setting_cmd}``
(the cmdline of the system and of the setting), ``{files}`` (the instance), ``{timeout}``,
``{memout}`` and ``{options}`` (the job's), ``{*_post}`` for arguments after the files.  A
Slurm template gets ``{walltime}``, ``{cpt}``, ``{partition}``, ``{dist_options}`` and
``{jobs}`` (the run scripts, one per line).  Literal braces are doubled.
"""

TEMPLATE = """#!/bin/bash
# One asprilo benchmark run under runlim, which holds it to the time and memory limits
# whatever it does; its record (a JSON line) goes to runsolver.solver, runlim's report to
# runsolver.watcher.
cd "$(dirname "$0")"
if [[ ! -e .finished ]]; then
  "{root}/programs/runlim" {options} --space-limit={memout} --real-time-limit={timeout} \\
      --output-file=runsolver.watcher \\
      "{root}/programs/{solver}" {sys_cmd} {setting_cmd} {files} {sys_cmd_post} {setting_cmd_post} \\
      > runsolver.solver
fi
touch .finished
"""

SLURM = """#!/bin/bash
#SBATCH --output=slurm-%j.out
#SBATCH --error=slurm-%j.err
#SBATCH --time={walltime}
#SBATCH --cpus-per-task={cpt}
#SBATCH --partition={partition}
{dist_options}
# A share of an asprilo benchmark for Slurm: its runs one after the other (each run's
# start.sh puts runlim's limits on it).
set -e
runs="{jobs}"
for run in $runs; do
  echo "$(date +%T) $run"
  "$run"
done
"""

PARSER = r'''"""btool result parser for asprilo runs (written by asprilo bench export-btool).

A run's record is the last JSON line that ``python -m asprilo.bench.single`` printed (it
prints the record's fields first and the whole record when the run ends); runlim's report
says whether runlim stopped the run.  A stopped run is a time-out or a mem-out.  The
record's fields become measures, which ``asprilo bench report RESULTS.xml`` reads back.
"""

import json
import os
import re
from xml.sax.saxutils import escape

TEXT = ("key", "set", "instance", "domain", "label", "encoding", "status", "method", "error")
NUMBERS = ("robots", "horizon", "time", "time_limit", "memory_mb", "ground_time", "solve_time", "rules",
           "atoms", "choices", "conflicts", "lower_bound")
OUT_OF_LIMITS = ("timeout", "memout", "no-makespan")


def _read(path, name):
    file = os.path.join(path, name)
    if not os.path.isfile(file):
        return []
    with open(file, encoding="utf-8", errors="replace") as stream:
        return stream.read().splitlines()


def _record(path):
    record = {}
    for line in _read(path, "runsolver.solver"):
        if line.startswith("{"):
            try:
                record = json.loads(line)
            except ValueError:
                pass
    return record


def _runlim_status(path):
    for line in _read(path, "runsolver.watcher"):
        match = re.match(r"\[runlim\] status:\s*(.*)", line)
        if match:
            return match.group(1).strip()
    return ""


def _fallback(runspec, instance):
    """The fields of a run that printed nothing, from the setting, the instance and the system."""
    label, _, encoding = runspec.setting.name.partition("-")
    name = sorted(instance.files)[0]
    robots = re.search(r"_r(\d+)_", name)
    limit = re.search(r"--time-limit (\S+)", runspec.system.cmdline.get("pre", ""))
    return {"set": instance.benchclass.name, "instance": name, "label": label, "encoding": encoding,
            "domain": label.split("_")[0].lower(), "assign": label.endswith("_a"),
            "robots": int(robots.group(1)) if robots else 0,
            "time_limit": float(limit.group(1)) if limit else float(runspec.project.job.timeout),
            "horizon": None, "key": "/".join((instance.benchclass.name, name, label, encoding))}


def parse(path, runspec, instance, run):
    if not _read(path, "runsolver.watcher") and not _read(path, "runsolver.solver"):
        return {}  # not run (e.g. the other job of the runscript)
    record = {**_fallback(runspec, instance), **_record(path)}
    stopped = _runlim_status(path)
    if stopped.startswith("out of memory"):
        record["status"] = "memout"
    elif stopped.startswith("out of time"):
        record["status"] = "timeout"
    elif "status" not in record:
        record["status"] = "error"
        record["error"] = "the run ended without a record" + (f" (runlim: {stopped})" if stopped else "")
    if record["status"] != "solved":
        record["time"] = record["time_limit"]
    measures = {name: ("string", escape(str(record[name]), {'"': "&quot;"})) for name in TEXT if name in record}
    measures.update({name: ("float", float(record[name])) for name in NUMBERS if record.get(name) is not None})
    measures["assign"] = ("float", float(bool(record.get("assign"))))
    measures["timeout"] = ("float", float(record["status"] in OUT_OF_LIMITS))
    measures["failed"] = ("float", float(record["status"] in ("invalid", "error")))
    return measures
'''
