"""Run a warehouse online without a window: orders released over time, a planner asked for the next actions.

The world is carried out step by step (asprilo/online/run.py): orders are revealed at their
release step, the planner plans from the state the world is in when orders arrived (or every
K steps: --replan K), within --budget seconds a call.  The world takes a step every
--step-seconds of the planner's time: robots stand still while the planner thinks, and those
waiting steps are counted.  The run ends after --steps steps, or once every order is released
and done.

Release steps: the instance's own (init(object(order,O),value(release,Step)), SPEC.md), or
--at STEP:ORDER[,ORDER...] (repeatable) or --every K (orders in id order, one every K steps
from step 0) instead; orders not named are known from the start.  --scenario FILE writes the
instance with the release steps used, so that `check FILE PLAN` checks them too.  With --live
the plan file (-o) is rewritten every few steps while the run goes, so that the viewer follows
it: viz SCENARIO PLAN (File > Reload on save, on by default).

Output: the plan carried out (occurs/3 facts: stdout, or -o PLAN), the figures on stderr
(throughput in lines and units per 100 steps beside the ceiling no planner can beat, order
latency, planner time per call, waiting steps; --json: on stdout as JSON), and with --record
FILE the run record (releases, planner calls, waiting steps, the figures) as JSON.  Progress
every 100 steps on stderr; Ctrl-C (SIGTERM, SIGHUP) ends the run after the step under way and
keeps what ran (exit status 130).

Examples:
  asprilo online instance.lp --every 4
  asprilo online instance.lp --at 3:2 --at 8:3,4 --planner asp -o run.lp
  asprilo online instance.lp --every 2 --steps 1000 --budget 1 --record run.json --json
  asprilo online m-instance.lp --every 2 --planner multishot [--encoding my-online.lp]
"""

from __future__ import annotations

import argparse
import json
import sys
import threading

from asprilo.arguments import chosen_domain, domain_argument, seconds_argument
from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.exits import INTERRUPTED, stopping_on_interrupt
from asprilo.model import Instance, Plan
from asprilo.reader import read_instance
from asprilo.writer import check_output, format_instance, format_plan, write_text

from .ceiling import Ceiling, ceiling
from .metrics import Metrics, counted, measure
from .planner import Planner, encodings_planner, release_steps
from .planning import FromScratch, multishot
from .record import figures, record
from .run import OnlineRun, run_online, scenario_of

#: steps between two progress lines
PROGRESS_EVERY = 100
#: steps between two writes of the plan so far (--live)
LIVE_EVERY = 5


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("instance", metavar="SCENARIO", help="the instance (its orders are released over time)")
    released = parser.add_mutually_exclusive_group()
    released.add_argument("--at", action="append", default=[], metavar="STEP:ORDER[,ORDER...]",
                          help="release these orders at STEP (repeatable)")
    released.add_argument("--every", type=_positive, metavar="K", help="release one order every K steps, in id order")
    parser.add_argument("--steps", type=_positive, metavar="N", help="run N steps (default: until every order is done)")
    parser.add_argument("--planner", choices=("anytime", "asp", "multishot"), default="anytime",
                        help="anytime: the anytime planner (default); asp: the exact search from scratch; "
                             "multishot: one clingo Control for the whole run (domains M and A, docs/ONLINE.md)")
    parser.add_argument("--encoding", nargs="+", metavar="FILE",
                        help="with --planner multishot: your own online encoding (default: the reference one)")
    parser.add_argument("--budget", type=seconds_argument, default=1.0, metavar="S",
                        help="seconds a planner call may take (default 1)")
    parser.add_argument("--step-seconds", type=seconds_argument, default=1.0, metavar="D",
                        help="seconds of planner time one step of the world takes (default 1)")
    parser.add_argument("--replan", default="arrival", metavar="arrival|K",
                        help="plan again when orders arrive (default), or also every K steps")
    parser.add_argument("--domain", type=domain_argument, help="a|b|c|m|md (default: detected)")
    parser.add_argument("-o", "--output", metavar="PLAN", help="write the plan carried out here (default: stdout)")
    parser.add_argument("--record", metavar="FILE", help="write the run record (JSON) here")
    parser.add_argument("--scenario", metavar="FILE", help="write the instance with the release steps used here")
    parser.add_argument("--live", action="store_true",
                        help=f"with -o: write the plan so far every {LIVE_EVERY} steps, and --scenario before the "
                             "run, so that viz SCENARIO PLAN follows the run (File > Reload on save)")
    parser.add_argument("--json", action="store_true", help="the figures as JSON on stdout")


