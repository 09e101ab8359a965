"""Find a plan fast and prove its makespan minimal: reference encodings, your own, anytime, max-flow.

By default (--method auto) two searches run side by side, each in a process of its own:
the exact search, which starts at a lower bound of the makespan and goes up one step at a
time, and the anytime planner, which finds a plan fast and then better ones.  The answer is
the best plan found, proven minimal as soon as the exact search has refuted every shorter
horizon (or found it), else with the bound proven so far and the gap; a plan once found is
never lost (time limit, Ctrl-C, SIGTERM).  --start PLAN gives the anytime planner a plan to
start from (of this domain, or for B an A plan, for C an A or B plan: C relaxes B relaxes A):
the answer is never longer than it.  M/Md with anonymous goals: max-flow, exact and fast.
--method asp, anytime or flow runs that method alone; --encoding runs that encoding alone
(method asp; with anytime or flow, which run none, it is refused).  The plan is checked,
then printed as occurs/3 facts (stdout, or -o PLAN); a summary goes to stderr.  On a
terminal a line redrawn twice a second says what the searches do (phase, horizon,
conflicts, best plan so far, elapsed and remaining time).

--encoding FILE... (one flag, several files, as clingo takes them; or the flag repeated)
runs your own encoding: single-shot with a horizon constant, incremental (#include <incmode>,
#program step(t)/check(t) and query(t)), or with &sum/&diff theory atoms (clingcon /
clingo-dl); the summary says which style was recognised.  -c NAME=VALUE and clingo's own
options (--name=value, e.g. --configuration=crafty) go to clingo.  --stage FILE... adds a
first stage (e.g. a task assignment of your own): solved once with the instance and the same
constants, the shown atoms of its first answer become facts of the encoding, as
"clingo stage.lp inst.lp | clingo - plan.lp inst.lp" would give them.  Exit status: 0 a valid
plan found (proven minimal or not: the summary and --json say which), 1 no plan within the
limits or a plan that breaks the rules (the violations are listed), 2 bad input, 130
interrupted (Ctrl-C, SIGTERM, SIGHUP: the best plan so far is still written and printed).

--variant NAME|FILE changes the rules (docs/VARIANTS.md): the plan is checked under them,
and without --encoding the search runs the variant's model solution (max-flow and the anytime
planner know only SPEC.md's rules; the summary says which methods serve the variant).

Examples:
  asprilo solve instance.lp
  asprilo solve instance.lp --encoding clingcon --time-limit 60 -o plan.lp
  asprilo solve instance.lp --encoding my.lp goal.lp -c lanes=2
  asprilo solve instance.lp --encoding plan.lp --stage assign.lp
  asprilo solve instance.lp --variant diagonal
  asprilo solve instance.lp --horizon 12 --domain b
  asprilo solve instance.lp --assign
  asprilo solve m-instance.lp --method flow
  asprilo solve instance.lp --method anytime --time-limit 30
  asprilo solve instance.lp --domain c --start b-plan.lp
  asprilo solve --list
"""

from __future__ import annotations

import argparse
import json
import sys
import threading
import time
from pathlib import Path
from typing import TextIO

from asprilo.arguments import (
    add_variant_option,
    chosen_domain,
    domain_argument,
    loaded_variants,
    megabytes_argument,
    seconds_argument,
)
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.exits import INTERRUPTED, stopping_on_interrupt
from asprilo.reader import read_instance
from asprilo.writer import check_output, format_plan, write_text

from .anytime import DEFAULT_SECONDS as ANYTIME_SECONDS
from .choice import choose_encoding, is_encoding_file, stage_encoding
from .registry import Encoding, default_encoding, reference_encodings
from .solving import Attempt, Phase, find_method, method_names, solve
from .solving.method import runs_no_encoding
from .solving.methods import methods_words
from .solving.minimality import learn_minimum
from .summary import SHOWN_VIOLATIONS, SHOWN_WARNINGS, report, summary
from .summary import verdict as _verdict

__all__ = ["CLINGO_OPTIONS", "DEFAULT_TIME_LIMIT", "SHOWN_VIOLATIONS", "SHOWN_WARNINGS", "SearchProgress",
           "_verdict", "chosen_encoding", "configure", "report", "run"]

