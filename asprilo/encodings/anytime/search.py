"""The anytime search: a first plan fast, then better ones until time is up or a plan
meets the lower bound.  Every plan it reports has passed the ASP checker.

Steps: the lower bound; the assignment (:mod:`.work`); the first tracks by prioritized
planning (:mod:`.prioritized`); then large-neighbourhood search (:mod:`.improve`).  Given a
plan to start from (``start``), it reports that one first and only shorter ones after it,
and improves it where it can read its work out of it (:mod:`.start`).  A
better plan is checked before it is reported, at most every few seconds when checking is
slow; the best plan not reported yet is checked at the end, with time kept for it.

Its clock, time limit and cancel are a :class:`~asprilo.encodings.solving.watch.Watch` (the
one of the solve that runs it, or its own); its statuses are
:class:`~asprilo.encodings.solving.status.SolveStatus`, and each plan it reports is an
:class:`Improvement`, an :class:`~asprilo.encodings.solving.status.Attempt` at its makespan.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial

from asprilo.bounds import Floor
from asprilo.checker import Report, check
from asprilo.domain import Domain, Job
from asprilo.model import Instance, Plan

from ..solving.bounds import AwaitedBounds, BoundsLost, LowerBounds, bounds_beside
from ..solving.status import IMPROVED, Attempt, SolveStatus
from ..solving.watch import Watch
from . import DEFAULT_SECONDS
from .grid import Grid
from .improve import Improver, score
from .lacam import lacam_tracks
from .plans import plan_of
from .prioritized import first_tracks
from .readings import stronger as _stronger
from .refine import Refiner
from .reservations import Reservations, Track
from .roadmap import Roadmap
from .router import Router
from .start import rebuild, tracks_of
from .work import ASSIGN_CAP, ASSIGN_SHARE, Work

#: the least time between two checks, and how many check durations to wait between two
CHECK_GAP, CHECK_FACTOR = 0.5, 3.0
#: the shares of the time limit LaCAM may take for a first plan of M/Md (then prioritized
#: planning takes over: LaCAM finds one for 200 labelled MovingAI agents in about 0.2 s, for
#: 400 in 0.2-2 s, where prioritized planning fails), and prioritized planning for a better
#: first plan than LaCAM's (not with labelled goals: the refinement does better)
FAST_SHARE, PRIORITIZED_SHARE = 0.5, 0.25
#: how many check durations the refinement of labelled M/Md waits between two checks: it
#: improves many times a second, and checking 400 robots' plan takes about 0.5 s of the 10
#: that 400 MovingAI agents get
REFINE_CHECK_FACTOR = 8.0
#: how many of the last neighbourhoods' durations say how long the next one may take
RECENT_STEPS = 10
#: the share of the time limit within which the first plan of B or C must have come for a
#: first plan under the stronger reading too (:mod:`.readings`; then the most it may take)
READING_SHARE = 0.1


@dataclass
class Improvement(Attempt):
    """One plan reported, as an ``improved`` attempt at its makespan: when (``seconds``
    since the start), its sum of costs, the gap of the makespan to the lower bound (a
    fraction of the bound), the plan and the checker's verdict on it (so that whoever hears
    of it need not check it again: on a large floor that takes seconds)."""

    sum_of_costs: int = 0
    gap: float | None = None
    verdict: Report | None = field(default=None, repr=False, compare=False)

    @classmethod
    def of(cls, seconds: float, makespan: int, sum_of_costs: int, gap: float | None, plan: Plan,
           verdict: Report | None = None) -> Improvement:
        """The report of a plan; its note gives the sum of costs and the gap."""
        above = "" if gap is None else f", {100 * gap:.1f}% above the lower bound"
        return cls(makespan, IMPROVED, seconds, f"sum of costs {sum_of_costs}{above}", plan,
                   sum_of_costs=sum_of_costs, gap=gap, verdict=verdict)

    @property
    def makespan(self) -> int:
        return self.horizon

    def figures(self) -> dict:
        """The numbers without the plan (a history entry of a report)."""
        return {"seconds": self.seconds, "makespan": self.makespan, "sum_of_costs": self.sum_of_costs,
                "gap": self.gap}


@dataclass
class AnytimeResult:
    """What :func:`plan_anytime` found.

    ``status``: ``FOUND`` (a checked plan), ``NONE`` (no plan can exist: some goal or line
    cannot be reached), ``LIMIT`` (no plan within the time), ``CANCELLED``, or ``INVALID``
    (the first plan failed the check: a bug, reported in ``message``).  ``minimal``:
    the plan's makespan meets the lower bound, so no shorter plan exists.
    """

    status: SolveStatus
    domain: Domain
    plan: Plan | None = None
    check: Report | None = None
    bound: float = 0.0
    sum_of_costs_bound: float | None = None
    minimal: bool = False
    history: list[Improvement] = field(default_factory=list)
    stats: dict = field(default_factory=dict)
    message: str = ""
    #: what went wrong beside the search, in sentences (the strong bound's process ran out of memory)
    notes: list[str] = field(default_factory=list)

    @property
    def makespan(self) -> int | None:
        return self.history[-1].makespan if self.history else None


class _Run:
    """One call of :func:`plan_anytime`: its watch, the best plan and its reports."""

    def __init__(self, instance: Instance, domain: Domain, watch: Watch, bounds: LowerBounds,
                 on_improvement: Callable[[Improvement], None] | None):
        self.instance, self.domain, self.watch = instance, domain, watch
        self.on_improvement = on_improvement
        self.result = AnytimeResult(SolveStatus.LIMIT, domain, bound=bounds.makespan,
                                    sum_of_costs_bound=bounds.sum_of_costs)
        #: bounds another process computes (method ``auto``): zero until they arrive
        self.awaited = bounds if isinstance(bounds, AwaitedBounds) else None
        self.check_seconds = 0.0
        self.checked_makespan = 0  # of the plan checked last, which took check_seconds
        self.last_check = -math.inf
        self.pending: dict[int, Track] | None = None
        self.good: dict[int, Track] | None = None  # the tracks of the last plan that passed the check
        self.work: Work | None = None
        self.good_work: tuple | None = None         # ... and the assignment they follow
        self.pending_work: tuple | None = None
        self.best: tuple[int, int] | None = None     # the score of the last plan offered

    def stopped(self, status: SolveStatus | None = None) -> SolveStatus:
        """``CANCELLED`` when the caller cancelled, else ``status`` (by default ``LIMIT``)."""
        return SolveStatus.CANCELLED if self.watch.cancelled else status or SolveStatus.LIMIT

    def refresh_bounds(self) -> None:
        """Take the awaited bounds once they have come (and tell the watch); when they never
        will, say why and go on with those at hand."""
        if self.awaited is None:
            return
        try:
            bounds = self.awaited.arrived()
        except BoundsLost as lost:
            self.awaited = None
            self.result.notes.append(f"{lost}; the lower bound is the cheap one")
            self.watch.note(self.result.notes[-1])
            return
        if bounds is not None:
            self.result.bound, self.result.sum_of_costs_bound = bounds.makespan, bounds.sum_of_costs
            self.awaited = None
            self.watch.lower_bounds(bounds)

    def out_of_time(self, keep: float = 0.0) -> bool:
        """The watch's question (cancelled, or less than ``keep`` seconds left), asked of the
        assignment and the first plan: the awaited bounds are looked for first (their
        process may have failed: said at once, whatever the search does)."""
        self.refresh_bounds()
        return self.watch.out_of_time(keep)

    def reached_bound(self, tracks: dict[int, Track]) -> bool:
        self.refresh_bounds()
        makespan = max((t.finish for t in tracks.values()), default=0)
        soc = sum(t.finish for t in tracks.values())
        bound, soc_bound = self.result.bound, self.result.sum_of_costs_bound
        return makespan <= bound and (soc_bound is None or soc <= soc_bound)

    def offer(self, tracks: dict[int, Track], force: bool = False, kept: bool = False) -> bool:
        """A better plan: report it now if checking is due (or ``force``), else later;
        ``False`` when it failed the check (the search then goes back to the last good one).
        A plan no better than the last one offered (one given to start from, say) is not
        reported.  ``kept``: a plan given whose work is not :attr:`work`'s (never gone back to)."""
        if self.best is not None and score(tracks) >= self.best:
            return True
        self.best = score(tracks)
        self.pending = dict(tracks)
        self.pending_work = None if kept else self.work.save()
        return self.report() if force or self.due() else True

    def due(self) -> bool:
        """Whether a plan may be checked now (:data:`CHECK_GAP`, :data:`CHECK_FACTOR`)."""
        return self.watch.clock() - self.last_check >= max(CHECK_GAP, CHECK_FACTOR * self.check_seconds)

    def check_estimate(self, makespan: int) -> float:
        """The seconds a check of a plan of ``makespan`` steps will take, from the last check:
        half of the checker's work grows with the steps (400 agents: 0.52 s for LaCAM's plan
        of about 180 steps, 0.29 s for the refined one of 58), the rest does not."""
        if not self.checked_makespan:
            return self.check_seconds
        return self.check_seconds * (1 + makespan / self.checked_makespan) / 2

    def report(self) -> bool:
        """Check the pending plan and report it; whether it passed."""
        tracks, self.pending = self.pending, None
        if tracks is None:
            return True
        self.refresh_bounds()
        result, clock = self.result, self.watch.clock
        plan = plan_of(tracks, self.instance, self.domain)
        began = clock()
        verdict = check(self.instance, plan, self.domain, makespan_bound=result.bound,
                        sum_of_costs_bound=result.sum_of_costs_bound)
        self.check_seconds = clock() - began
        self.checked_makespan = verdict.metrics.get("horizon") or 0
        self.last_check = clock()
        if not verdict.valid:
            result.message = "a plan failed the check and was dropped: " + verdict.errors[0].message
            self.best = None if self.good is None else score(self.good)
            return False
        if self.pending_work is not None:
            self.good, self.good_work = tracks, self.pending_work
        result.status, result.plan, result.check = SolveStatus.FOUND, plan, verdict
        makespan, soc = verdict.metrics["horizon"], verdict.metrics["sum_of_costs"]
        result.minimal = makespan <= result.bound
        gap = None if result.bound <= 0 or not math.isfinite(result.bound) else (makespan - result.bound) / result.bound
        improvement = Improvement.of(round(self.watch.elapsed(), 3), makespan, soc, gap, plan, verdict)
        result.history.append(improvement)
        if self.on_improvement is not None:
            self.on_improvement(improvement)
        return True


