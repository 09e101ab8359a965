"""Run a benchmark suite: make the instances, find their minimal makespans, run every
(instance, domain, encoding, assignment) under limits, check every plan, record results.

Output folder::

    DIR/instances/<batch>/...     instances made from the suite's gen batch files
    DIR/makespans.json            minimal makespan per instance and domain (null: unknown)
    DIR/assignments.json          the task assignment each makespan search with assignment
                                  followed: the runs follow the same one (as in the paper)
    DIR/results.jsonl             one line per finished run (see asprilo.bench.results)

Rerunning resumes: instances that exist are kept, known makespans are reused and finished
runs are skipped.
"""

from __future__ import annotations

import contextlib
import json
import os
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

from asprilo.checker import check
from asprilo.domain import Domain
from asprilo.encodings import SolveStatus
from asprilo.errors import InputError
from asprilo.generator import generate_batch
from asprilo.memory import usable_memory_mb
from asprilo.reader import read_instance, read_plan
from asprilo.sources import Source
from asprilo.writer import write_text

from .limits import DONE, LimitedRun, kill_running, resume_running, run_limited
from .results import (
    ERROR,
    FAILED,
    INVALID,
    MEMOUT,
    NO_MAKESPAN,
    OUT_OF_LIMITS,
    SOLVED,
    TIMEOUT,
    append_result,
    load_results,
    run_key,
)
from .suite import RunSpec, Suite, existing_files

MAKESPANS = "makespans.json"
ASSIGNMENTS = "assignments.json"


@dataclass(frozen=True)
class SuiteInstance:
    """An instance file of a suite's set, with the robot count the reports group by."""

    set: str
    path: Path
    name: str      # its path relative to the output folder (or as given), for keys and reports
    robots: int


#: why a run has no horizon when its makespan search is only known to have found none
UNKNOWN_MAKESPAN = "its search timed out"


def new_record(instance: SuiteInstance, spec: RunSpec, horizon: int | None, time_limit: float,
               unknown: str = UNKNOWN_MAKESPAN) -> dict:
    """The record of a run before it runs (``no-makespan`` when there is no horizon to run at,
    ``unknown`` saying why; an anytime run needs none)."""
    record = {"key": run_key(instance.set, instance.name, spec.label, spec.encoding),
              "set": instance.set, "instance": instance.name, "robots": instance.robots,
              "domain": spec.domain.value, "label": spec.label, "encoding": spec.encoding,
              "assign": spec.assign, "time_limit": time_limit, "horizon": horizon}
    if spec.variants:
        record["variants"] = [Path(name).stem for name in spec.variants]
    if spec.anytime:
        record["method"] = "anytime"
    elif horizon is None:
        record.update(status=NO_MAKESPAN, time=time_limit,
                      error=f"the minimal makespan is unknown ({unknown})")
    return record


def run_job(path: Path, spec: RunSpec, horizon: int, assignment: list[str] | None = None) -> dict:
    """A run at ``horizon``; with assignment, along ``assignment`` (the facts its makespan search
    followed) when known, else along one computed in the run."""
    job = {"kind": "run", "instance": str(path), **spec.domain_job(), "encoding": spec.encoding,
           "assign": spec.assign, "horizon": horizon}
    if spec.own is not None:  # the files, constants and options: the child makes the encoding again
        job["own"] = spec.own.job()
    if spec.assign and assignment:
        job["assignment"] = assignment
    return job


def complete(record: dict, path: Path, status: str, wall: float, report: dict, detail: str = "") -> dict:
    """Fill in a run's record from what its child process did, checking the plan it found."""
    limit = record["time_limit"]
    record = {**record, "time": min(wall, limit), "memory_mb": report.get("memory_mb"),
              **{key: report.get("stats", {}).get(key)
                 for key in ("ground_time", "solve_time", "rules", "atoms", "choices", "conflicts")}}
    if status != DONE:
        return {**record, "status": status, "time": limit if status != ERROR else record["time"], "error": detail}
    if report["status"] == SolveStatus.LIMIT.value:
        return {**record, "status": TIMEOUT, "time": limit}
    checked = (SolveStatus.FOUND.value, SolveStatus.INVALID.value)  # a plan: the runner checks it itself
    if report["status"] not in checked or not report.get("plan"):
        return {**record, "status": ERROR,
                "error": report.get("message") or no_plan_at_minimum(record["horizon"])}
    return {**record, "time": report["time"], **plan_verdict(path, record["domain"], report["plan"])}


