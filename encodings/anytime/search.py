"""The anytime search: a first plan fast, then better ones until time is up or a plan
meets the lower bound.  Every plan it reports has passed the ASP checker.

Steps: the lower bound; the assignment (:mod:`.work`); the first tracks by prioritized
planning (:mod:`.prioritized`); then large-neighbourhood search (:mod:`.improve`).  A
better plan is checked before it is reported, at most every few seconds when checking is
slow; the best plan not reported yet is checked at the end, with time kept for it.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial

from asprilo.checker import Report, check
from asprilo.domain import Domain
from asprilo.model import Instance, Plan

from .bound import makespan_bound, sum_of_costs_bound
from .grid import Grid
from .improve import Improver
from .plans import plan_of
from .prioritized import first_tracks
from .reservations import Reservations, Track
from .router import Router
from .work import ASSIGN_CAP, ASSIGN_SHARE, Work

#: the time limit when none is given (seconds)
DEFAULT_SECONDS = 60.0
#: the least time between two checks, and how many check durations to wait between two
CHECK_GAP, CHECK_FACTOR = 0.5, 3.0
#: how many of the last neighbourhoods' durations say how long the next one may take
RECENT_STEPS = 10


@dataclass
class Improvement:
    """One plan reported: when (seconds since the start), its makespan and sum of costs,
    the gap of the makespan to the lower bound (a fraction of the bound), and the plan."""

    seconds: float
    makespan: int
    sum_of_costs: int
    gap: float | None
    plan: Plan | None = field(default=None, repr=False, compare=False)

    def figures(self) -> dict:
        """The numbers without the plan (a history entry of a report)."""
        return {"seconds": self.seconds, "makespan": self.makespan, "sum_of_costs": self.sum_of_costs,
                "gap": self.gap}


@dataclass
class AnytimeResult:
    """What :func:`plan_anytime` found.

    ``status``: ``found`` (a checked plan), ``none`` (no plan can exist: some goal or line
    cannot be reached), ``limit`` (no plan within the time), ``cancelled``, or ``invalid``
    (the first plan failed the check: a bug, reported in ``message``).  ``minimal``:
    the plan's makespan meets the lower bound, so no shorter plan exists.
    """

    status: str
    domain: Domain
    plan: Plan | None = None
    check: Report | None = None
    bound: float = 0.0
    sum_of_costs_bound: float | None = None
    minimal: bool = False
    history: list[Improvement] = field(default_factory=list)
    stats: dict = field(default_factory=dict)
    message: str = ""

    @property
    def makespan(self) -> int | None:
        return self.history[-1].makespan if self.history else None


class _Run:
    """One call of :func:`plan_anytime`: the clock, the best plan and its reports."""

    def __init__(self, instance: Instance, domain: Domain, time_limit: float, cancel: threading.Event | None,
                 on_improvement: Callable[[Improvement], None] | None):
        self.instance, self.domain = instance, domain
        self.started = time.perf_counter()
        self.deadline = self.started + time_limit
        self.cancel, self.on_improvement = cancel, on_improvement
        self.result = AnytimeResult("limit", domain)
        self.check_seconds = 0.0
        self.last_check = -math.inf
        self.pending: dict[int, Track] | None = None
        self.good: dict[int, Track] | None = None  # the tracks of the last plan that passed the check
        self.work: Work | None = None
        self.good_work: tuple | None = None         # ... and the assignment they follow
        self.pending_work: tuple | None = None

    def elapsed(self) -> float:
        return time.perf_counter() - self.started

    def cancelled(self) -> bool:
        return self.cancel is not None and self.cancel.is_set()

    def out_of_time(self, keep: float = 0.0) -> bool:
        return self.cancelled() or time.perf_counter() >= self.deadline - keep

    def reached_bound(self, tracks: dict[int, Track]) -> bool:
        makespan = max((t.finish for t in tracks.values()), default=0)
        soc = sum(t.finish for t in tracks.values())
        bound, soc_bound = self.result.bound, self.result.sum_of_costs_bound
        return makespan <= bound and (soc_bound is None or soc <= soc_bound)

    def offer(self, tracks: dict[int, Track], force: bool = False) -> bool:
        """A better plan: report it now if checking is due (or ``force``), else later;
        ``False`` when it failed the check (the search then goes back to the last good one)."""
        self.pending = dict(tracks)
        self.pending_work = self.work.save()
        if not force and time.perf_counter() - self.last_check < max(CHECK_GAP, CHECK_FACTOR * self.check_seconds):
            return True
        return self.report()

    def report(self) -> bool:
        """Check the pending plan and report it; whether it passed."""
        tracks, self.pending = self.pending, None
        if tracks is None:
            return True
        plan = plan_of(tracks, self.instance, self.domain)
        began = time.perf_counter()
        verdict = check(self.instance, plan, self.domain)
        self.check_seconds = time.perf_counter() - began
        self.last_check = time.perf_counter()
        if not verdict.valid:
            self.result.message = "a plan failed the check and was dropped: " + verdict.errors[0].message
            return False
        self.good, self.good_work = tracks, self.pending_work
        result = self.result
        result.status, result.plan, result.check = "found", plan, verdict
        makespan, soc = verdict.metrics["horizon"], verdict.metrics["sum_of_costs"]
        result.minimal = makespan <= result.bound
        gap = None if result.bound <= 0 or not math.isfinite(result.bound) else (makespan - result.bound) / result.bound
        improvement = Improvement(round(self.elapsed(), 3), makespan, soc, gap, plan)
        result.history.append(improvement)
        if self.on_improvement is not None:
            self.on_improvement(improvement)
        return True


def plan_anytime(instance: Instance, domain: Domain, time_limit: float | None = DEFAULT_SECONDS,
                 cancel: threading.Event | None = None,
                 on_improvement: Callable[[Improvement], None] | None = None, seed: int = 0) -> AnytimeResult:
    """A checked plan for ``instance`` as soon as possible, then better ones (makespan first,
    then sum of costs) until ``time_limit`` seconds have passed, ``cancel`` is set, or a
    plan meets the lower bound.  ``on_improvement`` hears of every plan reported."""
    limit = DEFAULT_SECONDS if time_limit is None else time_limit
    run = _Run(instance, domain, limit, cancel, on_improvement)
    result = run.result
    result.bound = makespan_bound(instance, domain)
    result.sum_of_costs_bound = sum_of_costs_bound(instance, domain)
    if not math.isfinite(result.bound):
        result.status, result.minimal = "none", True
        result.message = "some goal or order line can never be reached"
        return result
    grid = Grid(instance.cells)
    work = run.work = Work(instance, domain, grid, result.bound)
    if not work.assign(min(ASSIGN_CAP, ASSIGN_SHARE * limit), run.out_of_time):
        result.status = "cancelled" if run.cancelled() else "limit"
        result.message = "no assignment of the work to the robots within the time limit"
        return result
    table = Reservations(instance, work.homes)
    router = Router(grid, table, run.out_of_time)
    tracks = first_tracks(work, router, table, run.out_of_time, seed)
    result.stats["first_plan_seconds"] = round(run.elapsed(), 3)
    if tracks is None:
        result.status = "cancelled" if run.cancelled() else "limit"
        result.message = "no first plan within the time limit"
        return result
    if not run.offer(tracks, force=True):
        result.status = "invalid"
        return result
    _improve(run, Improver(work, router, table, seed), table)
    if run.pending is not None:
        run.report()
    if run.cancelled() and result.status != "found":
        result.status = "cancelled"
    return result


def _improve(run: _Run, improver: Improver, table: Reservations) -> None:
    """Large-neighbourhood search until time is up or the bound is met.  Time is kept for
    the last check, and a neighbourhood starts only if one as long as the longest of the last
    few still fits (a routing call cannot be stopped while it grounds)."""
    steps, recent = 0, deque(maxlen=RECENT_STEPS)
    while not run.reached_bound(table.tracks):
        reserve = 1.5 * run.check_seconds + 0.05
        if run.out_of_time(keep=reserve + max(recent, default=0.0)):
            break
        steps += 1
        began = time.perf_counter()
        better = improver.step(partial(run.out_of_time, reserve))
        recent.append(time.perf_counter() - began)
        if better and not run.offer(table.tracks):
            _go_back(table, run.good)
            improver.work.restore(run.good_work)
    run.result.stats.update(neighbourhoods=steps, tried=dict(improver.tried), improved=dict(improver.won))


def _go_back(table: Reservations, tracks: dict[int, Track]) -> None:
    """Put the last plan that passed the check back into the table."""
    for robot in list(table.tracks):
        table.remove(robot)
    for track in tracks.values():
        table.add(track)