def _clock() -> float:
    """The planner's own clock (read through this module's ``time``, which a test may replace)."""
    return time.perf_counter()


def plan_anytime(instance: Instance, domain: Domain, time_limit: float | None = DEFAULT_SECONDS,
                 cancel: threading.Event | None = None,
                 on_improvement: Callable[[Improvement], None] | None = None, seed: int = 0, *,
                 watch: Watch | None = None, bounds: LowerBounds | None = None, router: str = "python",
                 start: Plan | None = None) -> AnytimeResult:
    """A checked plan for ``instance`` as soon as possible, then better ones (makespan first,
    then sum of costs) until ``time_limit`` seconds have passed, ``cancel`` is set, or a
    plan meets the lower bound.  ``on_improvement`` hears of every plan reported.

    ``watch``: the stop-watch of a solve that runs the planner (its time limit and cancel
    replace ``time_limit`` and ``cancel``); ``bounds``: the lower bounds, when known (else
    computed here, or beside the search for a large instance: ``bounds_beside``; or
    :class:`~asprilo.encodings.solving.bounds.AwaitedBounds`, when another process computes
    them: the planner starts at once and takes them when they come); ``router``: the routing
    engine, ``python`` or ``asp`` (``route.lp``; the same routes, slower); ``start``: a valid
    plan of ``domain`` to start from (:func:`.readings.reading_plan` makes one of a plan under
    a stronger reading), reported first: no plan reported after it is as long.
    """
    limit = DEFAULT_SECONDS if time_limit is None else time_limit
    own = watch is None
    if own:
        watch = Watch(limit, cancel, clock=_clock)
    elif watch.deadline is not None:
        limit = watch.remaining()
    helper = None
    try:
        floor = Floor(instance.cells)
        computed = bounds is None
        if bounds is None:
            bounds, helper = bounds_beside(instance, domain, floor)
        run = _Run(instance, domain, watch, bounds, on_improvement)
        if computed:  # said (the cheap ones, where the strong ones are awaited)
            run.watch.lower_bounds(LowerBounds(bounds.makespan, bounds.sum_of_costs))
        return _plan(run, floor, limit, seed, router, start)
    finally:
        if helper is not None:
            helper.wait(0)
        if own:
            watch.close()