def no_plan_at_minimum(horizon: int) -> str:
    """Why a run at the problem's minimum has no plan: its encoding allows none that short
    (the sentence of :mod:`asprilo.encodings.solving.minimality`)."""
    return f"the encoding has no plan at horizon {horizon}, the problem's minimum"


def complete_anytime(record: dict, path: Path, run: LimitedRun) -> dict:
    """A run of the anytime planner: ``solved`` when it returned a plan that passes the check,
    its time is the time to the first plan; the makespan it reached, its lower bound and the
    plans it reported on the way are kept."""
    if run.status != DONE or run.report.get("status") != SolveStatus.FOUND.value:
        return complete(record, path, run.status, run.wall, run.report, run.detail)
    history = run.report.get("history") or []
    record = complete(record, path, run.status, run.wall, run.report)
    record.update(time=history[0]["seconds"] if history else record["time"], horizon=run.report["horizon"],
                  lower_bound=run.report.get("lower_bound"), history=history)
    return record


#: how many violations of an invalid plan its record says in words, and keeps as err/3 atoms
SAID, VIOLATIONS = 3, 20


def plan_verdict(path: Path, domain: str, plan_text: str) -> dict:
    """Check a run's plan with the ASP checker: ``solved`` with its metrics, or ``invalid``
    with its first violations in words (``error``) and as ``err/3`` atoms (``violations``)."""
    report = check(read_instance(path), read_plan(Source("plan", plan_text)), Domain.parse(domain))
    if report.valid:
        return {"status": SOLVED, "metrics": report.metrics}
    errors = report.errors
    more = f"; and {len(errors) - SAID} more" if len(errors) > SAID else ""
    return {"status": INVALID, "violations": [error.atom for error in errors[:VIOLATIONS]],
            "error": f"the plan breaks the rules: {'; '.join(error.message for error in errors[:SAID])}{more}"}


def search_failure(run: LimitedRun) -> str:
    """Why a makespan search that is no time-out ended without a makespan, in words."""
    if run.status != DONE:
        return run.detail or f"its process ended ({run.status})"
    return str(run.report.get("message") or f"it ended with status {run.report.get('status')!r}")


def makespan_status(run: LimitedRun) -> str:
    """A makespan search as a run status: solved (minimal makespan found), a time-out, or an error."""
    if run.status != DONE:
        return run.status
    status = run.report.get("status")
    if status == SolveStatus.FOUND.value and run.report.get("minimal"):
        return SOLVED
    return TIMEOUT if status in (SolveStatus.LIMIT.value, SolveStatus.FOUND.value) else ERROR


def read_makespans(path: Path, stream: TextIO) -> dict[str, dict[str, int | None]]:
    """The makespans found before (instance -> domain label -> makespan or None); a file that is
    not a makespans file is reported on ``stream`` and its makespans are found again."""
    if not path.exists():
        return {}
    try:
        known = json.loads(path.read_text(encoding="utf-8"))
        if not isinstance(known, dict) or not all(
                isinstance(spans, dict) and all(v is None or type(v) is int for v in spans.values())
                for spans in known.values()):
            raise ValueError("not a mapping of instances to makespans by domain")
    except (ValueError, UnicodeDecodeError) as error:
        stream.write(f"warning: {path}: not a makespans file ({error}); finding the minimal makespans again\n")
        return {}
    return known


def read_json_object(path: Path) -> dict:
    """The JSON object in ``path``; ``{}`` when the file is missing, unreadable or holds
    something else (a cache: what it lacks is computed again)."""
    try:
        value = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return value if isinstance(value, dict) else {}


