"""The anytime planner's time limit holds in whatever phase it is (issue 45: a 200x200 floor
with 600 robots ran 260 s past a limit of 180 s, nothing said): the lower bounds, the task
assignment, the first plan, the improvements, the checks; the strong bound of a large floor is
computed beside the search, in a process of its own that is killed, not waited for, and whose
failure is said in one sentence.

The clock is the planner's own (``time`` in its module): it runs with the wall until the phase
under test begins, then jumps past any limit, so time runs out at the same point of the search
on every machine.  The limits set are hang guards only.
"""

from __future__ import annotations

import faulthandler
import os
import signal
import time

import pytest
from helpers.clocks import PAST_ANY_LIMIT, patient_anytime
from test_anytime import TWO_TRIPS

from asprilo.domain import Domain
from asprilo.encodings.anytime import improve, plan_anytime, search, work
from asprilo.encodings.anytime.router import Router
from asprilo.encodings.solving import bounds as solving_bounds
from asprilo.encodings.solving import front
from asprilo.encodings.solving.bounds import LowerBounds
from asprilo.encodings.solving.request import SolveRequest
from asprilo.encodings.solving.watch import Listeners
from asprilo.isolation import Isolated
from asprilo.reader import read_instance

# TWO_TRIPS (test_anytime.py): one robot, two shelves, two lines at one station (domain B):
# the robot brings one shelf, puts it down and fetches the other, 21 steps at least; the strong
# lower bound counts one trip per line (19), so the search improves until its time is up.  The cheap bound is the
# stations' bound, 10: shelf 1 at (4,2) is 2 steps from the robot, lifted at step 3, carried
# 4 steps to the station at (1,1) (step 7) and delivered at 8; shelf 2 at (5,2) is lifted at
# 4 and carried 5 steps, delivered at 10.

#: a hang guard: no search here comes near it
GUARD = 600.0


class PhaseClock:
    """The planner's clock: the wall's until :meth:`jump`, then past any limit.  It records
    every phase begun, and whether time was up by then."""

    def __init__(self) -> None:
        self.jumped = False
        self.begun: list[tuple[str, bool]] = []

    def perf_counter(self) -> float:
        return time.perf_counter() + (PAST_ANY_LIMIT if self.jumped else 0.0)

    def jump(self) -> None:
        self.jumped = True

    def after_jump(self) -> list[str]:
        """The phases begun once time was up."""
        return [name for name, late in self.begun if late]


#: the phases of a search, each with the function that begins it: (owner, attribute)
PHASES = {"bounds": (search, "bounds_beside"), "assignment": (work.Work, "assign"),
          "first plan": (search, "first_tracks"), "route": (Router, "route"),
          "improvement": (improve.Improver, "step"), "check": (search, "check")}


def watch_phases(monkeypatch, jump_at: str | None) -> PhaseClock:
    """Put a :class:`PhaseClock` into the planner and have it jump when ``jump_at`` begins."""
    clock = PhaseClock()
    monkeypatch.setattr(search, "time", clock)
    for name, (owner, attribute) in PHASES.items():
        monkeypatch.setattr(owner, attribute, _noted(clock, name, getattr(owner, attribute), name == jump_at))
    return clock


def _noted(clock: PhaseClock, name: str, function, jump: bool):
    def noted(*args, **options):
        clock.begun.append((name, clock.jumped))
        if jump:
            clock.jump()
        return function(*args, **options)

    return noted


@pytest.fixture
def two_trips(write):
    return read_instance(write("two-trips.lp", TWO_TRIPS))


@pytest.mark.parametrize("phase", ["bounds", "assignment", "first plan"])
def test_time_up_before_a_first_plan_routes_no_robot_after(phase, two_trips, monkeypatch):
    """Time runs out as the phase begins: no robot is routed after, no plan, and the planner
    says that time ran out.  (The assignment, found at once on this floor, is kept; the
    first plan is what time ran out for.)"""
    clock = watch_phases(monkeypatch, phase)
    result = plan_anytime(two_trips, Domain.B, time_limit=GUARD)
    assert (result.status, result.plan, result.history) == ("limit", None, [])
    assert result.message == "no first plan within the time limit"
    assert "route" not in clock.after_jump() and "check" not in clock.after_jump()