#: options asprilo does not know are clingo's (the command line passes them on)
CLINGO_OPTIONS = True
#: seconds ``asprilo solve`` may take unless told otherwise (the anytime method: its own default)
DEFAULT_TIME_LIMIT = 300.0


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="INSTANCE", nargs="?", help="instance file (- = stdin)")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    parser.add_argument("--encoding", action="extend", nargs="+", metavar="NAME|FILE",
                        help="a reference encoding by name (default: plain; --list shows them), or the files "
                             "of your own encoding (--encoding a.lp b.lp, or the flag repeated; give the "
                             "instance before it)")
    parser.add_argument("--stage", action="extend", nargs="+", metavar="FILE",
                        help="a first stage of your own (e.g. a task assignment), solved once with the instance "
                             "and the same -c constants: the shown atoms of its first answer become facts of "
                             "the encoding")
    add_variant_option(parser)
    parser.add_argument("-c", "--const", action="append", default=[], metavar="NAME=VALUE",
                        help="a constant for your encoding, as clingo's -c (-c horizon=H solves at H only)")
    parser.add_argument("--horizon", type=int, metavar="H", help="solve at this makespan only")
    parser.add_argument("--start", metavar="PLAN",
                        help="a plan to start from (methods auto and anytime): of this domain, or of a stronger "
                             "reading (an A plan for B or C, a B plan for C); the answer is never longer than it")
    parser.add_argument("--assign", action="store_true",
                        help="compute a task assignment first and plan along it (A/B/C: after a short "
                             "try without one from the lower bound up)")
    parser.add_argument("--time-limit", type=seconds_argument, metavar="S",
                        help=f"stop after S seconds, grounding included (default {DEFAULT_TIME_LIMIT:g}; "
                             f"anytime: {ANYTIME_SECONDS:g})")
    parser.add_argument("--memory-limit", type=megabytes_argument, metavar="MB",
                        help="stop when the solver needs more than MB megabytes (default for your own encoding: "
                             "half the machine's memory or 8192, whichever is less, and at most ulimit -v)")
    parser.add_argument("--method", choices=method_names(),
                        help="auto (default; asp with --encoding): the exact search and the anytime "
                             "planner side by side, the best plan with its proof or bound; asp: an "
                             "encoding alone; flow: exact max-flow solver for M/Md; anytime: a plan fast, "
                             "then better ones")
    parser.add_argument("-o", "--output", metavar="PLAN",
                        help="write the plan to this file (a regular file, not an input; - = standard output)")
    parser.add_argument("--json", action="store_true", help="print a JSON report instead of the plan")
    parser.add_argument("--list", action="store_true", help="list the encodings and exit")


def run(args: argparse.Namespace) -> int:
    if args.list:
        return _list_encodings()
    args.instance = _instance(args)
    if args.output == "-":
        args.output = None  # standard output, as without -o
    files = [name for name in [*(args.encoding or ()), *(args.stage or ()), *([args.start] if args.start else [])]
             if Path(name).is_file()]
    inputs = [args.instance, *files]
    check_output(args.output, inputs, standard_output="-o -")
    method, time_limit = _method_and_time_limit(args)
    if args.encoding and not find_method(method).encoded:  # anytime, flow: the encoding would go unused
        raise InputError(runs_no_encoding(method))
    loaded_variants(args)  # before reading: the attributes they declare are data
    instance = read_instance(args.instance)
    detected = detect_domain(instance)
    domain = chosen_domain(args, detected) or detected
    encoding, horizon = chosen_encoding(args, domain)
    stage = None
    if args.stage:
        stage = stage_encoding(args.stage, encoding.constants if encoding is not None else ())
    if args.encoding is None and encoding is not None and method in ("auto", "asp"):
        said = methods_words(domain, encoding)  # a domain the other methods do not serve: which do
        if said:
            print(said, file=sys.stderr)
    progress = SearchProgress(sys.stderr, time_limit, own=encoding is not None and encoding.own)
    cancel = threading.Event()
    try:
        with stopping_on_interrupt(cancel):
            outcome = solve(instance, domain, encoding=encoding, horizon=horizon, assign=args.assign,
                            time_limit=time_limit, method=method, isolate=True, memory_limit=args.memory_limit,
                            on_progress=progress.attempt, on_phase=progress.phase, cancel=cancel, stage=stage,
                            start=args.start)
    finally:
        progress.close()
    learn_minimum(outcome, instance)  # your encoding's plan above the bound: the problem's minimum, where cheap
    if outcome.plan is not None and outcome.found and args.output:
        write_text(args.output, format_plan(outcome.plan), inputs)
    summary(outcome, encoding, hint=args.method == "asp" and horizon is None, instance=instance)
    _answer(args, outcome)
    if cancel.is_set():  # Ctrl-C, SIGTERM, SIGHUP: the plan so far is kept, the exit status says so
        return INTERRUPTED
    return 0 if outcome.found else 1