def _plan(run: _Run, floor: Floor, limit: float, seed: int, engine: str, start: Plan | None = None
          ) -> AnytimeResult:
    """The steps of :func:`plan_anytime`: the plan given (reported first), assignment, first
    plan, improvements (from the plan given when it is as short as the first plan and its
    work can be read out of it: :func:`_follow`)."""
    instance, domain, out_of_time, result = run.instance, run.domain, run.out_of_time, run.result
    if not math.isfinite(result.bound):
        result.status, result.minimal = SolveStatus.NONE, True
        result.message = "some goal or order line can never be reached"
        return result
    grid = Grid(floor)
    work = run.work = Work(instance, domain, grid, result.bound)
    given = None
    if start is not None:
        given = tracks_of(start, instance)
        if not run.offer(given, force=True, kept=True):
            return result  # the plan given failed the check (said in the message): a bug
    table = Reservations(instance, work.homes)
    router = Router(grid, table, out_of_time, engine)
    roadmap = Roadmap(floor) if work.domain.work is Job.GOALS else None  # M/Md's numbered vertices
    tracks = _starting_tracks(run, work, floor, router, table, limit, seed, roadmap, given)
    if tracks is None:
        return result
    if not run.offer(tracks, force=True):  # not said again when it was said already (or is no better)
        if given is None:
            result.status = SolveStatus.INVALID
        return result
    if _own_goals(work):
        _refine(run, Refiner.of_tracks(roadmap or Roadmap(floor), tracks, work.goals, seed))
    else:
        stronger = None if given is not None else _stronger_reading(run, grid, engine, tracks, limit, seed)
        improver = stronger or Improver(work, router, table, seed)
        _improve(run, improver, improver.table)
    if run.pending is not None:
        run.report()
    if result.status is not SolveStatus.FOUND:
        result.status = run.stopped(result.status)
    return result