def test_time_up_while_improving_keeps_the_first_plan_and_starts_no_other_neighbourhood(two_trips, monkeypatch):
    clock = watch_phases(monkeypatch, "improvement")
    result = plan_anytime(two_trips, Domain.B, time_limit=GUARD)
    assert (result.status, result.minimal) == ("found", False)
    assert result.stats["neighbourhoods"] == 1  # the one under way when time ran out
    assert "improvement" not in clock.after_jump()


def test_time_up_while_checking_the_first_plan_reports_it_and_improves_no_more(two_trips, monkeypatch):
    clock = watch_phases(monkeypatch, "check")
    result = plan_anytime(two_trips, Domain.B, time_limit=GUARD)
    assert (result.status, len(result.history), result.stats["neighbourhoods"]) == ("found", 1, 0)
    assert result.history[0].verdict is result.check and result.check.valid  # its verdict goes with it
    assert clock.after_jump() == []


# --- the strong bound beside the search ---------------------------------------------------------

def _never_answers(instance, domain, report) -> None:
    """A bound's child that computes for ever."""
    time.sleep(GUARD)


def _aborts(instance, domain, report) -> None:
    """A bound's child that dies as C++ code does when it cannot allocate."""
    faulthandler.disable()  # (pytest's would print the child's stack)
    os.abort()


def bound_child(monkeypatch, function=None) -> list:
    """Count every floor as large (the strong bound is computed beside the search), in a child
    running ``function`` (default: the real one); the children started."""
    from asprilo import isolation

    started = []
    start = isolation.start_isolated

    def forked(target, args, standalone=False):  # forked: the test's own functions, monkeypatches
        child = start(function or target, args, standalone=False)
        started.append(child)
        return child

    monkeypatch.setattr(solving_bounds, "BACKGROUND_WORK", 0)
    monkeypatch.setattr(isolation, "start_isolated", forked)
    return started


def test_the_strong_bound_is_not_waited_for_and_its_process_ends_with_the_search(two_trips, monkeypatch):
    """A bound's child that never answers: the search plans with the cheap bound meanwhile,
    and when its time is up the child is killed, not waited for."""
    children = bound_child(monkeypatch, _never_answers)
    clock = patient_anytime(monkeypatch, stop_after=1)
    result = plan_anytime(two_trips, Domain.B, time_limit=GUARD, on_improvement=clock.reported)
    assert result.status == "found" and len(result.history) == 1
    assert result.bound == 10  # the cheap bound (see TWO_TRIPS), the strong one (19) never came
    child, = children
    assert not child.process.is_alive() and child.process.exitcode == -signal.SIGKILL
    assert result.notes == []


@pytest.mark.parametrize("failure,said", [
    ("memory", "the process computing the strong lower bound ran out of memory; the lower bound is the cheap one"),
    ("abort", "the process computing the strong lower bound ran out of memory (it aborted); the lower bound is the "
              "cheap one"),
])
def test_a_bound_process_out_of_memory_is_said_in_one_sentence(failure, said, two_trips, monkeypatch):
    """The bound's child runs out of memory (Python's MemoryError, or C++'s abort): the search
    goes on with the cheap bound and says so once; its time runs out once that is said."""
    from asprilo.encodings.solving.watch import Watch

    if failure == "memory":
        def no_memory(*args):
            raise MemoryError
        monkeypatch.setattr(solving_bounds, "lower_bounds", no_memory)  # in the forked child too
    bound_child(monkeypatch, None if failure == "memory" else _aborts)
    heard = []
    clock = patient_anytime(monkeypatch, stop_after=1, enough=lambda: bool(heard))
    watch = Watch(GUARD, listeners=Listeners(notes=heard.append), clock=clock)
    result = plan_anytime(two_trips, Domain.B, on_improvement=clock.reported, watch=watch)
    assert (result.status, result.bound, result.notes) == ("found", 10, [said])
    assert [note.text for note in heard] == [said]


