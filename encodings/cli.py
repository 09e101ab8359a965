"""Find a plan for an instance with a reference encoding (or max-flow for M/Md).

Without --horizon the search starts at a lower bound of the makespan and goes up one step
at a time, so the first plan found has minimal makespan.  --method anytime instead finds a
plan fast and then better ones until the time limit (default 60 s) or the lower bound;
each one is checked and reported with its gap to the bound.  The plan is checked, then
printed as occurs/3 facts (stdout, or -o PLAN); a summary goes to stderr.
Exit status: 0 plan found, 1 no plan within the limits, 2 bad input.

Examples:
  asprilo solve instance.lp
  asprilo solve instance.lp --encoding clingcon --time-limit 60 -o plan.lp
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

from asprilo.arguments import domain_argument
from asprilo.errors import InputError
from asprilo.writer import format_action, format_plan, write_text

from .registry import ENCODINGS
from .solve import Attempt, Outcome, solve


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="INSTANCE", nargs="?", help="instance file (- = stdin)")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    parser.add_argument("--encoding", default="plain", metavar="NAME",
                        help="reference encoding (default: plain; --list shows them)")
    parser.add_argument("--horizon", type=int, metavar="H", help="solve at this makespan only")
    parser.add_argument("--assign", action="store_true",
                        help="compute a task assignment first and plan along it")
    parser.add_argument("--time-limit", type=float, metavar="S", help="stop after S seconds")
    parser.add_argument("--method", choices=("asp", "flow", "anytime"), default="asp",
                        help="asp: an encoding (default); flow: exact max-flow solver for M/Md; "
                             "anytime: a plan fast, then better ones")
    parser.add_argument("-o", "--output", metavar="PLAN", help="write the plan to this file")
    parser.add_argument("--json", action="store_true", help="print a JSON report instead of the plan")
    parser.add_argument("--list", action="store_true", help="list the encodings and exit")


def run(args: argparse.Namespace) -> int:
    if args.list:
        for encoding in ENCODINGS:
            theory = f" [{encoding.theory}]" if encoding.theory else ""
            print(f"{encoding.domain.value:<3} {encoding.name:<13} {encoding.summary}{theory}")
        return 0
    if args.instance is None:
        raise InputError("no instance given (asprilo solve INSTANCE)")
    if args.time_limit is not None and args.time_limit <= 0:
        raise InputError(f"--time-limit must be positive, got {args.time_limit:g}")
    outcome = solve(args.instance, args.domain, args.encoding, args.horizon, args.assign,
                    args.time_limit, args.method, on_progress=_progress)
    if outcome.plan is not None and outcome.found and args.output:
        write_text(args.output, format_plan(outcome.plan))
    _summary(outcome)
    if args.json:
        print(json.dumps(report(outcome), indent=2))
    elif outcome.found and not args.output:
        sys.stdout.write(format_plan(outcome.plan))
    return 0 if outcome.found else 1


def _progress(attempt: Attempt) -> None:
    if attempt.result == "improved":
        print(f"plan: makespan {attempt.horizon}, {attempt.note} ({attempt.seconds:.2f} s)",
              file=sys.stderr, flush=True)
        return
    note = f" {attempt.note}" if attempt.note else ""
    print(f"horizon {attempt.horizon}{note}: {attempt.result} ({attempt.seconds:.2f} s)",
          file=sys.stderr, flush=True)


def _summary(outcome: Outcome) -> None:
    stats = outcome.stats
    lines = [f"domain {outcome.domain.label}, method {outcome.method}, encoding {outcome.encoding}, "
             f"lower bound {outcome.lower_bound:g}"]
    if outcome.assignment is not None:
        state = "optimal" if outcome.assignment.optimal else "best found"
        lines.append(f"assignment ({state}, cost {outcome.assignment.cost}): "
                     + " ".join(outcome.assignment.facts))
    if outcome.found:
        proof = "proven minimal" if outcome.minimal else "not proven minimal"
        lines.append(f"plan: horizon {outcome.horizon} ({proof}), {len(outcome.plan)} actions, checked: valid")
    else:
        lines.append({"none": "no plan exists", "limit": "no plan within the limits",
                      "cancelled": "cancelled", "invalid": "no valid plan"}[outcome.status.value]
                     + (f": {outcome.message}" if outcome.message else ""))
    if outcome.method == "flow":
        lines.append(f"max-flow {stats['solve_time']:.2f} s")
    elif outcome.method == "anytime":
        lines.append(f"first plan {stats.get('first_plan_seconds', 0):.2f} s, {len(outcome.history)} plans reported, "
                     f"{stats.get('neighbourhoods', 0)} neighbourhoods tried")
    else:
        lines.append(f"ground {stats['ground_time']:.2f} s, solve {stats['solve_time']:.2f} s, "
                     f"rules {stats['rules']}, atoms {stats['atoms']}, "
                     f"choices {stats['choices']}, conflicts {stats['conflicts']}")
    print("\n".join(lines), file=sys.stderr)


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
        "horizons_tried": [attempt.__dict__ for attempt in outcome.horizons_tried],
        "stats": outcome.stats,
        "assignment": outcome.assignment.facts if outcome.assignment is not None else None,
        "plan": [format_action(action) for action in outcome.plan.actions] if outcome.found else None,
        "message": outcome.message,
        **({"history": outcome.history} if outcome.method == "anytime" else {}),
    }
