"""Check a plan with the ASP checker: broken rules in plain words, metrics, lower bounds; --watch: again on every save.

Every broken rule is said in plain words, then a summary and the plan's metrics (horizon,
actions, sum of costs, idle steps, orders fulfilled, lower bounds and the ratios plan/bound).

The lower bounds shown are the cheap ones (milliseconds) unless --bound strong asks for the
strongest (what solve starts from; up to seconds on A/B/C, printed after the verdict); the
line says which, and so does "bounds" in the JSON's metrics.

Exit status: 0 the plan is valid, 1 it is not, 2 bad input.

Examples:
  check instance.lp plan.lp
  check instance.lp plan.lp --bound strong
  check instance.lp plan.lp --domain b --json
  python -m clingo instance.lp encoding.lp | check instance.lp -
"""

from __future__ import annotations

import argparse

from asprilo.arguments import add_variant_option, chosen_domain, domain_argument
from asprilo.domain import detect_domain
from asprilo.model import Instance, Plan

from . import STRENGTHS, Report, Strength, check
from .report import add_bounds


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="INSTANCE", help="instance file (- = stdin)")
    parser.add_argument("plan", metavar="PLAN", nargs="?", help="plan file or clingo output (- = stdin); "
                        "instance facts in it are ignored (with --watch --encoding: where the plan found "
                        "is written, if given)")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    add_variant_option(parser)
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.add_argument("--bound", choices=STRENGTHS, default="cheap",
                        help="the lower bounds shown: cheap (default: milliseconds) or strong (the strongest, "
                             "as solve computes them: up to seconds on A/B/C, shown after the verdict)")


def show(instance: Instance, plan: Plan, args: argparse.Namespace) -> int:
    """Check ``plan`` on ``instance`` (both read) as the options ``args`` say (``domain``,
    ``json``, ``bound``), print the report and return the exit status: the verdict and the
    violations first, then the bounds (``--bound strong``: when they come)."""
    strength: Strength = "strong" if getattr(args, "bound", None) == "strong" else "cheap"
    detected = args.domain is None
    domain = chosen_domain(args, detect_domain(instance, plan) if detected else None)
    if args.json:
        import json  # only --json prints JSON
        report = check(instance, plan, domain, bound=strength)
        print(json.dumps(report.as_json(), indent=2))
    elif strength == "cheap":
        report = check(instance, plan, domain, bound=strength)
        print(summary(report, detected=detected))
    else:
        report = check(instance, plan, domain, bound=None)
        print(summary(report, detected=detected), flush=True)
        if report.domain.bound is not None:  # else the summary said there is none
            add_bounds(report, instance, strength)
            print(bound_line(report.metrics))
    return 0 if report.valid else 1


def summary(report: Report, detected: bool = False) -> str:
    """One line per violation, then the verdict and the metrics, the bounds last
    (:func:`bound_line`) where the metrics have them."""
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
    if m.get("bounds") == "none":
        lines.append(f"lower bounds: none known for {report.domain.label} (its rules may allow shorter plans than "
                     f"those of {report.domain.label.split('+')[0]})")
    elif "bounds" in m:
        lines.append(bound_line(m))
    return "\n".join(lines)


#: what the bound line says of the bounds it shows
_WHICH = {"cheap": " (cheap; --bound strong for the strongest)", "strong": " (the strongest)", "given": ""}


def bound_line(metrics: dict) -> str:
    """``lower bounds (cheap; --bound strong for the strongest): makespan 17 (plan/bound 1.71)``."""
    return f"lower bounds{_WHICH[metrics['bounds']]}: " + "; ".join(
        _bound(metrics, name, word) for name, word in (("makespan", "makespan"), ("sum_of_costs", "sum of costs"))
        if f"{name}_bound" in metrics)


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