def test_a_bound_process_that_dies_is_said_at_once_to_whoever_listens(two_trips, monkeypatch):
    """Said as a note as soon as the planner sees it (so that a solve stopped from outside
    before any plan still says it): time runs out once it has been said."""
    from asprilo.encodings.solving.status import Note
    from asprilo.encodings.solving.watch import Watch

    bound_child(monkeypatch, _aborts)
    heard = []
    clock = patient_anytime(monkeypatch, stop_after=0, enough=lambda: bool(heard))
    watch = Watch(GUARD, listeners=Listeners(notes=heard.append), clock=clock)
    plan_anytime(two_trips, Domain.B, watch=watch)
    assert heard == [Note("the process computing the strong lower bound ran out of memory (it aborted); the lower "
                          "bound is the cheap one")]


def test_the_strong_bound_replaces_the_cheap_one_when_it_comes(two_trips, monkeypatch):
    """The real bound's child: its bound (19) is taken once it arrives, and the watch hears
    the cheap bound, then the strong one."""
    children = bound_child(monkeypatch)
    heard = []
    clock = patient_anytime(monkeypatch, stop_after=1, enough=lambda: bool(heard) and heard[-1].makespan == 19)
    from asprilo.encodings.solving.watch import Watch

    watch = Watch(GUARD, listeners=Listeners(bounds=heard.append), clock=clock)
    result = plan_anytime(two_trips, Domain.B, on_improvement=clock.reported, watch=watch)
    assert (result.status, result.bound) == ("found", 19) and len(children) == 1
    assert [bounds.makespan for bounds in heard] == [10, 19]


# --- the solve around it --------------------------------------------------------------------------

def test_solve_leaves_the_anytime_planner_s_bounds_to_it(two_trips, monkeypatch):
    """solve --method anytime computes no bound before the planner (on 200x200 the strong one
    took minutes, and the child the solve ran in was killed at the limit before planning)."""
    children = bound_child(monkeypatch, _never_answers)
    monkeypatch.setattr(front, "lower_bounds", _no_strong_bound)
    clock = patient_anytime(monkeypatch, stop_after=1)
    heard = []
    request = SolveRequest(two_trips, Domain.B, method="anytime", time_limit=GUARD)
    monkeypatch.setattr(front, "Watch", _watch_with(clock))
    outcome = front.solve_request(request, Listeners(progress=clock.reported, bounds=heard.append))
    assert (outcome.status, outcome.lower_bound) == ("found", 10) and len(children) == 1
    assert [bounds.makespan for bounds in heard] == [10]


def test_a_solve_stopped_from_outside_answers_with_the_cheap_bound_at_once(two_trips, monkeypatch):
    """A child killed at the time limit before it said its bounds: the parent takes the cheap
    ones (it computed the strong ones: minutes on 200x200, then out of memory under 3 GB)."""
    monkeypatch.setattr(solving_bounds, "BACKGROUND_WORK", 0)
    monkeypatch.setattr(solving_bounds, "lower_bounds", _no_strong_bound)
    request = SolveRequest(two_trips, Domain.B, method="anytime", time_limit=30.0)
    outcome = front._stopped_from_outside(request, front.method_for(request), Isolated("timeout"), None)
    assert (outcome.status, outcome.lower_bound, outcome.message) == ("limit", 10, "stopped at the time limit (30 s)")


def test_a_solve_stopped_from_outside_says_what_went_wrong_beside_it(two_trips):
    from asprilo.encodings.solving.status import Note

    request = SolveRequest(two_trips, Domain.B, method="anytime", time_limit=30.0, bounds=LowerBounds(19))
    child = Isolated("timeout", messages=[Note("the process computing the strong lower bound ran out of memory; "
                                               "the lower bound is the cheap one")])
    outcome = front._stopped_from_outside(request, front.method_for(request), child, None)
    assert outcome.message == ("stopped at the time limit (30 s); the process computing the strong lower bound ran "
                               "out of memory; the lower bound is the cheap one")