def _answer(args: argparse.Namespace, outcome) -> None:
    """The answer on standard output: the JSON report, or the plan found (unless written to ``-o``)."""
    if args.json:
        print(json.dumps(report(outcome), indent=2))
    elif outcome.found and not args.output:
        sys.stdout.write(format_plan(outcome.plan))


def _instance(args: argparse.Namespace) -> str:
    """The instance the command line names.  ``--encoding`` and ``--stage`` take every file
    that follows them, so an instance given after them is taken too: said so (a reference
    encoding, named alone, leaves the file after it to be the instance)."""
    if args.instance is not None:
        return args.instance
    values = args.encoding or []
    if len(values) == 2 and not is_encoding_file(values[0]):
        args.encoding = values[:1]
        return values[1]
    taken = [(flag, names) for flag, names in (("--encoding", args.encoding), ("--stage", args.stage)) if names]
    if not taken:
        raise InputError("no instance given (asprilo solve INSTANCE)")
    said = "; ".join(f"{flag} took {', '.join(names)}" for flag, names in taken)
    looks = [name for _flag, names in taken for name in names if _looks_like_instance(name)]
    hint = f" ({looks[-1]} looks like an instance: it has init/2 facts)" if looks else ""
    raise InputError(f"no instance given: {said}, every file after the flag{hint}; give the instance first: "
                     "asprilo solve INSTANCE --encoding FILE...")


def _looks_like_instance(name: str) -> bool:
    """Whether the file ``name`` holds an instance's facts (``init(object(``) in its first 64 kB."""
    try:
        with open(name, encoding="utf-8", errors="replace") as stream:
            return "init(object(" in stream.read(65536)
    except OSError:
        return False


def _list_encodings() -> int:
    """``solve --list``: a line per reference encoding."""
    for encoding in reference_encodings():
        theory = f" [{encoding.theory}]" if encoding.theory else ""
        print(f"{encoding.domain.value:<3} {encoding.name:<13} {encoding.summary}{theory}")
    return 0


def _method_and_time_limit(args: argparse.Namespace) -> tuple[str, float]:
    """The method (``auto``; ``asp`` with ``--encoding``) and its time limit (the anytime
    planner's own default when it runs alone)."""
    method = args.method or ("asp" if args.encoding else "auto")
    if args.time_limit is not None:
        return method, args.time_limit
    return method, ANYTIME_SECONDS if method == "anytime" else DEFAULT_TIME_LIMIT


def chosen_encoding(args: argparse.Namespace, domain: Domain) -> tuple[Encoding | None, int | None]:
    """The encoding the options name (none named: the domain's default, ``plain`` or a
    variant's model solution; ``None`` where it has none), and the horizon asked for
    (``--horizon``, or ``-c horizon=H`` for a single-shot encoding of one's own)."""
    values = args.encoding
    if not values:
        if not domain.encodings:
            if args.const:
                raise InputError("-c sets constants of your own encoding (--encoding FILE)")
            return None, args.horizon
        values = [default_encoding(domain).name]
    return choose_encoding(values, args.const, getattr(args, "clingo_options", None) or (), domain, args.horizon)