def fact_lists(labels: dict) -> dict[str, list[str]]:
    """The entries of ``labels`` (domain label -> assignment facts) that are lists of strings."""
    return {label: facts for label, facts in labels.items()
            if isinstance(facts, list) and all(isinstance(fact, str) for fact in facts)}


def read_assignments(path: Path) -> dict[str, dict[str, list[str]]]:
    """The assignments the makespan searches followed (instance -> label -> facts); an unreadable
    file counts as empty: the makespans with assignment are then searched again."""
    return {name: fact_lists(labels) for name, labels in read_json_object(path).items()
            if isinstance(labels, dict)}


def needs_search(spans: dict, assignments: dict, spec: RunSpec) -> bool:
    """Whether the minimal makespan for ``spec`` must be searched: not known, or found along an
    assignment that is not known (a run must follow the very assignment of its makespan)."""
    if spec.label not in spans:
        return True
    return spec.assign and spans[spec.label] is not None and spec.label not in assignments


def forget_unknown_makespans(folder: Path) -> None:
    """Drop the makespans not found before (null), so that they are searched again."""
    path = folder / MAKESPANS
    known = read_makespans(path, sys.stderr)
    if path.exists():
        kept = {name: {label: span for label, span in spans.items() if span is not None}
                for name, spans in known.items()}
        write_text(path, json.dumps(kept, indent=1, sort_keys=True) + "\n")


class BenchProgress:
    """``[done/total]`` with solved, time-outs and failures, elapsed time and an estimate.

    On a terminal the line is also redrawn every second while runs are under way (a
    heartbeat: a run may take its whole time limit); :meth:`close` ends that."""

    #: seconds between two redraws of the heartbeat
    BEAT = 1.0

    def __init__(self, total: int, what: str, stream: TextIO):
        self.total, self.what, self.stream = total, what, stream
        self.done = self.solved = self.timeouts = self.failures = 0
        self.started = time.perf_counter()
        self.live = stream.isatty()
        self.lock = threading.Lock()
        self.stopped = threading.Event()
        if self.live and total:
            threading.Thread(target=self._beating, daemon=True).start()

    def update(self, status: str) -> None:
        with self.lock:
            self.done += 1
            self.solved += status == SOLVED
            self.timeouts += status in OUT_OF_LIMITS
            self.failures += status in FAILED
            line = self.line(time.perf_counter())
            if self.live:
                self.stream.write("\r" + line + ("\n" if self.done == self.total else ""))
            else:
                self.stream.write(line + "\n")
            self.stream.flush()
        if self.done == self.total:
            self.close()

    def line(self, now: float) -> str:
        elapsed = now - self.started
        left = f"~{_clock(elapsed / self.done * (self.total - self.done))}" if self.done else "?"
        return (f"{self.what} [{self.done}/{self.total}] solved {self.solved}, time-outs {self.timeouts}, "
                f"failures {self.failures} | elapsed {_clock(elapsed)}, left {left}")

    def beat(self) -> None:
        """Redraw the line (on a terminal, while runs are under way)."""
        with self.lock:
            if self.live and not self.stopped.is_set() and self.done < self.total:
                self.stream.write("\r" + self.line(time.perf_counter()))
                self.stream.flush()

    def close(self) -> None:
        """No more heartbeats."""
        self.stopped.set()

    def _beating(self) -> None:
        while not self.stopped.wait(self.BEAT):
            self.beat()


@contextlib.contextmanager
def ticking(stream: TextIO, what: str) -> Iterator[None]:
    """While the block runs, on a terminal, say ``what`` and the seconds so far every second
    (a heartbeat for work that prints nothing for a while, e.g. drawing the plots)."""
    if not stream.isatty():
        yield
        return
    started, stopped = time.perf_counter(), threading.Event()

    def beat() -> None:
        while not stopped.wait(1.0):
            stream.write(f"\r\033[K{what} {time.perf_counter() - started:.0f} s")
            stream.flush()

    ticker = threading.Thread(target=beat, daemon=True)
    ticker.start()
    try:
        yield
    finally:
        stopped.set()
        ticker.join()
        stream.write("\r\033[K")
        stream.flush()


