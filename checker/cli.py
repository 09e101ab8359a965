"""Check a plan with the ASP checker: every broken rule in plain words, then a summary and
the plan's metrics (horizon, actions, sum of costs, idle steps, orders fulfilled, lower
bounds and the ratios plan/bound).

Exit status: 0 the plan is valid, 1 it is not, 2 bad input.

Examples:
  check instance.lp plan.lp
  check instance.lp plan.lp --domain b --json
  python -m clingo instance.lp encoding.lp | check instance.lp -
"""

from __future__ import annotations

import argparse
import json

from asprilo.arguments import domain_argument
from asprilo.errors import InputError
from asprilo.limits import require_plan_fits
from asprilo.reader import read_instance, read_plan

from . import Report, check


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="INSTANCE", help="instance file (- = stdin)")
    parser.add_argument("plan", metavar="PLAN", nargs="?", help="plan file or clingo output (- = stdin); "
                        "instance facts in it are ignored (with --watch --encoding: where the plan found "
                        "is written, if given)")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")


def run(args: argparse.Namespace) -> int:
    if args.plan is None:
        raise InputError("no plan given (check INSTANCE PLAN)")
    instance, plan = read_instance(args.instance), read_plan(args.plan)
    try:
        require_plan_fits(instance, plan)
    except InputError as error:
        raise error.at(args.plan) from None
    report = check(instance, plan, args.domain)
    if args.json:
        print(json.dumps(report.as_json(), indent=2))
    else:
        print(summary(report, detected=args.domain is None))
    return 0 if report.valid else 1


def summary(report: Report, detected: bool = False) -> str:
    """One line per violation, then the verdict and the metrics."""
    lines = [error.message for error in report.errors]
    lines.append(verdict(report, detected))
    m = report.metrics
    actions = ", ".join(f"{n} {name}" for name, n in m["actions"].items()) or "none"
    lines.append(f"actions: {sum(m['actions'].values())} ({actions}); sum of costs {m['sum_of_costs']}, "
                 f"idle steps {m['idle_steps']}")
    if "destinations" in m:
        lines.append(f"destinations reached: {m['destinations_reached']} of {m['destinations']}")
    else:
        lines.append(f"orders fulfilled: {m['orders_fulfilled']} of {m['orders']}")
    lines.append("lower bounds: " + "; ".join(_bound(m, name, word) for name, word in
                                              (("makespan", "makespan"), ("sum_of_costs", "sum of costs"))
                                              if f"{name}_bound" in m))
    return "\n".join(lines)


def verdict(report: Report, detected: bool = False) -> str:
    """The verdict line: ``valid plan (domain A, horizon 12)`` or ``invalid plan: 3 violations (...)``."""
    domain = report.domain.label + (" (detected)" if detected else "")
    count = len(report.errors)
    words = "valid plan" if report.valid else f"invalid plan: {count} violation{'s' * (count != 1)}"
    return f"{words} (domain {domain}, horizon {report.horizon})"


def _bound(metrics: dict, name: str, word: str) -> str:
    bound, ratio = metrics[f"{name}_bound"], metrics[f"{name}_ratio"]
    if bound is None:
        return f"{word} none (the goal cannot be reached)"
    return f"{word} {bound}" + (f" (plan/bound {ratio:.2f})" if ratio is not None else "")
