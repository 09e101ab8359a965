"""Grade your encoding on a ladder of instances: is each plan valid, is it minimal?

ENCODING is one or several files of your own encoding (as asprilo solve --encoding takes
them: single-shot with a horizon constant, incremental, clingcon, clingo-dl; -c NAME=VALUE
and clingo's --name=value options go to clingo), or the name of a reference encoding.  It
runs on the bundled ladder of the domain: instances from one robot on a few cells up to
11x6 floors with 3 to 5 robots, each with its minimal makespan established independently
(max-flow for M/Md, the reference encodings' proven minimum for A/B/C, cross-checked by
a breadth-first search over joint states where the instance is tiny; --list shows them).

Each instance is solved from a lower bound up in a child process under --time-limit
(default 20 s; so the whole run takes at most about that times the number of instances)
and its plan checked.  A line per instance: valid or not, minimal or "makespan 9,
minimum 7", the time, and the first violation in words or why there is no plan (time
limit, no answer set, no occurs/3 in the model, a crash); then a summary line.  --json
prints the same as JSON for course tools (docs/GRADING.md).  Progress goes to stderr.

Exit status: 0 every instance got a valid plan, 1 some did not, 2 bad input (a bad
encoding is refused before the first instance, with its located message).

Examples:
  asprilo grade my.lp --domain m
  asprilo grade main.lp goal.lp --domain a -c lanes=2 --configuration=crafty
  asprilo grade my.lp --domain m --json --time-limit 10 > grades.json
  asprilo grade my.lp --ladder course/week3/ladder.yml
  asprilo grade --list --domain c
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from typing import Any, TextIO

from asprilo.arguments import domain_argument, megabytes_argument, seconds_argument
from asprilo.errors import InputError
from asprilo.reader import read_instance

from .choice import choose_encoding
from .grading import JSON_VERSION, VALID, VERDICTS, Graded, Summary, grade_ladder, horizons, too_strong
from .ladder import Ladder, Rung, bundled_ladder, read_ladder
from .registry import Encoding
from .solving import Phase

#: options asprilo does not know are clingo's (the command line passes them on)
CLINGO_OPTIONS = True
#: seconds per instance unless told otherwise
DEFAULT_TIME_LIMIT = 20.0


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("encoding", metavar="ENCODING", nargs="*",
                        help="files of your own encoding (loaded in this order), or a reference encoding's name")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md: grade on this domain's ladder")
    parser.add_argument("--ladder", metavar="FILE", help="a ladder of your own (ladder.yml; docs/GRADING.md)")
    parser.add_argument("-c", "--const", action="append", default=[], metavar="NAME=VALUE",
                        help="a constant for your encoding, as clingo's -c (-c horizon=H solves at H only)")
    parser.add_argument("--time-limit", type=seconds_argument, metavar="S", default=DEFAULT_TIME_LIMIT,
                        help=f"seconds per instance, grounding and check included (default {DEFAULT_TIME_LIMIT:g})")
    parser.add_argument("--memory-limit", type=megabytes_argument, metavar="MB",
                        help="megabytes per instance (default: no limit)")
    parser.add_argument("--first", type=_count, metavar="N", help="grade only the first N instances of the ladder")
    parser.add_argument("--json", action="store_true", help="print the grades as JSON (docs/GRADING.md)")
    parser.add_argument("--list", action="store_true", help="list the ladder's instances and their minima, and exit")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")


def _count(text: str) -> int:
    try:
        number = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if number < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {number}")
    return number


def run(args: argparse.Namespace) -> int:
    ladder = _ladder(args)
    if args.list:
        _list(ladder)
        return 0
    if not args.encoding:
        raise InputError("no encoding given (asprilo grade ENCODING... --domain D)")
    encoding, horizon = choose_encoding(args.encoding, args.const, getattr(args, "clingo_options", None) or (),
                                        ladder.domain)
    progress = _Progress(sys.stderr, quiet=args.quiet)
    out = sys.stdout
    started = time.perf_counter()
    graded: list[Graded] = []
    steps = len(ladder.rungs) if args.first is None else min(args.first, len(ladder.rungs))
    try:
        for item in grade_ladder(encoding, ladder, time_limit=args.time_limit, horizon=horizon,
                                 memory_limit=args.memory_limit, first=args.first,
                                 on_start=progress.start, on_phase=progress.phase):
            progress.clear()
            if not args.json and not graded:  # after the first grade: a refused encoding is an error alone
                _say(out, _header(encoding, ladder, steps, args.time_limit))
            graded.append(item)
            if not args.json:
                _say(out, line(item, steps))
    finally:
        progress.clear()
    summary = Summary.of(graded, time.perf_counter() - started)
    if args.json:
        _say(out, json.dumps(report(encoding, horizon, ladder, args.time_limit, graded, summary), indent=2))
    else:
        _say(out, summary.line())
    return 0 if summary.valid == summary.instances else 1


def _ladder(args: argparse.Namespace) -> Ladder:
    if args.ladder is None:
        if args.domain is None:
            raise InputError("name the domain (--domain a|b|c|m|md) or a ladder (--ladder FILE)")
        return bundled_ladder(args.domain)
    ladder = read_ladder(args.ladder)
    if args.domain is not None and args.domain is not ladder.domain:
        raise InputError(f"the ladder is of domain {ladder.domain.label}, not {args.domain.label}", args.ladder)
    return ladder


def _list(ladder: Ladder) -> None:
    print(f"{ladder.label}: {len(ladder.rungs)} instances ({ladder.manifest})")
    width = max(len(rung.name) for rung in ladder.rungs)
    for step, rung in enumerate(ladder.rungs, 1):
        instance = read_instance(rung.file)
        (x, y), robots = instance.size, len(instance.robots)
        size = f"{x}x{y}, {robots} robot{'s' * (robots != 1)}"
        print(f"{step:>2}  {rung.name:<{width}}  {size:<15}  minimum {rung.minimum}")
        print(f"      established: {rung.established}")
        for method in rung.cross_checked:
            print(f"      cross-checked: {method}")


def _header(encoding: Encoding, ladder: Ladder, count: int, time_limit: float) -> str:
    if encoding.own:
        what = f"your encoding ({', '.join(str(file) for file in encoding.files)}: {encoding.summary})"
    else:
        what = f"the reference encoding {encoding.name}"
    lines = [f"grading {what} on {ladder.label}: {count} instance{'s' * (count != 1)}, "
             f"time limit {time_limit:g} s each"]
    lines += [f"  assumed: {note}" for note in encoding.assumed]
    return "\n".join(lines)


def line(graded: Graded, steps: int) -> str:
    """One instance's grade in a line: step, name, size, time, result and what to know."""
    number = f"{graded.step:>{len(str(steps))}}/{steps}"
    return (f"{number}  {graded.rung.name:<14} {graded.size:<15} {graded.seconds:6.1f} s  "
            f"{VERDICTS[graded.result]:<8} {detail(graded)}")