def _starting_tracks(run: _Run, work: Work, floor: Floor, router: Router, table: Reservations, limit: float,
                     seed: int, roadmap: Roadmap | None, given: dict[int, Track] | None) -> dict[int, Track] | None:
    """The tracks the improvement starts from: the planner's first plan, or the plan
    ``given`` when it is as short and its work can be read (:func:`_follow`); ``None`` when
    there are none (said in the result, unless a plan was given: that one is the answer)."""
    result, tracks = run.result, None
    if work.assign(min(ASSIGN_CAP, ASSIGN_SHARE * limit), run.out_of_time):
        tracks = _first_plan(run, work, floor, router, table, limit, seed, roadmap)
    elif given is None:
        result.status = run.stopped()
        result.message = "no assignment of the work to the robots within the time limit"
        return None
    if given is not None:
        if (tracks is None or score(given) <= score(tracks)) and _follow(run, work, table, given):
            return given
        result.stats.setdefault("start", "the planner's own first plan was shorter than the plan given")
    elif tracks is None:
        result.status = run.stopped()
        result.message = "no first plan within the time limit"
    return tracks


def _follow(run: _Run, work: Work, table: Reservations, given: dict[int, Track]) -> bool:
    """Improve from the plan given: its work read out of its tracks into ``work``
    (:func:`.start.rebuild`), its tracks alone in ``table``; or, where its work cannot be
    read, say why in the stats (``start``) and leave both as they are."""
    why = rebuild(work, given)
    if why is not None:
        run.result.stats["start"] = (f"the plan given was kept as given ({why}): the search started from its own "
                                     "first plan")
        return False
    _go_back(table, given)
    run.good, run.good_work = dict(given), work.save()
    run.result.stats["start"] = "the search started from the plan given"
    return True


def _first_plan(run: _Run, work: Work, floor: Floor, router: Router, table: Reservations, limit: float, seed: int,
                roadmap: Roadmap | None = None) -> dict[int, Track] | None:
    """The first tracks, held in ``table``: by prioritized planning; for robots with goals
    (M, Md), first by LaCAM within :data:`FAST_SHARE` of the time (all robots at once, fast
    on a crowded floor), reported at once, then (unless every robot has its own goal: the
    refinement does better from LaCAM's plan) by prioritized planning within
    :data:`PRIORITIZED_SHARE` of the time, kept if better (or with all the time left, when
    LaCAM found nothing)."""
    watch = run.watch
    fast = None
    if work.domain.work is Job.GOALS:
        starts = {robot: spot.at for robot, spot in run.instance.robots.items()}
        fast = lacam_tracks(floor, starts, work.goals, _stop_after(watch, FAST_SHARE * limit), seed, roadmap)
        if fast is not None:
            run.result.stats["first_plan_seconds"] = round(watch.elapsed(), 3)
            if not run.offer(fast, force=True):
                fast = None
            elif _own_goals(work):
                _go_back(table, fast)
                return fast
    stopped = run.out_of_time if fast is None else _stop_after(watch, PRIORITIZED_SHARE * limit)
    tracks = first_tracks(work, router, table, stopped, seed)
    if fast is None:
        if tracks is not None:
            run.result.stats["first_plan_seconds"] = round(watch.elapsed(), 3)
        return tracks
    if tracks is None or score(tracks) >= score(fast) or not run.offer(tracks, force=True):
        _go_back(table, fast)
        return fast
    return tracks


