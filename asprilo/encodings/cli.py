"""Find a plan fast and prove its makespan minimal: reference encodings, your own, anytime, max-flow.

By default (--method auto) two searches run side by side, each in a process of its own:
the exact search, which starts at a lower bound of the makespan and goes up one step at a
time, and the anytime planner, which finds a plan fast and then better ones.  The answer is
the best plan found, proven minimal as soon as the exact search has refuted every shorter
horizon (or found it), else with the bound proven so far and the gap; a plan once found is
never lost (time limit, Ctrl-C, SIGTERM).  M/Md with anonymous goals: max-flow, exact and fast.
--method asp, anytime or flow runs that method alone; --encoding runs that encoding alone
(method asp).  The plan is checked, then printed as occurs/3 facts (stdout, or -o PLAN); a
summary goes to stderr.  On a terminal a line redrawn twice a second says what the searches
do (phase, horizon, conflicts, best plan so far, elapsed and remaining time).

--encoding FILE (repeated for several files) runs your own encoding: single-shot with a
horizon constant, incremental (#include <incmode>, #program step(t)/check(t) and query(t)),
or with &sum/&diff theory atoms (clingcon / clingo-dl); the summary says which style was
recognised.  -c NAME=VALUE and clingo's own options (--name=value, e.g.
--configuration=crafty) go to clingo.  Exit status: 0 a valid plan found (proven minimal or
not: the summary and --json say which), 1 no plan within the limits or a plan that breaks
the rules (the violations are listed), 2 bad input.

Examples:
  asprilo solve instance.lp
  asprilo solve instance.lp --encoding clingcon --time-limit 60 -o plan.lp
  asprilo solve instance.lp --encoding my.lp --encoding goal.lp -c lanes=2
  asprilo solve instance.lp --horizon 12 --domain b
  asprilo solve instance.lp --assign
  asprilo solve m-instance.lp --method flow
  asprilo solve instance.lp --method anytime --time-limit 30
  asprilo solve --list
"""

from __future__ import annotations

import argparse
import contextlib
import json
import signal
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import TextIO

from asprilo.arguments import domain_argument, megabytes_argument, seconds_argument
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.model import Instance
from asprilo.reader import plan_misfits, read_instance
from asprilo.writer import check_output, format_action, format_plan, write_text

from .anytime import DEFAULT_SECONDS as ANYTIME_SECONDS
from .choice import choose_encoding
from .registry import Encoding, reference_encodings
from .solving import Attempt, Outcome, Phase, method_names, solve

#: options asprilo does not know are clingo's (the command line passes them on)
CLINGO_OPTIONS = True
#: the most violations the summary lists of a plan that breaks the rules, and of clingo's warnings
SHOWN_VIOLATIONS, SHOWN_WARNINGS = 20, 5

#: seconds ``asprilo solve`` may take unless told otherwise (the anytime method: its own default)
DEFAULT_TIME_LIMIT = 300.0


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="INSTANCE", nargs="?", help="instance file (- = stdin)")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    parser.add_argument("--encoding", action="append", metavar="NAME|FILE",
                        help="a reference encoding by name (default: plain; --list shows them), or a file "
                             "of your own encoding (repeat for several files)")
    parser.add_argument("-c", "--const", action="append", default=[], metavar="NAME=VALUE",
                        help="a constant for your encoding, as clingo's -c (-c horizon=H solves at H only)")
    parser.add_argument("--horizon", type=int, metavar="H", help="solve at this makespan only")
    parser.add_argument("--assign", action="store_true",
                        help="compute a task assignment first and plan along it (A/B/C: after a short "
                             "try without one from the lower bound up)")
    parser.add_argument("--time-limit", type=seconds_argument, metavar="S",
                        help=f"stop after S seconds, grounding included (default {DEFAULT_TIME_LIMIT:g}; "
                             f"anytime: {ANYTIME_SECONDS:g})")
    parser.add_argument("--memory-limit", type=megabytes_argument, metavar="MB",
                        help="stop when the solver needs more than MB megabytes (default: no limit)")
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
    if args.instance is None:
        raise InputError("no instance given (asprilo solve INSTANCE)")
    if args.output == "-":
        args.output = None  # standard output, as without -o
    inputs = [args.instance, *(name for name in args.encoding or () if Path(name).is_file())]
    check_output(args.output, inputs, standard_output="-o -")
    method, time_limit = _method_and_time_limit(args)
    instance = read_instance(args.instance)
    domain = args.domain or detect_domain(instance)
    encoding, horizon = chosen_encoding(args, domain)
    progress = SearchProgress(sys.stderr, time_limit)
    cancel = threading.Event()
    try:
        with _stopping_on_interrupt(cancel):
            outcome = solve(instance, domain, encoding=encoding, horizon=horizon, assign=args.assign,
                            time_limit=time_limit, method=method, isolate=True, memory_limit=args.memory_limit,
                            on_progress=progress.attempt, on_phase=progress.phase, cancel=cancel)
    finally:
        progress.close()
    if outcome.plan is not None and outcome.found and args.output:
        write_text(args.output, format_plan(outcome.plan), inputs)
    _summary(outcome, encoding, hint=args.method == "asp" and horizon is None, instance=instance)
    if args.json:
        print(json.dumps(report(outcome), indent=2))
    elif outcome.found and not args.output:
        sys.stdout.write(format_plan(outcome.plan))
    return 0 if outcome.found else 1


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