def _clock(seconds: float) -> str:
    seconds = int(seconds)
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


class Runner:
    def __init__(self, suite: Suite, folder: str | Path, jobs: int = 1, time_limit: float | None = None,
                 memory_limit: int | None = None, stream: TextIO | None = None):
        self.suite = suite
        self.folder = Path(folder)
        self.jobs = max(1, jobs)
        self.time_limit = time_limit or suite.time_limit
        # the suite's limit (8192 MB unless it says otherwise) within what this process may have:
        # lowered, and said once, under an outer limit (ulimit -v); --memory-limit above it is refused
        self.memory_limit, self.lowered = usable_memory_mb(memory_limit if memory_limit is not None
                                                           else suite.memory_limit)
        self.stream = stream if stream is not None else sys.stderr  # the one of the moment (not of the import)
        self.assignments: dict[str, dict[str, list[str]]] = {}
        #: (instance, label) -> (status, why) of the makespan searches of this session that found
        #: none: the runs of a search out of limits are ``no-makespan``, those of a search that
        #: failed (it could not start, the instance could not be read, ...) are errors
        self.searches: dict[tuple[str, str], tuple[str, str]] = {}

    # --- instances -----------------------------------------------------------------------

    def instances(self) -> list[SuiteInstance]:
        """Every instance of the suite, generating what is missing."""
        found = []
        for instance_set in self.suite.sets:
            if instance_set.batch is not None:
                target = self.folder / "instances" / instance_set.batch.stem
                self.stream.write(f"instances: {instance_set.batch.name} -> {target}\n")
                if generate_batch(instance_set.batch, target, skip_existing=True, stream=self.stream):
                    raise InputError(f"generating the instances of set '{instance_set.name}' failed",
                                     str(instance_set.batch))
                root = target / instance_set.select
                paths = instance_set.pick(sorted(root.rglob("*.lp")))
                if not paths:
                    raise InputError(f"instances.{instance_set.name}: the batch made no .lp file under "
                                     f"{instance_set.select!r}", str(self.suite.path))
            else:
                paths = instance_set.pick(existing_files(self.suite, instance_set))
            absolute = any(Path(pattern).is_absolute() for pattern in instance_set.files)
            for path in paths:
                found.append(SuiteInstance(instance_set.name, path, self._name(path, absolute),
                                           len(read_instance(path).robots)))
        return found

    # --- minimal makespans ---------------------------------------------------------------


    def _name(self, path: Path, absolute: bool) -> str:
        """An instance's name in keys and reports, the same however the suite's path is spelled
        (a resumed run finds its records): its path relative to the output folder when it lies
        there (generated), else relative to the suite's folder, or resolved where the suite
        names its files by absolute paths (``absolute``)."""
        resolved = path.resolve()
        try:
            return str(resolved.relative_to(self.folder.resolve()))
        except ValueError:
            return str(resolved) if absolute else os.path.relpath(resolved, self.suite.path.resolve().parent)
    def makespans(self, instances: list[SuiteInstance]) -> dict[str, dict[str, int | None]]:
        """Minimal makespan of every instance for every domain (and assignment) the runs use."""
        path = self.folder / MAKESPANS
        known = read_makespans(path, self.stream)
        self.assignments = read_assignments(self.folder / ASSIGNMENTS)
        todo = list(dict.fromkeys(
            (instance, spec.domain, spec.assign, spec.label) for instance in instances
            for spec in self.suite.runs
            if not spec.anytime and spec.runs_on(instance.set)
            and needs_search(known.get(instance.name, {}), self.assignments.get(instance.name, {}), spec)))
        named = {spec.label: spec.domain_job() for spec in self.suite.runs}  # with the variants of a label
        if todo:
            progress = BenchProgress(len(todo), "makespans", self.stream)

            def compute(item):
                instance, _domain, assign, label = item
                search = run_limited({"kind": "makespan", "instance": str(instance.path), **named[label],
                                      "assign": assign}, self.suite.makespan_time_limit, self.memory_limit)
                status = makespan_status(search)
                why = "" if status == SOLVED else search_failure(search)
                return item, search.report.get("horizon") if status == SOLVED else None, status, search.report, why

            try:
                for (instance, _d, _a, label), minimal, status, report, why in self._parallel(compute, todo):
                    if status != SOLVED:
                        self.searches[(instance.name, label)] = (status, why)
                    if status == ERROR:  # not cached (null says "out of limits"): searched again next time
                        progress.update(status)
                        continue
                    known.setdefault(instance.name, {})[label] = minimal
                    write_text(path, json.dumps(known, indent=1, sort_keys=True) + "\n")
                    if report.get("assignment"):
                        self.assignments.setdefault(instance.name, {})[label] = report["assignment"]
                        write_text(self.folder / ASSIGNMENTS,
                                   json.dumps(self.assignments, indent=1, sort_keys=True) + "\n")
                    progress.update(status)
            finally:
                progress.close()
        return known

    # --- runs ----------------------------------------------------------------------------

    def run(self) -> list[dict]:
        """Run everything not yet recorded; return all records of the folder."""
        self.folder.mkdir(parents=True, exist_ok=True)
        resume_running()
        if self.lowered:
            self.stream.write(f"note: {self.lowered}\n")
        instances = self.instances()
        makespans = self.makespans(instances)
        finished = {record["key"] for record in load_results(self.folder)}
        planned = [(instance, spec) for instance in instances for spec in self.suite.runs
                   if spec.runs_on(instance.set)]
        todo = [(instance, spec) for instance, spec in planned
                if run_key(instance.set, instance.name, spec.label, spec.encoding) not in finished]
        skipped = len(planned) - len(todo)
        if skipped:
            self.stream.write(f"resuming: {skipped} runs already recorded\n")
        progress = BenchProgress(len(todo), "runs", self.stream)
        try:
            for record in self._parallel(lambda item: self._run_one(*item, makespans), todo):
                append_result(self.folder, record)
                progress.update(record["status"])
        finally:
            progress.close()
        return load_results(self.folder)

    def _run_one(self, instance: SuiteInstance, spec: RunSpec, makespans: dict) -> dict:
        horizon = makespans.get(instance.name, {}).get(spec.label)
        status, why = self.searches.get((instance.name, spec.label), (TIMEOUT, UNKNOWN_MAKESPAN))
        unknown = {TIMEOUT: UNKNOWN_MAKESPAN, MEMOUT: "its search ran out of memory"}.get(status, why)
        record = new_record(instance, spec, horizon, self.time_limit, unknown)
        if not spec.anytime and horizon is None and status == ERROR:  # it could not run: an error, not a time-out
            return {**record, "status": ERROR, "time": 0.0,
                    "error": f"no minimal makespan to run at: its search failed ({why})"}
        if spec.anytime:
            job = {"kind": "anytime", "instance": str(instance.path), **spec.domain_job()}
            return complete_anytime(record, instance.path, run_limited(job, self.time_limit, self.memory_limit))
        if horizon is None:
            return record
        assignment = self.assignments.get(instance.name, {}).get(spec.label)
        outcome = run_limited(run_job(instance.path, spec, horizon, assignment), self.time_limit, self.memory_limit)
        return complete(record, instance.path, outcome.status, outcome.wall, outcome.report, outcome.detail)

    def _parallel(self, work: Callable, items: Iterable) -> Iterable:
        items = list(items)
        if not items:
            return
        with ThreadPoolExecutor(self.jobs) as pool:
            futures = [pool.submit(work, item) for item in items]
            try:
                for future in as_completed(futures):
                    yield future.result()
            except BaseException:
                for future in futures:
                    future.cancel()
                kill_running()
                raise
