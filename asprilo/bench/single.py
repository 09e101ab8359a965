"""One benchmark run for potassco's benchmark-tool, which enforces the limits itself (runlim):

    python -m asprilo.bench.single --domain m --encoding plain [--assign] --time-limit S
                                   [--makespan-time-limit S] INSTANCE
    python -m asprilo.bench.single --domain m --encoding mine --own-encoding encodings/mine.json
                                   [--root DIR] ... INSTANCE
    python -m asprilo.bench.single --domain a --method anytime --time-limit S INSTANCE
    python -m asprilo.bench.single --domain m --variant diagonal --encoding diagonal --time-limit S INSTANCE

An encoding of the suite's own is described by a JSON file that the export wrote (its
files, relative to that file, its constants and options; ``--own-encoding`` is relative to
``--root``: the export folder, which ``programs/asprilo-<version>`` passes) and made from it
as in a local run.

The horizon is the instance's minimal makespan, from ``INSTANCE.makespans.json`` beside it,
or else searched here (at most ``--makespan-time-limit`` seconds, not counted in the run's
time) and cached there for the runs after this one; a run with assignment follows the
assignment of that search, cached in ``INSTANCE.assignments.json``.  Prints the run's record (as in
results.jsonl) as a JSON line before the run and again, complete, after it; a run that runlim
stops leaves the first.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from asprilo.domain import Domain
from asprilo.reader import read_instance
from asprilo.writer import write_text

from .btool import assignment_cache, makespan_cache, read_assignment_cache, read_makespan_cache
from .limits import DONE, LimitedRun, failure
from .results import SOLVED
from .runner import SuiteInstance, complete, complete_anytime, makespan_status, needs_search, new_record, run_job
from .suite import OwnEncoding, RunSpec
from .worker import run


def minimal_makespan(instance: Path, spec: RunSpec, time_limit: float) -> tuple[int | None, list[str] | None]:
    """The cached minimal makespan of ``instance`` for ``spec``'s label, or search it and cache it;
    with assignment also the assignment that search followed (cached beside it too)."""
    cache, facts_cache = makespan_cache(instance), assignment_cache(instance)
    if needs_search(read_makespan_cache(cache), read_assignment_cache(facts_cache), spec):
        print(f"{instance.name}: finding the minimal makespan for {spec.label} (at most {time_limit:g} s)",
              file=sys.stderr, flush=True)
        started = time.perf_counter()
        report = run({"kind": "makespan", "instance": str(instance), **spec.domain_job(),
                      "assign": spec.assign, "time_limit": time_limit})
        search = LimitedRun(DONE, time.perf_counter() - started, report)
        known = {**read_makespan_cache(cache),  # another run may have cached another label meanwhile
                 spec.label: report["horizon"] if makespan_status(search) == SOLVED else None}
        if report.get("assignment"):
            facts = {**read_assignment_cache(facts_cache), spec.label: report["assignment"]}
            write_text(facts_cache, json.dumps(facts, sort_keys=True) + "\n")
        write_text(cache, json.dumps(known, sort_keys=True) + "\n")
    return read_makespan_cache(cache)[spec.label], read_assignment_cache(facts_cache).get(spec.label)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m asprilo.bench.single")
    parser.add_argument("instance", type=Path)
    parser.add_argument("--domain", required=True)
    parser.add_argument("--encoding", default="plain")
    parser.add_argument("--assign", action="store_true")
    parser.add_argument("--time-limit", type=float, required=True)
    parser.add_argument("--makespan-time-limit", type=float, default=600.0)
    parser.add_argument("--method", choices=("asp", "anytime"), default="asp")
    parser.add_argument("--own-encoding", type=Path, metavar="FILE",
                        help="the JSON description of the suite's own encoding --encoding (relative to --root)")
    parser.add_argument("--root", type=Path, default=Path("."), metavar="DIR",
                        help="the folder --own-encoding is relative to (the export folder)")
    parser.add_argument("--variant", action="append", default=[], metavar="NAME",
                        help="a built-in rule variant of the domain (repeat to compose)")
    args = parser.parse_args(argv)
    if args.method == "anytime":
        return _anytime(args)
    base = Domain.parse(args.domain)
    domain = base
    if args.variant:  # loaded before any instance is read: their attributes are data
        from asprilo.domain.variants import with_variants
        domain = with_variants(base, args.variant)
    spec = RunSpec(domain, args.encoding, args.assign, own=_own(args), variants=tuple(args.variant),
                   base=base if args.variant else None)
    horizon, assignment = minimal_makespan(args.instance, spec, args.makespan_time_limit)
    robots = len(read_instance(args.instance).robots)
    record = new_record(SuiteInstance(args.instance.parent.name, args.instance, args.instance.name, robots),
                        spec, horizon, args.time_limit)
    print(json.dumps(record, sort_keys=True), flush=True)
    if horizon is not None:
        started = time.perf_counter()
        try:
            report = run({**run_job(args.instance, spec, horizon, assignment), "time_limit": args.time_limit})
        except Exception as error:  # noqa: BLE001 - the run failed (e.g. its encoding): its record says why
            failed = failure(error, time.perf_counter() - started)
            record = complete(record, args.instance, failed.status, failed.wall, {}, failed.detail)
        else:
            record = complete(record, args.instance, DONE, time.perf_counter() - started, report)
        print(json.dumps(record, sort_keys=True), flush=True)
    return 0


def _own(args: argparse.Namespace) -> OwnEncoding | None:
    """The suite's own encoding that ``--own-encoding`` describes (``None``: a reference encoding)."""
    if args.own_encoding is None:
        return None
    path = args.root / args.own_encoding
    try:
        description = json.loads(path.read_text(encoding="utf-8"))
        files = [str((path.parent / file).absolute()) for file in description["files"]]
        stage = [str((path.parent / file).absolute()) for file in description.get("stage", ())]
        return OwnEncoding.from_job(args.encoding, {**description, "files": files, "stage": stage})
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise SystemExit(f"error: {path}: not the description of an encoding ({error})") from None


def _anytime(args: argparse.Namespace) -> int:
    """A run of the anytime planner: no minimal makespan needed."""
    spec = RunSpec(Domain.parse(args.domain), "anytime", False, method="anytime")
    robots = len(read_instance(args.instance).robots)
    record = new_record(SuiteInstance(args.instance.parent.name, args.instance, args.instance.name, robots),
                        spec, None, args.time_limit)
    print(json.dumps(record, sort_keys=True), flush=True)
    started = time.perf_counter()
    report = run({"kind": "anytime", "instance": str(args.instance), "domain": spec.domain.value,
                  "time_limit": args.time_limit})
    record = complete_anytime(record, args.instance, LimitedRun(DONE, time.perf_counter() - started, report))
    print(json.dumps(record, sort_keys=True), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