def detail(graded: Graded) -> str:
    """What to know about one grade, in words."""
    minimum = graded.rung.minimum
    if graded.result == VALID:
        if graded.makespan == minimum:
            return f"minimal (makespan {minimum})"
        if graded.makespan is not None and graded.makespan < minimum:
            return (f"makespan {graded.makespan}, below the stored minimum {minimum}: the ladder is wrong, "
                    "please report it")
        refuted = f" ({horizons(graded.too_strong)} refuted{too_strong(graded)})" if graded.too_strong else ""
        return f"makespan {graded.makespan}, minimum {minimum}{refuted}"
    if graded.violation is not None:
        more = graded.violations - 1
        others = f" (and {more} more violation{'s' * (more != 1)})" if more else ""
        return f"makespan {graded.makespan}: {graded.violation.message}{others}"
    return graded.reason


def report(encoding: Encoding, horizon: int | None, ladder: Ladder, time_limit: float, graded: list[Graded],
           summary: Summary) -> dict[str, Any]:
    """The grades as plain data (``--json``; the shape is docs/GRADING.md's)."""
    return {
        "version": JSON_VERSION,
        "domain": ladder.domain.value,
        "ladder": ladder.domain.value if ladder.bundled else str(ladder.manifest),
        "encoding": {
            "name": encoding.name,
            "own": encoding.own,
            "files": [str(file) for file in encoding.files] if encoding.own else [],
            "style": encoding.summary,
            "assumed": list(encoding.assumed),
            "constants": dict(encoding.constants),
            "horizon": horizon,
            "options": list(encoding.options),
        },
        "time_limit": time_limit,
        "instances": [item.as_json() for item in graded],
        "summary": summary.as_json(),
    }


def _say(stream: TextIO, text: str) -> None:
    stream.write(text + "\n")
    stream.flush()


class _Progress:
    """Says on stderr which instance is being graded: on a terminal one line redrawn as the
    search goes (the horizon and phase), otherwise a line per instance."""

    def __init__(self, stream: TextIO, quiet: bool = False):
        self.stream, self.quiet = stream, quiet
        self.live = stream.isatty() and not quiet
        self.current = ""

    def start(self, step: int, steps: int, rung: Rung) -> None:
        if self.quiet:
            return
        self.current = f"[{step}/{steps}] {rung.name} (minimum {rung.minimum})"
        if self.live:
            self.stream.write(f"\r\033[K{self.current}")
        else:
            self.stream.write(f"grading {self.current}\n")
        self.stream.flush()

    def phase(self, phase: Phase) -> None:
        if self.live and phase.name in ("grounding", "solving"):
            self.stream.write(f"\r\033[K{self.current}: horizon {phase.horizon}, {phase.name}")
            self.stream.flush()

    def clear(self) -> None:
        if self.live:
            self.stream.write("\r\033[K")
            self.stream.flush()
