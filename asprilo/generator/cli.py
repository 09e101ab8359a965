"""Generate instances with multi-shot ASP: random, structured (-H) and template (-T) layouts, YAML batches (-j).

The generator is a compartmentalised ASP program, solved stage by stage.

Layouts: random (default; -n for a partial grid with gaps), structured (-H: storage zones
surrounded by highways) and templates (-T: populate a hand-made layout).  The flags are those
of the original asprilo generator, so the paper's calls run unchanged.

Examples:
  gen -x 19 -y 9 -X 5 -Y 2 -p 3 -s 45 -r 6 -P 180 -u 540 -o 12 -H
  gen -x 11 -y 6 -X 4 -Y 2 -p 1 -s 16 -P 16 -u 16 -H --prs 1 -r 2 -o 2 -N 30 -d small
  gen -x 20 -y 20 -n 360 -p 4 -r 8 --sc 40 -R -P 20 -u 100 -o 10 -C
  gen -T layout.lp -r 5 -s 20 -P 10 -u 40 -o 5
  gen -j benchmarks/paper-m.yml -d instances/paper-m --skip-existing

Exit status: 0 instances written, 1 no instance (unsatisfiable request or time limit),
2 bad input (inconsistent options, bad template or batch file).
"""

from __future__ import annotations

import argparse
import warnings
from collections.abc import Mapping
from typing import Any

from asprilo import __version__
from asprilo.arguments import domain_argument
from asprilo.domain import DEFAULT
from asprilo.errors import InputError, InputWarning

from .config import parse_values
from .options import ALWAYS_ON, BY_NAME, OPTIONS, REFUSED, refuse_original
from .runs import Job, batch_jobs, command_job, run_jobs

_TYPES = {"int": int, "float": float, "str": str, "domain": domain_argument}


def configure(parser: argparse.ArgumentParser) -> None:
    groups: dict[str, argparse._ArgumentGroup] = {}
    for option in OPTIONS:
        group = groups.get(option.group) or groups.setdefault(option.group, parser.add_argument_group(option.group))
        kwargs: dict[str, Any] = {"dest": option.name, "help": option.help_text, "default": argparse.SUPPRESS}
        if option.kind == "flag":
            kwargs["action"] = "store_true"
        elif option.kind == "paths":  # repeatable: -T a.lp -T b.lp is -T a.lp b.lp
            kwargs.update(nargs="+", action="extend", metavar=option.metavar)
        else:
            kwargs.update(type=_TYPES[option.kind], metavar=option.metavar)
        group.add_argument(*option.flags, **kwargs)
    batch = groups["output and batches"]
    batch.add_argument("-j", "--batch", metavar="FILE",
                       help="run the configurations of a YAML batch file; options given here apply to "
                            "every run and override the file's")
    batch.add_argument("-V", "--verbose", action="store_true",
                       help="report each instance's stages (rounds and seconds) on stderr")
    batch.add_argument("-q", "--quiet", action="store_true",
                       help="no progress bar and no closing line saying where the files went")
    parser.add_argument("-v", "--version", action="version", version=f"gen (asprilo) {__version__}")
    _original_flags(parser)


class _Refused(argparse.Action):
    """Notes a flag of the original generator that is refused (after parsing, as bad input)."""

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        namespace.refused = option_string


def _original_flags(parser: argparse.ArgumentParser) -> None:
    """The original's flags that old command lines use: refused with advice, or taken (--random)."""
    for flags in REFUSED:
        parser.add_argument(*flags, action=_Refused, nargs="*", dest="refused", default=None, help=argparse.SUPPRESS)
    for flag in ALWAYS_ON:
        parser.add_argument(flag, action="store_true", help=argparse.SUPPRESS)


def run(args: argparse.Namespace) -> int:
    if args.refused:
        refuse_original(args.refused)
    given = {name: value for name, value in vars(args).items() if name in BY_NAME}
    values = parse_values(given)
    jobs = batch_jobs(args.batch, values) if args.batch else [command_job(values)]
    if run_jobs(jobs, args.verbose, quiet=args.quiet):
        return 1
    _warn_idle(jobs)
    return 0


def _warn_idle(jobs: list[Job]) -> None:
    """After the instances are made: one warning when what a run made has nothing to do -- no
    orders (an instance that is solved by doing nothing, and read as domain M), or no robots
    to fulfil them.  A warehouse to add orders to later (``-T FILE -o N``) is made so on
    purpose, hence a warning only; runs with a template (-T) take its orders and robots."""
    idle: list[tuple[Job, str]] = []
    for job in jobs:
        config: Mapping[str, Any] = vars(job.config)  # (a dataclass made at run time: fields by name)
        if config["templates"] or config["template"] is not None:
            continue
        domain = config["domain"] or DEFAULT
        aligned = domain.generation is not None and domain.generation.aligned
        if not config["orders"] and not (aligned and config["robots"]):
            idle.append((job, "no orders: the instance has nothing to do (give -o N; "
                              "or add orders later with -T FILE -o N)"))
        elif not config["robots"]:
            idle.append((job, "no robots: nobody can fulfil the orders (give -r N)"))
    if not idle:
        return
    (job, what), more = idle[0], len(idle) - 1
    if more:
        what += f" (and {more} more run{'s' * (more != 1)} of the batch)"
    warnings.warn(InputWarning(str(InputError(what, *job.where))), stacklevel=2)
