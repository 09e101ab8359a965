"""Run the whole tool chain on a small warehouse: generate, solve, check, render.

Generates a structured 11x6 warehouse with three robots (domain A: shelves hold product
units, orders ask for them at picking stations), finds a plan of minimal makespan with
the reference encoding, checks it with the ASP checker and draws the final state and an
animation.  Everything lands in one folder (default: asprilo-demo/), which must be new or
empty unless --force is given.

Examples:
  asprilo demo
  asprilo demo --domain m --seed 7 -o my-demo
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from asprilo.arguments import domain_argument
from asprilo.domain import DEFAULT, Domain, domains
from asprilo.errors import InputError
from asprilo.writer import format_instance, format_plan, write_text


def _demonstrated() -> list[Domain]:
    """The domains with an exercise-size scenario, which the reference encodings solve in seconds."""
    return [domain for domain in domains() if domain.generation is not None and domain.generation.exercise]


def _scenario(domain: Domain) -> dict:
    """The generator's options for the domain's exercise-size scenario."""
    aligned = {"domain": domain} if domain.generation.aligned else {}
    return {**domain.generation.exercise, **aligned}


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("-o", "--output", default="asprilo-demo", metavar="DIR",
                        help="folder for the instance, plan and pictures (default: asprilo-demo)")
    parser.add_argument("--domain", type=domain_argument, default=DEFAULT,
                        help=f"{'|'.join(d.value for d in _demonstrated())} (default: {DEFAULT.value})")
    parser.add_argument("--seed", type=int, default=1, help="generator seed (default: 1)")
    parser.add_argument("--time-limit", type=float, default=120, metavar="S",
                        help="seconds the solver may take (default: 120)")
    parser.add_argument("--no-pictures", action="store_true", help="skip the PNG and GIF")
    parser.add_argument("--force", action="store_true", help="write into the folder even if it holds files")


def _say(text: str) -> None:
    print(text, flush=True)


def run(args: argparse.Namespace) -> int:
    from asprilo.checker import check
    from asprilo.encodings import solve
    from asprilo.encodings.solving.minimality import proof
    from asprilo.generator import GeneratorConfig, generate

    domain: Domain = args.domain
    if domain not in _demonstrated():
        *others, last = [d.value for d in _demonstrated()]
        covered = f"{', '.join(others)} and {last}"
        raise InputError(f"the demo covers domains {covered}, not {domain.value}")
    folder = Path(args.output)
    _check_folder(folder, args.force)
    started = time.perf_counter()

    config = GeneratorConfig(**_scenario(domain))
    generated = generate(config, 1, args.seed, command=f"asprilo demo --domain {domain.value} --seed {args.seed}")[0]
    instance = generated.instance
    instance_path = folder / generated.file_name()
    write_text(instance_path, format_instance(instance, generated.header))
    c = instance.counts()
    _say(f"1. generated  {instance_path}: {c['x']}x{c['y']} floor, {c['robots']} robots, "
         f"{c['shelves']} shelves, {c['stations']} picking stations, {c['orders']} orders "
         f"({time.perf_counter() - started:.1f} s)")

    step = time.perf_counter()
    outcome = solve(instance, domain=domain, encoding="plain", time_limit=args.time_limit,
                    on_progress=lambda attempt: _say(f"   horizon {attempt.horizon}: {attempt.result} "
                                                     f"({attempt.seconds:.1f} s)"))
    if not outcome.found:
        _say(f"2. solving    no plan within {args.time_limit:.0f} s ({outcome.status.value}) {outcome.message}")
        return 1
    plan_path = folder / "plan.lp"
    write_text(plan_path, format_plan(outcome.plan))
    _say(f"2. solved     {plan_path}: horizon {outcome.horizon} ({proof(outcome)}), {len(outcome.plan)} actions "
         f"({time.perf_counter() - step:.1f} s)")

    report = check(instance, outcome.plan, domain)
    verdict = "valid" if report.valid else f"INVALID: {len(report.errors)} violations"
    _say(f"3. checked    the plan is {verdict} in domain {domain.label}")
    for error in report.errors[:5]:
        _say(f"   {error.message}")

    if not args.no_pictures:
        _render(instance, outcome.plan, folder, domain)
    _say(f"done in {time.perf_counter() - started:.1f} s; look at it with:  viz {instance_path} {plan_path}")
    return 0 if report.valid else 1


def _check_folder(folder: Path, force: bool) -> None:
    """The demo writes into a new or empty folder, or anywhere with ``--force``."""
    if folder.exists() and not folder.is_dir():
        raise InputError("is not a folder", str(folder))
    try:
        holds_files = folder.is_dir() and any(folder.iterdir())
    except OSError as error:
        raise InputError(f"cannot be read ({error.strerror or error})", str(folder)) from None
    if holds_files and not force:
        raise InputError("the folder holds files already; choose another (-o DIR) or add --force", str(folder))


def _render(instance, plan, folder: Path, domain: Domain) -> None:
    """Export the final state as PNG and the plan as GIF, without opening a window."""
    from asprilo.visualizer import render
    picture, animation = folder / "final.png", folder / "plan.gif"
    render(instance, plan, picture, domain, step=plan.horizon)
    render(instance, plan, animation, domain, frames=4)
    _say(f"4. rendered   {picture} (the final state) and {animation} (the whole plan)")