def chosen_encoding(args: argparse.Namespace, domain: Domain) -> tuple[Encoding, int | None]:
    """The encoding the options name, and the horizon asked for (``--horizon``, or
    ``-c horizon=H`` for a single-shot encoding of one's own)."""
    return choose_encoding(args.encoding or ["plain"], args.const, getattr(args, "clingo_options", None) or (),
                           domain, args.horizon)


class SearchProgress:
    """Says what the search does: a line per horizon tried and per better plan; while it works,
    on a terminal, one line redrawn twice a second (a heartbeat): what the exact search does
    (phase, horizon, seconds on it, conflicts so far), the best plan so far and what is proven,
    the seconds elapsed and left.  Otherwise (a pipe, a file) a line when each phase begins
    and nothing between.

    The heartbeat's thread starts with the first word from the search (its child processes
    are started by then: a process without threads may fork them)."""

    def __init__(self, stream: TextIO, time_limit: float | None = None):
        self.stream, self.live, self.time_limit = stream, stream.isatty(), time_limit
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
            if attempt.refutes:
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


@contextlib.contextmanager
def _stopping_on_interrupt(cancel: threading.Event) -> Iterator[None]:
    """While solving, the first Ctrl-C stops the search, which answers with the best plan it
    found (the second one interrupts as usual)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.getsignal(signal.SIGINT)

    def stop(_signal: int, _frame: object) -> None:
        cancel.set()
        signal.signal(signal.SIGINT, previous if previous is not None else signal.SIG_DFL)

    signal.signal(signal.SIGINT, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous if previous is not None else signal.SIG_DFL)


def _summary(outcome: Outcome, encoding: Encoding | None = None, hint: bool = False,
             instance: Instance | None = None) -> None:
    """The summary on stderr (``hint``: a search forced to method asp that ran out of time
    points to the default; ``instance``: a plan of the user's own encoding that does not fit
    it is said so in one sentence before its violations)."""
    lines = [f"domain {outcome.domain.label}, method {outcome.method}, encoding {outcome.encoding}, "
             f"lower bound {outcome.lower_bound:g}"]
    if encoding is not None and encoding.own and outcome.method == "asp":
        lines.append(f"your encoding ({', '.join(str(file) for file in encoding.files)}): {encoding.summary}")
        lines += [f"  assumed: {note}" for note in encoding.assumed]
        lines += [f"  clingo: {' '.join(warning.split())}" for warning in outcome.warnings[:SHOWN_WARNINGS]]
    if outcome.assignment is not None:
        assignment = outcome.assignment
        state = assignment.origin if assignment.origin != "optimised" else (
            f"{'optimal' if assignment.optimal else 'best found'}, cost {assignment.cost}")
        lines.append(f"assignment ({state}): " + " ".join(assignment.facts))
    lines += _misfit(outcome, encoding, instance) + _verdict(outcome)
    if hint and outcome.status.value == "limit":
        lines.append("for a plan fast (not proven minimal), leave out --method asp: the default runs the "
                     "anytime planner beside the exact search")
    lines.append(_figures(outcome))
    print("\n".join(lines), file=sys.stderr)


def _misfit(outcome: Outcome, encoding: Encoding | None, instance: Instance | None) -> list[str]:
    """One sentence for an invalid plan of the user's own encoding made for another instance
    or domain (robots the instance lacks, actions no domain knows, actions of another domain)."""
    if outcome.found or outcome.plan is None or instance is None or encoding is None or not encoding.own:
        return []
    said = plan_misfits(outcome.plan, instance, outcome.domain)
    return [f"your encoding's plan does not fit the instance: {'; '.join(said)}"] if said else []


#: who found the plan the answer holds (method auto), in words
_FOUND_BY = {"asp": "the exact search", "anytime": "the anytime planner"}


def _verdict(outcome: Outcome) -> list[str]:
    """What was found: the plan (proven minimal, or with the bound proven and the gap), the
    violations of a plan that breaks the rules, or why there is none; and what was tried
    and proven on the way, where that is not said by "proven minimal"."""
    if outcome.found:
        by = f"; found by {_FOUND_BY[outcome.found_by]}" if outcome.found_by in _FOUND_BY else ""
        line = f"plan: horizon {outcome.horizon} ({_proof(outcome)}), {len(outcome.plan)} actions, checked: valid{by}"
        ended = [f"the search ended: {outcome.message}"] if outcome.message and not outcome.minimal else []
        return [line] + ([] if outcome.minimal else _tried(outcome)) + ended
    if outcome.check is not None and not outcome.check.valid:
        errors = outcome.check.errors
        lines = [error.message for error in errors[:SHOWN_VIOLATIONS]]
        if len(errors) > SHOWN_VIOLATIONS:
            lines.append(f"... and {len(errors) - SHOWN_VIOLATIONS} more (asprilo check lists them all)")
        return lines + [f"no valid plan: the plan of makespan {outcome.plan.horizon} breaks the rules "
                        f"({len(errors)} violation{'s' * (len(errors) != 1)})"]
    lines = [{"none": "no plan exists", "limit": "no plan within the limits", "cancelled": "cancelled",
              "invalid": "no valid plan"}[outcome.status.value] + (f": {outcome.message}" if outcome.message else "")]
    if outcome.status.value in ("limit", "cancelled"):
        lines += _tried(outcome)
    return lines


def _proof(outcome: Outcome) -> str:
    """``proven minimal``, or the bound proven and the gap."""
    if outcome.minimal:
        return "proven minimal"
    bound, gap = outcome.proven_bound, outcome.gap
    if not bound or bound == float("inf") or gap is None:
        return "not proven minimal"
    return (f"not proven minimal: no plan is shorter than {bound:g}, gap {gap:g} step{'s' * (gap != 1)}, "
            f"{100 * gap / bound:.0f}%")


def _tried(outcome: Outcome) -> list[str]:
    """What was tried and proven: the horizons refuted (for the problem, and those refuted only
    along the task assignment), the horizons left undecided, the anytime planner's plans."""
    lines = []
    if outcome.refuted:
        lines.append(f"refuted horizons {_spans(outcome.refuted)}: no plan is shorter than {outcome.proven_bound:g}")
    along = [horizon for horizon in outcome.refuted_along if horizon not in outcome.refuted]
    if along:
        lines.append(f"no plan along the task assignment at horizon{'s' * (len(along) > 1)} {_spans(along)} "
                     "(refuted along the assignment only, not for the problem)")
    undecided = sorted({a.horizon for a in outcome.horizons_tried if a.result == "unknown"} - set(outcome.refuted))
    if undecided:
        lines.append(f"undecided: horizon{'s' * (len(undecided) > 1)} {_spans(undecided)}")
    plans = [a.horizon for a in outcome.horizons_tried if a.result == "improved"]
    if plans and outcome.method == "auto":
        shown = str(plans[0]) if len(plans) == 1 else f"{plans[0]} -> {min(plans)}"
        lines.append(f"anytime planner: {len(plans)} plan{'s' * (len(plans) > 1)}, makespan {shown}")
    return lines