def _stronger_reading(run: _Run, grid: Grid, engine: str, tracks: dict[int, Track], limit: float,
                      seed: int) -> Improver | None:
    """The improver of a first plan made under the stronger reading of B or C
    (:func:`.readings.stronger`), when that plan is shorter than ``tracks`` (then reported): C relaxes
    B and B relaxes A, so such a plan is one of the domain too, once the deliveries that
    close nothing are left out (:func:`.plans.plan_of`).  Tried only when the first plan
    came within :data:`READING_SHARE` of the time, and for as long again at most."""
    stronger = _stronger(run.domain)
    if stronger is None or run.watch.elapsed() > READING_SHARE * limit:
        return None
    stop = _stop_after(run.watch, READING_SHARE * limit)
    work = Work(run.instance, stronger, grid, run.result.bound)
    if not work.assign(min(ASSIGN_CAP, ASSIGN_SHARE * limit), stop):
        return None
    table = Reservations(run.instance, work.homes)
    router = Router(grid, table, stop, engine)
    other = first_tracks(work, router, table, stop, seed)
    if other is None or score(other) >= score(tracks):
        return None
    own, run.work = run.work, work
    if not run.offer(other, force=True):
        run.work = own
        return None
    router.stopped = run.out_of_time
    run.result.stats["reading"] = stronger.label  # the plans follow the stronger reading's work
    return Improver(work, router, table, seed)


def _own_goals(work: Work) -> bool:
    """Whether every robot has a goal of its own that stays (M/Md with labels): the plan is
    refined by :mod:`.refine`."""
    return work.domain.work is Job.GOALS and not work.reassignable()


def _refine(run: _Run, refiner: Refiner) -> None:
    """Large-neighbourhood search of :mod:`.refine` until time is up or the bounds are met;
    a better plan is offered when checking is due (:data:`REFINE_CHECK_FACTOR`), the last one
    at the end."""
    steps, unreported = 0, False
    while True:
        run.refresh_bounds()
        makespan, soc = refiner.score()
        bound, soc_bound = run.result.bound, run.result.sum_of_costs_bound
        reserve = 1.5 * run.check_estimate(makespan) + 0.05
        if (makespan <= bound and (soc_bound is None or soc <= soc_bound)) or run.watch.out_of_time(keep=reserve):
            break
        steps += 1
        unreported |= refiner.step(partial(run.watch.out_of_time, reserve))
        if unreported and run.watch.clock() - run.last_check >= max(CHECK_GAP, REFINE_CHECK_FACTOR * run.check_seconds):
            unreported = False
            if not run.offer(refiner.tracks(), force=True):
                break  # a bug: the plan reported last stays
    if unreported:
        run.offer(refiner.tracks(), force=True)
    run.result.stats.update(neighbourhoods=steps, tried=dict(refiner.tried), improved=dict(refiner.won))


def _stop_after(watch: Watch, seconds: float) -> Callable[[], bool]:
    """A stop question: true when time is up, or ``seconds`` from now."""
    until = watch.elapsed() + seconds
    return lambda: watch.out_of_time() or watch.elapsed() > until


def _improve(run: _Run, improver: Improver, table: Reservations) -> None:
    """Large-neighbourhood search until time is up or the bound is met.  Time is kept for
    the last check, and a neighbourhood starts only if one as long as the longest of the last
    few still fits (a routing call cannot be stopped while it grounds)."""
    steps, recent = 0, deque(maxlen=RECENT_STEPS)
    while not run.reached_bound(table.tracks):
        reserve = 1.5 * run.check_seconds + 0.05
        if run.watch.out_of_time(keep=reserve + max(recent, default=0.0)):
            break
        steps += 1
        began = run.watch.clock()
        better = improver.step(partial(run.watch.out_of_time, reserve))
        recent.append(run.watch.clock() - began)
        # a plan kept back while checking was not due is reported once it is
        passed = run.offer(table.tracks) if better else run.pending is None or not run.due() or run.report()
        if not passed:
            if run.good is None:
                break  # only a plan given was reported: nothing of the search's own to go back to
            _go_back(table, run.good)
            improver.work.restore(run.good_work)
    run.result.stats.update(neighbourhoods=steps, tried=dict(improver.tried), improved=dict(improver.won))


def _go_back(table: Reservations, tracks: dict[int, Track]) -> None:
    """Put the tracks of a plan that passed the check back into the table, alone."""
    table.reset(still=False)
    for track in tracks.values():
        table.add(track)
