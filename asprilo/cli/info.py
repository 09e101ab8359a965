"""Summarise an instance (and a plan): counts, standard file name, domain, horizon.

With --variant, the attributes the variant declares (a robot's energy, say) are listed too;
without it, facts asprilo does not know are named in one warning and kept.

Examples:
  asprilo info instance.lp
  asprilo info instance.lp plan.lp --json
  asprilo info instance.lp --variant energy
  python -m clingo instance.lp encoding.lp | asprilo info instance.lp -
"""

from __future__ import annotations

import argparse
import json
from collections import Counter

from asprilo.arguments import add_variant_option, chosen_domain, domain_argument, loaded_variants
from asprilo.domain import Domain, detect_domain
from asprilo.facts import format_value
from asprilo.model import Instance, Plan
from asprilo.reader import read_instance, read_instance_and_plan


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="INSTANCE", help="instance file (- = stdin)")
    parser.add_argument("plan", metavar="PLAN", nargs="?", help="plan file or clingo output (- = stdin)")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    add_variant_option(parser)
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")


def summary(args: argparse.Namespace) -> dict:
    loaded_variants(args)  # before reading: the attributes they declare are data
    if args.plan is None:
        instance, plan = read_instance(args.instance), None
    else:
        instance, plan = read_instance_and_plan(args.instance, args.plan)
    counts = instance.counts()
    report = {
        "name": instance.file_name(),
        "counts": counts,
        "order_lines": sum(len(order.lines) for order in instance.orders.values()),
        "domain": _domain(args, instance, plan).value,
        "domain_detected": args.domain is None,
        "labelled_robots": len(instance.assignment),
        "attributes": _attributes(instance),
    }
    if plan is not None:
        report["horizon"] = plan.horizon
        report["actions"] = dict(sorted(Counter(action.name for action in plan.actions).items()))
    return report


def _domain(args: argparse.Namespace, instance: Instance, plan: Plan | None) -> Domain:
    """``--domain`` or the one detected, changed by ``--variant``."""
    domain = chosen_domain(args, args.domain or detect_domain(instance, plan))
    assert domain is not None  # one was given or detected
    return domain


def _attributes(instance: Instance) -> dict[str, dict[str, dict[str, object]]]:
    """The declared attributes by kind, then attribute, then object id (as text, for JSON)."""
    table: dict[str, dict[str, dict[str, object]]] = {}
    for (kind, ident), values in sorted(instance.attributes.items()):
        for attribute, value in sorted(values.items()):
            table.setdefault(kind, {}).setdefault(attribute, {})[str(ident)] = value
    return table


def run(args: argparse.Namespace) -> int:
    report = summary(args)
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    c = report["counts"]
    domain = Domain.parse(report["domain"]).label + (" (detected)" if report["domain_detected"] else "")
    print(f"instance: {c['x']}x{c['y']} grid, {c['nodes']} nodes, {c['highways']} highways")
    print(f"objects:  {c['robots']} robots, {c['shelves']} shelves, {c['stations']} picking stations, "
          f"{c['destinations']} destinations")
    print(f"stock:    {c['products']} products, {c['units']} units; "
          f"{c['orders']} orders with {report['order_lines']} lines")
    print(f"name:     {report['name']}")
    print(f"domain:   {domain}")
    for kind, attributes in report["attributes"].items():
        for attribute, values in attributes.items():
            listed = ", ".join(f"{kind} {ident}: {format_value(value)}" for ident, value in values.items())
            print(f"{attribute + ':':<9} {listed}")
    if report["labelled_robots"]:
        print(f"labelled: {report['labelled_robots']} robots have an assigned goal")
    if "horizon" in report:
        kinds = ", ".join(f"{count} {name}" for name, count in report["actions"].items()) or "none"
        print(f"plan:     horizon {report['horizon']}, {sum(report['actions'].values())} actions ({kinds})")
    return 0