def _positive(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number of at least 1, not {text!r}")
    return value


def _replan(text: str) -> str | int:
    if text == "arrival":
        return text
    try:
        return _positive(text)
    except argparse.ArgumentTypeError:
        raise InputError(f"--replan {text}: expected 'arrival' or a number of steps") from None


def run(args: argparse.Namespace) -> int:
    replan = _replan(args.replan)
    if args.live and not args.output:
        raise InputError("--live writes the plan as the run goes: give it a file with -o PLAN")
    inputs = [args.instance]
    for output in (args.output, args.record, args.scenario):
        check_output(output, inputs)
    instance = read_instance(args.instance)
    detected = detect_domain(instance)
    domain = chosen_domain(args, detected) or detected
    releases = release_steps(instance, args.every, args.at)
    instance = scenario_of(instance, releases)
    if args.scenario:
        write_text(args.scenario, format_instance(instance), inputs)
    cancel = threading.Event()
    if args.encoding and args.planner != "multishot":
        raise InputError("--encoding goes with --planner multishot")

    def planner_for(seconds: float) -> Planner:
        return encodings_planner(time_limit=seconds, method=args.planner)

    def progress(step: int, so_far: OnlineRun) -> None:
        if step % PROGRESS_EVERY == 0:
            print(f"step {step}: {counted(len(so_far.calls), 'planner call')}, "
                  f"{counted(len(so_far.waiting), 'waiting step')}",
                  file=sys.stderr, flush=True)
        if args.live and step % LIVE_EVERY == 0:
            write_text(args.output, format_plan(Plan(list(so_far.carried))), inputs)

    planner = multishot(instance, domain, args.encoding or ()) if args.planner == "multishot" else \
        FromScratch(instance, domain, planner_for)
    with stopping_on_interrupt(cancel):
        outcome = run_online(instance, domain, planner, releases,
                             budget=args.budget, steps=args.steps, step_seconds=args.step_seconds, replan=replan,
                             cancel=cancel, on_step=progress)
    _answer(args, instance, domain, outcome, inputs)
    return INTERRUPTED if cancel.is_set() else 0


def _answer(args: argparse.Namespace, instance: Instance, domain: Domain, outcome: OnlineRun,
            inputs: list[str]) -> None:
    """The plan carried out, the run record and the figures, where the command line asks."""
    metrics = measure(instance, outcome.plan, domain, outcome.releases, outcome.steps, outcome.calls,
                      len(outcome.waiting))
    bound = ceiling(instance, domain, outcome.releases, outcome.steps)
    if args.output:
        write_text(args.output, format_plan(outcome.plan), inputs)
    if args.record:
        write_text(args.record, json.dumps(record(outcome, metrics, bound), indent=2) + "\n", inputs)
    print("\n".join(summary(outcome, metrics, bound)), file=sys.stderr)
    if args.json:
        print(json.dumps(figures(metrics, bound), indent=2))
    elif not args.output:
        sys.stdout.write(format_plan(outcome.plan))


def summary(outcome: OnlineRun, metrics: Metrics, bound: Ceiling | None) -> list[str]:
    """The figures in words."""
    share = "" if bound is None or not bound.lines else f"; ceiling {bound.lines_per_100:.1f}: " \
        f"{100 * metrics.lines_done / bound.lines:.0f} % of it"
    latency = metrics.latency
    lines = [f"online run: {outcome.steps} steps ({outcome.ended}); {counted(metrics.calls, 'planner call')}, "
             f"{counted(metrics.waiting_steps, 'waiting step')}",
             f"throughput: {metrics.lines_per_100:.1f} order lines per 100 steps{share}; "
             f"{metrics.units_per_100:.1f} units per 100 steps ({metrics.lines_done} of {metrics.lines} lines done)"]
    if latency.orders:
        lines.append(f"order latency: mean {latency.mean:.1f}, p95 {latency.p95}, max {latency.most} steps "
                     f"({counted(latency.orders, 'order')} done, {metrics.orders_open} open)")
    else:
        lines.append(f"order latency: no order done ({metrics.orders_open} open)")
    if metrics.calls:
        lines.append(f"planner: {metrics.planner_mean:.2f} s a call on average, {metrics.planner_max:.2f} s at most")
    return lines
