"""The ``check`` command: the checker's command line (:mod:`asprilo.checker.cli`) and
``--watch``, the student's edit-run loop in a terminal.

``check INSTANCE PLAN --watch`` checks, then checks again whenever the instance or the plan
is saved; with ``--encoding FILE...`` (several files after one flag, or the flag repeated,
with ``-c`` and clingo's options, as ``asprilo solve`` reads them) it solves with that
encoding instead, again whenever the instance or an encoding file (or a file one
``#include``\\ s) is saved, and checks the plan found.  Each run
prints a line with the time and what changed, then the violations (the first few) and the
verdict.  Bad input in a watched file is one line and the watch goes on; Ctrl-C ends it
(exit status 130).  The watch lives here, above the tools, because with ``--encoding`` it
solves (the checker is below the encodings); what it runs on every save is in
:mod:`asprilo.cli.reruns`, imported only with ``--watch``: a single check starts in a
blink, so this module imports what a verdict needs and no more.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from asprilo.arguments import loaded_variants, seconds_argument
from asprilo.checker import cli as checker_cli
from asprilo.errors import InputError
from asprilo.reader import read_instance_and_plan

if TYPE_CHECKING:  # the watch (and through it the writer, the solver) only with --watch: a check does without
    from .reruns import Rerun

#: options asprilo does not know are clingo's (for ``--watch --encoding``; refused otherwise)
CLINGO_OPTIONS = True
#: violations a re-check prints unless told otherwise, and seconds a re-solve may take
SHOWN_VIOLATIONS = 5
WATCH_TIME_LIMIT = 60.0

__doc__ = (checker_cli.__doc__ or "").rstrip() + f"""

Watching (the edit-run loop):
  check INSTANCE PLAN --watch             re-check whenever INSTANCE or PLAN is saved
  check INSTANCE [PLAN] --watch --encoding my.lp [-c lanes=2] [--configuration=crafty]
                                          re-solve with your encoding whenever INSTANCE, my.lp
                                          or a file it #includes is saved, and check the plan
                                          found (written to PLAN if given: a viz showing PLAN
                                          reloads it)
  Each run prints a line with the time and what changed, the first violations (--violations N,
  default {SHOWN_VIOLATIONS}) and the verdict; bad input is one line and the watch goes on; a solve still
  running when a file is saved again is cancelled; Ctrl-C ends the watch (exit status 130).
"""


def configure(parser: argparse.ArgumentParser) -> None:
    checker_cli.configure(parser)
    group = parser.add_argument_group("watching", "check --watch: check (or solve and check) again on every save")
    group.add_argument("--watch", action="store_true",
                       help="check again whenever the instance or the plan (or an --encoding file) is saved")
    group.add_argument("--encoding", action="extend", nargs="+", metavar="NAME|FILE",
                       help="with --watch: solve with this encoding (the files of your own, --encoding a.lp b.lp "
                            "or the flag repeated, after INSTANCE and PLAN; or a reference encoding by name) and "
                            "check the plan found")
    group.add_argument("-c", "--const", action="append", default=[], metavar="NAME=VALUE",
                       help="with --encoding: a constant for your encoding, as clingo's -c")
    group.add_argument("--horizon", type=int, metavar="H", help="with --encoding: solve at this makespan only")
    group.add_argument("--time-limit", type=seconds_argument, metavar="S",
                       help=f"with --encoding: seconds each solve may take (default {WATCH_TIME_LIMIT:g})")
    group.add_argument("--violations", type=_count, metavar="N",
                       help=f"with --watch: violations shown per run (default {SHOWN_VIOLATIONS})")


def run(args: argparse.Namespace) -> int:
    clingo_options = list(getattr(args, "clingo_options", None) or [])
    if not args.watch:
        _refuse_watch_options(args, clingo_options)
        return _check_once(args)
    from .watching import POLL, watch  # the polling loop: only for --watch
    rerun = _watched(args, clingo_options)
    watch(rerun.paths, rerun, poll=POLL)
    return 130  # watch() ends only by Ctrl-C (KeyboardInterrupt: the command line says 130 too)


def _check_once(args: argparse.Namespace) -> int:
    """``check INSTANCE PLAN``: the checker's command (:func:`asprilo.checker.cli.show`), with
    the plan read as the viewer reads it (:func:`asprilo.reader.read_instance_and_plan`): a plan
    made for another instance is one sentence and exit status 2 in both, not a page of
    violations here and one line there."""
    if args.plan is None:
        raise InputError("no plan given (check INSTANCE PLAN)")
    loaded_variants(args)  # before reading: the attributes they declare are data
    instance, plan = read_instance_and_plan(args.instance, args.plan, domain=args.domain)
    return checker_cli.show(instance, plan, args)


def _count(text: str) -> int:
    try:
        number = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if number < 0:
        raise argparse.ArgumentTypeError(f"must be 0 or more, got {number}")
    return number


def _refuse_watch_options(args: argparse.Namespace, clingo_options: list[str]) -> None:
    if args.violations is not None:
        raise InputError("--violations goes with --watch")
    _refuse_solve_options(args, clingo_options, "--watch --encoding")


def _refuse_solve_options(args: argparse.Namespace, clingo_options: list[str], where: str) -> None:
    """Options of a solve, without one to make."""
    if clingo_options:
        raise InputError(f"unrecognized arguments: {' '.join(clingo_options)} (clingo's options go with {where})")
    given = [flag for flag, value in (("--encoding", args.encoding), ("-c", args.const),
                                      ("--horizon", args.horizon is not None),
                                      ("--time-limit", args.time_limit is not None)) if value]
    if given:
        raise InputError(f"{given[0]} goes with {where}")


def _watched(args: argparse.Namespace, clingo_options: list[str]) -> Rerun:
    """What ``--watch`` runs on every save, its options checked before the first run."""
    if args.json:
        raise InputError("--json and --watch do not go together (a watch prints a few lines per run)")
    if "-" in (args.instance, args.plan):
        raise InputError("--watch watches files: standard input (-) is never saved")
    from .reruns import EncodingSolve, PlanCheck
    shown = SHOWN_VIOLATIONS if args.violations is None else args.violations
    variants = loaded_variants(args)  # before the first run reads the instance
    if not args.encoding:
        if args.plan is None:
            raise InputError("no plan given (check INSTANCE PLAN --watch, or --encoding FILE to solve)")
        _refuse_solve_options(args, clingo_options, "--encoding")
        _require_files([args.instance, args.plan])
        checking = PlanCheck(Path(args.instance), Path(args.plan), args.domain, shown)
        checking.variants = variants
        return checking
    from asprilo.encodings.choice import is_encoding_file
    from asprilo.encodings.own import program_files
    from asprilo.paths import input_file
    from asprilo.writer import check_output
    encodings = [value for value in args.encoding if is_encoding_file(value)]
    _require_files([args.instance])
    for encoding in encodings:  # a folder, a FIFO, a loop of links: refused in words
        input_file(encoding)
    check_output(args.plan, [args.instance, *program_files(encodings)])
    solver = EncodingSolve(Path(args.instance), None if args.plan is None else Path(args.plan), args.domain, shown,
                           args.encoding, args.const, clingo_options, args.horizon,
                           args.time_limit or WATCH_TIME_LIMIT)
    solver.variants = variants
    solver.validate()
    return solver


def _require_files(paths: Sequence[str]) -> None:
    """The files a watch starts on must be there (a name mistyped is no save to wait for)."""
    for path in paths:
        if not Path(path).exists():
            raise InputError("no such file", path)

