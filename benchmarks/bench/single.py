"""One benchmark run for potassco's benchmark-tool, which enforces the limits itself:

    python -m asprilo.bench.single --domain m --encoding plain [--assign] --time-limit S INSTANCE

The horizon is the instance's minimal makespan from ``makespans.json`` beside it (written by
``asprilo bench export-btool``).  Prints one JSON line: the run's record, as in results.jsonl.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from asprilo.domain import Domain
from asprilo.reader import read_instance

from .runner import SuiteInstance, complete, new_record
from .suite import RunSpec
from .worker import run


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m asprilo.bench.single")
    parser.add_argument("instance", type=Path)
    parser.add_argument("--domain", required=True)
    parser.add_argument("--encoding", default="plain")
    parser.add_argument("--assign", action="store_true")
    parser.add_argument("--time-limit", type=float, required=True)
    args = parser.parse_args(argv)
    spec = RunSpec(Domain.parse(args.domain), args.encoding, args.assign)
    makespans = json.loads((args.instance.parent / "makespans.json").read_text())
    horizon = makespans.get(args.instance.name, {}).get(spec.label)
    robots = len(read_instance(args.instance).robots)
    record = new_record(SuiteInstance(args.instance.parent.name, args.instance, args.instance.name, robots),
                        spec, horizon, args.time_limit)
    if horizon is not None:
        started = time.perf_counter()
        report = run({"kind": "run", "instance": str(args.instance), "domain": spec.domain.value,
                      "encoding": spec.encoding, "assign": spec.assign, "horizon": horizon,
                      "time_limit": args.time_limit})
        record = complete(record, args.instance, "done", time.perf_counter() - started, report)
    print(json.dumps(record, sort_keys=True), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
