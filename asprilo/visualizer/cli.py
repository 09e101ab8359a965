"""Show a warehouse, animate a plan (valid or not), edit the layout; or export pictures and animations.

Exports need no window.

FILE is the instance, then plan files or clingo output (- = standard input).  One file may
hold both (e.g. clingo output that shows init/2 and occurs/3 atoms).  Without files, piped
standard input is read.

Examples:
  viz instance.lp plan.lp
  python -m clingo instance.lp encoding.lp | viz instance.lp -
  python -m clingo instance.lp encoding.lp | viz          (output shows init/2 and occurs/3)
  viz instance.lp plan.lp --export state.png --step 12
  viz instance.lp plan.lp --export plan.gif --frames 4 --speed 4
  viz instance.lp plan.lp --export strip.png --strip 3-8      (steps 3 to 8 side by side)
  viz --solver 5000 --simulator 5001          (watch asprilo serve solver/simulator live)
  viz instance.lp plan.lp --variant diagonal  (the rules of a variant: its moves, checks, gauges)

A plan is read as check reads it: the same warnings, and a plan for another instance is
refused in the same sentence (exit status 2).  An export of a plan that breaks rules is
written, then check's verdict line follows on stderr and the exit status is 1, as check's;
the window shows the verdict in its status bar (exit status 0 when it closes).
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import re
import signal
import sys
import traceback
from collections.abc import Iterator

from asprilo.arguments import add_variant_option, domain_argument, loaded_variants
from asprilo.errors import InputError
from asprilo.writer import check_output

from .state.display import INSTALL, window_problem


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("files", metavar="FILE", nargs="*", help="INSTANCE [PLAN ...]")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    add_variant_option(parser)
    parser.add_argument("--step", type=int, metavar="K",
                        help="show the state after step K (pictures: default 0, the initial state)")
    parser.add_argument("--record", metavar="RUN.json",
                        help="the run record of 'asprilo online --record': the Online panel shows its planner figures")
    group = parser.add_argument_group("export without a window")
    group.add_argument("--export", metavar="OUT",
                       help="write OUT and exit: .png, .jpg or .svg (one state), .gif or .mp4 (the whole plan); "
                            "a regular file, not an input")
    group.add_argument("--frames", type=int, default=1, metavar="N",
                       help="animation frames per step; N > 1 adds in-between frames (default 1)")
    group.add_argument("--speed", type=float, default=2.0, metavar="S",
                       help="animation speed in steps per second (default 2)")
    group.add_argument("--cell", type=int, metavar="PX",
                       help="pixels per cell (default: pictures 128, for slides; animations 48; "
                            "less for big warehouses)")
    group.add_argument("--no-caption", dest="caption", action="store_false",
                       help="pictures: leave out the line below the warehouse that says which state it shows")
    group.add_argument("--strip", type=strip_argument, metavar="FIRST-LAST",
                       help="with --export OUT.png or .jpg: the states after steps FIRST to LAST side by side, "
                            "each captioned, in rows (e.g. --strip 3-8)")
    group.add_argument("--columns", type=int, metavar="N",
                       help="panels per row of a strip (default: as many as fit in 2000 pixels)")
    online = parser.add_argument_group("online link (see asprilo serve)")
    online.add_argument("--solver", type=int, metavar="PORT",
                        help="connect to a solver: it plans step by step for the INSTANCE, "
                             "or for the simulator's world")
    online.add_argument("--simulator", type=int, metavar="PORT",
                        help="connect to a simulator as well: it says what the world is and when orders arrive")
    online.add_argument("--host", default="127.0.0.1", help="where solver and simulator run (default 127.0.0.1)")



def strip_argument(text: str) -> tuple[int, int]:
    """``3-8`` -> ``(3, 8)``: the first and the last step of a strip."""
    match = re.fullmatch(r"\s*(\d+)\s*-\s*(\d+)\s*", text)
    if match is None:
        raise argparse.ArgumentTypeError(f"'{text}' is not FIRST-LAST, two steps such as 3-8")
    return int(match[1]), int(match[2])


def run(args: argparse.Namespace) -> int:
    _check_options(args)
    check_output(args.export, args.files)  # before any work: a regular file, none of the inputs
    args.run_record = None
    if args.record:
        from asprilo.online.record import read_record
        args.run_record = read_record(args.record)
    if args.export:
        os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")  # never needs a screen
    else:
        problem = window_problem()  # before Qt starts: it would abort without saying why
        if problem is not None:
            raise InputError(problem)
    _load_qt()
    from .state.loading import command_line_inputs, load_scenario
    variants = loaded_variants(args)  # before reading: the attributes they declare are data
    instance, plans = command_line_inputs(args.files)
    scenario = load_scenario(instance, plans, args.domain, variants) if instance else None
    if args.export:
        if scenario is None:
            raise InputError("nothing to export: give an INSTANCE file or pipe facts into viz")
        return _export(args, scenario)
    return _show(args, scenario)


def _load_qt() -> None:
    """Import Qt, or say which system library it lacks."""
    try:
        import PyQt5.QtWidgets  # noqa: F401
    except ImportError as error:
        raise InputError(f"Qt cannot be loaded ({error}); on Debian or Ubuntu: {INSTALL}") from None


def _check_options(args: argparse.Namespace) -> None:
    if args.record and args.export:
        raise InputError("--record shows a run record's figures in the window's Online panel; "
                         "leave it out with --export")
    for option, value, least in (("--frames", args.frames, 1), ("--cell", args.cell, 1), ("--step", args.step, 0)):
        if value is not None and value < least:
            raise InputError(f"{option} must be at least {least}, got {value}")
    if not 0 < args.speed < math.inf:  # (nan too)
        raise InputError(f"--speed must be a positive number of steps per second, got {args.speed:g}")
    if args.simulator is not None and args.solver is None:
        raise InputError("--simulator goes with --solver: the simulator's world needs a solver to plan it")
    if args.solver is not None and args.simulator is None and not args.files:
        raise InputError("--solver needs an INSTANCE to plan for, or a --simulator to say what the world is")
    if args.solver is not None and args.export:
        raise InputError("--solver and --export do not go together: an online session runs in the window")
    _check_strip(args)


def _check_strip(args: argparse.Namespace) -> None:
    if args.strip is not None and not args.export:
        raise InputError("--strip goes with --export OUT.png (or .jpg): a strip is a picture")
    if args.strip is not None and args.step is not None:
        raise InputError("--strip FIRST-LAST names its steps; leave out --step")
    if args.columns is not None and args.strip is None:
        raise InputError("--columns goes with --strip: the panels per row of a strip")
    if args.columns is not None and args.columns < 1:
        raise InputError(f"--columns must be at least 1, got {args.columns}")


def _export(args: argparse.Namespace, scenario) -> int:
    if args.strip is not None:
        return _export_strip(args, scenario)
    from .export.render import render

    def progress(done: int, total: int) -> None:
        if done == total or done % 50 == 0:
            print(f"\rrendering frame {done}/{total}", end="\n" if done == total else "", file=sys.stderr)

    written = render(scenario.instance, scenario.plan, args.export, _domain(args, scenario), args.step,
                     args.frames, args.speed, args.cell, progress, args.caption)
    print(f"wrote {args.export}: {written}", file=sys.stderr)
    return _verdict(args, scenario)


def _domain(args: argparse.Namespace, scenario):
    """The domain the scenario is shown in: ``--domain`` or detected, changed by ``--variant``."""
    from .state.loading import shown_domain
    return shown_domain(scenario, loaded_variants(args))


def _verdict(args: argparse.Namespace, scenario) -> int:
    """After an export: a plan that breaks rules (the variants' too) is said in ``check``'s
    verdict line, with its exit status 1 (the picture is written all the same); a valid plan,
    or none (an instance shown alone), is 0."""
    if not scenario.plan_sources and not len(scenario.plan):
        return 0
    from asprilo.checker import check
    from asprilo.checker.cli import verdict
    report = check(scenario.instance, scenario.plan, _domain(args, scenario))
    if report.valid:
        return 0
    print(f"{verdict(report, detected=scenario.domain is None)}; check INSTANCE PLAN lists them", file=sys.stderr)
    return 1


def _export_strip(args: argparse.Namespace, scenario) -> int:
    from .export.strip import export_strip
    first, last = args.strip
    written = export_strip(scenario.instance, scenario.plan, args.export, first, last, _domain(args, scenario),
                           args.columns, args.cell)
    print(f"wrote {args.export}: {written}", file=sys.stderr)
    return _verdict(args, scenario)


def _show(args: argparse.Namespace, scenario) -> int:
    from .export.render import application
    from .jobs.job import wait_for_jobs
    from .window import MainWindow
    app = application()
    window = MainWindow()
    window.state.document.follow_variants(loaded_variants(args))
    window.panels.online.set_record(args.run_record)
    sys.excepthook = report_exceptions_to(window)
    if scenario is not None:
        window.show_scenario(scenario)
        window.files.remember(scenario)
        if args.step:
            if args.step > window.track.horizon:
                raise InputError(f"--step {args.step} lies beyond the plan, whose last step is "
                                 f"{window.track.horizon}")
            window.go_to(args.step)
    window.show()
    if args.solver is not None:
        window.live.connect_to(args.host, args.solver, args.simulator)
    with _quitting_on_interrupts(app) as interrupted:
        code = app.exec_()
    wait_for_jobs()  # a cancelled generation may still run
    return 130 if interrupted else code


@contextlib.contextmanager
def _quitting_on_interrupts(app) -> Iterator[list[int]]:
    """Ctrl-C ends the viewer, and so do SIGTERM and SIGHUP (the command line hands them to
    the Ctrl-C handler): the event loop quits, the yielded list gets the signal.  Qt's event
    loop runs no Python while it waits, so a timer gives Python a moment to see a signal."""
    from PyQt5.QtCore import QTimer

    interrupted: list[int] = []

    def stop(number: int, _frame) -> None:
        interrupted.append(number)
        app.quit()

    previous = signal.signal(signal.SIGINT, stop)
    timer = QTimer()
    timer.timeout.connect(lambda: None)
    timer.start(200)
    try:
        yield interrupted
    finally:
        timer.stop()
        signal.signal(signal.SIGINT, previous)


def report_exceptions_to(window):
    """An exception hook that keeps the window alive: the traceback goes to standard error,
    a dialog says what broke (without a hook of its own PyQt would abort the viewer)."""
    def report(kind, value, trace) -> None:
        traceback.print_exception(kind, value, trace, file=sys.stderr)
        window.state.report_error(f"Something went wrong inside the viewer ({kind.__name__}: {value}). "
                                  "It goes on; the details are on standard error.")
    return report