def test_a_plan_checked_by_the_planner_is_not_checked_again_after_the_limit(two_trips, monkeypatch):
    """Its verdict came with it; its bound metrics are those the parent knows (here the cheap
    bound, 10: the planner checked it against the strong one, 19)."""
    clock = patient_anytime(monkeypatch, stop_after=1)
    found = plan_anytime(two_trips, Domain.B, time_limit=GUARD, on_improvement=clock.reported)
    assert found.check.metrics["makespan_bound"] == 19
    monkeypatch.setattr(front, "check", _no_check)
    request = SolveRequest(two_trips, Domain.B, method="anytime", time_limit=30.0, bounds=LowerBounds(10))
    outcome = front._stopped_from_outside(request, front.method_for(request),
                                          Isolated("timeout", messages=list(found.history)), None)
    assert outcome.found and outcome.horizon == found.history[-1].makespan
    assert outcome.check.valid and outcome.check.metrics["horizon"] == found.check.metrics["horizon"]
    assert (outcome.check.metrics["makespan_bound"], outcome.check.metrics["bounds"]) == (10, "given")


def test_a_planner_out_of_memory_is_said_and_its_plan_kept(two_trips, monkeypatch):
    """The planner's process runs out of memory right after its first plan (a MemoryError
    raised there, in the forked child): the solve says so in one sentence and answers with
    that plan, checked where it was found."""
    import asprilo.encodings.anytime as anytime_package

    planner = anytime_package.plan_anytime

    def runs_out(*args, on_improvement, **options):
        def heard(better):
            on_improvement(better)
            raise MemoryError

        return planner(*args, on_improvement=heard, **options)

    monkeypatch.setattr(anytime_package, "plan_anytime", runs_out)
    monkeypatch.setattr(front, "check", _no_check)  # in this process: the verdict came with the plan
    heard = []
    outcome = front.solve(two_trips, Domain.B, method="anytime", time_limit=GUARD, isolate=True,
                          on_progress=heard.append)
    assert outcome.found and outcome.check.valid and len(heard) == 1
    assert (outcome.plan, outcome.horizon) == (heard[0].plan, heard[0].makespan)
    assert outcome.message == "the solver process ran out of memory; the answer is the best plan found before"


@pytest.mark.parametrize("limit,said", [
    (None, "the solver process ran out of memory"),
    (2048 * 2**20, "the solver process ran out of memory (its address space is limited to 2048 MB: ulimit -v)"),
])
def test_a_solve_out_of_memory_without_a_memory_limit_says_so(limit, said, two_trips, monkeypatch):
    """It said 'stopped at the memory limit (None MB)'."""
    import resource

    monkeypatch.setattr(resource, "getrlimit", lambda _kind: (resource.RLIM_INFINITY if limit is None else limit,
                                                             resource.RLIM_INFINITY))
    request = SolveRequest(two_trips, Domain.B, method="anytime", time_limit=30.0)
    assert front.why_stopped(request, "memout", "out of memory", False) == said


def _no_strong_bound(*args, **options):
    raise AssertionError("the strong bound was computed")


def _no_check(*args, **options):
    raise AssertionError("the plan was checked again")


def _watch_with(clock):
    from asprilo.encodings.solving.watch import Watch

    def watch(time_limit=None, cancel=None, listeners=None):
        return Watch(time_limit, cancel, listeners, clock=clock)

    return watch


def test_the_time_kept_for_the_last_check_shrinks_with_the_plan():
    """The refinement keeps time for checking its last plan: a plan as long as the one checked
    last takes as long (0.6 s); one of a third of its steps 0.4 s (half of the check's work
    grows with the steps: 0.3 + 0.3 / 3), none checked yet: the measured time as it is."""
    run = search._Run.__new__(search._Run)
    run.check_seconds, run.checked_makespan = 0.6, 0
    assert run.check_estimate(60) == pytest.approx(0.6)
    run.checked_makespan = 180
    assert run.check_estimate(180) == pytest.approx(0.6)
    assert run.check_estimate(60) == pytest.approx(0.4)