class SearchProgress:
    """Says what the search does: a line per horizon tried and per better plan; while it works,
    on a terminal, one line redrawn twice a second (a heartbeat): what the exact search does
    (phase, horizon, seconds on it, conflicts so far), the best plan so far and what is proven
    (nothing by the horizons a user's ``own`` encoding refutes), the seconds elapsed and left.
    Otherwise (a pipe, a file) a line when each phase begins
    and nothing between.

    The heartbeat's thread starts with the first word from the search (its child processes
    are started by then: a process without threads may fork them)."""

    def __init__(self, stream: TextIO, time_limit: float | None = None, own: bool = False):
        self.stream, self.live, self.time_limit = stream, stream.isatty(), time_limit
        self.own = own  # a user's own encoding: its refuted horizons say nothing of the problem
        self.started = time.perf_counter()
        self.current: Phase | None = None
        self.since = self.started
        self.best: int | None = None        # the shortest plan reported
        self.proven: int | None = None      # no plan is shorter (the horizons refuted)
        self.lock = threading.Lock()
        self.done = threading.Event()
        self.ticker: threading.Thread | None = None

    def phase(self, phase: Phase) -> None:
        if phase.name not in ("bounding", "grounding", "solving", "assigning"):
            return
        with self.lock:
            current = self.current
            again = current is not None and (current.name, current.horizon) == (phase.name, phase.horizon)
            self.current = phase
            if not again:
                self.since = time.perf_counter()
                if not self.live and phase.name != "bounding":
                    self._say(f"{self._label(phase)}: {phase.name} (elapsed {self.since - self.started:.1f} s)")
        self._beat()

    def attempt(self, attempt: Attempt) -> None:
        with self.lock:
            if attempt.plan is not None and (self.best is None or attempt.horizon < self.best):
                self.best = attempt.horizon
            if attempt.refutes and not self.own:
                self.proven = max(self.proven or 0, attempt.horizon + 1)
            if attempt.result == "improved":
                self._say(f"plan: makespan {attempt.horizon}, {attempt.note} ({attempt.seconds:.2f} s)")
            else:
                self.current = None
                note = f" {attempt.note}" if attempt.note else ""
                self._say(f"horizon {attempt.horizon}{note}: {attempt.result} ({attempt.seconds:.2f} s)")
        self._beat()

    def close(self) -> None:
        self.done.set()
        if self.ticker is not None:
            self.ticker.join()
        if self.live:
            self.stream.write("\r\033[K")
            self.stream.flush()

    def heartbeat(self, now: float) -> str:
        """The line the heartbeat redraws."""
        parts = []
        phase = self.current
        if phase is not None:
            conflicts = f", {phase.conflicts:,} conflicts" if phase.conflicts else ""
            doing = "computing" if phase.name == "bounding" else phase.name
            parts.append(f"{self._label(phase)}: {doing} {now - self.since:.0f} s{conflicts}")
        if self.best is not None:
            proven = " (proven minimal)" if self.proven is not None and self.best <= self.proven else ""
            parts.append(f"best plan: makespan {self.best}{proven}")
        if self.proven is not None:
            parts.append(f"no plan shorter than {self.proven}")
        elapsed = now - self.started
        left = "" if self.time_limit is None else f", {max(0.0, self.time_limit - elapsed):.0f} s left"
        parts.append(f"elapsed {elapsed:.0f} s{left}")
        return " | ".join(parts)

    @staticmethod
    def _label(phase: Phase) -> str:
        if phase.name == "bounding":
            return "lower bound"
        return "task assignment" if phase.name == "assigning" else f"horizon {phase.horizon}"

    def _say(self, line: str) -> None:
        prefix = "\r\033[K" if self.live else ""
        self.stream.write(f"{prefix}{line}\n")
        self.stream.flush()

    def _beat(self) -> None:
        """Start the heartbeat (on a terminal, once)."""
        if self.live and self.ticker is None and not self.done.is_set():
            self.ticker = threading.Thread(target=self._tick, daemon=True)
            self.ticker.start()

    def _tick(self) -> None:
        while not self.done.wait(0.5):
            with self.lock:
                self.stream.write("\r\033[K" + self.heartbeat(time.perf_counter())[:_width() - 1])
                self.stream.flush()


def _width() -> int:
    """The terminal's width (the heartbeat fits on one line, so that it redraws in place)."""
    import shutil

    return max(40, shutil.get_terminal_size((120, 24)).columns)