def _figures(outcome: Outcome) -> str:
    """The method's statistics in one line."""
    stats = outcome.stats
    if outcome.method == "flow":
        return f"max-flow {stats['solve_time']:.2f} s"
    if outcome.method == "anytime":
        return (f"first plan {stats.get('first_plan_seconds', 0):.2f} s, {len(outcome.history)} plans reported, "
                f"{stats.get('neighbourhoods', 0)} neighbourhoods tried")
    figures = (f"ground {stats.get('ground_time', 0):.2f} s, solve {stats.get('solve_time', 0):.2f} s, "
               f"rules {stats.get('rules', 0)}, atoms {stats.get('atoms', 0)}, choices {stats.get('choices', 0)}, "
               f"conflicts {stats.get('conflicts', 0)}")
    return f"exact search: {figures}" if outcome.method == "auto" else figures


def report(outcome: Outcome) -> dict:
    """The outcome as plain data (``--json``)."""
    finite = outcome.proven_bound != float("inf")
    return {
        "status": outcome.status.value,
        "domain": outcome.domain.value,
        "method": outcome.method,
        "encoding": outcome.encoding,
        "horizon": outcome.horizon,
        "minimal": outcome.minimal,
        "lower_bound": outcome.lower_bound if outcome.lower_bound != float("inf") else None,
        "horizons_tried": [attempt.as_json() for attempt in outcome.horizons_tried],
        "refuted": outcome.refuted,
        "refuted_along_assignment": outcome.refuted_along,
        "proven_bound": outcome.proven_bound if finite else None,
        "gap": outcome.gap if finite else None,
        "stats": outcome.stats,
        "assignment": outcome.assignment.facts if outcome.assignment is not None else None,
        "plan": [format_action(action) for action in outcome.plan.actions] if outcome.found else None,
        "message": outcome.message,
        **({"found_by": outcome.found_by} if outcome.method == "auto" else {}),
        **({"history": outcome.history} if outcome.method in ("anytime", "auto") else {}),
    }


def _spans(horizons: list[int]) -> str:
    """``[3, 4, 5, 8]`` -> ``"3-5, 8"``."""
    spans: list[list[int]] = []
    for horizon in horizons:
        if spans and horizon == spans[-1][1] + 1:
            spans[-1][1] = horizon
        else:
            spans.append([horizon, horizon])
    return ", ".join(str(a) if a == b else f"{a}-{b}" for a, b in spans)
