"""Find a plan for an instance with a reference encoding, your own encoding, or max-flow.

Without --horizon the search starts at a lower bound of the makespan and goes up one step
at a time, so the first plan found has minimal makespan.  --method anytime instead finds a
plan fast and then better ones until the time limit (default 60 s) or the lower bound;
each one is checked and reported with its gap to the bound.  The plan is checked, then
printed as occurs/3 facts (stdout, or -o PLAN); a summary goes to stderr.

--encoding FILE (repeated for several files) runs your own encoding: single-shot with a
horizon constant, incremental (#include <incmode>, #program step(t)/check(t) and query(t)),
or with &sum/&diff theory atoms (clingcon / clingo-dl); the summary says which style was
recognised.  -c NAME=VALUE and clingo's own options (--name=value, e.g.
--configuration=crafty) go to clingo.  Exit status: 0 a valid plan found, 1 no plan within
the limits or a plan that breaks the rules (the violations are listed), 2 bad input.

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
import json
import sys
import threading
import time
from typing import TextIO

from asprilo.arguments import domain_argument, megabytes_argument, seconds_argument
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.reader import read_instance
from asprilo.writer import format_action, format_plan, refuse_overwriting, write_text

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
    parser.add_argument("--method", choices=method_names(), default="asp",
                        help="asp: an encoding (default); flow: exact max-flow solver for M/Md; "
                             "anytime: a plan fast, then better ones")
    parser.add_argument("-o", "--output", metavar="PLAN", help="write the plan to this file")
    parser.add_argument("--json", action="store_true", help="print a JSON report instead of the plan")
    parser.add_argument("--list", action="store_true", help="list the encodings and exit")


def run(args: argparse.Namespace) -> int:
    if args.list:
        for encoding in reference_encodings():
            theory = f" [{encoding.theory}]" if encoding.theory else ""
            print(f"{encoding.domain.value:<3} {encoding.name:<13} {encoding.summary}{theory}")
        return 0
    if args.instance is None:
        raise InputError("no instance given (asprilo solve INSTANCE)")
    refuse_overwriting(args.output, [args.instance])
    time_limit = args.time_limit
    if time_limit is None:
        time_limit = ANYTIME_SECONDS if args.method == "anytime" else DEFAULT_TIME_LIMIT
    instance = read_instance(args.instance)
    domain = args.domain or detect_domain(instance)
    encoding, horizon = chosen_encoding(args, domain)
    progress = SearchProgress(sys.stderr)
    try:
        outcome = solve(instance, domain, encoding=encoding, horizon=horizon,
                        assign=args.assign, time_limit=time_limit, method=args.method, isolate=True,
                        memory_limit=args.memory_limit, on_progress=progress.attempt, on_phase=progress.phase)
    finally:
        progress.close()
    if outcome.plan is not None and outcome.found and args.output:
        write_text(args.output, format_plan(outcome.plan))
    _summary(outcome, encoding)
    if args.json:
        print(json.dumps(report(outcome), indent=2))
    elif outcome.found and not args.output:
        sys.stdout.write(format_plan(outcome.plan))
    return 0 if outcome.found else 1


def chosen_encoding(args: argparse.Namespace, domain: Domain) -> tuple[Encoding, int | None]:
    """The encoding the options name, and the horizon asked for (``--horizon``, or
    ``-c horizon=H`` for a single-shot encoding of one's own)."""
    return choose_encoding(args.encoding or ["plain"], args.const, getattr(args, "clingo_options", None) or (),
                           domain, args.horizon)


class SearchProgress:
    """Says what the search does: a line per horizon tried, and while it works the phase
    (grounding or solving), the horizon and the seconds so far -- on a terminal as one line
    redrawn in place, otherwise as a line when each phase begins."""

    def __init__(self, stream: TextIO):
        self.stream, self.live = stream, stream.isatty()
        self.started = time.perf_counter()
        self.current: Phase | None = None
        self.since = self.started
        self.done = threading.Event()
        if self.live:
            threading.Thread(target=self._tick, daemon=True).start()

    def phase(self, phase: Phase) -> None:
        if phase.name not in ("grounding", "solving", "assigning"):
            return
        self.current, self.since = phase, time.perf_counter()
        if not self.live:
            self._say(f"{self._label(phase)}: {phase.name} (elapsed {self.since - self.started:.1f} s)")

    def attempt(self, attempt: Attempt) -> None:
        self.current = None
        if attempt.result == "improved":
            self._say(f"plan: makespan {attempt.horizon}, {attempt.note} ({attempt.seconds:.2f} s)")
            return
        note = f" {attempt.note}" if attempt.note else ""
        self._say(f"horizon {attempt.horizon}{note}: {attempt.result} ({attempt.seconds:.2f} s)")

    def close(self) -> None:
        self.done.set()
        if self.live:
            self.stream.write("\r\033[K")
            self.stream.flush()

    @staticmethod
    def _label(phase: Phase) -> str:
        return "task assignment" if phase.name == "assigning" else f"horizon {phase.horizon}"

    def _say(self, line: str) -> None:
        prefix = "\r\033[K" if self.live else ""
        self.stream.write(f"{prefix}{line}\n")
        self.stream.flush()

    def _tick(self) -> None:
        while not self.done.wait(0.5):
            phase = self.current
            if phase is not None:
                now = time.perf_counter()
                self.stream.write(f"\r\033[K{self._label(phase)}: {phase.name} {now - self.since:.0f} s "
                                  f"(elapsed {now - self.started:.0f} s)")
                self.stream.flush()


def _summary(outcome: Outcome, encoding: Encoding | None = None) -> None:
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
    lines += _verdict(outcome)
    lines.append(_figures(outcome))
    print("\n".join(lines), file=sys.stderr)


def _verdict(outcome: Outcome) -> list[str]:
    """What was found: the plan, the violations of a plan that breaks the rules, or why there
    is none (with the horizons refuted)."""
    if outcome.found:
        proof = "proven minimal" if outcome.minimal else "not proven minimal"
        return [f"plan: horizon {outcome.horizon} ({proof}), {len(outcome.plan)} actions, checked: valid"]
    if outcome.check is not None and not outcome.check.valid:
        errors = outcome.check.errors
        lines = [error.message for error in errors[:SHOWN_VIOLATIONS]]
        if len(errors) > SHOWN_VIOLATIONS:
            lines.append(f"... and {len(errors) - SHOWN_VIOLATIONS} more (asprilo check lists them all)")
        return lines + [f"no valid plan: the plan of makespan {outcome.plan.horizon} breaks the rules "
                        f"({len(errors)} violation{'s' * (len(errors) != 1)})"]
    lines = [{"none": "no plan exists", "limit": "no plan within the limits", "cancelled": "cancelled",
              "invalid": "no valid plan"}[outcome.status.value] + (f": {outcome.message}" if outcome.message else "")]
    if outcome.refuted and outcome.status.value == "limit":
        lines.append(f"refuted horizons {_spans(outcome.refuted)}: no plan is shorter than {outcome.proven_bound:g}")
    if outcome.status.value == "limit" and outcome.method == "asp":
        lines.append("for a plan fast (not proven minimal), try --method anytime")
    return lines


def _figures(outcome: Outcome) -> str:
    """The method's statistics in one line."""
    stats = outcome.stats
    if outcome.method == "flow":
        return f"max-flow {stats['solve_time']:.2f} s"
    if outcome.method == "anytime":
        return (f"first plan {stats.get('first_plan_seconds', 0):.2f} s, {len(outcome.history)} plans reported, "
                f"{stats.get('neighbourhoods', 0)} neighbourhoods tried")
    return (f"ground {stats['ground_time']:.2f} s, solve {stats['solve_time']:.2f} s, rules {stats['rules']}, "
            f"atoms {stats['atoms']}, choices {stats['choices']}, conflicts {stats['conflicts']}")


def report(outcome: Outcome) -> dict:
    """The outcome as plain data (``--json``)."""
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
        "proven_bound": outcome.proven_bound if outcome.proven_bound != float("inf") else None,
        "stats": outcome.stats,
        "assignment": outcome.assignment.facts if outcome.assignment is not None else None,
        "plan": [format_action(action) for action in outcome.plan.actions] if outcome.found else None,
        "message": outcome.message,
        **({"history": outcome.history} if outcome.method == "anytime" else {}),
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
